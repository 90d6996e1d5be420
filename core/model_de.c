/* model_de.c: the Douady-Hubbard distance estimate of a smooth Mandelbrot or Julia shape, 8 lanes at a time. */
#include "model.h"

#include <math.h>
#include <stdint.h>
#include <string.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#define DE_LANES 8

/* The escape iteration of nl <= 8 setup-frame points at once (structure of arrays, double):
 * Mandelbrot z <- z^2 + p from z = 0, Julia z <- z^2 + k from z = p, with dz/dp. Every lane
 * does the scalar iteration's arithmetic in the same order (so one lane alone gives the same
 * bits as eight); a lane that has escaped (|z|^2 > bail) or is NaN keeps its values while the
 * others go on. pw = 2^n. */
static void de_iterate(const model_param_t *c, const double *restrict pr, const double *restrict pi,
                       double *restrict zr, double *restrict zi, double *restrict dr, double *restrict di,
                       double *restrict n, double *restrict pw, double bail)
{
	const double jl = c->julia ? 1.0 : 0.0, one = c->julia ? 0.0 : 1.0;
	double kr[DE_LANES], ki[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		zr[k] = jl > 0 ? pr[k] : 0.0;
		zi[k] = jl > 0 ? pi[k] : 0.0;
		dr[k] = jl;
		di[k] = 0.0;
		kr[k] = jl > 0 ? c->k[0] : pr[k];
		ki[k] = jl > 0 ? c->k[1] : pi[k];
		n[k] = 0.0;
		pw[k] = 1.0;
	}
#if defined(__AVX512F__) && DE_LANES == 8
	/* the eight lanes in one 512-bit register each; the lanes that go on are kept by a mask
	 * register: one masked move a value, and the loop ends when the mask is empty (a kmov and a
	 * test, where the vector code below ORs its lanes down with a chain of shuffles). The
	 * arithmetic is the scalar expressions' in the same order (no fused multiply-add), so the
	 * bits are the same */
	{
		__m512d vzr = _mm512_loadu_pd(zr), vzi = _mm512_loadu_pd(zi), vdr = _mm512_loadu_pd(dr),
		        vdi = _mm512_loadu_pd(di), vkr = _mm512_loadu_pd(kr), vki = _mm512_loadu_pd(ki),
		        vn = _mm512_loadu_pd(n), vpw = _mm512_loadu_pd(pw);
		const __m512d two = _mm512_set1_pd(2.0), vone = _mm512_set1_pd(one), vb = _mm512_set1_pd(bail),
		              unit = _mm512_set1_pd(1.0);
		for (int it = 0; it < c->maxit; it++) {
			__m512d a = _mm512_add_pd(_mm512_mul_pd(vzr, vzr), _mm512_mul_pd(vzi, vzi));
			__mmask8 go = _mm512_cmp_pd_mask(a, vb, _CMP_LE_OQ);
			if (!go)
				break;
			__m512d ndr = _mm512_add_pd(_mm512_mul_pd(two, _mm512_sub_pd(_mm512_mul_pd(vzr, vdr), _mm512_mul_pd(vzi, vdi))), vone);
			__m512d ndi = _mm512_mul_pd(two, _mm512_add_pd(_mm512_mul_pd(vzr, vdi), _mm512_mul_pd(vzi, vdr)));
			__m512d nzr = _mm512_add_pd(_mm512_sub_pd(_mm512_mul_pd(vzr, vzr), _mm512_mul_pd(vzi, vzi)), vkr);
			__m512d nzi = _mm512_add_pd(_mm512_mul_pd(_mm512_mul_pd(two, vzr), vzi), vki);
			vdr = _mm512_mask_mov_pd(vdr, go, ndr);
			vdi = _mm512_mask_mov_pd(vdi, go, ndi);
			vzr = _mm512_mask_mov_pd(vzr, go, nzr);
			vzi = _mm512_mask_mov_pd(vzi, go, nzi);
			vn = _mm512_mask_add_pd(vn, go, vn, unit);
			vpw = _mm512_mask_mul_pd(vpw, go, vpw, two);
		}
		_mm512_storeu_pd(zr, vzr);
		_mm512_storeu_pd(zi, vzi);
		_mm512_storeu_pd(dr, vdr);
		_mm512_storeu_pd(di, vdi);
		_mm512_storeu_pd(n, vn);
		_mm512_storeu_pd(pw, vpw);
		return;
	}
#endif
	/* the lanes as one vector (GCC/Clang vector extension) so that the state stays in registers
	 * through the iteration; each lane's arithmetic is the scalar expression's */
	typedef double v8 __attribute__((vector_size(DE_LANES * sizeof(double))));
	typedef long long m8 __attribute__((vector_size(DE_LANES * sizeof(double))));
	v8 vzr, vzi, vdr, vdi, vn, vpw, vkr, vki;
	memcpy(&vzr, zr, sizeof vzr);
	memcpy(&vzi, zi, sizeof vzi);
	memcpy(&vdr, dr, sizeof vdr);
	memcpy(&vdi, di, sizeof vdi);
	memcpy(&vkr, kr, sizeof vkr);
	memcpy(&vki, ki, sizeof vki);
	memcpy(&vn, n, sizeof vn);
	memcpy(&vpw, pw, sizeof vpw);
	for (int it = 0; it < c->maxit; it++) {
		v8 a = vzr * vzr + vzi * vzi;
		m8 go = a <= bail;   /* -1 where the lane goes on */
		v8 ndr = 2 * (vzr * vdr - vzi * vdi) + one;
		v8 ndi = 2 * (vzr * vdi + vzi * vdr);
		v8 nzr = vzr * vzr - vzi * vzi + vkr;
		v8 nzi = 2 * vzr * vzi + vki;
#define DE_SEL(m, a, b) ((v8)(((m8)(a) & (m)) | ((m8)(b) & ~(m))))
		vdr = DE_SEL(go, ndr, vdr);
		vdi = DE_SEL(go, ndi, vdi);
		vzr = DE_SEL(go, nzr, vzr);
		vzi = DE_SEL(go, nzi, vzi);
		vn = DE_SEL(go, vn + 1.0, vn);
		vpw = DE_SEL(go, vpw * 2.0, vpw);   /* 2^n exactly (infinite past 2^1023, as ldexp) */
#undef DE_SEL
		long long live = 0;
		for (int k = 0; k < DE_LANES; k++)
			live |= go[k];
		if (!live)
			break;
	}
	memcpy(zr, &vzr, sizeof vzr);
	memcpy(zi, &vzi, sizeof vzi);
	memcpy(dr, &vdr, sizeof vdr);
	memcpy(di, &vdi, sizeof vdi);
	memcpy(n, &vn, sizeof vn);
	memcpy(pw, &vpw, sizeof vpw);
}

