#!/usr/bin/env bash
# Every slip a user makes gets the program's one line: each case exits 2 with exactly the line
# given (stderr holds nothing else), prints nothing on stdout, and leaves no file behind.
# Command-line mistakes of every sub-command; the parse error on 2 ranks prints one line.
# usage: slips_test.sh SKEWBRIDGE MPIEXEC SOURCE_ROOT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec root work -- "$@"
fresh_dir "$work"
cases=0
snapshot() { find . -mindepth 1 -not -name out.txt -not -name err.txt | sort; }
expect() {  # expect LINE ARGS...: exit 2, stderr exactly "skewbridge: error: LINE", no new file
  local want="skewbridge: error: $1" status=0 before; shift
  before=$(snapshot)
  "$exe" "$@" > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$*: exit $status, expected 2: $(cat err.txt)"
  [ "$(cat err.txt)" = "$want" ] || fail "$*:
  got:  $(cat err.txt)
  want: $want"
  [ ! -s out.txt ] || fail "$*: printed on stdout: $(cat out.txt)"
  [ "$(snapshot)" = "$before" ] || fail "$*: left $(comm -13 <(echo "$before") <(snapshot))"
  cases=$((cases + 1))
  echo "ok: $want"
}
ok() {  # ok ARGS...: exit 0
  "$exe" "$@" > out.txt 2> err.txt || fail "$*: exit $?: $(cat err.txt)"
  cases=$((cases + 1))
}
spec="$root/jobs/specs/default.toml"
model="$root/docs/examples/subsystem.toml"
cp "$model" model.toml

# --- the command line, every sub-command ---
commands="version, run, modes, sweep, inspect, records, risk, restitution"
expect "unknown sub-command 'swep'; allowed: $commands; did you mean \`sweep\`?" swep x
expect "unknown sub-command 'frobnicate'; allowed: $commands" frobnicate
expect "unknown option --bogus; allowed: --help, -h, --version, -V" --bogus
expect "version: unexpected argument 'x' (see skewbridge version --help)" version x
expect "run: MODEL is required (Model file (TOML, docs/model-format.md)), or --from-cube CUBE.h5 with --cell AXIS=VALUE,... or --cell-index N" run
expect "run: unknown option --cvs; allowed: --help, -h, --csv, --out, --output-interval, --record, --format, --units, --dt, --record-set, --label, --scale, --target-sa-g, --target-pga-g, --target-rotd50-g, --incidence-deg, --from-cube, --sweep, --cell, --cell-index; did you mean \`--csv\`?" \
  run model.toml --cvs run.csv
expect "run: --output-interval: 'abc' is not a number" run model.toml --output-interval abc
expect "run: --output-interval needs a number" run model.toml --output-interval
expect "run: unexpected argument 'model.toml' (see skewbridge run --help)" run model.toml model.toml
expect "modes: MODEL is required (Model file (TOML, docs/model-format.md))" modes
expect "modes: unknown option --out; allowed: --help, -h, --plan" modes model.toml --out x.h5
expect "sweep: --out is required (Output cube FILE.h5 (checkpoints in FILE.h5.partial, lock in FILE.h5.lock))" \
  sweep "$spec"
expect "sweep: spec is required (Sweep specification (TOML, docs/sweep-format.md))" sweep --out out.h5
expect "sweep: --max-cells: '-5' is not allowed; must be > 0" sweep "$spec" --out out.h5 --max-cells -5
expect "sweep: --checkpoint-seconds: '0' is not allowed; must be > 0" \
  sweep "$spec" --out out.h5 --checkpoint-seconds 0
expect "sweep: --max-cells: 'many' is not a number" sweep "$spec" --out out.h5 --max-cells many
expect "sweep: unknown option --resmue; allowed: --help, -h, --out, -o, --resume, --force, --quiet, -q, --checkpoint-seconds, --checkpoint-cells, --max-cells, --dry-run, --ranks, --sample-cells, --scale-table; did you mean \`--resume\`?" \
  sweep "$spec" --out out.h5 --resmue
