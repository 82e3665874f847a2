#!/usr/bin/env bash
# The farm's failure path against a real scheduler (the single-node Slurm of cluster.sh):
#
# - a task whose frame cannot be written fails, requeues itself through the script's own retry
#   logic exactly --retries times (Slurm's restart count says so), then gives up;
# - a task whose render process is killed requeues itself and completes on its retry;
# - the verification job then reports the frames the task that gave up left unwritten (frame 5
#   was written before frame 6 failed) as a `--frames` list,
#   and a resubmission with that list completes the shot, every frame byte-identical to a local
#   render;
# - the array's tasks run in the partition and with the memory they were given (--partition,
#   --mem), as `scontrol show job` reports them.
#
#   tests/farm/failure.sh            (after cargo build --release; run by .ci/run)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
glint="$root/target/release/glint"
[ -x "$glint" ] || { echo "build glint first: cargo build --release" >&2; exit 2; }

# shellcheck source=tests/farm/cluster.sh
source "$root/tests/farm/cluster.sh"
start_cluster
trap stop_cluster EXIT

fail() {
    echo "failure test: $*" >&2
    exit 1
}

project="$work/project"
copy_turntable "$project"
shot="$project/shots/teapot_turntable.ron"
out="$project/out/teapot_turntable"
logs="$project/shots/slurm-logs"
options=(--size 640x360 --preset final)
retries=2

# Frame 6 cannot be written: a folder stands where its file goes, so the task of frames 5-8
# writes frame 5 and fails at frame 6 on every try.
mkdir -p "$out/teapot_turntable.0006.png"

# Let a task that Slurm holds back after a requeue start again at once, so that the test does
# not wait out Slurm's requeue delay.
release_requeued() {
    squeue -h -j "$1" -t PENDING -o "%A %r" 2>/dev/null | while read -r task reason; do
        [ "$reason" = BeginTime ] || continue
        release_requeued_job "$task" || true
    done
}

# Waits for jobs $1 (a comma-separated list) to leave the queue; kills the render of task
# $2 of job $3 once, while it runs, when $2 is given.
wait_for() {
    local jobs="$1" victim="${2:-}" array="${3:-}" killed=no
    for _ in $(seq 2400); do
        # What the queue held, every reading, for a failure to show.
        { date +%T.%N; squeue -h -j "$jobs" -t all -o "%i %T %r" 2>&1; } >> "$work/queue.log"
        queue_empty "$jobs" && { echo "$killed"; return; }
        if [ -n "$victim" ] && [ "$killed" = no ] \
            && [ "$(squeue -h -j "${array}_${victim}" -o %T 2>/dev/null)" = RUNNING ]; then
            # The render of that task: its command line names the task's chunk.
            pid="$(pgrep -f -- "--frames 9-12 " | head -n 1 || true)"
            if [ -n "$pid" ]; then
                kill -KILL "$pid" && killed=yes
            fi
        fi
        [ -n "$array" ] && release_requeued "$array"
        sleep 0.1
    done
    fail "the jobs $jobs did not finish"
}

submitted="$("$glint" farm slurm "$shot" --frames 1-16 "${options[@]}" --chunk 4 --cpus 1 \
    --retries "$retries" --partition local --mem 300M --submit)"
echo "$submitted"
array="$(echo "$submitted" | sed -n 's/^array job \([0-9]*\):.*/\1/p')"
check="$(echo "$submitted" | sed -n 's/^verify job \([0-9]*\):.*/\1/p')"
[ -n "$array" ] && [ -n "$check" ] || fail "no job ids in: $submitted"

# What Slurm received: the partition and the memory per task.
details="$(scontrol show job "${array}_0")"
echo "$details" | grep -q "Partition=local" || fail "task 0 is not in partition local: $details"
echo "$details" | grep -Eq "MinMemoryNode=300M|mem=300M" || fail "task 0 does not ask for 300M: $details"

# A slow render leaves time to kill task 2 (frames 9-12) while it runs: the shot is rendered
# at its full preview cost, one thread.
killed="$(wait_for "$array,$check" 2 "$array")"
[ "$killed" = yes ] || fail "task 2 ended before its render could be killed"

restarts() {
    scontrol show job "$1" | sed -n 's/.*Restarts=\([0-9]*\).*/\1/p' | head -n 1
}
# The task that could not write gave up after exactly --retries requeues.
gave_up="$(restarts "${array}_1")"
[ "$gave_up" = "$retries" ] \
    || fail "task 1 was requeued $gave_up times, not $retries: $(cat "$logs/glint-${array}_1.log"; tail -40 "$work/queue.log"; slurm_logs)"
# Its log keeps every try: two that requeued themselves, and the last.
requeues="$(grep -c "failed (1): requeued" "$logs/glint-${array}_1.log" || true)"
[ "$requeues" = "$retries" ] \
    || fail "task 1 requeued itself $requeues times: $(cat "$logs/glint-${array}_1.log")"
# The killed one requeued itself once and then completed.
again="$(restarts "${array}_2")"
[ "${again:-0}" -ge 1 ] || fail "task 2 was not requeued after its render was killed"
for frame in 9 10 11 12; do
    [ -s "$out/teapot_turntable.$(printf %04d "$frame").png" ] \
        || fail "frame $frame is missing after task 2's retry: $(cat "$logs/glint-${array}_2.log"; scontrol show job "${array}_2"; slurm_logs)"
done

# The verification job names what is missing as a frame list, and nothing else.
verify_log="$logs/verify-$check.log"
grep -q "16 frames checked: 13 complete, 3 to render again" "$verify_log" \
    || fail "the verification did not count the missing frames: $(cat "$verify_log")"
list="$(sed -n 's/^render again: --frames \(.*\)$/\1/p' "$verify_log")"
[ "$list" = "6-8" ] || fail "the verification listed '$list', not 6-8"

# Once the cause is gone, resubmitting that list completes the shot.
rmdir "$out/teapot_turntable.0006.png"
resubmitted="$("$glint" farm slurm "$shot" --frames "$list" "${options[@]}" --chunk 4 --cpus 1 \
    --retries "$retries" --partition local --mem 300M --submit)"
array2="$(echo "$resubmitted" | sed -n 's/^array job \([0-9]*\):.*/\1/p')"
check2="$(echo "$resubmitted" | sed -n 's/^verify job \([0-9]*\):.*/\1/p')"
wait_for "$array2,$check2" >/dev/null
grep -q "3 frames checked: 3 complete, 0 to render again" "$logs/verify-$check2.log" \
    || fail "the resubmission did not complete: $(cat "$logs/verify-$check2.log")"
"$glint" verify "$shot" --frames 1-16 "${options[@]}" >/dev/null || fail "glint verify does not find frames 1-16 complete"

"$glint" render "$shot" --frames 1-16 "${options[@]}" --out "$work/local/tt.####.png" --quiet
for frame in $(seq -f %04g 1 16); do
    cmp -s "$out/teapot_turntable.$frame.png" "$work/local/tt.$frame.png" \
        || fail "frame $frame differs from the local render"
done
echo "farm failure test passed: task 1 gave up after $retries requeues, task 2 killed and requeued ($again), verify listed $list, resubmitted, 16 frames identical to a local render"
