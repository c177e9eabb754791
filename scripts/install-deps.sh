#!/usr/bin/env bash
# Installs the Debian packages surfgrow needs, by group; does nothing when they are all present.
#   scripts/install-deps.sh build        compiler, CMake, libraries (enough to build and run)
#   scripts/install-deps.sh test         + GoogleTest, Google Benchmark, test-only tools
#   scripts/install-deps.sh package      + qemu-user, clang and its OpenMP, for the portability check (scripts/check-package.sh)
#   scripts/install-deps.sh fuzz         + clang with libFuzzer and its OpenMP, for scripts/fuzz.sh (docs/fuzzing.md)
#   scripts/install-deps.sh python       + pybind11, Python headers, pytest, Open3D, tqdm (the Python module, docs/python.md)
#   scripts/install-deps.sh cross        + the aarch64 cross compiler and Debian's arm64 libraries (scripts/check-aarch64.sh)
#   scripts/install-deps.sh peers        + PCL, CGAL, Open3D for bench/peers (optional)
set -euo pipefail

declare -A group=(
    [build]="cmake make g++ pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev liblzf-dev libpng-dev zlib1g-dev libfreetype-dev libfontconfig-dev fonts-dejavu-core liboctomap-dev python3 python3-matplotlib python3-numpy"
    [test]="libgtest-dev libgmock-dev libbenchmark-dev clang-format strace"
    [package]="qemu-user clang libomp-dev"
    [fuzz]="clang libclang-rt-14-dev libomp-dev"
    [python]="pybind11-dev python3-dev python3-numpy python3-setuptools python3-wheel python3-pip python3-venv python3-pytest python3-tqdm python3-open3d"
    [peers]="libpcl-dev libcgal-dev libtbb-dev python3-open3d libgmp-dev libmpfr-dev"
    [cross]="g++-aarch64-linux-gnu qemu-user libc6-dev:arm64 libgomp1:arm64 liblzf-dev:arm64 libpng-dev:arm64 zlib1g-dev:arm64 libfreetype-dev:arm64 libfontconfig-dev:arm64 liboctomap1.9:arm64 libgtest-dev:arm64 libgmock-dev:arm64"
)
# liboctomap-dev cannot be installed for two architectures at once (its CMake files differ), so the
# cross build takes the arm64 one's files from its package, unpacked here (octomap_DIR).
cross_octomap=/opt/surfgrow-cross/arm64
# surfgrow view: three.js from Debian, embedded into the binary at build time; its browser test.
group[build]+=" libjs-three"
group[test]+=" chromium"

wanted=()
for g in "${@:-build}"; do
    [[ -n "${group[$g]+x}" ]] || { echo "install-deps: unknown group '$g' (build, test, python, package, fuzz, peers, cross)" >&2; exit 2; }
    read -r -a pk <<<"${group[$g]}"
    wanted+=("${pk[@]}")
done

sudo=""
[[ $(id -u) -eq 0 ]] || sudo="sudo"
if [[ " ${wanted[*]} " == *":arm64 "* ]] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    $sudo dpkg --add-architecture arm64  # the lists are refreshed below: the install fails first
fi

# The arm64 octomap's CMake package and libraries, unpacked from its .deb files.
unpack_cross_octomap() {
    [[ -f $cross_octomap/usr/share/octomap/octomap-config.cmake ]] && return 0
    local debs
    debs=$(mktemp -d)
    chmod 777 "$debs"  # apt's download user writes there
    (cd "$debs" && apt-get download -q liboctomap-dev:arm64 liboctomap1.9:arm64 >>/tmp/surfgrow-apt.log 2>&1) ||
        { echo "install-deps: could not download the arm64 octomap (log: /tmp/surfgrow-apt.log)" >&2; exit 1; }
    $sudo mkdir -p "$cross_octomap"
    for d in "$debs"/*.deb; do $sudo dpkg -x "$d" "$cross_octomap"; done
    rm -rf "$debs"
}

missing=()
for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
    [[ " $* " == *" cross "* ]] && unpack_cross_octomap
    exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
# Try without refreshing first (works offline from a warm cache); refresh the lists if that fails.
if ! $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >/tmp/surfgrow-apt.log 2>&1; then
    $sudo apt-get update -q >>/tmp/surfgrow-apt.log 2>&1 || true
    $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >>/tmp/surfgrow-apt.log 2>&1 ||
        { tail -n 20 /tmp/surfgrow-apt.log >&2; echo "install-deps: apt-get failed (log: /tmp/surfgrow-apt.log)" >&2; exit 1; }
fi
[[ " $* " == *" cross "* ]] && unpack_cross_octomap
exit 0
