#!/usr/bin/env bash
# The main job: set up, build, and run the verification set, writing VTK files, PNG plots and
# verification/output/report.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# The program alone: the unit tests are the test command's (scripts/test.sh).
UNSATMPM_TARGETS=unsatmpm bash scripts/build.sh build
/usr/bin/python3 verification/run_verification.py --unsatmpm build/bin/unsatmpm \
  --output verification/output --threads "$(nproc)" "$@"
