/* rt_march.c: marching 8 rays at once against one shape (certified sphere tracing, regula falsi, bracketing fallback). */
#include "rt_int.h"

#include <math.h>
#include <string.h>
#ifdef __AVX__
#include <immintrin.h>
#include "rt_points8.h"
#endif

enum { M_MARCH = 0, M_BRACKET = 1, M_DONE = 2 };

static __attribute__((unused)) float minf(float a, float b) { return a < b ? a : b; }
static float maxf(float a, float b) { return a > b ? a : b; }

/* 8 lanes in vector registers (gcc's vector extensions: AVX2 and AVX-512 alike, without relying
 * on the auto-vectoriser's if-conversion). Masks are all-ones or zero per lane. */
typedef float vf8 __attribute__((vector_size(32)));
typedef int vi8 __attribute__((vector_size(32)));

/* The helpers are macros, not functions: without AVX, gcc notes at every function that takes or
 * returns a 32-byte vector that its ABI changed (a pragma does not silence the note). Their
 * arguments are plain expressions without side effects. Unaligned loads and stores of 8 lanes: */
typedef float vf8u __attribute__((vector_size(32), aligned(4), may_alias));
typedef int vi8u __attribute__((vector_size(32), aligned(4), may_alias));
#define ldf(p) ((vf8) * (const vf8u *)(p))
#define ldi(p) ((vi8) * (const vi8u *)(p))
#define stf(p, v) (*(vf8u *)(p) = (v))
#define sti(p, v) (*(vi8u *)(p) = (v))
/* m ? a : b lane by lane (m all ones or zero) */
#define self(m, a, b) ((vf8)(((vi8)(a) & (m)) | ((vi8)(b) & ~(m))))
#define seli(m, a, b) (((a) & (m)) | ((b) & ~(m)))
/* maxf and minf lane by lane (a NaN gives b, as there): with AVX one MAXPS/MINPS each (hmax, hmin
 * below), which are exactly a > b ? a : b and a < b ? a : b */
#ifdef __AVX__
#define vmax(a, b) hmax(a, b)
#define vmin(a, b) hmin(a, b)
#else
#define vmax(a, b) self((a) > (b), (a), (b))
#define vmin(a, b) self((a) < (b), (a), (b))
#endif
#define vabs(a) ((vf8)((vi8)(a) & 0x7fffffff))
#define splat(x) ((vf8){(x), (x), (x), (x), (x), (x), (x), (x)})
#define spliti(x) ((vi8){(x), (x), (x), (x), (x), (x), (x), (x)})

#ifdef __AVX__
/* maxf and minf lane by lane in one instruction each: MAXPS(a, b) is a > b ? a : b and MINPS(a, b)
 * is a < b ? a : b (b when either is NaN), the same as vmax and vmin */
#define hmax(a, b) ((vf8)_mm256_max_ps((__m256)(a), (__m256)(b)))
#define hmin(a, b) ((vf8)_mm256_min_ps((__m256)(a), (__m256)(b)))

/* Clip the rays to the object's region (box and, if bounded, sphere): [a, b] per lane, empty when
 * a > b; on[k] = 1 when the entry a lies on the bounding sphere. Eight lanes at a time in vector
 * registers (gcc left the loop scalar), the same float operations lane by lane. */
