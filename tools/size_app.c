/* SPDX-License-Identifier: MIT */
/*
 * size_app.c - the smallest whole program an embedder would flash: parse a
 * scene from text, plan one request, render frames, hand the pixels to a
 * display buffer.  tools/size_table.sh links it with the core for a
 * Cortex-M4 (-Os -mthumb, -ffunction-sections, --gc-sections, no C library
 * but platform/baremetal/libc_mini.c) under each configuration of feature
 * switches and prints the .text the linker kept.  Not a program to run:
 * its entry never returns and nothing reads its display buffer.
 *
 * What it asks for follows the switches it is built with:
 *   TG_SIZE_AO_ONLY=1   the AO AOV as grey 8, a scene with no light;
 *   otherwise           colour as RGB565, a scene with a shadowed point
 *                       light (and a sky, unless TG_NO_ENVIRONMENT).
 * With TG_NO_TEMPORAL=1 it renders frame 0 twice (one frame per request, no
 * history).  With TG_NO_SCENE_TEXT=1 the scene is not parsed: tools/size_table.sh
 * bakes the same text into C data (tinygi-bake --name tgs_baked_scene) and
 * links it in.  Built on the host with TG_SIZE_PRINT_SCENE=1 it is a
 * program that prints that text, for the baking.
 */
#include "tinygi.h"
#include "room_scene.h"

#ifndef TG_SIZE_AO_ONLY
#define TG_SIZE_AO_ONLY 0
#endif
#ifndef TG_SIZE_PRINT_SCENE
#define TG_SIZE_PRINT_SCENE 0
#endif
#define SIZE_W 64
#define SIZE_H 48

#if !TG_NO_SCENE_TEXT || TG_SIZE_PRINT_SCENE
static const char scene_text[] =
    TG_ROOM_SCENE
#if !TG_SIZE_AO_ONLY
    "light point pos 0 2.8 0  color 1 0.9 0.8  intensity 10  shadows\n"
#if !defined(TG_NO_ENVIRONMENT) || !TG_NO_ENVIRONMENT
    "env sky 0.45 0.6 0.9  ground 0.25 0.22 0.2\n"
#endif
#endif
    ;
#endif

#if TG_SIZE_PRINT_SCENE
#include <stdio.h>
int main(void)
{
    return fputs(scene_text, stdout) < 0;
}
#else
#if TG_NO_SCENE_TEXT
const tg_scene *tgs_baked_scene(void); /* tinygi-bake's file, from scene_text */
#endif

static unsigned char arena_memory[1u << 20] __attribute__((aligned(16)));
#if TG_SIZE_AO_ONLY
static uint8_t display[SIZE_W * SIZE_H];
#else
static uint16_t display[SIZE_W * SIZE_H];
#endif

void tgs_start(void);

static void render(void)
{
    tg_arena arena;
    const tg_scene *scene;
    tg_plan plan;
    tg_request req;
    tg_frame *frame;
    tg_error err;
    void *memory;
    int i;
    tg_arena_init(&arena, arena_memory, sizeof arena_memory);
#if TG_NO_SCENE_TEXT
    scene = tgs_baked_scene();
#else
    tg_scene *parsed;
    if (tg_scene_parse(scene_text, sizeof scene_text - 1, "size", NULL, &arena, &parsed, &err) != TG_OK)
        return;
    scene = parsed;
#endif
    tg_request_defaults(&req);
    req.width = SIZE_W;
    req.height = SIZE_H;
#if TG_NO_TEMPORAL
    req.frames = 1;   /* every frame alone: the request is planned once and rendered again */
#else
    req.frames = 2;
#endif
#if TG_SIZE_AO_ONLY
    req.aovs = 1u << TG_AOV_AO;
#endif
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) return;
    memory = tg_arena_alloc(&arena, plan.total_bytes);
    if (tg_frame_create(&plan, memory, plan.total_bytes, &frame, &err) != TG_OK) return;
    for (i = 0; i < 2; i++) {
        if (tg_frame_render(frame, TG_NO_TEMPORAL ? 0 : i, &err) != TG_OK) return;
#if TG_SIZE_AO_ONLY
        tg_frame_write_pixels(frame, TG_AOV_AO, 0, SIZE_H, TG_PIXEL_GREY8, 0, display, SIZE_W);
#else
        tg_frame_write_pixels(frame, TG_AOV_COLOR, 0, SIZE_H, TG_PIXEL_RGB565, TG_PIXELS_DITHER,
                              display, 2 * SIZE_W);
#endif
    }
}

void tgs_start(void)
{
    render();
    for (;;) {
    }
}
#endif /* !TG_SIZE_PRINT_SCENE */
