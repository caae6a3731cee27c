/* SPDX-License-Identifier: MIT */
/*
 * test_anim.c - keyframe interpolation (exact at keys, linear between, same
 * axis angles kept past 180 degrees, slerp otherwise), frame times, posing,
 * and motion vectors against exact double-precision reprojection.
 */
#include <stdlib.h>
#include "check.h"
#include "scene/scene.h"
#include "scene/anim.h"
#include "raster/motion.h"
#include "storage_fixture.h"

#define PI 3.14159265358979
#define DEG (PI / 180.0)
#define W 160
#define H 120

static double dv(tg_real r) { return check_d(r); }
static tg_real rv(double x) { return tg_from_float((float)x); }
static tg_vec3 v3d(double x, double y, double z) { return tg_v3(rv(x), rv(y), rv(z)); }
static int v3_eq(tg_vec3 a, tg_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* A hand-built scene: camera keys at t = 0, 1, 3; object 0 static (one
 * triangle), object 1 keyed (one triangle). */
typedef struct {
    tg_scene s;
    tgi_camera_key ck[3];
    tgi_object obj[2];
    tgi_key ok[3];
    tg_vec3 pos[6], nrm[6];
    uint16_t tri_object[2], tri_material[2];
} test_scene;

static void make_scene(test_scene *ts)
{
    tg_scene *s = &ts->s;
    int i;
    memset(ts, 0, sizeof *ts);
    ts->ck[0].t = 0;         ts->ck[0].pos = v3d(0, 2, -6); ts->ck[0].target = v3d(0, 0, 0);
    ts->ck[1].t = TG_ONE;    ts->ck[1].pos = v3d(1.5, 2.5, -5.5); ts->ck[1].target = v3d(0.2, 0.1, 0);
    ts->ck[2].t = rv(3.0);   ts->ck[2].pos = v3d(-2, 3, -4); ts->ck[2].target = v3d(0, 0.5, 0.5);
    ts->obj[0].first_tri = 0; ts->obj[0].tri_count = 1;
    ts->obj[1].first_tri = 1; ts->obj[1].tri_count = 1; ts->obj[1].first_key = 0; ts->obj[1].key_count = 3;
    ts->ok[0].t = rv(0.5); ts->ok[0].translate = v3d(0, 0, 0);   ts->ok[0].axis = v3d(0, 1, 0); ts->ok[0].angle = 0;
    ts->ok[1].t = rv(1.5); ts->ok[1].translate = v3d(2, 0, 0);   ts->ok[1].axis = v3d(0, 1, 0); ts->ok[1].angle = rv(270 * DEG);
    ts->ok[2].t = rv(2.5); ts->ok[2].translate = v3d(2, 1, -1);  ts->ok[2].axis = v3d(1, 0, 0); ts->ok[2].angle = rv(90 * DEG);
    for (i = 0; i < 6; i++) {
        ts->pos[i] = v3d(i * 0.5, (i % 3) * 0.25, 1 - i * 0.1);
        ts->nrm[i] = tgi_v3_normalize(v3d(0.2 * i, 1, 0.1));
    }
    ts->tri_object[0] = 0; ts->tri_object[1] = 1;
    s->camera.pos = ts->ck[0].pos; s->camera.target = ts->ck[0].target; s->camera.up = v3d(0, 1, 0);
    s->camera.fov = rv(60 * DEG); s->camera.znear = TG_R(0.05f); s->camera.zfar = TG_R(1000.0f);
    s->camera_key_count = 3; s->camera_keys = ts->ck;
    s->object_count = 2; s->objects = ts->obj;
    s->object_key_count = 3; s->object_keys = ts->ok;
    s->tri_count = 2; s->tri_pos = ts->pos; s->tri_nrm = ts->nrm;
    s->tri_object = ts->tri_object; s->tri_material = ts->tri_material;
}

/* Rotation about a unit axis (double Rodrigues) applied to p. */
static void rotate_d(const double axis[3], double ang, const double p[3], double out[3])
{
    double c = cos(ang), s = sin(ang), d = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
    double cr[3] = { axis[1] * p[2] - axis[2] * p[1], axis[2] * p[0] - axis[0] * p[2], axis[0] * p[1] - axis[1] * p[0] };
    int k;
    for (k = 0; k < 3; k++) out[k] = p[k] * c + cr[k] * s + axis[k] * d * (1 - c);
}

TEST(keys_interpolate_exactly_at_keys)
{
    test_scene *ts = (test_scene *)malloc(sizeof *ts);
    tg_vec3 pos, target;
    tgi_mat4 m, want;
    int k, i;
    make_scene(ts);
    for (k = 0; k < 3; k++) {
        tgi_anim_camera(&ts->s, ts->ck[k].t, &pos, &target);
        CHECK(v3_eq(pos, ts->ck[k].pos) && v3_eq(target, ts->ck[k].target), "camera key %d exact", k);
        tgi_anim_object_matrix(&ts->s, 1, ts->ok[k].t, &m);
        want = tgi_m4_rotate(ts->ok[k].axis, ts->ok[k].angle);
        want.m[3] = ts->ok[k].translate.x; want.m[7] = ts->ok[k].translate.y; want.m[11] = ts->ok[k].translate.z;
        for (i = 0; i < 16; i++) CHECK(m.m[i] == want.m[i], "object key %d element %d exact", k, i);
    }
    /* before the first / after the last key the ends hold */
    tgi_anim_camera(&ts->s, rv(-2), &pos, &target);
    CHECK(v3_eq(pos, ts->ck[0].pos), "before the first key");
    tgi_anim_camera(&ts->s, rv(9), &pos, &target);
    CHECK(v3_eq(pos, ts->ck[2].pos), "after the last key");
    /* linear between keys: t = 2 is halfway between keys 1 and 3 */
    tgi_anim_camera(&ts->s, rv(2.0), &pos, &target);
    CHECK_NEAR(dv(pos.x), (1.5 + -2) / 2, 1e-3);
    CHECK_NEAR(dv(pos.y), (2.5 + 3) / 2, 1e-3);
    CHECK_NEAR(dv(target.z), 0.25, 1e-3);
    /* static object: identity */
    tgi_anim_object_matrix(&ts->s, 0, rv(1.0), &m);
    want = tgi_m4_identity();
    for (i = 0; i < 16; i++) CHECK(m.m[i] == want.m[i], "unkeyed object is at rest");
    free(ts);
}

TEST(rotation_interpolation)
{
    test_scene *ts = (test_scene *)malloc(sizeof *ts);
    tgi_mat4 m;
    double p[3] = { 1, 0.5, 0.25 }, axis_y[3] = { 0, 1, 0 }, want[3];
    tg_vec3 got;
    int k;
    make_scene(ts);
    /* same axis, 0 -> 270 degrees: halfway is 135 degrees, not the short way round */
    tgi_anim_object_matrix(&ts->s, 1, rv(1.0), &m);
    got = tgi_m4_point(&m, v3d(p[0], p[1], p[2]));
    rotate_d(axis_y, 135 * DEG, p, want);
    CHECK_NEAR(dv(got.x), want[0] + 1.0, 2e-3);
    CHECK_NEAR(dv(got.y), want[1], 2e-3);
    CHECK_NEAR(dv(got.z), want[2], 2e-3);
    /* different axes: slerp - a rigid rotation (lengths kept) between the two key poses */
    for (k = 1; k < 4; k++) {
        double t = 1.5 + k * 0.25, len0 = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), len;
        tg_vec3 r;
        tgi_anim_object_matrix(&ts->s, 1, rv(t), &m);
        r = tgi_m4_dir(&m, v3d(p[0], p[1], p[2]));
        len = sqrt(dv(r.x) * dv(r.x) + dv(r.y) * dv(r.y) + dv(r.z) * dv(r.z));
        CHECK(fabs(len - len0) < 2e-3, "rigid at t %g: |Rp| %g vs %g", t, len, len0);
    }
    {   /* at the segment midpoint the rotation is the quaternion halfway (double slerp) */
        double qa[4] = { 0, sin(135 * DEG), 0, cos(135 * DEG) }; /* 270 deg about y */
        double qb[4] = { sin(45 * DEG), 0, 0, cos(45 * DEG) };   /* 90 deg about x */
        double d = qa[0] * qb[0] + qa[1] * qb[1] + qa[2] * qb[2] + qa[3] * qb[3], q[4], th, s, angle, ax[3];
        int j;
        if (d < 0) { for (j = 0; j < 4; j++) qb[j] = -qb[j]; d = -d; }
        th = acos(d);
        for (j = 0; j < 4; j++) q[j] = (sin(0.5 * th) * qa[j] + sin(0.5 * th) * qb[j]) / sin(th);
        s = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        angle = 2 * atan2(s, q[3]);
        for (j = 0; j < 3; j++) ax[j] = q[j] / s;
        rotate_d(ax, angle, p, want);
        tgi_anim_object_matrix(&ts->s, 1, rv(2.0), &m);
        got = tgi_m4_dir(&m, v3d(p[0], p[1], p[2]));
        CHECK_NEAR(dv(got.x), want[0], 3e-3);
        CHECK_NEAR(dv(got.y), want[1], 3e-3);
        CHECK_NEAR(dv(got.z), want[2], 3e-3);
    }
    free(ts);
}

