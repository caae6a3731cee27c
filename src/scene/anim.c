/* SPDX-License-Identifier: MIT */
/*
 * anim.c - keyframes to camera and object poses at time t, posed triangles,
 * and the rigid deltas between two times.  See anim.h.
 */
#include <string.h>
#include "anim.h"

tg_real tgi_anim_time(const tg_scene *s, int frame, int frames)
{
    tg_real t0 = TG_REAL_MAX, t1 = TG_REAL_MIN;
    int i;
    for (i = 0; i < s->camera_key_count; i++) {
        t0 = tg_min(t0, s->camera_keys[i].t); t1 = tg_max(t1, s->camera_keys[i].t);
    }
    for (i = 0; i < s->object_key_count; i++) {
        t0 = tg_min(t0, s->object_keys[i].t); t1 = tg_max(t1, s->object_keys[i].t);
    }
    if (t0 > t1) return 0;                  /* no keys */
    if (frames <= 1 || frame <= 0) return t0;
    if (frame >= frames - 1) return t1;
    return tg_add(t0, tg_mul(tg_sub(t1, t0), tg_ratio(frame, frames - 1)));
}

/* The time of key i, keys `stride` bytes apart starting at `times`. */
static tg_real key_time(const tg_real *times, size_t stride, int i)
{
    tg_real t;
    memcpy(&t, (const unsigned char *)times + (size_t)i * stride, sizeof t);
    return t;
}

/* Segment of sorted key times containing t: *a, *b key indices and the
 * fraction u; a == b when t is at or outside a key (exact values). */
static void key_segment(const tg_real *times, size_t stride, int count, tg_real t,
                        int *a, int *b, tg_real *u)
{
    int k;
    *u = 0;
    if (t <= key_time(times, stride, 0)) { *a = *b = 0; return; }
    if (t >= key_time(times, stride, count - 1)) { *a = *b = count - 1; return; }
    for (k = 0; k + 1 < count; k++) {
        tg_real ta = key_time(times, stride, k), tb = key_time(times, stride, k + 1);
        if (t == ta) { *a = *b = k; return; }
        if (t < tb) {
            *a = k; *b = k + 1;
            *u = tb > ta ? tg_saturate(tg_div(tg_sub(t, ta), tg_sub(tb, ta))) : 0;
            return;
        }
    }
    *a = *b = count - 1;
}

void tgi_anim_camera(const tg_scene *s, tg_real t, tg_vec3 *pos, tg_vec3 *target)
{
    const tgi_camera_key *k = s->camera_keys;
    int a, b;
    tg_real u;
    if (s->camera_key_count <= 0) { *pos = s->camera.pos; *target = s->camera.target; return; }
    key_segment(&k[0].t, sizeof k[0], s->camera_key_count, t, &a, &b, &u);
    if (a == b) { *pos = k[a].pos; *target = k[a].target; return; }
    *pos = tgi_v3_lerp(k[a].pos, k[b].pos, u);
    *target = tgi_v3_lerp(k[a].target, k[b].target, u);
}

static tgi_mat4 key_matrix(tg_vec3 translate, tgi_mat4 rot)
{
    rot.m[3] = translate.x; rot.m[7] = translate.y; rot.m[11] = translate.z;
    return rot;
}

tgi_mat4 tgi_anim_key_matrix(tg_vec3 translate, tg_vec3 axis, tg_real angle)
{
    return key_matrix(translate, tgi_m4_rotate(axis, angle));
}

void tgi_anim_object_matrix(const tg_scene *s, int object, tg_real t, tgi_mat4 *m)
{
    const tgi_object *o;
    const tgi_key *k;
    int a, b;
    tg_real u;
    *m = tgi_m4_identity();
    if (object < 0 || object >= s->object_count) return;
    o = &s->objects[object];
    if (o->key_count <= 0) return;
    k = &s->object_keys[o->first_key];
    key_segment(&k[0].t, sizeof k[0], o->key_count, t, &a, &b, &u);
    if (a == b) {
        *m = tgi_anim_key_matrix(k[a].translate, k[a].axis, k[a].angle);
        return;
    }
    {
        tg_vec3 tr = tgi_v3_lerp(k[a].translate, k[b].translate, u);
        tgi_mat4 rot;
        if (tgi_v3_dot(k[a].axis, k[b].axis) >= TG_R(0.9999f)) {
            /* same axis: the angle itself is interpolated (turns > 180 degrees kept) */
            rot = tgi_m4_rotate(k[a].axis, tg_lerp(k[a].angle, k[b].angle, u));
        } else {
            tgi_quat q = tgi_q_slerp(tgi_q_axis_angle(k[a].axis, k[a].angle),
                                   tgi_q_axis_angle(k[b].axis, k[b].angle), u);
            rot = tgi_q_to_m4(q);
        }
        *m = key_matrix(tr, rot);
    }
}