expect "restitution: --velocity-mps: speeds must be > 0 m/s (got -1)" \
  restitution --mass-kg 1e3 --k-max-Npm 1e8 --r-f 0.7 --f-ult-N 1e6 --velocity-mps -1
expect "restitution: law: give exactly one of --k-max-Npm (OpenSees constants with --r-f and --f-ult-N), --k50-Npm (Shamsabadi, with --f-ult-N and --height-m or --y-max-m), --caltrans (with --width-m and --height-m), --spring-Npm (linear spring-dashpot, with --damping-ratio)" \
  restitution --mass-kg 1e3 --velocity-mps 1
expect "inspect: file is required (Cube FILE.h5 (or FILE.h5.partial))" inspect
expect "records: a sub-command is required; allowed: info, spectrum, synth" records
expect "records: unknown sub-command 'inf'; allowed: info, spectrum, synth; did you mean \`info\`?" records inf x
expect "records info: path is required (record file, or record-set manifest (.toml))" records info
expect "records info: --dt: 'abc' is not a number" records info x.txt --dt abc
expect "records info: --channel: '1.5' is not a whole number" records info x.txt --channel 1.5
expect "records info: --csv excludes --json (see skewbridge records info --help)" \
  records info x.txt --csv --json
expect "records synth: --seed is required (seed of the suite)" records synth --count 3 --out suite
# --help and --version still exit 0.
ok --help
ok --version
ok sweep --help
ok records info --help
# --- the wall friction of compliant abutments: a coefficient >= 0, a number ---
cp "$root/docs/examples/pilot-bridge-compliant.toml" "$root/docs/examples/pilot-signal.txt" .
sed 's/^law = "compliant"$/&\nmu = -0.2/' pilot-bridge-compliant.toml > wall_mu.toml
expect "wall_mu.toml:31: abutments.mu: must be >= 0 (got -0.2)" run wall_mu.toml --out run.h5
sed 's/^law = "compliant"$/&\nmu = "rough"/' pilot-bridge-compliant.toml > wall_mu_text.toml
expect "wall_mu_text.toml:31: abutments.mu: must be a number" run wall_mu_text.toml --out run.h5
sed 's/^law = "compliant"$/&\nmu = nan/' pilot-bridge-compliant.toml > wall_mu_nan.toml
expect "wall_mu_nan.toml:31: abutments.mu: must be a finite number (got nan)" modes wall_mu_nan.toml
sed 's/^law = "compliant"$/&\nstick_stiffness_Npm = 1e9/' pilot-bridge-compliant.toml > wall_kt.toml
expect "wall_kt.toml:31: abutments.stick_stiffness_Npm: belongs to a wall with friction (mu > 0)" \
  run wall_kt.toml --out run.h5
# a sweep's eps_N over compliant abutments (their springs have no restitution; mu is allowed)
printf '[sweep]\nname = "c"\nfamily = "model-file"\nmodel = "pilot-bridge-compliant.toml"\n[axes]\nscale = [1.0, 2.0]\n[fixed]\nmu = 0.2\neps_N = 0.4\n' \
  > compliant_eps.toml
expect "compliant_eps.toml:9: fixed.eps_N: the abutments of pilot-bridge-compliant.toml are compliant (law = \"compliant\"), whose springs have no restitution; remove eps_N (mu, the backwall friction, and every other key of family 'model-file' are allowed)" \
  sweep compliant_eps.toml --out out.h5
# --- misspelt keys of model files and sweep specifications: unknown, with the nearest ---
sed 's/^skew_deg = /skew = /' model.toml > skew.toml
expect "skew.toml:12: deck.skew: unknown key (allowed: m, I_m, L, W, eta0, skew_deg); did you mean \`skew_deg\`?" \
  run skew.toml --out run.h5 --csv run.csv
sed 's/^W0 = /w_theta = /' model.toml > w_theta.toml
expect "w_theta.toml:17: substructure.w_theta: unknown key (allowed: kind, w0, w0x, w0y, W0, xi, C (with kind = \"uncoupled\")); it is a key of kind = \"principal\"" \
  modes w_theta.toml
