/* test_rt_grad.c: the ray tracer's normal gradient for point-and-segment shapes (rt_grad) gives model_grad's bits. */
#include "unit.h"
#include "model.h"
#include "rt_int.h"

#include <math.h>
#include <stdlib.h>

/* A shape of points and segments with constant c, translated by (tx, ty, tz) through its frame
 * when move != 0 (the kernel's fast path takes both). */
static model_shape_t *shape(int kind, double move)
{
	model_shape_t *s = model_new();
	char err[160];
	const char *warn;
	double P[9] = {1, 0, 0, -1, 0, 0, 0, 1.2, 0.3}, S[6] = {-1, 0, 0, 1, 0.2, 0}, Q[3] = {0, 1, 0};
	if (kind == 0) {   /* trifocal */
		for (int i = 0; i < 3; i++)
			model_add(s, MODEL_POINT, 1, P + 3 * i, 1, 0, NULL, err, sizeof err);
		s->c.c0 = 3.6;
	} else {           /* segment + point, unequal weights */
		model_add(s, MODEL_SEGMENT, 1.5, S, 2, 0, NULL, err, sizeof err);
		model_add(s, MODEL_POINT, 0.75, Q, 1, 0, NULL, err, sizeof err);
		s->c.c0 = 2.4;
	}
	if (move != 0)
		model_translate(s, move, -0.5 * move, 0.25);
	if (model_prepare(s, err, sizeof err, &warn) != 0)
		fprintf(stderr, "prepare: %s\n", err);
	return s;
}

int main(void)
{
	srand(26);
	for (int kind = 0; kind < 2; kind++)
		for (int mv = 0; mv < 2; mv++) {
			model_shape_t *s = shape(kind, mv ? 0.7 : 0);
			CHECK(s->fast_points, "shape %d (moved %d) takes the fast path", kind, mv);
			int diff = 0;
			for (int i = 0; i < 20000; i++) {
				double p[3], a[3], b[3];
				for (int j = 0; j < 3; j++)
					p[j] = 6.0 * rand() / RAND_MAX - 3;
				if (i == 0)   /* on a focus: that distance is 0 and drops out */
					memcpy(p, (double[]){1, 0, 0}, sizeof p);
				rt_grad(s, p, a);
				model_grad(s, p, b);
				diff += memcmp(a, b, sizeof a) != 0;
			}
			CHECK(diff == 0, "rt_grad gives model_grad's bits at 20000 points (shape %d, moved %d): %d differ", kind, mv, diff);
			model_free(s);
		}
	return UNIT_DONE();
}
