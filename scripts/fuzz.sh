#!/usr/bin/env bash
# Builds surfgrow's libFuzzer targets with clang (ASan + UBSan) and runs them; docs/fuzzing.md.
#   scripts/fuzz.sh                       every target, 10^7 executions each, one after another
#   scripts/fuzz.sh raw_scan --runs 1e6   one target (the name of its fuzz/<name>.cpp)
#   scripts/fuzz.sh --time 120            every target for 120 s each instead of a count
#   scripts/fuzz.sh poses_file --merge    minimise fuzz/corpus/poses_file with what the runs found
#   scripts/fuzz.sh --list                the targets
# Anything after "--" goes to libFuzzer (e.g. -- -jobs=4 -workers=4). Runs one process on one
# core at low priority; new inputs go to build-fuzz/corpus/<target>/ (the committed corpus is
# only read), findings to build-fuzz/findings/<target>/, logs to build-fuzz/logs/. A finding
# stops that target's run and the script exits 1 at the end. Not run in CI (too long); CI
# replays the corpora and fuzz/crashes/ (ctest -L fuzz).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${SURFGROW_FUZZ_BUILD:-$root/build-fuzz}
jobs=${SURFGROW_JOBS:-2}
runs=10000000
seconds=""
merge=0
list=0
targets=()
extra=()
while [[ $# -gt 0 ]]; do
    case $1 in
        --runs) runs=$(python3 -c "print(int(float('$2')))"); shift 2 ;;
        --time) seconds=$2; shift 2 ;;
        --merge) merge=1; shift ;;
        --list) list=1; shift ;;
        -h | --help) sed -n '2,12p' "$0"; exit 0 ;;
        --) shift; extra=("$@"); break ;;
        -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
        *) targets+=("$1"); shift ;;
    esac
done

all=()
for f in "$root"/fuzz/*.cpp; do
    name=$(basename "$f" .cpp)
    [[ $name == replay_main ]] || all+=("$name")
done
if [[ $list -eq 1 ]]; then printf '%s\n' "${all[@]}"; exit 0; fi
[[ ${#targets[@]} -gt 0 ]] || targets=("${all[@]}")
for t in "${targets[@]}"; do
    [[ -f $root/fuzz/$t.cpp ]] || { echo "fuzz.sh: no target '$t' (--list)" >&2; exit 2; }
done

command -v clang++ >/dev/null || { echo "fuzz.sh: needs clang (scripts/install-deps.sh fuzz)" >&2; exit 2; }
# -O1 and line tables: quick to build, fast enough to fuzz, stacks with file:line. No NDEBUG:
# assertions are findings too.
if [[ ! -f $build/CMakeCache.txt ]]; then
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DSURFGROW_BUILD_FUZZERS=ON \
        -DSURFGROW_BUILD_TESTS=OFF -DSURFGROW_BUILD_BENCHMARKS=OFF -DSURFGROW_BUILD_EXAMPLES=OFF \
        -DSURFGROW_BUILD_PYTHON=OFF -DSURFGROW_INSTALL=OFF >/dev/null
fi
nice cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"

limits=(-rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10)
if [[ -n $seconds ]]; then limits+=(-max_total_time="$seconds"); else limits+=(-runs="$runs"); fi
failed=()
for t in "${targets[@]}"; do
    bin=$build/fuzz/fuzz_$t
    corpus=$root/fuzz/corpus/$t
    work=$build/corpus/$t
    mkdir -p "$work" "$build/findings/$t" "$build/logs"
    if [[ $merge -eq 1 ]]; then
        # The smallest set of inputs with all the coverage of the committed corpus and the runs'.
        fresh=$(mktemp -d)
        nice -n 19 "$bin" -merge=1 "${limits[@]:0:2}" "$fresh" "$corpus" "$work" "${extra[@]}" \
            >"$build/logs/$t.merge.log" 2>&1
        rm -rf "$corpus" && mkdir -p "$corpus" && cp "$fresh"/* "$corpus"/ && rm -rf "$fresh"
        echo "$t: corpus $(ls "$corpus" | wc -l) files, $(du -sk "$corpus" | cut -f1) KB"
        continue
    fi
    log=$build/logs/$t.log
    echo "== $t ($log)"
    start=$(date +%s)
    status=0
    nice -n 19 "$bin" "${limits[@]}" -print_final_stats=1 \
        -artifact_prefix="$build/findings/$t/" "${extra[@]}" "$work" "$corpus" >"$log" 2>&1 || status=$?
    secs=$(($(date +%s) - start))
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    echo "$t: ${execs:-?} executions in ${secs} s, corpus $(ls "$work" | wc -l) new files, exit $status"
    if [[ $status -ne 0 ]]; then
        failed+=("$t")
        grep -m3 -E "ERROR|runtime error|SUMMARY|terminate|uncaught" "$log" || true
        ls "$build/findings/$t"
    fi
done
if [[ ${#failed[@]} -gt 0 ]]; then
    echo "findings in: ${failed[*]} (inputs in $build/findings/<target>/)" >&2
    exit 1
fi
