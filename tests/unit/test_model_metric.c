/* test_model_metric.c: distance powers and metrics: the sum of squares is a sphere, L1/Lp/anisotropic values, their Lipschitz bounds and gradients. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

/* Random pairs inside the shape's box: |f(P) - f(Q)| <= L |P - Q|; the gradient against central differences. */
static void check_lip(const model_shape_t *s, const char *what)
{
	int bad = 0, gbad = 0;
	srand(5);
	for (int i = 0; i < 3000; i++) {
		double p[3], q[3], dd = 0;
		for (int j = 0; j < 3; j++) {
			p[j] = s->box[j] + (s->box[3 + j] - s->box[j]) * rand() / RAND_MAX;
			q[j] = fmin(fmax(p[j] + 0.2 * rand() / RAND_MAX - 0.1, s->box[j]), s->box[3 + j]);
			dd += (p[j] - q[j]) * (p[j] - q[j]);
		}
		bad += fabs(model_eval(s, p) - model_eval(s, q)) > s->lip * sqrt(dd) * (1 + 1e-9) + 1e-12;
		double g[3], h = 1e-6;
		model_grad(s, p, g);
		for (int j = 0; j < 3; j++) {
			double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]};
			a[j] += h, b[j] -= h;
			gbad += fabs((model_eval(s, a) - model_eval(s, b)) / (2 * h) - g[j]) > 1e-4 * (1 + fabs(g[j]));
		}
	}
	CHECK(bad == 0 && gbad < 10, "%s: L = %g holds on 3000 pairs in the region (%d violations), gradient (%d off)", what, s->lip, bad, gbad);
}

int main(void)
{
	char err[200];
	const char *warn;
	/* sum of squared distances to three points = c: the sphere about the centroid G of radius
	 * sqrt((c - sum |F_i - G|^2) / 3) */
	double F[9] = {-0.8, 0, 0, 0.8, 0, 0, 0, 1.2, 0.3};
	model_shape_t *s = model_new();
	for (int i = 0; i < 3; i++) {
		model_add(s, MODEL_POINT, 1, F + 3 * i, 1, 0, NULL, err, sizeof err);
		CHECK(model_set_measure(s, 2, MODEL_EUCLID, (double[]){0, 0, 0}, err, sizeof err) == 0, "power 2");
	}
	s->c.c0 = 3.4;
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->bounded && s->lip_local, "sum of squares: bounded, L local to the region");
	double G[3] = {0, 0.4, 0.1}, m2 = 0;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			m2 += (F[3 * i + j] - G[j]) * (F[3 * i + j] - G[j]);
	double R = sqrt((3.4 - m2) / 3);
	int off = 0;
	for (int k = 0; k < 50; k++) {
		double th = k * 0.7, ph = k * 1.3, p[3] = {G[0] + R * sin(th) * cos(ph), G[1] + R * sin(th) * sin(ph), G[2] + R * cos(th)};
		off += fabs(model_eval(s, p)) > 1e-9;
	}
	CHECK(off == 0 && s->radius >= R, "sum of squares = 3.4 is the sphere of radius %.4f about the centroid (%d points off; region %g)", R, off, s->radius);
	check_lip(s, "power 2");
	model_free(s);
	/* L1: |x| + |y| + |z| - 0.9, an octahedron; L6; anisotropic */
	double mp[3][3] = {{1, 0, 0}, {6, 0, 0}, {1, 4, 0.5}};
	int met[3] = {MODEL_LP, MODEL_LP, MODEL_ANISO};
	const char *nm[3] = {"L1", "L6", "anisotropic"};
	for (int m = 0; m < 3; m++) {
		s = model_new();
		model_add(s, MODEL_POINT, 1, (double[]){0.2, 0, 0}, 1, 0, NULL, err, sizeof err);
		CHECK(model_set_measure(s, 1, met[m], mp[m], err, sizeof err) == 0, "%s metric", nm[m]);
		s->c.c0 = 0.9;
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->bounded, "%s: bounded", nm[m]);
		double p[3] = {0.5, -0.3, 0.2}, v[3] = {0.3, -0.3, 0.2}, want;
		if (m == 0)
			want = 0.8;
		else if (m == 1)
			want = pow(pow(0.3, 6) * 2 + pow(0.2, 6), 1.0 / 6);
		else
			want = sqrt(0.09 + 4 * 0.09 + 0.5 * 0.04);
		(void)v;
		CHECK(fabs(model_eval(s, p) - (want - 0.9)) < 1e-12, "%s: value %g (want %g)", nm[m], model_eval(s, p) + 0.9, want);
		check_lip(s, nm[m]);
		model_free(s);
	}
	s = model_new();
	model_add(s, MODEL_SEGMENT, 1, (double[]){0, 0, 0, 1, 0, 0}, 2, 0, NULL, err, sizeof err);
	CHECK(model_set_measure(s, 1, MODEL_LP, (double[]){1, 0, 0}, err, sizeof err) < 0 && strstr(err, "point or points"), "a metric on a segment refused");
	CHECK(model_set_measure(s, 0.5, MODEL_EUCLID, (double[]){0, 0, 0}, err, sizeof err) < 0 && strstr(err, "from 1 to 16"), "a power below 1 refused");
	model_free(s);
	return UNIT_DONE();
}
