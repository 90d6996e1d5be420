/* test_model_csg.c: constructive combinations: union/intersection/difference/blend values, their 1-Lipschitz bound, regions, octree and float kernel agreement. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

static model_shape_t *sphere(double x, double y, double z, double r)
{
	char err[128];
	const char *warn;
	model_shape_t *s = model_new();
	model_add(s, MODEL_POINT, 1, (double[]){x, y, z}, 1, 0, NULL, err, sizeof err);
	s->c.c0 = r;
	model_prepare(s, err, sizeof err, &warn);
	return s;
}

int main(void)
{
	char err[200];
	const char *warn;
	model_shape_t *a = sphere(-0.5, 0, 0, 1), *b = sphere(0.5, 0, 0, 1);
	const char *names[] = {"union", "intersection", "difference", "blend"};
	for (int op = MODEL_UNION; op <= MODEL_BLEND; op++) {
		model_shape_t *s = model_new();
		CHECK(model_add_csg(s, 1, op, a, b, 0.5, err, sizeof err) == 0 && model_prepare(s, err, sizeof err, &warn) == 0,
		      "%s: prepared without a bound box (%s)", names[op], err);
		CHECK(s->has_lip && fabs(s->lip - 1) < 1e-12, "%s: L = 1 (%g)", names[op], s->lip);
		/* values against the analytic spheres; the Lipschitz bound on random pairs; float agrees */
		int bad = 0, lipbad = 0, fbad = 0;
		srand(7 + op);
		for (int i = 0; i < 2000; i++) {
			double p[3], q[3];
			for (int j = 0; j < 3; j++) {
				p[j] = 4.0 * rand() / RAND_MAX - 2;
				q[j] = p[j] + 0.2 * rand() / RAND_MAX - 0.1;
			}
			double da = sqrt((p[0] + 0.5) * (p[0] + 0.5) + p[1] * p[1] + p[2] * p[2]) - 1;
			double db = sqrt((p[0] - 0.5) * (p[0] - 0.5) + p[1] * p[1] + p[2] * p[2]) - 1;
			double want = op == MODEL_UNION ? fmin(da, db) : op == MODEL_INTERSECTION ? fmax(da, db) : op == MODEL_DIFFERENCE ? fmax(da, -db) : 0;
			double f = model_eval(s, p);
			if (op == MODEL_BLEND)
				bad += !(f <= fmin(da, db) + 1e-12 && f >= fmin(da, db) - 0.5 / 4 - 1e-12);
			else
				bad += fabs(f - want) > 1e-12;
			double dpq = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
			lipbad += fabs(model_eval(s, q) - f) > dpq * (1 + 1e-9);
			float x[8], y[8], z[8], o[8];
			for (int k = 0; k < 8; k++)
				x[k] = (float)p[0], y[k] = (float)p[1], z[k] = (float)p[2];
			model_eval8(s, x, y, z, o);
			fbad += fabs(o[0] - f) > 1e-5;
			double g[3], h = 1e-6, num[3];
			model_grad(s, p, g);
			for (int j = 0; j < 3; j++) {
				double pa[3] = {p[0], p[1], p[2]}, pb[3] = {p[0], p[1], p[2]};
				pa[j] += h, pb[j] -= h;
				num[j] = (model_eval(s, pa) - model_eval(s, pb)) / (2 * h);
			}
			if (fabs(da - db) > 1e-3 && fabs(da + db) > 1e-3 && fabs(fabs(da - db) - 0.5) > 1e-3)
				fbad += fabs(g[0] - num[0]) + fabs(g[1] - num[1]) + fabs(g[2] - num[2]) > 1e-4;
		}
		CHECK(bad == 0, "%s: values as the analytic spheres give (%d wrong)", names[op], bad);
		CHECK(lipbad == 0, "%s: |f(P) - f(Q)| <= |P - Q| on 2000 random pairs (%d violations)", names[op], lipbad);
		CHECK(fbad == 0, "%s: the float kernel and the gradient agree with the double value (%d off)", names[op], fbad);
		const double *bx = s->box;
		CHECK(op == MODEL_INTERSECTION ? bx[0] >= -0.5 - 1e-3 && bx[3] <= 0.5 + 1e-3
		      : op == MODEL_DIFFERENCE ? bx[0] <= -1.5 + 1e-9 && bx[3] >= 0 && bx[3] <= 0.5 + 1e-3
		      : bx[0] <= -1.5 + 1e-9 && bx[3] >= 1.5 - 1e-9,
		      "%s: region from the operands' (x %g..%g)", names[op], bx[0], bx[3]);
		model_free(s);
	}
	model_shape_t *s = model_new();
	CHECK(model_add_csg(s, 1, MODEL_BLEND, a, b, 0, err, sizeof err) < 0 && strstr(err, "blend radius > 0"), "blend radius 0 refused: %s", err);
	model_free(s);
	model_free(a);
	model_free(b);
	return UNIT_DONE();
}
