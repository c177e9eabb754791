#!/usr/bin/env bash
# Configures and builds surfgrow in $SURFGROW_BUILD_DIR (default: build/), Release.
# Extra CMake arguments: $SURFGROW_CMAKE_ARGS. Targets: the script's arguments (default: all).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SURFGROW_BUILD_DIR:-build}
read -r -a extra <<<"${SURFGROW_CMAKE_ARGS:-}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release \
      -DSURFGROW_WERROR="${SURFGROW_WERROR:-OFF}" "${extra[@]}" >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
