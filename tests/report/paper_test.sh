#!/usr/bin/env bash
# scripts/paper --quick end to end on 2 ranks: every figure and paper.md (check_paper.py), then
# a second run, in-process under check_readability.py --paper (figure titles carry the paper's
# figure numbers, one correlation statistic per claim), that must reuse every cube and run file
# (their modification times unchanged).
# usage: paper_test.sh SKEWBRIDGE MPIEXEC SOURCE_ROOT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec root work -- "$@"
rm -rf "$work" && mkdir -p "$work"
paper() {
  "$root/scripts/paper" --quick --exe "$exe" --mpiexec "$mpiexec" --work "$work/cubes" \
    --out "$work/out" >"$work/paper.log" 2>&1 || fail "scripts/paper: $(tail -3 "$work/paper.log")"
}
paper
/usr/bin/python3 "$root/tests/report/check_paper.py" "$work/out" "$work/cubes" || fail "outputs"
before=$(stat -c '%n %Y' "$work"/cubes/*.h5 | sort)
sleep 1
/usr/bin/python3 "$root/tests/report/check_readability.py" "$root" --paper "$exe" "$mpiexec" \
  "$work/cubes" "$work/out" >"$work/readability.log" 2>&1 ||
  fail "check_readability --paper: $(tail -3 "$work/readability.log")"
after=$(stat -c '%n %Y' "$work"/cubes/*.h5 | sort)
[ "$before" = "$after" ] || fail "a re-run recomputed a cube or run file"
echo "paper_test: ok"
