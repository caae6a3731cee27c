/* SPDX-License-Identifier: MIT */
/*
 * test_techniques.c - every technique through the public API, on exact
 * cases:
 *   - the far field is consistent with the AO it uses: under a uniform sky
 *     L, with no light and no emitter, every pixel's colour is
 *     Lo = albedo / pi (1 - F0) pi L AO exactly (the AO AOV's own value,
 *     within its 8-bit and RGB9E5 storage), for any AO, in both far-field
 *     modes, for every technique whose far field is read from its AO;
 *   - the cone AOV is the cone whose cosine-weighted AO is the AO:
 *     cos(cone) = sqrt(1 - AO) (src/light/sh.h), not HBIL eq. 12's 1 - AO.
 */
#include <math.h>
#include "frame_fixture.h"

#define PI 3.14159265358979

/* A floor, a wall and a box on the floor: AO from 0 to 1.  No light, no
 * emitter: the sky is the only light. */
static const char *groove_under_uniform_sky =
    "camera pos 3 2.5 5  target 0 0.6 0  fov 60\n"
    "material m albedo 0.6 0.5 0.4 f0 0.04\n"
    "quad p0 -6 0 -1  p1 -6 0 6  p2 6 0 6  p3 6 0 -1  material m\n"
    "quad p0 -6 0 -1  p1 6 0 -1  p2 6 5 -1  p3 -6 5 -1  material m\n"
    "box min -0.5 0 0 max 0.5 0.8 1 material m\n"
    "env uniform 0.8 1.0 1.3\n"
    "gi radius 2\n";

/* The far field reads these techniques' AO (SSDO and bent cones integrate
 * their own). */
static const tg_technique far_from_ao[] = {
    TG_TECH_HBIL, TG_TECH_GTAO, TG_TECH_HBAO, TG_TECH_SSAO, TG_TECH_VO, TG_TECH_REFERENCE
};

static void uniform_sky_case(tg_technique t, int far_mode, int quarter)
{
    static const double L[3] = { 0.8, 1.0, 1.3 }, albedo[3] = { 0.6, 0.5, 0.4 }, f0 = 0.04;
    tg_request q = request(48, 36, AOVBIT(TG_AOV_COLOR) | AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_CONE) | AOVBIT(TG_AOV_DEPTH));
    rendered r;
    double *color, *ao, *cone, *depth, worst = 0, worst_cone = 0, ao_min = 1;
    int i, c, n = 48 * 36, bad = 0;
    q.technique = t;
    q.far_mode = far_mode;
    q.gi_scale = quarter ? 2 : 1;
    q.samples = 8;
    if (!setup(&r, groove_under_uniform_sky, &q)) {
        CHECK(0, "%s sets up: %s", tg_technique_name(t), r.msg);
        return;
    }
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders");
    color = read_aov(&r, TG_AOV_COLOR);
    ao = read_aov(&r, TG_AOV_AO);
    cone = read_aov(&r, TG_AOV_CONE);
    depth = read_aov(&r, TG_AOV_DEPTH);
    for (i = 0; i < n; i++) {
        double A = ao[i], dc = fabs(cone[i] - acos(sqrt(1 - A)));
        if (depth[i] == 0) continue;   /* sky: the environment itself */
        if (A < ao_min) ao_min = A;
        if (dc > worst_cone) worst_cone = dc;
        for (c = 0; c < 3; c++) {
            /* the AOV's AO is 8 bits of the value compose used (1/510), colour is RGB9E5 (2^-9) */
            double want = albedo[c] * (1 - f0) * L[c] * A, got = color[3 * i + c];
            double tol = albedo[c] * (1 - f0) * L[c] / 500 + want / 256 + (TG_FIXED ? 2e-3 : 1e-5);
            if (fabs(got - want) > worst) worst = fabs(got - want);
            if (fabs(got - want) > tol && bad++ < 3)
                CHECK(0, "%s far mode %d pixel %d ch %d: Lo %g, albedo (1 - F0) L AO = %g (AO %g)",
                      tg_technique_name(t), far_mode, i, c, got, want, A);
        }
    }
    printf("# %s%s, far mode %d: AO down to %.2f, largest |Lo - a (1-F0) L AO| %.2g, |cone - acos sqrt(1-AO)| %.2g\n",
           tg_technique_name(t), quarter ? " (quarter)" : "", far_mode, ao_min, worst, worst_cone);
    CHECK(bad == 0, "%s far mode %d: %d channels off", tg_technique_name(t), far_mode, bad);
    CHECK(ao_min < 0.7, "%s: the scene has occluded pixels (AO down to %g)", tg_technique_name(t), ao_min);
    CHECK(worst_cone < (TG_FIXED ? 2e-3 : 1e-4), "%s: cone = acos(sqrt(1 - AO)) within %g", tg_technique_name(t),
          worst_cone);
    free(color); free(ao); free(cone); free(depth);
    teardown(&r);
}

TEST(uniform_sky_gives_albedo_times_ao_for_every_technique)
{
    size_t k;
    for (k = 0; k < sizeof far_from_ao / sizeof far_from_ao[0]; k++) {
        uniform_sky_case(far_from_ao[k], 0, 0);
        uniform_sky_case(far_from_ao[k], 1, 0);
    }
    uniform_sky_case(TG_TECH_HBIL, 0, 1);
}

int main(void)
{
    RUN(uniform_sky_gives_albedo_times_ao_for_every_technique);
    return check_summary();
}
