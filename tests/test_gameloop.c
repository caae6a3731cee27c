/* SPDX-License-Identifier: MIT */
/*
 * test_gameloop.c - driving frames from a program (tinygi.h "the game
 * loop"): the camera and an object set through the API give the very
 * frames, bit for bit, that the same path in scene keys gives (every AOV,
 * reprojection on); the program's camera and poses take precedence over the
 * keys; a teleport (detected) or a declared cut drops the history and
 * renders the first frame a fresh frame would, finite; a moved light
 * renders its shadow map again, a recoloured one does not; a changed light
 * or environment gives the frame a scene with that light or environment
 * gives; misuse is refused with TG_ERR_INPUT and changes nothing.
 */
#include "frame_fixture.h"
#include "frame/frame_internal.h"
#include "scene/anim.h"

#define W 40
#define H 30
#define FRAMES 5

/* A lit room (shadows, environment, near field) with a box named mover. */
static const char *room =
    "camera pos 0 1.2 -3.5 target 0 0.8 0 fov 55\n"
    "material wall albedo 0.7 0.7 0.7\n"
    "material red albedo 0.7 0.2 0.1\n"
    "material lamp albedo 0.5 0.5 0.5 emissive 4 4 4\n"
    "box min -2 0 -4 max 2 3 2 material wall inward\n"
    "box min -0.4 0 -0.4 max 0.4 0.8 0.4 material red name mover\n"
    "sphere center -1 0.5 0.8 radius 0.5 material wall segments 12 name ball\n"
    "quad p0 -0.5 2.99 -0.5  p1 0.5 2.99 -0.5  p2 0.5 2.99 0.5  p3 -0.5 2.99 0.5 material lamp\n"
    "env sky 0.3 0.4 0.6 ground 0.1 0.1 0.1\n"
    "gi radius 2 bounces 2\n";
static const char *room_light = "light point pos 0 2.5 0 color 1 0.9 0.8 intensity 5 shadows\n";

/* Camera keys (t = 2 and 3 fall between keys) and the mover's keys, one
 * at each frame's time (t = 0..4 over 5 frames). */
static const char *camera_keys =
    "camera_key t 0 pos 0 1.2 -3.5 target 0 0.8 0\n"
    "camera_key t 1 pos 0.3 1.25 -3.4 target 0 0.8 0\n"
    "camera_key t 4 pos 0.8 1.4 -3.2 target 0.1 0.7 0\n";
static const char *object_keys =
    "object_key name mover t 0\n"
    "object_key name mover t 1 translate 0.2 0 0 rotate 0 1 0 20\n"
    "object_key name mover t 2 translate 0.35 0.05 0 rotate 0 1 0 35\n"
    "object_key name mover t 3 translate 0.4 0.1 0.1 rotate 1 1 0 15\n"
    "object_key name mover t 4 translate 0.5 0.1 0.2 rotate 0 1 0 -10\n";
/* The same poses as numbers: translate, axis, angle in degrees. */
static const float mover_pose[FRAMES][7] = {
    { 0, 0, 0, 0, 1, 0, 0 },
    { 0.2f, 0, 0, 0, 1, 0, 20 },
    { 0.35f, 0.05f, 0, 0, 1, 0, 35 },
    { 0.4f, 0.1f, 0.1f, 1, 1, 0, 15 },
    { 0.5f, 0.1f, 0.2f, 0, 1, 0, -10 },
};

static char text_buf[4][4096];

/* The room with the given extra lines (a light, keys, ...), in buffer k. */
static const char *scene_with(int k, const char *a, const char *b, const char *c)
{
    snprintf(text_buf[k], sizeof text_buf[k], "%s%s%s%s", room, a ? a : "", b ? b : "", c ? c : "");
    return text_buf[k];
}

static tg_request loop_request(int frames, int game_loop)
{
    tg_request q = request(W, H, ALL_AOVS);
    q.frames = frames;
    q.game_loop = game_loop;
    /* one map size in every plan: the size rule sizes maps by the views
     * and lights a plan knows (a game loop's: every face whole) */
    q.shadow_map_size = 64;
    return q;
}

