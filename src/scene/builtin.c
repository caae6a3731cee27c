/* SPDX-License-Identifier: MIT */
/*
 * builtin.c - the built-in scenes, as scene-format v1 text (format.md)
 * compiled into the core and named builtin:NAME by the CLI.  Each one has a
 * camera that frames it at 4:3; triangle counts stay small (< 5k).
 */
#include <string.h>
#include "../tinygi.h"

#if !TG_NO_BUILTIN_SCENES /* the scenes' text is left out with TG_NO_BUILTIN_SCENES=1 */
static const char scene_plane[] =
    "# A large floor seen at an angle under a sky.\n"
    "camera pos 0 3 12  target 0 0 0  fov 60\n"
    "material floor albedo 0.6 0.6 0.6  f0 0.04\n"
    "quad p0 -20 0 -20  p1 -20 0 20  p2 20 0 20  p3 20 0 -20  material floor name floor\n"
    "light directional dir -0.3 -1 -0.5  color 1 0.95 0.85  intensity 2.5\n"
    "env sky 0.45 0.6 0.9  ground 0.25 0.22 0.2\n";

static const char scene_groove[] =
    "# Two large planes meeting at 90 degrees: the crease darkens in AO and GI.\n"
    "camera pos 5 4 9  target 0 1 0  fov 60\n"
    "material floor albedo 0.7 0.7 0.7  f0 0.04\n"
    "material wall  albedo 0.7 0.55 0.4  f0 0.04\n"
    "quad p0 -10 0 0  p1 -10 0 10  p2 10 0 10  p3 10 0 0  material floor name floor\n"
    "quad p0 -10 0 0  p1 10 0 0  p2 10 10 0  p3 -10 10 0  material wall name wall\n"
    "light directional dir -0.4 -1 -0.6  color 1 0.95 0.85  intensity 2.5  shadows\n"
    "env sky 0.45 0.6 0.9  ground 0.25 0.22 0.2\n";

static const char scene_cornell[] =
    "# The Cornell box (after the Cornell University data, in metres/100):\n"
    "# red wall on the left, green on the right, open toward the camera.\n"
    "camera pos 2.78 2.73 -8  target 2.78 2.73 0  fov 38\n"
    "material white albedo 0.73 0.73 0.73  f0 0.04\n"
    "material red   albedo 0.63 0.065 0.05 f0 0.04\n"
    "material green albedo 0.14 0.45 0.091 f0 0.04\n"
    "material lamp  albedo 0.78 0.78 0.78  emissive 4 3.2 2.4\n"
    "quad p0 0 0 0  p1 0 0 5.592  p2 5.56 0 5.592  p3 5.56 0 0  material white name floor\n"
    "quad p0 0 5.488 0  p1 5.56 5.488 0  p2 5.56 5.488 5.592  p3 0 5.488 5.592  material white name ceiling\n"
    "quad p0 0 0 5.592  p1 0 5.488 5.592  p2 5.56 5.488 5.592  p3 5.56 0 5.592  material white name back_wall\n"
    "quad p0 5.56 0 0  p1 5.56 0 5.592  p2 5.56 5.488 5.592  p3 5.56 5.488 0  material red name left_wall\n"
    "quad p0 0 0 5.592  p1 0 0 0  p2 0 5.488 0  p3 0 5.488 5.592  material green name right_wall\n"
    "quad p0 2.13 5.478 2.27  p1 3.43 5.478 2.27  p2 3.43 5.478 3.32  p3 2.13 5.478 3.32  material lamp name ceiling_light\n"
    "quad p0 1.3 1.65 0.65  p1 0.82 1.65 2.25  p2 2.4 1.65 2.72  p3 2.9 1.65 1.14  material white name short_block\n"
    "quad p0 1.3 0 0.65  p1 0.82 0 2.25  p2 0.82 1.65 2.25  p3 1.3 1.65 0.65  material white\n"
    "quad p0 0.82 0 2.25  p1 2.4 0 2.72  p2 2.4 1.65 2.72  p3 0.82 1.65 2.25  material white\n"
    "quad p0 2.4 0 2.72  p1 2.9 0 1.14  p2 2.9 1.65 1.14  p3 2.4 1.65 2.72  material white\n"
    "quad p0 2.9 0 1.14  p1 1.3 0 0.65  p2 1.3 1.65 0.65  p3 2.9 1.65 1.14  material white\n"
    "quad p0 4.23 3.3 2.47  p1 2.65 3.3 2.96  p2 3.14 3.3 4.56  p3 4.72 3.3 4.06  material white name tall_block\n"
    "quad p0 4.23 0 2.47  p1 2.65 0 2.96  p2 2.65 3.3 2.96  p3 4.23 3.3 2.47  material white\n"
    "quad p0 2.65 0 2.96  p1 3.14 0 4.56  p2 3.14 3.3 4.56  p3 2.65 3.3 2.96  material white\n"
    "quad p0 3.14 0 4.56  p1 4.72 0 4.06  p2 4.72 3.3 4.06  p3 3.14 3.3 4.56  material white\n"
    "quad p0 4.72 0 4.06  p1 4.23 0 2.47  p2 4.23 3.3 2.47  p3 4.72 3.3 4.06  material white\n"
    "light point pos 2.78 5.3 2.795  color 1 0.85 0.65  intensity 18  shadows\n";