TEST(frame_times_and_posing)
{
    test_scene *ts = (test_scene *)malloc(sizeof *ts);
    tg_vec3 pos[6], nrm[6];
    tgi_mat4 m;
    int v;
    make_scene(ts);
    CHECK(tgi_anim_time(&ts->s, 0, 7) == 0, "frame 0 is the first key");
    CHECK(tgi_anim_time(&ts->s, 6, 7) == rv(3.0), "the last frame is the last key");
    CHECK_NEAR(dv(tgi_anim_time(&ts->s, 2, 7)), 1.0, 1e-4);
    CHECK(tgi_anim_time(&ts->s, 0, 1) == 0, "one frame: the first key");
    CHECK(tgi_anim_has_motion(&ts->s), "keys move");
    tgi_anim_pose(&ts->s, rv(2.5), pos, nrm);
    tgi_anim_object_matrix(&ts->s, 1, rv(2.5), &m);
    for (v = 0; v < 3; v++) CHECK(v3_eq(pos[v], ts->pos[v]) && v3_eq(nrm[v], ts->nrm[v]), "static triangle untouched");
    for (v = 3; v < 6; v++) {
        tg_vec3 p = tgi_m4_point(&m, ts->pos[v]), n = nrm[v];
        CHECK(v3_eq(pos[v], p), "keyed triangle moved by its key");
        CHECK(fabs(dv(tgi_v3_length(n)) - 1) < 1e-3, "posed normal unit");
        CHECK(fabs(dv(tgi_v3_dot(n, tgi_v3_normalize(tgi_m4_dir(&m, ts->nrm[v])))) - 1) < 1e-3, "normal rotated");
    }
    {
        tg_vec3 lo, hi;
        tgi_anim_bounds(pos, 2, &lo, &hi);
        for (v = 0; v < 6; v++)
            CHECK(pos[v].x >= lo.x && pos[v].y >= lo.y && pos[v].z >= lo.z &&
                  pos[v].x <= hi.x && pos[v].y <= hi.y && pos[v].z <= hi.z, "bounds hold vertex %d", v);
        CHECK((lo.x == pos[0].x || lo.x == pos[1].x || lo.x == pos[2].x || lo.x == pos[3].x || lo.x == pos[4].x || lo.x == pos[5].x), "tight");
    }
    ts->s.camera_key_count = 1; ts->obj[1].key_count = 1;
    CHECK(!tgi_anim_has_motion(&ts->s), "single keys do not move");
    ts->s.camera_key_count = 0; ts->s.object_key_count = 0; ts->obj[1].key_count = 0;
    CHECK(tgi_anim_time(&ts->s, 3, 10) == 0, "no keys: t = 0");
    free(ts);
}

