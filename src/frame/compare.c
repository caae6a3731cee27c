/*
 * compare.c - the papers' other screen-space techniques, run at full
 * resolution from the G-buffer so the bench can set them beside HBIL and the
 * ray-traced reference (issue 5).  Each gets the request's samples and
 * radius; everything else is the technique's documented default.
 */
#include "technique.h"
#include "../ao/ssao.h"

void tg_frame_technique_other(tg_frame *f, tg_ao_io io)
{
    const tg_request *r = &f->plan.request;
    switch (r->technique) {
    case TG_TECH_SSAO: {
        tg_ssao_params p;
        tg_ssao_defaults(&p);
        p.samples = r->samples;
        p.radius = r->radius;
        tg_ssao_rows(&p, &io, 0, f->height);
        break;
    }
    default:
        break;
    }
}
