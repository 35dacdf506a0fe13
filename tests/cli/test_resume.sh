#!/usr/bin/env bash
# Checkpoint and resume end to end (docs/output.md, "Checkpoints and resume"): a run killed with
# SIGKILL part-way and resumed with `unsatmpm resume` writes the same files, bit for bit, as a run
# that was never interrupted (the explicit cycles and the main cycle with a deformable skeleton;
# with a rigid one, the pressures agree within ten times CVODE's error weight); checkpoints at
# wall-time intervals, a second kill, SIGINT, a finished run, damaged checkpoints, and a run whose
# reader has gone.
# Usage: test_resume.sh PATH_TO_UNSATMPM
here=$(dirname "$(realpath "$0")")
source "$here/cli_common.sh" "$1"
cd "$work"

# run_and_kill CASE DIR FILE [options]: starts a run into DIR and kills it with SIGKILL once FILE
# exists in DIR; true if the run was still going when killed.
run_and_kill() {
  local case=$1 dir=$2 file=$3; shift 3
  "$exe" run "$case" -o "$dir" -q "$@" &
  local pid=$!
  for _ in $(seq 1 3000); do [ -e "$dir/$file" ] && break; sleep 0.01; done
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  grep -q '"status": "running"' "$dir/run_summary.json"
}

# same_outputs A B: every file of A but the checkpoint and the summary is in B, bit for bit.
same_outputs() {
  local f ok=0
  for f in "$1"/*; do
    case $(basename "$f") in checkpoint.bin | run_summary.json | unsatmpm_manifest.txt) continue ;; esac
    cmp -s "$f" "$2/$(basename "$f")" || { echo "  differs: $(basename "$f")" >&2; ok=1; }
  done
  [ "$(ls "$1" | wc -l)" -eq "$(ls "$2" | wc -l)" ] || { echo "  file counts differ" >&2; ok=1; }
  return $ok
}

# One-phase, 2D GIMP, Mohr-Coulomb under a ramped surface load.
cat > one_phase.yaml <<'YAML'
name: block
dimension: 2
grid: {origin: [0, 0], size: [1, 2], cells: [20, 40]}
shape_function: gimp
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: mohr_coulomb, young_modulus: 1.0e+6, poisson_ratio: 0.3,
     friction_angle: 30, dilatancy_angle: 0, cohesion: 1000}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1.5]}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 1}, mechanical: roller}
  - name: top
    plane: {axis: y, at: 1.5}
    traction: {normal: {ramp: {from: 0, to: 2.0e+4, start: 0, end: 0.5}}}
solver: {end_time: 2.5, damping: 0.02}
output:
  times: [0.5, 1, 1.5, 2]
  history_interval: 0.01
  control_points: [{name: "top, middle", position: [0.5, 1.5]}]
YAML

# V9's loaded saturated column, in the `cycle` given.
column() {
  sed -e "s/^  end_time: .*/  end_time: 0.4/" \
      -e "s/^  times: .*/  times: [0.008, 0.04, 0.08, 0.12, 0.2, 0.3]/" \
      -e "s/^  cycle: implicit/  cycle: $1/" "$here/../../verification/terzaghi_load/case.yaml"
}
column explicit > three_phase.yaml
column implicit > main_deformable.yaml
# V1's infiltration into a rigid column, in the main cycle.
sed -e "s/^  end_time: 6 .*/  end_time: 6\n  cycle: implicit/" \
  "$here/../../verification/infiltration/case.yaml" > main_rigid.yaml

# V16's heavy rain in the main cycle, its top half a cell past a node line (1/512 m cells): the
# nodes' modes and the top points' ponding pressures (cycles/top_row_pressures.hpp) rebuilt on
# resuming as the uninterrupted run has them.
sed -e "s/cells: \[160\]/cells: [640]/" -e "s/max: \[1\]}/max: [1.0009765625]}/" \
  -e "s/^  times: \[3\]/  times: [0.5, 1, 1.5, 2, 2.5, 3]/" \
  "$here/../../verification/rain/case.yaml" > main_rain.yaml

