/* test_model_vor.c: the 3D Voronoi element with multiplicative weights and polyline nuclei: the estimate (e2 - e1)/2 over distinct nuclei, its bound max(1/M), float agreement. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

static double seg_d(const double *a, const double *b, const double *p)
{
	double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, pa[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
	double l2 = ba[0] * ba[0] + ba[1] * ba[1] + ba[2] * ba[2], h = l2 > 0 ? (pa[0] * ba[0] + pa[1] * ba[1] + pa[2] * ba[2]) / l2 : 0;
	h = h < 0 ? 0 : h > 1 ? 1 : h;
	double v[3] = {pa[0] - h * ba[0], pa[1] - h * ba[1], pa[2] - h * ba[2]};
	return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

int main(void)
{
	char err[200];
	const char *warn;
	/* nucleus 0: point, M = 2; nucleus 1: a polyline of 3 segments (one nucleus); nucleus 2: point, M = 0.5, W = 0.1 */
	double ab[] = {0.5, 0, 0, 0.5, 0, 0,
	               -1, 1, 0, 0, 0.5, 0,   0, 0.5, 0, 1, 1, 0,   1, 1, 0, 1, 1, 1,
	               0, -1, 0.5, 0, -1, 0.5};
	double wt[] = {0, 0, 0, 0, 0.1}, fac[] = {2, 1, 1, 1, 0.5};
	int grp[] = {0, 1, 1, 1, 2};
	model_shape_t *s = model_new();
	CHECK(model_add_nuclei2(s, 1, ab, wt, fac, grp, 5, err, sizeof err) == 0, "three nuclei of five segments");
	s->c.c0 = 0.05;
	s->user_box = 1;
	memcpy(s->box, (double[]){-2, -2, -2, 2, 2, 2}, sizeof s->box);
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->has_lip && fabs(s->lip - 2) < 1e-12, "L = max(1/M) = 2 (%g)", s->lip);
	int bad = 0, lipbad = 0, fbad = 0;
	srand(9);
	for (int i = 0; i < 3000; i++) {
		double p[3], q[3], dd = 0;
		for (int j = 0; j < 3; j++) {
			p[j] = 4.0 * rand() / RAND_MAX - 2;
			q[j] = p[j] + 0.1 * rand() / RAND_MAX - 0.05;
			dd += (p[j] - q[j]) * (p[j] - q[j]);
		}
		double e[3];
		e[0] = seg_d(ab, ab + 3, p) / 2;
		e[1] = fmin(seg_d(ab + 6, ab + 9, p), fmin(seg_d(ab + 12, ab + 15, p), seg_d(ab + 18, ab + 21, p)));
		e[2] = seg_d(ab + 24, ab + 27, p) / 0.5 - 0.1;
		double lo = fmin(e[0], fmin(e[1], e[2])), hi = e[0] + e[1] + e[2] - lo - fmax(e[0], fmax(e[1], e[2]));
		double want = (hi - lo) / 2 - 0.05, f = model_eval(s, p);
		bad += fabs(f - want) > 1e-12;
		lipbad += fabs(model_eval(s, q) - f) > s->lip * sqrt(dd) * (1 + 1e-9);
		float x[8], y[8], z[8], o[8];
		for (int k = 0; k < 8; k++)
			x[k] = (float)p[0], y[k] = (float)p[1], z[k] = (float)p[2];
		model_eval8(s, x, y, z, o);
		fbad += fabs(o[0] - model_eval(s, (double[]){x[0], y[0], z[0]})) > 1e-5;
	}
	CHECK(bad == 0, "the estimate is (e2 - e1)/2 over distinct nuclei, e = d/M - W (%d wrong)", bad);
	CHECK(lipbad == 0 && fbad == 0, "Lipschitz 2 on 3000 pairs (%d), the float kernel agrees (%d)", lipbad, fbad);
	model_free(s);
	s = model_new();
	CHECK(model_add_nuclei2(s, 1, ab, wt, fac, (int[]){0, 0, 0, 0, 0}, 5, err, sizeof err) < 0 && strstr(err, "at least 2 nuclei"), "one polyline nucleus alone refused");
	CHECK(model_add_nuclei2(s, 1, ab, wt, (double[]){1, 1, 1, 1, 0}, grp, 5, err, sizeof err) < 0 && strstr(err, "above 0"), "M = 0 refused");
	model_free(s);
	return UNIT_DONE();
}