static void clip8(const model_shape_t *s, const rt_packet_t *pk, float *restrict a, float *restrict b,
                  float *restrict on)
{
	const float bx0 = (float)s->box[0], by0 = (float)s->box[1], bz0 = (float)s->box[2];
	const float bx1 = (float)s->box[3], by1 = (float)s->box[4], bz1 = (float)s->box[5];
	const float cx = (float)s->centre[0], cy = (float)s->centre[1], cz = (float)s->centre[2];
	const float r2 = s->bounded ? (float)(s->radius * s->radius) : 0.0f;
	const int sph = s->bounded != 0;
	for (int k = 0; k < RT_LANES; k += 8) {
		vf8 OX = ldf(pk->ox + k), OY = ldf(pk->oy + k), OZ = ldf(pk->oz + k);
		vf8 DX = ldf(pk->dx + k), DY = ldf(pk->dy + k), DZ = ldf(pk->dz + k);
		vf8 lo = ldf(pk->tmin + k), hi = ldf(pk->tmax + k);
		vf8 ix = 1.0f / DX, iy = 1.0f / DY, iz = 1.0f / DZ;
		vf8 u0 = (bx0 - OX) * ix, u1 = (bx1 - OX) * ix;
		vf8 v0 = (by0 - OY) * iy, v1 = (by1 - OY) * iy;
		vf8 w0 = (bz0 - OZ) * iz, w1 = (bz1 - OZ) * iz;
		lo = hmax(lo, hmin(u0, u1));
		hi = hmin(hi, hmax(u0, u1));
		lo = hmax(lo, hmin(v0, v1));
		hi = hmin(hi, hmax(v0, v1));
		lo = hmax(lo, hmin(w0, w1));
		hi = hmin(hi, hmax(w0, w1));
		if (sph) {
			vf8 ox = OX - cx, oy = OY - cy, oz = OZ - cz;
			vf8 bb = ox * DX + oy * DY + oz * DZ;
			vf8 disc = bb * bb - (ox * ox + oy * oy + oz * oz - r2);
			vf8 q = (vf8)_mm256_sqrt_ps((__m256)hmax(disc, splat(0.0f)));
			vi8 in = disc >= 0.0f;
			vf8 slo = self(in, -bb - q, splat(INFINITY)), shi = self(in, -bb + q, splat(-INFINITY));
			stf(on + k, self(slo >= lo, splat(1.0f), splat(0.0f)));
			lo = hmax(lo, slo);
			hi = hmin(hi, shi);
		} else {
			stf(on + k, splat(0.0f));
		}
		/* NaN (a zero direction component with the origin on a slab face) counts as empty */
		stf(a + k, self(lo == lo, lo, splat(INFINITY)));
		stf(b + k, self(hi == hi, hi, splat(-INFINITY)));
	}
}
#else
/* Clip the 8 rays to the object's region (box and, if bounded, sphere):
 * [a, b] per lane, empty when a > b; on[k] = 1 when the entry a lies on the
 * bounding sphere. Branch-free so that it vectorises. */
static void clip8(const model_shape_t *s, const rt_packet_t *pk, float *restrict a, float *restrict b,
                  float *restrict on)
{
	const float bx0 = (float)s->box[0], by0 = (float)s->box[1], bz0 = (float)s->box[2];
	const float bx1 = (float)s->box[3], by1 = (float)s->box[4], bz1 = (float)s->box[5];
	const float cx = (float)s->centre[0], cy = (float)s->centre[1], cz = (float)s->centre[2];
	const float r2 = s->bounded ? (float)(s->radius * s->radius) : 0.0f, sph = s->bounded ? 1.0f : 0.0f;
	for (int k = 0; k < RT_LANES; k++) {
		float lo = pk->tmin[k], hi = pk->tmax[k];
		float ix = 1.0f / pk->dx[k], iy = 1.0f / pk->dy[k], iz = 1.0f / pk->dz[k];
		float u0 = (bx0 - pk->ox[k]) * ix, u1 = (bx1 - pk->ox[k]) * ix;
		float v0 = (by0 - pk->oy[k]) * iy, v1 = (by1 - pk->oy[k]) * iy;
		float w0 = (bz0 - pk->oz[k]) * iz, w1 = (bz1 - pk->oz[k]) * iz;
		lo = maxf(lo, minf(u0, u1));
		hi = minf(hi, maxf(u0, u1));
		lo = maxf(lo, minf(v0, v1));
		hi = minf(hi, maxf(v0, v1));
		lo = maxf(lo, minf(w0, w1));
		hi = minf(hi, maxf(w0, w1));
		float ox = pk->ox[k] - cx, oy = pk->oy[k] - cy, oz = pk->oz[k] - cz;
		float bb = ox * pk->dx[k] + oy * pk->dy[k] + oz * pk->dz[k];
		float disc = bb * bb - (ox * ox + oy * oy + oz * oz - r2);
		float q = sqrtf(maxf(disc, 0.0f));
		float slo = disc >= 0.0f ? -bb - q : INFINITY, shi = disc >= 0.0f ? -bb + q : -INFINITY;
		on[k] = sph > 0 && slo >= lo ? 1.0f : 0.0f;
		lo = sph > 0 ? maxf(lo, slo) : lo;
		hi = sph > 0 ? minf(hi, shi) : hi;
		/* NaN (a zero direction component with the origin on a slab face) counts as empty */
		a[k] = lo == lo ? lo : INFINITY;
		b[k] = hi == hi ? hi : -INFINITY;
	}
}

