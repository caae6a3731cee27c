#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tree_test.sh - the source tree reads bottom-up: tests/include_graph.sh
# finds no cycle and no upward include among the folders of src/, platform/
# and tools/ (it prints the graph; run it alone to see it).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
out=$(bash tests/include_graph.sh 2>&1); rc=$?
if [ $rc -eq 0 ]; then ok "include graph: no cycle, no upward include"
else fail "include graph" "$(echo "$out" | grep -E 'UPWARD|SIDEWAYS|UNKNOWN|CYCLE|tsort|#include' | tr '\n' ' ')"; fi
# the parsers share one lexer, and nothing but the scene folder sees it
expect "scene/obj.c reads OBJ and MTL text through scene/lex.h" grep -q '"lex.h"' src/scene/parse_internal.h
lexdefs=$(grep -lE '^(int|void) tgi_lex_' src/*/*.c | tr '\n' ' ')
expect "the lexer is defined once, in src/scene/lex.c (found: $lexdefs)" test "$lexdefs" = "src/scene/lex.c "
summary
