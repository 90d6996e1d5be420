/* test_model_elems.c: circle, triangle, polygon and box elements: distances against dense samples of the sets, 1-Lipschitz, float agreement, refusals. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

/* Distance from p to a dense sample (n points) of the set, minus the computed one: must lie in
 * [-1e-9, spacing]. Returns the number of points outside that window. */
static int against_samples(const model_elem_t *e, const double *pts, size_t n, double spacing, int *lip)
{
	int bad = 0;
	srand(11);
	*lip = 0;
	for (int i = 0; i < 300; i++) {
		double p[3], q[3];
		for (int j = 0; j < 3; j++) {
			p[j] = 3.0 * rand() / RAND_MAX - 1.5;
			q[j] = p[j] + 0.1 * rand() / RAND_MAX - 0.05;
		}
		double d = model_elem_distance(e, p), best = INFINITY;
		for (size_t k = 0; k < n; k++) {
			const double *s = pts + 3 * k;
			best = fmin(best, sqrt((p[0] - s[0]) * (p[0] - s[0]) + (p[1] - s[1]) * (p[1] - s[1]) + (p[2] - s[2]) * (p[2] - s[2])));
		}
		bad += !(best - d >= -1e-9 && best - d <= spacing);
		double dq = model_elem_distance(e, q), l = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
		*lip += fabs(dq - d) > l * (1 + 1e-9);
	}
	return bad;
}

int main(void)
{
	char err[200];
	const char *warn;
	enum { N = 40000 };
	double *pts = malloc(3 * N * sizeof *pts);
	model_shape_t *s = model_new();
	/* circle: centre (0.1, 0, 0), normal z, radius 0.8: sampled every 2*pi*0.8/N */
	CHECK(model_add(s, MODEL_CIRCLE, 1, (double[]){0.1, 0, 0, 0, 0, 2}, 2, 0.8, NULL, err, sizeof err) == 0, "circle");
	for (int k = 0; k < N; k++)
		pts[3 * k] = 0.1 + 0.8 * cos(2 * M_PI * k / N), pts[3 * k + 1] = 0.8 * sin(2 * M_PI * k / N), pts[3 * k + 2] = 0;
	int lip, bad = against_samples(&s->el[0], pts, N, 2e-4, &lip);
	CHECK(bad == 0 && lip == 0, "circle: the distance to the ring (%d off, %d Lipschitz violations)", bad, lip);
	/* triangle (0,0,0) (1,0,0) (0,1,0.5): sampled on a 200x200 barycentric grid */
	CHECK(model_add(s, MODEL_TRIANGLE, 1, (double[]){0, 0, 0, 1, 0, 0, 0, 1, 0.5}, 3, 0, NULL, err, sizeof err) == 0, "triangle");
	size_t n = 0;
	for (int i = 0; i <= 199; i++)
		for (int j = 0; i + j <= 199; j++, n++) {
			double u = i / 199.0, v = j / 199.0;
			pts[3 * n] = u, pts[3 * n + 1] = v, pts[3 * n + 2] = 0.5 * v;
		}
	bad = against_samples(&s->el[1], pts, n, 0.01, &lip);
	CHECK(bad == 0 && lip == 0, "triangle: the distance to the filled triangle (%d off, %d)", bad, lip);
	/* an L-shaped (non-convex) hexagon in z = 0.2 */
	double L[] = {0, 0, 0.2, 1, 0, 0.2, 1, 0.4, 0.2, 0.4, 0.4, 0.2, 0.4, 1, 0.2, 0, 1, 0.2};
	CHECK(model_add(s, MODEL_POLYGON, 1, L, 6, 0, NULL, err, sizeof err) == 0, "L-shaped polygon");
	n = 0;
	for (int i = 0; i <= 200; i++)
		for (int j = 0; j <= 200; j++) {
			double x = i / 200.0, y = j / 200.0;
			if (x > 0.4 && y > 0.4)
				continue;
			pts[3 * n] = x, pts[3 * n + 1] = y, pts[3 * n + 2] = 0.2;
			n++;
		}
	bad = against_samples(&s->el[2], pts, n, 0.005, &lip);
	CHECK(bad == 0 && lip == 0, "non-convex polygon: the distance to the filled L (%d off, %d)", bad, lip);
	/* box (-0.5,-0.2,-0.3)..(0.4,0.6,0.3), given corner order swapped: 0 inside, else to the solid */
	CHECK(model_add(s, MODEL_BOX, 1, (double[]){0.4, -0.2, 0.3, -0.5, 0.6, -0.3}, 2, 0, NULL, err, sizeof err) == 0, "box");
	CHECK(model_elem_distance(&s->el[3], (double[]){0, 0, 0}) == 0, "box: 0 inside");
	CHECK(fabs(model_elem_distance(&s->el[3], (double[]){1.4, 1.6, 0}) - sqrt(2.0)) < 1e-12, "box: to the nearest edge from outside");
	/* float kernel agrees with the double distances (shape of all four) */
	s->c.c0 = 2;
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->bounded, "a shape of the four is bounded");
	float x[8], y[8], z[8], o[8];
	int fbad = 0;
	for (int i = 0; i < 64; i++) {
		for (int k = 0; k < 8; k++)
			x[k] = (float)(0.05 * i - 1.5), y[k] = (float)(0.1 * k - 0.4), z[k] = 0.3f;
		model_eval8(s, x, y, z, o);
		for (int k = 0; k < 8; k++)
			fbad += fabs(o[k] - model_eval(s, (double[]){x[k], y[k], z[k]})) > 1e-5;
	}
	CHECK(fbad == 0, "8-wide kernel matches model_eval (%d off)", fbad);
	CHECK(model_add(s, MODEL_POLYGON, 1, (double[]){0, 0, 0, 1, 0, 0, 1, 1, 0.3, 0, 1, 0}, 4, 0, NULL, err, sizeof err) < 0
	      && strstr(err, "a planar polygon (corner"), "a non-planar polygon refused: %s", err);
	CHECK(model_add(s, MODEL_TRIANGLE, 1, (double[]){0, 0, 0, 1, 1, 1, 2, 2, 2}, 3, 0, NULL, err, sizeof err) < 0
	      && strstr(err, "span an area"), "a degenerate triangle refused: %s", err);
	model_free(s);
	free(pts);
	return UNIT_DONE();
}