# 1. Killed and resumed: the same files as an uninterrupted run.
for c in one_phase three_phase main_deformable main_rain; do
  threads=1
  [ $c = three_phase ] && threads=2
  "$exe" run $c.yaml -o ${c}_whole -q -t $threads
  check "$c: the uninterrupted run completes" grep -q '"status": "completed"' ${c}_whole/run_summary.json
  check "$c: killed part-way" run_and_kill $c.yaml ${c}_resumed points_0002.vtu -t $threads
  "$exe" resume ${c}_resumed -q -t $threads
  check "$c: resume exits 0" test $? -eq 0
  check "$c: resumed run completes" grep -q '"status": "completed"' ${c}_resumed/run_summary.json
  check "$c: the summary counts the resume" grep -q '"resumes": 1' ${c}_resumed/run_summary.json
  check "$c: series and histories bit for bit" same_outputs ${c}_whole ${c}_resumed
  check "$c: the same steps" test "$(grep '"steps"' ${c}_whole/run_summary.json)" = \
    "$(grep '"steps"' ${c}_resumed/run_summary.json)"
done

# 2. The rigid main cycle: CVODE restarts where the uninterrupted run's ran on.
"$exe" run main_rigid.yaml -o rigid_whole -q
check "rigid: killed part-way" run_and_kill main_rigid.yaml rigid_resumed points_0002.vtu
"$exe" resume rigid_resumed -q
check "rigid: resume exits 0" test $? -eq 0
check "rigid: the histories' and series' files are all there" test "$(ls rigid_whole | wc -l)" -eq "$(ls rigid_resumed | wc -l)"
check "rigid: pressures within 10 (rtol max|P| + atol) of the uninterrupted run" \
  /usr/bin/python3 - rigid_whole rigid_resumed <<'PY'
import glob, os, sys
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy
def fields(f):
    r = vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update()
    pd = r.GetOutput().GetPointData()
    return {k: vtk_to_numpy(pd.GetArray(k)) for k in ("liquid_pressure", "gas_pressure")}
rtol, atol, worst = 1e-6, 1.0, 0.0
for f in sorted(glob.glob(os.path.join(sys.argv[1], "points_0*.vtu"))):
    a, b = fields(f), fields(os.path.join(sys.argv[2], os.path.basename(f)))
    for k in a:
        ratio = np.abs(a[k] - b[k]).max() / (10 * (rtol * np.abs(a[k]).max() + atol))
        worst = max(worst, ratio)
print("rigid resume: largest difference / bound = %.3f" % worst)
sys.exit(0 if worst <= 1.0 else 1)
PY

# 3. Checkpoints at wall-time intervals (between output times), and a second kill.
sed -e 's/^  times: .*/  times: [2]/' one_phase.yaml > sparse.yaml
# kill_after_new_checkpoint PID: SIGKILL once the checkpoint in sparse_resumed is replaced (a new
# file: the atomic rename gives it a new inode); true if it was.
kill_after_new_checkpoint() {
  for _ in $(seq 1 500); do [ -e sparse_resumed/checkpoint.bin ] && break; sleep 0.01; done
  local first
  first=$(stat -c %i sparse_resumed/checkpoint.bin)
  for _ in $(seq 1 1000); do
    [ "$(stat -c %i sparse_resumed/checkpoint.bin)" != "$first" ] && break
    sleep 0.01
  done
  kill -9 "$1"
  wait "$1" 2>/dev/null
  [ "$(stat -c %i sparse_resumed/checkpoint.bin)" != "$first" ] &&
    grep -q '"status": "running"' sparse_resumed/run_summary.json
}
"$exe" run sparse.yaml -o sparse_whole -q
"$exe" run sparse.yaml -o sparse_resumed -q --checkpoint-every 0.3 &
check "a wall-time checkpoint between output times, then killed" kill_after_new_checkpoint $!
# The histories were rewritten with that checkpoint: rows past t = 0, though no output time passed.
check "a wall-time checkpoint brings the histories up to date" \
  awk -F, 'NR > 2 && $1 > 0 { found = 1 } END { exit !found }' sparse_resumed/globals.csv