/* ---- motion vectors ---- */

/* Scene: floor y = 0, a back wall z = 5 (2.5 high), and box [-1,1]x[0,1.5]x[-1,1] posed by M (rotation + translation). */
typedef struct { double R[3][3], T[3]; } rigid;

static void rigid_from_m4(const tgi_mat4 *m, rigid *r)
{
    int i, j;
    for (i = 0; i < 3; i++) { for (j = 0; j < 3; j++) r->R[i][j] = dv(m->m[i * 4 + j]); r->T[i] = dv(m->m[i * 4 + 3]); }
}
static void rigid_apply(const rigid *r, const double p[3], double o[3])
{
    int i;
    for (i = 0; i < 3; i++) o[i] = r->R[i][0] * p[0] + r->R[i][1] * p[1] + r->R[i][2] * p[2] + r->T[i];
}
static void rigid_inverse_apply(const rigid *r, const double p[3], double o[3])
{
    double q[3] = { p[0] - r->T[0], p[1] - r->T[1], p[2] - r->T[2] };
    int i;
    for (i = 0; i < 3; i++) o[i] = r->R[0][i] * q[0] + r->R[1][i] * q[1] + r->R[2][i] * q[2];
}

/* Ray against the posed box; returns t or -1. */
static double ray_box_posed(const rigid *m, const double o[3], const double d[3])
{
    static const double lo[3] = { -1, 0, -1 }, hi[3] = { 1, 1.5, 1 };
    double ol[3], dl[3], zero[3] = { 0, 0, 0 }, t0 = -1e30, t1 = 1e30, tmp[3];
    int a;
    rigid_inverse_apply(m, o, ol);
    rigid_apply(m, zero, tmp);
    { double dd[3] = { d[0] + tmp[0], d[1] + tmp[1], d[2] + tmp[2] }; rigid_inverse_apply(m, dd, dl); }
    for (a = 0; a < 3; a++) {
        double u, v;
        if (fabs(dl[a]) < 1e-15) { if (ol[a] < lo[a] || ol[a] > hi[a]) return -1; continue; }
        u = (lo[a] - ol[a]) / dl[a]; v = (hi[a] - ol[a]) / dl[a];
        if (u > v) { double s = u; u = v; v = s; }
        if (u > t0) t0 = u;
        if (v < t1) t1 = v;
    }
    return t0 <= t1 && t0 > 1e-9 ? t0 : -1;
}

