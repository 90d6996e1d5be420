/* model.c: elements, transforms, the double-precision reference evaluator, gradients and bounds of a shape. */
#include "model.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double len3(const double *a) { return sqrt(dot3(a, a)); }

static void set_identity(double *m)
{
	memset(m, 0, 12 * sizeof *m);
	m[0] = m[5] = m[10] = 1;
}

static void update_inverse(model_shape_t *s)
{
	const double *a = s->m;
	double det = a[0] * (a[5] * a[10] - a[6] * a[9]) - a[1] * (a[4] * a[10] - a[6] * a[8])
	           + a[2] * (a[4] * a[9] - a[5] * a[8]);
	double *b = s->minv;
	double id = 1.0 / det;
	b[0] = (a[5] * a[10] - a[6] * a[9]) * id;
	b[1] = (a[2] * a[9] - a[1] * a[10]) * id;
	b[2] = (a[1] * a[6] - a[2] * a[5]) * id;
	b[4] = (a[6] * a[8] - a[4] * a[10]) * id;
	b[5] = (a[0] * a[10] - a[2] * a[8]) * id;
	b[6] = (a[2] * a[4] - a[0] * a[6]) * id;
	b[8] = (a[4] * a[9] - a[5] * a[8]) * id;
	b[9] = (a[1] * a[8] - a[0] * a[9]) * id;
	b[10] = (a[0] * a[5] - a[1] * a[4]) * id;
	for (int r = 0; r < 3; r++)
		b[r * 4 + 3] = -(b[r * 4] * a[3] + b[r * 4 + 1] * a[7] + b[r * 4 + 2] * a[11]);
	for (int i = 0; i < 12; i++)
		s->mf[i] = (float)b[i];
}

static void apply(const double *m, const double *p, double *q)
{
	double r[3];
	for (int i = 0; i < 3; i++)
		r[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
	memcpy(q, r, sizeof r);
}

model_shape_t *model_new(void)
{
	model_shape_t *s = calloc(1, sizeof *s);
	if (!s)
		return NULL;
	set_identity(s->m);
	s->norm_m = s->norm_minv = 1;
	update_inverse(s);
	return s;
}

void model_free(model_shape_t *s)
{
	if (!s)
		return;
	for (size_t i = 0; i < s->nel; i++) {
		free(s->el[i].p);
		free(s->el[i].pf);
		free(s->el[i].nw);
		free(s->el[i].nm);
		free(s->el[i].grp);
		expr_free(s->el[i].wexpr);
	}
	free(s->el);
	expr_free(s->c.expr);
	free(s);
}

static void premultiply(model_shape_t *s, const double r[9])
{
	double n[12];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 4; j++)
			n[i * 4 + j] = r[i * 3] * s->m[j] + r[i * 3 + 1] * s->m[4 + j] + r[i * 3 + 2] * s->m[8 + j];
	memcpy(s->m, n, sizeof n);
	update_inverse(s);
}

void model_translate(model_shape_t *s, double x, double y, double z)
{
	s->m[3] += x;
	s->m[7] += y;
	s->m[11] += z;
	update_inverse(s);
}

void model_rotate(model_shape_t *s, int axis, double degrees)
{
	double a = degrees * (3.14159265358979323846 / 180), c = cos(a), sn = sin(a);
	double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
	int i = (axis + 1) % 3, j = (axis + 2) % 3;
	r[i * 3 + i] = c;
	r[i * 3 + j] = -sn;
	r[j * 3 + i] = sn;
	r[j * 3 + j] = c;
	premultiply(s, r);
}

int model_scale(model_shape_t *s, double sx, double sy, double sz)
{
	if (!(isfinite(sx) && isfinite(sy) && isfinite(sz)) || sx == 0 || sy == 0 || sz == 0)
		return -1;
	double r[9] = {sx, 0, 0, 0, sy, 0, 0, 0, sz};
	double mx = fmax(fabs(sx), fmax(fabs(sy), fabs(sz)));
	double mn = fmin(fabs(sx), fmin(fabs(sy), fabs(sz)));
	s->norm_m *= mx;
	s->norm_minv /= mn;
	premultiply(s, r);
	return 0;
}

