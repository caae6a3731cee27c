/* SPDX-License-Identifier: MIT */
/*
 * light_fixture.h - the light the light tests shine (test_light.c, and
 * test_shadow.c and test_pathtrace.c through raster_fixture.h).  Hosted
 * test code.
 */
#ifndef TG_LIGHT_FIXTURE_H
#define TG_LIGHT_FIXTURE_H

#include <string.h>
#include "light/direct.h"

/* A light with shadows, colour (1, 0.5, 0.25). */
static inline tgi_light make_light(tgi_light_type type, tg_vec3 pos, tg_vec3 dir, double intensity, double angle)
{
    tgi_light l;
    memset(&l, 0, sizeof l);
    l.type = type; l.pos = pos; l.dir = tgi_v3_normalize(dir);
    l.color = tg_v3(tg_from_float(1.0f), tg_from_float(0.5f), tg_from_float(0.25f));
    l.intensity = tg_from_float((float)intensity); l.angle = tg_from_float((float)angle); l.shadows = 1;
    return l;
}

#endif