"$exe" resume sparse_resumed -q --checkpoint-every 0.3 &
check "the resumed run's own wall-time checkpoint, then killed again" kill_after_new_checkpoint $!
check "the summary counts the first resume" grep -q '"resumes": 1' sparse_resumed/run_summary.json
"$exe" resume sparse_resumed -q
check "resumed twice: completes" grep -q '"status": "completed"' sparse_resumed/run_summary.json
check "resumed twice: bit for bit" same_outputs sparse_whole sparse_resumed

# 4. SIGINT writes a checkpoint of the state reached; resume finishes the run.
"$exe" run one_phase.yaml -o interrupted -q &
pid=$!
for _ in $(seq 1 3000); do [ -e interrupted/points_0001.vtu ] && break; sleep 0.01; done
kill -INT $pid; wait $pid
check "SIGINT exits 130" test $? -eq 130
"$exe" resume interrupted -q
check "resume after SIGINT completes" grep -q '"status": "completed"' interrupted/run_summary.json

# 5. A finished run has nothing to resume, and is left as it is.
cp one_phase_whole/run_summary.json summary_before.json
"$exe" resume one_phase_whole 2> finished.err
check "resume of a finished run exits 0" test $? -eq 0
check "resume of a finished run says so" grep -q "nothing to resume" finished.err
check "a finished run's summary is untouched" cmp -s summary_before.json one_phase_whole/run_summary.json

# 6. Folders without a checkpoint, and damaged checkpoints: exit 1, a message naming the file.
"$exe" resume no_such_folder 2> missing.err
check "resume of a missing folder exits 1" test $? -eq 1
check "missing folder: message names the checkpoint" grep -q "no_such_folder/checkpoint.bin" missing.err
cp -r one_phase_resumed damaged
truncate -s -9 damaged/checkpoint.bin
"$exe" resume damaged 2> damaged.err
check "truncated checkpoint exits 1" test $? -eq 1
check "truncated checkpoint: message says so" grep -q "checkpoint 'damaged/checkpoint.bin': truncated" damaged.err
check "truncated checkpoint: nothing deleted" test -e damaged/points_0004.vtu
cp one_phase_resumed/checkpoint.bin damaged/checkpoint.bin
printf '\x63' | dd of=damaged/checkpoint.bin bs=1 seek=16 conv=notrunc 2>/dev/null
"$exe" resume damaged 2> version.err
check "checkpoint of another format version exits 1" test $? -eq 1
check "another version: message names it" grep -q "checkpoint format version 99" version.err

# 7. A run that stops at rest (solver.stop_at_rest): killed after the kinetic energy's peak and
# resumed, it stops at the same step as an uninterrupted run (the peak is in the checkpoint); a
# run that has come to rest has nothing to resume.
cat > settling.yaml <<'YAML'
name: settling
dimension: 2
grid: {origin: [0, 0], size: [1, 1.5], cells: [60, 90]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: linear_elastic, young_modulus: 1.0e+6, poisson_ratio: 0.3}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1]}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 1}, mechanical: roller}
solver:
  end_time: 5
  damping: 0.3
  stop_at_rest: {fraction: 1.0e-3, hold: 0.1, min_peak: 1.0e-3}
output:
  times: [0.1, 0.15, 0.4, 0.6]
  history_interval: 0.01