/* Every AOV of a and b, bit for bit. */
static int same_frames(const rendered *a, const rendered *b)
{
    size_t na, nb;
    unsigned char *x = raw_aovs(a, &na), *y = raw_aovs(b, &nb);
    int same = na == nb && memcmp(x, y, na) == 0;
    free(x);
    free(y);
    return same;
}

/* Render frame `index` of r and frame 0 of fresh (its camera set alike):
 * r starts afresh (it does not reproject) and renders what fresh renders. */
static void check_starts_afresh(const rendered *r, const rendered *fresh, int index, const char *what)
{
    tg_error err;
    tg_frame_render(r->frame, index, &err);
    tg_frame_render(fresh->frame, 0, &err);
    CHECK(!tg_frame_reprojected(r->frame), "%s: a first frame (no history)", what);
    CHECK(same_frames(r, fresh), "%s: a fresh first frame", what);
}

/* One AOV of a and b, bit for bit. */
static int same_aov(const rendered *a, const rendered *b, tg_aov aov)
{
    double *x = read_aov(a, aov), *y = read_aov(b, aov);
    int same = memcmp(x, y, sizeof(double) * (size_t)tg_aov_channels(aov) * W * H) == 0;
    free(x);
    free(y);
    return same;
}

static void put3(tg_real v[3], tg_vec3 p) { v[0] = p.x; v[1] = p.y; v[2] = p.z; }
static void put3f(tg_real v[3], float x, float y, float z) { v[0] = TG_R(x); v[1] = TG_R(y); v[2] = TG_R(z); }

/* The camera the keys give at frame i of FRAMES, set through the API. */
static tg_status set_key_camera(rendered *api, const tg_scene *keyed, int i, tg_error *err)
{
    tg_vec3 pos, target;
    tg_real p[3], t[3], up[3];
    tgi_anim_camera(keyed, tgi_anim_time(keyed, i, FRAMES), &pos, &target);
    put3(p, pos);
    put3(t, target);
    put3(up, keyed->camera.up);
    return tg_frame_set_camera(api->frame, p, t, up, keyed->camera.fov, err);
}

/* The mover's key pose of frame i, set through the API. */
static tg_status set_key_pose(rendered *api, int i, tg_error *err)
{
    tg_real tr[3], axis[3];
    const float *k = mover_pose[i];
    put3f(tr, k[0], k[1], k[2]);
    put3f(axis, k[3], k[4], k[5]);
    return tg_frame_set_object(api->frame, tg_scene_find_object(api->scene, "mover"), tr, axis,
                               tgi_deg_to_rad(TG_R(k[6])), err);
}

/* Keys (the CLI's path), keys in a game-loop plan, and the API driving a
 * scene without keys: the same frames, bit for bit, every AOV, with
 * reprojection from frame 1 on. */
TEST(api_gives_the_frames_of_the_keys)
{
    rendered keys, keys_loop, api;
    tg_request q = loop_request(FRAMES, 0), ql = loop_request(FRAMES, 1);
    tg_error err;
    int i, same = 0, same_loop = 0, reprojected = 0;
    CHECK(setup(&keys, scene_with(0, room_light, camera_keys, object_keys), &q), "keyed scene: %s", keys.msg);
    CHECK(setup(&keys_loop, scene_with(1, room_light, camera_keys, object_keys), &ql), "keyed, game loop: %s", keys_loop.msg);
    CHECK(setup(&api, scene_with(2, room_light, NULL, NULL), &ql), "scene without keys: %s", api.msg);
    if (keys.ok && keys_loop.ok && api.ok) {
        CHECK(keys.plan.effects & TG_EFFECT_REPROJECTION, "the keyed plan reprojects");
        CHECK(keys.plan.effects & TG_EFFECT_SHADOWS, "and has shadows");
        CHECK(keys.plan.total_bytes < keys_loop.plan.total_bytes, "the game loop keeps the program's state");
        for (i = 0; i < FRAMES; i++) {
            CHECK(set_key_camera(&api, keys.scene, i, &err) == TG_OK, "set camera: %s", err.message);
            CHECK(set_key_pose(&api, i, &err) == TG_OK, "set mover: %s", err.message);
            tg_frame_render(keys.frame, i, &err);
            tg_frame_render(keys_loop.frame, i, &err);
            tg_frame_render(api.frame, i, &err);
            same += same_frames(&keys, &api);
            same_loop += same_frames(&keys, &keys_loop);
            reprojected += tg_frame_reprojected(keys.frame) + tg_frame_reprojected(api.frame);
        }
        CHECK(same == FRAMES, "the API's frames are the keys' in %d of %d frames", same, FRAMES);
        CHECK(same_loop == FRAMES, "a game-loop plan follows the keys: %d of %d", same_loop, FRAMES);
        CHECK(reprojected == 2 * (FRAMES - 1), "frames 1.. reproject (%d)", reprojected);
    }
    teardown(&keys); teardown(&keys_loop); teardown(&api);
}

