/* SPDX-License-Identifier: MIT */
/*
 * scene_text.c - tg_scene_parse in a build without the scene-text parser
 * (TG_NO_SCENE_TEXT=1, tinygi.h "FEATURE SWITCHES"): parse.c, lex.c and
 * obj.c compile to nothing, and every text is refused, naming the switch.
 * Such a program renders a scene baked into C data on the host
 * (tools/scene_bake.c).
 */
#include "../tinygi.h"
#include "../core/error.h"

#if TG_NO_SCENE_TEXT
tg_status tg_scene_parse(const char *text, size_t size, const char *filename,
                         const tg_io *io, tg_arena *arena, tg_scene **scene,
                         tg_error *err)
{
    (void)text; (void)size; (void)io; (void)arena;
    if (scene) *scene = NULL;
    tgi_error_set(err, TG_ERR_INPUT, filename ? filename : "<scene>", 0, 0,
                  "scene text is left out of this build (TG_NO_SCENE_TEXT=1): "
                  "bake the scene into C data with tinygi-bake");
    return TG_ERR_INPUT;
}
#endif
