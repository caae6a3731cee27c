/* SPDX-License-Identifier: MIT */
/*
 * real.c - the core's own transcendentals and the decimal parser, for both
 * number types (float and Q16.16).  No libm: every function is a range
 * reduction plus a polynomial (Taylor series of the reduced argument, short
 * enough that the truncation error is far below the target), or an exact
 * integer algorithm.
 *
 * Each kernel is written ONCE against an internal "wide" number `wreal`:
 *   float build : wreal is float;
 *   fixed build : wreal is int64_t in Q2.30 (30 fraction bits), so the
 *                 polynomials run 14 bits finer than the Q16.16 result and
 *                 the final rounding dominates the error.
 * Only the range reductions and the bit-level steps (sqrt seeds, exponent
 * fields) differ between the builds.
 *
 * Worst-case error, MEASURED by tests/test_real.c against libm (64-bit
 * precision) over the stated domain: dense grids of 1e5..1e7 points, every
 * representable input where that is feasible in fixed point (sqrt below
 * 2^22 ulps, asin/acos on [-1, 1], tan, exp2, sin/cos on [-16, 16]).
 * Fixed: |error| in ulps (2^-16) divided by max(1, |true value|), i.e.
 * absolute up to 1 and relative (in 2^-16 units) above.  The best possible
 * is 0.5 ulp (the final rounding); the Q30 internals add ~1e-4 ulp.
 * Float: relative error; for sin/cos within 1e-2 of a zero other than
 * x = 0 (relative error is meaningless there) the ABSOLUTE error, and for
 * true values below FLT_MIN the absolute error (subnormal results).
 *
 *   function        domain                      fixed        float
 *   tg_sqrt         x >= 0                      0.5000 ulp   rel 1.6e-7
 *                   (fixed: exactly rounded, checked once for all 2^31 inputs)
 *   tg_rsqrt        x > 0                       0.5000 ulp   rel 1.8e-7
 *                   (fixed: 0.50004 ulp over every 8th of all 2^31 inputs)
 *   tg_sin          fixed all; float |x| < 2^22 0.5001 ulp   rel 1.5e-7; abs 1.1e-9 near k pi
 *   tg_cos          as sin                      0.5001 ulp   rel 1.4e-7; abs 1.1e-9 near zeros
 *   tg_tan          |x| <= pi/2 - 2^-10         0.5000 ulp   rel 2.2e-7
 *   tg_asin         [-1, 1] (clamped outside)   0.5001 ulp   rel 3.9e-7
 *   tg_acos         [-1, 1] (clamped outside)   0.5000 ulp   rel 1.9e-7
 *   tg_atan2        all (y, x)                  0.5000 ulp   rel 2.9e-7
 *   tg_exp2         fixed [-17, 15), float      0.5000 ulp   rel 8.8e-8
 *                   [-126, 128)
 *   tg_log2         x > 0                       0.5001 ulp   rel 2.6e-7
 *   tg_pow          x > 0, |y log2 x| < 15      0.5000 ulp   rel 3.9e-6
 *                   (fixed) or < 64 (float)
 *   tg_floor        all                         exact        exact
 *   tgi_isqrt64      all uint64                  exact floor (both builds; 6e6 values incl. k^2, k^2-1)
 *   tg_parse_real   decimal text                correctly rounded, ties to even
 *                                               (300000 random strings vs strtof/strtod)
 * Targets from issue 2: fixed trig within 2^-12 = 16 ulp, sqrt within 1 ulp;
 * float within 1e-5 relative (1e-6 absolute near zeros).
 * Rerun:  make BUILD=build-real tests-build &&
 *         build-real/float/tests/test_real; build-real/fixed/tests/test_real
 * (each prints "measured FUNCTION ..." lines).
 *
 * Outside its domain each function still returns a finite, deterministic
 * value: float sin/cos of |x| >= 2^22 (or NaN/inf) give 0 and 1; NaN inputs
 * elsewhere give 0 or the documented limit.
 */
#include "real.h"
#include <string.h>

/* ---------------------------------------------------------------------- */
/* integer helpers, shared                                                 */

/* Rounded right shift: in Q16.16 tinygi.h's tgi_shr_round (to nearest,
 * ties toward +infinity; compiling for size its one copy below); the float
 * build's range reduction keeps its ties away from zero (and its bits),
 * without shifting negative values. */
static int64_t shr_round(int64_t p, int s)
{
#if TG_FIXED
    return tgi_shr_round(p, s);
#else
    int64_t half = (int64_t)1 << (s - 1);
    return p >= 0 ? (p + half) >> s : -((-p + half) >> s);
#endif
}

#if TG_FIXED
/* a / b rounded to nearest (half away from zero); b != 0. */
static int64_t div_round(int64_t a, int64_t b)
{
    int64_t ab = b < 0 ? -b : b, aa = a < 0 ? -a : a;
    int64_t q = (aa + ab / 2) / ab;
    return (a < 0) != (b < 0) ? -q : q;
}

#endif

#if TG_FIXED
const uint32_t tgi_rsqrt_seed_q30[24] = {
    1041682578u, 985333074u, 937238702u, 895562589u, 858993459u, 826566842u,
    797555404u, 771398898u, 747657839u, 725981977u, 706088274u, 687745184u,
    670761200u, 654976372u, 640255922u, 626485368u, 613566757u, 601415717u,
    589959130u, 579133272u, 568882316u, 559157115u, 549914212u, 541115017u };
#endif

/* 1/sqrt(M) in Q30 at the middle of [i/64, (i+1)/64), i = 16..63
 * (tgi_rsqrt_q30, real.h). */
