#!/usr/bin/env bash
# The excitation file of a model file, read as strictly as a record: each malformed file makes
# `skewbridge run` exit 2 with exactly the one line given here (file:line, what is wrong, what is
# allowed) and leaves no output behind; the well-formed variants (commas, comments, CR LF, one
# column with dt_s) give the same summary as the plain two-column file.
# usage: signal_file_test.sh SKEWBRIDGE SUBSYSTEM_TOML WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe base work -- "$@"
fresh_dir "$work"
cases=0
leftovers() { ls -d run.h5* run.csv* 2> /dev/null || true; }
model() {  # model FILE EXCITATION_LINES: the subsystem under a sampled excitation
  sed -e '/^\[excitation\]/,$d' "$base" > "$1"
  printf '[excitation]\nkind = "sampled"\ndirection = "x"\n%b\n' "$2" >> "$1"
}
refused() {  # refused SIGNAL_TEXT EXCITATION_LINES EXACT_LINE
  printf "$1" > sig.txt
  model bad.toml "file = \"sig.txt\"\n$2"
  local status=0
  "$exe" run bad.toml --out run.h5 --csv run.csv > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$3: exit $status, expected 2: $(cat err.txt)"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$3: not one line: $(cat err.txt)"
  [ "$(cat err.txt)" = "skewbridge: error: $3" ] || fail "got '$(cat err.txt)', expected '$3'"
  [ ! -s out.txt ] || fail "$3: printed a summary: $(cat out.txt)"
  [ -z "$(leftovers)" ] || fail "$3: left $(leftovers)"
  cases=$((cases + 1))
  echo "ok: $3"
}
allowed_num="allowed: finite decimal numbers such as -1.234e-02"
same_cols="allowed: the same columns on every data line"
grid="allowed: times increasing by one constant step"

# The cases of the issue: a third column, trailing characters, a conflicting dt, NaN with and
# without dt_s (on its own line, not the next one).
refused '0.00 0.0\n0.01 0.1 7\n0.02 0.0\n' '' \
  "sig.txt:2: 3 columns where the first data line (line 1) has 2 (time in s, acceleration); $same_cols"
refused '0.00 0.0 7\n0.01 0.1 7\n' '' \
  "sig.txt:1: the first data line has 3 columns; allowed: 1 (acceleration, with excitation.dt_s) or 2 (time in s, acceleration)"
refused '0.00 0.0\n0.01 0.123xyz\n0.02 0.0\n' '' \
  "sig.txt:2: '0.123xyz' in column 2 (acceleration) is not a finite number; $allowed_num"
refused '0.0\n0.123xyz\n0.0\n' 'dt_s = 0.01' \
  "sig.txt:2: '0.123xyz' in the acceleration column is not a finite number; $allowed_num"
refused '0.00 0.0\n0.01 0.1\n0.02 0.0\n0.03 0.0\n' 'dt_s = 0.02' \
  "sig.txt:2: the time column steps by 0.01 s but the model file gives excitation.dt_s = 0.02 s; allowed: no dt_s, or the step of the time column"
refused '0.00 0.0\n0.01 0.1\n0.02 0.0\n4.00 nan\n' 'dt_s = 0.01' \
  "sig.txt:4: 'nan' in column 2 (acceleration) is NaN; $allowed_num"
refused '0.00 0.0\n1.00 0.1\n1.50 nan\n2.00 0.0\n' '' \
  "sig.txt:3: 'nan' in column 2 (acceleration) is NaN; $allowed_num"
refused '0.0\n0.1\nNaN\n0.0\n' 'dt_s = 0.01' \
  "sig.txt:3: 'NaN' in the acceleration column is NaN; $allowed_num"
refused '0.00 0.0\n0.01 -inf\n0.02 0.0\n' '' \
  "sig.txt:2: '-inf' in column 2 (acceleration) is an infinite value; $allowed_num"