/* tg_frame_set_time samples the keys at t: a 2-frame plan driven by time
 * renders the frames of the 5-frame plan. */
TEST(set_time_samples_the_keys)
{
    rendered by_index, by_time;
    tg_request q5 = loop_request(FRAMES, 0), q2 = loop_request(2, 0);
    tg_error err;
    int i, same = 0;
    const char *text = scene_with(0, room_light, camera_keys, object_keys);
    CHECK(setup(&by_index, text, &q5) && setup(&by_time, text, &q2), "set up");
    if (by_index.ok && by_time.ok) {
        for (i = 0; i < FRAMES; i++) {
            CHECK(tg_frame_set_time(by_time.frame, tgi_anim_time(by_index.scene, i, FRAMES), &err) == TG_OK, "time");
            tg_frame_render(by_index.frame, i, &err);
            tg_frame_render(by_time.frame, i, &err);
            same += same_frames(&by_index, &by_time);
        }
        CHECK(same == FRAMES, "time-driven frames equal index-driven ones in %d of %d", same, FRAMES);
    }
    teardown(&by_index); teardown(&by_time);
}

/* Once the program sets the camera the camera keys no longer drive it,
 * while the objects it did not set follow their keys: a keyed scene whose
 * camera the program holds still renders the frames of a scene with that
 * fixed camera and the same object keys. */
TEST(program_camera_takes_precedence)
{
    rendered held, fixed;
    tg_request q = loop_request(FRAMES, 1);
    tg_error err;
    int i, same = 0;
    tg_real pos[3], target[3], up[3];
    CHECK(setup(&held, scene_with(0, room_light, camera_keys, object_keys), &q), "keyed");
    CHECK(setup(&fixed, scene_with(1, room_light, object_keys, NULL), &q), "fixed camera");
    if (held.ok && fixed.ok) {
        put3(pos, fixed.scene->camera.pos);
        put3(target, fixed.scene->camera.target);
        put3(up, fixed.scene->camera.up);
        for (i = 0; i < FRAMES; i++) {
            if (i == 1) CHECK(tg_frame_set_camera(held.frame, pos, target, up, fixed.scene->camera.fov, &err) == TG_OK,
                              "set camera: %s", err.message);
            tg_frame_render(held.frame, i, &err);
            tg_frame_render(fixed.frame, i, &err);
            if (i >= 1) same += same_frames(&held, &fixed);
        }
        CHECK(same == FRAMES - 1, "the program's camera holds over the keys in %d of %d frames", same, FRAMES - 1);
    }
    teardown(&held); teardown(&fixed);
}

static int all_finite(const rendered *r)
{
    int a, bad = 0;
    size_t i, n = (size_t)W * H;
    for (a = 0; a < TG_AOV_COUNT; a++) {
        double *v = read_aov(r, (tg_aov)a);
        for (i = 0; i < n * (size_t)tg_aov_channels((tg_aov)a); i++)
            if (!isfinite(v[i])) bad++;
        if (a == TG_AOV_AO)
            for (i = 0; i < n; i++)
                if (!(v[i] >= 0 && v[i] <= 1)) bad++;
        free(v);
    }
    return bad == 0;
}