static int need_points(int kind, size_t np)
{
	switch (kind) {
	case MODEL_POINT: return np == 1;
	case MODEL_SEGMENT: case MODEL_LINE: case MODEL_PLANE: case MODEL_DISK: case MODEL_CIRCLE: case MODEL_BOX: return np == 2;
	case MODEL_TRIANGLE: return np == 3;
	case MODEL_POLYGON: return np >= 3;
	case MODEL_POINTS: return np >= 1;
	case MODEL_POLYLINE: return np >= 2;
	default: return np == 0;
	}
}

/* A triangle's or polygon's unit normal (Newell's method), stored after its corners; -1 with
 * a message when it has no area or is not planar. */
static int polygon_plane(model_elem_t *e, char *err, size_t errlen)
{
	double n[3] = {0, 0, 0}, size = 0;
	const double *v = e->p;
	for (size_t k = 0; k < e->np; k++) {
		const double *a = v + 3 * k, *b = v + 3 * ((k + 1) % e->np);
		n[0] += (a[1] - b[1]) * (a[2] + b[2]);
		n[1] += (a[2] - b[2]) * (a[0] + b[0]);
		n[2] += (a[0] - b[0]) * (a[1] + b[1]);
		for (int j = 0; j < 3; j++)
			size = fmax(size, fabs(a[j] - v[j]));
	}
	double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
	if (!(l > 1e-12 * size * size) || !(size > 0)) {
		snprintf(err, errlen, "corners that span an area (not all on one line)");
		return -1;
	}
	for (int j = 0; j < 3; j++)
		n[j] /= l;
	for (size_t k = 1; k < e->np; k++) {
		const double *a = v + 3 * k;
		double h = (a[0] - v[0]) * n[0] + (a[1] - v[1]) * n[1] + (a[2] - v[2]) * n[2];
		if (fabs(h) > 1e-9 * size) {
			snprintf(err, errlen, "a planar polygon (corner %zu is %g off the plane of the others)", k + 1, h);
			return -1;
		}
	}
	memcpy(e->p + 3 * e->np, n, sizeof n);
	return 0;
}

static int push(model_shape_t *s, model_elem_t *e, char *err, size_t errlen)
{
	if (s->nel == s->cap) {
		size_t cap = s->cap ? 2 * s->cap : 4;
		model_elem_t *n = realloc(s->el, cap * sizeof *n);
		if (!n) {
			free(e->p);
			free(e->pf);
			free(e->nw);
			snprintf(err, errlen, "out of memory");
			return -1;
		}
		s->el = n;
		s->cap = cap;
	}
	s->el[s->nel++] = *e;
	return 0;
}

int model_add_nuclei(model_shape_t *s, double w, const double *ab, const double *wt, size_t n,
                     char *err, size_t errlen)
{
	return model_add_nuclei2(s, w, ab, wt, NULL, NULL, n, err, errlen);
}

