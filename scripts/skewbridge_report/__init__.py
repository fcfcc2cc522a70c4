"""Post-processing of skewbridge cubes and run files: figures and a Markdown summary.

Modules: sweep (a sweep held in memory), data (reading and checking files), planning (what
each sweep supports, pure), common (what the figure modules share: style, symbols, captions,
axes, legends, saving, the texts of limit states), stats (correlation statistics), figures
(the figure kinds of the dimensionless study), generic (the figures and tables of any sweep,
from the cube's own axes, units and responses), fragility and ida (the figures of limit
states), plan (a model file in plan), response_spectra, cli (the `scripts/report` command);
paper (the `scripts/paper` command) with paper_running (the sweeps and runs it needs),
paper_figures (its figures and their measurements) and paper_claims (the paper's claims and
the rules that judge them)."""
