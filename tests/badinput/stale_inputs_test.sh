#!/usr/bin/env bash
# A cube never outlives its inputs. After a complete and after an interrupted sweep, on 1 and 2
# ranks, each kind of input is edited in turn: a key of the specification, the model file, the
# model file's excitation file, a record file of a folder set, a record-set manifest and a record
# file it names. Every --resume then exits 2 with one line naming the changed key or file, and
# leaves the cube or checkpoint byte for byte as it was, with nothing beside it; with the input
# restored, --resume goes on (the checkpoint completes, the cube is "already complete"). The cube
# lists every input with the SHA-256 that sha256sum prints; a comment added to the specification
# is no change.
# usage: stale_inputs_test.sh SKEWBRIDGE MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec work -- "$@"
fresh_dir "$work"
checks=0
touch out.txt err.txt

# --- inputs: records of 20 s, a model with an excitation file ---------------------------------
mkdir -p recs exc
/usr/bin/python3 - <<'PY'
import math
for name, amp, period in (("recs/r1.txt", 3.0, 0.5), ("recs/r2.txt", 4.5, 0.8),
                          ("exc/ground.txt", 2.0, 0.6)):
    with open(name, "w") as f:
        for k in range(2000):
            t = 0.01 * k
            f.write("%.17g\n" % (amp * math.sin(2 * math.pi * t / period) * math.exp(-t / 8.0)))
PY
# The one-deck model of the model-file sweep tests under the samples of exc/ground.txt.
sed -e 's/^kind = "pulse"/kind = "sampled"\nfile = "exc\/ground.txt"\ndt_s = 0.01\nunits = "mps2"/' \
    -e '/^shape = /d' -e '/^a_g_g = /d' -e '/^T_g = /d' "$test_data/models/one-deck-pulse.toml" > deck.toml
cat > set.toml <<'TOML'
name = "two"
[[record]]
file = "recs/r1.txt"
units = "m/s^2"
dt = 0.01
[[record]]
file = "recs/r2.txt"
units = "m/s^2"
dt = 0.01
TOML
# spec NAME RECORDS_TABLE PI_DELTA_AXIS: a model-file sweep of deck.toml over the two records
spec() {
  printf '[sweep]\nname = "stale"\nfamily = "model-file"\nmodel = "deck.toml"\n[records]\n%b\n' \
    "$2" > "$1"
  printf '[axes]\nrecord = "*"\nPi_delta = %s\n[fixed]\nmu = 0.1\n' "$3" >> "$1"
}
folder='folder = "recs"\npattern = "r?.txt"\nunits = "m/s^2"\ndt = 0.01'
spec folder-small.toml "$folder" '[0.5, 1.0]'
spec folder-big.toml "$folder" '{linspace = [0.05, 3.0, 1000]}'
spec set-small.toml 'set = "set.toml"' '[0.5, 1.0]'
spec set-big.toml 'set = "set.toml"' '{linspace = [0.05, 3.0, 1000]}'

run() {  # run RANKS ARGS...: skewbridge, directly on 1 rank, through mpiexec on more
  local ranks=$1; shift
  if [ "$ranks" -eq 1 ]; then "$exe" "$@"; else on_ranks "$ranks" "$exe" "$@"; fi
}
py() { /usr/bin/python3 -c "import h5py,numpy as np,sys; f=h5py.File(sys.argv[1],'r'); g=f['sweeps/stale']; $2" "$1"; }

# interrupted RANKS SPEC OUT: a sweep stopped by SIGTERM at a checkpoint with cells done
interrupted() {
  local ranks=$1 spec=$2 out=$3 pid done_cells=0 status=0
  if [ "$ranks" -eq 1 ]; then
    "$exe" sweep "$spec" --out "$out" --quiet --checkpoint-cells 4 &
  else
    "$mpiexec" -n "$ranks" --oversubscribe "$exe" sweep "$spec" --out "$out" --quiet \
      --checkpoint-cells 4 &
  fi
  pid=$!
  interrupt_at_checkpoint "$pid" "$out.partial"
  wait "$pid" || status=$?
  [ "$status" -ne 0 ] || fail "$spec ($ranks ranks): finished before it could be interrupted"
  [ ! -f "$out" ] || fail "$spec ($ranks ranks): $out exists after an interrupted sweep"
  done_cells=$(py "$out.partial" "d=int(g['done'][()].sum()); assert 0 < d < int(g.attrs['cells']); print(d)") ||
    fail "$spec ($ranks ranks): $out.partial holds no interrupted sweep"
  echo "$spec ($ranks ranks): interrupted with $done_cells cells checkpointed"
}

# refused RANKS SPEC OUT PATTERN: --resume exits 2 with one line matching PATTERN, touching nothing
refused() {
  local ranks=$1 spec=$2 out=$3 pattern=$4 status=0 target=$3
  [ -f "$out.partial" ] && target=$out.partial
  cp "$target" before.bin
  local listing
  listing=$(ls)
  run "$ranks" sweep "$spec" --out "$out" --resume --quiet > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$spec ($ranks ranks): --resume exit $status, expected 2: $(cat err.txt)"
  local own
  own=$(grep -c "^skewbridge: error: " err.txt || true)
  [ "$own" -eq 1 ] || fail "$spec ($ranks ranks): $own error lines, expected 1: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "$spec ($ranks ranks): '$(cat err.txt)' lacks '$pattern'"
  cmp -s "$target" before.bin || fail "$spec ($ranks ranks): the refused resume changed $target"
  # Nothing may appear or change but a lock file whose holder died: mpiexec may stop a rank of
  # the interrupted sweep before its own clean-up, and the next run takes such a lock over and
  # removes it when it ends (jobs/output_lock.cpp).
  local after
  after=$(ls)
  [ "$(grep -v '\.lock$' <<< "$after")" = "$(grep -v '\.lock$' <<< "$listing")" ] &&
    [ -z "$(comm -13 <(grep '\.lock$' <<< "$listing") <(grep '\.lock$' <<< "$after"))" ] ||
    fail "$spec ($ranks ranks): the refused resume changed the folder: $(diff <(echo "$listing") <(echo "$after") | tr '\n' ' ')"
  rm before.bin
  checks=$((checks + 1))
  echo "  refused: $(grep '^skewbridge: error: ' err.txt)"
}