static const char scene_spheres[] =
    "# Spheres resting on a floor under the sun and a sky.\n"
    "camera pos 0 2.6 8  target 0 0.8 0  fov 45\n"
    "material floor  albedo 0.6 0.6 0.6   f0 0.04\n"
    "material white  albedo 0.8 0.8 0.8   f0 0.04\n"
    "material red    albedo 0.75 0.12 0.1 f0 0.04\n"
    "material blue   albedo 0.12 0.25 0.7 f0 0.04\n"
    "material yellow albedo 0.8 0.65 0.1  f0 0.04\n"
    "quad p0 -10 0 -10  p1 -10 0 10  p2 10 0 10  p3 10 0 -10  material floor name floor\n"
    "sphere center -2.2 1 0      radius 1    material white  name sphere_white\n"
    "sphere center 0.3 0.7 1.3   radius 0.7  material red    name sphere_red\n"
    "sphere center 2.4 1.2 -0.8  radius 1.2  material blue   name sphere_blue\n"
    "sphere center -0.7 0.4 2.6  radius 0.4  material yellow name sphere_yellow\n"
    "sphere center 1.5 0.3 3     radius 0.3  material white  segments 16\n"
    "light directional dir -0.5 -1 -0.4  color 1 0.95 0.85  intensity 2.5  shadows\n"
    "env sky 0.45 0.6 0.9  ground 0.25 0.22 0.2\n";

static const char scene_columns[] =
    "# A colonnade: a row of columns with stepped arches under a beam, a wall\n"
    "# behind, over a floor (the kind of scene the HBIL paper shows).\n"
    "camera pos -6 3 10  target 1 2 -1  fov 55\n"
    "material floor  albedo 0.55 0.5 0.45 f0 0.04\n"
    "material stone  albedo 0.75 0.7 0.62 f0 0.04\n"
    "material wall   albedo 0.6 0.3 0.2   f0 0.04\n"
    "quad p0 -24 0 -6  p1 -24 0 14  p2 24 0 14  p3 24 0 -6  material floor name floor\n"
    "box min -20 0 -4.4  max 20 6 -4  material wall  name back_wall\n"
    "box min -10.8 4 -0.5  max 10.8 4.6 0.5  material stone  name beam\n"
    "box min -10.8 0 -0.3  max -10.2 4 0.3  material stone  name column0\n"
    "box min -7.8 0 -0.3  max -7.2 4 0.3  material stone  name column1\n"
    "box min -4.8 0 -0.3  max -4.2 4 0.3  material stone  name column2\n"
    "box min -1.8 0 -0.3  max -1.2 4 0.3  material stone  name column3\n"
    "box min 1.2 0 -0.3  max 1.8 4 0.3  material stone  name column4\n"
    "box min 4.2 0 -0.3  max 4.8 4 0.3  material stone  name column5\n"
    "box min 7.2 0 -0.3  max 7.8 4 0.3  material stone  name column6\n"
    "box min 10.2 0 -0.3  max 10.8 4 0.3  material stone  name column7\n"
    "box min -10.2 3.5 -0.3  max -9.7 4 0.3  material stone\n"
    "box min -8.3 3.5 -0.3  max -7.8 4 0.3  material stone\n"
    "box min -7.2 3.5 -0.3  max -6.7 4 0.3  material stone\n"
    "box min -5.3 3.5 -0.3  max -4.8 4 0.3  material stone\n"
    "box min -4.2 3.5 -0.3  max -3.7 4 0.3  material stone\n"
    "box min -2.3 3.5 -0.3  max -1.8 4 0.3  material stone\n"
    "box min -1.2 3.5 -0.3  max -0.7 4 0.3  material stone\n"
    "box min 0.7 3.5 -0.3  max 1.2 4 0.3  material stone\n"
    "box min 1.8 3.5 -0.3  max 2.3 4 0.3  material stone\n"
    "box min 3.7 3.5 -0.3  max 4.2 4 0.3  material stone\n"
    "box min 4.8 3.5 -0.3  max 5.3 4 0.3  material stone\n"
    "box min 6.7 3.5 -0.3  max 7.2 4 0.3  material stone\n"
    "box min 7.8 3.5 -0.3  max 8.3 4 0.3  material stone\n"
    "box min 9.7 3.5 -0.3  max 10.2 4 0.3  material stone\n"
    "light directional dir -0.6 -0.8 -0.5  color 1 0.93 0.8  intensity 3  shadows\n"
    "env sky 0.45 0.6 0.9  ground 0.3 0.27 0.22\n"
    "gi radius 1.5\n";

static const struct { const char *name, *text; } builtins[] = {
    {"plane", scene_plane},
    {"groove", scene_groove},
    {"cornell", scene_cornell},
    {"spheres", scene_spheres},
    {"columns", scene_columns},
};

#define BUILTIN_COUNT ((int)(sizeof builtins / sizeof builtins[0]))

const char *tg_builtin_scene(const char *name)
{
    int i;
    if (!name) return NULL;
    if (strncmp(name, "builtin:", 8) == 0) name += 8;
    for (i = 0; i < BUILTIN_COUNT; i++)
        if (strcmp(name, builtins[i].name) == 0) return builtins[i].text;
    return NULL;
}

const char *tg_builtin_name(int i)
{
    return i >= 0 && i < BUILTIN_COUNT ? builtins[i].name : NULL;
}

#else /* TG_NO_BUILTIN_SCENES: no scene has a name */

const char *tg_builtin_scene(const char *name)
{
    (void)name;
    return NULL;
}

const char *tg_builtin_name(int i)
{
    (void)i;
    return NULL;
}

#endif