sed 's/^\[excitation\]/[excitaton]/' model.toml > section.toml
expect "section.toml:26: excitaton: unknown section (allowed: deck, substructure, abutments, excitation, run); did you mean \`excitation\`?" \
  run section.toml --out run.h5
sed 's/^a_deg = /skew = /' "$spec" > skew_spec.toml
expect "skew_spec.toml:10: axes.skew: unknown parameter; allowed: record, pulse, incidence_deg, spans, a_g_g, w_g, T_g, scale, im_g, im_mps, a_deg, eta0, W_over_L, delta_over_L, L_over_Le, W0_over_w0, xi, eps_N, mu, Pi_delta, gap_m, k_factor, seat_over_L, seat_m, w0_over_wg, method; did you mean \`a_deg\` (skew angle a)?" \
  sweep skew_spec.toml --out out.h5
# --- compliant abutments' shear keys: a broken backbone, a key table under the rigid law ---
cp "$root/docs/examples/pilot-bridge-compliant-keys.toml" "$root/docs/examples/pilot-signal.txt" .
sed 's/^dd_m = .*/dd_m = 0.01/' pilot-bridge-compliant-keys.toml > keys_dd.toml
expect "keys_dd.toml:43: abutments.shear_keys.dd_m: must be > d3_m = 0.0313436 m (got 0.01)" \
  run keys_dd.toml --out run.h5
sed 's/^\[excitation\]/[abutments.shear_keys]\ngap_m = 0.01\n\n&/' "$root/docs/examples/pilot-bridge.toml" \
  > keys_rigid.toml
expect "keys_rigid.toml:30: abutments.shear_keys: belongs to law = \"compliant\" (the law here is \"impact\")" \
  run keys_rigid.toml --out run.h5
# --- a compliant law per wall: a key for both walls beside a wall's table, a wall's table missing
# or outside the set, springs for one wall of two ---
cp "$root/docs/examples/pilot-bridge-one-keyed-abutment.toml" one_keyed.toml
sed 's/^\[abutments.backfill."+x"\]/[abutments.backfill]/' one_keyed.toml > wall_mix.toml
expect "wall_mix.toml:37: abutments.backfill.form: a key for both walls beside the per-wall table [abutments.backfill.\"-x\"]: give one table for both walls or one per wall, not both" \
  run wall_mix.toml --out run.h5
awk '/^\[abutments.backfill."-x"\]/ { skip = 1; next } /^\[/ { skip = 0 } !skip' one_keyed.toml \
  > wall_missing.toml
expect "wall_missing.toml:36: abutments.backfill.\"-x\": missing required key (the -x wall's backfill: a table [abutments.backfill.\"-x\"])" \
  run wall_missing.toml --out run.h5
sed -e 's/^set = "both"/set = "+x"/' -e 's/^gap_m = .*/gap_m = 0.008/' -e 's/^springs = .*/springs = 5/' \
  one_keyed.toml > wall_set.toml
expect "wall_set.toml:42: abutments.backfill.\"-x\": no -x wall with set = \"+x\" (allowed: \"+x\")" \
  run wall_set.toml --out run.h5
sed 's/^springs = .*/springs = { "+x" = 5 }/' one_keyed.toml > wall_springs.toml
expect "wall_springs.toml:34: abutments.springs.\"-x\": missing required key (springs along the -x wall, 2 to 1000)" \
  run wall_springs.toml --out run.h5
sed 's/^\[abutments.shear_keys."+x"\]/[abutments.shear_keys]\ngap_m = 0.002\n\n&/' one_keyed.toml \
  > keys_mix.toml
expect "keys_mix.toml:48: abutments.shear_keys.gap_m: a key for both walls beside the per-wall table [abutments.shear_keys.\"+x\"]: give one table for both walls or one per wall, not both" \
  run keys_mix.toml --out run.h5
