#!/bin/sh
# bench/gpu_figures.sh on this machine's lavapipe: with --allow-cpu it runs every step and writes
# gpu_figures.md naming the CPU device and each variant's cost; without it, it refuses, exit 1,
# whether it looks for a GPU (none here) or is named the CPU device.
# Usage: gpu_figures_test.sh SCRIPT KDOP
set -eu
script=$1 kdop=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
unset KDOP_DEVICE
"$script" --out "$dir/cpu" --quick --allow-cpu --kdop "$kdop" 2>"$dir/cpu.err"
report="$dir/cpu/gpu_figures.md"
fail() { echo "gpu_figures_test: $1" >&2; cat "$report" >&2 2>/dev/null || true; exit 1; }
grep -q "^- device: llvmpipe.*(cpu)$" "$report" || fail "the report names no CPU device"
for variant in aabb-clip-n9 aabb-varclip-n9 dop16-grass-clip-n9 dop22-clip-n9 dop32-clip-n9; do
    grep -q "^| $variant | [0-9.]* | [0-9.-]* | [0-9.]* |$" "$report" || fail "no cost row for $variant"
done
for step in bench taa_default scene taa_sequence flip_ldr flip_hdr; do
    grep -q "^| $step | [0-9.]* | " "$report" || fail "no wall time for $step"
done
if "$script" --out "$dir/gpu" --quick --kdop "$kdop" 2>"$dir/gpu.err"; then fail "ran without a GPU"; fi
grep -q "no Vulkan GPU" "$dir/gpu.err" || { cat "$dir/gpu.err" >&2; fail "no word of the missing GPU"; }
if "$script" --out "$dir/named" --device llvmpipe --quick --kdop "$kdop" 2>"$dir/named.err"; then
    fail "measured a CPU device without --allow-cpu"
fi
grep -q "is a CPU device, not a GPU" "$dir/named.err" || { cat "$dir/named.err" >&2; fail "no word of the CPU device"; }
[ ! -e "$dir/named" ] || fail "output written for a refused device"
[ -z "$(ls -d "$dir"/named.partial-* 2>/dev/null)" ] || fail "a partial folder left behind"
echo "gpu_figures_test: the script runs on lavapipe with --allow-cpu and refuses it without"
