#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang (ASan + UBSan, -DTACTILE_FUZZ=ON, in
# build-fuzz/) and runs each one. See tests/fuzz/README.md.
#
#   scripts/fuzz.sh                     every target for 5 s (what CI runs)
#   scripts/fuzz.sh --seconds 60        every target for 60 s
#   scripts/fuzz.sh --runs 1000000 csv  one target for a million executions
#
# New inputs go to build-fuzz/corpus/TARGET (the seeds in tests/fuzz/corpus are read, never
# written); a crash, a timeout (> 1 s per input), a leak or a run past 2 GB leaves its input
# in build-fuzz/artifacts/TARGET/ and makes the script exit non-zero. Add that input to
# tests/fuzz/regressions/TARGET/ with the fix: `make test` replays it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=5
runs=""
targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    -h|--help) sed -n 2,14p "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1 (--seconds S, --runs N)" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
all=(csv layout hdf5 packet labels script arrays eaf label_studio mat edf xdf)
if [[ ${#targets[@]} -eq 0 ]]; then targets=("${all[@]}"); fi
for target in "${targets[@]}"; do
  if [[ ! " ${all[*]} " == *" $target "* ]]; then
    echo "fuzz.sh: no target '$target' (${all[*]})" >&2
    exit 2
  fi
done

./scripts/install-deps.sh
build=build-fuzz
# -O2 with line tables only (CMakeLists.txt adds -gline-tables-only): enough for the stack trace
# of a finding, at a fraction of full debug information's compile time. Batched like CI's builds.
if [[ -f "$build/CMakeCache.txt" ]] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$build/CMakeCache.txt"; then
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
fi
cmake -S . -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DTACTILE_FUZZ=ON -DTACTILE_BATCH=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

# Inputs larger than this teach the fuzzer little and slow it down; the HDF5 seeds are 5 KB.
declare -A max_len=([csv]=4096 [layout]=8192 [hdf5]=16384 [packet]=4096 [labels]=4096
                    [script]=2048 [arrays]=8192 [eaf]=8192 [label_studio]=8192 [edf]=8192
                    [xdf]=8192 [mat]=8192)

# Leaks inside third-party libraries we cannot mend (tests/lsan.supp says which and why).
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
status=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  artifacts="$build/artifacts/$target"
  mkdir -p "$corpus" "$artifacts"
  limit=(-max_total_time="$seconds")
  if [[ -n "$runs" ]]; then limit=(-runs="$runs"); fi
  log="$build/fuzz_$target.log"
  echo "fuzz.sh: $target ${limit[*]}"
  if ! "$build/bin/fuzz_$target" "${limit[@]}" -timeout=1 -rss_limit_mb=2048 -detect_leaks=1 \
      -max_len="${max_len[$target]}" -print_final_stats=1 -artifact_prefix="$artifacts/" \
      "$corpus" "tests/fuzz/corpus/$target" >"$log" 2>&1; then
    echo "fuzz.sh: $target FAILED; input in $artifacts, log $log" >&2
    grep -E "ERROR|SUMMARY|==[0-9]+==|Test unit written" "$log" | head -20 >&2 || true
    status=1
    continue
  fi
  runs_done=$(grep -E "^stat::number_of_executed_units" "$log" | awk '{print $2}')
  speed=$(grep -E "^stat::average_exec_per_sec" "$log" | awk '{print $2}')
  echo "fuzz.sh: $target ok: $runs_done executions, $speed per second, corpus $(ls "$corpus" | wc -l) inputs"
done
exit $status