/* ln x for a positive normal x, in arithmetic that vectorises (no call): x = m 2^e with m in
 * [sqrt(1/2), sqrt(2)), ln m = 2 atanh(f), f = (m - 1)/(m + 1), |f| < 0.172, by its series to
 * f^21 (remainder below 2e-17 of the value); within about 2 units in the last place of libm's. */
static inline double de_log(double x)
{
	uint64_t b;
	memcpy(&b, &x, sizeof b);
	uint64_t eb = (b >> 52) | 0x4330000000000000ull;   /* 2^52 + the biased exponent, as a double */
	b = (b & 0x000fffffffffffffull) | 0x3ff0000000000000ull;
	double m, e;
	memcpy(&m, &b, sizeof m);
	memcpy(&e, &eb, sizeof e);
	e -= 4503599627370496.0 + 1023.0;
	double big = m > 1.4142135623730951 ? 1.0 : 0.0;
	m *= 1.0 - 0.5 * big;   /* exact: m or m/2 */
	e += big;
	double f = (m - 1.0) / (m + 1.0), f2 = f * f;
	double p = ((((((((((1.0 / 21 * f2 + 1.0 / 19) * f2 + 1.0 / 17) * f2 + 1.0 / 15) * f2 + 1.0 / 13) * f2 + 1.0 / 11) * f2
	           + 1.0 / 9) * f2 + 1.0 / 7) * f2 + 1.0 / 5) * f2 + 1.0 / 3) * f2 + 1.0);
	return e * 6.93147180369123816490e-01 + (2.0 * f * p + e * 1.90821492927058770002e-10);
}

/* e^y in arithmetic that vectorises: y = n ln 2 + r, |r| <= ln2/2, e^r by its Taylor series to
 * r^13, scaled by 2^n through the exponent bits; 0 below -700 (e^-700 is 1e-304: against the 1
 * it is subtracted from, nothing). y <= 700. */
