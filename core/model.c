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