#endif

/* 1 when one of the 8 lanes from mode is bracketing. */
static inline int bracketing8(const int *mode)
{
#ifdef __AVX__
	return _mm256_movemask_ps((__m256)(ldi(mode) == M_BRACKET)) != 0;
#else
	int b = 0;
	for (int k = 0; k < 8; k++)
		b |= mode[k] == M_BRACKET;
	return b;
#endif
}

/* The number of the 8 lanes from mode that are not done. */
static inline int live8(const int *mode)
{
#ifdef __AVX__
	return __builtin_popcount((unsigned)_mm256_movemask_ps((__m256)(ldi(mode) != M_DONE)));
#else
	int n = 0;
	for (int k = 0; k < 8; k++)
		n += mode[k] != M_DONE;
	return n;
#endif
}

/* The update of 8 lanes after one evaluation (their modes, states, hits), the same float
 * operations lane by lane as the scalar rules in rt.h. Inlined into one copy per (nolip,
 * shadow, strict) the marcher uses, so that the masks of the other cases fold away. */
static inline __attribute__((always_inline)) void
update8(int *restrict mode, float *restrict t, float *restrict f, float *restrict s,
        float *restrict lo, float *restrict flo, float *restrict hi, float *restrict fhi,
        float *restrict side, float *restrict hit, const float *restrict u,
        const float *restrict val, const float *restrict fa, const float *restrict fb,
        const float *restrict t1, const float *restrict smin, float L, float invL,
        int nolip, float acc, float step, int shadow, int strict, int brk)
{
	const float Lv = nolip ? 1.0f : L, capk = strict ? 1.5f : 16.0f;
	const vi8 ones = spliti(-1), zero = spliti(0);
	vf8 uk = ldf(u), v = ldf(val), F = ldf(f), S = ldf(s), T = ldf(t);
	vf8 LO = ldf(lo), FLO = ldf(flo), HI = ldf(hi), FHI = ldf(fhi), SD = ldf(side);
	vi8 md = ldi(mode);
	vf8 fp = ldf(fa) + ldf(fb) * uk, emin = 0.05f * fp;
	/* the tolerance never goes below what float positions can resolve */
	vf8 eps = vmax(acc * fp, 2e-6f * (vabs(uk) + 1.0f));
	v = self(v == v, v, emin * Lv);
	/* brk 0: no lane is bracketing (a shadow ray never does), and the bracket rules fold away */
	vi8 inm = md == M_MARCH, inb = brk ? md == M_BRACKET : zero;
	/* march */
	vi8 beyond = uk >= ldf(t1);  /* the sample is at the region's exit */
	vi8 cross_raw = v <= 0.0f;
	vi8 c1 = (F + v) * invL >= S * 0.999999f;
	vi8 c2 = S <= emin * 1.0001f;
	vi8 cert = nolip ? ones : c1 | c2;
	/* strict: a sign change counts only when the ball outside at t and the ball inside at
	 * the sample overlap (one crossing between them); a long proposal that lands inside
	 * past a thin gap is rejected like an uncertified step */
	vi8 cross_ok = !strict || shadow || nolip ? ones : ((F - v) * invL >= S * 0.999999f - emin) | c2;
	vi8 cross = cross_raw & cross_ok;
	/* slope m = (v - f)/s; secant step -1.05 v/m when falling, the largest step two
	 * overlapping balls allow, 2 * 0.9 v/(L - m), when rising: one division */
	vf8 dv = v - F;
	vf8 den = self(dv < 0.0f, -dv * (1.0f / 1.05f), (L * S - dv) * (1.0f / 1.8f));
	vf8 safe = v * invL;
	vf8 sg = self(den > 0.0f, v * S / den, safe);
	/* a distance estimate is not Lipschitz: its slope says little about the next ball, so
	 * a rising ray grows its step by at most 1.5x */
	sg = vmax(vmax(safe, vmin(sg, capk * safe)), emin);
	if (nolip)
		sg = vmax(step * fp, ldf(smin));
	vf8 rej = vmax(F * invL, emin);
	vi8 m_brk = shadow ? zero : inm & cross;   /* march -> bracket */
	vi8 m_shd = shadow ? inm & cross : zero;   /* shadow ray blocked */
	vi8 m_out = inm & ~cross_raw & beyond & cert;    /* certified to the exit: a miss */
	vi8 m_acc = inm & ~cross_raw & ~beyond & cert;   /* step accepted */
	vi8 m_rej = inm & ~cross & ~(~cross_raw & cert);
	/* bracket */
	vi8 conv = (vabs(v) < eps * Lv) | (HI - LO < eps);
	vi8 pos = v > 0.0f;
	vi8 b_hit = inb & conv;
	vi8 b_lo = inb & ~conv & pos, b_hi = inb & ~conv & ~pos;
	/* new state */
	vf8 nlo = self(m_brk, T, self(b_lo, uk, LO));
	vf8 nflo = self(m_brk, F, self(b_lo, v, self(b_hi & (SD < 0.0f), 0.5f * FLO, FLO)));
	vf8 nhi = self(m_brk | b_hi, uk, HI);
	vf8 nfhi = self(m_brk | b_hi, v, self(b_lo & (SD > 0.0f), 0.5f * FHI, FHI));
	stf(side, self(m_brk, splat(0.0f), self(b_lo, splat(1.0f), self(b_hi, splat(-1.0f), SD))));
	stf(lo, nlo);
	stf(flo, nflo);
	stf(hi, nhi);
	stf(fhi, nfhi);
	vi8 narrow = inb & ~b_hit & (nhi - nlo < eps);
	stf(hit, self(m_shd | b_hit, uk, self(narrow, 0.5f * (nlo + nhi), ldf(hit))));
	stf(t, self(m_acc, uk, T));
	stf(f, self(m_acc, v, F));
	stf(s, self(m_acc, sg, self(m_rej, rej, S)));
	vi8 done = m_shd | m_out | b_hit | narrow;
	sti(mode, seli(done, spliti(M_DONE), seli(m_brk, spliti(M_BRACKET), md)));
}