const uint32_t tgi_rsqrt_seed_q30_64[48] = {
    2114695713, 2053387115, 1997119227, 1945237133, 1897199172, 1852552937, 1810917218, 1771968208,
    1735428857, 1701060526, 1668656406, 1638036256, 1609042172, 1581535151, 1555392273, 1530504391,
    1506774204, 1484114654, 1462447584, 1441702596, 1421816090, 1402730445, 1384393311, 1366757007,
    1349778000, 1333416450, 1317635818, 1302402522, 1287685637, 1273456629, 1259689126, 1246358707,
    1233442724, 1220920139, 1208771378, 1196978204, 1185523604, 1174391680, 1163567563, 1153037323,
    1142787899, 1132807028, 1123083182, 1113605518, 1104363818, 1095348453, 1086550331, 1077960865
};

#if TG_FIXED
/* tinygi.h's tgi_shr_round and tg_div, once, for builds that compile for
 * size (TG_OUTLINE_HELPERS); the same statements. */
#if defined(__GNUC__)
__attribute__((noinline))   /* short enough for -flto to copy into every caller: 1.5 KB more */
#endif
int64_t tgi_shr_round_q16(int64_t p, int s) { return tgi_shr_round_inline(p, s); }
int32_t tgi_div_q16(int32_t a, int32_t b) { return tgi_div_inline(a, b); }
#endif

/* v > 0 as M 2^e: returns M in Q32 (M in [1/4, 1)) and an even e. */
static uint64_t mantissa_even(uint64_t v, int *e)
{
    int bl = tgi_bit_length64(v);
    uint64_t m = bl > 32 ? v >> (bl - 32) : v << (32 - bl);
    if (bl & 1) { m >>= 1; bl++; }
    *e = bl;
    return m;
}

/* 1/sqrt(M) in Q30 for M in [1/4, 1) given in Q32: tgi_rsqrt_q30
 * (real.h), out of line for tgi_isqrt64 and compiling for size. */
static uint64_t rsqrt_q30(uint64_t m) { return tgi_rsqrt_q30(m); }

/* floor(sqrt(v)): sqrt(M) 2^(e/2) from the Newton reciprocal (within a few
 * units), then made exact by integer tests r^2 <= v < (r+1)^2. */
uint32_t tgi_isqrt64(uint64_t v)
{
    int e;
    uint64_t m, sm, r;
    if (v == 0) return 0;
    m = mantissa_even(v, &e);
    sm = (m * rsqrt_q30(m)) >> 32; /* sqrt(M), Q30 */
    r = e >= 60 ? sm << (e / 2 - 30) : sm >> (30 - e / 2);
    if (r > 0xffffffffu) r = 0xffffffffu;
    while (r * r > v) r--;
    while (r < 0xffffffffu && v - r * r > 2 * r) r++;
    return (uint32_t)r;
}

/* ---------------------------------------------------------------------- */
/* the wide internal number                                                */

#if TG_FIXED
typedef int64_t wreal; /* Q2.30 */
#define WC(f, q30) ((wreal)(q30))
#define W_ONE ((wreal)1 << 30)
static wreal w_mul(wreal a, wreal b) { return shr_round(a * b, 30); }
static wreal w_div(wreal a, wreal b) { return div_round(a * W_ONE, b); }
static wreal w_sqrt(wreal a) { return a <= 0 ? 0 : (wreal)tgi_isqrt_round64((uint64_t)a << 30); }
static wreal w_from_real(tg_real x) { return (wreal)x * 16384; }
static tg_real w_to_real(wreal a) { return tgi_sat64(shr_round(a, 14)); }
#else
typedef float wreal;
#define WC(f, q30) (f)
#define W_ONE 1.0f
static wreal w_mul(wreal a, wreal b) { return a * b; }
static wreal w_div(wreal a, wreal b) { return a / b; }
static wreal w_sqrt(wreal a) { return tg_sqrt(a); }
static wreal w_from_real(tg_real x) { return x; }
static tg_real w_to_real(wreal a) { return a; }
#endif

#define W_HALF WC(0.5f, 536870912)
#define W_PI WC(3.14159265f, 3373259426)
#define W_HALF_PI WC(1.57079633f, 1686629713)
#define W_PI_6 WC(0.523598776f, 562209904)
#define W_SQRT3 WC(1.73205081f, 1859775393)
#define W_TAN_PI_12 WC(0.267949192f, 287708255)
#define W_2_LN2 WC(2.88539008f, 3098164009)

/* c[0] + z (c[1] + z (c[2] + ...)) */
static wreal w_poly(wreal z, const wreal *c, int n)
{
    wreal acc = c[n - 1];
    int i;
    for (i = n - 2; i >= 0; i--) acc = c[i] + w_mul(acc, z);
    return acc;
}

/* ---------------------------------------------------------------------- */
/* sqrt, rsqrt                                                             */

#if TG_FIXED

/* sqrt(x) = sqrt(v), v = x_raw 2^16 < 2^47, rounded to nearest: exact to
 * 0.5 ulp.  v = m 4^-h with m = X 2^60, X in [1, 4); sqrt(X) in Q30 from a
 * quadratic on X's interval of width 1/32 (sqrt_quad below, within 2^-24),
 * times 2^-h within 0.52 of sqrt(v) (h >= 7), so that rounded is within 1
 * of R, the nearest integer to sqrt(v); then one step of the integer tests
 * R^2 - R < v <= R^2 + R makes it exact. */
