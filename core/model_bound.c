/* model_bound.c: Lipschitz bound, bounding region and the emptiness proof of a shape. */
#include "model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void apply(const double *m, const double *p, double *q)
{
	for (int i = 0; i < 3; i++)
		q[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
}

/* Axis-aligned box (setup frame) holding the image of the actual box under minv. */
static void box_to_setup(const model_shape_t *s, const double *box, double *lo, double *hi)
{
	for (int i = 0; i < 3; i++) {
		lo[i] = INFINITY;
		hi[i] = -INFINITY;
	}
	for (int c = 0; c < 8; c++) {
		double p[3] = {box[(c & 1) ? 3 : 0], box[(c & 2) ? 4 : 1], box[(c & 4) ? 5 : 2]}, q[3];
		apply(s->minv, p, q);
		for (int i = 0; i < 3; i++) {
			lo[i] = fmin(lo[i], q[i]);
			hi[i] = fmax(hi[i], q[i]);
		}
	}
}

/* Range and gradient bound of c over the setup box; -1 when unknown. */
static int param_bound(const model_shape_t *s, const double *lo, const double *hi,
                       double *cmax, double *g)
{
	const model_param_t *c = &s->c;
	double vlo;
	switch (c->kind) {
	case MODEL_C_CONST: *cmax = c->c0; *g = 0; return 0;
	case MODEL_C_NOISE: *cmax = c->c0 + fabs(c->amp); *g = 2 * sqrt(3.0) * fabs(c->amp) * c->freq; return 0;   /* docs/scene-language.md: the noise bound */
	case MODEL_C_MANDEL: *cmax = fmax(c->c0, c->c0 + c->amp); *g = -1; return 0;
	case MODEL_C_EXPR: return expr_bound(c->expr, lo, hi, &vlo, cmax, g);
	default: *cmax = INFINITY; *g = fabs(c->amp) * c->shape->lip; return 0;
	}
}

static int elem_finite(const model_elem_t *e)
{
	return e->kind == MODEL_POINT || e->kind == MODEL_POINTS || e->kind == MODEL_SEGMENT
	    || e->kind == MODEL_POLYLINE || e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE
	    || e->kind == MODEL_TRIANGLE || e->kind == MODEL_POLYGON || e->kind == MODEL_BOX;
}

/* Bounding sphere in the setup frame from sum w_i (|P - C| - R_i) <= c_max. */
static int setup_sphere(const model_shape_t *s, double *C, double *R)
{
	double wf = 0, n = 0;
	C[0] = C[1] = C[2] = 0;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->w < 0 || e->wexpr)
			return -1;   /* negative or varying weights: no sphere, a user box */
		if (!elem_finite(e))
			continue;
		wf += e->w;
		size_t np = e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE ? 1 : e->np;
		for (size_t k = 0; k < np; k++) {
			for (int j = 0; j < 3; j++)
				C[j] += e->p[3 * k + j];
			n++;
		}
	}
	if (!(wf > 0))
		return -1;
	for (int j = 0; j < 3; j++)
		C[j] /= n;
	double wr = 0;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (!elem_finite(e))
			continue;
		double rmax = 0;
		size_t np = e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE ? 1 : e->np;
		for (size_t k = 0; k < np; k++) {
			double d[3] = {e->p[3 * k] - C[0], e->p[3 * k + 1] - C[1], e->p[3 * k + 2] - C[2]};
			rmax = fmax(rmax, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
		}
		if (e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE)
			rmax += e->r;
		wr += e->w * rmax;
	}
	/* measured elements (powers, metrics): with x = |P - C| - max R_i >= 1 every term is at
	 * least w_i (low_i x)^p_i >= w_i low_i^p_i x^pmin, so the surface lies within
	 * max R_i + max(1, (c_max / sum w_i low_i^p_i)^(1/pmin)) */
	double pmin = INFINITY, wl = 0, rbig = 0;
	int measured = 0;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		measured |= e->measured;
	}
	if (measured) {
		for (size_t i = 0; i < s->nel; i++) {
			const model_elem_t *e = &s->el[i];
			if (!elem_finite(e))
				continue;
			double low = 1;
			if (e->metric == MODEL_LP)
				low = pow(3, fmin(1 / e->mp[0] - 0.5, 0));
			else if (e->metric == MODEL_ANISO)
				low = sqrt(fmin(e->mp[0], fmin(e->mp[1], e->mp[2])));
			pmin = fmin(pmin, e->pw);
			wl += e->w * pow(low, e->pw);
			double rmax = 0;
			size_t np = e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE ? 1 : e->np;
			for (size_t k = 0; k < np; k++) {
				double d[3] = {e->p[3 * k] - C[0], e->p[3 * k + 1] - C[1], e->p[3 * k + 2] - C[2]};
				rmax = fmax(rmax, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
			}
			rbig = fmax(rbig, rmax + (e->kind == MODEL_DISK || e->kind == MODEL_CIRCLE ? e->r : 0));
		}
	}
	for (double r = 1; r <= 1e6; r *= 2) {
		double lo[3] = {C[0] - r, C[1] - r, C[2] - r}, hi[3] = {C[0] + r, C[1] + r, C[2] + r};
		double cmax, g;
		if (param_bound(s, lo, hi, &cmax, &g) < 0 || !isfinite(cmax))
			return -1;
		double need = (cmax + wr) / wf;
		if (measured)
			need = rbig + fmax(1, pow(fmax(cmax, 0) / wl, 1 / pmin));
		if (s->c.kind != MODEL_C_EXPR || need <= r) {
			*R = fmax(need, 0) * 1.0001 + 1e-6;
			return 0;
		}
	}
	return -1;
}

