#!/usr/bin/env bash
# The CPU-side code under AddressSanitizer + UndefinedBehaviorSanitizer, and a short fuzz run:
#   1. configures <work-dir>/build with clang, BRICKLIGHT_SANITIZE=ON and BRICKLIGHT_FUZZ=ON, without the GPU
#      backends, as a unity build (two thirds of the time), and builds only the CPU-side test programs (target
#      bricklight-cpu-tests) and the fuzzers;
#   2. runs the CPU-side tests there (ctest -L cpu): any sanitizer report fails its test;
#   3. runs every fuzzer for BRICKLIGHT_FUZZ_SECONDS seconds (default 8: the seeds replayed and new inputs
#      tried; a longer hunt: BRICKLIGHT_FUZZ_SECONDS=300, within the ctest test's 30-minute timeout) from its
#      seeds (tests/fuzz/seeds/<fuzzer>/) and prints how many inputs it ran; a crash, a leak, a timeout or an
#      out-of-memory fails the script (the input that did it is left in <work-dir>/findings/<fuzzer>/).
# tests/CMakeLists.txt registers this as the ctest test bricklight-sanitizers, with the main build's shader
# compiler: the shaders are data to the code under test, and a compiler built and run under ASan only costs time.
#
#   scripts/test_sanitizers.sh <work-dir> [<bricklight-shaderc to use>]
set -euo pipefail
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 <work-dir> [<bricklight-shaderc>]" >&2
  exit 2
fi
shaderc=()
if [ $# -eq 2 ]; then shaderc=(-DBRICKLIGHT_SHADERC="$2"); fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mkdir -p "$1"
work="$(cd "$1" && pwd)"
seconds="${BRICKLIGHT_FUZZ_SECONDS:-8}"
if ! command -v clang++ > /dev/null; then
  echo "test_sanitizers: clang++ is missing (scripts/bootstrap.sh installs it)" >&2
  exit 1
fi
start=$SECONDS
step() { echo "== [$((SECONDS - start)) s] $*"; }

step "configure (clang, ASan + UBSan, fuzzers, no GPU backend)"
cmake -S "$root" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DBRICKLIGHT_SANITIZE=ON -DBRICKLIGHT_FUZZ=ON \
  -DBRICKLIGHT_VULKAN=OFF -DBRICKLIGHT_GL=OFF -DBRICKLIGHT_INSTALL=OFF -DCMAKE_UNITY_BUILD=ON "${shaderc[@]}" > "$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
step "build the CPU-side tests and the fuzzers"
# The build runs bricklight-shaderc, itself built with the sanitizers: glslang keeps its pools to the end.
ASAN_OPTIONS=detect_leaks=0 cmake --build "$work/build" --target bricklight-cpu-tests bricklight-fuzzers > "$work/build.log" ||
  { tail -50 "$work/build.log"; exit 1; }

step "CPU-side tests under the sanitizers"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
(cd "$work/build" && ctest -L cpu --output-on-failure --timeout 600)

fuzzers=$(find "$work/build/tests/fuzz" -maxdepth 1 -type f -executable -name '*_fuzzer' | sort)
for fuzzer in $fuzzers; do
  name="$(basename "$fuzzer")"
  corpus="$work/corpus/$name"
  findings="$work/findings/$name"
  rm -rf "$corpus" "$findings"
  mkdir -p "$corpus" "$findings"
  if [ -d "$root/tests/fuzz/seeds/$name" ]; then cp -r "$root/tests/fuzz/seeds/$name/." "$corpus/"; fi
  step "fuzz $name for $seconds s"
  # -rss_limit_mb and -timeout turn runaway memory and hangs into findings; -max_len bounds one input.
  if ! "$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
      -artifact_prefix="$findings/" -print_final_stats=1 "$corpus" > "$work/$name.log" 2>&1; then
    tail -40 "$work/$name.log"
    echo "test_sanitizers: $name found a failure (inputs in $findings)" >&2
    exit 1
  fi
  echo "   $(grep -m1 'stat::number_of_executed_units' "$work/$name.log" | awk '{print $2}') inputs run," \
       "$(grep -m1 'stat::peak_rss_mb' "$work/$name.log" | awk '{print $2}') MB peak"
done
[ -n "$fuzzers" ] || echo "   (no fuzzer built)"
step "sanitizers and fuzzing passed"
