/* model_eval.c: f and its gradient at a point: element distances and measures, weights, metrics, CSG. */
#include "model.h"

#include <math.h>
#include <string.h>
#include "expr.h"

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double len3(const double *a) { return sqrt(dot3(a, a)); }

static void apply(const double *m, const double *p, double *q)
{
	double r[3];
	for (int i = 0; i < 3; i++)
		r[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
	memcpy(q, r, sizeof r);
}

/* The combination of the normalised values a, b; *la = the weight of a's gradient in its gradient
 * (b's is sb * (1 - *la), sb = -1 for a difference). */
static double csg_combine(int op, double k, double a, double b, double *la, double *sb)
{
	*sb = 1;
	switch (op) {
	case MODEL_UNION: *la = a <= b; return fmin(a, b);
	case MODEL_INTERSECTION: *la = a >= b; return fmax(a, b);
	case MODEL_DIFFERENCE: *sb = -1; *la = a >= -b; return fmax(a, -b);
	default: {
		double h = fmax(k - fabs(a - b), 0) / k;
		/* for a < b: d/da = 1 - h/2, d/db = h/2 (and mirrored): a convex combination */
		*la = a < b ? 1 - h / 2 : h / 2;
		return fmin(a, b) - k * h * h / 4;
	}
	}
}

/* The weight of e at the setup point q. */
static double weight_at(const model_elem_t *e, const double *q)
{
	return e->wexpr ? expr_eval(e->wexpr, q[0], q[1], q[2]) : e->w;
}

/* Lipschitz factor of the metric against the Euclidean length, and its lower factor. */
static void metric_factors(const model_elem_t *e, double *up, double *low)
{
	*up = *low = 1;
	if (e->metric == MODEL_LP) {
		double x = 1 / e->mp[0] - 0.5;
		*up = pow(3, fmax(x, 0));
		*low = pow(3, fmin(x, 0));
	} else if (e->metric == MODEL_ANISO) {
		*up = sqrt(fmax(e->mp[0], fmax(e->mp[1], e->mp[2])));
		*low = sqrt(fmin(e->mp[0], fmin(e->mp[1], e->mp[2])));
	}
}

/* The measure of element e at q with its gradient g (setup frame; g may be NULL). */
static double measure(const model_elem_t *e, const double *q, double *g)
{
	double d, gg[3] = {0, 0, 0};
	if (e->metric == MODEL_EUCLID) {
		double near[3];
		d = model_elem_nearest(e, q, near);
		if (d > 0)
			for (int j = 0; j < 3; j++)
				gg[j] = (q[j] - near[j]) / d;
	} else {
		d = INFINITY;
		for (size_t k = 0; k < e->np; k++) {
			const double *a = e->p + 3 * k;
			double v[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]}, m = 0, gk[3];
			if (e->metric == MODEL_LP) {
				double pp = e->mp[0], big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
				if (big > 0) {
					for (int j = 0; j < 3; j++)
						m += pow(fabs(v[j]) / big, pp);
					m = big * pow(m, 1 / pp);
					for (int j = 0; j < 3; j++)   /* d/dv_j = sign(v_j) (|v_j| / m)^(p-1) */
						gk[j] = (v[j] < 0 ? -1 : 1) * pow(fabs(v[j]) / m, pp - 1);
				} else {
					gk[0] = gk[1] = gk[2] = 0;
				}
			} else {
				for (int j = 0; j < 3; j++)
					m += e->mp[j] * v[j] * v[j];
				m = sqrt(m);
				for (int j = 0; j < 3; j++)
					gk[j] = m > 0 ? e->mp[j] * v[j] / m : 0;
			}
			if (m < d) {
				d = m;
				memcpy(gg, gk, sizeof gg);
			}
		}
	}
	if (e->pw != 1) {
		double k = e->pw * pow(d, e->pw - 1);
		d = pow(d, e->pw);
		for (int j = 0; j < 3; j++)
			gg[j] *= k;
	}
	if (g)
		memcpy(g, gg, sizeof gg);
	return d;
}

double model_elem_measure(const model_elem_t *e, const double q[3])
{
	double near[3];
	return e->measured ? measure(e, q, NULL) : model_elem_nearest(e, q, near);
}

void model_measure_bounds(model_shape_t *s, const double *lo, const double *hi)
{
	for (size_t i = 0; i < s->nel; i++) {
		model_elem_t *e = &s->el[i];
		e->lipm = 1;
		e->dmax = INFINITY;
		if (e->kind == MODEL_VORONOI)   /* (e2 - e1)/2 of (1/M)-Lipschitz e's */
			for (size_t k = 0; k < e->np; k++)
				e->lipm = k ? fmax(e->lipm, e->nm[k]) : e->nm[k];
		if (e->kind == MODEL_SHAPE || e->kind == MODEL_CSG || e->kind == MODEL_VORONOI || !e->np)
			continue;
		double up, low, D = 0;
		metric_factors(e, &up, &low);
		/* the distance to the set is at most the distance to its first point */
		for (int c = 0; c < 8; c++) {
			double v[3] = {((c & 1) ? hi[0] : lo[0]) - e->p[0], ((c & 2) ? hi[1] : lo[1]) - e->p[1], ((c & 4) ? hi[2] : lo[2]) - e->p[2]};
			D = fmax(D, len3(v));
		}
		e->dmax = pow(up * (D + (e->kind == MODEL_CIRCLE ? e->r : 0)), e->pw);
		if (e->measured)
			e->lipm = up * e->pw * pow(up * D, e->pw - 1);
	}
}

