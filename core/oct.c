/* oct.c: octree conversion of a shape with spherical or cubical cell tests, and painter's drawing of the leaves. */
#include "oct.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
	const model_shape_t *s;
	int depth, test;
	oct_leaf_t *leaves;
	size_t n, cap;
	oct_stats_t *st;
	int oom, too_many;
	int keep;                /* store the leaves (else only count them) */
	int exact_points;        /* identity linear part: point ranges are exact */
	double margin;           /* float rounding allowance of the float tests */
	int fast_cubical;        /* points only, constant c, translation only */
} build_t;

static void add_leaf(build_t *b, const double *p, double h)
{
	if (!b->keep)
		return;   /* counting only */
	if (b->n == OCT_MAX_LEAVES) {
		b->too_many = 1;
		return;
	}
	if (b->n == b->cap) {
		size_t cap = b->cap ? 2 * b->cap : 1024;
		oct_leaf_t *q = realloc(b->leaves, cap * sizeof *q);
		if (!q) {
			b->oom = 1;
			return;
		}
		b->leaves = q;
		b->cap = cap;
	}
	oct_leaf_t *l = &b->leaves[b->n++];
	for (int i = 0; i < 3; i++)
		l->c[i] = (float)p[i];
	l->h = (float)h;
}

/* Interval enclosure of f over the cube (centre p, half side h): 0 when it
 * cannot contain 0, 1 when it may. */
static int cubical(const build_t *b, const double *p, double h)
{
	const model_shape_t *s = b->s;
	double q[3], lo = 0, hi = 0, r = sqrt(3.0) * h;
	const double *mi = s->minv;
	for (int i = 0; i < 3; i++)
		q[i] = mi[i * 4] * p[0] + mi[i * 4 + 1] * p[1] + mi[i * 4 + 2] * p[2] + mi[i * 4 + 3];
	double rs = r * s->norm_minv;
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		double dlo, dhi;
		if (e->kind == MODEL_POINT && b->exact_points && !e->measured) {
			const double *a = e->p;
			double mn = 0, mx = 0;
			for (int j = 0; j < 3; j++) {
				double l = q[j] - h, u = q[j] + h;
				double c = a[j] < l ? l - a[j] : a[j] > u ? a[j] - u : 0;
				double far = fmax(fabs(a[j] - l), fabs(a[j] - u));
				mn += c * c;
				mx += far * far;
			}
			dlo = sqrt(mn);
			dhi = sqrt(mx);
		} else if (e->kind == MODEL_SHAPE) {
			double d = fabs(model_eval(e->shape, p)) / e->shape->lip;
			dlo = fmax(d - r, 0);
			dhi = d + r;
		} else if (e->kind == MODEL_CSG) {   /* signed, 1-Lipschitz in the actual frame */
			double d = model_elem_value(e, p, q);
			dlo = d - r;
			dhi = d + r;
		} else {
			double d = model_elem_measure(e, q);
			dlo = fmax(d - e->lipm * rs, 0);
			dhi = d + e->lipm * rs;
		}
		if (e->wexpr) {   /* the weight's interval over the cell's setup box times [dlo, dhi] */
			double cl[3] = {q[0] - rs, q[1] - rs, q[2] - rs}, ch[3] = {q[0] + rs, q[1] + rs, q[2] + rs}, wl, wh, gw;
			if (expr_bound(e->wexpr, cl, ch, &wl, &wh, &gw) < 0)
				return 1;
			double a = wl * dlo, b2 = wl * dhi, c = wh * dlo, d = wh * dhi;
			lo += fmin(fmin(a, b2), fmin(c, d));
			hi += fmax(fmax(a, b2), fmax(c, d));
		} else if (e->w >= 0) {
			lo += e->w * dlo;
			hi += e->w * dhi;
		} else {
			lo += e->w * dhi;
			hi += e->w * dlo;
		}
	}
	/* the parameter: exact for constants, interval arithmetic for expressions,
	 * its Lipschitz enclosure otherwise */
	double clo, chi;
	if (s->c.kind == MODEL_C_CONST) {
		clo = chi = s->c.c0;
	} else {
		double g = s->lip, sum = 0;
		for (size_t i = 0; i < s->nel; i++)
			sum += s->el[i].wexpr ? 0 : fabs(s->el[i].w) * (s->el[i].kind == MODEL_SHAPE || s->el[i].kind == MODEL_CSG ? 1 : s->norm_minv * s->el[i].lipm);
		g = fmax(s->lip - sum, 0);
		double c = model_param(s, p, q);
		clo = c - g * r;
		chi = c + g * r;
		if (s->c.kind == MODEL_C_EXPR) {
			double bl[3], bh[3], v0, v1, gg;
			for (int i = 0; i < 3; i++) {
				double ext = h * (fabs(mi[i * 4]) + fabs(mi[i * 4 + 1]) + fabs(mi[i * 4 + 2]));
				bl[i] = q[i] - ext;
				bh[i] = q[i] + ext;
			}
			if (expr_bound(s->c.expr, bl, bh, &v0, &v1, &gg) == 0) {
				clo = fmax(clo, v0);
				chi = fmin(chi, v1);
			}
		}
	}
	lo -= chi;
	hi -= clo;
	return lo <= 0 && hi >= 0;
}