refused '0.00 0.0\ninf 0.1\n' '' \
  "sig.txt:2: 'inf' in column 1 (time, s) is an infinite value; $allowed_num"
# Time columns that are not one uniform grid.
refused '0.00 0.0\n0.01 0.1\n0.03 0.0\n0.04 0.0\n0.05 0.0\n' '' \
  "sig.txt:2: time 0.01 s is off the uniform grid of step 0.0125 s (from the first and last times); $grid"
refused '0.00 0.0\n0.02 0.1\n0.01 0.0\n' '' \
  "sig.txt:3: time 0.01 s does not increase (the line before has 0.02 s); $grid"
# Column counts after the first line, one column without dt_s, too few samples.
refused '0.00 0.0\n0.1\n0.02 0.0\n' '' \
  "sig.txt:2: 1 column where the first data line (line 1) has 2 (time in s, acceleration); $same_cols"
refused '# acc\n0.0\n0.1 0.2\n' 'dt_s = 0.01' \
  "sig.txt:3: 2 columns where the first data line (line 2) has 1 (acceleration); $same_cols"
refused '0.0\n0.1\n0.0\n' '' \
  "sig.txt:1: one column (acceleration) needs excitation.dt_s in the model file; allowed: dt_s, or two columns (time in s, acceleration)"
refused '# nothing\n\n' 'dt_s = 0.01' "sig.txt: no samples (only blank or '#' lines)"
refused '\n0.00 0.5\n' '' "sig.txt:2: one sample; a sampled excitation needs at least two"
# The factor of units and scale is applied on the line it overflows.
refused '0.00 0.0\n0.01 1e307\n' 'scale = 100' \
  "sig.txt:2: acceleration 1e+307 times units and scale (100) is not a finite number in m/s^2"
# A folder where the file should be.
mkdir -p folder.txt
model folder.toml 'file = "folder.txt"'
status=0
"$exe" run folder.toml --out run.h5 > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] && [ "$(cat err.txt)" = "skewbridge: error: folder.txt: is a folder; excitation.file names a text file of samples" ] \
  || fail "folder: exit $status: $(cat err.txt)"
cases=$((cases + 1))

# Well-formed spellings of one signal read the same samples: spaces, commas (the `t,a` lines of
# the issue, with the matching dt_s), comments and CR LF line ends, one column with dt_s.
summary() {  # summary EXCITATION_LINES SIGNAL_TEXT: the run's summary, model line dropped
  printf "$2" > sig.txt
  model good.toml "file = \"sig.txt\"\n$1"
  "$exe" run good.toml > out.txt 2> err.txt || fail "good run: $(cat err.txt)"
  tail -n +2 out.txt
}
signal='0.00 0.0\n0.05 2.0\n0.10 -3.0\n0.15 1.0\n0.20 0.0\n'
reference=$(summary '' "$signal")
[ "$(summary 'dt_s = 0.05' '0.00,0.0\n0.05,2.0\n0.10,-3.0\n0.15,1.0\n0.20,0.0\n')" = "$reference" ] \
  || fail "comma-separated lines read differently"
[ "$(summary '' '# t a\r\n0.00 0.0\r\n0.05 2.0\r\n\r\n0.10 -3.0\r\n0.15 1.0\r\n0.20 0.0')" = "$reference" ] \
  || fail "comments and CR LF read differently"
[ "$(summary 'dt_s = 0.05' '0.0\n2.0\n-3.0\n1.0\n0.0\n')" = "$reference" ] \
  || fail "one column with dt_s reads differently"
[ "$(summary 'units = "cmps2"' '0.00 0.0\n0.05 200\n0.10 -300\n0.15 100\n0.20 0.0\n')" \
  = "$reference" ] || fail "cm/s^2 reads differently"
# One units vocabulary: the spellings `records info --units` takes name the same factors here.
for spelling in m/s^2 m/s2 mps2 'M/S/S'; do
  [ "$(summary "units = \"$spelling\"" "$signal")" = "$reference" ] || fail "units $spelling"
