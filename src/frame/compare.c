/* SPDX-License-Identifier: MIT */
/*
 * compare.c - the papers' other screen-space techniques, run at full
 * resolution from the G-buffer so the bench can set them beside HBIL and the
 * ray-traced reference (issue 5).  The request's knobs map onto each:
 *   slices  -> GTAO slices, HBAO directions (2 per slice: a slice has two sides)
 *   samples -> GTAO/HBAO steps per direction, SSAO/VO/SSDO/bent-cone samples
 *   radius  -> every technique's world-space radius
 * Everything else is the technique's documented default.  SSDO and bent
 * cones compute their own environment term (returns 1: far field done).
 */
#include "technique.h"
#include "../ao/sampling.h"
#include "../ao/ssao.h"
#include "../ao/vo.h"
#include "../ao/hbao.h"
#include "../ao/gtao.h"
#include "../ao/ssdo.h"
#include "../ao/bentcone.h"

static int clamp_samples(int n)
{
    return n < 1 ? 1 : n > TG_AO_MAX_SAMPLES ? TG_AO_MAX_SAMPLES : n;
}

int tgi_frame_technique_other(tg_frame *f, tgi_ao_io io)
{
    const tg_request *r = &f->plan.request;
    const tg_vec3 *sh = (f->effects & TG_EFFECT_FAR) ? f->sh : NULL;
    switch (r->technique) {
    case TG_TECH_SSAO: {
        tgi_ssao_params p;
        tgi_ssao_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        tgi_ssao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_VO: {
        tgi_vo_params p;
        tgi_vo_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        tgi_vo_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_HBAO: {
        tgi_hbao_params p;
        tgi_hbao_defaults(&p);
        p.directions = clamp_samples(2 * r->slices);
        p.steps = clamp_samples(r->samples);
        p.radius = r->radius;
        tgi_hbao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_GTAO: {
        tgi_gtao_params p;
        tgi_gtao_defaults(&p);
        p.slices = clamp_samples(r->slices);
        p.steps = clamp_samples(r->samples);
        p.radius = r->radius;
        tgi_gtao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_SSDO: {
        tgi_ssdo_params p;
        tgi_ssdo_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        p.env_sh9 = sh;
        if (sh) { p.far_r = f->far.r; p.far_g = f->far.g; p.far_b = f->far.b; }
        tgi_ssdo_rows(&p, &io, 0, f->height);
        return sh != NULL;
    }
    case TG_TECH_BENTCONE: {
        tgi_bentcone_params p;
        tgi_bentcone_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        p.env_sh9 = sh;
        if (sh) { p.far_r = f->far.r; p.far_g = f->far.g; p.far_b = f->far.b; }
        tgi_bentcone_rows(&p, &io, 0, f->height);
        return sh != NULL;
    }
    default:
        return 0;
    }
}