# --- a friction per wall: both walls of the set, a wall's stick stiffness with its own mu, the
# rigid law's mu one number ---
sed 's/^springs = .*/&\nmu = { "+x" = 0.3 }/' one_keyed.toml > wall_mu_one.toml
expect "wall_mu_one.toml:35: abutments.mu.\"-x\": missing required key (the Coulomb friction coefficient of the -x wall, >= 0)" \
  run wall_mu_one.toml --out run.h5
sed 's/^springs = .*/&\nmu = { "+x" = 0.3, "-x" = -0.1 }/' one_keyed.toml > wall_mu_neg.toml
expect "wall_mu_neg.toml:35: abutments.mu.\"-x\": must be >= 0 (got -0.1)" \
  run wall_mu_neg.toml --out run.h5
sed 's/^springs = .*/&\nmu = { "+x" = 0.3, "-x" = 0 }\nstick_stiffness_Npm = { "-x" = 1e9 }/' \
  one_keyed.toml > wall_kt_minus.toml
expect "wall_kt_minus.toml:36: abutments.stick_stiffness_Npm.\"-x\": belongs to a wall with friction (the -x wall's mu is 0; give it mu > 0 or omit its stick stiffness)" \
  run wall_kt_minus.toml --out run.h5
sed -e 's/^set = "both"/set = "+x"/' -e 's/^gap_m = .*/gap_m = 0.008/' -e 's/^springs = .*/springs = 5\nmu = { "+x" = 0.3, "-x" = 0.1 }/' \
  one_keyed.toml > wall_mu_set.toml
expect "wall_mu_set.toml:35: abutments.mu.\"-x\": no -x wall with set = \"+x\" (allowed: \"+x\")" \
  run wall_mu_set.toml --out run.h5
sed 's/^mu = 0.3$/mu = { "+x" = 0.3, "-x" = 0.1 }/' "$root/docs/examples/pilot-bridge.toml" \
  > rigid_mu_walls.toml
expect "rigid_mu_walls.toml:28: abutments.mu: a friction per wall belongs to law = \"compliant\"; with law = \"impact\" give one number, or one per corner in [abutments.contacts.P1] (mu)" \
  run rigid_mu_walls.toml --out run.h5
# --- a law per abutment: a table of both abutments with set = "both", a single deck, the rigid
# wall without springs, keys or a stick stiffness, the compliant wall's corners without contacts ---
cp "$root/docs/examples/pilot-bridge-mixed.toml" mixed.toml
sed 's/^set = "both"/set = "+x"/' mixed.toml > law_set.toml
expect "law_set.toml:29: abutments.law: a law per abutment needs set = \"both\"; with set = \"+x\" give one law (allowed: \"impact\", \"compliant\")" \
  run law_set.toml --out run.h5
sed 's/^law = .*/law = { "+x" = "impact" }/' mixed.toml > law_one.toml
expect "law_one.toml:29: abutments.law.\"-x\": missing required key (the law of the -x abutment: \"impact\" or \"compliant\")" \
  run law_one.toml --out run.h5
sed 's/^law = .*/law = { "+x" = "impact", "-x" = "springy" }/' mixed.toml > law_bad.toml
expect "law_bad.toml:29: abutments.law.\"-x\": must be one of impact, compliant (got \"springy\")" \
  run law_bad.toml --out run.h5
sed 's/^\[abutments.backfill\].*/[abutments.backfill."+x"]/' mixed.toml > law_backfill.toml
expect "law_backfill.toml:34: abutments.backfill.\"+x\": the +x abutment's law is \"impact\" (rigid contacts, no springs or keys); allowed: \"-x\"" \
  run law_backfill.toml --out run.h5
sed 's/^springs = .*/springs = { "+x" = 5, "-x" = 5 }/' mixed.toml > law_springs.toml
expect "law_springs.toml:32: abutments.springs.\"+x\": the +x abutment's law is \"impact\" (rigid contacts, no springs or keys); allowed: \"-x\"" \
  run law_springs.toml --out run.h5
