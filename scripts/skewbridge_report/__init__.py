"""Post-processing of skewbridge cubes and run files: figures and a Markdown summary.

Modules: data (reading and checking files), stats (correlation statistics), figures (one
function per figure kind), generic (the figures and tables of any sweep, from the cube's own
axes, units and responses), cli (the `scripts/report` command)."""