#if TG_OUTLINE_HELPERS
/* Compiling for size (tinygi.h): the same rounded-to-nearest sqrt(v) from
 * the integer square root the vector lengths already link, without the
 * fast path's own code.  floor r, then r + 1 when v - r^2 > r, that is
 * when sqrt(v) >= r + 1/2: the same R as the tests below. */
tg_real tg_sqrt(tg_real x)
{
    return x <= 0 ? 0 : (tg_real)tgi_isqrt_round64((uint64_t)x << 16);
}
#else
/* sqrt(X) ~ c[0] + c[1] t - c[2] t^2 for X = 1 + i/32 + t, t in [0, 1/32),
 * i = 0..95: the quadratic through sqrt at the three Chebyshev nodes of the
 * interval, (1/64)(1 - cos(k pi/6)) for k = 1, 3, 5, as integers Q30, Q32,
 * Q32 (rounded to nearest); within 2^-24 of sqrt(X) on the interval. */
static const uint32_t sqrt_quad[96][3] = {
    { 1073741886u, 2147340253u, 524558458u }, { 1090390034u, 2114562824u, 501245293u }, { 1106787792u, 2083241726u, 479609282u },
    { 1122946129u, 2053272229u, 459486235u }, { 1138875234u, 2024559851u, 440732063u }, { 1154584596u, 1997019105u, 423219858u },
    { 1170083066u, 1970572425u, 406837443u }, { 1185378916u, 1945149249u, 391485344u }, { 1200479890u, 1920685227u, 377075071u },
    { 1215393253u, 1897121531u, 363527670u }, { 1230125828u, 1874404265u, 350772498u }, { 1244684035u, 1852483943u, 338746179u },
    { 1259073922u, 1831315037u, 327391708u }, { 1273301195u, 1810855578u, 316657690u }, { 1287371247u, 1791066810u, 306497673u },
    { 1301289177u, 1771912872u, 296869585u }, { 1315059815u, 1753360537u, 287735238u }, { 1328687740u, 1735378957u, 279059897u },
    { 1342177301u, 1717939459u, 270811906u }, { 1355532626u, 1701015343u, 262962363u }, { 1368757647u, 1684581717u, 255484831u },
    { 1381856104u, 1668615338u, 248355087u }, { 1394831562u, 1653094479u, 241550898u }, { 1407687423u, 1637998798u, 235051826u },
    { 1420426935u, 1623309232u, 228839053u }, { 1433053200u, 1609007895u, 222895228u }, { 1445569185u, 1595077981u, 217204330u },
    { 1457977731u, 1581503688u, 211751542u }, { 1470281558u, 1568270139u, 206523146u }, { 1482483273u, 1555363312u, 201506424u },
    { 1494585378u, 1542769983u, 196689570u }, { 1506590272u, 1530477662u, 192061610u }, { 1518500261u, 1518474546u, 187612334u },
    { 1530317562u, 1506749472u, 183332231u }, { 1542044304u, 1495291868u, 179212430u }, { 1553682539u, 1484091718u, 175244650u },
    { 1565234240u, 1473139522u, 171421151u }, { 1576701311u, 1462426265u, 167734695u }, { 1588085583u, 1451943384u, 164178501u },
    { 1599388826u, 1441682740u, 160746215u }, { 1610612744u, 1431636588u, 157431877u }, { 1621758986u, 1421797560u, 154229888u },
    { 1632829141u, 1412158634u, 151134989u }, { 1643824748u, 1402713120u, 148142230u }, { 1654747291u, 1393454633u, 145246955u },
    { 1665598209u, 1384377084u, 142444775u }, { 1676378892u, 1375474653u, 139731553u }, { 1687090687u, 1366741783u, 137103384u },
    { 1697734898u, 1358173158u, 134556582u }, { 1708312787u, 1349763694u, 132087664u }, { 1718825581u, 1341508524u, 129693335u },
    { 1729274464u, 1333402987u, 127370478u }, { 1739660590u, 1325442616u, 125116141u }, { 1749985076u, 1317623130u, 122927529u },
    { 1760249006u, 1309940421u, 120801988u }, { 1770453433u, 1302390547u, 118737004u }, { 1780599381u, 1294969726u, 116730188u },
    { 1790687843u, 1287674321u, 114779272u }, { 1800719786u, 1280500840u, 112882100u }, { 1810696149u, 1273445923u, 111036622u },
    { 1820617846u, 1266506341u, 109240887u }, { 1830485766u, 1259678984u, 107493038u }, { 1840300773u, 1252960861u, 105791306u },
    { 1850063710u, 1246349089u, 104134006u }, { 1859775397u, 1239840891u, 102519529u }, { 1869436633u, 1233433592u, 100946344u },
    { 1879048196u, 1227124611u, 99412986u }, { 1888610844u, 1220911459u, 97918058u }, { 1898125316u, 1214791735u, 96460225u },
    { 1907592334u, 1208763120u, 95038210u }, { 1917012600u, 1202823376u, 93650794u }, { 1926386801u, 1196970340u, 92296810u },
    { 1935715605u, 1191201924u, 90975141u }, { 1944999666u, 1185516108u, 89684716u }, { 1954239621u, 1179910939u, 88424512u },
    { 1963436093u, 1174384528u, 87193547u }, { 1972589691u, 1168935049u, 85990881u }, { 1981701008u, 1163560733u, 84815609u },
    { 1990770626u, 1158259868u, 83666867u }, { 1999799110u, 1153030796u, 82543825u }, { 2008787016u, 1147871911u, 81445683u },
    { 2017734887u, 1142781656u, 80371676u }, { 2026643252u, 1137758524u, 79321068u }, { 2035512630u, 1132801052u, 78293151u },
    { 2044343529u, 1127907822u, 77287245u }, { 2053136445u, 1123077458u, 76302696u }, { 2061891864u, 1118308626u, 75338875u },
    { 2070610262u, 1113600030u, 74395174u }, { 2079292104u, 1108950413u, 73471012u }, { 2087937846u, 1104358554u, 72565827u },
    { 2096547935u, 1099823267u, 71679077u }, { 2105122809u, 1095343399u, 70810241u }, { 2113662896u, 1090917832u, 69958817u },
    { 2122168616u, 1086545476u, 69124319u }, { 2130640381u, 1082225275u, 68306282u }, { 2139078594u, 1077956199u, 67504252u }
};

