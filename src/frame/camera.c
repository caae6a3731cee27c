/* SPDX-License-Identifier: MIT */
/*
 * camera.c - the frame's first pass and the game loop that feeds it.
 *
 * A frame renders the scene as it is now.  Before each render this pass
 * makes that state: the camera and every object's pose, each taken from
 * the program (tg_frame_set_camera, tg_frame_set_object) or from the
 * scene's keys at the keys' time (scene/anim.c), by the precedence
 * tinygi.h states; the posed triangles; every object's motion since the
 * last frame (raster/motion.h turns it into motion vectors); and whether
 * this frame continues the last one or is a cut.  The keys and the program
 * are two producers of the same state, so the same camera and poses give
 * the same bits whoever set them.  The program's lights and environment
 * live in the frame's own copy of its scene (tgi_frame_own_scene), which
 * every pass reads through f->scene.
 */
#include <string.h>
#include "frame_internal.h"
#include "../core/error.h"
#include "../scene/anim.h"
#include "../light/sh.h"

enum { TGI_SET_CAMERA = 1u << 0, TGI_SET_TIME = 1u << 1 };

/* f->shadows_stale holds a bit per light */
typedef char tgi_stale_bits_hold_every_light[TG_MAX_LIGHTS <= 64 ? 1 : -1];

void tgi_frame_own_scene(tg_frame *f, tg_scene *own, tgi_light *lights)
{
    *own = *f->scene;
    if (lights) memcpy(lights, f->scene->lights, (size_t)f->scene->light_count * sizeof *lights);
    own->lights = lights;
    f->scene = own;
}

/* ---- the pass ---- */

/* This frame's camera: the program's, else the keys' at f->time, else the
 * scene's fixed camera. */
static void camera_view(const tg_frame *f, tgi_view *v)
{
    const tg_scene *s = f->scene;
    const struct tgi_drive *d = &f->drive;
    tg_vec3 pos = s->camera.pos, target = s->camera.target;
    if (d->set & TGI_SET_CAMERA) {
        tgi_view_make(v, d->pos, d->target, d->up, d->fov, s->camera.znear, s->camera.zfar, f->width, f->height);
        return;
    }
#if !TG_NO_ANIMATION /* the keys are left out with TG_NO_ANIMATION=1 (tinygi.h "FEATURE SWITCHES") */
    if (s->camera_key_count > 0) tgi_anim_camera(s, f->time, &pos, &target);
#endif
    tgi_view_make(v, pos, target, s->camera.up, s->camera.fov, s->camera.znear, s->camera.zfar,
                  f->width, f->height);
}

/* A jump the history cannot follow: the eye moved further than
 * TG_CUT_DISTANCE times the scene's size, or the view turned by more than
 * the vertical fov. */
#if !(TG_NO_COLOR && TG_NO_TEMPORAL)
static int camera_cut(const tg_scene *s, const tgi_view *before, const tgi_view *now)
{
    tg_real size = tgi_v3_length(tgi_v3_sub(s->bounds_max, s->bounds_min));
    tg_real moved = tgi_v3_length(tgi_v3_sub(now->eye, before->eye));
    if (moved > tg_mul(TG_R(TG_CUT_DISTANCE), size)) return 1;
    return tgi_v3_dot(before->forward, now->forward) < tg_cos(now->fov_y);
}
#endif

/* The frame renders as a first frame: no reprojection, the temporal filter
 * restarts, the full bounce count (tg_frame_render counted them before this
 * pass ran), no motion. */
static void drop_history(tg_frame *f)
{
    f->has_history = 0;
    f->frames_rendered = 0;
    f->bounces = (f->effects & TG_EFFECT_NEAR) && f->request.bounces > 1 ? f->request.bounces : 1;
    f->prev_view = f->view;
}

/* The plan carries something from frame to frame. */
static int keeps_history(const tg_frame *f)
{
    return (f->effects & TG_EFFECT_REPROJECTION) || (f->needs & (TG_NEED_TEMPORAL | TG_NEED_MOTION));
}

