#!/usr/bin/env bash
# Set up, build and pass the tests: the unit tests and the fast verification cases (Release),
# then the unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer.
# The slow verification runs carry the CTest label "slow" and are left out here; run them with
#   ctest --test-dir build -L slow
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE slow
# The sanitizer build compiles only the unit tests, at -O1 with line tables only (-g1), to keep CI
# within its time budget; the sanitizers' reports still name file and line.
cmake -S . -B build-sanitize -DUNSATMPM_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target unsatmpm_tests unsatmpm_mpi_tests
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)" -L unit
