/* rt_march1.c: one ray marched in double precision (far eyes, large coordinates, narrow views), the float marcher's exact twin in rules. */
#include "rt_int.h"

#include <math.h>

/* Clip the ray to the object's region (box and, if bounded, sphere): [*a, *b], empty when a > b;
 * *on = 1 when the entry lies on the bounding sphere. */
static void clip1(const model_shape_t *s, const double *o, const double *d, double *a, double *b, int *on)
{
	double lo = *a, hi = *b;
	for (int i = 0; i < 3; i++) {
		if (d[i] == 0) {
			if (o[i] < s->box[i] || o[i] > s->box[3 + i])
				lo = INFINITY;
			continue;
		}
		double u0 = (s->box[i] - o[i]) / d[i], u1 = (s->box[3 + i] - o[i]) / d[i];
		lo = fmax(lo, fmin(u0, u1));
		hi = fmin(hi, fmax(u0, u1));
	}
	*on = 0;
	if (s->bounded) {
		double oc[3] = {o[0] - s->centre[0], o[1] - s->centre[1], o[2] - s->centre[2]};
		double bb = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
		/* |oc|^2 - bb^2 is the squared distance of the centre from the line, computed without
		 * the cancellation of |oc|^2 - r^2 for a far eye */
		double q[3] = {oc[0] - bb * d[0], oc[1] - bb * d[1], oc[2] - bb * d[2]};
		double disc = s->radius * s->radius - (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
		if (!(disc >= 0)) {
			lo = INFINITY;
		} else {
			double h = sqrt(disc), slo = -bb - h, shi = -bb + h;
			*on = slo >= lo;
			lo = fmax(lo, slo);
			hi = fmin(hi, shi);
		}
	}
	*a = lo;
	*b = hi;
}

static double eval_at(const model_shape_t *s, const double *o, const double *d, double t, double sg)
{
	double p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
	double v = sg * (s->de ? model_de(s, p) : model_eval(s, p));
	return v;
}

double rt_march1(const model_shape_t *s, const double *o, const double *d, double tmin, double tmax,
                 double fa, double fb, double acc, double step, int shadow, int *side, uint64_t *evals)
{
	double a = tmin, b = tmax, L = rt_bound(s);
	int on;
	*side = 0;
	clip1(s, o, d, &a, &b, &on);
	if (!(a <= b))
		return INFINITY;
	double fp = fa + fb * a, eps = fmax(acc * fp, 1e-13 * (fabs(a) + 1));
	double f = eval_at(s, o, d, a, 1);
	(*evals)++;
	if (f < 0 && on) {   /* entering the bounding sphere inside the solid: they touch here */
		*side = 1;
		return a;
	}
	double sg = f < 0 ? -1 : 1;
	f *= sg;
	if (f == f && f <= eps * (L > 0 ? L : 1))
		return a;    /* on the surface at the entry: side unknown */
	if (f != f)
		f = 0.05 * fp * (L > 0 ? L : 1);
	double t = a, smin = (b - a) * 1e-3, lo = 0, hi = 0, flo = 0, fhi = 0;
	int bracket = 0;
	for (int it = 0; it < 200000; it++) {
		fp = fa + fb * t;
		double emin = 0.05 * fp;
		eps = fmax(acc * fp, 1e-13 * (fabs(t) + 1));
		if (!bracket) {
			double s1 = L > 0 ? fmax(f / L, emin) : fmax(step * fp, smin);
			/* try the over-relaxed step 1.6 f/L first: accepted when the two balls overlap */
			double s2 = L > 0 ? fmax(1.6 * f / L, emin) : s1;
			double u = fmin(t + s2, b), v = eval_at(s, o, d, u, sg);
			(*evals)++;
			if (v != v)
				v = emin * (L > 0 ? L : 1);
			/* rejected unless the ball at t and the one at u overlap (outside: both free of
			 * surface; a sign change: exactly one crossing between them) */
			double du = (u - t) * 0.999999;
			if (L > 0 && u - t > emin * 1.0001 && (v > 0 ? (f + v) / L < du : !shadow && (f - v) / L < du)) {
				u = fmin(t + s1, b);     /* rejected: the plain sphere-tracing step */
				v = eval_at(s, o, d, u, sg);
				(*evals)++;
				if (v != v)
					v = emin * L;
			}
			if (v <= 0) {
				if (shadow) {
					*side = (int)sg;
					return u;
				}
				bracket = 1;
				lo = t, flo = f, hi = u, fhi = v;
				continue;
			}
			if (u >= b)
				return INFINITY;
			t = u;
			f = v;
			continue;
		}
		/* regula falsi (Illinois) on [lo, hi], f(lo) > 0 >= f(hi) */
		double r = lo + (hi - lo) * flo / (flo - fhi);
		if (!(r > lo && r < hi))
			r = 0.5 * (lo + hi);
		double v = eval_at(s, o, d, r, sg);
		(*evals)++;
		if (fabs(v) < eps * (L > 0 ? L : 1) || hi - lo < eps) {
			*side = (int)sg;
			return r;
		}
		if (v > 0) {
			lo = r, flo = v, fhi *= 0.5;
		} else {
			hi = r, fhi = v, flo *= 0.5;
		}
		if (hi - lo < eps) {
			*side = (int)sg;
			return 0.5 * (lo + hi);
		}
	}
	return bracket ? 0.5 * (lo + hi) : INFINITY;
}
