/* test_model_de.c: the Douady-Hubbard distance estimate of Mandelbrot and Julia shapes never exceeds the distance to the surface. */
#include "unit.h"
#include "model.h"

#include <math.h>

/* Worst ratio over a grid of points P: no point of the ball of radius d(P) = |model_de(P)|
 * may have f of the other sign (checked on 200 points of the sphere and 3 inner shells).
 * Returns the number of violations; *checked counts the points with a usable estimate. */
static int check_bound(const model_shape_t *s, int *checked)
{
	int bad = 0;
	*checked = 0;
	for (int i = 0; i < 24; i++)
		for (int j = 0; j < 18; j++) {
			double p[3] = {-2.3 + 2.9 * i / 23.0, -1.3 + 2.6 * j / 17.0, 0.05};
			double f = model_eval(s, p), d = model_de(s, p);
			if (!(fabs(d) > 1e-6) || (f > 0) != (d > 0))
				continue;
			(*checked)++;
			for (int k = 0; k < 200; k++) {
				/* Fibonacci sphere */
				double zz = 1 - 2 * (k + 0.5) / 200, rr = sqrt(1 - zz * zz), ph = k * 2.39996322972865332;
				for (double sh = 0.25; sh <= 1.0; sh += 0.25) {
					double q[3] = {p[0] + sh * 0.999 * fabs(d) * rr * cos(ph), p[1] + sh * 0.999 * fabs(d) * rr * sin(ph), p[2] + sh * 0.999 * fabs(d) * zz};
					if ((model_eval(s, q) > 0) != (f > 0))
						bad++;
				}
			}
		}
	return bad;
}

int main(void)
{
	char err[200];
	const char *warn;
	/* the gallery's Mandelbrot solid: c = -0.2 + mu/40 (the equipotential mu = 8), revolved */
	model_shape_t *s = model_new();
	s->c = (model_param_t){.kind = MODEL_C_MANDEL, .c0 = -0.2, .amp = 1, .maxit = 40, .smooth = 1, .revolve = 1,
	                       .u = {1, 0, 0, 0}, .v = {0, 1, 0, 0}};
	s->user_box = 1;
	memcpy(s->box, (double[]){-2.1, -1.3, -1.3, 0.6, 1.3, 1.3}, sizeof s->box);
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->de && !warn, "smooth Mandelbrot: distance-estimated, no warning");
	int n, bad = check_bound(s, &n);
	CHECK(n > 200 && bad == 0, "Mandelbrot: no surface inside the estimated ball at %d points (%d violations)", n, bad);
	/* scaled by 2 and the u map stretched: the bound divides by both norms */
	model_scale(s, 2, 2, 2);
	s->c.u[0] = 1.5;
	model_prepare(s, err, sizeof err, &warn);
	bad = check_bound(s, &n);
	CHECK(s->de && fabs(s->de_scale - 1 / (1.5 * 0.5)) < 1e-12 && n > 50 && bad == 0, "scaled, stretched map: scale %g, %d points, %d violations", s->de_scale, n, bad);
	model_free(s);
	/* the basilica Julia set k = -1, not revolved; the estimate takes the sign of f */
	s = model_new();
	s->c = (model_param_t){.kind = MODEL_C_MANDEL, .c0 = -0.1, .amp = 1, .maxit = 60, .smooth = 1, .julia = 1, .k = {-1, 0},
	                       .u = {1, 0, 0, 0}, .v = {0, 1, 0, 0}};
	s->user_box = 1;
	memcpy(s->box, (double[]){-1.7, -1.1, -1, 1.7, 1.1, 1}, sizeof s->box);
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->de, "Julia basilica: distance-estimated");
	bad = check_bound(s, &n);
	CHECK(n > 100 && bad == 0, "Julia: no surface inside the estimated ball at %d points (%d violations)", n, bad);
	/* a negative amplitude turns inside out: the estimate's sign follows f */
	s->c.c0 = 0.1;
	s->c.amp = -1;
	model_prepare(s, err, sizeof err, &warn);
	bad = check_bound(s, &n);
	CHECK(s->de && n > 100 && bad == 0, "Julia, amplitude -1: %d points, %d violations", n, bad);
	/* k outside the Mandelbrot set: no estimate, bracketing with a warning */
	s->c.k[0] = 0.4;
	s->c.k[1] = 0.3;
	CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && !s->de && warn && strstr(warn, "not connected"), "Cantor-dust Julia set: bracketing, %s", warn ? warn : "");
	model_free(s);
	return UNIT_DONE();
}
