#!/bin/sh
# Every GPU figure docs/results.md gives, in one run, on a machine with a Vulkan GPU (NVIDIA's
# driver or any other ICD): the rectification pass's cost at 1080p for the RGB box, its variance
# clip and the 16-, 22- and 32-DOP (the paper's comparison, ms and ratio to the box), the default
# `kdop taa` run, a 1080p sequence through the TAA resolve, and FLIP of one 1080p pair in LDR and
# HDR. Writes OUT/gpu_figures.md (the device, its driver, each command and its figures) beside each
# command's own output, all or nothing, and says clearly, exiting 1, where the device is not a GPU:
# lavapipe is a CPU device, measured only with --allow-cpu (which the tests use).
#
# Usage: bench/gpu_figures.sh --out DIR [--device NAME] [--allow-cpu] [--quick] [--kdop PATH]
#   --device NAME  a substring of the device's name [default: $KDOP_DEVICE, else the first GPU;
#                  with --allow-cpu and neither, lavapipe]
#   --quick        small sizes and few frames: the script's own test, not figures to report
#   --kdop PATH    the kdop binary [default: build/bin/kdop beside this script's repository]
set -eu

here=$(cd "$(dirname "$0")" && pwd)
kdop="$here/../build/bin/kdop"
out= device=${KDOP_DEVICE:-} allow_cpu=0 quick=0
usage() {
    echo "usage: bench/gpu_figures.sh --out DIR [--device NAME] [--allow-cpu] [--quick] [--kdop PATH]" >&2
    exit 2
}
while [ $# -gt 0 ]; do
    case $1 in
    --out) [ $# -ge 2 ] || usage; out=$2; shift 2 ;;
    --device) [ $# -ge 2 ] || usage; device=$2; shift 2 ;;
    --kdop) [ $# -ge 2 ] || usage; kdop=$2; shift 2 ;;
    --allow-cpu) allow_cpu=1; shift ;;
    --quick) quick=1; shift ;;
    *) echo "bench/gpu_figures.sh: unknown argument '$1'" >&2; usage ;;
    esac
done
[ -n "$out" ] || usage
[ -x "$kdop" ] || { echo "bench/gpu_figures.sh: no kdop at $kdop (build it, or give --kdop)" >&2; exit 2; }
if [ -z "$device" ]; then
    if [ "$allow_cpu" = 1 ]; then device=lavapipe; else device=gpu; fi
fi
# Every kdop command below finds the device through $KDOP_DEVICE, so a name with spaces stays one
# word. kdop names lavapipe's device llvmpipe, and an empty name chooses it.
if [ "$device" = lavapipe ]; then unset KDOP_DEVICE; else export KDOP_DEVICE="$device"; fi

if [ "$quick" = 1 ]; then
    size=160x90 seq_size=64x36 frames=12 warmup=4 taa_sizes="--size 64x36 --warmup 4 --frames 4"
else
    size=1920x1080 seq_size=1920x1080 frames=60 warmup=30 taa_sizes=""
fi
# All or nothing: the run writes into a folder beside OUT and moves it into place at the end, so a
# failure or Ctrl-C leaves no half of it (the failing step's output is shown first).
if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
    echo "bench/gpu_figures.sh: $out exists and is not empty; give a new folder" >&2
    exit 2
fi
final=$out
out="$final.partial-$$"
trap 'rm -rf "$out"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
log="$out/commands.txt"
: >"$log"
# run NAME COMMAND...: runs a command, recording it and its wall time in seconds.
run() {
    name=$1
    shift
    echo "== $name: $*" | tee -a "$log" >&2
    start=$(date +%s.%N)
    "$@" >"$out/$name.log" 2>&1 || {
        tail -n 20 "$out/$name.log" >&2
        echo "bench/gpu_figures.sh: $name failed (the last lines of its output above); nothing written" >&2
        exit 1
    }
    end=$(date +%s.%N)
    awk -v name="$name" -v start="$start" -v end="$end" 'BEGIN { printf "%s %.2f\n", name, end - start }' \
        >>"$out/wall_seconds.txt"
}
: >"$out/wall_seconds.txt"

# The device first, in a second: a CPU device stops the script before any long run.
run probe "$kdop" bench --out "$out/probe" --variants aabb-clip-n9 --size 64x64 --repeat 1 --no-sweep \
    --no-callgrind --no-charts
type=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["run"]["device_type"])' "$out/probe/cost.json")
device_name=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["run"]["device"])' "$out/probe/cost.json")
if [ "$type" = cpu ] && [ "$allow_cpu" != 1 ]; then
    echo "bench/gpu_figures.sh: $device_name is a CPU device, not a GPU (lavapipe is not one): these figures are for a" \
         "machine with a Vulkan GPU; give --allow-cpu to measure this device anyway" >&2
    exit 1
fi

run bench "$kdop" bench --out "$out/bench" --size "$size" --no-sweep --no-callgrind --no-charts \
    --variants aabb-clip-n9 aabb-varclip-n9 dop16-grass-clip-n9 dop22-clip-n9 dop32-clip-n9
run taa_default "$kdop" taa --out "$out/taa" --no-charts $taa_sizes
run scene "$kdop" scene --scenes grass3d --size "$seq_size" --frames "$frames" --out "$out/scene"
run taa_sequence "$kdop" taa --sequence "$out/scene/grass3d-ghosting" --warmup "$warmup" --viewer-frames 0 \
    --no-charts --out "$out/taa-sequence"
frames_dir="$out/scene/grass3d-ghosting/color"
first=$(ls "$frames_dir" | head -n 1)
last=$(ls "$frames_dir" | tail -n 1)
# kdop flip computes on the CPU unless a device is named: name the one measured.
flip_device=${KDOP_DEVICE:-llvmpipe}
run flip_ldr "$kdop" flip --device "$flip_device" --reference "$frames_dir/$first" --test "$frames_dir/$last"
run flip_hdr "$kdop" flip --hdr --device "$flip_device" --reference "$frames_dir/$first" --test "$frames_dir/$last"

python3 "$here/gpu_figures_report.py" "$out" "$quick" >"$out/gpu_figures.md"
rmdir "$final" 2>/dev/null || true
mv "$out" "$final"
trap - EXIT
echo "bench/gpu_figures.sh: $device_name ($type): $final/gpu_figures.md" >&2