/* The next sample of 8 lanes: regula falsi in a bracket, else the proposed step (never past
 * the exit); the point in x, y, z (x NaN for a done lane of a distance estimate: model_de8
 * skips it, its value is not used). */
static inline void propose8(const rt_packet_t *pk, int g, const int *mode, const float *t, const float *st,
                            const float *lo, const float *flo, const float *hi, const float *fhi, const float *t1,
                            float *u, float *x, float *y, float *z, int de, int brk)
{
	vi8 md = ldi(mode + g);
	vf8 U = vmin(ldf(t + g) + ldf(st + g), ldf(t1 + g));
	if (brk) {   /* some lane is bracketing */
		vf8 LO = ldf(lo + g), HI = ldf(hi + g), FLO = ldf(flo + g), FHI = ldf(fhi + g);
		vf8 rf = LO + (HI - LO) * FLO / (FLO - FHI);
		rf = self((rf > LO) & (rf < HI), rf, 0.5f * (LO + HI));
		U = self(md == M_BRACKET, rf, U);
	}
	stf(u + g, U);
	vf8 X = ldf(pk->ox + g) + U * ldf(pk->dx + g);
	if (de)
		X = self(md == M_DONE, splat(NAN), X);
	stf(x + g, X);
	stf(y + g, ldf(pk->oy + g) + U * ldf(pk->dy + g));
	stf(z + g, ldf(pk->oz + g) + U * ldf(pk->dz + g));
}

