#!/usr/bin/env bash
# Sizes bounded before work, and a state that is not finite never called ok.
# - Every size a run would ask for is counted before the first step (or the first cell of a
#   sweep), also when it comes from a file: a model file of 3000 decks (`run` and `modes`), an
#   excitation file whose samples are 1e5 s apart with histories every 10 ms, one of 1e6 s steps,
#   more samples than run.max_steps, a --output-interval of 1e-9 s, and a model-file sweep whose
#   pulse period is 1e7 s (1 and 2 ranks). Each exits 2 with exactly the line given, quickly,
#   and leaves nothing behind.
# - A run whose state stops being finite (a sample of 1e300 m/s^2, allowed by max_pga_g) ends
#   with status non-finite (exit 3, one line naming the time), its summary prints no nan or inf,
#   and a model-file sweep stores the cell as failed with the status name non-finite.
# usage: run_size_test.sh SKEWBRIDGE MPIEXEC SUBSYSTEM_TOML WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec base work -- "$@"
fresh_dir "$work"
cases=0
leftovers() { ls -d out.h5* run.h5* run.csv* 2> /dev/null || true; }
refused() {  # refused RANKS EXACT_LINE ARGS...: exit 2 within 20 s, exactly one line, no output
  local ranks=$1 line=$2 status=0; shift 2
  local start=$SECONDS
  if [ "$ranks" -eq 1 ]; then "$exe" "$@" > out.txt 2> err.txt || status=$?
  else on_ranks "$ranks" "$exe" "$@" > out.txt 2> err.txt || status=$?; fi
  [ "$status" -eq 2 ] || fail "$*: exit $status, expected 2: $(head -c 600 err.txt)"
  [ $((SECONDS - start)) -le 20 ] || fail "$*: took $((SECONDS - start)) s to refuse"
  [ "$(grep -c '^skewbridge: error: ' err.txt)" -eq 1 ] || fail "$*: $(cat err.txt)"
  [ "$(grep '^skewbridge: error: ' err.txt)" = "skewbridge: error: $line" ] \
    || fail "$*: got '$(cat err.txt)', expected '$line'"
  [ "$ranks" -gt 1 ] || [ "$(wc -l < err.txt)" -eq 1 ] || fail "$*: more than one line"
  [ -z "$(leftovers)" ] || fail "$* left $(leftovers)"
  cases=$((cases + 1))
  echo "ok ($ranks ranks): $line"
}
sampled() {  # sampled FILE EXCITATION_LINES [RUN_LINES]: the subsystem under sampled motion
  sed -e '/^\[excitation\]/,$d' "$base" > "$1"
  printf '[excitation]\nkind = "sampled"\ndirection = "x"\n%b\n[run]\n%b\n' "$2" "${3:-}" >> "$1"
}

# 3000 decks in a row: refused at the first deck beyond the bound, by run and by modes.
/usr/bin/python3 - <<'PY'
with open("decks.toml", "w") as f:
    for i in range(3000):
        f.write("[[deck]]\nm = 1e6\nL = 30.0\nW = 10.0\nskew_deg = 20.0\n")
        if i < 2999:
            f.write("[[joint]]\ngap_m = 0.05\n")
    f.write('[abutments]\ngap_m = 0.05\n[[support]]\ndeck = 0\nk_x = 1e7\nk_y = 1e7\nk_theta = 1e9\n')
    f.write('[excitation]\nkind = "pulse"\nshape = "sine"\na_g_g = 0.3\nT_g = 0.5\n')
PY
line=$(awk '/^\[\[deck\]\]/ { n++; if (n == 201) { print NR; exit } }' decks.toml)
msg="decks.toml:$line: deck: 3000 [[deck]] tables (9000 DOFs); allowed: at most 200 decks (600 DOFs, 402 contacts)"
refused 1 "$msg" run decks.toml --out run.h5
refused 1 "$msg" modes decks.toml

# Excitation files whose sizes only show when read.
printf '0 0.0\n1e5 0.1\n2e5 0.0\n' > slow.txt
sampled slow.toml 'file = "slow.txt"' 'output_interval_s = 0.01'
refused 1 "slow.toml: run.output_interval_s: the run of 200002 s would store 20000200 history samples; allowed at most 1e7 (a larger interval, or 0 for none)" \
  run slow.toml --out run.h5 --csv run.csv
printf '0 0.0\n1e6 0.1\n2e6 0.0\n' > slower.txt
sampled slower.toml 'file = "slower.txt"'
refused 1 "slower.toml: excitation.file: the run would end at t = 2000002 s (the excitation's duration plus run.tail_s, or run.end_time_s); allowed: a finite end time up to 1e6 s" \
  run slower.toml --out run.h5
