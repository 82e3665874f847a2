#!/usr/bin/env bash
# Throughput on a farm against one process: the 96-frame teapot turntable (640×360, final) as 4
# single-thread tasks of the local single-node Slurm cluster, and as one 2-thread `glint
# render`, one after the other on this machine. Prints the frames per second of each, their
# ratio, and the scheduler's overhead per task: the array's wall time less the tasks' own render
# time spread over the CPUs, per task.
#
#   tests/farm/throughput.sh       (after cargo build --release)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
glint="$root/target/release/glint"
source "$root/tests/farm/cluster.sh"
start_cluster
trap stop_cluster EXIT

project="$work/project"
copy_turntable "$project"
shot="$project/shots/teapot_turntable.ron"
cpus=$(nproc)

started=$(date +%s.%N)
submitted="$("$glint" farm slurm "$shot" --chunk 24 --cpus 1 --submit)"
array="$(echo "$submitted" | sed -n 's/^array job \([0-9]*\):.*/\1/p')"
check="$(echo "$submitted" | sed -n 's/^verify job \([0-9]*\):.*/\1/p')"
while [ -n "$(squeue -h -j "$array" 2>/dev/null)" ]; do sleep 0.1; done
farm_seconds=$(echo "$(date +%s.%N) - $started" | bc -l)
while [ -n "$(squeue -h -j "$check" 2>/dev/null)" ]; do sleep 0.1; done
# Each task's summary line: "N frames written, 0 skipped, in S s".
busy=$(cat "$project/shots/slurm-logs/glint-${array}_"*.log | sed -n 's/.* in \([0-9.]*\) s$/\1/p' | paste -sd+ | bc -l)

started=$(date +%s.%N)
"$glint" render "$shot" --threads "$cpus" --out "$work/local/tt.####.png" --quiet
local_seconds=$(echo "$(date +%s.%N) - $started" | bc -l)

printf 'teapot turntable, 96 frames at 640x360 final, %d CPUs\n' "$cpus"
printf '  slurm, 4 tasks x 1 thread:  %6.2f s  %5.2f frames/s\n' "$farm_seconds" "$(echo "96 / $farm_seconds" | bc -l)"
printf '  one render, %d threads:      %6.2f s  %5.2f frames/s\n' "$cpus" "$local_seconds" "$(echo "96 / $local_seconds" | bc -l)"
printf '  farm / local frames per second: %.2f\n' "$(echo "$local_seconds / $farm_seconds" | bc -l)"
printf '  scheduler overhead per task: %.2f s (wall %.2f s less %.2f s of rendering over %d CPUs, over 4 tasks)\n' \
    "$(echo "($farm_seconds - $busy / $cpus) * $cpus / 4" | bc -l)" "$farm_seconds" "$busy" "$cpus"
