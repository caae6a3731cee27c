/* SPDX-License-Identifier: MIT */
/*
 * tinygi_scene.h - the parsed scene's tables (tg_scene, its materials,
 * objects, lights and keys) for files baked by tinygi-bake
 * (tools/scene_bake.c), which include this header and nothing else of the
 * core.  In the tree it is src/scene/scene.h; `make install` and `make
 * amalgamation` write it as one file beside tinygi.h (scene.h with the core
 * headers it needs inlined), so a baked scene compiles against the
 * installed library as well as against src/.  These are the core's own
 * types, not a stable API: a file baked for another layout stops at its
 * #error (TGI_SCENE_LAYOUT); bake it again.
 */
#ifndef TINYGI_SCENE_H
#define TINYGI_SCENE_H
#include "scene/scene.h"
#endif
