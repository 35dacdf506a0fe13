#!/usr/bin/env bash
# Set up, build and pass the tests: the program end to end and the fast verification cases
# (Release), and the unit tests under AddressSanitizer + UndefinedBehaviorSanitizer.
# The slow verification runs carry the CTest label "slow" and are left out here; run them with
#   ctest --test-dir build -L slow
# The unit tests are compiled once, in the sanitizer build: compiling them a second time at -O3
# took 350 of the Release build's 709 s of compiler time (2026-11-28), and CI's two cores have
# 20 minutes. The whole Release suite, unit tests included, stays one command away:
#   bash scripts/build.sh build && ctest --test-dir build -LE slow
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
UNSATMPM_TARGETS=unsatmpm bash scripts/build.sh build
# Every test carries the label unit, cli, verification or slow: one with none of them would be
# left out of the line below without a word, so the command refuses it instead.
unlabelled=$(ctest --test-dir build -N -LE "slow|unit|cli|verification" | grep "Test *#" |
  grep -v "_NOT_BUILT" || true)
if [ -n "$unlabelled" ]; then
  echo "test.sh: tests without the label unit, cli, verification or slow:" >&2
  echo "$unlabelled" >&2
  exit 1
fi
ctest --test-dir build --output-on-failure -j"$(nproc)" -L "cli|verification" -LE slow
# The sanitizer build compiles only the unit tests, at -Og with line tables only (-g1); the
# sanitizers' reports still name file and line. -Og rather than -O1: 650 s of compiler time
# against 920 s, for tests that run 75 s against 69 s on two cores (2026-12-01).
cmake -S . -B build-sanitize -DUNSATMPM_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-Og -g1 -DNDEBUG" >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target unsatmpm_tests unsatmpm_mpi_tests
# The unit tests run in one process per core (GoogleTest's sharding), not one per test as CTest
# would: a sanitized process takes 0.4 s to start (scripts/run_unit_shards.sh). The same tests as
# `ctest --test-dir build-sanitize -L unit`, which still works.
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
bash scripts/run_unit_shards.sh "$(nproc)" 1800 build-sanitize/tests/unsatmpm_tests
LSAN_OPTIONS="suppressions=$PWD/tests/lsan_mpi.supp:fast_unwind_on_malloc=0" \
  bash scripts/run_unit_shards.sh 1 600 build-sanitize/tests/unsatmpm_mpi_tests