sed 's/^\[excitation\]/[abutments.shear_keys."+x"]\ngap_m = 0.01\nv_n_N = 1e6\nd3_m = 0.01\ndd_m = 0.05\n\n&/' \
  mixed.toml > law_keys.toml
expect "law_keys.toml:40: abutments.shear_keys.\"+x\": the +x abutment's law is \"impact\" (rigid contacts, no springs or keys); allowed: \"-x\"" \
  run law_keys.toml --out run.h5
sed 's/^springs = .*/&\nstick_stiffness_Npm = 1e9/' mixed.toml > law_kt.toml
expect "law_kt.toml:33: abutments.stick_stiffness_Npm: belongs to a compliant wall with friction (the -x wall's mu is 0)" \
  run law_kt.toml --out run.h5
sed 's/^springs = .*/&\n\n[abutments.contacts.P3]\neps_N = 0.6/' mixed.toml > law_p3.toml
expect "law_p3.toml:34: abutments.contacts.P3: P3 is a corner of the -x wall, whose law is \"compliant\" (springs, no rigid contact); allowed: P1, P2" \
  run law_p3.toml --out run.h5
awk '/^\[abutments.backfill\]/ { skip = 1; next } /^\[/ { skip = 0 } !skip' mixed.toml > law_nobackfill.toml
expect "law_nobackfill.toml:26: abutments.backfill: missing required key (the backfill of the compliant -x wall: a table [abutments.backfill])" \
  run law_nobackfill.toml --out run.h5
sed 's/^tail_s = .*/&\nmethod = "time-stepping"/' mixed.toml > law_ts.toml
expect "law_ts.toml:48: run.method: a law per abutment (abutments.law, one wall compliant) runs with the event-driven method only (allowed: \"event-driven\")" \
  run law_ts.toml --out run.h5
sed 's/^\[abutments\].*/&\nlaw = { "+x" = "impact", "-x" = "compliant" }/' "$root/docs/examples/three-span.toml" \
  > law_decks.toml
expect "law_decks.toml:25: joint[0].law: missing required key (the abutments have a law per abutment, one of each: give each joint its law, \"impact\" or \"compliant\")" \
  run law_decks.toml --out run.h5
# A row with a rigid joint[0] and a compliant joint[1] (a spring-dashpot), the abutments rigid.
sed '32,33c law = "compliant"\n\n[joint.spring_dashpot]\nk_Npm = 1.0e9\nc_Nspm = 7.4e6' \
  "$root/docs/examples/three-span.toml" > law_row.toml
sed 's/^tail_s = .*/&\nmethod = "time-stepping"/' law_row.toml > law_row_ts.toml
expect "law_row_ts.toml:76: run.method: a row with compliant joints (abutments.law, joint[i].law) runs with the event-driven method only (allowed: \"event-driven\")" \
  run law_row_ts.toml --out run.h5
sed -e '26a law = "impact"' \
  -e '41a law = { "+x" = "impact", "-x" = "compliant" }\nsprings = 5\n\n[abutments.backfill]\nform = "caltrans"\nwidth_m = 12.0\nheight_m = 2.0\n\n[abutments.contacts.P1]\neps_N = 0.6' \
  law_row.toml > law_row_p1.toml
expect "law_row_p1.toml:51: abutments.contacts: unknown key (allowed: set, gap_m, law, eps_N, mu, springs, backfill, stick_stiffness_Npm, shear_keys (with [[deck]] tables))" \
  run law_row_p1.toml --out run.h5
sed '41a law = "compliant"\nsprings = 5\n\n[abutments.backfill]\nform = "caltrans"\nwidth_m = 12.0\nheight_m = 2.0' \
  law_row.toml | sed '/^eps_N = 0.5$/d; /^mu = 0.2$/d' > law_row_taken.toml
expect "law_row_taken.toml:25: joint[0].backfill: missing required key (the joint's law, compliant as [abutments] law is: a table [joint.backfill] or [joint.spring_dashpot] with k_Npm and c_Nspm, or law = \"impact\" for a rigid joint)" \
  run law_row_taken.toml --out run.h5