awk 'BEGIN { for (i = 0; i < 50; i++) printf "%.2f 0.0\n", i * 0.01 }' > fifty.txt
sampled fifty.toml 'file = "fifty.txt"' 'max_steps = 10'
refused 1 "fifty.toml: excitation.file: its 50 samples take one step each at least, more than run.max_steps = 10" \
  run fifty.toml --out run.h5
refused 1 "$base: run.output_interval_s: the run of 2.5 s would store 2.5e+09 history samples; allowed at most 1e7 (a larger interval, or 0 for none)" \
  run "$base" --output-interval 1e-9 --out run.h5

# A model-file sweep over a pulse period that no run would take: refused before the first cell.
cp "$base" deck.toml
printf '[sweep]\nname = "slow"\nfamily = "model-file"\nmodel = "deck.toml"\n[axes]\nT_g = [0.5, 1e7]\n' > slow_sweep.toml
for ranks in 1 2; do
  refused "$ranks" "slow_sweep.toml: cell T_g = 10000000: deck.toml: excitation: the run would end at t = 10000002 s (the excitation's duration plus run.tail_s, or run.end_time_s); allowed: a finite end time up to 1e6 s" \
    sweep slow_sweep.toml --out out.h5
done

# A state that stops being finite: status non-finite, never ok, no nan in the summary.
sampled blowup.toml 'values = [0.0, 1e300, 0.0]\ndt_s = 0.01\nmax_pga_g = inf'
status=0
"$exe" run blowup.toml > out.txt 2> err.txt || status=$?
[ "$status" -eq 3 ] || fail "blow-up run: exit $status, expected 3: $(cat err.txt)"
[ "$(wc -l < err.txt)" -eq 1 ] || fail "blow-up run: $(cat err.txt)"
grep -Eq '^skewbridge: run stopped: non-finite: the state \(q, u\) stopped being finite \(or its square overflowed\) between t = [0-9.e+-]+ s and t = [0-9.e+-]+ s|^skewbridge: run stopped: non-finite: the energy of the state is not finite at t = [0-9.e+-]+ s' err.txt \
  || fail "blow-up run: $(cat err.txt)"
head -1 out.txt | grep -q 'status non-finite' || fail "blow-up summary: $(head -1 out.txt)"
! grep -Eiq 'nan|inf( |$|,)' out.txt || fail "the summary prints nan or inf: $(cat out.txt)"
cases=$((cases + 1))
echo "ok: $(cat err.txt)"
sed -i 's/^\[run\]/[run]\nmethod = "time-stepping"/' blowup.toml
status=0
"$exe" run blowup.toml > out.txt 2> err.txt || status=$?
[ "$status" -eq 3 ] && grep -q '^skewbridge: run stopped: non-finite: ' err.txt \
  || fail "blow-up run, time-stepping: exit $status: $(cat err.txt)"
! grep -Eiq 'nan|inf( |$|,)' out.txt || fail "the summary prints nan or inf: $(cat out.txt)"
cases=$((cases + 1))
echo "ok (time-stepping): $(cat err.txt)"
sampled blowup.toml 'values = [0.0, 1e300, 0.0]\ndt_s = 0.01\nmax_pga_g = inf'
printf '[sweep]\nname = "blowup"\nfamily = "model-file"\nmodel = "blowup.toml"\n[axes]\nscale = [1.0, 1e-300]\n' > blowup_sweep.toml
"$exe" sweep blowup_sweep.toml --out cube.h5 > out.txt 2> err.txt || fail "blow-up sweep: $(cat err.txt)"
/usr/bin/python3 - <<'PY' || fail "blow-up sweep cube"
import h5py, math
with h5py.File("cube.h5", "r") as f:
    g = f["sweeps/blowup"]
    status = g["status"]
    names = dict(zip(status.attrs["status_codes"], [n.decode() if isinstance(n, bytes) else n
                                                      for n in status.attrs["status_names"]]))
    codes = list(status[...].ravel())
    assert names[codes[0]] == "non-finite", (codes, names)
    assert names[codes[1]] == "ok", (codes, names)
    x = g["responses/x_end_d0"][...].ravel()
    assert math.isnan(x[0]) and math.isfinite(x[1]), x
print("ok: the cell of scale 1 is stored as non-finite, its responses NaN; scale 1e-300 is ok")
PY
rm -f cube.h5
cases=$((cases + 1))
echo "run_size_test: $cases cases ok"
