/* SPDX-License-Identifier: MIT */
/*
 * pack.c - with TG_OUTLINE_HELPERS (tinygi.h; on at -Os) the one copy of
 * pack.h's larger helpers that every file calls, instead of a copy per file.
 */
#include "pack.h"

#if TG_OUTLINE_HELPERS
tg_vec3 tgi_oct_unit(tgi_oct_dir d) { return tgi_oct_unit_inline(d); }
tg_vec3 tgi_oct_unpack(uint32_t w, int bits) { return tgi_oct_unit(tgi_oct_fold(w, bits)); }
uint32_t tgi_rgb9e5_pack(tg_vec3 c) { return tgi_rgb9e5_pack_inline(c); }
tg_vec3 tgi_rgb9e5_unpack(uint32_t w) { return tgi_rgb9e5_unpack_inline(w); }
#endif