static void view_ray(const tgi_view *v, double sx, double sy, double o[3], double d[3])
{
    double vx = (sx / v->width * 2 - 1) / dv(v->focal_x), vy = (1 - sy / v->height * 2) / dv(v->focal_y);
    o[0] = dv(v->eye.x); o[1] = dv(v->eye.y); o[2] = dv(v->eye.z);
    d[0] = vx * dv(v->right.x) + vy * dv(v->up.x) + dv(v->forward.x);
    d[1] = vx * dv(v->right.y) + vy * dv(v->up.y) + dv(v->forward.y);
    d[2] = vx * dv(v->right.z) + vy * dv(v->up.z) + dv(v->forward.z);
}

/* Exact screen position of world point p in view v (double). */
static int project_d(const tgi_view *v, const double p[3], double *sx, double *sy)
{
    double q[3] = { p[0] - dv(v->eye.x), p[1] - dv(v->eye.y), p[2] - dv(v->eye.z) };
    double x = q[0] * dv(v->right.x) + q[1] * dv(v->right.y) + q[2] * dv(v->right.z);
    double y = q[0] * dv(v->up.x) + q[1] * dv(v->up.y) + q[2] * dv(v->up.z);
    double z = q[0] * dv(v->forward.x) + q[1] * dv(v->forward.y) + q[2] * dv(v->forward.z);
    if (z <= 1e-6) return 0;
    *sx = (x * dv(v->focal_x) / z + 1) / 2 * v->width;
    *sy = (1 - y * dv(v->focal_y) / z) / 2 * v->height;
    return 1;
}

typedef struct {
    tgi_gbuffer gb;                  /* the build's storage of depth (normals unused) */
    tg_real depth[W * H], mx[W * H], my[W * H];
    uint8_t sky[W * H];
    uint16_t object[W * H];
    double world[W * H][3];
} motion_gb;

/* Cast the floor, wall (object 0) and the box posed by `box` (object 1). */
static void cast(motion_gb *g, const tgi_view *v, const rigid *box)
{
    int x, y, k;
    if (!g->gb.depth) sf_gbuffer_alloc(&g->gb, W, H, NULL, 0);
    g->gb.object = g->object; g->gb.motion_x = g->mx; g->gb.motion_y = g->my;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = y * W + x, obj = 0;
            double o[3], d[3], best = -1, t;
            view_ray(v, x + 0.5, y + 0.5, o, d);
            if (d[1] < -1e-12) best = -o[1] / d[1];
            if (d[2] > 1e-12) {  /* the wall is 2.5 high: above it is sky */
                t = (5 - o[2]) / d[2];
                if (o[1] + t * d[1] < 2.5 && (best < 0 || t < best)) best = t;
            }
            if (best > 60) best = -1; /* a finite room: beyond is sky */
            t = ray_box_posed(box, o, d);
            if (t > 0 && (best < 0 || t < best)) { best = t; obj = 1; }
            g->sky[i] = best < 0;
            g->depth[i] = best < 0 ? 0 : rv(best); /* the direction has view z = 1 */
            g->object[i] = (uint16_t)obj;
            for (k = 0; k < 3; k++) g->world[i][k] = o[k] + best * d[k];
            sf_gbuffer_set(&g->gb, (size_t)i, g->depth[i], tg_v3(0, TG_ONE, 0), 0);
        }
}

