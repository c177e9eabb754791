#!/usr/bin/env bash
# surfgrow as a library, checked as a user meets it (CI runs this after the tests):
#  1. `cmake --install` of a Release build into a fresh prefix;
#  2. examples/cpp built against that prefix with find_package(surfgrow), and run;
#  3. a parent project that takes surfgrow in with add_subdirectory, built and run;
#  4. the installed CLI under qemu-user emulating a Westmere CPU (SSE4.2, no AVX): the default
#     build runs on any x86-64, with the SIMD paths chosen at run time;
#  5. the libraries and CLI built with Debian's clang: every SIMD path it has gives the bytes of
#     the GCC build's;
#  6. the Python package: the module `cmake --install` put in the prefix imports, and
#     `pip install --no-build-isolation .` into a fresh venv builds one that passes tests/python.
# Usage: scripts/check-package.sh [build dir, default build]
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
build=${1:-build}
scripts/install-deps.sh build package python
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "check-package: install" >&2
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
test -f "$tmp/prefix/lib/cmake/surfgrow/surfgrowConfig.cmake"
test -f "$tmp/prefix/include/surfgrow/core/surface_grower.hpp"
test -f "$tmp/prefix/lib/pkgconfig/surfgrow.pc"

echo "check-package: find_package(surfgrow) consumer (examples/cpp)" >&2
cmake -S examples/cpp -B "$tmp/examples" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/examples" -j "$(nproc)" >/dev/null
ctest --test-dir "$tmp/examples" --output-on-failure

echo "check-package: add_subdirectory consumer" >&2
cmake -S tests/package/add_subdirectory -B "$tmp/subdir" -DCMAKE_BUILD_TYPE=Release \
      -DSURFGROW_SOURCE_DIR="$src" >/dev/null
cmake --build "$tmp/subdir" -j "$(nproc)" --target grow_cloud >/dev/null
"$tmp/subdir/grow_cloud"
if ls "$tmp/subdir/surfgrow" | grep -q -e '^tests$' -e '^bench$'; then
    echo "check-package: add_subdirectory configured surfgrow's tests or benchmarks" >&2
    exit 1
fi

if [[ $(uname -m) == x86_64 ]]; then
    echo "check-package: the installed CLI on an emulated Westmere (no AVX)" >&2
    cli="$tmp/prefix/bin/surfgrow"
    qemu-x86_64 -cpu Westmere "$cli" --version
    "$cli" scan --scene room-corner --poses 1 -q -o "$tmp/scan"
    "$cli" grow "$tmp/scan/cloud.ply" -o "$tmp/native" -q --no-picture --no-octomap
    qemu-x86_64 -cpu Westmere "$cli" grow "$tmp/scan/cloud.ply" -o "$tmp/westmere" -q \
        --no-picture --no-octomap
    # The baseline and the widest SIMD path give the same bytes.
    for f in surfaces.json surfaces.ply labels.bin planes.json coverage.json coverage.ply; do
        cmp "$tmp/native/$f" "$tmp/westmere/$f"
    done
fi
echo "check-package: the libraries and CLI built with clang" >&2
CC=clang CXX=clang++ cmake -S . -B "$tmp/clang" -DCMAKE_BUILD_TYPE=Release -DSURFGROW_WERROR=ON \
    -DSURFGROW_BUILD_TESTS=OFF -DSURFGROW_BUILD_BENCHMARKS=OFF -DSURFGROW_BUILD_EXAMPLES=OFF \
    -DSURFGROW_INSTALL=OFF >/dev/null
cmake --build "$tmp/clang" -j "$(nproc)" --target surfgrow >/dev/null
gcc_cli="$build/apps/surfgrow/surfgrow"
"$gcc_cli" scan --scene ibeam-channel --poses 1 -q -o "$tmp/channel"
"$gcc_cli" grow "$tmp/channel/cloud.ply" -o "$tmp/gcc" -q --no-picture --no-octomap
for isa in baseline avx2 avx512; do
    SURFGROW_SIMD=$isa "$tmp/clang/apps/surfgrow/surfgrow" grow "$tmp/channel/cloud.ply" \
        -o "$tmp/clang-$isa" -q --no-picture --no-octomap
    for f in surfaces.json surfaces.ply labels.bin planes.json coverage.json coverage.ply; do
        cmp "$tmp/gcc/$f" "$tmp/clang-$isa/$f"
    done
done
if [[ -d "$build/python/surfgrow" ]]; then
    echo "check-package: the installed Python module" >&2
    site=$(find "$tmp/prefix/lib" -maxdepth 3 -type d -name dist-packages -o -maxdepth 3 -type d \
           -name site-packages | head -n 1)
    (cd "$tmp" && PYTHONPATH="$site" /usr/bin/python3 -c \
        'import surfgrow, numpy; r = surfgrow.grow(numpy.random.rand(1000, 3)); print(surfgrow.__file__)' |
        grep -q "^$tmp/prefix/")
fi
echo "check-package: pip install --no-build-isolation . in a venv, and tests/python there" >&2
/usr/bin/python3 -m venv --system-site-packages "$tmp/venv"
"$tmp/venv/bin/pip" install -q --no-build-isolation --no-index "$src"
(cd "$tmp" && SURFGROW_CLI="$tmp/prefix/bin/surfgrow" PYTHONDONTWRITEBYTECODE=1 \
    "$tmp/venv/bin/python" -m pytest -q -p no:cacheprovider "$src/tests/python")
echo "check-package: ok" >&2
