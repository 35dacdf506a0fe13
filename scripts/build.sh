#!/usr/bin/env bash
# Configures and builds unsatmpm (Release) in ./build. Usage: scripts/build.sh [BUILD_DIR [cmake args...]]
# UNSATMPM_TARGETS="unsatmpm ..." builds only those targets (default: all of them, tests included).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
shift || true
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${UNSATMPM_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}"
