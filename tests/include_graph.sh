#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# include_graph.sh - the folder-to-folder include graph of src/, platform/
# and tools/, printed bottom-up; exits 1 on a cycle or an upward include.
#
#   bash tests/include_graph.sh          print the graph, then "include graph: ok"
#
# The tree reads bottom-up (each folder includes only folders below it):
#   0 tinygi.h (the public header)
#   1 core
#   2 scene, raster        (independent of each other)
#   3 light, gi, ao        (may include each other, without a cycle);
#     tinygi_scene.h       (the scene's tables for baked files: scene/scene.h)
#   4 frame
#   5 platform
#   6 tools
# Includes resolve as the compiler does: beside the including file, then
# src/, then platform/ (the -I paths of the Makefile).  tests/ may include
# anything and are not part of the graph.
set -u
cd "$(dirname "$0")/.."

level() {
    case $1 in
        tinygi.h) echo 0 ;; core) echo 1 ;; scene|raster) echo 2 ;;
        light|gi|ao|tinygi_scene.h) echo 3 ;; frame) echo 4 ;; platform) echo 5 ;; tools) echo 6 ;;
        *) echo -1 ;;
    esac
}
peers_allowed() { [ "$1" = 3 ]; }   # the level whose folders may include each other

folder_of() { # a repository path to its folder in the graph
    case $1 in
        src/tinygi.h) echo tinygi.h ;;
        src/tinygi_scene.h) echo tinygi_scene.h ;;
        src/*/*) p=${1#src/}; echo "${p%%/*}" ;;
        platform/*) echo platform ;;
        tools/*) echo tools ;;
        *) echo "?$1" ;;
    esac
}

resolve() { # including file, included name -> repository path
    local dir; dir=$(dirname "$1")
    for base in "$dir" src platform; do
        if [ -f "$base/$2" ]; then realpath -m --relative-to=. "$base/$2"; return; fi
    done
    echo "?$2"
}

edges=$(
    find src platform tools -name '*.[ch]' | sort | while read -r f; do
        from=$(folder_of "$f")
        sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" | while read -r inc; do
            to=$(folder_of "$(resolve "$f" "$inc")")
            [ "$from" = "$to" ] || echo "$from $to $f $inc"
        done
    done
)

bad=0
echo "include graph (folder -> folder, number of #include lines), bottom-up:"
pairs=$(echo "$edges" | awk 'NF {print $1, $2}' | sort | uniq -c | awk '{print $2, $3, $1}')
while read -r from to n; do
    [ -n "$from" ] || continue
    lf=$(level "$from"); lt=$(level "$to"); note=
    if [ "$lf" -lt 0 ] || [ "$lt" -lt 0 ]; then note="  <- UNKNOWN FOLDER (give it a level in tests/include_graph.sh)"; bad=1
    elif [ "$lt" -gt "$lf" ]; then note="  <- UPWARD"; bad=1
    elif [ "$lt" -eq "$lf" ]; then
        if peers_allowed "$lf"; then note="  (same level)"; else note="  <- SIDEWAYS (not allowed at level $lf)"; bad=1; fi
    fi
    printf '%s %-9s -> %-9s %3d%s\n' "$lf" "$from" "$to" "$n" "$note"
    if [ -n "$note" ] && [ "$note" != "  (same level)" ]; then
        echo "$edges" | awk -v a="$from" -v b="$to" '$1 == a && $2 == b {print "      " $3 ": #include \"" $4 "\""}'
    fi
done < <(echo "$pairs" | while read -r a b n; do [ -n "$a" ] && echo "$(level "$a") $a $b $n"; done | sort -n -k1,1 -k2,2 | cut -d' ' -f2-)

# cycles among folders (tsort reports a loop on stderr)
if ! echo "$pairs" | awk 'NF {print $1, $2}' | tsort >/dev/null 2>/tmp/tsort.$$; then :; fi
if [ -s /tmp/tsort.$$ ]; then
    echo "CYCLE:"; sed 's/^/  /' /tmp/tsort.$$; bad=1
fi
rm -f /tmp/tsort.$$

if [ "$bad" = 0 ]; then echo "include graph: ok (no cycle, no upward include)"; else echo "include graph: FAILED"; fi
exit "$bad"