tg_real tg_sqrt(tg_real x)
{
    const uint32_t *c;
    uint64_t x30, t, s, r, r2, v;
    int h;
    if (x <= 0) return 0;
    h = (tgi_clz32_nz((uint32_t)x) + 14) >> 1;       /* (46 - bit length) / 2, 7..22: v = x_raw 2^16, v 4^h in [2^60, 2^62) */
    x30 = (uint64_t)x << (2 * h - 14);       /* X = v 4^h 2^-60 in Q30, [2^30, 2^32) */
    c = sqrt_quad[(x30 >> 25) - 32];
    t = x30 & 0x1ffffffu;                    /* t in Q30, < 2^25 */
    s = c[0] + ((c[1] * t) >> 32) - ((c[2] * ((t * t) >> 18)) >> 44);   /* sqrt(X), Q30 */
    r = ((s >> (h - 1)) + 1) >> 1;           /* sqrt(v) = sqrt(X) 2^(30 - h), within 1 of R */
    r2 = r * r;
    v = (uint64_t)x << 16;
    if (r2 + r < v) r++;
    else if (r2 - r >= v) r--;
    return (tg_real)r;
}
#endif

/* 1/sqrt(x): x_raw = M 2^e, raw = 2^24 / sqrt(x_raw) = 2^(24 - e/2) / sqrt(M). */
tg_real tg_rsqrt(tg_real x)
{
#if TG_OUTLINE_HELPERS   /* compiling for size: mantissa_even's code, shared */
    int e;
    uint64_t y;
    if (x <= 0) return TG_REAL_MAX;
    y = rsqrt_q30(mantissa_even((uint64_t)x, &e));
    return tgi_sat64((int64_t)((y + ((uint64_t)1 << (5 + e / 2))) >> (6 + e / 2)));
#else   /* tgi_rsqrt_pos (real.h), rsqrt_q30 inline */
    if (x <= 0) return TG_REAL_MAX;
    return tgi_rsqrt_pos(x);
#endif
}

#else


/* tg_rsqrt and tg_sqrt are static inline in real.h for the float build. */

#endif

/* ---------------------------------------------------------------------- */
/* sin, cos, tan                                                           */

/* pi/2 in Q40 (high part) and the next 24 bits (low part). */
#define PIO2_Q40_HI ((int64_t)1727108826178)
#define PIO2_Q40_LO ((int64_t)13730922)

/* x - k pi/2 in Q40 given x in Q40 and k. */
static int64_t reduce_q40(int64_t x40, int64_t k)
{
    return x40 - k * PIO2_Q40_HI - shr_round(k * PIO2_Q40_LO, 24);
}

#if TG_FIXED
/* x = k pi/2 + r, |r| <= pi/4 (+ rounding); quadrant = k mod 4. */
static wreal reduce_half_pi(tg_real x, int *quadrant)
{
    int64_t k = shr_round((int64_t)x * 1367130551, 47); /* x 2/pi, 2/pi in Q31 */
    *quadrant = (int)((uint64_t)k & 3u);
    return shr_round(reduce_q40((int64_t)x * 16777216, k), 10);
}
#else
/* x * 2^40 as an integer, for pi/4 < |x| < 2^22, where it is exact (the
 * float's ulp is 2^-24 or more).  Compiling for size (TG_OUTLINE_HELPERS,
 * tinygi.h) it is read from the float's bits: libgcc converts a float to a
 * 64-bit integer through double, 2 KB of double arithmetic in a program
 * without an FPU for it; the same integer either way. */
static int64_t times_2_40(float x)
{
#if TG_OUTLINE_HELPERS
    uint32_t b = tgi_f_bits(x);
    int64_t m = (int64_t)((b & 0x7fffffu) | 0x800000u) << ((int)((b >> 23) & 255u) - 127 + 17);
    return (b >> 31) ? -m : m;
#else
    return (int64_t)(x * 1099511627776.0f);
#endif
}

static wreal reduce_half_pi(tg_real x, int *quadrant)
{
    float ax = x < 0.0f ? -x : x;
    int32_t k;
    int64_t r;
    if (ax <= 0.785398163f) { *quadrant = 0; return x; }
    if (!(ax < 4194304.0f)) { *quadrant = 0; return 0.0f; } /* outside the domain, NaN */
    k = (int32_t)(x * 0.636619772f + (x >= 0.0f ? 0.5f : -0.5f));
    *quadrant = (int)((uint32_t)k & 3u);
    /* x * 2^40 is an exact integer for |x| > pi/4 */
    r = reduce_q40(times_2_40(x), k);
    return (float)r * (1.0f / 1099511627776.0f);
}
#endif

/* Taylor series of sin r / r and cos r in z = r^2, |r| <= pi/4:
 * truncation below 3e-9 relative. */
