/* SPDX-License-Identifier: MIT */
/*
 * test_arena.c - the caller's arena (src/core/arena.c): every block is
 * 16-byte aligned as an ADDRESS, whatever the alignment of the memory handed
 * to tg_arena_init (a struct at base + 1 is a fault on a Cortex-M0 and
 * undefined behaviour everywhere), zeroed, inside the memory, and the
 * scene parser's and the frame plan's byte counts hold at every base
 * offset; the overflow-checked size helpers.
 */
#include "check.h"
#include <stdlib.h>

static unsigned char mem[(1 << 21) + 64];

static int aligned(const void *p) { return ((uintptr_t)p & 15u) == 0; }

/* The first 16-byte aligned address in mem. */
static unsigned char *mem16(void) { return mem + ((16u - ((uintptr_t)mem & 15u)) & 15u); }

TEST(alloc_aligned_at_any_base)
{
    int off, k, bad_align = 0, bad_zero = 0, bad_range = 0;
    for (off = 0; off < 16; off++) {
        tg_arena a;
        unsigned char *base = mem + off;
        memset(mem, 0xAB, 4096);
        tg_arena_init(&a, base, 2048);
        for (k = 1; k <= 20; k++) {
            unsigned char *p = (unsigned char *)tg_arena_alloc(&a, (size_t)(k * 7));
            size_t i;
            if (!p) { bad_range++; break; }
            if (!aligned(p)) bad_align++;
            if (p < base || p + k * 7 > base + 2048 || a.used != (size_t)(p - base) + (size_t)(k * 7)) bad_range++;
            for (i = 0; i < (size_t)(k * 7); i++) if (p[i]) bad_zero++;
        }
    }
    CHECK(bad_align == 0, "%d blocks not 16-byte aligned", bad_align);
    CHECK(bad_zero == 0, "%d bytes not zeroed", bad_zero);
    CHECK(bad_range == 0, "%d blocks outside the arena or a wrong 'used'", bad_range);
}

TEST(alloc_full)
{
    tg_arena a;
    void *p;
    tg_arena_init(&a, mem16() + 3, 64);
    p = tg_arena_alloc(&a, 64 - 13);           /* 13 bytes of padding first */
    CHECK(p == mem16() + 16 && a.used == 64, "padding then the whole rest: %p %zu", p, a.used);
    CHECK(tg_arena_alloc(&a, 1) == NULL && a.failed_request == 1, "full");
    tg_arena_init(&a, mem16() + 3, 64);
    CHECK(tg_arena_alloc(&a, 64 - 12) == NULL && a.used == 0 && a.failed_request == 52, "one byte too many");
    CHECK(tg_arena_alloc(&a, (size_t)-1) == NULL && a.failed_request == (size_t)-1, "huge");
    tg_arena_init(&a, NULL, 100);
    CHECK(a.size == 0 && tg_arena_alloc(&a, 1) == NULL, "no memory");
}

/* bytes_needed is what the parse needs at THAT base; the scene's arrays are
 * aligned there (UBSan saw misaligned tg_scene structs at base + 1). */
TEST(scene_parse_at_any_base)
{
    const char *text = tg_builtin_scene("cornell");
    int off, bad = 0;
    for (off = 0; off < 16; off++) {
        tg_arena a;
        tg_scene *s = NULL;
        tg_error err;
        size_t need;
        tg_arena_init(&a, mem + off, 16);
        if (tg_scene_parse(text, strlen(text), "cornell", NULL, &a, &s, &err) != TG_ERR_MEMORY) { bad++; continue; }
        need = err.bytes_needed;
        tg_arena_init(&a, mem + off, need - 1);
        if (tg_scene_parse(text, strlen(text), "cornell", NULL, &a, &s, &err) != TG_ERR_MEMORY ||
            err.bytes_needed != need) {
            CHECK(0, "base + %d: one byte short of %zu must fail asking for %zu", off, need, need);
            bad++;
        }
        tg_arena_init(&a, mem + off, need);
        if (tg_scene_parse(text, strlen(text), "cornell", NULL, &a, &s, &err) != TG_OK || !s) {
            CHECK(0, "base + %d: bytes_needed %zu is not enough: %s", off, need, err.message);
            bad++;
            continue;
        }
        if (!aligned(s)) { CHECK(0, "base + %d: scene at %p", off, (void *)s); bad++; }
    }
    CHECK(bad == 0, "%d base offsets failed", bad);
}

/* A frame carved at base + 1 renders what one at an aligned base renders. */
TEST(frame_at_odd_base)
{
    static unsigned char scene_mem[1 << 20];
    const char *text = tg_builtin_scene("spheres");
    unsigned char *frame_mem;
    tg_arena a;
    tg_scene *s;
    tg_error err;
    tg_request req;
    tg_plan plan;
    tg_frame *f0, *f1;
    tg_real r0[3 * 40], r1[3 * 40];
    int y, same = 1;
    tg_arena_init(&a, scene_mem + 1, sizeof scene_mem - 1);
    if (tg_scene_parse(text, strlen(text), "spheres", NULL, &a, &s, &err) != TG_OK) { CHECK(0, "%s", err.message); return; }
    tg_request_defaults(&req);
    req.width = 40; req.height = 30;
    req.aovs = (1u << TG_AOV_COLOR) | (1u << TG_AOV_AO);
    if (tg_plan_make(&plan, s, &req, &err) != TG_OK) { CHECK(0, "%s", err.message); return; }
    frame_mem = (unsigned char *)malloc(2 * plan.total_bytes + 64);
    if (!frame_mem) return;
    CHECK(tg_frame_create(&plan, frame_mem + 16, plan.total_bytes, &f0, &err) == TG_OK, "aligned: %s", err.message);
    CHECK(tg_frame_create(&plan, frame_mem + plan.total_bytes + 33, plan.total_bytes, &f1, &err) == TG_OK,
          "at an odd address, with plan.total_bytes: %s", err.message);
    if (f0 && f1 && tg_frame_render(f0, 0, &err) == TG_OK && tg_frame_render(f1, 0, &err) == TG_OK) {
        for (y = 0; y < 30; y++) {
            tg_frame_aov_row(f0, TG_AOV_COLOR, y, r0);
            tg_frame_aov_row(f1, TG_AOV_COLOR, y, r1);
            if (memcmp(r0, r1, sizeof r0)) same = 0;
            tg_frame_aov_row(f0, TG_AOV_AO, y, r0);
            tg_frame_aov_row(f1, TG_AOV_AO, y, r1);
            if (memcmp(r0, r1, 40 * sizeof(tg_real))) same = 0;
        }
        CHECK(same, "the same image at both bases");
    } else {
        CHECK(0, "render: %s", err.message);
    }
    free(frame_mem);
}

TEST(size_helpers)
{
    size_t out = 7;
    CHECK(tg_size_mul(0, (size_t)-1, &out) == 0 && out == 0, "0 * max");
    CHECK(tg_size_mul((size_t)-1 / 3, 3, &out) == 0 && out == (size_t)-1 / 3 * 3, "exact");
    CHECK(tg_size_mul((size_t)-1 / 3 + 1, 3, &out) == 1, "overflow");
    CHECK(tg_size_add((size_t)-1 - 5, 5, &out) == 0 && out == (size_t)-1, "max");
    CHECK(tg_size_add((size_t)-1 - 5, 6, &out) == 1, "overflow");
}

int main(void)
{
    RUN(alloc_aligned_at_any_base);
    RUN(alloc_full);
    RUN(scene_parse_at_any_base);
    RUN(frame_at_odd_base);
    RUN(size_helpers);
    return check_summary();
}
