#!/usr/bin/env bash
# run_verification.py --resume (verification/run_verification.py): a case's runs already completed
# are kept as they are, a run killed part-way goes on from its checkpoint and ends with what an
# uninterrupted run writes, bit for bit, and a folder holding another case or a failed run is run
# again from the start. On V9 (verification/terzaghi_load: the main cycle from the case itself,
# the explicit cycle from a case file the runner writes).
# Usage: test_verification_resume.sh PATH_TO_UNSATMPM PATH_TO_PYTHON
set -u
exe=$(realpath "$1")
python=$2
runner=$(dirname "$(realpath "$0")")/../../verification/run_verification.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fails=0
pass=0

check() {  # check NAME CONDITION...
  local name=$1; shift
  if "$@"; then pass=$((pass + 1)); else echo "FAIL: $name" >&2; fails=$((fails + 1)); fi
}

verify() {  # verify OUTPUT [--resume]: runs the runner on V9 into OUTPUT
  local out=$1; shift
  "$python" "$runner" --unsatmpm "$exe" --output "$out" --case terzaghi_load "$@" > /dev/null
}

# reused OUTPUT RUN: what result.json says was kept of RUN ("completed", "unfinished" or "")
reused() {
  "$python" -c 'import json, sys
r = json.load(open(sys.argv[1]))["runs"][sys.argv[2]]
print(r.get("reused", ""))' "$1/terzaghi_load/result.json" "$2"
}

# same_outputs A B: every file of A but the checkpoint, the summary and the manifest is in B, bit
# for bit (the effective case but its first line, which names the case file as given), and the
# two hold as many files.
same_outputs() {
  local f ok=0
  for f in "$1"/*; do
    case $(basename "$f") in checkpoint.bin | run_summary.json | unsatmpm_manifest.txt) continue ;; esac
    if [ "$(basename "$f")" = effective_case.yaml ]; then
      cmp -s <(tail -n +2 "$f") <(tail -n +2 "$2/effective_case.yaml") ||
        { echo "  differs: $f" >&2; ok=1; }
      continue
    fi
    cmp -s "$f" "$2/$(basename "$f")" || { echo "  differs: $(basename "$f")" >&2; ok=1; }
  done
  [ "$(ls "$1" | wc -l)" -eq "$(ls "$2" | wc -l)" ] || { echo "  file counts differ" >&2; ok=1; }
  return $ok
}

status_is() { grep -q "\"status\": \"$2\"" "$1/run_summary.json"; }

# The reference: both runs from the start.
check "a first run passes" verify ref
cp -a ref/terzaghi_load/explicit explicit_uninterrupted
check "nothing kept without --resume" test -z "$(reused ref explicit)"

# Completed runs are kept: nothing is run or rewritten, the checks give the same values.
cp -a ref again
touch -d '2000-01-01' again/terzaghi_load/*/points_0000.vtu
check "completed runs: the runner passes" verify again --resume
check "completed runs: the main cycle's kept" test "$(reused again implicit)" = completed
check "completed runs: the explicit cycle's kept" test "$(reused again explicit)" = completed
check "completed runs: not rewritten" \
  test -z "$(find again/terzaghi_load/*/points_0000.vtu -newermt '2001-01-01')"
values() { grep -o '"value": [^,]*' "$1/terzaghi_load/result.json"; }
check "completed runs: the same check values" test "$(values ref)" = "$(values again)"

# A run killed part-way is resumed from its checkpoint and ends as the uninterrupted one.
cp -a ref killed
run=killed/terzaghi_load/explicit
rm -rf "$run"
"$exe" run killed/terzaghi_load/explicit.yaml -o "$run" -q &
pid=$!
for _ in $(seq 1 3000); do [ -e "$run/points_0002.vtu" ] && break; sleep 0.01; done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
if status_is "$run" running; then
  check "killed run: the runner passes" verify killed --resume
  check "killed run: resumed" test "$(reused killed explicit)" = unfinished
  check "killed run: its summary counts the resume" grep -q '"resumes": 1' "$run/run_summary.json"
  check "killed run: completed" status_is "$run" completed
  check "killed run: the uninterrupted run's files" same_outputs explicit_uninterrupted "$run"
else
  echo "note: the explicit run ended before it could be killed; its resume is not tested" >&2
fi

# Another case in a run's folder, or a failed run: run again from the start.
cp -a ref other
sed -i 's/^  end_time: .*/  end_time: 0.5/' other/terzaghi_load/implicit/effective_case.yaml
sed -i 's/"status": "completed"/"status": "failed"/' other/terzaghi_load/explicit/run_summary.json
check "another case, a failed run: the runner passes" verify other --resume
check "another case: run again" test -z "$(reused other implicit)"
check "another case: its own configuration again" \
  cmp -s {ref,other}/terzaghi_load/implicit/effective_case.yaml
check "a failed run: run again" test -z "$(reused other explicit)"
check "a failed run: completed" status_is other/terzaghi_load/explicit completed

# A run made by another program (another build): run again, and the folder says this one made it.
cp -a ref rebuilt
echo 0000 > rebuilt/terzaghi_load/implicit.program
check "another program: the runner passes" verify rebuilt --resume
check "another program: run again" test -z "$(reused rebuilt implicit)"
check "another program: this program's id kept" \
  cmp -s ref/terzaghi_load/implicit.program rebuilt/terzaghi_load/implicit.program
check "another program: the other run kept" test "$(reused rebuilt explicit)" = completed

echo "verification runner --resume: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