# edited FILE SED_SCRIPT RANKS SPEC OUT PATTERN: edit FILE, expect the refusal, restore FILE
edited() {
  local file=$1 script=$2; shift 2
  cp "$file" "$file.orig"
  sed -i -e "$script" "$file"
  cmp -s "$file" "$file.orig" && fail "the edit '$script' left $file unchanged"
  refused "$@"
  mv "$file.orig" "$file"
}

sum() { sha256sum "$1" | cut -d' ' -f1; }
changed() { echo "$1 ($2) has changed since the cube was computed from it (sha256 $(sum "$1"), now "; }

for n in 1 2; do
  echo "== $n rank(s): folder set"
  run "$n" sweep folder-small.toml --out fc$n.h5 --quiet
  # The cube names every input with the checksum sha256sum gives.
  py fc$n.h5 "
i = g['inputs']
rows = list(zip(i['role'].asstr()[()], i['file'].asstr()[()], i['sha256'].asstr()[()], i['bytes'][()]))
import hashlib, os
want = [('spec', 'folder-small.toml'), ('model', 'deck.toml'), ('excitation', 'exc/ground.txt'),
        ('record', 'recs/r1.txt'), ('record', 'recs/r2.txt')]
assert [(r, f) for r, f, _, _ in rows] == want, rows
for r, f, s, b in rows:
    assert s == hashlib.sha256(open(f, 'rb').read()).hexdigest(), (f, s)
    assert b == os.path.getsize(f), (f, b)
assert 'exc/ground.txt' in g.attrs['inputs_canonical']
" || fail "fc$n.h5: inputs/ does not list the inputs with their checksums"
  interrupted "$n" folder-big.toml fb$n.h5
  for case in "fc$n.h5 folder-small.toml" "fb$n.h5 folder-big.toml"; do
    set -- $case
    out=$1 s=$2
    edited "$s" 's/^mu = 0.1/mu = 0.2/' "$n" "$s" "$out" \
      "$out[.partial]*: cannot resume: $s: key fixed.mu differs from the specification the cube was computed with (cube: 0.1; now: 0.2); restore it"
    edited deck.toml 's/^w0 = 10.0/w0 = 10.5/' "$n" "$s" "$out" "$(changed deck.toml model)"
    edited exc/ground.txt '5s/^-*/&9/' "$n" "$s" "$out" "$(changed exc/ground.txt excitation)"
    edited recs/r2.txt '9s/^-*/&9/' "$n" "$s" "$out" "$(changed recs/r2.txt record)"
  done
  # A comment is no change: the cube is complete, the checkpoint completes.
  echo "# a comment" >> folder-small.toml
  run "$n" sweep folder-small.toml --out fc$n.h5 --resume 2> err.txt ||
    fail "fc$n.h5: --resume after a comment: $(cat err.txt)"
  grep -q "already complete" err.txt || fail "fc$n.h5: not 'already complete': $(cat err.txt)"
  run "$n" sweep folder-big.toml --out fb$n.h5 --resume --quiet ||
    fail "fb$n.h5: --resume with the inputs restored failed"
  py fb$n.h5 "assert g.attrs['complete'] == 1 and g.attrs['runs'] == 2" ||
    fail "fb$n.h5: not completed by the resume"

  echo "== $n rank(s): manifest set"
  run "$n" sweep set-small.toml --out sc$n.h5 --quiet
  py sc$n.h5 "
i = g['inputs']
assert list(i['role'].asstr()[()]) == ['spec', 'model', 'excitation', 'record-set', 'record', 'record']
assert list(i['file'].asstr()[()])[3:] == ['set.toml', 'recs/r1.txt', 'recs/r2.txt']
" || fail "sc$n.h5: inputs/ lacks the manifest and its records"
  interrupted "$n" set-big.toml sb$n.h5
  for case in "sc$n.h5 set-small.toml" "sb$n.h5 set-big.toml"; do
    set -- $case
    out=$1 s=$2
    # The manifest scales a record by 2: the same files, other accelerations.
    edited set.toml '0,/^dt = 0.01/s//dt = 0.01\nscale = 2.0/' "$n" "$s" "$out" \
      "$(changed set.toml record-set)"
    edited recs/r1.txt '7s/^-*/&9/' "$n" "$s" "$out" "$(changed recs/r1.txt record)"
  done
  run "$n" sweep set-big.toml --out sb$n.h5 --resume --quiet ||
    fail "sb$n.h5: --resume with the inputs restored failed"
  run "$n" sweep set-small.toml --out sc$n.h5 --resume 2> err.txt ||
    fail "sc$n.h5: --resume of the complete cube: $(cat err.txt)"
  grep -q "already complete" err.txt || fail "sc$n.h5: not 'already complete': $(cat err.txt)"
done
echo "stale_inputs_test: ok ($checks refusals)"