/* Object o is not at rest: it has keys, or the program set its pose. */
static int object_posed(const tg_frame *f, int o)
{
    return f->scene->objects[o].key_count > 0 || (f->drive.object_set && f->drive.object_set[o].m[15] != 0);
}

/* Object o's pose now: the program's, else its keys' at f->time (identity
 * without keys). */
static void object_now(const tg_frame *f, int o, tgi_mat4 *m)
{
    if (f->drive.object_set && f->drive.object_set[o].m[15] != 0) *m = f->drive.object_set[o];
#if TG_NO_ANIMATION /* no keys: at rest (tg_plan_make refuses a scene with keys) */
    else *m = tgi_m4_identity();
#else
    else tgi_anim_object_matrix(f->scene, o, f->time, m);
#endif
}

/* Every object's pose and motion since the last frame (none on a first
 * frame), and the posed triangles when a pose changed. */
static void pose_objects(tg_frame *f, int first)
{
    const tg_scene *s = f->scene;
    int o, moved = first;
    for (o = 0; o < s->object_count; o++) {
        tgi_mat4 now, *shown = &f->drive.object_pose[o];
        object_now(f, o, &now);
        if (first) *shown = now;
        if (memcmp(shown, &now, sizeof now) != 0) moved = 1;
        tgi_anim_delta(&now, shown, &f->object_delta[o]);
        *shown = now;
    }
    if (!moved) return; /* the posed triangles are last frame's, bit for bit */
    memcpy(f->posed_pos, s->tri_pos, (size_t)s->tri_count * 3 * sizeof *f->posed_pos);
    memcpy(f->posed_nrm, s->tri_nrm, (size_t)s->tri_count * 3 * sizeof *f->posed_nrm);
    for (o = 0; o < s->object_count; o++)
        if (object_posed(f, o)) tgi_anim_pose_object(s, o, &f->drive.object_pose[o], f->posed_pos, f->posed_nrm);
    f->shadows_stale = ~(uint64_t)0;
}

/* The camera and poses of this frame, and whether it continues the last. */
void tgi_pass_animate(tg_frame *f)
{
    const tg_scene *s = f->scene;
    int first = f->index == 0 || f->frames_rendered == 0 || f->drive.cut;
    f->prev_view = f->view;
    f->prev_time = f->time;
    f->time = (f->drive.set & TGI_SET_TIME) ? f->drive.time : tgi_anim_time(s, f->index, f->request.frames);
    camera_view(f, &f->view);
#if !(TG_NO_COLOR && TG_NO_TEMPORAL)
    /* (without colour and temporal accumulation, tinygi.h "FEATURE SWITCHES",
     * nothing carries over between frames, so a jump changes nothing a frame
     * shows: the test is left out with them) */
    if (!first && camera_cut(s, &f->prev_view, &f->view)) first = 1;
#endif
    if (first) drop_history(f);
    f->drive.cut = 0;
    f->drive.reprojected = !first && keeps_history(f);
    if (f->posed_pos) pose_objects(f, first);
}

/* ---- the program's calls ---- */

static tg_status refuse(tg_error *err, const char *what, const char *more)
{
    tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, what);
    if (more) tgi_error_append(err, more);
    return TG_ERR_INPUT;
}

/* TG_OK when f can be driven by the program. */
static tg_status drivable(const tg_frame *f, tg_error *err)
{
    tgi_error_clear(err);
    if (!f) return refuse(err, "frame is NULL", NULL);
    if (!f->request.game_loop)
        return refuse(err, "the frame's plan was made without request.game_loop = 1, ",
                      "so it keeps no state the program can set");
    return TG_OK;
}

static tg_status not_finite(tg_error *err, const char *name, tg_real v)
{
    refuse(err, name, " must be finite, got ");
    tgi_error_append_real(err, v);
    return TG_ERR_INPUT;
}