# --- the wrong kind of file, named as what it is ---
cp "$spec" spec.toml
for command in run modes; do
  expect "spec.toml: this is a sweep specification ([sweep] table), not a model file (docs/model-format.md); \`skewbridge sweep SPEC --out FILE.h5\` takes it" \
    $command spec.toml
done
expect "model.toml: this is a model file ([deck] table), not a sweep specification (docs/sweep-format.md); \`skewbridge run\` and \`skewbridge modes\` take it, and a sweep of it names it in [sweep] model = \"FILE\" with family = \"model-file\"" \
  sweep model.toml --out out.h5
printf '[sweep]\nname = "m"\nfamily = "model-file"\nmodel = "spec.toml"\n[axes]\nscale = [1.0, 2.0]\n' > of_spec.toml
expect "spec.toml: this is a sweep specification ([sweep] table), not a model file (docs/model-format.md); \`skewbridge sweep SPEC --out FILE.h5\` takes it" \
  sweep of_spec.toml --out out.h5
printf 'name = "set"\n[[record]]\nfile = "a.AT2"\n' > set.toml
expect "set.toml: this is a record-set manifest ([[record]] tables), not a model file (docs/model-format.md); \`skewbridge records info\` and a sweep's [records] set take it" \
  run set.toml

expect "spec.toml: this is a sweep specification ([sweep] table), not a record-set manifest (docs/records.md); \`skewbridge sweep SPEC --out FILE.h5\` takes it" \
  records info spec.toml
printf 'name = "s"\n[[record]]\nfile = "a.AT2"\nlable = "A"\n' > lable.toml
expect "lable.toml:4: lable: unknown key (allowed: file, label, component, scale, units, dt, format, channel, max_pga_g; h1, h2, component_h1, component_h2 for a pair); did you mean \`label\`?" \
  records info lable.toml

# An HDF5 file (a run file here) or a record file where a TOML file belongs.
"$exe" run model.toml --out cube.h5 > /dev/null || fail "run --out cube.h5"
for command in run modes; do
  expect "cube.h5: this is an HDF5 file (a sweep cube or a run file), not a model file (TOML, docs/model-format.md); \`skewbridge inspect\` summarises a cube" \
    $command cube.h5
done
expect "cube.h5: this is an HDF5 file (a sweep cube or a run file), not a sweep specification (TOML, docs/sweep-format.md); \`skewbridge inspect\` summarises a cube" \
  sweep cube.h5 --out out.h5
expect "cube.h5: this is an HDF5 file (a sweep cube or a run file), not a record; \`skewbridge inspect\` summarises a cube" \
  records info cube.h5
cp "$root/tests/data/records/NIS090.AT2" .
expect "NIS090.AT2:1: syntax error: Error while parsing key-value pair: expected '=', saw 'N' (a model file is TOML, docs/model-format.md)" \
  run NIS090.AT2

# --- records info, inspect: what is really wrong ---
awk 'BEGIN { for (i = 0; i < 200; i++) printf "%.6f\n", 0.1 * sin(0.1 * i) }' > bare.txt
expect "records info: --dt: must be a time step > 0 s (got 0)" records info bare.txt --units g --dt 0
expect "records info: --dt: must be a time step > 0 s (got -0.01)" records info bare.txt --units g --dt -0.01
ok records info bare.txt --units g --dt 0.01
mkdir recs
cp "$root/tests/data/records/NIS090.AT2" "$root/tests/data/records/RSN763_LOMAP_GIL067.AT2" recs/
expect "recs: is a folder; \`records info\` takes a record file or a record-set manifest .toml (a folder of records is a set through a sweep's [records] folder and pattern)" \
  records info recs
expect "nothere.AT2: the file does not exist (\`records info\` takes a record file or a record-set manifest .toml)" \
  records info nothere.AT2
