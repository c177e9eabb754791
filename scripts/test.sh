#!/usr/bin/env bash
# The README's test command: installs what is missing, builds everything, runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh build test python
# Tests and the Python module on explicitly: a build folder the demo configured (tests off) gets
# them back. The module is for Debian's interpreter, which has the packages installed above.
SURFGROW_CMAKE_ARGS="-DSURFGROW_BUILD_TESTS=ON -DSURFGROW_BUILD_PYTHON=ON \
-DPython3_EXECUTABLE=/usr/bin/python3 ${SURFGROW_CMAKE_ARGS:-}" scripts/build.sh
ctest --test-dir "${SURFGROW_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" --timeout 600