/* Test the 8 children of the cell (centre p, half side h) and recurse into those kept.
 * The spherical test evaluates the 8 child centres in one model_eval8 call; its
 * threshold carries a small margin for float rounding so that no cell holding
 * the surface is dropped. */
static void visit_children(build_t *b, const double *p, double h, int level)
{
	double q[8][3], hc = h / 2;
	int keep[8];
	float x[8], y[8], z[8], f[8];
	for (int c = 0; c < 8; c++) {
		q[c][0] = p[0] + ((c & 1) ? hc : -hc);
		q[c][1] = p[1] + ((c & 2) ? hc : -hc);
		q[c][2] = p[2] + ((c & 4) ? hc : -hc);
		x[c] = (float)q[c][0];
		y[c] = (float)q[c][1];
		z[c] = (float)q[c][2];
	}
	b->st->visited += 8;
	b->st->evals += 8;
	if (b->s->de) {
		/* a distance-estimated shape (Douady-Hubbard): the estimate at the centre bounds the
		 * distance to the surface, so a cell is empty when it exceeds the half-diagonal (either
		 * test); a centre without a bound (never escaped, or undefined) keeps its cell */
		double lim = sqrt(3.0) * hc * (1 + 1e-9);
		for (int c = 0; c < 8; c++) {
			double d;
			keep[c] = !model_de_known(b->s, q[c], &d) || !(fabs(d) > lim);
		}
	} else if (b->test == OCT_SPHERICAL) {
		model_eval8(b->s, x, y, z, f);
		double lim = b->s->lip * sqrt(3.0) * hc * (1 + 1e-4) + b->margin;
		for (int c = 0; c < 8; c++)
			keep[c] = !(f[c] == f[c]) || fabs(f[c]) <= lim;
	} else if (b->fast_cubical) {
		/* all elements are points, c is constant and the frame is only translated:
		 * the exact range of each |P - A| over the 8 child cubes, in float lanes */
		const model_shape_t *s = b->s;
		float lo8[8], hi8[8];
		float hx = (float)hc;
		for (int c = 0; c < 8; c++) {
			x[c] += (float)s->minv[3];
			y[c] += (float)s->minv[7];
			z[c] += (float)s->minv[11];
			lo8[c] = hi8[c] = (float)-s->c.c0;
		}
		for (size_t i = 0; i < s->nel; i++) {
			const float *a = s->el[i].pf, w = (float)s->el[i].w;
			const float ax = a[0], ay = a[1], az = a[2];
			for (int c = 0; c < 8; c++) {
				float ex = fabsf(x[c] - ax), ey = fabsf(y[c] - ay), ez = fabsf(z[c] - az);
				float nx = ex - hx, ny = ey - hx, nz = ez - hx;
				nx = nx > 0.0f ? nx : 0.0f;
				ny = ny > 0.0f ? ny : 0.0f;
				nz = nz > 0.0f ? nz : 0.0f;
				float fx = ex + hx, fy = ey + hx, fz = ez + hx;
				float dmin = sqrtf(nx * nx + ny * ny + nz * nz), dmax = sqrtf(fx * fx + fy * fy + fz * fz);
				float l = w >= 0 ? dmin : dmax, h = w >= 0 ? dmax : dmin;
				lo8[c] += w * l;
				hi8[c] += w * h;
			}
		}
		float m = (float)b->margin;
		for (int c = 0; c < 8; c++)
			keep[c] = lo8[c] <= m && hi8[c] >= -m;
	} else {
		for (int c = 0; c < 8; c++)
			keep[c] = cubical(b, q[c], hc);
	}
	for (int c = 0; c < 8 && !b->oom && !b->too_many; c++) {
		if (!keep[c])
			continue;
		if (level + 1 == b->depth) {
			b->st->leaves++;
			add_leaf(b, q[c], hc);
		} else {
			visit_children(b, q[c], hc, level + 1);
		}
	}
}