/* A teleport (the camera jumps across the room) is a cut: the history is
 * dropped and the frame is the first frame a fresh frame renders there,
 * bit for bit, finite.  A declared cut does the same for a small move. */
TEST(teleport_and_declared_cut_drop_the_history)
{
    rendered r, fresh;
    tg_request q = loop_request(6, 1);
    tg_error err;
    tg_real up[3], pos[3], target[3];
    tg_real fov = tgi_deg_to_rad(TG_R(55.0f));
    int i;
    const char *text = scene_with(0, room_light, NULL, NULL);
    put3f(up, 0, 1, 0);
    CHECK(setup(&r, text, &q) && setup(&fresh, text, &q), "set up");
    if (!r.ok || !fresh.ok) { teardown(&r); teardown(&fresh); return; }
    for (i = 0; i < 3; i++) {   /* a slow dolly: reprojected */
        put3f(pos, 0.1f * (float)i, 1.2f, -3.5f);
        put3f(target, 0, 0.8f, 0);
        tg_frame_set_camera(r.frame, pos, target, up, fov, &err);
        tg_frame_render(r.frame, i, &err);
        if (i > 0) CHECK(tg_frame_reprojected(r.frame), "frame %d follows frame %d", i, i - 1);
    }
    /* teleport to the far corner, looking back */
    put3f(pos, 1.6f, 2.5f, 1.6f);
    put3f(target, -1, 0.5f, -2);
    CHECK(tg_frame_set_camera(r.frame, pos, target, up, fov, &err) == TG_OK, "teleport: %s", err.message);
    tg_frame_set_camera(fresh.frame, pos, target, up, fov, &err);
    check_starts_afresh(&r, &fresh, 3, "a teleport is a cut");
    CHECK(all_finite(&r), "the frame after the teleport is finite, AO in [0, 1]");
    /* a tiny move, declared a cut */
    pos[0] = tg_add(pos[0], TG_R(0.01f));
    tg_frame_set_camera(r.frame, pos, target, up, fov, &err);
    tg_frame_render(r.frame, 4, &err);
    CHECK(tg_frame_reprojected(r.frame), "a tiny move is not a cut");
    CHECK(tg_frame_cut(r.frame) == TG_OK, "cut");
    tg_frame_set_camera(fresh.frame, pos, target, up, fov, &err);
    check_starts_afresh(&r, &fresh, 5, "a declared cut drops the history");
    teardown(&r); teardown(&fresh);
}

/* Frame index 0 starts afresh: rendered again after a sequence, it is the
 * first frame of a fresh frame (it reprojected stale history before). */
TEST(index_zero_starts_afresh)
{
    rendered r, fresh;
    tg_request q = loop_request(FRAMES, 0);
    tg_error err;
    int i;
    const char *text = scene_with(0, room_light, camera_keys, object_keys);
    CHECK(setup(&r, text, &q) && setup(&fresh, text, &q), "set up");
    if (r.ok && fresh.ok) {
        for (i = 0; i < 3; i++) tg_frame_render(r.frame, i, &err);
        check_starts_afresh(&r, &fresh, 0, "index 0 again");
    }
    teardown(&r); teardown(&fresh);
}

/* The keys' jumps are cuts too (the same detection): a key that turns the
 * camera round, and one that moves it across the room. */
TEST(key_jumps_are_cuts)
{
    rendered r;
    tg_request q = loop_request(6, 0);
    tg_error err;
    int i, cuts = 0;
    const char *jumps =
        "camera_key t 0 pos 0 1.2 -3.5 target 0 0.8 0\n"
        "camera_key t 1 pos 0 1.2 -3.5 target 0 0.8 0\n"
        "camera_key t 2 pos 0 1.2 -3.5 target 0 0.8 -8\n"   /* turned round */
        "camera_key t 3 pos 0 1.2 -3.5 target 0 0.8 -8\n"
        "camera_key t 4 pos 1.5 2.5 1.5 target 1.5 2.5 -8\n" /* across the room */
        "camera_key t 5 pos 1.5 2.5 1.5 target 1.5 2.5 -8\n";
    CHECK(setup(&r, scene_with(0, room_light, jumps, NULL), &q), "set up");
    if (r.ok) {
        for (i = 0; i < 6; i++) {
            tg_frame_render(r.frame, i, &err);
            if (i > 0 && !tg_frame_reprojected(r.frame)) cuts |= 1 << i;
        }
        CHECK(cuts == ((1 << 2) | (1 << 4)), "cuts at frames 2 and 4 (mask %#x)", (unsigned)cuts);
    }
    teardown(&r);
}