static void motion_gb_free(motion_gb *g)
{
    g->gb.object = NULL; g->gb.motion_x = g->gb.motion_y = NULL;   /* the struct's own arrays */
    sf_gbuffer_free(&g->gb);
    free(g);
}

TEST(static_scene_moving_camera_reprojects_onto_itself)
{
    test_scene *ts = (test_scene *)malloc(sizeof *ts);
    motion_gb *g = (motion_gb *)calloc(1, sizeof *g);
    tgi_view cur, prev;
    tg_vec3 pos, target;
    rigid still = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, { 0, 0.0, 0 } };
    double worst = 0;
    int i, seen = 0, sky_seen = 0, frame;
    make_scene(ts);
    for (frame = 1; frame < 12; frame++) {
        tg_real tc = tgi_anim_time(&ts->s, frame, 12), tp = tgi_anim_time(&ts->s, frame - 1, 12);
        tgi_anim_camera(&ts->s, tc, &pos, &target);
        tgi_view_make(&cur, pos, target, v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(100.0f), W, H);
        tgi_anim_camera(&ts->s, tp, &pos, &target);
        tgi_view_make(&prev, pos, target, v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(100.0f), W, H);
        cast(g, &cur, &still);
        tgi_motion_rows(&g->gb, &cur, &prev, NULL, 0, H);
        for (i = 0; i < W * H; i++) {
            double ex, ey;
            if (g->sky[i]) {   /* a direction: reprojects by rotation only */
                double o[3], d[3], far[3];
                view_ray(&cur, i % W + 0.5, i / W + 0.5, o, d);
                far[0] = dv(prev.eye.x) + d[0] * 1e6; far[1] = dv(prev.eye.y) + d[1] * 1e6; far[2] = dv(prev.eye.z) + d[2] * 1e6;
                if (!project_d(&prev, far, &ex, &ey)) continue;
                sky_seen++;
            } else {
                if (!project_d(&prev, g->world[i], &ex, &ey)) continue;
                seen++;
            }
            {
                double err = hypot(dv(g->mx[i]) - ex, dv(g->my[i]) - ey);
                if (err > worst) worst = err;
                CHECK(err <= 0.1, "pixel %d: motion (%g, %g) exact (%g, %g)", i, dv(g->mx[i]), dv(g->my[i]), ex, ey);
            }
        }
    }
    CHECK(seen > 10 * W * H / 2 && sky_seen > 100, "coverage %d surface, %d sky", seen, sky_seen);
    printf("# static scene, moving camera: worst reprojection error %.4f px\n", worst);
    free(ts); motion_gb_free(g);
}

