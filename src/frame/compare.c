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

int tg_frame_technique_other(tg_frame *f, tg_ao_io io)
{
    const tg_request *r = &f->plan.request;
    const tg_vec3 *sh = (f->effects & TG_EFFECT_FAR) ? f->sh : NULL;
    switch (r->technique) {
    case TG_TECH_SSAO: {
        tg_ssao_params p;
        tg_ssao_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        tg_ssao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_VO: {
        tg_vo_params p;
        tg_vo_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        tg_vo_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_HBAO: {
        tg_hbao_params p;
        tg_hbao_defaults(&p);
        p.directions = clamp_samples(2 * r->slices);
        p.steps = clamp_samples(r->samples);
        p.radius = r->radius;
        tg_hbao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_GTAO: {
        tg_gtao_params p;
        tg_gtao_defaults(&p);
        p.slices = clamp_samples(r->slices);
        p.steps = clamp_samples(r->samples);
        p.radius = r->radius;
        tg_gtao_rows(&p, &io, 0, f->height);
        return 0;
    }
    case TG_TECH_SSDO: {
        tg_ssdo_params p;
        tg_ssdo_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        p.env_sh9 = sh;
        if (sh) { p.far_r = f->far.r; p.far_g = f->far.g; p.far_b = f->far.b; }
        tg_ssdo_rows(&p, &io, 0, f->height);
        return sh != NULL;
    }
    case TG_TECH_BENTCONE: {
        tg_bentcone_params p;
        tg_bentcone_defaults(&p);
        p.samples = clamp_samples(r->samples);
        p.radius = r->radius;
        p.env_sh9 = sh;
        if (sh) { p.far_r = f->far.r; p.far_g = f->far.g; p.far_b = f->far.b; }
        tg_bentcone_rows(&p, &io, 0, f->height);
        return sh != NULL;
    }
    default:
        return 0;
    }
}
