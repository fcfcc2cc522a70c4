#!/usr/bin/env bash
# Values more often a unit slip than a bridge get a warning line each, naming the field, the
# value and the likely slip, and the command goes on (exit 0): a 35 m deck with its gap in mm
# typed as m and its mass in tonnes typed as kg (`run`, `modes`), and a sweep whose axes give a
# gap of 50 m, a seat of 0.3 L, bearings 1000 times too soft and stripes up to 40 g (`sweep
# --dry-run`); the same bridge as meant gets none.
# usage: plausibility_test.sh SKEWBRIDGE SOURCE_ROOT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe root work -- "$@"
fresh_dir "$work"

bridge() {  # bridge MASS GAP: the 35 m x 12 m deck at 35 deg on 30 MN/m, torsion k rho^2
  cat <<TOML
[deck]
m = $1
I_m = "uniform"
L = 35.0
W = 12.0
skew_deg = 35.0
[substructure]
kind = "matrix"
K = [[3e7, 0, 0], [0, 3e7, 0], [0, 0, 3.6e9]]
xi = 0.05
[abutments]
set = "both"
gap_m = $2
[excitation]
kind = "pulse"
shape = "cosine"
a_g_g = 0.5
T_g = 0.5
[run]
tail_s = 0.5
TOML
}
bridge 700e3 0.05 > meant.toml
bridge 700 50 > slips.toml

# As meant: no warning.
"$exe" run meant.toml > out.txt 2> err.txt || fail "run meant.toml: exit $?: $(cat err.txt)"
[ ! -s err.txt ] || fail "run meant.toml warned: $(cat err.txt)"

want_file="skewbridge: warning: slips.toml: deck.m: 700 kg is 20 kg per metre of the 35 m span, below 1 t/m (road decks weigh 10-30 t/m): a mass in tonnes typed as kg?
skewbridge: warning: slips.toml: abutments.gap_m: a gap of 50 m is more than a tenth of the 35 m span: a width in millimetres typed as metres?"
for command in run modes; do
  "$exe" $command slips.toml > out.txt 2> err.txt || fail "$command slips.toml: exit $?: $(cat err.txt)"
  [ "$(cat err.txt)" = "$want_file" ] || fail "$command slips.toml:
  got:  $(cat err.txt)
  want: $want_file"
  [ -s out.txt ] || fail "$command slips.toml printed no result"
done

# A sweep of the bridge as meant whose axes slip: each warning once, before the dry run's report.
cat > spec.toml <<TOML
[sweep]
name = "slips"
family = "model-file"
model = "meant.toml"
[records]
set = "$test_data/records/two-records.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
[axes]
record = "*"
im_g = [1.0, 40.0]
k_factor = [1.0, 0.001]
gap_m = [0.05, 50.0]
seat_over_L = [0.01, 0.3]
TOML
"$exe" sweep --dry-run --sample-cells 1 spec.toml > out.txt 2> err.txt ||
  fail "sweep --dry-run: exit $?: $(cat err.txt)"
want_sweep="skewbridge: warning: spec.toml: axes.seat_over_L: up to 0.3, a seat wider than a tenth of the span: a width in metres typed as a fraction of L?
skewbridge: warning: spec.toml: axes.im_g: up to 40 g, above 5 g (beyond the strongest recorded motions): accelerations in m/s^2 or cm/s^2 typed as g?
skewbridge: warning: spec.toml: axes.gap_m: a gap of 50 m is more than a tenth of the 35 m span: a width in millimetres typed as metres?"
got=$(grep '^skewbridge: warning: ' err.txt | head -3)
[ "$got" = "$want_sweep" ] || fail "sweep warnings:
  got:  $got
  want: $want_sweep"
# k_factor = 0.001: T1 = 0.96 s x sqrt(1000) = 30.4 s in half the cells (record x im_g x gap x
# seat = 16 of 32), named by the first.
grep -q '^skewbridge: warning: .*meant.toml: the fundamental period T1 of the cell (.*k_factor = 0.001.*) is 30.4 s, above 10 s: a stiffness in kN/m or MN/m typed as N/m? (16 of 32 cells lie outside 0.02-10 s)$' err.txt ||
  fail "no period warning: $(cat err.txt)"
[ "$(grep -c '^skewbridge: warning: ' err.txt)" -eq 4 ] || fail "not 4 warnings: $(cat err.txt)"
grep -q "cells" out.txt || fail "no dry-run report: $(cat out.txt)"
echo "plausibility_test: ok"
