/* SPDX-License-Identifier: MIT */
/*
 * room_scene.h - the small room, lights left to the caller, that the
 * feature-switch check (tests/switches_check.c) and the flash-size program
 * (tools/size_app.c) render: a camera, a white floor, a red back wall and a
 * white block, as scene text.
 */
#ifndef TG_ROOM_SCENE_H
#define TG_ROOM_SCENE_H

#define TG_ROOM_SCENE \
    "camera pos 0 1.5 -4  target 0 1 0  fov 50\n" \
    "material white albedo 0.73 0.73 0.73\n" \
    "material red albedo 0.63 0.065 0.05\n" \
    "quad p0 -2 0 -2  p1 -2 0 2  p2 2 0 2  p3 2 0 -2  material white name floor\n" \
    "quad p0 -2 0 2  p1 -2 3 2  p2 2 3 2  p3 2 0 2  material red name back\n" \
    "box min -0.5 0 -0.5  max 0.5 1 0.5  material white name block\n"

#endif