int oct_build(const model_shape_t *s, int depth, int test, oct_leaf_t **leaves, size_t *n,
              oct_stats_t *st, char *err, size_t errlen)
{
	if (leaves)
		*leaves = NULL;
	*n = 0;
	memset(st, 0, sizeof *st);
	if (depth < 1 || depth > 12) {
		snprintf(err, errlen, "expected an octree depth from 1 to 12");
		return -1;
	}
	if (!s->has_lip && !s->de) {
		snprintf(err, errlen, "the octree needs a Lipschitz bound or a distance estimate, and this shape's defining parameter has neither (use raytrace, which brackets)");
		return -1;
	}
	build_t b;
	memset(&b, 0, sizeof b);
	b.s = s;
	b.depth = depth;
	b.test = test;
	b.st = st;
	b.keep = leaves != NULL;
	const double *m = s->m;
	b.exact_points = m[0] == 1 && m[1] == 0 && m[2] == 0 && m[4] == 0 && m[5] == 1 && m[6] == 0
	              && m[8] == 0 && m[9] == 0 && m[10] == 1;
	const double *x = s->root;
	double h = fmax(x[3] - x[0], fmax(x[4] - x[1], x[5] - x[2])) / 2;
	double p[3] = {(x[0] + x[3]) / 2, (x[1] + x[4]) / 2, (x[2] + x[5]) / 2};
	b.fast_cubical = b.exact_points && s->c.kind == MODEL_C_CONST;
	for (size_t i = 0; i < s->nel; i++)
		if (s->el[i].kind != MODEL_POINT)
			b.fast_cubical = 0;
	b.margin = 1e-5 * (1 + fabs(s->c.c0));
	for (size_t i = 0; i < s->nel; i++)
		b.margin += 1e-5 * fabs(s->el[i].w) * (2 * h + 1);
	st->visited = 1;   /* the root is kept without a test: it is the clip box */
	visit_children(&b, p, h, 0);
	if (b.oom || b.too_many) {
		free(b.leaves);
		if (b.oom)
			snprintf(err, errlen, "out of memory for the octree leaves");
		else
			snprintf(err, errlen, "the octree has more than %u leaves to draw (the memory limit of "
				"drawing): lower its depth, or count its cells with 'draw no'", (unsigned)OCT_MAX_LEAVES);
		return -1;
	}
	if (!leaves)
		return 0;
	*leaves = b.leaves;
	*n = b.n;
	return 0;
}
