#!/usr/bin/env bash
# Regenerates every figure and number of docs/validation.md (except the time-stepping section,
# whose command is given there): the §6 sweeps of jobs/specs on 2 ranks, the 62-record pilot
# study, a batch of frictional runs for fact 6, then the measurements (facts.py) and the figures
# (scripts/report). About 2-4 minutes on 2 cores.
#
# usage: scripts/validation/run.sh [BUILD_DIR (build/release)] [WORK_DIR (BUILD_DIR/validation)]
# The figures referenced by docs/validation.md are copied to docs/figures/ with --update-docs.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
update_docs=0
args=()
for a in "$@"; do
  if [ "$a" = "--update-docs" ]; then update_docs=1; else args+=("$a"); fi
done
build=$(realpath -m "${args[0]:-$root/build/release}")
work=$(realpath -m "${args[1]:-$build/validation}")
exe="$build/skewbridge"
[ -x "$exe" ] || { echo "run.sh: $exe not built (cmake --build $build --target skewbridge)" >&2; exit 2; }
set -a && source "$root/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
mkdir -p "$work" && cd "$work"

sweep() {  # sweep SPEC OUT: once; an existing complete cube is reused
  [ -e "$2" ] || mpiexec -n 2 "$exe" sweep "$1" --out "$2" --quiet
}
sweep "$root/jobs/specs/eta0-1.toml" eta0-1.h5
sweep "$root/jobs/specs/eta0-2.toml" eta0-2.h5
sweep "$root/jobs/specs/pi-delta-family.toml" pi-delta.h5
sweep "$root/jobs/specs/rotation-vs-eta0.toml" rotation-vs-eta0.h5
sweep "$root/scripts/validation/zero-skew.toml" zero-skew.h5
sweep "$root/scripts/validation/friction-eta0.toml" friction-eta0.h5
# The pilot study reads its suite next to its specification: both go into the work folder.
[ -d synth62 ] || "$exe" records synth --count 62 --seed 2011 --out synth62 >/dev/null
cp "$root/jobs/specs/pilot-records.toml" pilot-records.toml
sweep pilot-records.toml pilot-records.h5
[ -e run-subsystem.h5 ] || "$exe" run "$root/docs/examples/subsystem.toml" --out run-subsystem.h5 >/dev/null

/usr/bin/python3 "$root/scripts/validation/facts.py" "$exe" "$work" | tee facts.txt
"$root/scripts/report" eta0-1.h5 eta0-2.h5 pi-delta.h5 rotation-vs-eta0.h5 pilot-records.h5 \
  friction-eta0.h5 --run run-subsystem.h5 --out report >report.log
cat report.log
if [ $update_docs -eq 1 ]; then
  mkdir -p "$root/docs/figures"
  # The figures validation.md shows, reduced to a 128-colour palette to stay well under 200 kB.
  /usr/bin/python3 - "$root/docs/figures" report/spectra_subsystem-eta0-2.png \
    report/pi_delta_family_subsystem-pi-delta.png report/rotation_vs_eta0_rotation-vs-eta0.png \
    facts-rotation-fixed-w0.png report/rotation_vs_eta0_friction-eta0.png \
    report/correlation_theta_vs_Le_pilot-records.png \
    report/correlation_rotation_vs_w0x_pilot-records.png report/history_run-subsystem.png <<'PY'
import os, sys
from PIL import Image
for path in sys.argv[2:]:
    out = os.path.join(sys.argv[1], os.path.basename(path))
    Image.open(path).convert("RGB").quantize(colors=128).save(out, optimize=True)
    print(f"{out}: {os.path.getsize(out) // 1024} kB")
PY
fi
echo "validation: numbers in $work/facts.txt, figures in $work/report"