/* v as a vector: TG_OK, or TG_ERR_INPUT when NULL or not finite. */
static tg_status vec_arg(tg_error *err, const char *name, const tg_real *v, tg_vec3 *out)
{
    int i;
    if (!v) return refuse(err, name, " is NULL");
    for (i = 0; i < 3; i++)
        if (!tg_isfinite(v[i])) return not_finite(err, name, v[i]);
    *out = tg_v3(v[0], v[1], v[2]);
    return TG_OK;
}

/* A direction, normalized as the scene's are (tgi_unit); zero is refused. */
static tg_status dir_arg(tg_error *err, const char *name, const tg_real *v, tg_vec3 *out)
{
    tg_vec3 d;
    if (vec_arg(err, name, v, &d)) return TG_ERR_INPUT;
    *out = tgi_unit(d);
    if (out->x == 0 && out->y == 0 && out->z == 0)
        return refuse(err, name, " must be a direction of non-zero length");
    return TG_OK;
}

/* A colour: every channel finite and >= 0. */
static tg_status color_arg(tg_error *err, const char *name, const tg_real *v, tg_vec3 *out)
{
    int i;
    if (vec_arg(err, name, v, out)) return TG_ERR_INPUT;
    for (i = 0; i < 3; i++)
        if (v[i] < 0) {
            refuse(err, name, " must be 0 or more in each channel, got ");
            tgi_error_append_real(err, v[i]);
            return TG_ERR_INPUT;
        }
    return TG_OK;
}

/* An index into a table of `count` (objects, lights). */
static tg_status index_arg(tg_error *err, const char *name, const char *plural, int i, int count)
{
    if (count <= 0) return refuse(err, "the scene has no ", plural);
    if (i >= 0 && i < count) return TG_OK;
    tgi_error_range(err, name, 0, count - 1);
    tgi_error_append_int(err, i);
    return TG_ERR_INPUT;
}

int tg_scene_find_object(const tg_scene *scene, const char *name)
{
    int i;
    if (!scene || !name || !name[0]) return -1;
    for (i = 0; i < scene->object_count; i++)
        if (strcmp(scene->objects[i].name, name) == 0) return i;
    return -1;
}

int tg_scene_light_count(const tg_scene *scene)
{
    return scene ? scene->light_count : 0;
}

tg_status tg_frame_set_camera(tg_frame *f, const tg_real pos[3], const tg_real target[3],
                              const tg_real up[3], tg_real fov, tg_error *err)
{
    tg_vec3 p, t, u;
    if (drivable(f, err) || vec_arg(err, "pos", pos, &p) || vec_arg(err, "target", target, &t) ||
        dir_arg(err, "up", up, &u))
        return TG_ERR_INPUT;
    if (p.x == t.x && p.y == t.y && p.z == t.z) return refuse(err, "target must differ from pos", NULL);
    if (!(fov > 0 && fov < TG_PI)) {
        refuse(err, "fov must be between 0 and pi radians (exclusive), got ", NULL);
        tgi_error_append_real(err, fov);
        return TG_ERR_INPUT;
    }
    f->drive.pos = p;
    f->drive.target = t;
    f->drive.up = u;
    f->drive.fov = fov;
    f->drive.set |= TGI_SET_CAMERA;
    return TG_OK;
}

tg_status tg_frame_set_object(tg_frame *f, int object, const tg_real translate[3],
                              const tg_real axis[3], tg_real angle, tg_error *err)
{
    tg_vec3 t, a;
    if (drivable(f, err) || index_arg(err, "object", "objects", object, f->scene->object_count) ||
        vec_arg(err, "translate", translate, &t) || dir_arg(err, "axis", axis, &a))
        return TG_ERR_INPUT;
    if (!tg_isfinite(angle)) return not_finite(err, "angle", angle);
    f->drive.object_set[object] = tgi_anim_key_matrix(t, a, angle);
    return TG_OK;
}

tg_status tg_frame_set_time(tg_frame *f, tg_real t, tg_error *err)
{
    tgi_error_clear(err);
    if (!f) return refuse(err, "frame is NULL", NULL);
    if (!tg_isfinite(t)) return not_finite(err, "time", t);
    f->drive.time = t;
    f->drive.set |= TGI_SET_TIME;
    return TG_OK;
}

