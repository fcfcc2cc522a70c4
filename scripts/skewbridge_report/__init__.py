"""Post-processing of skewbridge cubes and run files: figures and a Markdown summary.

Modules: data (reading and checking files), stats (correlation statistics), figures (one
function per figure kind), cli (the `scripts/report` command)."""
