#!/usr/bin/env bash
# surfgrow on aarch64 (a robot's Jetson or Raspberry Pi), checked without one: cross-compiled with
# Debian's g++-aarch64-linux-gnu against Debian's arm64 libraries (warnings as errors) and run under
# qemu-user.
#   scripts/check-aarch64.sh [BUILD]          the whole test suite (CLI tests and the README's
#                                             command lines included; about 35 min on 2 cores)
#   scripts/check-aarch64.sh --quick [BUILD]  what CI runs (about 9 min): the CLI and examples/cpp;
#       the examples run, and the CLI's scan and grow of the I-beam channel give the x86-64 build's
#       result (build/, same labels, numbers within float rounding: scripts/same-result.py)
# BUILD defaults to build-aarch64.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
if [[ ${1:-} == --quick ]]; then
    quick=1
    shift
fi
build=${1:-build-aarch64}
scripts/install-deps.sh build test cross

echo "check-aarch64: cross build into $build" >&2
tests=ON
((quick)) && tests=OFF
cmake -S . -B "$build" -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake \
      -DCMAKE_BUILD_TYPE=Release -DSURFGROW_WERROR=ON -DSURFGROW_BUILD_BENCHMARKS=OFF \
      -DSURFGROW_BUILD_TESTS=$tests -Doctomap_DIR=/opt/surfgrow-cross/arm64/usr/share/octomap \
      >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null
cli=$build/apps/surfgrow/surfgrow
readelf -h "$cli" | grep -q AArch64 || { echo "check-aarch64: $cli is not for aarch64" >&2; exit 1; }

if ((quick == 0)); then
    echo "check-aarch64: every test under qemu-aarch64" >&2
    ctest --test-dir "$build" -j "$(nproc)" --timeout 900 --output-on-failure
    echo "check-aarch64: ok" >&2
    exit 0
fi

echo "check-aarch64: examples/cpp under qemu-aarch64" >&2
ctest --test-dir "$build" -R '^example\.' --output-on-failure
echo "check-aarch64: the CLI under qemu-aarch64 against the x86-64 build" >&2
native=build/apps/surfgrow/surfgrow
[[ -x $native ]] || { echo "check-aarch64: --quick compares with $native: build it first" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
qemu-aarch64 "$cli" scan --scene ibeam-channel --poses 1 -q -o "$tmp/scan"
"$native" scan --scene ibeam-channel --poses 1 -q -o "$tmp/scan-x86"
cmp "$tmp/scan/cloud.ply" "$tmp/scan-x86/cloud.ply"
qemu-aarch64 "$cli" grow "$tmp/scan/cloud.ply" -o "$tmp/aarch64" -q --no-picture --no-octomap
"$native" grow "$tmp/scan/cloud.ply" -o "$tmp/x86" -q --no-picture --no-octomap
python3 scripts/same-result.py "$tmp/x86" "$tmp/aarch64"
echo "check-aarch64: ok" >&2
