#!/usr/bin/env bash
# Renders every shot in shots/ and every example with an earlier revision and with the working
# tree, and compares the files byte for byte: what a change that must not alter output runs.
#
#   scripts/same-bytes.sh REV [WORKDIR]
#
# Every frame of every shot with its own settings; each shot's first, middle and last frame
# again with every AOV at the preview and final presets; the examples' images. REV is built in a
# git worktree under WORKDIR (default: a new temporary folder); set OLD_TARGET to reuse a
# release build of REV, and KEEP_OLD=1 to keep the files REV rendered into WORKDIR on an earlier
# run (only REV's files: the working tree's are rendered again). A shot that REV does not have,
# or has with other text, is left out and named. Exits 0 when every file is the same, 1
# otherwise.
set -euo pipefail
rev=${1:?usage: scripts/same-bytes.sh REV [WORKDIR]}
root=$(cd "$(dirname "$0")/.." && pwd)
work=${2:-$(mktemp -d)}
mkdir -p "$work"
old_tree=$work/tree
if [ ! -d "$old_tree" ]; then
    git -C "$root" worktree add --detach "$old_tree" "$rev" >/dev/null
fi
old_target=${OLD_TARGET:-$work/target}

sums() { (cd "$1" && find . -type f ! -name '*.tmp' | sort | xargs sha256sum); }

build() { # TREE TARGET
    (cd "$1" && CARGO_TARGET_DIR=$2 cargo build --release --quiet --bins --examples)
}

render_all() { # TREE TARGET OUT
    local tree=$1 bin=$2/release/glint out=$3
    rm -rf "$out"
    mkdir -p "$out"
    for shot in "$root"/shots/*.ron; do
        local name
        name=$(basename "$shot" .ron)
        # A shot REV does not have, or has otherwise, is not compared (and is named once).
        if ! cmp -s "$shot" "$old_tree/shots/$name.ron"; then
            [ "$tree" = "$root" ] || echo "not compared: shots/$name.ron differs in $rev" >&2
            continue
        fi
        "$bin" render "$shot" --quiet --out "$out/$name/$name.####.png"
        local range first last middle
        range=$(grep -m1 -o 'frames: *([^)]*)' "$shot" | tr -dc '0-9,-')
        first=${range%,*}
        last=${range#*,}
        middle=$(((first + last) / 2))
        for preset in preview final; do
            "$bin" render "$shot" --quiet --frames "$first,$middle,$last" --preset "$preset" \
                --aov matte,patch_id,depth,normal,uv,n_dot_h \
                --out "$out/$name-aov-$preset/$name.####.png"
        done
    done
    (cd "$tree" && "$2/release/examples/ops_gallery" "$out/examples/ops_gallery" >/dev/null)
    (cd "$tree" && "$2/release/examples/render_teapot" "$out/examples/render_teapot" >/dev/null)
    (cd "$tree" && "$2/release/examples/xtoon_gallery" "$out/examples/xtoon_gallery" >/dev/null)
    (cd "$tree" && "$2/release/examples/toon_textures" "$out/examples/toon_textures" >/dev/null)
}

if [ "${KEEP_OLD:-0}" = 1 ] && [ -s "$work/old.sha256" ]; then
    echo "keeping what $rev rendered into $work/old" >&2
else
    echo "building and rendering $rev" >&2
    build "$old_tree" "$old_target"
    render_all "$old_tree" "$old_target" "$work/old"
    sums "$work/old" >"$work/old.sha256"
fi
echo "building and rendering the working tree" >&2
build "$root" "$root/target"
render_all "$root" "$root/target" "$work/new"

sums "$work/new" >"$work/new.sha256"
files=$(wc -l <"$work/old.sha256")
if diff -q "$work/old.sha256" "$work/new.sha256" >/dev/null; then
    echo "same bytes: $files files (every shot, its AOVs at both presets, every example)"
else
    echo "DIFFERENT: $(diff "$work/old.sha256" "$work/new.sha256" | grep -c '^>') of $files files differ:"
    diff "$work/old.sha256" "$work/new.sha256" | grep '^[<>]' | head -20
    exit 1
fi
