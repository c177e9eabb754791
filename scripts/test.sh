#!/usr/bin/env bash
# The README's test command: installs what is missing, builds everything, runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh build test
# Tests on explicitly: a build folder the demo configured (tests off) gets them back.
SURFGROW_CMAKE_ARGS="-DSURFGROW_BUILD_TESTS=ON ${SURFGROW_CMAKE_ARGS:-}" scripts/build.sh
ctest --test-dir "${SURFGROW_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" --timeout 600
