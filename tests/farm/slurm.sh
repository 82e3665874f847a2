#!/usr/bin/env bash
# `glint farm slurm` against a real scheduler: a single-node Slurm cluster (Debian's slurm-wlm
# and munge) started in a temporary folder, the teapot turntable submitted as a 4-task array,
# one task requeued while it renders, and then: the verification job and `glint verify` report
# the shot complete, and every frame is byte-identical to a local single-process render. The
# daemons are stopped by pid at the end, whatever happened.
#
#   tests/farm/slurm.sh            (after cargo build --release; run by .ci/run)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
glint="$root/target/release/glint"
[ -x "$glint" ] || { echo "build glint first: cargo build --release" >&2; exit 2; }

# shellcheck source=tests/farm/cluster.sh
source "$root/tests/farm/cluster.sh"
start_cluster
trap stop_cluster EXIT

# The shot, in a folder of its own.
project="$work/project"
copy_turntable "$project"
shot="$project/shots/teapot_turntable.ron"
options=(--frames 1-96 --size 320x180 --preset final)

submitted="$("$glint" farm slurm "$shot" "${options[@]}" --chunk 24 --cpus 1 --retries 2 --submit)"
echo "$submitted"
array="$(echo "$submitted" | sed -n 's/^array job \([0-9]*\):.*/\1/p')"
check="$(echo "$submitted" | sed -n 's/^verify job \([0-9]*\):.*/\1/p')"

# Requeue task 1 once it has written a frame and before it ends: as a node failure would.
logs="$project/shots/slurm-logs"
requeued=no
for _ in $(seq 600); do
    state="$(squeue -h -j "${array}_1" -o %T 2>/dev/null || true)"
    if [ "$state" = RUNNING ] && grep -q "^frame" "$logs/glint-${array}_1.log" 2>/dev/null; then
        scontrol requeue "${array}_1"
        # Slurm holds a requeued job back for a while; let it start again as soon as its
        # first try has left the node.
        task="$(squeue -h -j "${array}_1" -o %A 2>/dev/null || true)"
        for _ in $(seq 600); do
            [ -n "$task" ] && release_requeued_job "$task" && break
            sleep 0.1
        done
        requeued=yes
        break
    fi
    [ -z "$state" ] && break
    sleep 0.05
done
[ "$requeued" = yes ] || { echo "task 1 ended before it could be requeued" >&2; exit 1; }

for _ in $(seq 1200); do
    queue_empty "$array,$check" && break
    sleep 0.25
done
[ -z "$(squeue -h -j "$array,$check")" ] || { echo "the jobs did not finish" >&2; exit 1; }

restarts="$(scontrol show job "${array}_1" | sed -n 's/.*Restarts=\([0-9]*\).*/\1/p')"
[ "${restarts:-0}" -ge 1 ] || { echo "task 1 was not requeued (Restarts=$restarts)" >&2; exit 1; }
grep -q "96 frames checked: 96 complete" "$logs/verify-$check.log" \
    || { echo "the verification job did not find the shot complete:" >&2; cat "$logs/verify-$check.log" >&2; exit 1; }
"$glint" verify "$shot" "${options[@]}" > /dev/null

# The same frames from one local process, byte for byte.
"$glint" render "$shot" "${options[@]}" --out "$work/local/tt.####.png" --quiet
for frame in $(seq -f %04g 1 96); do
    cmp -s "$project/out/teapot_turntable/teapot_turntable.$frame.png" "$work/local/tt.$frame.png" \
        || { echo "frame $frame differs from the local render" >&2; exit 1; }
done
echo "slurm test passed: 4 tasks, task 1 requeued (Restarts=$restarts), verified, 96 frames identical to a local render"
