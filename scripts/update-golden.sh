#!/usr/bin/env bash
# Re-renders the golden images in tests/golden/ after an intended change of the renderer's
# output. Usage: scripts/update-golden.sh [BUILD_DIR]   (default build/release)
# Look at the new PNGs (git diff shows which changed) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
TELLUS_UPDATE_GOLDEN=1 "$build/tests/tellus_gpu_tests" --gtest_filter='GoldenImageTest.*'
git status --short tests/golden