/* The direct light of every frame is the direct light of a fresh frame of
 * the scene with the light as it is now: a moved light's shadow map is
 * fitted and rendered again, a recoloured one's is kept. */
TEST(changed_lights_render_their_shadow_maps)
{
    rendered r, moved, recoloured;
    tg_request q = loop_request(4, 1);
    tg_error err;
    tg_real pos[3], color[3];
    const char *moved_light = "light point pos 1.2 2.2 -0.5 color 1 0.9 0.8 intensity 5 shadows\n";
    const char *recoloured_light = "light point pos 1.2 2.2 -0.5 color 0.25 0.5 1 intensity 3 shadows\n";
    CHECK(setup(&r, scene_with(0, room_light, NULL, NULL), &q), "room");
    CHECK(setup(&moved, scene_with(1, moved_light, NULL, NULL), &q), "room, light moved");
    CHECK(setup(&recoloured, scene_with(2, recoloured_light, NULL, NULL), &q), "room, light recoloured");
    if (r.ok && moved.ok && recoloured.ok) {
        tg_frame_render(r.frame, 0, &err);
        tg_frame_render(r.frame, 1, &err);
        CHECK(r.frame->shadows_stale == 0, "a static scene keeps its maps");
        put3f(pos, 1.2f, 2.2f, -0.5f);
        CHECK(tg_frame_move_light(r.frame, 0, pos, NULL, &err) == TG_OK, "move: %s", err.message);
        CHECK(r.frame->shadows_stale == 1, "the moved light's map is stale");
        tg_frame_render(r.frame, 2, &err);
        tg_frame_render(moved.frame, 0, &err);
        CHECK(same_aov(&r, &moved, TG_AOV_DIRECT), "direct light of the moved light, shadows included");
        put3f(color, 0.25f, 0.5f, 1);
        CHECK(tg_frame_set_light(r.frame, 0, color, TG_R(3.0f), &err) == TG_OK, "recolour: %s", err.message);
        CHECK(r.frame->shadows_stale == 0, "a recoloured light's map is kept");
        tg_frame_render(r.frame, 3, &err);
        tg_frame_render(recoloured.frame, 0, &err);
        CHECK(same_aov(&r, &recoloured, TG_AOV_DIRECT), "direct light of the recoloured light");
        CHECK(r.scene->lights[0].pos.y == TG_R(2.5f) && r.scene->lights[0].intensity == TG_R(5.0f),
              "the parsed scene's light is never written");
    }
    teardown(&r); teardown(&moved); teardown(&recoloured);
}

/* A directional light turned through the API lights as the scene would. */
TEST(turned_directional_light)
{
    rendered r, turned;
    tg_request q = loop_request(2, 1);
    tg_error err;
    tg_real dir[3];
    CHECK(setup(&r, scene_with(0, "light directional dir 0.3 -1 0.2 color 1 1 1 shadows\n", NULL, NULL), &q), "room");
    CHECK(setup(&turned, scene_with(1, "light directional dir -0.5 -1 0.4 color 1 1 1 shadows\n", NULL, NULL), &q), "turned");
    if (r.ok && turned.ok) {
        tg_frame_render(r.frame, 0, &err);
        put3f(dir, -0.5f, -1, 0.4f);
        CHECK(tg_frame_move_light(r.frame, 0, NULL, dir, &err) == TG_OK, "turn: %s", err.message);
        tg_frame_render(r.frame, 1, &err);
        tg_frame_render(turned.frame, 0, &err);
        CHECK(same_aov(&r, &turned, TG_AOV_DIRECT), "direct light of the turned light");
    }
    teardown(&r); teardown(&turned);
}