/* The frame's own copy of light i (the scene's lights are never written). */
static tgi_light *own_light(tg_frame *f, int i)
{
    return (tgi_light *)(void *)&f->scene->lights[i];
}

tg_status tg_frame_set_light(tg_frame *f, int light, const tg_real color[3], tg_real intensity,
                             tg_error *err)
{
    tg_vec3 c;
    if (drivable(f, err) || index_arg(err, "light", "lights", light, f->scene->light_count) ||
        color_arg(err, "color", color, &c))
        return TG_ERR_INPUT;
    if (!(tg_isfinite(intensity) && intensity >= 0)) {
        refuse(err, "intensity must be 0 or more, got ", NULL);
        tgi_error_append_real(err, intensity);
        return TG_ERR_INPUT;
    }
    own_light(f, light)->color = c;
    own_light(f, light)->intensity = intensity;
    return TG_OK;
}

tg_status tg_frame_move_light(tg_frame *f, int light, const tg_real pos[3], const tg_real dir[3],
                              tg_error *err)
{
    tg_vec3 p, d;
    tgi_light *l;
    if (drivable(f, err) || index_arg(err, "light", "lights", light, f->scene->light_count)) return TG_ERR_INPUT;
    l = own_light(f, light);
    if (!pos && !dir) return refuse(err, "pos and dir are both NULL: nothing to move", NULL);
    if (pos && l->type == TG_LIGHT_DIRECTIONAL) return refuse(err, "a directional light has no pos", NULL);
    if (dir && l->type == TG_LIGHT_POINT) return refuse(err, "a point light has no dir", NULL);
    if ((pos && vec_arg(err, "pos", pos, &p)) || (dir && dir_arg(err, "dir", dir, &d))) return TG_ERR_INPUT;
    if (pos) l->pos = p;
    if (dir) l->dir = d;
    f->shadows_stale |= (uint64_t)1 << light;
    return TG_OK;
}

/* Install env as the frame's environment (and its SH9 projection). */
static tg_status set_env(tg_frame *f, const tgi_env *env, tg_error *err)
{
    tg_scene *own = (tg_scene *)(void *)f->scene;
    if (own->env.type == TG_ENV_NONE)
        return refuse(err, "the scene has no environment (no env line), so the plan has no far field", NULL);
    own->env = *env;
    if (f->effects & TG_EFFECT_FAR) tgi_sh9_from_env(&own->env, f->sh);
    return TG_OK;
}

tg_status tg_frame_set_env_uniform(tg_frame *f, const tg_real radiance[3], tg_error *err)
{
    tgi_env env;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM;
    if (drivable(f, err) || color_arg(err, "radiance", radiance, &env.uniform)) return TG_ERR_INPUT;
    return set_env(f, &env, err);
}

tg_status tg_frame_set_env_sky(tg_frame *f, const tg_real sky[3], const tg_real ground[3],
                               const tg_real up[3], tg_error *err)
{
    tgi_env env;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SKY;
    if (drivable(f, err) || color_arg(err, "sky", sky, &env.sky) || color_arg(err, "ground", ground, &env.ground) ||
        dir_arg(err, "up", up, &env.up))
        return TG_ERR_INPUT;
    return set_env(f, &env, err);
}

tg_status tg_frame_set_env_sh9(tg_frame *f, const tg_real coeffs[27], tg_error *err)
{
    tgi_env env;
    int i;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SH9;
    if (drivable(f, err)) return TG_ERR_INPUT;
    if (!coeffs) return refuse(err, "coeffs is NULL", NULL);
    for (i = 0; i < 9; i++)
        if (vec_arg(err, "coeffs", coeffs + 3 * i, &env.sh9[i])) return TG_ERR_INPUT;
    return set_env(f, &env, err);
}

tg_status tg_frame_cut(tg_frame *f)
{
    if (!f) return TG_ERR_INPUT;
    f->drive.cut = 1;
    return TG_OK;
}

int tg_frame_reprojected(const tg_frame *f)
{
    return f ? f->drive.reprojected : 0;
}
