#!/usr/bin/env bash
# Fuzzes the untrusted-input parsers of VTK::IOCaustics with libFuzzer
# (docs/reliability.md): configures build-fuzz/ with clang and CAUSTICS_FUZZ=ON,
# builds the fuzz targets and runs each for the given time, one after the other.
#
#   scripts/fuzz.sh [seconds-per-target] [target...]     (default: 60 s, every target)
#   scripts/fuzz.sh smoke [target...]                    (CI: 3000 inputs each, <= 30 s)
#
# Targets: FuzzGLTF FuzzGLB FuzzOBJ FuzzSTL FuzzPLY. Each starts from its seed corpus
# (Testing/Fuzz/corpus/<target>, read only) and the inputs it found before
# (build-fuzz/corpus/<target>); an input that crashes, hangs (-timeout), runs out of
# memory (-rss_limit_mb) or leaks is saved as Testing/Fuzz/crashes/<target>/<kind>-<sha1>.
# Once fixed, give it a descriptive name and commit it: ctest FuzzCorpusReplay
# replays that folder. Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev).
# CAUSTICS_FUZZ_JOBS sets the build's parallel jobs (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-60}"
shift || true
# A smoke run (CI): a few thousand inputs from the seed corpus alone, at most 30 s.
limit=()
smoke=0
if [ "$seconds" = smoke ]; then
  smoke=1
  seconds=30
  limit=(-runs=3000 -seed=1) # the same inputs every run: CI is not left to chance
fi
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(FuzzGLTF FuzzGLB FuzzOBJ FuzzSTL FuzzPLY)
fi
case "$seconds" in
  '' | *[!0-9]*) echo "fuzz.sh: seconds-per-target must be a whole number, not '$seconds'" >&2; exit 2 ;;
esac

launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
mkdir -p build-fuzz
log=build-fuzz/build.log
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -Wno-dev \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
  -DCAUSTICS_FUZZ=ON -DBUILD_TESTING=OFF > "$log" 2>&1 ||
  { tail -n 30 "$log" >&2; echo "fuzz.sh: configuration failed ($log)" >&2; exit 1; }
cmake --build build-fuzz --parallel "${CAUSTICS_FUZZ_JOBS:-2}" --target "${targets[@]}" \
  >> "$log" 2>&1 || { tail -n 40 "$log" >&2; echo "fuzz.sh: build failed ($log)" >&2; exit 1; }

# LeakSanitizer is on (libFuzzer's default under ASan): memory unreachable after an
# input is a finding, objects VTK keeps for the life of the process are not.
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
status=0
for target in "${targets[@]}"; do
  case "$target" in
    FuzzGLTF | FuzzGLB) dict=gltf.dict ;;
    FuzzOBJ) dict=obj.dict ;;
    FuzzSTL) dict=stl.dict ;;
    FuzzPLY) dict=ply.dict ;;
    *) echo "fuzz.sh: unknown target '$target'" >&2; exit 2 ;;
  esac
  mkdir -p "build-fuzz/corpus/$target" "Testing/Fuzz/crashes/$target"
  log="build-fuzz/$target.log"
  echo "fuzz.sh: $target for $seconds s (log: $log)"
  found="build-fuzz/corpus/$target"
  if [ "$smoke" = 1 ]; then
    found="build-fuzz/smoke-corpus/$target" # this run's new inputs only
    rm -rf "$found" && mkdir -p "$found"
  fi
  if ! nice -n 10 "build-fuzz/bin/$target" "$found" "${limit[@]}" \
    "Testing/Fuzz/corpus/$target" -dict="Testing/Fuzz/$dict" -max_total_time="$seconds" \
    -max_len=8192 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="Testing/Fuzz/crashes/$target/" > "$log" 2>&1; then
    status=1
    echo "fuzz.sh: $target FOUND A PROBLEM:" >&2
    grep -E "^(==[0-9]+==ERROR|SUMMARY|caustics fuzz:|artifact_prefix|Test unit written)|runtime error" \
      "$log" | head -n 8 >&2 || tail -n 20 "$log" >&2
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$log" | sed "s/^/  $target /" || true
done
exit $status
