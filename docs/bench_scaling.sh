#!/bin/sh
# The strong-scaling figures of docs/results.md, "Frames, ranks and threads": kdop optimize on a sequence
# as 1 rank x 1 thread, 2 ranks x 1 thread (mpirun), 1 rank x 2 threads, and 1 rank x 2 threads
# streamed (--memory 1), interleaved over three rounds. Prints each run's search seconds and
# volumes, its peak memory and wall time, then the files' md5 (all the same).
#   docs/bench_scaling.sh SEQUENCE_DIR [KDOP]
set -eu
seq=$1
kdop=${2:-build/bin/kdop}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
root=""
[ "$(id -u)" = 0 ] && root="--allow-run-as-root"
args="optimize --sequence $seq --axes 8 --starts 1 --iterations 5 --accuracy-samples 0 --name scaling"
for round in 1 2 3; do
  for mode in r1t1 r2t1 r1t2 r1t2s; do
    case $mode in
      r1t1) launch=""; extra="--threads 1" ;;
      r2t1) launch="mpirun $root -np 2"; extra="--threads 1" ;;
      r1t2) launch=""; extra="--threads 2" ;;
      r1t2s) launch=""; extra="--threads 2 --memory 1" ;;
    esac
    start=$(date +%s.%N)
    # shellcheck disable=SC2086 # the options are split on purpose
    result=$($launch "$kdop" $args $extra --out "$out/$mode.axes" 2>/dev/null)
    end=$(date +%s.%N)
    echo "round $round $mode: $(echo "$result" | grep 'k-DOP volumes') | $(echo "$result" | grep -o 'peak memory [0-9]* MB') | wall $(awk "BEGIN { print $end - $start }") s"
  done
done
md5sum "$out"/*.axes