static const wreal sin_c[6] = {
    WC(1.0f, 1073741824), WC(-1.66666667e-01f, -178956971), WC(8.33333333e-03f, 8947849),
    WC(-1.98412698e-04f, -213044), WC(2.75573192e-06f, 2959), WC(-2.50521084e-08f, -27)
};
static const wreal cos_c[7] = {
    WC(1.0f, 1073741824), WC(-0.5f, -536870912), WC(4.16666667e-02f, 44739243),
    WC(-1.38888889e-03f, -1491308), WC(2.48015873e-05f, 26631), WC(-2.75573192e-07f, -296),
    WC(2.08767570e-09f, 2)
};

static wreal sin_reduced(wreal r) { return w_mul(r, w_poly(w_mul(r, r), sin_c, 6)); }
static wreal cos_reduced(wreal r) { return w_poly(w_mul(r, r), cos_c, 7); }

/* sin(k pi/2 + r) by quadrant. */
static wreal sin_quadrant(wreal r, int q)
{
    switch (q & 3) {
    case 0: return sin_reduced(r);
    case 1: return cos_reduced(r);
    case 2: return -sin_reduced(r);
    default: return -cos_reduced(r);
    }
}

tg_real tg_sin(tg_real x)
{
    int q;
    wreal r = reduce_half_pi(x, &q);
    return w_to_real(sin_quadrant(r, q));
}

tg_real tg_cos(tg_real x)
{
    int q;
    wreal r = reduce_half_pi(x, &q);
    return w_to_real(sin_quadrant(r, q + 1));
}

tg_real tg_tan(tg_real x)
{
    int q;
    wreal r = reduce_half_pi(x, &q);
    wreal s = sin_quadrant(r, q), c = sin_quadrant(r, q + 1);
#if TG_FIXED
    if (c == 0) return s >= 0 ? TG_REAL_MAX : TG_REAL_MIN;
    return tgi_sat64(div_round(s * 65536, c));
#else
    if (c == 0.0f) return s >= 0.0f ? TG_REAL_MAX : TG_REAL_MIN;
    return s / c;
#endif
}

/* ---------------------------------------------------------------------- */
/* asin, acos                                                              */

/* asin(a)/a = sum (2n)! / (4^n (n!)^2 (2n+1)) a^2n, used for |a| <= 1/2:
 * truncation after 11 terms < 1e-8 relative. */
static const wreal asin_c[11] = {
    WC(1.0f, 1073741824), WC(1.66666667e-01f, 178956971), WC(7.50000000e-02f, 80530637),
    WC(4.46428571e-02f, 47934903), WC(3.03819444e-02f, 32622364), WC(2.23721591e-02f, 24021923),
    WC(1.73527644e-02f, 18632389), WC(1.39648438e-02f, 14994637), WC(1.15518009e-02f, 12403652),
    WC(9.76160953e-03f, 10481448), WC(8.39033581e-03f, 9009054)
};

static wreal asin_series(wreal a) { return w_mul(a, w_poly(w_mul(a, a), asin_c, 11)); }

/* |x| clamped to 1, as wide. */
static wreal abs_clamped_unit(tg_real x)
{
    tg_real a = tg_abs(x);
    if (!(a < TG_ONE)) a = TG_ONE; /* NaN too */
    return w_from_real(a);
}

/* For a > 1/2: asin(a) = pi/2 - 2 asin(sqrt((1 - a) / 2)). */
static wreal half_angle_sqrt(wreal a) { return w_sqrt(w_mul(W_ONE - a, W_HALF)); }

tg_real tg_asin(tg_real x)
{
    wreal a = abs_clamped_unit(x), r;
    if (a <= W_HALF) r = asin_series(a);
    else { wreal t = asin_series(half_angle_sqrt(a)); r = W_HALF_PI - (t + t); }
    return w_to_real(x < 0 ? -r : r);
}

tg_real tg_acos(tg_real x)
{
    wreal a = abs_clamped_unit(x), t;
    if (a <= W_HALF) {
        t = asin_series(a);
        return w_to_real(x < 0 ? W_HALF_PI + t : W_HALF_PI - t);
    }
    /* acos(a) = 2 asin(sqrt((1 - a) / 2)): no cancellation near a = 1 */
    t = asin_series(half_angle_sqrt(a));
    t = t + t;
    return w_to_real(x < 0 ? W_PI - t : t);
}

/* ---------------------------------------------------------------------- */
/* atan2                                                                   */

/* atan(u)/u = sum (-1)^n u^2n / (2n+1) for |u| <= tan(pi/12). */
static const wreal atan_c[9] = {
    WC(1.0f, 1073741824), WC(-3.33333333e-01f, -357913941), WC(2.0e-01f, 214748365),
    WC(-1.42857143e-01f, -153391689), WC(1.11111111e-01f, 119304647), WC(-9.09090909e-02f, -97612893),
    WC(7.69230769e-02f, 82595525), WC(-6.66666667e-02f, -71582788), WC(5.88235294e-02f, 63161284)
};

/* atan(t) for t in [0, 1]: above tan(pi/12) use
 * atan(t) = pi/6 + atan((t sqrt3 - 1) / (t + sqrt3)). */
static wreal atan_unit(wreal t)
{
    if (t > W_TAN_PI_12) {
        wreal u = w_div(w_mul(t, W_SQRT3) - W_ONE, t + W_SQRT3);
        return W_PI_6 + w_mul(u, w_poly(w_mul(u, u), atan_c, 9));
    }
    return w_mul(t, w_poly(w_mul(t, t), atan_c, 9));
}

