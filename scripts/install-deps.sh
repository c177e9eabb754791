#!/usr/bin/env bash
# Installs the Debian packages surfgrow needs, by group; does nothing when they are all present.
#   scripts/install-deps.sh build        compiler, CMake, libraries (enough to build and run)
#   scripts/install-deps.sh test         + GoogleTest, Google Benchmark, test-only tools
#   scripts/install-deps.sh package      + qemu-user, clang and its OpenMP, for the portability check (scripts/check-package.sh)
#   scripts/install-deps.sh peers        + PCL, CGAL, Open3D for bench/peers (optional)
set -euo pipefail

declare -A group=(
    [build]="cmake make g++ pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev liblzf-dev libpng-dev libfreetype-dev libfontconfig-dev fonts-dejavu-core liboctomap-dev python3 python3-matplotlib python3-numpy"
    [test]="libgtest-dev libgmock-dev libbenchmark-dev clang-format"
    [package]="qemu-user clang libomp-dev"
    [peers]="libpcl-dev libcgal-dev libtbb-dev python3-open3d libgmp-dev libmpfr-dev"
)
# surfgrow view: three.js from Debian, embedded into the binary at build time; its browser test.
group[build]+=" libjs-three"
group[test]+=" chromium"

wanted=()
for g in "${@:-build}"; do
    [[ -n "${group[$g]+x}" ]] || { echo "install-deps: unknown group '$g' (build, test, package, peers)" >&2; exit 2; }
    read -r -a pk <<<"${group[$g]}"
    wanted+=("${pk[@]}")
done

missing=()
for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
[[ $(id -u) -eq 0 ]] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
# Try without refreshing first (works offline from a warm cache); refresh the lists if that fails.
if ! $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >/tmp/surfgrow-apt.log 2>&1; then
    $sudo apt-get update -q >>/tmp/surfgrow-apt.log 2>&1 || true
    $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >>/tmp/surfgrow-apt.log 2>&1 ||
        { tail -n 20 /tmp/surfgrow-apt.log >&2; echo "install-deps: apt-get failed (log: /tmp/surfgrow-apt.log)" >&2; exit 1; }
fi