int model_add_nuclei2(model_shape_t *s, double w, const double *ab, const double *wt, const double *fac,
                      const int *grp, size_t n, char *err, size_t errlen)
{
	size_t groups = 0;
	for (size_t k = 0; k < n; k++)
		groups += !grp || k == 0 || grp[k] != grp[k - 1];
	if (groups < 2) {
		snprintf(err, errlen, "at least 2 nuclei");
		return -1;
	}
	if (!isfinite(w)) {
		snprintf(err, errlen, "a finite weight");
		return -1;
	}
	for (size_t i = 0; i < 6 * n; i++)
		if (!isfinite(ab[i]) || (i < n && !isfinite(wt[i]))) {
			snprintf(err, errlen, "finite coordinates and weights (found NaN or infinity)");
			return -1;
		}
	for (size_t k = 0; fac && k < n; k++)
		if (!(fac[k] > 0 && fac[k] <= 1e6)) {
			snprintf(err, errlen, "multiplicative weights above 0");
			return -1;
		}
	model_elem_t e = {0};
	e.kind = MODEL_VORONOI;
	e.pw = 1;
	e.w = w;
	e.np = n;
	e.p = malloc(6 * n * sizeof *e.p);
	e.nw = malloc(n * sizeof *e.nw);
	e.nm = malloc(n * sizeof *e.nm);
	e.grp = malloc(n * sizeof *e.grp);
	e.pf = malloc(10 * n * sizeof *e.pf);
	if (!e.p || !e.nw || !e.pf || !e.nm || !e.grp) {
		free(e.p);
		free(e.nw);
		free(e.nm);
		free(e.grp);
		free(e.pf);
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	memcpy(e.p, ab, 6 * n * sizeof *ab);
	memcpy(e.nw, wt, n * sizeof *wt);
	for (size_t k = 0; k < n; k++) {
		e.nm[k] = fac ? 1 / fac[k] : 1;
		e.grp[k] = grp ? grp[k] : (int)k;
		const double *a = ab + 6 * k, *b = a + 3;
		double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, l2 = dot3(ba, ba);
		float *f = e.pf + 10 * k;
		for (int i = 0; i < 3; i++) {
			f[i] = (float)a[i];
			f[3 + i] = (float)ba[i];
		}
		f[6] = l2 > 0 ? (float)(1.0 / l2) : 0.0f;
		f[7] = (float)wt[k];
		f[8] = (float)e.nm[k];
		f[9] = k > 0 && e.grp[k] == e.grp[k - 1] ? 1.0f : 0.0f;   /* continues the previous nucleus */
	}
	return push(s, &e, err, errlen);
}

int model_add(model_shape_t *s, int kind, double w, const double *pts, size_t np, double r,
              const model_shape_t *shape, char *err, size_t errlen)
{
	if (kind == MODEL_VORONOI && np >= 2) {
		double *ab = malloc(6 * np * sizeof *ab), *wt = calloc(np, sizeof *wt);
		int rc = -1;
		if (ab && wt) {
			for (size_t k = 0; k < np; k++) {
				memcpy(ab + 6 * k, pts + 3 * k, 3 * sizeof *ab);
				memcpy(ab + 6 * k + 3, pts + 3 * k, 3 * sizeof *ab);
			}
			rc = model_add_nuclei(s, w, ab, wt, np, err, errlen);
		} else {
			snprintf(err, errlen, "out of memory");
		}
		free(ab);
		free(wt);
		return rc;
	}
	if (!need_points(kind, np)) {
		snprintf(err, errlen, "%s", kind == MODEL_POLYGON ? "at least 3 corners" : kind == MODEL_POLYLINE || kind == MODEL_VORONOI ? "at least 2 points"
		         : kind == MODEL_POINTS ? "at least 1 point" : "the element's number of points");
		return -1;
	}
	if (!isfinite(w) || !isfinite(r) || r < 0) {
		snprintf(err, errlen, "a finite weight%s", kind == MODEL_DISK || kind == MODEL_CIRCLE ? " and radius >= 0" : "");
		return -1;
	}
	for (size_t i = 0; i < 3 * np; i++)
		if (!isfinite(pts[i])) {
			snprintf(err, errlen, "finite coordinates (found NaN or infinity)");
			return -1;
		}
	if (kind == MODEL_SHAPE && (!shape || !shape->has_lip || shape->lip <= 0)) {
		snprintf(err, errlen, "a shape with a known Lipschitz bound as a distance element");
		return -1;
	}
	if (kind == MODEL_SHAPE && shape->lip_local) {
		snprintf(err, errlen, "a shape whose Lipschitz bound holds everywhere (a power above 1 bounds it only in its region)");
		return -1;
	}
	model_elem_t e = {0};
	e.kind = kind;
	e.pw = 1;
	e.w = w;
	e.np = np;
	e.r = r;
	e.shape = shape;
	size_t nf = kind == MODEL_POLYLINE ? 7 * (np - 1) : 3 * np + 8;
	e.p = malloc((3 * np + 4) * sizeof *e.p);
	e.pf = calloc(nf, sizeof *e.pf);
	if (!e.p || !e.pf) {
		free(e.p);
		free(e.pf);
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	if (np)
		memcpy(e.p, pts, 3 * np * sizeof *pts);
	if (kind == MODEL_TRIANGLE || kind == MODEL_POLYGON) {
		if (polygon_plane(&e, err, errlen) < 0) {
			free(e.p);
			free(e.pf);
			return -1;
		}
	}
	if (kind == MODEL_LINE || kind == MODEL_PLANE || kind == MODEL_DISK || kind == MODEL_CIRCLE) {
		double l = len3(e.p + 3);
		if (!(l > 0)) {
			free(e.p);
			free(e.pf);
			snprintf(err, errlen, "a non-zero direction or normal");
			return -1;
		}
		for (int i = 3; i < 6; i++)
			e.p[i] /= l;
	}
	/* float layout for the kernels */
	if (kind == MODEL_SEGMENT || kind == MODEL_POLYLINE) {
		for (size_t k = 0; k + 1 < np; k++) {
			const double *a = e.p + 3 * k, *b = a + 3;
			double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
			double l2 = dot3(ba, ba);
			float *f = e.pf + 7 * k;
			for (int i = 0; i < 3; i++) {
				f[i] = (float)a[i];
				f[3 + i] = (float)ba[i];
			}
			f[6] = l2 > 0 ? (float)(1.0 / l2) : 0.0f;
		}
	} else if (kind == MODEL_PLANE) {
		for (int i = 0; i < 3; i++)
			e.pf[i] = (float)e.p[3 + i];
		e.pf[3] = (float)dot3(e.p, e.p + 3);
	} else {
		for (size_t i = 0; i < 3 * np; i++)
			e.pf[i] = (float)e.p[i];
		e.pf[3 * np] = (float)r;
	}
	if (push(s, &e, err, errlen) < 0)
		return -1;
	if (kind == MODEL_SHAPE && model_check_nesting(s, err, errlen) < 0) {
		s->nel--;   /* refused: the shape stays as it was */
		free(s->el[s->nel].p);
		free(s->el[s->nel].pf);
		model_check_nesting(s, NULL, 0);
		return -1;
	}
	return 0;
}

static double nearest(const model_elem_t *e, const double *p, double *q);

int model_add_csg(model_shape_t *s, double w, int op, const model_shape_t *a, const model_shape_t *b,
                  double k, char *err, size_t errlen)
{
	if (!a || !b || !a->has_lip || !b->has_lip || !(a->lip > 0) || !(b->lip > 0) || a->lip_local || b->lip_local) {
		snprintf(err, errlen, "shapes with a Lipschitz bound that holds everywhere to combine (not Mandelbrot, Julia or powers above 1)");
		return -1;
	}
	if (!isfinite(w) || (op == MODEL_BLEND && !(k > 0 && isfinite(k)))) {
		snprintf(err, errlen, "%s", op == MODEL_BLEND ? "a blend radius > 0 (and a finite weight)" : "a finite weight");
		return -1;
	}
	model_elem_t e = {0};
	e.kind = MODEL_CSG;
	e.pw = 1;
	e.w = w;
	e.r = k;
	e.op = op;
	e.shape = a;
	e.shape2 = b;
	e.p = malloc(sizeof *e.p);
	e.pf = calloc(8, sizeof *e.pf);
	if (!e.p || !e.pf) {
		free(e.p);
		free(e.pf);
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	if (push(s, &e, err, errlen) < 0)
		return -1;
	if (model_check_nesting(s, err, errlen) < 0) {
		s->nel--;
		free(s->el[s->nel].p);
		free(s->el[s->nel].pf);
		model_check_nesting(s, NULL, 0);
		return -1;
	}
	return 0;
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

int model_set_weight_expr(model_shape_t *s, expr_t *x, char *err, size_t errlen)
{
	if (s->nel == 0) {
		expr_free(x);
		return snprintf(err, errlen, "an element before its weight"), -1;
	}
	model_elem_t *e = &s->el[s->nel - 1];
	if (e->kind == MODEL_VORONOI || e->kind == MODEL_SHAPE || e->kind == MODEL_CSG) {
		expr_free(x);
		return snprintf(err, errlen, "a constant weight on voronoi, distance-to and combination elements"), -1;
	}
	expr_free(e->wexpr);
	e->wexpr = x;
	e->w = 1;
	return 0;
}

/* The weight of e at the setup point q. */
static double weight_at(const model_elem_t *e, const double *q)
{
	return e->wexpr ? expr_eval(e->wexpr, q[0], q[1], q[2]) : e->w;
}

int model_set_measure(model_shape_t *s, double pw, int metric, const double mp[3], char *err, size_t errlen)
{
	if (s->nel == 0)
		return snprintf(err, errlen, "an element before its measure"), -1;
	model_elem_t *e = &s->el[s->nel - 1];
	if (!(pw >= 1 && pw <= 16))
		return snprintf(err, errlen, "a power from 1 to 16 (below 1 the power of a distance has no Lipschitz bound at the element)"), -1;
	if (e->kind == MODEL_VORONOI || e->kind == MODEL_SHAPE || e->kind == MODEL_CSG)
		return snprintf(err, errlen, "a power or metric on a distance element (not voronoi, distance-to or a combination)"), -1;
	if (metric != MODEL_EUCLID && e->kind != MODEL_POINT && e->kind != MODEL_POINTS)
		return snprintf(err, errlen, "a metric on a point or points element only"), -1;
	if (metric == MODEL_LP && !(mp[0] >= 1 && mp[0] <= 64))
		return snprintf(err, errlen, "an Lp metric with 1 <= p <= 64"), -1;
	if (metric == MODEL_ANISO && !(mp[0] > 0 && mp[1] > 0 && mp[2] > 0 && mp[0] <= 1e6 && mp[1] <= 1e6 && mp[2] <= 1e6))
		return snprintf(err, errlen, "anisotropic metric weights above 0"), -1;
	e->pw = pw;
	e->metric = metric;
	if (metric != MODEL_EUCLID)
		memcpy(e->mp, mp, sizeof e->mp);
	e->measured = pw != 1 || metric != MODEL_EUCLID;
	return 0;
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
		d = nearest(e, q, near);
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
	return e->measured ? measure(e, q, NULL) : nearest(e, q, near);
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
	return nearest(e, q, near);
}

int model_check_nesting(model_shape_t *s, char *err, size_t errlen)
{
	int nest = 0;
	double ev = 1, gr = 1;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		if (e->kind == MODEL_SHAPE || e->kind == MODEL_CSG) {
			for (int j = 0; j < (e->kind == MODEL_CSG ? 2 : 1); j++) {
				const model_shape_t *o = j ? e->shape2 : e->shape;
				if (o->nest + 1 > nest)
					nest = o->nest + 1;
				ev += o->eval_cost;
				gr += o->eval_cost + o->grad_cost;
			}
		} else {   /* one distance evaluation, however many points the element holds */
			ev += 1;
			gr += 1;
		}
	}
	if (s->c.kind == MODEL_C_SHAPE && s->c.shape) {
		if (s->c.shape->nest + 1 > nest)
			nest = s->c.shape->nest + 1;
		ev += s->c.shape->eval_cost;
		gr += 6 * s->c.shape->eval_cost;   /* central differences of c */
	} else if (s->c.kind != MODEL_C_CONST) {
		ev += 1;
		gr += 6;
	}
	s->nest = nest;
	s->eval_cost = ev;
	s->grad_cost = gr;
	if (nest > MODEL_MAX_NEST) {
		if (err)
			snprintf(err, errlen, "shapes nested at most %d deep (through distance-to and c shape), "
				"found %d", MODEL_MAX_NEST, nest);
		return -1;
	}
	if (ev + gr > MODEL_MAX_COST) {
		if (err)
			snprintf(err, errlen, "a shape that costs at most %d distance evaluations per point with "
				"its gradient, found %.0f (every distance-to repeats the other shape's work)",
				MODEL_MAX_COST, ev + gr);
		return -1;
	}
	return 0;
}

/* The point c of segment a b nearest to p; returns |p - c|. */
static double seg_nearest(const double *p, const double *a, const double *b, double c[3])
{
	double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
	double pa[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
	double l2 = dot3(ba, ba), h = l2 > 0 ? dot3(pa, ba) / l2 : 0;
	h = h < 0 ? 0 : h > 1 ? 1 : h;
	for (int j = 0; j < 3; j++)
		c[j] = a[j] + h * ba[j];
	double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
	return len3(d);
}

/* Nearest point q of the element to p (setup frame); returns the distance. */
static double nearest(const model_elem_t *e, const double *p, double *q)
{
	double best = INFINITY;
	switch (e->kind) {
	case MODEL_VORONOI: {
		/* e_k = d(p, N_k) - w_k; the estimate (e2 - e1)/2 has gradient (u2 - u1)/2
		 * with u the unit vectors from the nearest points of the two nuclei; q is
		 * placed so that (p - q) / estimate is that gradient */
		double e1 = INFINITY, e2 = INFINITY, n1[3] = {0, 0, 0}, n2[3] = {0, 0, 0}, d1 = 0, d2 = 0, m1 = 1, m2 = 1;
		/* the nucleus being gathered (a run of segments): its smallest e, nearest point, d, 1/M */
		double ce = INFINITY, cn[3] = {0, 0, 0}, cd = 0, cm = 1;
		for (size_t k = 0; k <= e->np; k++) {
			if (k == e->np || k == 0 || e->grp[k] != e->grp[k - 1]) {
				if (k > 0) {   /* fold the finished nucleus into the two smallest */
					if (ce < e1) {
						e2 = e1, d2 = d1, m2 = m1;
						memcpy(n2, n1, sizeof n1);
						e1 = ce, d1 = cd, m1 = cm;
						memcpy(n1, cn, sizeof cn);
					} else if (ce < e2) {
						e2 = ce, d2 = cd, m2 = cm;
						memcpy(n2, cn, sizeof cn);
					}
				}
				ce = INFINITY;
				if (k == e->np)
					break;
			}
			double c[3], d = seg_nearest(p, e->p + 6 * k, e->p + 6 * k + 3, c);
			double ev = d * e->nm[k] - e->nw[k];
			if (ev < ce) {
				ce = ev, cd = d, cm = e->nm[k];
				memcpy(cn, c, sizeof c);
			}
		}
		double est = (e2 - e1) / 2;
		for (int j = 0; j < 3; j++) {
			double u1 = d1 > 0 ? m1 * (p[j] - n1[j]) / d1 : 0, u2 = d2 > 0 ? m2 * (p[j] - n2[j]) / d2 : 0;
			q[j] = p[j] - est * (u2 - u1) / 2;
		}
		return est;
	}
	case MODEL_POINT: case MODEL_POINTS:
		for (size_t k = 0; k < e->np; k++) {
			const double *a = e->p + 3 * k;
			double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
			double l = len3(d);
			if (l < best) {
				best = l;
				memcpy(q, a, 3 * sizeof *q);
			}
		}
		return best;
	case MODEL_SEGMENT: case MODEL_POLYLINE:
		for (size_t k = 0; k + 1 < e->np; k++) {
			double c[3], l = seg_nearest(p, e->p + 3 * k, e->p + 3 * k + 3, c);
			if (l < best) {
				best = l;
				memcpy(q, c, sizeof c);
			}
		}
		return best;
	case MODEL_BOX:
		for (int j = 0; j < 3; j++) {
			double lo = fmin(e->p[j], e->p[3 + j]), hi = fmax(e->p[j], e->p[3 + j]);
			q[j] = p[j] < lo ? lo : p[j] > hi ? hi : p[j];
		}
		return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
	case MODEL_TRIANGLE: case MODEL_POLYGON: {
		const double *v = e->p, *n = e->p + 3 * e->np;
		double h = (p[0] - v[0]) * n[0] + (p[1] - v[1]) * n[1] + (p[2] - v[2]) * n[2];
		double pp[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
		/* inside test in the plane: the crossing number along the axis pair the normal leaves */
		int ax = fabs(n[0]) >= fabs(n[1]) && fabs(n[0]) >= fabs(n[2]) ? 0 : fabs(n[1]) >= fabs(n[2]) ? 1 : 2;
		int i0 = (ax + 1) % 3, i1 = (ax + 2) % 3, in = 0;
		for (size_t k = 0, j = e->np - 1; k < e->np; j = k++) {
			const double *a = v + 3 * k, *b = v + 3 * j;
			if ((a[i1] > pp[i1]) != (b[i1] > pp[i1])
			    && pp[i0] < (b[i0] - a[i0]) * (pp[i1] - a[i1]) / (b[i1] - a[i1]) + a[i0])
				in = !in;
		}
		if (in) {
			memcpy(q, pp, sizeof pp);
			return fabs(h);
		}
		for (size_t k = 0; k < e->np; k++) {
			double c[3], l = seg_nearest(p, v + 3 * k, v + 3 * ((k + 1) % e->np), c);
			if (l < best) {
				best = l;
				memcpy(q, c, sizeof c);
			}
		}
		return best;
	}
	case MODEL_CIRCLE: {
		const double *a = e->p, *n = e->p + 3;
		double v[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
		double h = dot3(v, n);
		double rv[3] = {v[0] - h * n[0], v[1] - h * n[1], v[2] - h * n[2]}, rho = len3(rv);
		if (!(rho > 0)) {   /* on the axis: every ring point is nearest; take one */
			double t[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0}, k = dot3(t, n);
			for (int i = 0; i < 3; i++)
				rv[i] = t[i] - k * n[i];
			rho = len3(rv);
		}
		for (int i = 0; i < 3; i++)
			q[i] = a[i] + e->r / rho * rv[i];
		double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
		return len3(d);
	}
	case MODEL_LINE: case MODEL_PLANE: case MODEL_DISK: {
		const double *a = e->p, *n = e->p + 3;
		double v[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
		double h = dot3(v, n);
		if (e->kind == MODEL_LINE) {
			for (int i = 0; i < 3; i++)
				q[i] = a[i] + h * n[i];
		} else {
			double rv[3] = {v[0] - h * n[0], v[1] - h * n[1], v[2] - h * n[2]};
			double rho = len3(rv), s = 1;
			if (e->kind == MODEL_DISK && rho > e->r)
				s = e->r / rho;
			for (int i = 0; i < 3; i++)
				q[i] = a[i] + s * rv[i];
		}
		double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
		return len3(d);
	}
	}
	return 0;
}

static double mandel_count(const model_param_t *c, const double *q, int smooth)
{
	return model_count(c, q, smooth);
}

static double mandel(const model_param_t *c, const double *q)
{
	return c->c0 + c->amp * mandel_count(c, q, c->smooth) / c->maxit;
}

int model_de_level(const model_param_t *c, double *m0)
{
	if (c->kind != MODEL_C_MANDEL || !c->smooth || c->amp == 0)
		return 0;
	*m0 = -c->c0 * c->maxit / c->amp;
	return *m0 > 0 && *m0 < c->maxit;
}

static unsigned hash3(unsigned seed, int x, int y, int z)
{
	unsigned h = seed * 0x9e3779b1u ^ (unsigned)x * 0x85ebca77u ^ (unsigned)y * 0xc2b2ae3du ^ (unsigned)z * 0x27d4eb2fu;
	h ^= h >> 15;
	h *= 0x2c1b3c6du;
	h ^= h >> 12;
	h *= 0x297a2d39u;
	h ^= h >> 15;
	return h;
}

double model_noise(unsigned seed, double x, double y, double z)
{
	double fx = floor(x), fy = floor(y), fz = floor(z);
	int ix = (int)fx, iy = (int)fy, iz = (int)fz;
	double tx = x - fx, ty = y - fy, tz = z - fz;
	double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty), sz = tz * tz * (3 - 2 * tz);
	double v[8];
	for (int k = 0; k < 8; k++)
		v[k] = hash3(seed, ix + (k & 1), iy + ((k >> 1) & 1), iz + (k >> 2)) / 2147483647.5 - 1.0;
	double x00 = v[0] + sx * (v[1] - v[0]), x10 = v[2] + sx * (v[3] - v[2]);
	double x01 = v[4] + sx * (v[5] - v[4]), x11 = v[6] + sx * (v[7] - v[6]);
	double y0 = x00 + sy * (x10 - x00), y1 = x01 + sy * (x11 - x01);
	return y0 + sz * (y1 - y0);
}

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

double model_elem_distance(const model_elem_t *e, const double q[3])
{
	double near[3];
	return nearest(e, q, near);
}

double model_eval(const model_shape_t *s, const double p[3])
{
	double q[3], near[3], sum = 0;
	apply(s->minv, p, q);
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		double d = e->kind == MODEL_SHAPE || e->kind == MODEL_CSG ? model_elem_value(e, p, q)
		         : e->measured ? measure(e, q, NULL) : nearest(e, q, near);
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
		double d = nearest(e, q, near);
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