static void tighten_box(model_shape_t *s);

/* A shape made only of constructive elements (positive weights, constant c) lies in its
 * operands' regions (union: both, intersection: their overlap, difference: A's) grown by c/w
 * (the combination is 1-Lipschitz): that box becomes its region, as if given by `bound`. */
static void csg_region(model_shape_t *s)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, wsum = 0;
	if (s->nel == 0 || s->c.kind != MODEL_C_CONST)
		return;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->kind != MODEL_CSG || !(e->w > 0))
			return;
		wsum += e->w;
		const double *a = e->shape->box, *b = e->shape2->box;
		for (int j = 0; j < 3; j++) {
			double l = a[j], h = a[3 + j];
			if (e->op == MODEL_UNION || e->op == MODEL_BLEND)
				l = fmin(l, b[j]), h = fmax(h, b[3 + j]);
			else if (e->op == MODEL_INTERSECTION)
				l = fmax(l, b[j]), h = fmin(h, b[3 + j]);
			lo[j] = fmin(lo[j], l);
			hi[j] = fmax(hi[j], h);
		}
	}
	double grow = fmax(s->c.c0, 0) / wsum;
	for (int j = 0; j < 3; j++) {
		if (!(lo[j] < hi[j]))
			return;   /* an empty intersection: left to the 'bound' error */
		s->box[j] = lo[j] - grow;
		s->box[3 + j] = hi[j] + grow;
	}
	s->user_box = 1;
}

/* 1 when z <- z^2 + k stays bounded from 0 for 1000 steps: k in the Mandelbrot set as far as
 * that tells, so the Julia set is connected and its Boettcher map conformal outside it. */
static int julia_connected(const model_param_t *c)
{
	double zr = 0, zi = 0;
	for (int i = 0; i < 1000; i++) {
		double t = zr * zr - zi * zi + c->k[0];
		zi = 2 * zr * zi + c->k[1];
		zr = t;
		if (zr * zr + zi * zi > 4)
			return 0;
	}
	return 1;
}

/* The Douady-Hubbard distance estimate applies to a shape that is only a smooth process
 * (f = -c(P)): set s->de, its level and scale. */
static void set_de(model_shape_t *s)
{
	const model_param_t *c = &s->c;
	double m0;
	s->de = 0;
	if (s->nel != 0 || c->stepping || !model_de_level(c, &m0) || (c->julia && !julia_connected(c)))
		return;
	double uu = 0, vv = 0, uv = 0;
	for (int i = 0; i < 3; i++) {
		uu += c->u[i] * c->u[i];
		vv += c->v[i] * c->v[i];
		uv += c->u[i] * c->v[i];
	}
	/* operator norm of the 2x3 map (u, v): the larger eigenvalue of its Gram matrix */
	double lam = 0.5 * (uu + vv) + sqrt(0.25 * (uu - vv) * (uu - vv) + uv * uv), jn = sqrt(lam);
	if (!(jn > 0) || !(s->norm_minv > 0))
		return;
	s->de = 1;
	s->de_m0 = m0;
	s->de_scale = 1 / (jn * s->norm_minv);
}

