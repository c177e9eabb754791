#!/usr/bin/env bash
# The README's main command: installs what is missing, builds the CLI, runs `surfgrow demo`
# (simulated I-beam channel scan -> surfaces, labels, summary and a picture) into demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh build
SURFGROW_CMAKE_ARGS="${SURFGROW_CMAKE_ARGS:-} -DSURFGROW_BUILD_TESTS=OFF -DSURFGROW_BUILD_BENCHMARKS=OFF" \
    SURFGROW_BUILD_DIR="${SURFGROW_BUILD_DIR:-build-demo}" scripts/build.sh surfgrow
"${SURFGROW_BUILD_DIR:-build-demo}/apps/surfgrow/surfgrow" demo -o "${1:-demo}"
