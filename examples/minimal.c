/* SPDX-License-Identifier: MIT */
/* examples/minimal.c - embed tinygi: parse a scene, plan a frame, render it
 * and write the colour image as a PPM on stdout (`./minimal > cornell.ppm`).
 * Every call's status is checked.  The README's "Embedding" section is this
 * file, and tests/readme_snippet_test.sh keeps the two identical. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"

static unsigned char scene_memory[256 * 1024]; /* the parsed scene lives here */

static int fail(const tg_error *err)
{
    char text[600];
    tg_error_format(err, text, sizeof text); /* FILE:LINE:COL: error: ... */
    fprintf(stderr, "minimal: %s\n", text);
    return 1;
}

int main(void)
{
    const char *text = tg_builtin_scene("cornell"); /* or a scene file's text */
    tg_arena scene_arena;
    tg_scene *scene;
    tg_request req;
    tg_plan plan;
    tg_frame *frame;
    tg_error err;
    void *frame_memory;
    uint8_t *rgb;
    int y, w, h;

    if (!text) { /* a library built with TG_NO_BUILTIN_SCENES=1 has none */
        fputs("minimal: no built-in scenes in this build: parse a scene file's text\n", stderr);
        return 1;
    }
    tg_arena_init(&scene_arena, scene_memory, sizeof scene_memory);
    if (tg_scene_parse(text, strlen(text), "builtin:cornell", NULL, &scene_arena, &scene, &err) != TG_OK)
        return fail(&err); /* TG_ERR_MEMORY: err.bytes_needed says how many bytes */
    tg_request_defaults(&req); /* 320x240, colour, HBIL with the paper's settings */
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK)
        return fail(&err);
    w = plan.request.width;
    h = plan.request.height;
    frame_memory = malloc(plan.total_bytes); /* the one block a frame needs */
    rgb = malloc((size_t)w * 3);
    if (!frame_memory || !rgb) {
        fprintf(stderr, "minimal: out of memory (%zu bytes)\n", plan.total_bytes);
        return 1;
    }
    if (tg_frame_create(&plan, frame_memory, plan.total_bytes, &frame, &err) != TG_OK)
        return fail(&err);
    if (tg_frame_render(frame, 0, &err) != TG_OK)
        return fail(&err);

    printf("P6\n%d %d\n255\n", w, h);
    for (y = 0; y < h; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb); /* exposed, tonemapped, sRGB */
        if (fwrite(rgb, 3, (size_t)w, stdout) != (size_t)w)
            break;
    }
    free(rgb);
    free(frame_memory);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        perror("minimal: writing the image");
        return 1;
    }
    return 0;
}