/* Why setup_sphere found no bounding sphere, in words the user can act on. */
static const char *unbounded_reason(const model_shape_t *s)
{
	double wf = 0;
	int finite = 0, shapes = 0, infinite = 0, negative = 0;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->kind == MODEL_SHAPE)
			shapes++;
		else if (elem_finite(e))
			finite++, wf += e->w;
		else
			infinite++;
		negative |= e->w < 0;
	}
	if (s->nel == 0)
		return "no elements: the solid is wherever the defining parameter is positive";
	for (size_t i = 0; i < s->nel; i++)
		if (s->el[i].wexpr)
			return "a weight varies with position, and its bound is taken over the box";
	if (!finite && shapes && !infinite)
		return "its elements are only distance-to other shapes, and Locus does not carry their extent over";
	if (!finite)
		return "its only elements are infinite: lines or planes";
	if (wf == 0 && !negative)
		return "the weights of its finite elements are all 0";
	if (!(wf > 0))
		return "the weights of its finite elements sum to 0 or less (negative weights)";
	return "its defining parameter has no known maximum over space";
}

int model_prepare(model_shape_t *s, char *err, size_t errlen, const char **warn)
{
	if (warn)
		*warn = NULL;
	if (s->nel == 0 && s->c.kind == MODEL_C_CONST) {
		snprintf(err, errlen, "a shape needs at least one distance element (or a defining parameter that is not a constant)");
		return -1;
	}
	if (model_check_nesting(s, err, errlen) < 0)
		return -1;
	int nonzero = 0;
	for (size_t i = 0; i < s->nel; i++)
		nonzero |= s->el[i].w != 0;
	if (s->nel > 0 && !nonzero && s->c.kind == MODEL_C_CONST) {
		snprintf(err, errlen, "expected a non-zero weight: every element has weight 0, so f = -c is the same"
		         " everywhere and has no surface");
		return -1;
	}
	double C[3], R, lo[3], hi[3];
	const double *mi = s->minv;
	s->fast_points = s->c.kind == MODEL_C_CONST && mi[0] == 1 && mi[1] == 0 && mi[2] == 0 && mi[4] == 0
	              && mi[5] == 1 && mi[6] == 0 && mi[8] == 0 && mi[9] == 0 && mi[10] == 1;
	for (size_t i = 0; i < s->nel; i++)
		if ((s->el[i].kind != MODEL_POINT && s->el[i].kind != MODEL_SEGMENT) || s->el[i].measured || s->el[i].wexpr)
			s->fast_points = 0;
	s->bounded = setup_sphere(s, C, &R) == 0;
	if (s->bounded) {
		apply(s->m, C, s->centre);
		s->radius = R * s->norm_m;
	}
	if (!s->bounded && !s->user_box)
		csg_region(s);
	if (!s->bounded && !s->user_box) {
		snprintf(err, errlen, "expected a 'bound' box: the shape is unbounded (%s); add 'bound X0 Y0 Z0 X1 Y1 Z1'"
		         " around the part to draw", unbounded_reason(s));
		return -1;
	}
	if (s->user_box) {
		memcpy(s->root, s->box, sizeof s->root);
		box_to_setup(s, s->box, lo, hi);
	}
	if (s->bounded) {
		for (int i = 0; i < 3; i++) {
			double a = C[i] - R, b = C[i] + R;
			lo[i] = s->user_box ? fmax(lo[i], a) : a;
			hi[i] = s->user_box ? fmin(hi[i], b) : b;
		}
		if (!s->user_box) {
			for (int i = 0; i < 3; i++) {
				s->box[i] = s->centre[i] - s->radius;
				s->box[3 + i] = s->centre[i] + s->radius;
			}
		}
	}
	double ws = 0, wa = 0, cmax, g;
	model_measure_bounds(s, lo, hi);
	s->lip_local = 0;
	for (size_t i = 0; i < s->nel; i++)
		s->lip_local |= (s->el[i].measured && s->el[i].pw > 1) || s->el[i].wexpr != NULL;
	int wbad = 0;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->kind == MODEL_SHAPE || e->kind == MODEL_CSG)
			wa += fabs(e->w);
		else if (e->wexpr) {
			/* |grad (w d)| <= max|w| L_d + G_w D over the box */
			double wlo, whi, gw;
			if (expr_bound(e->wexpr, lo, hi, &wlo, &whi, &gw) < 0 || !isfinite(e->dmax) || !isfinite(gw))
				wbad = 1;
			else
				ws += fmax(fabs(wlo), fabs(whi)) * e->lipm + gw * e->dmax;
		} else
			ws += fabs(e->w) * e->lipm;
	}
	s->has_lip = 0;
	s->lip = 0;
	if (!wbad && param_bound(s, lo, hi, &cmax, &g) == 0 && g >= 0) {
		s->has_lip = 1;
		if (s->c.kind == MODEL_C_SHAPE)
			s->lip = s->norm_minv * ws + wa + g;
		else
			s->lip = s->norm_minv * (ws + g) + wa;
	}
	if (s->has_lip && !(s->lip > 0))
		s->has_lip = 0;
	set_de(s);
	if (!s->has_lip && !s->de && warn)
		*warn = s->c.kind == MODEL_C_MANDEL && s->c.julia && s->nel == 0 && s->c.smooth && !julia_connected(&s->c)
		        ? "the Julia set of this k is not connected (k is outside the Mandelbrot set), so the distance estimate"
		          " is not a proven bound: using step-and-bisect bracketing (slower)"
		        : "no Lipschitz bound for this defining parameter: using step-and-bisect bracketing (slower)";
	if (s->has_lip && model_is_empty(s)) {
		if (warn)
			*warn = "the shape is empty (the defining parameter is below the minimum of the distance sum)";
	} else if (s->has_lip) {
		tighten_box(s);
	}
	if (!s->user_box)
		memcpy(s->root, s->box, sizeof s->root);
	return 0;
}

