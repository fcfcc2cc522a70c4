#!/usr/bin/env bash
# `skewbridge run` and run.method: the canonical subsystem (docs/examples/subsystem.toml) by the
# Moreau-Jean time-stepping scheme with h = 1e-4 s gives maxima within 1 % of the event-driven
# run; and a run that ends in a Painleve situation exits with status 3, the status and time in
# the summary and one line on stderr (docs/model-format.md, "Exit status").
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe root -- "$@"
temp_dir

cp "$root/docs/examples/subsystem.toml" "$work/ed.toml"
cp "$root/docs/examples/subsystem.toml" "$work/ts.toml"
# [run] is the file's last table: the keys appended here belong to it.
printf 'method = "time-stepping"\ntime_step_s = 1e-4\n' >>"$work/ts.toml"
"$exe" run "$work/ed.toml" >"$work/ed.out" 2>&1 || fail "event-driven run: exit $?"
"$exe" run "$work/ts.toml" >"$work/ts.out" 2>&1 || fail "time-stepping run: exit $? ($(cat "$work/ts.out"))"
grep -q "method event-driven, status ok" "$work/ed.out" || fail "no event-driven status line"
grep -q "method time-stepping (h = 0.0001 s), status ok" "$work/ts.out" ||
  fail "no time-stepping status line: $(head -1 "$work/ts.out")"
for dof in x0 y0 theta0; do
  ed=$(sed -n "s/.*max|$dof| = \([^ ]*\) at.*/\1/p" "$work/ed.out")
  ts=$(sed -n "s/.*max|$dof| = \([^ ]*\) at.*/\1/p" "$work/ts.out")
  [ -n "$ed" ] && [ -n "$ts" ] || fail "no maximum of $dof in the summaries"
  awk -v a="$ed" -v b="$ts" 'BEGIN { d = (b - a) / a; if (d < 0) d = -d; exit !(d <= 0.01) }' ||
    fail "$dof: time-stepping $ts against event-driven $ed differs by more than 1 %"
done

# A free deck (K = 0) whose corners slide along the +x face (mu = 5, slip along +t) while the
# ground pushes them in: every entry of the 2 x 2 contact LCP matrix
# W_N^T M^-1 (W_N - mu W_T) is negative (1/m + r_i (r_j - mu r_T) / I_m with r_1 = 9.90,
# r_2 = 4.24, r_T = 7.07 m, I_m / m = 36 m^2) and b < 0, so it has no solution. The corners
# close slowly (plastically) at t = sqrt(2 delta cos a / a_N) = 0.0402819 s,
# a_N = -n . (cos 40 deg, sin 40 deg) = 0.0871557 m/s^2.
cat >"$work/painleve.toml" <<'TOML'
[deck]
m = 1000.0
L = 20.0
eta0 = 2.5
skew_deg = 45.0

[substructure]
kind = "uncoupled"
w0 = 0.0
W0 = 0.0
xi = 0.0

[abutments]
set = "+x"
gap_m = 1e-4
eps_N = 0.5
mu = 5.0

[excitation]
kind = "sampled"
values = [-1.0, -1.0]
dt_s = 1.0
angle_deg = 40.0

[run]
end_time_s = 1.0
accumulation_threshold = 0.05
TOML
status=0
"$exe" run "$work/painleve.toml" --csv "$work/p.csv" >"$work/p.out" 2>"$work/p.err" || status=$?
[ $status -eq 3 ] || fail "Painleve run: exit status $status, expected 3 ($(cat "$work/p.err"))"
grep -q "status painleve" "$work/p.out" || fail "Painleve run: no 'status painleve' in the summary"
# The free deck of 1 t is what the plausibility warnings name (a light deck, an infinite T1);
# besides them the stop is one line.
[ "$(grep -vc '^skewbridge: warning: ' "$work/p.err")" -eq 1 ] ||
  fail "Painleve run: stderr holds more than the warnings and one line: $(cat "$work/p.err")"
grep -q "skewbridge: run stopped: painleve: Painleve situation" "$work/p.err" ||
  fail "Painleve run: unexpected message: $(cat "$work/p.err")"
t_end=$(sed -n 's/.*t_end \([^ ]*\) s.*/\1/p' "$work/p.out")
awk -v t="$t_end" 'BEGIN { d = t - 0.0402819; if (d < 0) d = -d; exit !(d <= 1e-6) }' ||
  fail "Painleve run: stopped at t = $t_end s, expected 0.0402819 s"
[ -f "$work/p.csv" ] || fail "Painleve run: the CSV of the run up to the stop was not written"
echo "ok"