TEST(moving_object_motion)
{
    test_scene *ts = (test_scene *)malloc(sizeof *ts);
    motion_gb *g = (motion_gb *)calloc(1, sizeof *g);
    tgi_view cur, prev;
    tgi_mat4 mcur, mprev, delta[2];
    rigid rc, rp;
    double worst = 0;
    int i, seen = 0;
    tg_real tc = rv(1.2), tp = rv(1.0);
    make_scene(ts);
    ts->ok[1].translate = v3d(0.6, 0, 0.4); /* a gentler motion keeps the box in view */
    tgi_view_make(&cur, v3d(0, 3, -6), v3d(0, 0.5, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(100.0f), W, H);
    tgi_view_make(&prev, v3d(0.3, 3, -6.2), v3d(0, 0.5, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(100.0f), W, H);
    tgi_anim_object_matrix(&ts->s, 1, tc, &mcur);
    tgi_anim_object_matrix(&ts->s, 1, tp, &mprev);
    rigid_from_m4(&mcur, &rc); rigid_from_m4(&mprev, &rp);
    tgi_anim_object_delta(&ts->s, 0, tc, tp, &delta[0]);
    tgi_anim_object_delta(&ts->s, 1, tc, tp, &delta[1]);
    cast(g, &cur, &rc);
    tgi_motion_rows(&g->gb, &cur, &prev, delta, 0, H);
    for (i = 0; i < W * H; i++) {
        double p[3], rest[3], ex, ey, err;
        if (g->sky[i] || g->object[i] != 1) continue;
        rigid_inverse_apply(&rc, g->world[i], rest);
        rigid_apply(&rp, rest, p);
        if (!project_d(&prev, p, &ex, &ey)) continue;
        err = hypot(dv(g->mx[i]) - ex, dv(g->my[i]) - ey);
        if (err > worst) worst = err;
        seen++;
        CHECK(err <= 0.1, "box pixel %d: motion (%g, %g) exact (%g, %g)", i, dv(g->mx[i]), dv(g->my[i]), ex, ey);
    }
    CHECK(seen > 100, "box pixels %d", seen);
    printf("# moving object: worst error %.4f px\n", worst);
    free(ts); motion_gb_free(g);
}

/* A surface on the previous camera's eye plane has no motion vector: the
 * camera looks along -z from z = 2 now and from z = 0 last frame (it backed
 * away), so the points at depth 2 (the plane z = 0, exactly in both number
 * types) were in its eye plane, those at depth 1.99995 just behind it and
 * those at depth 2.00005 less than the 1e-4 margin in front of it: none
 * has a motion vector; at depth 2.01 they were 0.01 in front, and have one. */
TEST(motion_on_the_previous_eye_plane_is_invalid)
{
    tgi_view cur, prev;
    int x, y, valid_on = 0, valid_near = 0, valid_front = 0;
    tgi_view_make(&cur, tg_v3(0, 0, TG_R(2.0f)), tg_v3(0, 0, 0), tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f),
                  TG_R(100.0f), 32, 24);
    tgi_view_make(&prev, tg_v3(0, 0, 0), tg_v3(0, 0, tg_neg(TG_ONE)), tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f),
                  TG_R(100.0f), 32, 24);
    for (y = 0; y < 24; y++)
        for (x = 0; x < 32; x++) {
            tg_real px, py, z;
            valid_on += tgi_motion_prev_position(&cur, &prev, NULL, x, y, TG_R(2.0f), &px, &py, &z);
            valid_near += tgi_motion_prev_position(&cur, &prev, NULL, x, y, TG_R(1.99995f), &px, &py, &z);
            valid_near += tgi_motion_prev_position(&cur, &prev, NULL, x, y, TG_R(2.00005f), &px, &py, &z);
            valid_front += tgi_motion_prev_position(&cur, &prev, NULL, x, y, TG_R(2.01f), &px, &py, &z);
        }
    CHECK(valid_on == 0, "%d points on the previous eye plane got a motion vector", valid_on);
    CHECK(valid_near == 0, "%d points within 1e-4 of it got a motion vector", valid_near);
    CHECK(valid_front == 32 * 24, "only %d points 0.01 in front of it got one", valid_front);
}

/* A time exactly on a middle key takes that key, not the interpolation
 * toward it (in float 0.7 + (0.1 - 0.7) * 1 is 0.100000024, not 0.1). */
TEST(a_time_on_a_middle_key_takes_it_exactly)
{
    tg_scene s;
    tgi_camera_key keys[3];
    tg_vec3 pos, target;
    int k;
    memset(&s, 0, sizeof s);
    memset(keys, 0, sizeof keys);
    for (k = 0; k < 3; k++) {
        keys[k].t = tg_from_int(k);
        keys[k].pos = tg_v3(rv(k == 0 ? 0.7 : k == 1 ? 0.1 : 0.5), rv(0.3 * k), 0);
        keys[k].target = tg_v3(0, 0, rv(-1.0 - 0.7 * k));
    }
    s.camera_keys = keys;
    s.camera_key_count = 3;
    tgi_anim_camera(&s, TG_ONE, &pos, &target);
    CHECK(pos.x == keys[1].pos.x && pos.y == keys[1].pos.y && target.z == keys[1].target.z,
          "camera at key 1: (%.9g, %.9g), want (%.9g, %.9g)", dv(pos.x), dv(pos.y), dv(keys[1].pos.x), dv(keys[1].pos.y));
}

int main(void)
{
    RUN(keys_interpolate_exactly_at_keys);
    RUN(rotation_interpolation);
    RUN(frame_times_and_posing);
    RUN(static_scene_moving_camera_reprojects_onto_itself);
    RUN(moving_object_motion);
    RUN(motion_on_the_previous_eye_plane_is_invalid);
    RUN(a_time_on_a_middle_key_takes_it_exactly);
    return check_summary();
}
