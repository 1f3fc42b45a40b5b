#!/bin/sh
# CI after the Quick start's tests: the fast tests under AddressSanitizer and
# UndefinedBehaviorSanitizer, the multithreaded paths under ThreadSanitizer, and the libFuzzer
# targets on their committed corpora for a fixed number of inputs. Any sanitizer report or fuzzing
# finding fails the run, but for the leaks inside Debian's libraries that .ci/lsan-suppressions.txt
# names. Run from the repository root as root (it installs clang and LLVM for the fuzzers when they
# are missing).
set -eu

./install-deps.sh clang-16 libclang-rt-16-dev llvm-16

# Debian's glslang is built without RTTI, so the vptr check cannot run; every other UBSan check
# stops the test that trips it.
flags="-fsanitize=address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1"
export LSAN_OPTIONS="suppressions=$(pwd)/.ci/lsan-suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

# -O1 with line tables only (-g1): reports still name functions and lines, and the sanitized
# builds compile in half the time of RelWithDebInfo's -O2 -g (optimize_command.cpp under ASan and
# UBSan: 31.5 s against 71.6 s here; under TSan 12.5 s against 21.9 s).
quick="-O1 -g1 -DNDEBUG"

echo "== fast tests under AddressSanitizer and UndefinedBehaviorSanitizer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$quick" \
      -DCMAKE_CXX_FLAGS="$flags" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-asan --target kdop_tests
ctest --test-dir build-asan -L fast --output-on-failure

echo "== the multithreaded paths under ThreadSanitizer"
# Variant generation (build_variants: kdop-gen checking generated/ builds every default variant on
# every core), the ideal clip, the CPU reference and axis fitting run on every core, and one
# LDR-FLIP evaluator serves several threads at once; their suites run here, from kdop_thread_tests,
# which builds only what they link (the whole kdop_tests took most of this stage's time).
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$quick" \
      -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread"
cmake --build build-tsan --target kdop_thread_tests kdop-gen
build-tsan/bin/kdop-gen glsl --check --out generated
build-tsan/bin/kdop_thread_tests --gtest_filter='ParallelFor.*:Prefetch.*:Reference.*:IdealClip.*:IdealExits.*:Volume.*:AxisFit.*:Flip.*'

echo "== fuzzing"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
      -DCMAKE_CXX_COMPILER=clang++-16 -DKDOP_FUZZ=ON \
      -DKDOP_BUILD_TESTS=OFF
cmake --build build-fuzz --target kdop_axis_set_fuzzer kdop_manifest_fuzzer kdop_sequence_fuzzer kdop_nss_capture_fuzzer kdop_resolve_bindings_fuzzer kdop_sequence_list_fuzzer kdop_image_fuzzer \
      kdop_hdr_fuzzer kdop_output_listing_fuzzer
# Reports name functions and lines.
export ASAN_SYMBOLIZER_PATH=/usr/bin/llvm-symbolizer-16
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# fuzz NAME RUNS [OPTION...]: runs kdop_NAME_fuzzer on a scratch copy of tests/fuzz/NAME_corpus
# (libFuzzer adds what it finds to the first corpus folder; the tree stays as it is) for a fixed
# number of inputs from a fixed seed: the same inputs on every machine, however fast. The target's
# own output (the codecs' complaints about damaged files) goes to a log, shown only on a finding.
fuzz() {
  name=$1 runs=$2
  shift 2
  mkdir "$scratch/$name"
  cp "tests/fuzz/${name}_corpus/"* "$scratch/$name"
  echo "-- $name: $runs inputs"
  if ! "build-fuzz/bin/kdop_${name}_fuzzer" -seed=1 -runs="$runs" -max_len=4096 -print_final_stats=1 \
       -artifact_prefix="$scratch/" "$@" "$scratch/$name" >"$scratch/$name.log" 2>&1; then
    tail -n 100 "$scratch/$name.log"
    echo "sanitizers.sh: kdop_${name}_fuzzer found a failing input (above)" >&2
    exit 1
  fi
  grep -E '^(Done|stat::)' "$scratch/$name.log"
}
fuzz axis_set 200000
fuzz manifest 200000
fuzz sequence 100000
fuzz nss_capture 50000
fuzz resolve_bindings 100000
fuzz sequence_list 100000
fuzz output_listing 100000
# Two 4x3 HDR images of any float bits, a color map and an exposure: about 2 ms an input (HDR-FLIP).
fuzz hdr 10000
# Image loading leaks inside Debian's libraries, which have no frame pointers: matching those
# leaks to the suppressions needs a slow unwind at every allocation (half the speed). The image
# fuzzer looks for memory errors only; leaks on kdop's image paths are the ASan stage's (its fast
# tests read and write every format under detect_leaks=1).
export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"
# OpenEXR 3.1 allocates up to about 2 GB for some damaged headers (a 600-byte file) before it finds
# the file short and throws, which read_image reports as an error; the limit leaves room for that.
# 2000 inputs, down from 3000, for .ci/run's time on 2 cores since the 3-D testbed's build and
# tests came in (3000 inputs took 257 s in one run, 2000 took 228 s in another: the machine varies).
fuzz image 2000 -rss_limit_mb=4096