tg_real tg_atan2(tg_real y, tg_real x)
{
    wreal t, a;
#if TG_FIXED
    int64_t ax = x < 0 ? -(int64_t)x : x, ay = y < 0 ? -(int64_t)y : y;
    if (ax == 0 && ay == 0) return 0;
    t = ay > ax ? div_round(ax * W_ONE, ay) : div_round(ay * W_ONE, ax);
#else
    float ax = x < 0.0f ? -x : x, ay = y < 0.0f ? -y : y;
    if (!(ax > 0.0f || ay > 0.0f) || ax != ax || ay != ay) return 0.0f; /* (0,0), NaN */
    t = ay > ax ? ax / ay : ay / ax;
    if (!(t == t)) t = 1.0f; /* both infinite */
#endif
    a = atan_unit(t);
    if (ay > ax) a = W_HALF_PI - a;
    if (x < 0) a = W_PI - a;
    return w_to_real(y < 0 ? -a : a);
}

/* ---------------------------------------------------------------------- */
/* exp2, log2, pow                                                         */

/* 2^f = sum (f ln2)^k / k!, f in [-1/2, 1) : truncation < 3e-11. */
static const wreal exp2_c[12] = {
    WC(1.0f, 1073741824), WC(6.93147181e-01f, 744261118), WC(2.40226507e-01f, 257941248),
    WC(5.55041087e-02f, 59597083), WC(9.61812911e-03f, 10327387), WC(1.33335581e-03f, 1431680),
    WC(1.54035304e-04f, 165394), WC(1.52527338e-05f, 16377), WC(1.32154868e-06f, 1419),
    WC(1.01780860e-07f, 109), WC(7.05491672e-09f, 8), WC(4.44553541e-10f, 0)
};

/* log2(m) = 2/ln2 atanh(s), s = (m-1)/(m+1), m in [sqrt(1/2), sqrt2]:
 * atanh(s)/s = sum s^2n / (2n+1); |s| <= 0.172, truncation < 1e-11. */
static const wreal atanh_c[7] = {
    WC(1.0f, 1073741824), WC(3.33333333e-01f, 357913941), WC(2.0e-01f, 214748365),
    WC(1.42857143e-01f, 153391689), WC(1.11111111e-01f, 119304647), WC(9.09090909e-02f, 97612893),
    WC(7.69230769e-02f, 82595525)
};

static wreal log2_mantissa(wreal m)
{
    wreal s = w_div(m - W_ONE, m + W_ONE);
    return w_mul(w_mul(s, w_poly(w_mul(s, s), atanh_c, 7)), W_2_LN2);
}

#if TG_FIXED

/* log2(x) in Q30 for x > 0: x = m 2^e, m in [sqrt(1/2), sqrt2). */
static wreal log2_wide(tg_real x)
{
    int p = tgi_bit_length64((uint64_t)x) - 1; /* x_raw = m 2^p, m in [1, 2) */
    int64_t e = p - 16;
    wreal m = (wreal)x << (30 - p);
    if (m > 1518500250) { m = (m + 1) >> 1; e++; } /* m > sqrt2 */
    return e * W_ONE + log2_mantissa(m);
}

/* 2^v for v in Q30: v = n + f, f in [0, 1). */
static tg_real exp2_wide(wreal v)
{
    int64_t n = v >= 0 ? v >> 30 : -((-v + W_ONE - 1) >> 30);
    wreal p;
    if (n >= 15) return TG_REAL_MAX;
    if (n < -40) return 0;
    p = w_poly(v - n * W_ONE, exp2_c, 12); /* [2^30, 2^31) */
    return tgi_sat64(n == 14 ? p : shr_round(p, (int)(14 - n)));
}

tg_real tg_exp2(tg_real x) { return exp2_wide(w_from_real(x)); }

tg_real tg_log2(tg_real x)
{
    if (x <= 0) return TG_REAL_MIN;
    return w_to_real(log2_wide(x));
}

/* L * y where y is Q16.16, L is Q30, split to stay inside 64 bits. */
static wreal w_mul_real(wreal l, tg_real y)
{
    int64_t yi = y >= 0 ? (int64_t)y >> 16 : -((-(int64_t)y) >> 16);
    int64_t yf = (int64_t)y - yi * 65536;
    int64_t r = l * yi + shr_round(l * yf, 16);
    if (r > ((int64_t)64 << 30)) r = (int64_t)64 << 30;
    if (r < -((int64_t)64 << 30)) r = -((int64_t)64 << 30);
    return r;
}

#else

static float pow2i(int n) { return tgi_f_from_bits((uint32_t)(n + 127) << 23); } /* n in [-126, 127] */

static tg_real exp2_wide(wreal v)
{
    int32_t n;
    float p;
    if (!(v == v)) return 0.0f;
    if (v >= 128.0f) return TG_REAL_MAX;
    if (v < -150.0f) return 0.0f;
    n = (int32_t)(v + (v >= 0.0f ? 0.5f : -0.5f));
    p = w_poly(v - (float)n, exp2_c, 12); /* f in [-1/2, 1/2] */
    if (n > 127) return p * pow2i(127) * 2.0f;
    if (n < -126) return p * pow2i(n + 64) * pow2i(-64);
    return p * pow2i(n);
}