/* Each environment the API sets gives the far field a scene with that
 * `env` line gives. */
TEST(environment_changes)
{
    static const char *envs[3] = {
        "env uniform 0.5 0.25 0.125\n",
        "env sky 1 0.5 0.25 ground 0.125 0.25 0.5 up 0 1 1\n",
        "env sh9 1 1 1 0.5 0.25 0 0 0.5 0 0.25 0 0 0 0 0 0.125 0 0 0 0.125 0 0 0 0 0 0 0.0625\n" };
    static const float sh9[27] = { 1, 1, 1, 0.5f, 0.25f, 0, 0, 0.5f, 0, 0.25f, 0, 0, 0, 0, 0,
                                   0.125f, 0, 0, 0, 0.125f, 0, 0, 0, 0, 0, 0, 0.0625f };
    rendered r;
    tg_request q = loop_request(2, 1);
    tg_error err;
    int k, i;
    char room_env[2048];
    /* the room without its own env line, each env in turn */
    const char *cut = strstr(room, "env sky");
    snprintf(room_env, sizeof room_env, "%.*s", (int)(cut - room), room);
    CHECK(setup(&r, scene_with(0, room_light, NULL, NULL), &q), "room");
    for (k = 0; k < 3 && r.ok; k++) {
        rendered want;
        tg_real a[3], b[3], c[3], coeffs[27];
        tg_status s;
        snprintf(text_buf[1], sizeof text_buf[1], "%s%s%sgi radius 2 bounces 2\n", room_env, room_light, envs[k]);
        if (!setup(&want, text_buf[1], &q)) { CHECK(0, "env %d: %s", k, want.msg); continue; }
        if (k == 0) { put3f(a, 0.5f, 0.25f, 0.125f); s = tg_frame_set_env_uniform(r.frame, a, &err); }
        else if (k == 1) {
            put3f(a, 1, 0.5f, 0.25f); put3f(b, 0.125f, 0.25f, 0.5f); put3f(c, 0, 1, 1);
            s = tg_frame_set_env_sky(r.frame, a, b, c, &err);
        } else {
            for (i = 0; i < 27; i++) coeffs[i] = TG_R(sh9[i]);
            s = tg_frame_set_env_sh9(r.frame, coeffs, &err);
        }
        CHECK(s == TG_OK, "env %d: %s", k, err.message);
        tg_frame_cut(r.frame); /* compare first frames: the far field alone */
        tg_frame_render(r.frame, 1, &err);
        tg_frame_render(want.frame, 0, &err);
        CHECK(same_aov(&r, &want, TG_AOV_FAR), "env %d: the far field of the scene's env", k);
        teardown(&want);
    }
    teardown(&r);
}

/* Depth of frame `index` of `text` (W x H doubles, malloc'd), or NULL. */
static double *depth_of(const char *text, int frames, int index)
{
    rendered r;
    tg_request q = request(W, H, AOVBIT(TG_AOV_DEPTH));
    tg_error err;
    double *d = NULL;
    int i;
    q.frames = frames;
    if (setup(&r, text, &q)) {
        for (i = 0; i <= index; i++) tg_frame_render(r.frame, i, &err);
        d = read_aov(&r, TG_AOV_DEPTH);
    }
    teardown(&r);
    return d;
}

/* Objects stand at their keys' pose whatever the frame count: one frame of
 * a moving object, and an object with a single key (it showed the rest
 * pose in both cases), match the object built where the key puts it. */