#ifdef __AVX__
/* The march of a points-and-segments shape (s->fast_points, a Lipschitz bound, no distance
 * estimate) with each group of 8 lanes' state in vector registers and the kernel inlined: the
 * general loop below keeps its state in arrays and goes through them and model_eval8's call at
 * every step. The same operations in the same order lane by lane as propose8, model_eval8 and
 * update8 (nolip 0, strict 0), so the same bits. */
typedef struct {
	vf8 t, f, s, lo, flo, hi, fhi, side, hit, t1, sgn, fa, fb, ox, oy, oz, dx, dy, dz;
	vi8 md;
} grp_t;

static inline __attribute__((always_inline)) void
update_fast(grp_t *G, vf8 uk, vf8 v, float L, float invL, float acc, int shadow, int brk)
{
	const float Lv = L, capk = 16.0f;
	const vi8 ones = spliti(-1), zero = spliti(0);
	vf8 F = G->f, S = G->s, T = G->t;
	vf8 LO = G->lo, FLO = G->flo, HI = G->hi, FHI = G->fhi, SD = G->side;
	vi8 md = G->md;
	vf8 fp = G->fa + G->fb * uk, emin = 0.05f * fp;
	vf8 eps = hmax(acc * fp, 2e-6f * (vabs(uk) + 1.0f));
	v = self(v == v, v, emin * Lv);
	vi8 inm = md == M_MARCH, inb = brk ? md == M_BRACKET : zero;
	vi8 beyond = uk >= G->t1;
	vi8 cross_raw = v <= 0.0f;
	vi8 c1 = (F + v) * invL >= S * 0.999999f;
	vi8 c2 = S <= emin * 1.0001f;
	vi8 cert = c1 | c2;
	vi8 cross_ok = ones;
	vi8 cross = cross_raw & cross_ok;
	vf8 dv = v - F;
	vf8 den = self(dv < 0.0f, -dv * (1.0f / 1.05f), (L * S - dv) * (1.0f / 1.8f));
	vf8 safe = v * invL;
	vf8 sg = self(den > 0.0f, v * S / den, safe);
	sg = hmax(hmax(safe, hmin(sg, capk * safe)), emin);
	vf8 rej = hmax(F * invL, emin);
	vi8 m_brk = shadow ? zero : inm & cross;
	vi8 m_shd = shadow ? inm & cross : zero;
	vi8 m_out = inm & ~cross_raw & beyond & cert;
	vi8 m_acc = inm & ~cross_raw & ~beyond & cert;
	vi8 m_rej = inm & ~cross & ~(~cross_raw & cert);
	vi8 conv = (vabs(v) < eps * Lv) | (HI - LO < eps);
	vi8 pos = v > 0.0f;
	vi8 b_hit = inb & conv;
	vi8 b_lo = inb & ~conv & pos, b_hi = inb & ~conv & ~pos;
	vf8 nlo = self(m_brk, T, self(b_lo, uk, LO));
	vf8 nflo = self(m_brk, F, self(b_lo, v, self(b_hi & (SD < 0.0f), 0.5f * FLO, FLO)));
	vf8 nhi = self(m_brk | b_hi, uk, HI);
	vf8 nfhi = self(m_brk | b_hi, v, self(b_lo & (SD > 0.0f), 0.5f * FHI, FHI));
	G->side = self(m_brk, splat(0.0f), self(b_lo, splat(1.0f), self(b_hi, splat(-1.0f), SD)));
	G->lo = nlo;
	G->flo = nflo;
	G->hi = nhi;
	G->fhi = nfhi;
	vi8 narrow = inb & ~b_hit & (nhi - nlo < eps);
	G->hit = self(m_shd | b_hit, uk, self(narrow, 0.5f * (nlo + nhi), G->hit));
	G->t = self(m_acc, uk, T);
	G->f = self(m_acc, v, F);
	G->s = self(m_acc, sg, self(m_rej, rej, S));
	vi8 done = m_shd | m_out | b_hit | narrow;
	G->md = seli(done, spliti(M_DONE), seli(m_brk, spliti(M_BRACKET), md));
}

