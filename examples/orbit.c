/* SPDX-License-Identifier: MIT */
/* examples/orbit.c - a game loop: a camera swinging round the Cornell box,
 * set frame by frame through tinygi's game-loop API (tinygi.h), each frame
 * reprojected from the one before.  The orbit is computed with tinygi's own
 * numbers (tg_sin, tg_cos), so it runs in both number types.  Frames are
 * written as numbered PPM files with plain stdio (each to a temporary file,
 * then renamed), and a line per frame says what it holds:
 *
 *   orbit [-n FRAMES] [-s WIDTHxHEIGHT] [-o PREFIX]
 *   ./orbit -n 48 -o frames/orbit-      frames/orbit-000.ppm ... orbit-047.ppm
 *
 * Defaults: 48 frames (one swing there and back) at 320x240, prefix "orbit-".
 * Every call's status is checked. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"

#define PERIOD 48 /* frames per swing, there and back */

static unsigned char scene_memory[256 * 1024];

static int fail(const tg_error *err)
{
    char text[600];
    tg_error_format(err, text, sizeof text);
    fprintf(stderr, "orbit: %s\n", text);
    return 1;
}

/* The game loop's frame: the built-in Cornell box (parsed into
 * scene_memory), frames of w x h, each reprojecting the last, the camera
 * set by the program; *memory the block it lives in (malloc).  NULL
 * (reported) on failure. */
static tg_frame *start_frame(int w, int h, int frames, void **memory)
{
    const char *text = tg_builtin_scene("cornell");
    tg_arena scene_arena;
    tg_scene *scene;
    tg_request req;
    tg_plan plan;
    tg_frame *frame = NULL;
    tg_error err;
    if (!text) { /* a library built with TG_NO_BUILTIN_SCENES=1 has none */
        fputs("orbit: no built-in scenes in this build: parse a scene file's text\n", stderr);
        return NULL;
    }
    tg_arena_init(&scene_arena, scene_memory, sizeof scene_memory);
    if (tg_scene_parse(text, strlen(text), "builtin:cornell", NULL, &scene_arena, &scene, &err) != TG_OK) {
        fail(&err);
        return NULL;
    }
    tg_request_defaults(&req);
    req.width = w;
    req.height = h;
    req.frames = frames;   /* more than one: each frame reprojects the last */
    req.game_loop = 1;     /* the program sets the camera */
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) {
        fail(&err);
        return NULL;
    }
    *memory = malloc(plan.total_bytes);
    if (!*memory) {
        fprintf(stderr, "orbit: out of memory (%zu bytes)\n", plan.total_bytes);
        return NULL;
    }
    if (tg_frame_create(&plan, *memory, plan.total_bytes, &frame, &err) != TG_OK) fail(&err);
    return frame;
}

/* Frame i's camera: on a circle round the box's centre, swinging 40
 * degrees either side of the open front and rising a little with it. */
static void orbit_camera(int i, tg_real pos[3], tg_real target[3])
{
    tg_real phase = tg_mul(TG_TWO_PI, tg_ratio(i, PERIOD));
    tg_real swing = tg_mul(tg_mul(TG_R(40.0f), TG_DEG2RAD), tg_sin(phase));
    tg_real radius = TG_R(10.8f);
    target[0] = TG_R(2.78f);
    target[1] = TG_R(2.74f);
    target[2] = TG_R(2.8f);
    pos[0] = tg_add(target[0], tg_mul(radius, tg_sin(swing)));
    pos[1] = tg_add(target[1], tg_mul(TG_R(0.8f), tg_sub(TG_ONE, tg_cos(phase))));
    pos[2] = tg_sub(target[2], tg_mul(radius, tg_cos(swing)));
}

/* The colour AOV as a PPM file (through a temporary file), and the mean of
 * its linear radiance in mean[3]; 0 on success. */
static int write_frame(const tg_frame *frame, int w, int h, const char *path, float mean[3])
{
    char tmp[1200];
    uint8_t *rgb = malloc((size_t)w * 3);
    tg_real *row = malloc((size_t)w * 3 * sizeof *row);
    FILE *out;
    int x, y, c, bad;
    sprintf(tmp, "%s.tmp", path);
    out = fopen(tmp, "wb");
    bad = !rgb || !row || !out || fprintf(out, "P6\n%d %d\n255\n", w, h) < 0;
    mean[0] = mean[1] = mean[2] = 0;
    for (y = 0; y < h && !bad; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb);
        tg_frame_aov_row(frame, TG_AOV_COLOR, y, row);
        for (x = 0; x < w; x++)
            for (c = 0; c < 3; c++) mean[c] += tg_to_float(row[3 * x + c]) / ((float)w * (float)h);
        bad = fwrite(rgb, 3, (size_t)w, out) != (size_t)w;
    }
    if (out && fclose(out) != 0) bad = 1;
    free(rgb);
    free(row);
    if (!bad && rename(tmp, path) == 0) return 0;
    perror(path);
    remove(tmp);
    return 1;
}

int main(int argc, char **argv)
{
    const char *prefix = "orbit-";
    void *frame_memory = NULL;
    tg_frame *frame;
    tg_error err;
    tg_real up[3] = { 0, TG_ONE, 0 }, pos[3], target[3];
    tg_real fov = tg_mul(TG_R(38.0f), TG_DEG2RAD);
    int frames = PERIOD, w = 320, h = 240, i;

    for (i = 1; i + 1 < argc; i += 2) {
        const char *opt = argv[i], *val = argv[i + 1];
        if (strcmp(opt, "-n") == 0) frames = atoi(val);
        else if (strcmp(opt, "-s") == 0) { if (sscanf(val, "%dx%d", &w, &h) != 2) break; }
        else if (strcmp(opt, "-o") == 0 && strlen(val) < 1000) prefix = val;
        else break;
    }
    if (i < argc || frames < 1) {
        if (i >= argc) fprintf(stderr, "orbit: error: -n: expected a frame count >= 1\n");
        else fprintf(stderr, "orbit: error: unexpected '%s'\n", argv[i]);
        fprintf(stderr, "usage: orbit [-n FRAMES] [-s WIDTHxHEIGHT] [-o PREFIX]\n");
        return 2;
    }
    frame = start_frame(w, h, frames, &frame_memory);
    if (!frame)
        return 1;

    for (i = 0; i < frames; i++) { /* the game loop */
        char path[1100];
        float mean[3];
        orbit_camera(i, pos, target);
        if (tg_frame_set_camera(frame, pos, target, up, fov, &err) != TG_OK ||
            tg_frame_render(frame, i, &err) != TG_OK)
            return fail(&err);
        sprintf(path, "%s%03d.ppm", prefix, i);
        if (write_frame(frame, w, h, path, mean) != 0)
            return 1;
        printf("%s: %s, mean radiance %.4f %.4f %.4f\n", path,
               tg_frame_reprojected(frame) ? "reprojected" : "first frame",
               (double)mean[0], (double)mean[1], (double)mean[2]);
    }
    free(frame_memory);
    return 0;
}