static inline double de_exp(double y)
{
	double lo = y < -700.0, yc = lo ? 0.0 : y;
	double t = yc * 1.44269504088896338700 + 6755399441055744.0;   /* round to nearest: 1.5 2^52 */
	double n = t - 6755399441055744.0;
	double r = (yc - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
	double p = ((((((((((((1.0 / 6227020800.0 * r + 1.0 / 479001600) * r + 1.0 / 39916800) * r + 1.0 / 3628800) * r
	           + 1.0 / 362880) * r + 1.0 / 40320) * r + 1.0 / 5040) * r + 1.0 / 720) * r + 1.0 / 120) * r + 1.0 / 24) * r
	           + 1.0 / 6) * r + 1.0 / 2) * r + 1.0) * r + 1.0;
	uint64_t sb = (uint64_t)((int64_t)n + 1023) << 52;
	double sc;
	memcpy(&sc, &sb, sizeof sc);
	return lo ? 0.0 : p * sc;
}

/* The estimates from the iteration's end (n escapes, n = maxit: none; pw = 2^n; z_n and
 * dz_n/dp), all lanes in branch-free arithmetic. */
#if defined(__AVX512F__) && DE_LANES == 8
__attribute__((unused))   /* de_finish8 below does its work */
#endif
static void de_finish(const model_shape_t *s, const double *restrict n, const double *restrict pw,
                      const double *restrict zr, const double *restrict zi, const double *restrict dr,
                      const double *restrict di, double *restrict out)
{
	const model_param_t *c = &s->c;
	const double sg = c->amp > 0 ? 1 : -1;   /* f > 0 (outside) where the potential is above the level */
	const double k = c->julia ? 1 : 2, maxit = c->maxit, none = -sg * 1e-3 * s->de_scale;
	const double G0 = k * 2.0 * exp2(-s->de_m0);   /* the level's potential */
	for (int j = 0; j < DE_LANES; j++) {
		/* potential G = lim 2^-n ln|z_n| (Julia), twice that for the Mandelbrot set (whose z_n
		 * is the Julia iterate of p one step late); |grad G| = |z_n'| / (|z_n| 2^n) likewise */
		double az2 = zr[j] * zr[j] + zi[j] * zi[j];
		double esc = (n[j] < maxit ? 1.0 : 0.0) * (az2 > 1.0 ? 1.0 : 0.0);   /* escaped (|z_n|^2 > 1e6); else no bound */
		double a = esc > 0 ? az2 : 2.0;
		double G = k * (0.5 * de_log(a)) / pw[j], dG = k * sqrt((dr[j] * dr[j] + di[j] * di[j]) / a) / pw[j];
		/* Koebe 1/4 on the Boettcher map's inverse: the disk of radius e^G - e^G0 about Phi(p)
		 * lies where the potential exceeds G0, so its image holds a disk of a quarter of that
		 * radius times |Phi^-1'| = 1/(e^G |grad G|) around p: the distance to the level set is
		 * at least (1 - e^(G0-G)) / (4 |grad G|); inside, the disk also has to keep out of the
		 * unit disk */
		double gc = G < 700.0 ? G : 700.0;
		double e1 = de_exp(G0 - gc), e2 = de_exp(-gc);
		double in = e1 - 1 < 1 - e2 ? e1 - 1 : 1 - e2;
		double d = (G >= G0 ? 1 - e1 : -in) / (4 * dG);
		double ok = esc * (dG > 0 ? 1.0 : 0.0) * (G - G == 0.0 ? 1.0 : 0.0);   /* G finite */
		out[j] = n[j] != n[j] ? NAN : ok > 0 ? sg * d * s->de_scale : none;
	}
}

#if defined(__AVX512F__)
/* de_finish with the 8 lanes in one 512-bit vector each (gcc vectorises the loop above in two
 * 256-bit halves): de_log's and de_exp's operations inline, lane by lane in the same order, so
 * the same bits. */
typedef double vd8 __attribute__((vector_size(64)));
typedef long long vl8 __attribute__((vector_size(64)));
typedef unsigned long long vu8 __attribute__((vector_size(64)));
#define DSEL8(m, a, b) ((vd8)(((vl8)(a) & (m)) | ((vl8)(b) & ~(m))))

/* e^Y into R (de_exp), Y a vd8 expression without side effects */
#define DE_EXP8(R, Y)                                                                                        \
	do {                                                                                                      \
		vd8 y_ = (Y);                                                                                         \
		vl8 lo_ = y_ < -700.0;                                                                               \
		vd8 yc_ = DSEL8(lo_, zero, y_);                                                                       \
		vd8 t_ = yc_ * 1.44269504088896338700 + 6755399441055744.0;                                         \
		vd8 n_ = t_ - 6755399441055744.0;                                                                    \
		vd8 r_ = (yc_ - n_ * 6.93147180369123816490e-01) - n_ * 1.90821492927058770002e-10;                \
		vd8 p_ = ((((((((((((1.0 / 6227020800.0 * r_ + 1.0 / 479001600) * r_ + 1.0 / 39916800) * r_        \
		           + 1.0 / 3628800) * r_ + 1.0 / 362880) * r_ + 1.0 / 40320) * r_ + 1.0 / 5040) * r_ + 1.0 / 720) \
		           * r_ + 1.0 / 120) * r_ + 1.0 / 24) * r_ + 1.0 / 6) * r_ + 1.0 / 2) * r_ + 1.0) * r_ + 1.0;    \
		vu8 sb_ = (vu8)(__builtin_convertvector(n_, vl8) + 1023) << 52;                                      \
		(R) = DSEL8(lo_, zero, p_ * (vd8)sb_);                                                                \
	} while (0)

static void de_finish8(const model_shape_t *s, const double *restrict n, const double *restrict pw,
                       const double *restrict zr, const double *restrict zi, const double *restrict dr,
                       const double *restrict di, double *restrict out)
{
	const model_param_t *c = &s->c;
	const double sg = c->amp > 0 ? 1 : -1;
	const double k = c->julia ? 1 : 2, maxit = c->maxit, none = -sg * 1e-3 * s->de_scale;
	const double G0 = k * 2.0 * exp2(-s->de_m0);
	const vd8 zero = {0, 0, 0, 0, 0, 0, 0, 0};
	vd8 N, PW, ZR, ZI, DR, DI;
	memcpy(&N, n, sizeof N);
	memcpy(&PW, pw, sizeof PW);
	memcpy(&ZR, zr, sizeof ZR);
	memcpy(&ZI, zi, sizeof ZI);
	memcpy(&DR, dr, sizeof DR);
	memcpy(&DI, di, sizeof DI);
	vd8 az2 = ZR * ZR + ZI * ZI;
	vl8 esc = (N < maxit) & (az2 > 1.0);
	vd8 a = DSEL8(esc, az2, zero + 2.0);
	/* de_log(a) */
	vu8 b = (vu8)a;
	vu8 eb = (b >> 52) | 0x4330000000000000ull;
	b = (b & 0x000fffffffffffffull) | 0x3ff0000000000000ull;
	vd8 m = (vd8)b, e = (vd8)eb;
	e -= 4503599627370496.0 + 1023.0;
	vd8 big = DSEL8(m > 1.4142135623730951, zero + 1.0, zero);
	m *= 1.0 - 0.5 * big;
	e += big;
	vd8 f = (m - 1.0) / (m + 1.0), f2 = f * f;
	vd8 p = ((((((((((1.0 / 21 * f2 + 1.0 / 19) * f2 + 1.0 / 17) * f2 + 1.0 / 15) * f2 + 1.0 / 13) * f2 + 1.0 / 11) * f2
	         + 1.0 / 9) * f2 + 1.0 / 7) * f2 + 1.0 / 5) * f2 + 1.0 / 3) * f2 + 1.0);
	vd8 lg = e * 6.93147180369123816490e-01 + (2.0 * f * p + e * 1.90821492927058770002e-10);
	vd8 G = k * (0.5 * lg) / PW;
	vd8 q = (DR * DR + DI * DI) / a;
	vd8 dG = k * (vd8)_mm512_sqrt_pd((__m512d)q) / PW;
	vd8 gc = DSEL8(G < 700.0, G, zero + 700.0), e1, e2;
	DE_EXP8(e1, G0 - gc);
	DE_EXP8(e2, -gc);
	vd8 in = DSEL8(e1 - 1 < 1 - e2, e1 - 1, 1 - e2);
	vd8 d = DSEL8(G >= G0, 1 - e1, -in) / (4 * dG);
	vl8 ok = esc & (dG > 0) & (G - G == 0.0);
	vd8 r = DSEL8(ok, sg * d * s->de_scale, zero + none);
	r = DSEL8(N != N, zero + NAN, r);
	memcpy(out, &r, sizeof r);
}
#undef DE_EXP8
#undef DSEL8
#endif

/* The process' complex point of the setup point q: u, v affine in it, or in (x, sqrt(y^2+z^2), 0)
 * when revolved. */
static inline void de_point(const model_param_t *c, double q0, double q1, double q2, double *pr, double *pi)
{
	double r1 = c->revolve ? sqrt(q1 * q1 + q2 * q2) : q1, r2 = c->revolve ? 0 : q2;
	*pr = c->u[0] * q0 + c->u[1] * r1 + c->u[2] * r2 + c->u[3];
	*pi = c->v[0] * q0 + c->v[1] * r1 + c->v[2] * r2 + c->v[3];
}

/* One point's escape iteration, scalar (the lanes' arithmetic, for single evaluations: eight
 * lanes for one point would cost eight times its work): n escapes with z_n. */
static double de_iterate1(const model_param_t *c, double pr, double pi, double bail, double *zr_, double *zi_)
{
	double zr = c->julia ? pr : 0, zi = c->julia ? pi : 0, kr = c->julia ? c->k[0] : pr, ki = c->julia ? c->k[1] : pi;
	int n = 0;
	while (n < c->maxit && zr * zr + zi * zi <= bail) {
		double t = zr * zr - zi * zi + kr;
		zi = 2 * zr * zi + ki;
		zr = t;
		n++;
	}
	*zr_ = zr;
	*zi_ = zi;
	return n;
}

/* The continuous count from n escapes with z_n (smooth), else n. */
static double de_count(const model_param_t *c, double n, double zr, double zi, int smooth)
{
	double m = n;
	if (smooth && n < c->maxit) {
		/* continuous count: |z_n| ~ e^(2^n G), G the potential; ln|z_n| = ln(zr^2 + zi^2) / 2 */
		m = n + 1 - log2(0.5 * log(zr * zr + zi * zi));
		m = m < 0 ? 0 : m > c->maxit ? c->maxit : m;
	}
	return m;
}

double model_count(const model_param_t *c, const double q[3], int smooth)
{
	double pr, pi, zr, zi;
	de_point(c, q[0], q[1], q[2], &pr, &pi);
	double n = de_iterate1(c, pr, pi, smooth ? 1e6 : 4, &zr, &zi);
	return de_count(c, n, zr, zi, smooth);
}

void model_counts(const model_param_t *c, int nl, const double *q, int smooth, double *out)
{
	double pr[DE_LANES], pi[DE_LANES], zr[DE_LANES], zi[DE_LANES], dr[DE_LANES], di[DE_LANES], n[DE_LANES], pw[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		pr[k] = pi[k] = NAN;   /* an idle lane */
		if (k < nl)
			de_point(c, q[3 * k], q[3 * k + 1], q[3 * k + 2], &pr[k], &pi[k]);
	}
	de_iterate(c, pr, pi, zr, zi, dr, di, n, pw, smooth ? 1e6 : 4);
	for (int k = 0; k < nl; k++)
		out[k] = de_count(c, n[k], zr[k], zi[k], smooth);
}

/* The estimate at nl <= 8 actual-frame points (NaN in: NaN out, the lane is idle). */
static void de_lanes(const model_shape_t *s, int nl, const double *x, const double *y, const double *z, double *out)
{
	const model_param_t *c = &s->c;
	const double *m = s->minv;
	double pr[DE_LANES], pi[DE_LANES], zr[DE_LANES], zi[DE_LANES], dr[DE_LANES], di[DE_LANES], n[DE_LANES], pw[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		double p0 = k < nl ? x[k] : NAN, p1 = k < nl ? y[k] : NAN, p2 = k < nl ? z[k] : NAN;
		/* the setup point (M^-1 p), then the process' complex point */
		double q0 = m[0] * p0 + m[1] * p1 + m[2] * p2 + m[3];
		double q1 = m[4] * p0 + m[5] * p1 + m[6] * p2 + m[7];
		double q2 = m[8] * p0 + m[9] * p1 + m[10] * p2 + m[11];
		de_point(c, q0, q1, q2, &pr[k], &pi[k]);
	}
	de_iterate(c, pr, pi, zr, zi, dr, di, n, pw, 1e6);
	double o[DE_LANES];
#if defined(__AVX512F__) && DE_LANES == 8
	de_finish8(s, n, pw, zr, zi, dr, di, o);
#else
	de_finish(s, n, pw, zr, zi, dr, di, o);
#endif
	for (int k = 0; k < nl; k++)
		out[k] = o[k];
}

double model_de(const model_shape_t *s, const double p[3])
{
	double out;
	de_lanes(s, 1, &p[0], &p[1], &p[2], &out);
	return out;
}

void model_de8(const model_shape_t *s, const float *x, const float *y, const float *z, float *out)
{
	double px[DE_LANES], py[DE_LANES], pz[DE_LANES], o[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		px[k] = x[k];   /* NaN: an idle lane */
		py[k] = y[k];
		pz[k] = z[k];
	}
	de_lanes(s, DE_LANES, px, py, pz, o);
	for (int k = 0; k < DE_LANES; k++)
		out[k] = (float)o[k];
}

int model_de_known(const model_shape_t *s, const double p[3], double *d)
{
	double none = -(s->c.amp > 0 ? 1 : -1) * 1e-3 * s->de_scale;
	*d = model_de(s, p);
	return *d == *d && *d != none;
}