double model_elem_value(const model_elem_t *e, const double p[3], const double q[3])
{
	double near[3];
	if (e->kind == MODEL_SHAPE)
		return fabs(model_eval(e->shape, p)) / e->shape->lip;
	if (e->kind == MODEL_CSG) {
		double la, sb;
		return csg_combine(e->op, e->r, model_eval(e->shape, p) / e->shape->lip,
		                   model_eval(e->shape2, p) / e->shape2->lip, &la, &sb);
	}
	return model_elem_nearest(e, q, near);
}

double model_elem_distance(const model_elem_t *e, const double q[3])
{
	double near[3];
	return model_elem_nearest(e, q, near);
}

static double mandel(const model_param_t *c, const double *q)
{
	return c->c0 + c->amp * model_count(c, q, c->smooth) / c->maxit;
}

/* The defining parameter; another shape's value recurses into model_eval. */
double model_param(const model_shape_t *s, const double p[3], const double q[3])
{
	const model_param_t *c = &s->c;
	switch (c->kind) {
	case MODEL_C_CONST: return c->c0;
	case MODEL_C_EXPR: return expr_eval(c->expr, q[0], q[1], q[2]);
	case MODEL_C_NOISE: return c->c0 + c->amp * model_noise(c->seed, c->freq * q[0], c->freq * q[1], c->freq * q[2]);
	case MODEL_C_MANDEL: return mandel(c, q);
	default: return c->c0 + c->amp * model_eval(c->shape, p);
	}
}

double model_eval(const model_shape_t *s, const double p[3])
{
	double q[3], near[3], sum = 0;
	apply(s->minv, p, q);
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		double d = e->kind == MODEL_SHAPE || e->kind == MODEL_CSG ? model_elem_value(e, p, q)
		         : e->measured ? measure(e, q, NULL) : model_elem_nearest(e, q, near);
		sum += weight_at(e, q) * d;
	}
	return sum - model_param(s, p, q);
}

void model_grad(const model_shape_t *s, const double p[3], double g[3])
{
	double q[3], near[3], gs[3] = {0, 0, 0}, ga[3] = {0, 0, 0};
	apply(s->minv, p, q);
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->kind == MODEL_CSG) {
			double a = model_eval(e->shape, p) / e->shape->lip, b = model_eval(e->shape2, p) / e->shape2->lip;
			double la, sb, ga_[3], gb_[3];
			csg_combine(e->op, e->r, a, b, &la, &sb);
			model_grad(e->shape, p, ga_);
			model_grad(e->shape2, p, gb_);
			for (int j = 0; j < 3; j++)
				ga[j] += e->w * (la * ga_[j] / e->shape->lip + sb * (1 - la) * gb_[j] / e->shape2->lip);
			continue;
		}
		if (e->kind == MODEL_SHAPE) {
			double f = model_eval(e->shape, p), sg[3];
			model_grad(e->shape, p, sg);
			double k = e->w * (f < 0 ? -1 : 1) / e->shape->lip;
			for (int j = 0; j < 3; j++)
				ga[j] += k * sg[j];
			continue;
		}
		if (e->wexpr) {   /* grad (w d) = w grad d + d grad w, grad w by central differences */
			double gm[3], d = measure(e, q, gm), w = weight_at(e, q), h = 1e-5 * (1 + len3(q));
			for (int j = 0; j < 3; j++) {
				double qa[3] = {q[0], q[1], q[2]}, qb[3] = {q[0], q[1], q[2]};
				qa[j] += h;
				qb[j] -= h;
				gs[j] += w * gm[j] + d * (weight_at(e, qa) - weight_at(e, qb)) / (2 * h);
			}
			continue;
		}
		if (e->measured) {
			double gm[3];
			measure(e, q, gm);
			for (int j = 0; j < 3; j++)
				gs[j] += e->w * gm[j];
			continue;
		}
		double d = model_elem_nearest(e, q, near);
		if (d > 0)
			for (int j = 0; j < 3; j++)
				gs[j] += e->w * (q[j] - near[j]) / d;
	}
	if (s->c.kind == MODEL_C_MANDEL) {
		/* the six central-difference points' counts iterated together; terraces (no smooth)
		 * take the smooth count's normals */
		double h = 1e-5 * (1 + len3(q)), qs[18], m[6];
		for (int j = 0; j < 6; j++) {
			memcpy(qs + 3 * j, q, sizeof q);
			qs[3 * j + j / 2] += j % 2 ? -h : h;
		}
		model_counts(&s->c, 6, qs, 1, m);
		for (int j = 0; j < 3; j++) {
			if (!s->c.smooth)
				gs[j] -= s->c.amp * (m[2 * j] - m[2 * j + 1]) / (2 * h * s->c.maxit);
			else
				gs[j] -= ((s->c.c0 + s->c.amp * m[2 * j] / s->c.maxit) - (s->c.c0 + s->c.amp * m[2 * j + 1] / s->c.maxit)) / (2 * h);
		}
	} else if (s->c.kind != MODEL_C_CONST) {
		double h = 1e-5 * (1 + len3(q));
		for (int j = 0; j < 3; j++) {
			double qa[3] = {q[0], q[1], q[2]}, qb[3] = {q[0], q[1], q[2]};
			qa[j] += h;
			qb[j] -= h;
			double pa[3], pb[3];
			apply(s->m, qa, pa);
			apply(s->m, qb, pb);
			gs[j] -= (model_param(s, pa, qa) - model_param(s, pb, qb)) / (2 * h);
		}
	}
	/* setup gradient to actual: g = A^-T gs */
	for (int j = 0; j < 3; j++)
		g[j] = s->minv[j] * gs[0] + s->minv[4 + j] * gs[1] + s->minv[8 + j] * gs[2] + ga[j];
}