static wreal log2_wide(tg_real x)
{
    uint32_t b;
    int32_t e, bias = 0;
    float m;
    if (x > TG_REAL_MAX) return 128.0f;
    if (x < 1.17549435e-38f) { x *= 18446744073709551616.0f; bias = 64; }
    b = tgi_f_bits(x);
    e = (int32_t)((b >> 23) & 255u) - 127;
    m = tgi_f_from_bits((b & 0x7fffffu) | 0x3f800000u);
    if (m > 1.41421356f) { m *= 0.5f; e++; }
    return (float)(e - bias) + log2_mantissa(m);
}

tg_real tg_exp2(tg_real x) { return exp2_wide(x); }

tg_real tg_log2(tg_real x)
{
    if (!(x > 0.0f)) return TG_REAL_MIN;
    return log2_wide(x);
}

static wreal w_mul_real(wreal l, tg_real y) { return l * y; }

#endif

tg_real tg_pow(tg_real x, tg_real y)
{
    if (y == 0) return TG_ONE;
    if (!(x > 0)) return y > 0 ? 0 : TG_REAL_MAX;
    if (x == TG_ONE) return TG_ONE;
    return exp2_wide(w_mul_real(log2_wide(x), y));
}

/* ---------------------------------------------------------------------- */
/* floor, smoothstep                                                       */

tg_real tg_floor(tg_real x)
{
#if TG_FIXED
    int64_t f = x >= 0 ? (int64_t)x - (x & 65535) : -((-(int64_t)x + 65535) / 65536 * 65536);
    return tgi_sat64(f);
#else
    int32_t i;
    float f;
    if (!(x < 8388608.0f && x > -8388608.0f)) return x; /* integral, inf or NaN */
    i = (int32_t)x;
    f = (float)i;
    return f > x ? f - 1.0f : f;
#endif
}

tg_real tg_smoothstep(tg_real a, tg_real b, tg_real x)
{
    tg_real t;
    if (!(b > a)) return x < a ? 0 : TG_ONE;
    t = tg_saturate(tg_div(tg_sub(x, a), tg_sub(b, a)));
    return tg_mul(tg_mul(t, t), tg_sub(TG_R(3.0f), tg_add(t, t)));
}

/* ---------------------------------------------------------------------- */
/* decimal parsing                                                         */

/* Significant digits kept.  A float rounding boundary has at most 113
 * significant decimal digits and a Q16.16 one at most 17 after the point,
 * so 120 digits plus a sticky "something nonzero followed" flag decide
 * every rounding exactly. */
#define DEC_DIGITS 120
#define DEC_POINT_LIMIT 100000000

typedef struct decimal {
    unsigned char d[DEC_DIGITS]; /* value = 0.d[0]d[1]... * 10^point */
    int n;
    int sticky;
    int32_t point;
} decimal;

static int is_digit(char c) { return c >= '0' && c <= '9'; }

static void dec_push(decimal *dec, int digit, int before_point)
{
    if (dec->n == 0 && digit == 0) { /* leading zero */
        if (!before_point && dec->point > -DEC_POINT_LIMIT) dec->point--;
        return;
    }
    if (dec->n < DEC_DIGITS) dec->d[dec->n++] = (unsigned char)digit;
    else if (digit) dec->sticky = 1;
    if (before_point && dec->point < DEC_POINT_LIMIT) dec->point++;
}

#if TG_FIXED

/* round(value * 2^16) in integers, ties to even. */
static tg_real dec_to_real(const decimal *dec, int *overflow)
{
    unsigned char f[DEC_DIGITS + 8];
    int32_t i, nf = 0;
    int64_t ip = 0, raw;
    uint32_t carry = 0;
    int cmp = 0; /* remainder vs 1/2 */
    if (dec->n == 0 || dec->point < -5) return 0; /* < 1e-6 < 2^-17 */
    if (dec->point > 5) { *overflow = 1; return TG_REAL_MAX; }
    for (i = 0; i < dec->point; i++) ip = ip * 10 + (i < dec->n ? dec->d[i] : 0);
    for (i = dec->point; i < 0; i++) f[nf++] = 0;
    for (i = dec->point > 0 ? dec->point : 0; i < dec->n; i++) f[nf++] = dec->d[i];
    for (i = nf - 1; i >= 0; i--) { /* 0.f * 65536, digit by digit */
        uint32_t v = f[i] * 65536u + carry;
        f[i] = (unsigned char)(v % 10u);
        carry = v / 10u;
    }
    if (nf > 0) {
        cmp = f[0] > 5 ? 1 : f[0] < 5 ? -1 : 0;
        for (i = 1; i < nf && cmp == 0; i++) if (f[i]) cmp = 1;
        if (cmp == 0 && dec->sticky) cmp = 1;
    } else {
        cmp = -1;
    }
    raw = ip * 65536 + carry;
    if (cmp > 0 || (cmp == 0 && (raw & 1))) raw++;
    if (raw > (int64_t)TG_REAL_MAX) { *overflow = 1; return TG_REAL_MAX; }
    return (tg_real)raw;
}

#else

/* Little big integers for the exact float conversion (768 bits). */
#define BIG_LIMBS 24
typedef struct big { uint32_t w[BIG_LIMBS]; } big;

