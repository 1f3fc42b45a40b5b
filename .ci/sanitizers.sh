#!/bin/sh
# CI after the Quick start's tests: the fast tests under AddressSanitizer and
# UndefinedBehaviorSanitizer, the multithreaded paths under ThreadSanitizer, and the libFuzzer
# targets on their committed corpora for a fixed number of inputs. Any sanitizer report or fuzzing finding fails the run. Run from the repository
# root as root (it installs clang and libc++ for the fuzzers when they are missing).
set -eu

./install-deps.sh clang-16 libclang-rt-16-dev libc++-16-dev libc++abi-16-dev

# Debian's glslang is built without RTTI, so the vptr check cannot run; every other UBSan check
# stops the test that trips it.
flags="-fsanitize=address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1"
export LSAN_OPTIONS="suppressions=$(pwd)/.ci/lsan-suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

echo "== fast tests under AddressSanitizer and UndefinedBehaviorSanitizer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-asan --target kdop_tests
ctest --test-dir build-asan -L fast --output-on-failure

echo "== the multithreaded paths under ThreadSanitizer"
# Variant generation (build_variants, and kdop-gen through generated_is_fresh), the ideal clip and
# the CPU reference run on every core; their suites run here.
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread"
cmake --build build-tsan --target kdop_tests
ctest --test-dir build-tsan -R '^(SpirvBuild|Reference|IdealClip|IdealExits|Volume|generated_is_fresh)$' --output-on-failure

echo "== fuzzing"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-16 -DKDOP_FUZZ=ON \
      -DBUILD_TESTING=OFF
cmake --build build-fuzz --target kdop_axis_set_fuzzer
# libFuzzer adds what it finds to the first corpus folder: a scratch copy, so the tree stays as it is.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp tests/fuzz/axis_set_corpus/* "$scratch"
# A fixed number of runs from a fixed seed: the same inputs on every machine, however fast.
build-fuzz/bin/kdop_axis_set_fuzzer -seed=1 -runs=200000 -max_len=4096 -print_final_stats=1 \
    -artifact_prefix="$scratch/" "$scratch"
