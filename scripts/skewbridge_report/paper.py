"""The `scripts/paper` command: the analogue of each result figure of Dimitrakopoulos (2011),
Figs. 5 to 13 (sections 3 and 4 of the paper) and two extensions, with paper.md: per figure the
paper's statement, this reproduction's parameters, the measured numbers and a verdict
(reproduced / partly / not), then a table of every claim of sections 3 and 4.

The work is in three parts: paper_running.py runs the sweeps (jobs/specs/paper/, jobs/specs/)
and the runs of jobs/specs/paper/subsystem-run.toml; paper_figures.py draws each figure and
measures its numbers; paper_claims.py holds each claim with the rule that judges it. Every
number in paper.md is computed from the cubes and run files, so a re-run with another solver
rewrites them; the verdict rules are stated next to each figure."""
import argparse
import os
import sys

from . import paper_claims, paper_figures
from .data import ReportError
from .paper_running import ROOT, Runner


def _md_figure(paths, out):
    return [f"![{os.path.basename(p)}]({os.path.relpath(p, out)})" for p in paths]


def _name(key):
    """A figure by its claim's key: "Fig. 5"; "after Fig. 10" for an extension "10x"."""
    return "Fig. " + key if not key.endswith("x") else "after Fig. " + key[:-1]


def main(argv):
    parser = argparse.ArgumentParser(prog="paper", description="The paper's result figures "
                                     "(Figs. 5-13) with paper.md, from fresh sweeps.")
    parser.add_argument("--quick", action="store_true", help="thin every grid (tests)")
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "skewbridge"))
    parser.add_argument("--mpiexec", default="mpiexec")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--work", help="folder of the cubes and runs (reused on re-runs)")
    parser.add_argument("--out", help="folder of the figures and paper.md")
    parser.add_argument("--palette", action="store_true",
                        help="reduce each PNG to 128 colours (for docs/figures/paper)")
    args = parser.parse_args(argv)
    build = os.path.dirname(os.path.realpath(args.exe))
    tag = "paper-quick" if args.quick else "paper"
    args.work = os.path.realpath(args.work or os.path.join(build, tag, "work"))
    args.out = os.path.realpath(args.out or os.path.join(build, tag, "figures"))
    try:
        if not os.access(args.exe, os.X_OK):
            raise ReportError(f"{args.exe}: not built (cmake --build build/release "
                              "--target skewbridge)")
        return run(args)
    except ReportError as err:
        print(f"paper: error: {err}", file=sys.stderr)
        return 2


def run(args):
    os.makedirs(args.work, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    runner = Runner(args)
    md = ["# The paper's result figures, reproduced", "",
          "Each result figure of Dimitrakopoulos (2011), Engineering Structures 33:813-826, "
          "Figs. 5 to 13 (sections 3 and 4 of the paper) with the paper's numbering, redrawn by "
          "`scripts/paper" + (" --quick" if args.quick else "") +
          "` from sweeps of jobs/specs/paper/ and jobs/specs/ and runs of "
          "jobs/specs/paper/subsystem-run.toml, with the paper's statement, the numbers "
          "measured here and a verdict: **reproduced**, **partly** or **not**, with the reason. "
          "Where the paper's text gives no parameter the choice is stated. The **Paper.** "
          "lines state the paper's claims in the symbols of this document; only the words in "
          "quotation marks are the paper's own. Symbols are those "
          "of docs/theory.md; values below 1e-9 are printed as 0." +
          (" This is the --quick run: every grid is thinned, so the numbers are coarse." if
           args.quick else ""), ""]
    verdicts = []
    measurements = {}
    for claim in paper_claims.FIGURES:
        paths, m = paper_figures.BY_CLAIM[claim.key](runner, args.out)
        judged = claim.judge(m, measurements)
        heading = _name(claim.key)
        md.extend([f"## {heading[0].upper() + heading[1:]}: {claim.title}", ""]
                  + _md_figure(paths, args.out) + [
            "", f"**Paper.** {claim.statement}", "", f"**Here.** {claim.setup_text(m)}", "",
            f"**Measured.** {judged.measured}"] + list(judged.extra) + [
            "", f"**Verdict: {judged.verdict}.** {judged.reason}.", ""])
        verdicts.append((claim.key, claim.title, judged.verdict))
        measurements[claim.key] = m
        print(f"Fig. {claim.key}: {judged.verdict}", flush=True)
    claims = paper_claims.claim_table(measurements,
                                      {key: verdict for key, _, verdict in verdicts})
    md.extend(["## Every claim of sections 3 and 4", "",
               "One row per claim of the paper's sections 3 (the subsystem) and 4 (the pilot "
               "bridge); the verdict is held by the source named, here or in "
               "docs/validation.md, and only repeated here.", "",
               "| claim (section) | measured | verdict | reason | source |",
               "|---|---|---|---|---|"] + [f"| {' | '.join(r)} |" for r in claims] + [""])
    md[4:4] = ["| figure | verdict |", "|---|---|"] + [
        f"| {_name(n)}: {t} | {v} |" for n, t, v in verdicts] + [""]
    with open(os.path.join(args.out, "paper.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    if args.palette:  # as scripts/validation/run.sh does for docs/figures
        from PIL import Image
        for name in sorted(os.listdir(args.out)):
            if name.endswith(".png"):
                path = os.path.join(args.out, name)
                Image.open(path).convert("RGB").quantize(colors=128).save(path, optimize=True)
    print(f"wrote {os.path.join(args.out, 'paper.md')}")
    return 0