TEST(objects_stand_at_their_key_pose)
{
    const char *keys[2] = { "object_key name mover t 0 translate 1 0 0.5\n"
                            "object_key name mover t 1 translate 2 0 0\n",
                            "object_key name mover t 0 translate 1 0 0.5\n" };
    int frames[2] = { 1, 2 }, k, i;
    char placed[2048];
    const char *box = strstr(room, "box min -0.4");
    const char *after = strchr(box, '\n') + 1;
    double *want;
    snprintf(placed, sizeof placed, "%.*sbox min 0.6 0 0.1 max 1.4 0.8 0.9 material red name mover\n%s%s",
             (int)(box - room), room, after, room_light);
    want = depth_of(placed, 1, 0);
    CHECK(want != NULL, "the placed scene renders");
    for (k = 0; k < 2 && want; k++) {
        double *got = depth_of(scene_with(0, room_light, keys[k], NULL), frames[k], frames[k] - 1), worst = 0;
        CHECK(got != NULL, "case %d renders", k);
        if (!got) continue;
        for (i = 0; i < W * H; i++) worst = fmax(worst, fabs(got[i] - want[i]));
        CHECK(worst < 2e-3, "case %d: the object at its key pose (depth off by %g)", k, worst);
        free(got);
    }
    free(want);
}

