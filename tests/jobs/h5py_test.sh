#!/usr/bin/env bash
# Writes a small cube with the test driver (one process, no mpiexec) and checks it from h5py.
# usage: h5py_test.sh SWEEP_DRIVER CHECK_SCRIPT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args driver check work -- "$@"
rm -rf "$work" && mkdir -p "$work"
cat > "$work/spec.toml" <<'TOML'
[sweep]
name = "h5py"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 30, 50]
w0_over_wg = {logspace = [0.1, 10.0, 40]}
[fixed]
eta0 = 1.5
TOML
"$driver" "$work/spec.toml" --out "$work/cube.h5" --quiet --work 10
/usr/bin/python3 "$check" "$work/cube.h5" h5py
