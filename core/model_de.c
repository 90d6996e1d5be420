/* model_de.c: the Douady-Hubbard distance estimate of a smooth Mandelbrot or Julia shape, 8 lanes at a time. */
#include "model.h"

#include <math.h>

#define DE_LANES 8

/* The escape iteration of nl <= 8 setup-frame points at once (structure of arrays, double):
 * Mandelbrot z <- z^2 + p from z = 0, Julia z <- z^2 + k from z = p, with dz/dp. Every lane
 * does the scalar iteration's arithmetic in the same order (so one lane alone gives the same
 * bits as eight); a lane that has escaped (|z|^2 > bail) or is NaN keeps its values while the
 * others go on. Branch-free selects so that the compiler vectorises the lanes. */
static void de_iterate(const model_param_t *c, const double *restrict pr, const double *restrict pi,
                       double *restrict zr, double *restrict zi, double *restrict dr, double *restrict di,
                       double *restrict n)
{
	const double bail = 1e6, jl = c->julia ? 1.0 : 0.0, one = c->julia ? 0.0 : 1.0;
	double kr[DE_LANES], ki[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		zr[k] = jl > 0 ? pr[k] : 0.0;
		zi[k] = jl > 0 ? pi[k] : 0.0;
		dr[k] = jl;
		di[k] = 0.0;
		kr[k] = jl > 0 ? c->k[0] : pr[k];
		ki[k] = jl > 0 ? c->k[1] : pi[k];
		n[k] = 0.0;
	}
	for (int it = 0; it < c->maxit; it++) {
		long live = 0;
		for (int k = 0; k < DE_LANES; k++) {
			double a = zr[k] * zr[k] + zi[k] * zi[k];
			long go = a <= bail;
			double ndr = 2 * (zr[k] * dr[k] - zi[k] * di[k]) + one;
			double ndi = 2 * (zr[k] * di[k] + zi[k] * dr[k]);
			double nzr = zr[k] * zr[k] - zi[k] * zi[k] + kr[k];
			double nzi = 2 * zr[k] * zi[k] + ki[k];
			dr[k] = go ? ndr : dr[k];
			di[k] = go ? ndi : di[k];
			zr[k] = go ? nzr : zr[k];
			zi[k] = go ? nzi : zi[k];
			n[k] += go ? 1.0 : 0.0;
			live |= go;
		}
		if (!live)
			break;
	}
}

/* The estimate from the iteration's end: n escapes (n = maxit: none) with z_n and dz_n/dp. */
static double de_finish(const model_shape_t *s, double n, double zr, double zi, double dr, double di)
{
	const model_param_t *c = &s->c;
	double sg = c->amp > 0 ? 1 : -1;   /* f > 0 (outside) where the potential is above the level */
	if (n != n)
		return NAN;
	if (n >= c->maxit)
		return -sg * 1e-3 * s->de_scale;    /* never escaped: inside the set, a sign and no bound */
	/* potential G = lim 2^-n ln|z_n| (Julia), twice that for the Mandelbrot set (whose z_n is
	 * the Julia iterate of p one step late); |grad G| = |z_n'| / (|z_n| 2^n) likewise */
	int ni = (int)n;
	double az2 = zr * zr + zi * zi, lz = 0.5 * log(az2), k = c->julia ? 1 : 2;
	double G = k * lz / ldexp(1, ni), dG = k * sqrt((dr * dr + di * di) / az2) / ldexp(1, ni);
	double G0 = k * ldexp(1, 1) * exp2(-s->de_m0);
	if (!(dG > 0) || !isfinite(G))
		return -sg * 1e-3 * s->de_scale;
	/* Koebe 1/4 on the Boettcher map's inverse: the disk of radius e^G - e^G0 about Phi(p) lies
	 * where the potential exceeds G0, so its image holds a disk of a quarter of that radius
	 * times |Phi^-1'| = 1/(e^G |grad G|) around p: the distance to the level set is at least
	 * (1 - e^(G0-G)) / (4 |grad G|); inside, the disk also has to keep out of the unit disk */
	double d = G >= G0 ? (1 - exp(G0 - G)) / (4 * dG) : -fmin(exp(G0 - G) - 1, 1 - exp(-G)) / (4 * dG);
	return sg * d * s->de_scale;
}

/* The estimate at nl <= 8 actual-frame points (NaN in: NaN out, the lane is idle). */
static void de_lanes(const model_shape_t *s, int nl, const double *x, const double *y, const double *z, double *out)
{
	const model_param_t *c = &s->c;
	const double *m = s->minv;
	double pr[DE_LANES], pi[DE_LANES], zr[DE_LANES], zi[DE_LANES], dr[DE_LANES], di[DE_LANES], n[DE_LANES];
	for (int k = 0; k < DE_LANES; k++) {
		double p0 = k < nl ? x[k] : NAN, p1 = k < nl ? y[k] : NAN, p2 = k < nl ? z[k] : NAN;
		/* the setup point (M^-1 p), then the process' complex point: u, v affine in it or in
		 * (x, sqrt(y^2+z^2), 0) when revolved */
		double q0 = m[0] * p0 + m[1] * p1 + m[2] * p2 + m[3];
		double q1 = m[4] * p0 + m[5] * p1 + m[6] * p2 + m[7];
		double q2 = m[8] * p0 + m[9] * p1 + m[10] * p2 + m[11];
		double r1 = c->revolve ? sqrt(q1 * q1 + q2 * q2) : q1, r2 = c->revolve ? 0 : q2;
		pr[k] = c->u[0] * q0 + c->u[1] * r1 + c->u[2] * r2 + c->u[3];
		pi[k] = c->v[0] * q0 + c->v[1] * r1 + c->v[2] * r2 + c->v[3];
	}
	de_iterate(c, pr, pi, zr, zi, dr, di, n);
	for (int k = 0; k < nl; k++)
		out[k] = de_finish(s, n[k], zr[k], zi[k], dr[k], di[k]);
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