YAML
"$exe" run settling.yaml -o settling_whole -q
check "settling: stops at rest, completed" grep -q '"message": "at rest at t = 0.2' settling_whole/run_summary.json
check "settling: the state at rest is the last frame" test -e settling_whole/points_0003.vtu -a ! -e settling_whole/points_0004.vtu
check "settling: killed part-way" run_and_kill settling.yaml settling_resumed points_0002.vtu
"$exe" resume settling_resumed -q
check "settling: resumed run completes" grep -q '"status": "completed"' settling_resumed/run_summary.json
check "settling: series and histories bit for bit" same_outputs settling_whole settling_resumed
"$exe" resume settling_whole 2> rest.err
check "resume of a run at rest exits 0" test $? -eq 0
check "resume of a run at rest says so" grep -q "came to rest at t = 0.2.*nothing to resume" rest.err

# 8. SIGINT inside a long flow integration: one main-cycle step of 12.8 s on this machine kind
# (a rigid block wetted from its top, the whole run one coupling interval at rtol 1e-10). The
# step is abandoned within a second, not after it ends; its start is written as the last good
# state; a resumed run starts from the checkpoint and is interrupted the same way.
cat > long_step.yaml <<'YAML'
name: long_step
dimension: 2
grid: {origin: [0, 0], size: [1, 1], cells: [40, 40]}
shape_function: linear
gravity: [0, 0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e+7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
pressure_update: nodal
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 5.0e-11,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1]},
     initial_state: {suction: 5.0e+5, gas_pressure: 0}}
boundaries:
  - {name: top, plane: {axis: y, at: 1}, liquid: {suction: 0}, gas: {pressure: 0}}
solver:
  end_time: 60
  damping: 0
  cycle: implicit
  implicit: {coupling_interval: 60, relative_tolerance: 1.0e-10, absolute_tolerance: 1.0e-6}
output: {times: []}
YAML
# sigint_inside_step PID: SIGINT one second into the step; true if the run then exits 130 within
# 3 s (the step itself lasts 12.8 s).
sigint_inside_step() {
  sleep 1
  kill -INT "$1"
  for _ in $(seq 1 300); do kill -0 "$1" 2>/dev/null || break; sleep 0.01; done
  wait "$1"
  test $? -eq 130
}
"$exe" run long_step.yaml -o long_step -q > long_step.out 2> long_step.err &
pid=$!
for _ in $(seq 1 3000); do [ -e long_step/checkpoint.bin ] && break; sleep 0.01; done
check "SIGINT inside a flow integration: exits 130 at once" sigint_inside_step $pid
check "inside a step: the summary says interrupted" grep -q '"status": "interrupted"' long_step/run_summary.json
check "inside a step: the step named, no step completed" \
  grep -q '"failure_step": 1' long_step/run_summary.json
check "inside a step: the message says what was kept" \
  grep -q "the last good state (t = 0 s) is written as points_last_good.vtu, and a resumed run goes on from the checkpoint at t = 0 s" long_step.err
# (The worst unknown at the interrupt may be a node's pressure or an inflow integral, which CVODE
# integrates beside them: which one depends on how far the flow got in that second.)
flow_stood() {  # prints the message where it does not match
  grep -Eq "$1" long_step.err || { sed 's/^/  long_step.err: /' long_step.err >&2; return 1; }
}
check "inside a step: the message says where the flow stood" \
  flow_stood "step 1 \(t = 0 s -> 60 s\): interrupted by SIGINT inside the step, which was abandoned \(the flow had reached t = [0-9.e+-]+ s in steps of [0-9.e+-]+ s, worst unknown: ((liquid|gas) pressure at node [0-9]+ \([0-9., -]+\) m|the (liquid|gas) inflow integral)( \(no error estimate yet: the unknown changing fastest\))?\);"
check "inside a step: the last good state written" test -s long_step/points_last_good.vtu
check "inside a step, quiet: no progress printed" test ! -s long_step.out
# Not quiet: the progress inside the long step says where its flow stands, every 2 s.
"$exe" run long_step.yaml -o long_step_progress > long_step_progress.out 2>&1 &
pid=$!
sleep 4.5
kill -INT $pid
wait $pid
check "inside a step: the progress says where the flow stands" \
  grep -Eq "step 1 \(t = 0 s -> 60 s\) in progress: the flow at t = [0-9.e+-]+ s in steps of [0-9.e+-]+ s, wall [0-9.]+ s" long_step_progress.out
