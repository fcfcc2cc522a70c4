#!/usr/bin/env bash
# Seat widths in metres: a sweep with seat_m = S gives every response, unseating margin and
# limit-state outcome of the same sweep with seat_over_L = S / L, byte for byte, for the pilot
# bridge (L = 89.14 m) and a one-deck model file (L = 30 m); S / L is a power of two, so
# seat_over_L L is S exactly. Both keys at once are refused with one line naming both.
# usage: seat_m_test.sh SKEWBRIDGE MPIEXEC CHECK_PY WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec check work -- "$@"
fresh_dir "$work"
cp "$test_data/models/one-deck-pulse.toml" deck.toml

# sweep NAME FAMILY_LINES SEAT_LINE OUT: one small sweep with the unseating limit state.
sweep() {
  printf '[sweep]\nname = "seat"\n%b\n[axes]\n%b\n%b\n[limit_states]\nunseating = true\n' \
    "$2" "$3" "$4" > "$1.toml"
  on_ranks 1 "$exe" sweep "$1.toml" --out "$1.h5" > "$1.log" 2>&1 || {
    cat "$1.log" >&2
    fail "$1: the sweep failed"
  }
}

pilot='family = "pilot-bridge"\n[fixed]\npulse = "sine"'
pilot_axes='Pi_delta = [0.05, 0.5]\na_g_g = [0.5, 1.5]'
# 89.14 / 8192 and 89.14 / 1024 (the division by a power of two is exact; %.17g round-trips).
widths=$(/usr/bin/python3 -c 'print("[%.17g, %.17g]" % (89.14 / 8192, 89.14 / 1024))')
sweep pilot-rel "$pilot" "$pilot_axes" 'seat_over_L = [0.0001220703125, 0.0009765625]'
sweep pilot-abs "$pilot" "$pilot_axes" "seat_m = $widths"
/usr/bin/python3 "$check" pilot-rel.h5 pilot-abs.h5 seat_over_L seat_m ||
  fail "pilot bridge: seat_m differs from seat_over_L L"

deck='family = "model-file"\nmodel = "deck.toml"\n[fixed]\npulse = "sine"'
deck_axes='Pi_delta = [0.5, 1.0]\na_deg = [20, 45]'
sweep deck-rel "$deck" "$deck_axes" 'seat_over_L = [0.000244140625, 0.00390625]'
sweep deck-abs "$deck" "$deck_axes" 'seat_m = [0.00732421875, 0.1171875]'
/usr/bin/python3 "$check" deck-rel.h5 deck-abs.h5 seat_over_L seat_m ||
  fail "model file: seat_m differs from seat_over_L L"

# Both keys: one line naming both, non-zero exit, no cube.
printf '[sweep]\nname = "seat"\nfamily = "pilot-bridge"\n[fixed]\npulse = "sine"\nseat_m = 0.5\n[axes]\nseat_over_L = [0.01]\n' > both.toml
status=0
"$exe" sweep both.toml --out both.h5 > both.log 2>&1 || status=$?
[ "$status" -ne 0 ] || fail "both seat keys: exit status 0"
[ "$(wc -l < both.log)" -eq 1 ] || fail "both seat keys: not one line: $(cat both.log)"
grep -q 'seat_over_L' both.log && grep -q 'seat_m' both.log ||
  fail "both seat keys: the line does not name both: $(cat both.log)"
[ ! -e both.h5 ] || fail "both seat keys: a cube was written"
echo "seat_m_test: ok"