#define REFUSED(call, words)                                                            \
    do {                                                                                \
        tg_status s_ = (call);                                                          \
        CHECK(s_ == TG_ERR_INPUT && strstr(err.message, words), "%s: status %d, \"%s\"", \
              #call, (int)s_, err.message);                                             \
    } while (0)

/* NULLs, indices out of range, values outside their domain (NaN in the
 * float build), a frame planned without game_loop, an env on a scene with
 * none: TG_ERR_INPUT with a message, and the frame renders as if the call
 * had not been made. */
TEST(misuse_is_refused)
{
    rendered r, plain, reference;
    tg_request q = loop_request(2, 1), qp = loop_request(2, 0);
    tg_error err;
    tg_real v[3], up[3], zero[3], neg[3], sh[27];
    tg_real nan_ = tg_from_float(NAN);
    int mover;
    memset(sh, 0, sizeof sh);
    put3f(v, 0, 1, -3); put3f(up, 0, 1, 0); put3f(zero, 0, 0, 0); put3f(neg, 1, -1, 1);
    CHECK(setup(&r, scene_with(0, room_light, NULL, NULL), &q), "room");
    CHECK(setup(&plain, scene_with(1, room_light, NULL, NULL), &qp), "room, no game loop");
    CHECK(setup(&reference, scene_with(2, room_light, NULL, NULL), &q), "reference");
    if (!r.ok || !plain.ok || !reference.ok) { teardown(&r); teardown(&plain); teardown(&reference); return; }
    mover = tg_scene_find_object(r.scene, "mover");
    CHECK(mover >= 0 && tg_scene_find_object(r.scene, "ball") >= 0 && mover != tg_scene_find_object(r.scene, "ball"),
          "named objects are found");
    CHECK(tg_scene_find_object(r.scene, "nobody") == -1 && tg_scene_find_object(r.scene, "") == -1 &&
          tg_scene_find_object(r.scene, NULL) == -1 && tg_scene_find_object(NULL, "mover") == -1, "unknown: -1");
    CHECK(tg_scene_light_count(r.scene) == 1 && tg_scene_light_count(NULL) == 0, "light count");

    REFUSED(tg_frame_set_camera(NULL, v, zero, up, TG_ONE, &err), "frame is NULL");
    REFUSED(tg_frame_set_camera(r.frame, NULL, zero, up, TG_ONE, &err), "pos is NULL");
    REFUSED(tg_frame_set_camera(r.frame, v, zero, zero, TG_ONE, &err), "up must be a direction");
    REFUSED(tg_frame_set_camera(r.frame, v, v, up, TG_ONE, &err), "target must differ from pos");
    REFUSED(tg_frame_set_camera(r.frame, v, zero, up, 0, &err), "fov must be between 0 and pi");
    REFUSED(tg_frame_set_camera(r.frame, v, zero, up, TG_R(3.2f), &err), "fov must be between 0 and pi");
    REFUSED(tg_frame_set_camera(plain.frame, v, zero, up, TG_ONE, &err), "request.game_loop");
    REFUSED(tg_frame_set_object(r.frame, -1, v, up, 0, &err), "object must be 0..3, got -1");
    REFUSED(tg_frame_set_object(r.frame, 4, v, up, 0, &err), "object must be 0..3, got 4");
    REFUSED(tg_frame_set_object(r.frame, mover, v, zero, 0, &err), "axis must be a direction");
    REFUSED(tg_frame_set_object(r.frame, mover, NULL, up, 0, &err), "translate is NULL");
    REFUSED(tg_frame_set_light(r.frame, 1, v, TG_ONE, &err), "light must be 0..0, got 1");
    REFUSED(tg_frame_set_light(r.frame, 0, neg, TG_ONE, &err), "color must be 0 or more");
    REFUSED(tg_frame_set_light(r.frame, 0, up, TG_R(-1.0f), &err), "intensity must be 0 or more");
    REFUSED(tg_frame_move_light(r.frame, 0, NULL, NULL, &err), "nothing to move");
    REFUSED(tg_frame_move_light(r.frame, 0, NULL, up, &err), "a point light has no dir");
    REFUSED(tg_frame_set_env_uniform(r.frame, neg, &err), "radiance must be 0 or more");
    REFUSED(tg_frame_set_env_sh9(r.frame, NULL, &err), "coeffs is NULL");
    REFUSED(tg_frame_set_time(NULL, 0, &err), "frame is NULL");
    CHECK(tg_frame_cut(NULL) == TG_ERR_INPUT, "cut of NULL");
    CHECK(tg_frame_reprojected(NULL) == 0, "reprojected of NULL");
#if !TG_FIXED
    v[1] = nan_;
    REFUSED(tg_frame_set_camera(r.frame, v, zero, up, TG_ONE, &err), "pos must be finite, got nan");
    v[1] = TG_ONE;
    REFUSED(tg_frame_set_camera(r.frame, v, zero, up, nan_, &err), "fov must be between 0 and pi");
    REFUSED(tg_frame_set_object(r.frame, mover, v, up, nan_, &err), "angle must be finite");
    REFUSED(tg_frame_set_time(r.frame, nan_, &err), "time must be finite");
    REFUSED(tg_frame_set_light(r.frame, 0, up, nan_, &err), "intensity must be 0 or more");
    sh[13] = nan_;
    REFUSED(tg_frame_set_env_sh9(r.frame, sh, &err), "coeffs must be finite");
#else
    (void)nan_;
#endif
    {   /* a scene without env, objects or lights */
        rendered bare;
        CHECK(setup(&bare, "camera pos 0 1 -3 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\n"
                           "quad p0 -1 0 -1 p1 -1 0 1 p2 1 0 1 p3 1 0 -1 material m\n", &q), "bare");
        if (bare.ok) {
            REFUSED(tg_frame_set_env_uniform(bare.frame, up, &err), "no environment");
            REFUSED(tg_frame_set_light(bare.frame, 0, up, TG_ONE, &err), "the scene has no lights");
            REFUSED(tg_frame_set_object(bare.frame, 1, v, up, 0, &err), "object must be 0..0, got 1");
        }
        teardown(&bare);
    }
    {   /* game_loop is a switch */
        rendered bad;
        tg_request qb = loop_request(2, 2);
        CHECK(!setup(&bad, room, &qb) && strstr(bad.msg, "game_loop must be 0..1, got 2"), "game_loop 2: %s", bad.msg);
        teardown(&bad);
    }
    tg_frame_render(r.frame, 0, &err);
    tg_frame_render(reference.frame, 0, &err);
    CHECK(same_frames(&r, &reference), "refused calls change nothing");
    teardown(&r); teardown(&plain); teardown(&reference);
}

int main(void)
{
    RUN(api_gives_the_frames_of_the_keys);
    RUN(set_time_samples_the_keys);
    RUN(program_camera_takes_precedence);
    RUN(teleport_and_declared_cut_drop_the_history);
    RUN(index_zero_starts_afresh);
    RUN(key_jumps_are_cuts);
    RUN(changed_lights_render_their_shadow_maps);
    RUN(turned_directional_light);
    RUN(environment_changes);
    RUN(objects_stand_at_their_key_pose);
    RUN(misuse_is_refused);
    return check_summary();
}