static void big_set(big *a, uint32_t v) { memset(a, 0, sizeof *a); a->w[0] = v; }
static void big_mul_add(big *a, uint32_t m, uint32_t add)
{
    uint64_t c = add;
    int i;
    for (i = 0; i < BIG_LIMBS; i++) {
        c += (uint64_t)a->w[i] * m;
        a->w[i] = (uint32_t)c;
        c >>= 32;
    }
}
static void big_pow10(big *a, int32_t e) /* a *= 10^e */
{
    while (e >= 9) { big_mul_add(a, 1000000000u, 0); e -= 9; }
    while (e-- > 0) big_mul_add(a, 10u, 0);
}
static void big_shl(big *a, int32_t s)
{
    int32_t i, limbs = s / 32, bits = s % 32;
    for (i = BIG_LIMBS - 1; i >= 0; i--) {
        uint32_t hi = i - limbs >= 0 ? a->w[i - limbs] : 0;
        uint32_t lo = i - limbs - 1 >= 0 ? a->w[i - limbs - 1] : 0;
        a->w[i] = bits ? (hi << bits) | (lo >> (32 - bits)) : hi;
    }
}
static int big_cmp(const big *a, const big *b)
{
    int i;
    for (i = BIG_LIMBS - 1; i >= 0; i--)
        if (a->w[i] != b->w[i]) return a->w[i] > b->w[i] ? 1 : -1;
    return 0;
}
static void big_sub(big *a, const big *b) /* a >= b */
{
    uint64_t borrow = 0;
    int i;
    for (i = 0; i < BIG_LIMBS; i++) {
        uint64_t d = (uint64_t)a->w[i] - b->w[i] - borrow;
        a->w[i] = (uint32_t)d;
        borrow = (d >> 63) & 1u;
    }
}
static int32_t big_bits(const big *a)
{
    int i;
    for (i = BIG_LIMBS - 1; i >= 0; i--)
        if (a->w[i]) return i * 32 + tgi_bit_length64(a->w[i]);
    return 0;
}
static int big_is_zero(const big *a) { return big_bits(a) == 0; }

/* value = num / den; returns the correctly rounded float (ties to even). */
static tg_real dec_to_real(const decimal *dec, int *overflow)
{
    big num, den;
    int32_t e, b, nbits, i;
    uint32_t q = 0, m, bits;
    int guard, sticky;
    if (dec->n == 0 || dec->point <= -46) return 0.0f; /* < 1e-46 < 2^-150 */
    if (dec->point >= 40) { *overflow = 1; return TG_REAL_MAX; }
    big_set(&num, 0);
    for (i = 0; i < dec->n; i++) big_mul_add(&num, 10u, dec->d[i]);
    big_set(&den, 1);
    e = dec->point - dec->n;
    if (e >= 0) big_pow10(&num, e);
    else big_pow10(&den, -e);
    /* scale so that 1 <= num/den < 2; value in [2^b, 2^(b+1)) */
    b = big_bits(&num) - big_bits(&den);
    if (b >= 0) big_shl(&den, b);
    else big_shl(&num, -b);
    if (big_cmp(&num, &den) < 0) { big_shl(&num, 1); b--; }
    if (b < -150) return 0.0f;
    nbits = b >= -126 ? 25 : b + 151; /* mantissa bits + guard */
    for (i = 0; i < nbits; i++) {
        q <<= 1;
        if (big_cmp(&num, &den) >= 0) { big_sub(&num, &den); q |= 1u; }
        big_shl(&num, 1);
    }
    m = q >> 1;
    guard = (int)(q & 1u);
    sticky = !big_is_zero(&num) || dec->sticky;
    if (guard && (sticky || (m & 1u))) m++;
    if (b >= -126) {
        if (b > 127) { *overflow = 1; return TG_REAL_MAX; }
        bits = ((uint32_t)(b + 127) << 23) + (m - 0x800000u);
    } else {
        bits = m;
    }
    if (bits >= 0x7f800000u) { *overflow = 1; return TG_REAL_MAX; }
    return tgi_f_from_bits(bits);
}

#endif

/* Grammar: [+-] digits [. digits] [(e|E) [+-] digits], at least one mantissa
 * digit (".5" and "5." are numbers).  No white space, "inf", "nan" or hex:
 * "0x10" consumes only "0", so a caller that checks the count against the
 * token length rejects it.  An exponent without digits ("1e", "1e+") is not
 * consumed.  Huge exponents saturate (overflow set) or give 0.  The same
 * text gives the same bits on every target: integer arithmetic only. */
size_t tg_parse_real(const char *s, size_t len, tg_real *out, int *overflow)
{
    decimal dec;
    size_t i = 0;
    int neg = 0, any = 0, ovf = 0;
    tg_real r;
    dec.n = 0;
    dec.sticky = 0;
    dec.point = 0;
    if (out) *out = 0;
    if (overflow) *overflow = 0;
    if (i < len && (s[i] == '+' || s[i] == '-')) { neg = s[i] == '-'; i++; }
    for (; i < len && is_digit(s[i]); i++) { any = 1; dec_push(&dec, s[i] - '0', 1); }
    if (i < len && s[i] == '.') {
        if (!any && !(i + 1 < len && is_digit(s[i + 1]))) return 0;
        for (i++; i < len && is_digit(s[i]); i++) { any = 1; dec_push(&dec, s[i] - '0', 0); }
    }
    if (!any) return 0;
    if (i < len && (s[i] == 'e' || s[i] == 'E')) {
        size_t j = i + 1;
        int eneg = 0;
        int32_t ex = 0;
        if (j < len && (s[j] == '+' || s[j] == '-')) { eneg = s[j] == '-'; j++; }
        if (j < len && is_digit(s[j])) {
            for (; j < len && is_digit(s[j]); j++)
                if (ex < DEC_POINT_LIMIT) ex = ex * 10 + (s[j] - '0');
            dec.point += eneg ? -ex : ex;
            i = j;
        }
    }
    r = dec_to_real(&dec, &ovf);
    if (overflow) *overflow = ovf;
    if (out) *out = neg ? tg_neg(r) : r;
    return i;
}
