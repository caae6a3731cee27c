/* SPDX-License-Identifier: MIT */
/*
 * technique.h - the frame's GI/AO step: HBIL (interleaved or full-res, with
 * its filters) or one of the comparison techniques, and the reprojection of
 * last frame's radiance the near field gathers from.
 */
#ifndef TG_TECHNIQUE_H
#define TG_TECHNIQUE_H

#include "frame_internal.h"

/* Run the plan's technique: fills f->ao, f->bent, f->cone, f->near (and
 * f->far for techniques that shade the environment themselves: returns 1). */
int tgi_frame_technique(tg_frame *f, int index);

/* The comparison techniques (compare.c): ssao, vo, hbao, gtao, ssdo,
 * bentcone.  Returns 1 when the technique wrote the far field itself. */
int tgi_frame_technique_other(tg_frame *f, tgi_ao_io io);

/* Reproject last frame's radiance into f->source; 0 if there was none. */
int tgi_frame_reproject(tg_frame *f);
/* Its two passes (HBIL sec. 3.2): scatter with a z-test, then push/pull. */
void tgi_frame_reproject_scatter(tg_frame *f);
void tgi_frame_reproject_fill(tg_frame *f);

/* HBIL's stages in the order the frame runs them (the bench times each).
 * Downsample and upsample do nothing unless the plan is quarter-res. */
void tgi_hbil_stage_downsample(tg_frame *f);
void tgi_hbil_stage_split(tg_frame *f);
void tgi_hbil_stage_kernel(tg_frame *f);
void tgi_hbil_stage_merge(tg_frame *f);
void tgi_hbil_stage_filter(tg_frame *f);
void tgi_hbil_stage_upsample(tg_frame *f);
void tgi_hbil_stage_temporal(tg_frame *f, int index);

#endif