/* Spherical cell test: can the cell centred at p of half-diagonal r hold f <= 0? */
static int cell_may_hold(const model_shape_t *s, const double *p, double r, int depth, int *neg)
{
	double f = model_eval(s, p);
	if (!(f == f))
		return 1;
	if (f <= 0) {
		*neg = 1;
		return 1;
	}
	if (f > s->lip * r)
		return 0;
	if (depth == 0)
		return 1;
	for (int c = 0; c < 8 && !*neg; c++) {
		double h = r / (2 * sqrt(3.0));
		double q[3] = {p[0] + ((c & 1) ? h : -h), p[1] + ((c & 2) ? h : -h), p[2] + ((c & 4) ? h : -h)};
		if (cell_may_hold(s, q, r / 2, depth - 1, neg))
			return 1;
	}
	return *neg;
}

/* Grow lo/hi by the cells (centre p, half side h) that the spherical test cannot clear. */
static void tight(const model_shape_t *s, const double *p, double h, int depth, double *lo, double *hi)
{
	double f = model_eval(s, p), r = h * sqrt(3.0);
	if (f == f && fabs(f) > s->lip * r)
		return;
	if (depth == 0 || f != f) {
		for (int i = 0; i < 3; i++) {
			lo[i] = fmin(lo[i], p[i] - h);
			hi[i] = fmax(hi[i], p[i] + h);
		}
		return;
	}
	for (int c = 0; c < 8; c++) {
		double q[3] = {p[0] + ((c & 1) ? h : -h) / 2, p[1] + ((c & 2) ? h : -h) / 2, p[2] + ((c & 4) ? h : -h) / 2};
		tight(s, q, h / 2, depth - 1, lo, hi);
	}
}

/* Shrink the clip box to the cells of a depth-5 octree that may hold the surface. */
static void tighten_box(model_shape_t *s)
{
	double *b = s->box, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	double h = fmax(b[3] - b[0], fmax(b[4] - b[1], b[5] - b[2])) / 2;
	double p[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
	tight(s, p, h, 5, lo, hi);
	if (!(lo[0] <= hi[0]))
		return;
	for (int i = 0; i < 3; i++) {
		double pad = 1e-3 * h;
		b[i] = fmax(b[i], lo[i] - pad);
		b[3 + i] = fmin(b[3 + i], hi[i] + pad);
	}
}

int model_is_empty(const model_shape_t *s)
{
	if (!s->has_lip)
		return 0;
	const double *b = s->box;
	double size = fmax(b[3] - b[0], fmax(b[4] - b[1], b[5] - b[2]));
	double p[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
	int neg = 0;
	return !cell_may_hold(s, p, size * sqrt(3.0) / 2, 6, &neg);
}