/* Inverse of a rigid transform: [R^T, -R^T t]. */
static tgi_mat4 rigid_inverse(const tgi_mat4 *m)
{
    tgi_mat4 r = tgi_m4_identity();
    tg_vec3 t = tg_v3(m->m[3], m->m[7], m->m[11]);
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i * 4 + j] = m->m[j * 4 + i];
    t = tgi_m4_dir(&r, t);
    r.m[3] = tg_neg(t.x); r.m[7] = tg_neg(t.y); r.m[11] = tg_neg(t.z);
    return r;
}

void tgi_anim_delta(const tgi_mat4 *cur, const tgi_mat4 *prev, tgi_mat4 *d)
{
    tgi_mat4 inv = rigid_inverse(cur);
    *d = tgi_m4_mul(prev, &inv);
}

void tgi_anim_object_delta(const tg_scene *s, int object, tg_real t_cur, tg_real t_prev, tgi_mat4 *d)
{
    tgi_mat4 cur, prev;
    tgi_anim_object_matrix(s, object, t_cur, &cur);
    tgi_anim_object_matrix(s, object, t_prev, &prev);
    tgi_anim_delta(&cur, &prev, d);
}

int tgi_anim_object_moves(const tg_scene *s, int object)
{
    return object >= 0 && object < s->object_count && s->objects[object].key_count >= 2;
}

int tgi_anim_has_motion(const tg_scene *s)
{
    int i;
    if (s->camera_key_count >= 2) return 1;
    for (i = 0; i < s->object_count; i++)
        if (tgi_anim_object_moves(s, i)) return 1;
    return 0;
}

int tgi_anim_has_posed_objects(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->object_count; i++)
        if (s->objects[i].key_count > 0) return 1;
    return 0;
}

void tgi_anim_pose_object(const tg_scene *s, int object, const tgi_mat4 *m, tg_vec3 *pos, tg_vec3 *nrm)
{
    const tgi_object *ob = &s->objects[object];
    int v;
    for (v = ob->first_tri * 3; v < (ob->first_tri + ob->tri_count) * 3; v++) {
        pos[v] = tgi_m4_point(m, s->tri_pos[v]);
        nrm[v] = tgi_v3_normalize_or(tgi_m4_dir(m, s->tri_nrm[v]), s->tri_nrm[v]);
    }
}

void tgi_anim_pose(const tg_scene *s, tg_real t, tg_vec3 *pos, tg_vec3 *nrm)
{
    size_t n = (size_t)s->tri_count * 3;
    int o;
    memcpy(pos, s->tri_pos, n * sizeof *pos);
    memcpy(nrm, s->tri_nrm, n * sizeof *nrm);
    for (o = 0; o < s->object_count; o++) {
        tgi_mat4 m;
        if (s->objects[o].key_count <= 0) continue;
        tgi_anim_object_matrix(s, o, t, &m);
        tgi_anim_pose_object(s, o, &m, pos, nrm);
    }
}

void tgi_anim_bounds(const tg_vec3 *pos, int tri_count, tg_vec3 *lo, tg_vec3 *hi)
{
    int v, n = tri_count * 3;
    *lo = *hi = n > 0 ? pos[0] : tg_v3(0, 0, 0);
    for (v = 1; v < n; v++) {
        lo->x = tg_min(lo->x, pos[v].x); lo->y = tg_min(lo->y, pos[v].y); lo->z = tg_min(lo->z, pos[v].z);
        hi->x = tg_max(hi->x, pos[v].x); hi->y = tg_max(hi->y, pos[v].y); hi->z = tg_max(hi->z, pos[v].z);
    }
}