/* One step of a group: propose, evaluate, update; returns the mask of its lanes still live. */
static inline __attribute__((always_inline)) unsigned
step_fast(const model_shape_t *s, grp_t *G, float L, float invL, float acc, int shadow)
{
	int brk = !shadow && _mm256_movemask_ps((__m256)(G->md == M_BRACKET)) != 0;
	vf8 U = hmin(G->t + G->s, G->t1);
	if (brk) {
		vf8 LO = G->lo, HI = G->hi, FLO = G->flo, FHI = G->fhi;
		vf8 rf = LO + (HI - LO) * FLO / (FLO - FHI);
		rf = self((rf > LO) & (rf < HI), rf, 0.5f * (LO + HI));
		U = self(G->md == M_BRACKET, rf, U);
	}
	vf8 v = rt_points8v(s, G->ox + U * G->dx, G->oy + U * G->dy, G->oz + U * G->dz);
	v = v * G->sgn;
	if (shadow)
		update_fast(G, U, v, L, invL, acc, 1, 0);
	else if (brk)
		update_fast(G, U, v, L, invL, acc, 0, 1);
	else
		update_fast(G, U, v, L, invL, acc, 0, 0);
	return (unsigned)_mm256_movemask_ps((__m256)(G->md != M_DONE));
}

static inline __attribute__((always_inline)) void
load_grp(grp_t *G, const rt_packet_t *pk, int g, const int *mode, const float *t, const float *f, const float *st,
         const float *t1, const float *sgn)
{
	G->md = ldi(mode + g);
	G->t = ldf(t + g);
	G->f = ldf(f + g);
	G->s = ldf(st + g);
	G->lo = G->flo = G->hi = G->fhi = G->side = splat(0.0f);
	G->hit = ldf(pk->thit + g);
	G->t1 = ldf(t1 + g);
	G->sgn = ldf(sgn + g);
	G->fa = ldf(pk->fa + g);
	G->fb = ldf(pk->fb + g);
	G->ox = ldf(pk->ox + g);
	G->oy = ldf(pk->oy + g);
	G->oz = ldf(pk->oz + g);
	G->dx = ldf(pk->dx + g);
	G->dy = ldf(pk->dy + g);
	G->dz = ldf(pk->dz + g);
}

/* Both groups stepped together while both are live, then the one left alone; inlined once for
 * shadow rays and once for primary ones, so that step_fast sees shadow as a constant. */
static inline __attribute__((always_inline)) void
step_pair(const model_shape_t *s, grp_t *A, grp_t *B, unsigned la, unsigned lb, float L, float invL, float acc,
          int shadow, uint64_t *evp, uint64_t *lnp)
{
	int iter = 0;
	uint64_t ev = 0, ln = 0;
	while (la && lb && iter < 4000) {
		iter++;
		ev += (unsigned)__builtin_popcount(la) + (unsigned)__builtin_popcount(lb);
		ln += 16;
		la = step_fast(s, A, L, invL, acc, shadow);
		lb = step_fast(s, B, L, invL, acc, shadow);
	}
	for (; la && iter < 4000; iter++, ln += 8) {
		ev += (unsigned)__builtin_popcount(la);
		la = step_fast(s, A, L, invL, acc, shadow);
	}
	for (; lb && iter < 4000; iter++, ln += 8) {
		ev += (unsigned)__builtin_popcount(lb);
		lb = step_fast(s, B, L, invL, acc, shadow);
	}
	*evp += ev;
	*lnp += ln;
}

/* The march loop of rt_march8 for such a shape: both groups stepped together while both are live
 * (their dependency chains overlap), then the one left alone; the same steps, the same count. */