done
for spelling in gal cm/s^2 cmps2 cm/sec2; do
  [ "$(summary "units = \"$spelling\"" '0.00 0.0\n0.05 200\n0.10 -300\n0.15 100\n0.20 0.0\n')" \
    = "$reference" ] || fail "units $spelling"
done
grep -q "max|x0|" <<< "$reference" || fail "no summary: $reference"
cases=$((cases + 12))
refused "$signal" 'units = "furlong/fortnight"' \
  "bad.toml:30: excitation.units: unknown units \"furlong/fortnight\" (allowed: g, m/s^2 (or m/s2, mps2), cm/s^2 (or cm/s2, gal, cmps2))"
# Amplitudes implausible for the units given (a record in cm/s^2 read as m/s^2): refused with
# the units option named, unless the user raises max_pga_g.
cms='0.00 0.0\n0.05 245.0\n0.10 -300.0\n0.15 100.0\n0.20 0.0\n'
pga_allowed="allowed: the true excitation.units (g, m/s^2 (or m/s2, mps2), cm/s^2 (or cm/s2, gal, cmps2)), or a larger excitation.max_pga_g (inf: no bound) if the motion means it"
refused "$cms" 'units = "m/s^2"' \
  "bad.toml: excitation.file (sig.txt): PGA 300 m/s^2 (30.59 g) in the units m/s^2 is above max_pga_g = 10 g, beyond any recorded ground motion; $pga_allowed"
refused "$cms" 'scale = 0.001' \
  "bad.toml: excitation.file (sig.txt): PGA 300 m/s^2 (30.59 g) in the units m/s^2 is above max_pga_g = 10 g, beyond any recorded ground motion; $pga_allowed"
printf "$cms" > sig.txt
model inline.toml 'values = [0.0, 2.0, 400.0]\ndt_s = 0.01'
status=0
"$exe" run inline.toml > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] && [ "$(cat err.txt)" = "skewbridge: error: inline.toml:29: excitation.values: PGA 400 m/s^2 (40.79 g) in the units m/s^2 is above max_pga_g = 10 g, beyond any recorded ground motion; $pga_allowed" ] \
  || fail "inline values of 40 g: exit $status: $(cat err.txt)"
cases=$((cases + 1))
[ "$(summary 'units = "gal"' "$cms" | head -1)" != "" ] || fail "the same file in gal"
model big.toml 'file = "sig.txt"\nmax_pga_g = 50'
status=0
"$exe" run big.toml > out.txt 2> err.txt || status=$?
[ "$status" -ne 2 ] && head -1 out.txt | grep -q "status" || fail "max_pga_g = 50: $(cat err.txt)"
cases=$((cases + 2))
# The same rule for records: `records info` names --units; --max-pga-g raises the bound.
printf "$cms" > rec.txt
status=0
"$exe" records info rec.txt --format time-acc --units m/s^2 > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] && [ "$(cat err.txt)" = "skewbridge: error: rec.txt: PGA 300 m/s^2 (30.59 g) read in m/s^2 as given is above 10 g, beyond any recorded ground motion; allowed: the record's true units (--units of records info, units of a record set), or a larger max_pga_g (--max-pga-g) if the record means it" ] \
  || fail "records info of 30 g: exit $status: $(cat err.txt)"
"$exe" records info rec.txt --format time-acc --units m/s^2 --max-pga-g 40 > out.txt 2> err.txt \
  || fail "records info --max-pga-g 40: $(cat err.txt)"
"$exe" records info rec.txt --format time-acc --units gal > out.txt 2> err.txt \
  || fail "records info --units gal: $(cat err.txt)"
cases=$((cases + 3))
[ -z "$(leftovers)" ] || fail "left $(leftovers)"
echo "signal_file_test: $cases cases ok"
