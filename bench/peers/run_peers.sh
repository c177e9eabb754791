#!/usr/bin/env bash
# The peers benchmark, one command: surfgrow against PCL, CGAL and Open3D on the same clouds.
#   bench/peers/run_peers.sh            full set: BENCHMARK.md at the repository root
#   bench/peers/run_peers.sh --quick    smoke run: build-peers/peers-work-quick/BENCHMARK.md
# Other options go to run_peers.py (--help). Installs the Debian packages it needs (as root or
# with sudo), builds Release with -DSURFGROW_BUILD_PEERS=ON in $SURFGROW_PEERS_BUILD_DIR
# (default build-peers/, separate from build/ so the test build stays light; SURFGROW_PEERS_BUILD_DIR=build
# reuses the main build's libraries instead, at the price of building the peers there), then runs.
# Idempotent: clouds and finished runs in the work folder are reused (--rerun to redo them).
set -euo pipefail
cd "$(dirname "$0")/../.."
command_line="bench/peers/run_peers.sh${*:+ $*}"
scripts/install-deps.sh build test peers
build_dir=${SURFGROW_PEERS_BUILD_DIR:-build-peers}
fresh=()  # a new build folder needs no tests; an existing one (e.g. build/) keeps its choice
[[ -f "$build_dir/CMakeCache.txt" ]] || fresh=(-DSURFGROW_BUILD_TESTS=OFF)
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSURFGROW_BUILD_PEERS=ON \
      -DSURFGROW_BUILD_BENCHMARKS=ON "${fresh[@]}" >/dev/null
cmake --build "$build_dir" -j "$(nproc)" \
      --target surfgrow make_clouds peer_surfgrow peer_pcl peer_cgal bench_io
# Debian's Open3D: the system interpreter, not a pyenv/venv python3 that lacks Debian's modules.
exec /usr/bin/python3 bench/peers/run_peers.py --build "$build_dir" --command "$command_line" "$@"