static void march_fast(const model_shape_t *s, rt_packet_t *pk, int shadow, const int *mode, const float *t,
                       const float *f, const float *st, const float *t1, const float *sgn, float L, float invL,
                       uint64_t *evals, uint64_t *lanes)
{
	_Static_assert(RT_LANES == 16, "march_fast marches two groups of 8");
	grp_t A, B;
	const float acc = pk->acc;
	load_grp(&A, pk, 0, mode, t, f, st, t1, sgn);
	load_grp(&B, pk, 8, mode, t, f, st, t1, sgn);
	unsigned la = (unsigned)_mm256_movemask_ps((__m256)(A.md != M_DONE));
	unsigned lb = (unsigned)_mm256_movemask_ps((__m256)(B.md != M_DONE));
	uint64_t ev = 0, ln = 0;
	if (shadow)
		step_pair(s, &A, &B, la, lb, L, invL, acc, 1, &ev, &ln);
	else
		step_pair(s, &A, &B, la, lb, L, invL, acc, 0, &ev, &ln);
	*evals += ev;
	*lanes += ln;
	stf(pk->thit, A.hit);
	stf(pk->thit + 8, B.hit);
}
#endif

void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes)
{
	int mode[RT_LANES];
	float t[RT_LANES], f[RT_LANES], st[RT_LANES], lo[RT_LANES], flo[RT_LANES], hi[RT_LANES], fhi[RT_LANES], side[RT_LANES], u[RT_LANES], t1[RT_LANES];
	float x[RT_LANES], y[RT_LANES], z[RT_LANES], val[RT_LANES];
	float L = (float)rt_bound(s), invL = L > 0 ? 1.0f / L : 0.0f;
	const int nolip = !(L > 0), de = s->de != 0;
	int n = 0;
	for (int k = 0; k < RT_LANES; k++)
		n += pk->active[k] && pk->tmin[k] < INFINITY;
	if (!n) {   /* nothing to march (e.g. a cone found the object out of reach) */
		for (int k = 0; k < RT_LANES; k++)
			pk->thit[k] = INFINITY;
		return;
	}
	n = 0;
	float ca[RT_LANES], cb[RT_LANES], con[RT_LANES], sgn[RT_LANES], smin[RT_LANES];
	for (int k = 0; k < RT_LANES; k++)
		sgn[k] = 1;
	clip8(s, pk, ca, cb, con);
	for (int k = 0; k < RT_LANES; k++) {
		pk->thit[k] = INFINITY;
		pk->side[k] = 0;
		mode[k] = M_DONE;
		t[k] = f[k] = st[k] = lo[k] = flo[k] = hi[k] = fhi[k] = side[k] = 0;
		t1[k] = 0;
		u[k] = 0;
		smin[k] = 0;
		if (!pk->active[k])
			continue;
		if (!(ca[k] <= cb[k]))
			continue;
		mode[k] = M_MARCH;
		u[k] = ca[k];
		t1[k] = cb[k];
		n++;
	}
	if (!n)
		return;
	/* first sample at the region entry (a group of 8 lanes that are all done is not evaluated) */
	for (int g = 0; g < RT_LANES; g += 8) {
		int busy = 0;
		for (int k = g; k < g + 8; k++) {
			x[k] = pk->ox[k] + u[k] * pk->dx[k];
			y[k] = pk->oy[k] + u[k] * pk->dy[k];
			z[k] = pk->oz[k] + u[k] * pk->dz[k];
			if (de && mode[k] == M_DONE)
				x[k] = NAN;
			busy |= mode[k] != M_DONE;
		}
		if (busy) {
#ifdef __AVX__
			if (s->fast_points && !de)   /* the kernel inline, the same bits */
				stf(val + g, rt_points8v(s, ldf(x + g), ldf(y + g), ldf(z + g)));
			else
#endif
				rt_eval8(s, x + g, y + g, z + g, val + g);
			*lanes += 8;
		}
	}
	*evals += (uint64_t)n;
	for (int k = 0; k < RT_LANES; k++) {
		if (mode[k] != M_MARCH)
			continue;
		float fp = pk->fa[k] + pk->fb[k] * u[k], emin = 0.05f * fp, v = val[k];
		/* a ray that enters the region inside the solid looks for the surface as the
		 * sign change from negative to positive: march on -f. One that enters it on
		 * the surface (within the hit tolerance), or inside the solid through the
		 * bounding sphere (which holds the whole solid, so the two touch there: when
		 * the sphere is tight, as for a sphere, float rounding of the entry near the
		 * rim lands inside), hits there. */
		float eps = maxf(pk->acc * fp, 2e-6f * (fabsf(u[k]) + 1.0f));
		int touch = v < 0 && con[k] > 0;
		sgn[k] = v < 0 ? -1.0f : 1.0f;
		v *= sgn[k];
		if (v == v && (touch || v <= eps * (L > 0 ? L : 1.0f))) {
			pk->thit[k] = u[k];
			pk->side[k] = touch ? 1.0f : 0.0f;   /* touching the bounding sphere: entered from outside */
			mode[k] = M_DONE;
			n--;
			continue;
		}
		if (v != v)
			v = emin * (L > 0 ? L : 1);
		t[k] = u[k];
		f[k] = v;
		/* bracketing: at most about 1000 steps through the region, whatever its depth */
		smin[k] = (t1[k] - u[k]) * 1e-3f;
		st[k] = L > 0 ? maxf(v * invL, emin) : maxf(pk->step * fp, smin[k]);
	}
	int iter = 0;
	for (int k = 0; k < RT_LANES; k++)
		if (mode[k] == M_MARCH)
			pk->side[k] = sgn[k];
#ifdef __AVX__
	if (s->fast_points && !nolip && !de) {
		march_fast(s, pk, shadow, mode, t, f, st, t1, sgn, L, invL, evals, lanes);
		return;
	}
#endif
	while (n > 0 && iter++ < 4000) {
		int busy[RT_LANES / 8], brk[RT_LANES / 8];
		for (int g = 0; g < RT_LANES; g += 8) {
			/* a group of 8 lanes whose rays are all done is neither evaluated nor updated */
			busy[g / 8] = live8(mode + g) > 0;
			if (!busy[g / 8])
				continue;
			brk[g / 8] = !shadow && bracketing8(mode + g);
			propose8(pk, g, mode, t, st, lo, flo, hi, fhi, t1, u, x, y, z, de, brk[g / 8]);
			rt_eval8(s, x + g, y + g, z + g, val + g);
			*lanes += 8;
		}
		*evals += (uint64_t)n;
		n = 0;
		for (int g = 0; g < RT_LANES; g += 8) {
			if (!busy[g / 8])
				continue;
			stf(val + g, ldf(val + g) * ldf(sgn + g));
#define RT_UPDATE8(NOLIP, SHADOW, STRICT, BRK) \
	update8(mode + g, t + g, f + g, st + g, lo + g, flo + g, hi + g, fhi + g, side + g, pk->thit + g, u + g, \
	        val + g, pk->fa + g, pk->fb + g, t1 + g, smin + g, L, invL, NOLIP, pk->acc, pk->step, SHADOW, STRICT, BRK)
			/* one copy for each common case (a Lipschitz bound or a distance estimate; a shadow
			 * ray, a primary one with or without lanes in a bracket), the general one for the
			 * bracketing fallback */
			int b = brk[g / 8];
			if (nolip)
				RT_UPDATE8(1, shadow != 0, de, b);
			else if (de)
				shadow ? RT_UPDATE8(0, 1, 1, 0) : b ? RT_UPDATE8(0, 0, 1, 1) : RT_UPDATE8(0, 0, 1, 0);
			else
				shadow ? RT_UPDATE8(0, 1, 0, 0) : b ? RT_UPDATE8(0, 0, 0, 1) : RT_UPDATE8(0, 0, 0, 0);
#undef RT_UPDATE8
			n += live8(mode + g);
		}
	}
}
