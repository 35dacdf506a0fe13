#!/usr/bin/env bash
# End-to-end checks of the program's behaviour on failures: blow-ups, CVODE failures, signals, a
# full disk, a killed run, permission errors: exit codes, messages naming the step, time and
# place, the last good state and a failed summary. Bad input: test_cli.sh.
# Usage: test_cli_failures.sh PATH_TO_UNSATMPM
source "$(dirname "$(realpath "$0")")/cli_common.sh" "$1"
good_case > "$work/good.yaml"

# 6. A blow-up (points thrown out of the grid): exit 3, last good state and a failed summary.
good_case | sed 's/box: {min: \[0.0\], max: \[0.5\]}}/box: {min: [0.0], max: [0.5]}, initial_velocity: [500.0]}/; /name: base/d; s/^boundaries:$//' \
  > "$work/blowup.yaml"
"$exe" run "$work/blowup.yaml" --output "$work/blowup_out" --quiet 2> "$work/blowup.err"
check "blow-up exits 3" test $? -eq 3
check "blow-up message names step and point" grep -q "step .*material point" "$work/blowup.err"
check "last good state written" test -f "$work/blowup_out/points_last_good.vtu"
check "summary says failed" grep -q '"status": "failed"' "$work/blowup_out/run_summary.json"
check "failed summary names the failing step" grep -q '"failure_step": [1-9]' "$work/blowup_out/run_summary.json"
check "failed summary gives the last good state's time" grep -q '"last_good_time_s": ' "$work/blowup_out/run_summary.json"
check "last good state is not a frame of the series" sh -c "! grep -q last_good '$work/blowup_out/points.pvd'"

# The three-phase soil of the two implicit-cycle cases below (6b, 6c).
soil_1d='phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e+7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 5.0e-11,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 5.0e+5, gas_pressure: 0}}'

# 6b. A CVODE failure in the implicit cycle (tolerances CVODE cannot meet): exit 3,
# the flag's name and the time in the message, the last good state and a failed summary.
cat > "$work/cvode.yaml" <<YAML
name: cvode_failure
dimension: 1
grid: {origin: [0], size: [1], cells: [10]}
shape_function: linear
gravity: [0]
skeleton: rigid
$soil_1d
boundaries:
  - {name: top, plane: {axis: x, at: 1}, liquid: {suction: 0}, gas: {pressure: 0}}
solver: {end_time: 1, damping: 0, cycle: implicit, implicit: {relative_tolerance: 1.0e-300, absolute_tolerance: 1.0e-300}}
output: {times: [0.5]}
YAML
"$exe" run "$work/cvode.yaml" --output "$work/cvode_out" --quiet 2> "$work/cvode.err"
check "CVODE failure exits 3" test $? -eq 3
check "CVODE failure names the flag and the time" grep -q "CVODE failed (CV_.*) at t = " "$work/cvode.err"
check "CVODE failure names an unknown or says why none" grep -Eq "worst unknown: |no worst unknown" "$work/cvode.err"
check "CVODE failure: last good state written" test -f "$work/cvode_out/points_last_good.vtu"
check "CVODE failure: summary says failed" grep -q '"status": "failed"' "$work/cvode_out/run_summary.json"
check "CVODE failure: summary has the CVODE statistics" grep -q '"cvode_steps"' "$work/cvode_out/run_summary.json"

# 6b'. A soil left without water above a deep water table (the linear law's S_l = 0 from 1e5 Pa
# of suction; a uniform dry state is refused on input, test_cli.sh) fails at its first step, whose
# explicit step has no wave to set it: the summary is still JSON (no inf), its step size null.
sed -e 's/a_s: 1.0e-6}/a_s: 1.0e-5}/' \
  -e 's/initial_state: {suction: 5.0e+5, gas_pressure: 0}}/initial_state: {water_table: {elevation: -20, max_suction: 1.0e+6}, gas_pressure: 0}}/' \
  <<< "$soil_1d" > "$work/dry_soil.txt"
cat > "$work/dry_table.yaml" <<YAML
name: dry_table
dimension: 1
grid: {origin: [0], size: [1], cells: [10]}
shape_function: linear
gravity: [-9.81]
$(cat "$work/dry_soil.txt")
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
solver: {end_time: 1, damping: 0, cycle: explicit}
output: {times: [0.5]}
YAML
"$exe" run "$work/dry_table.yaml" --output "$work/dry_table_out" --quiet 2> "$work/dry_table.err"
check "a soil without water fails at its first step" test $? -eq 3
check "its summary is JSON with a null step size" /usr/bin/python3 -c \
  "import json, sys; s = json.load(open(sys.argv[1])); sys.exit(s['last_time_step_s'] is not None)" \
  "$work/dry_table_out/run_summary.json"