expect "nothere.h5: the file does not exist" inspect nothere.h5
expect "recs: is a folder; \`inspect\` takes a cube file FILE.h5 (or FILE.h5.partial)" inspect recs
# --- an unknown record label: the nearest labels of the set, and that labels keep extensions ---
printf '[sweep]\nname = "r"\nfamily = "pilot-bridge"\n[records]\nfolder = "recs"\npattern = "*.AT2"\n[axes]\nrecord = ["NIS090"]\nPi_delta = [1.0]\n' > folder_spec.toml
expect "folder_spec.toml: record: label 'NIS090' is not in the records of folder recs (pattern *.AT2) of 2 record(s); nearest: NIS090.AT2, RSN763_LOMAP_GIL067.AT2; the labels of a folder set are the file names, extension included" \
  sweep folder_spec.toml --out out.h5
printf 'name = "s"\n[[record]]\nfile = "recs/NIS090.AT2"\n[[record]]\nfile = "recs/RSN763_LOMAP_GIL067.AT2"\nlabel = "LOMAP"\n' > labels.toml
printf '[sweep]\nname = "r"\nfamily = "pilot-bridge"\n[records]\nset = "labels.toml"\n[axes]\nrecord = ["LOMA"]\nPi_delta = [1.0]\n' > set_spec.toml
expect "set_spec.toml: record: label 'LOMA' is not in the record set labels.toml of 2 record(s); nearest: LOMAP, NIS090.AT2" \
  sweep set_spec.toml --out out.h5
# A set entry whose file is missing: "no such file" at the set's line of that record.
printf 'name = "s"\n[[record]]\nfile = "recs/NIS090.AT2"\n[[record]]\nfile = "recs/GONE.AT2"\nlabel = "GONE"\n' > gone.toml
printf '[sweep]\nname = "r"\nfamily = "pilot-bridge"\n[records]\nset = "gone.toml"\n[axes]\nrecord = ["GONE"]\nPi_delta = [1.0]\n' > gone_spec.toml
expect "gone.toml:4: record 'GONE': no such file: recs/GONE.AT2" sweep gone_spec.toml --out out.h5
# A folder of record pairs: a file without its other component, then a pair of two time steps.
mkdir pf
cp "$root"/tests/data/records/pairs/RSN107_* "$root/tests/data/records/pairs/RSN430_SMART1.25_25M01EW.AT2" pf/
printf '[sweep]\nname = "r"\nfamily = "pilot-bridge"\n[records]\nfolder = "pf"\npattern = "*.AT2"\npairs = true\n[axes]\nrecord = "*"\nPi_delta = [1.0]\n' > pairs_spec.toml
expect "pairs_spec.toml:7: records.pairs: unpaired file RSN430_SMART1.25_25M01EW.AT2 of pf: no other file matching '*.AT2' differs from its name only in the component (one run without '_', '-', '.' or blank, as 180 and 270, EW and NS); allowed: two files per station, or pairs = \"TABLE.csv\" naming them" \
  sweep pairs_spec.toml --out out.h5
sed 's/DT=   .0100/DT=   .0050/' "$root/tests/data/records/pairs/RSN430_SMART1.25_25M01NS.AT2" > pf/RSN430_SMART1.25_25M01NS.AT2
expect "pf/RSN430_SMART1.25_25M01EW.AT2, pf/RSN430_SMART1.25_25M01NS.AT2: the two components of a pair have different time steps (0.01 s and 0.005 s); allowed: two components sampled at one dt (resample one of them outside skewbridge)" \
  sweep pairs_spec.toml --out out.h5

# Under mpiexec the command line fails on every rank: one line, exit 2.
status=0
on_ranks 2 "$exe" sweep "$spec" > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] || fail "2 ranks: exit $status: $(cat err.txt)"
[ "$(grep -c '^skewbridge: error: ' err.txt)" -eq 1 ] || fail "2 ranks: $(cat err.txt)"
grep -qx "skewbridge: error: sweep: --out is required (.*)" err.txt || fail "2 ranks: $(cat err.txt)"
cases=$((cases + 1))
echo "slips_test: $cases cases ok"
