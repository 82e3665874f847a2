#!/usr/bin/env bash
# Runs frame benchmarks of an earlier revision and of the working tree in turns, and prints each
# ratio both print, side by side: what a change that must not alter speed is checked with.
#
#   scripts/bench-turns.sh REV TURNS BENCH [BENCH …]     e.g. scripts/bench-turns.sh main 2 render xtoon
#
# Each turn runs every BENCH of REV, then of the working tree; a ratio is each run's median
# per-round ratio (see benches/support/frames.rs), so the machine's load between runs cancels
# within a run. REV is built in a git worktree under WORKDIR (default: a new temporary folder);
# set OLD_TARGET to reuse a release build of REV. The runs' whole output is kept in WORKDIR.
set -euo pipefail
rev=${1:?usage: scripts/bench-turns.sh REV TURNS BENCH [BENCH …]}
turns=${2:?usage: scripts/bench-turns.sh REV TURNS BENCH [BENCH …]}
shift 2
[ $# -gt 0 ] || { echo "usage: scripts/bench-turns.sh REV TURNS BENCH [BENCH …]" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
work=${WORKDIR:-$(mktemp -d)}
mkdir -p "$work"
old_tree=$work/tree
if [ ! -d "$old_tree" ]; then
    git -C "$root" worktree add --detach "$old_tree" "$rev" >/dev/null
fi
old_target=${OLD_TARGET:-$work/target}

bench() { # TREE TARGET NAME OUT
    (cd "$1" && CARGO_TARGET_DIR=$2 cargo bench --quiet --bench "$3" >"$4" 2>&1)
}

echo "building the benchmarks of $rev and of the working tree" >&2
for name in "$@"; do
    (cd "$old_tree" && CARGO_TARGET_DIR=$old_target cargo bench --quiet --no-run --bench "$name")
    (cd "$root" && cargo bench --quiet --no-run --bench "$name")
done
for turn in $(seq 1 "$turns"); do
    for name in "$@"; do
        echo "turn $turn: $name" >&2
        bench "$old_tree" "$old_target" "$name" "$work/old.$name.$turn.txt"
        bench "$root" "$root/target" "$name" "$work/new.$name.$turn.txt"
    done
done

# A ratio line is a label, its median, and its quartiles in brackets.
ratios() { sed -nE 's/^(.*[^ ]) +([0-9]+\.[0-9]{3}) +\[[0-9.]+, [0-9.]+\]$/\1\t\2/p' "$1"; }
for name in "$@"; do
    echo
    echo "$name: median per-round ratio of each run, $rev then the working tree, turn by turn"
    {
        for turn in $(seq 1 "$turns"); do
            ratios "$work/old.$name.$turn.txt" | sed "s/^/old\t$turn\t/"
            ratios "$work/new.$name.$turn.txt" | sed "s/^/new\t$turn\t/"
        done
    } | awk -F'\t' '
        { key = $3; if (!(key in seen)) { seen[key] = 1; order[++n] = key }
          v[key, $1] = v[key, $1] sprintf(" %6s", $4) }
        END { for (i = 1; i <= n; i++) { k = order[i]
              printf "%-42s old%s   new%s\n", k, v[k, "old"], v[k, "new"] } }'
done
echo
echo "whole output: $work" >&2
