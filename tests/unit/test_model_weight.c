/* test_model_weight.c: weights that vary with position: values, the Lipschitz bound over the box, gradient, the bound box required. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

int main(void)
{
	char err[200];
	const char *warn;
	size_t at;
	model_shape_t *s = model_new();
	double F[9] = {-1, 0, 0, 1, 0, 0, 0, 1.2, 0.3};
	for (int i = 0; i < 3; i++) {
		expr_t *w;
		CHECK(expr_compile(i == 2 ? "1+0.2*sin(3*x)" : "1+0.15*y", &w, err, sizeof err, &at) == 0, "weight expression");
		model_add(s, MODEL_POINT, 1, F + 3 * i, 1, 0, NULL, err, sizeof err);
		CHECK(model_set_weight_expr(s, w, err, sizeof err) == 0, "set the weight");
	}
	s->c.c0 = 3.6;
	CHECK(model_prepare(s, err, sizeof err, &warn) < 0 && strstr(err, "a weight varies with position"), "no bound box: refused, saying why (%s)", err);
	s->user_box = 1;
	memcpy(s->box, (double[]){-2, -1.6, -1.6, 2, 2.2, 1.9}, sizeof s->box);
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->has_lip && s->lip_local, "with a box: a bound (L = %g), local to it", s->lip);
	double p[3] = {0.3, 0.5, -0.2}, want = 0;
	for (int i = 0; i < 3; i++) {
		double w = i == 2 ? 1 + 0.2 * sin(3 * p[0]) : 1 + 0.15 * p[1];
		want += w * sqrt((p[0] - F[3 * i]) * (p[0] - F[3 * i]) + (p[1] - F[3 * i + 1]) * (p[1] - F[3 * i + 1]) + (p[2] - F[3 * i + 2]) * (p[2] - F[3 * i + 2]));
	}
	CHECK(fabs(model_eval(s, p) - (want - 3.6)) < 1e-12, "value: sum w(P) d - c");
	int bad = 0, gbad = 0, fbad = 0;
	srand(3);
	for (int i = 0; i < 3000; i++) {
		double a[3], b[3], dd = 0;
		for (int j = 0; j < 3; j++) {
			a[j] = s->box[j] + (s->box[3 + j] - s->box[j]) * rand() / RAND_MAX;
			b[j] = fmin(fmax(a[j] + 0.2 * rand() / RAND_MAX - 0.1, s->box[j]), s->box[3 + j]);
			dd += (a[j] - b[j]) * (a[j] - b[j]);
		}
		bad += fabs(model_eval(s, a) - model_eval(s, b)) > s->lip * sqrt(dd) * (1 + 1e-9);
		double g[3], h = 1e-6;
		model_grad(s, a, g);
		for (int j = 0; j < 3; j++) {
			double u[3] = {a[0], a[1], a[2]}, v[3] = {a[0], a[1], a[2]};
			u[j] += h, v[j] -= h;
			gbad += fabs((model_eval(s, u) - model_eval(s, v)) / (2 * h) - g[j]) > 1e-4;
		}
		float x[8], y[8], z[8], o[8];
		for (int k = 0; k < 8; k++)
			x[k] = (float)a[0], y[k] = (float)a[1], z[k] = (float)a[2];
		model_eval8(s, x, y, z, o);
		fbad += fabs(o[0] - model_eval(s, (double[]){x[0], y[0], z[0]})) > 1e-4;
	}
	CHECK(bad == 0 && gbad == 0 && fbad == 0, "L holds on 3000 pairs (%d), gradient (%d), float kernel (%d)", bad, gbad, fbad);
	model_free(s);
	return UNIT_DONE();
}