"$exe" resume long_step -q &
check "the resumed run: interrupted inside its step again" sigint_inside_step $!
check "the resumed run: counted" grep -q '"resumes": 1' long_step/run_summary.json

# 9. Signals inside a long mechanics sub-cycle: a deformable unsaturated block settling under
# gravity, the whole run one coupling interval of 60 s (about a minute of mechanics here). Once
# the progress says the mechanics runs, a first SIGINT lets the step finish (the run says so and
# goes on); a second abandons it within 3 s.
sed -e 's/name: long_step/name: long_mechanics/' -e 's/cells: \[40, 40\]/cells: [20, 20]/' \
  -e 's/gravity: \[0, 0\]/gravity: [0, -9.81]/' -e '/^skeleton: rigid/d' \
  -e 's/suction: 5.0e+5/suction: 5.0e+4/' \
  -e 's/{name: top, .*}/{name: base, plane: {axis: y, at: 0}, mechanical: fixed}\n  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}\n  - {name: right, plane: {axis: x, at: 1}, mechanical: roller}/' \
  -e 's/, relative_tolerance: 1.0e-10, absolute_tolerance: 1.0e-6//' long_step.yaml > long_mechanics.yaml
"$exe" run long_mechanics.yaml -o long_mechanics > long_mechanics.out 2> long_mechanics.err &
pid=$!
for _ in $(seq 1 3000); do grep -q "in progress: the mechanics at" long_mechanics.out && break; sleep 0.01; done
check "inside the mechanics: the progress says where it stands" \
  grep -Eq "step 1 \(t = 0 s -> 60 s\) in progress: the mechanics at t = [0-9.e+-]+ s in steps of [0-9.e+-]+ s, wall [0-9.]+ s" long_mechanics.out
kill -INT $pid
sleep 1
check "a first SIGINT in the mechanics: the run goes on" kill -0 $pid
check "a first SIGINT in the mechanics: the run says it stops after the step" \
  grep -q "SIGINT received: the run stops after this step, at t = 60 s, with a checkpoint; a second one abandons the step" long_mechanics.err
kill -INT $pid
for _ in $(seq 1 300); do kill -0 $pid 2>/dev/null || break; sleep 0.01; done
wait $pid
check "a second SIGINT in the mechanics: exits 130 at once" test $? -eq 130
check "inside the mechanics: the message says where it stood" \
  grep -Eq "step 1 \(t = 0 s -> 60 s\): interrupted by SIGINT inside the step, which was abandoned \(the mechanics had reached t = [0-9.e+-]+ s in sub-steps of [0-9.e+-]+ s\);" long_mechanics.err
check "inside the mechanics: the last good state written" test -s long_mechanics/points_last_good.vtu

# 10. Steps of about 2 s of wall time each: the line after a step (with its ETA) still appears
# beside the lines inside the steps.
sed -e 's/end_time: 60/end_time: 4/' -e 's/coupling_interval: 60/coupling_interval: 1/' \
  long_mechanics.yaml > short_steps.yaml
"$exe" run short_steps.yaml -o short_steps > short_steps.out 2>&1
check "steps of seconds: the lines inside them" grep -q "in progress: the mechanics at" short_steps.out
check "steps of seconds: the line after a step" grep -Eq "t = [0-9.]+ s of 4 s \([0-9.]+%\), step [0-9]+, .*ETA" short_steps.out

# 11. A reader of the run's output that has gone (`| head -c 1`) does not end the run: before
# SIGPIPE was ignored the next progress line killed it (exit 141), without summary or checkpoint.
"$exe" run short_steps.yaml -o reader_gone 2>&1 | head -c 1 > /dev/null
check "a run whose reader has gone exits 0" test "${PIPESTATUS[0]}" -eq 0
check "a run whose reader has gone completes" \
  grep -q '"status": "completed"' reader_gone/run_summary.json

echo "test_resume: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