# 6c. The implicit cycle keeps the state after every coupling interval as the last good one: a
# mechanics blow-up (a fixed step over three times the critical one) in the second interval
# leaves the state at the end of the first (t = 0.004 s), not at t = 0.
cat > "$work/interval.yaml" <<YAML
name: implicit_blowup
dimension: 1
grid: {origin: [0], size: [1.5], cells: [30]}
shape_function: linear
gravity: [-9.81]
$soil_1d
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
solver: {end_time: 1, damping: 0, cycle: implicit, time_step: {fixed: 2.0e-3},
         implicit: {coupling_interval: 4.0e-3}}
output: {times: [0.5]}
YAML
"$exe" run "$work/interval.yaml" --output "$work/interval_out" --quiet 2> "$work/interval.err"
check "implicit blow-up exits 3" test $? -eq 3
check "implicit blow-up: last good state after the last whole interval" \
  grep -q "at step 2 (t = 0.004 s.*the last good state (t = 0.004 s)" "$work/interval.err"
# 6c'. A point whose fluid masses no pressures hold after the main cycle's undrained update (a
# saturated column of 1e-6 m^2, far beyond gravel, loaded over 10 ms: it desaturates beside its
# drained top at t = 0.034 s) is named with its state before that update, not as non-finite.
cat > "$work/gravel.yaml" <<YAML
name: gravel
dimension: 1
grid: {origin: [0], size: [1], cells: [20]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-6,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {liquid_pressure: 0, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
  - {name: top, plane: {axis: x, at: 1}, liquid: {pressure: 0}, gas: {pressure: 0},
     traction: {normal: {ramp: {from: 0, to: 1.0e+4, start: 0, end: 0.01}}}}
solver: {end_time: 0.4, damping: 0, cycle: implicit}
output: {times: []}
YAML
"$exe" run "$work/gravel.yaml" --output "$work/gravel_out" --quiet > "$work/gravel.out" \
  2> "$work/gravel.err"
check "undrained failure exits 3" test $? -eq 3
check "a permeability beyond gravel is warned about (app/plausibility.hpp)" \
  grep -qF "intrinsic_permeability = 1e-06 m^2 exceeds 1e-07 m^2" "$work/gravel.out"
check "undrained failure: the point's masses and its state before the update" \
  grep -q "material point [0-9]* at (.*) m holds fluid masses that no pressures hold after the pore pressures' update at t = .* s (before it: P_l = .* Pa, P_g = .* Pa, porosity .*); the last good state" "$work/gravel.err"
check "the main cycle's grid series starts at t = 0" \
  grep -q 'timestep="0" .*file="grid_0000.vtu"' "$work/interval_out/grid.pvd"

# 6d. SIGINT and SIGTERM end a long run after its current step: exit 128 + signal, the state
# reached written as the last frame of the series, the summary "interrupted", the lock released.
good_case | sed 's/end_time: 0.01/end_time: 1.0e+4/; s/times: \[0.005\]/times: [0.005], history_interval: 0.001/' \
  > "$work/long.yaml"
for sig in INT TERM; do
  out="$work/long_$sig"
  "$exe" run "$work/long.yaml" --output "$out" --quiet 2> "$work/long_$sig.err" &
  pid=$!
  for _ in $(seq 1 200); do test -f "$out/points_0001.vtu" && break; sleep 0.05; done  # t = 0.005 written
  kill -s "$sig" "$pid"
  wait "$pid"
  rc=$?
  expected=$([ "$sig" = INT ] && echo 130 || echo 143)
  check "SIG$sig ends the run with exit $expected" test "$rc" -eq "$expected"
  check "SIG$sig: summary says interrupted" grep -q '"status": "interrupted"' "$out/run_summary.json"
  check "SIG$sig: the message names the signal" grep -q "interrupted by SIG$sig after step" "$work/long_$sig.err"
  last=$(grep -o 'timestep="[^"]*"' "$out/points.pvd" | tail -1 | tr -dc '0-9.e+-')
  reached=$(grep -o '"simulated_time_s": [^,]*' "$out/run_summary.json" | tr -dc '0-9.e+-')
  check "SIG$sig: the last frame (t = $last s) is the state reached ($reached s)" \
    awk -v a="$last" -v b="$reached" 'BEGIN { d = a - b; exit !(b >= 0.005 && d * d <= 1e-18 * b * b) }'
  check "SIG$sig: the lock is released" test ! -e "$out/unsatmpm.lock"
done

# 11. A full disk (a 200 kB tmpfs, where this runs as root): exit 4, the message and the summary
# say "No space left on device" and name the file; the summary says failed.
mkdir -p "$work/small"
if mount -t tmpfs -o size=200k tmpfs "$work/small" 2> /dev/null; then
  sed 's/cells: \[10\]/cells: [2000]/' <(good_case) > "$work/fill.yaml"
  "$exe" run "$work/fill.yaml" --output "$work/small/out" --quiet 2> "$work/full.err"
  check "a full disk exits 4" test $? -eq 4
  check "the message names the file and the OS reason" \
    grep -q "points_0000.vtu.*No space left on device" "$work/full.err"
  check "the summary says failed" grep -q '"status": "failed"' "$work/small/out/run_summary.json"
  check "the summary says why" grep -q "No space left on device" "$work/small/out/run_summary.json"
  check "the lock is released after a full disk" test ! -e "$work/small/out/unsatmpm.lock"
  umount "$work/small"
else
  echo "note: no tmpfs mount here (not root?): the full-disk checks are skipped"
fi

# 12. A gravity loading that throws points out of the grid (no support): exit 3, the message
# names the loading, its step and time, and the last good state is written with a failed summary.
good_case | sed '/name: base/d; /^boundaries:/d; s/damping: 0.1}/damping: 0.1, gravity_loading: {damping: 0.05, tolerance: 1.0e-3, max_time: 100}}/' > "$work/falling.yaml"
"$exe" run "$work/falling.yaml" --output "$work/falling_out" --quiet 2> "$work/falling.err"
check "a failed gravity loading exits 3" test $? -eq 3
check "its message names the loading, the step and the time" \
  grep -q "gravity loading (before t = 0) failed at its step [0-9]* (loading time" "$work/falling.err"
check "its last good state is written" test -f "$work/falling_out/points_last_good.vtu"
check "its summary says failed" grep -q '"status": "failed"' "$work/falling_out/run_summary.json"

# 13. A run killed with SIGKILL just after its start still leaves a summary (saying "running",
# the truth at its last word), and the next run into its folder reports the dead one.
"$exe" run "$work/long.yaml" --output "$work/killed" --quiet 2> /dev/null &
pid=$!
for _ in $(seq 1 200); do test -f "$work/killed/run_summary.json" && break; sleep 0.02; done
kill -9 "$pid"
wait "$pid" 2> /dev/null
check "a killed run leaves a summary" grep -q '"status": "running"' "$work/killed/run_summary.json"
"$exe" run "$work/good.yaml" --output "$work/killed" --quiet 2> "$work/killed.err"
check "the next run into its folder reports it" grep -q "did not end" "$work/killed.err"

# 14. Permission errors name the file and the reason (as user nobody, where this runs as root):
# an output folder under a folder nobody may write, and a folder made read-only mid-run.
if [ "$(id -u)" -eq 0 ] && command -v runuser > /dev/null; then
  perm="$work/perm"
  mkdir -p "$perm/locked" "$perm/mine"
  chmod 755 "$work" "$perm" "$perm/locked"
  chown nobody "$perm/mine"
  cp "$work/long.yaml" "$perm/long.yaml"
  chmod 644 "$perm/long.yaml"
  runuser -u nobody -- "$exe" run "$perm/long.yaml" --output "$perm/locked/out" --quiet \
    2> "$work/perm.err"
  check "an unwritable parent folder exits 4" test $? -eq 4
  check "an unwritable parent folder: path and reason" \
    grep -q "Permission denied.*$perm/locked/out" "$work/perm.err"
  # A checkpoint every 50 ms of wall time: a new file is due soon after the folder turns
  # read-only, whatever the output times the run has already passed.
  runuser -u nobody -- "$exe" run "$perm/long.yaml" --output "$perm/mine/out" --quiet \
    --checkpoint-every 0.05 2> "$work/perm2.err" &
  pid=$!
  for _ in $(seq 1 500); do test -f "$perm/mine/out/points_0000.vtu" && break; sleep 0.01; done
  chmod 555 "$perm/mine/out"
  wait "$pid"
  check "a folder made read-only mid-run exits 4" test $? -eq 4
  check "a folder made read-only mid-run: the file and the reason" \
    grep -q "cannot write .*$perm/mine/out/.*Permission denied" "$work/perm2.err"
  chmod 755 "$perm/mine/out"
else
  echo "note: not root, or no runuser: the permission checks are skipped"
fi

echo "$pass passed, $fails failed"
test $fails -eq 0
