/* test_model.c: extended distances against hand-computed values, Lipschitz bounds on random samples, regions. */
#include "unit.h"
#include "model.h"

#include <math.h>
#include <stdlib.h>

static model_shape_t *shape1(int kind, const double *p, size_t np, double r)
{
	model_shape_t *s = model_new();
	char err[128];
	if (model_add(s, kind, 1, p, np, r, NULL, err, sizeof err) < 0)
		printf("# %s\n", err);
	return s;
}

static double dist(int kind, const double *p, size_t np, double r, double x, double y, double z)
{
	model_shape_t *s = shape1(kind, p, np, r);
	double q[3] = {x, y, z};
	double d = model_eval(s, q);
	model_free(s);
	return d;
}

static double urand(void) { return rand() / (double)RAND_MAX; }

/* Worst ratio |f(p) - f(q)| / (L |p - q|) over random pairs in the shape's box, and the worst
 * disagreement between the float kernel and the double evaluator. */
static double lip_ratio(const model_shape_t *s, double *kerr)
{
	double worst = 0;
	*kerr = 0;
	for (int i = 0; i < 4000; i++) {
		double p[3], q[3];
		float x[8], y[8], z[8], out[8];
		for (int j = 0; j < 3; j++) {
			double lo = s->box[j], hi = s->box[3 + j];
			p[j] = lo + (hi - lo) * urand();
			q[j] = p[j] + (urand() - 0.5) * (i % 2 ? 0.01 : 1.0) * (hi - lo);
		}
		double a = model_eval(s, p), b = model_eval(s, q);
		double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
		if (d > 0)
			worst = fmax(worst, fabs(a - b) / (s->lip * d));
		for (int k = 0; k < 8; k++) {
			x[k] = (float)p[0];
			y[k] = (float)p[1];
			z[k] = (float)p[2];
		}
		model_eval8(s, x, y, z, out);
		double pf[3] = {x[0], y[0], z[0]};
		*kerr = fmax(*kerr, fabs(out[0] - model_eval(s, pf)) / (1 + fabs(model_eval(s, pf))));
	}
	return worst;
}

int main(void)
{
	char err[128];
	const char *warn;
	/* hand-computed distances */
	double pt[3] = {1, 2, 3};
	CHECK(fabs(dist(MODEL_POINT, pt, 1, 0, 4, 6, 3) - 5) < 1e-12, "point: 3-4-5 triangle");
	double pts[6] = {0, 0, 0, 10, 0, 0};
	CHECK(fabs(dist(MODEL_POINTS, pts, 2, 0, 7, 4, 0) - 5) < 1e-12, "point set: nearest of two points");
	double seg[6] = {0, 0, 0, 2, 0, 0};
	CHECK(fabs(dist(MODEL_SEGMENT, seg, 2, 0, 1, 3, 4) - 5) < 1e-12, "segment: interior projection");
	CHECK(fabs(dist(MODEL_SEGMENT, seg, 2, 0, -3, 4, 0) - 5) < 1e-12, "segment: beyond the first end");
	CHECK(fabs(dist(MODEL_SEGMENT, seg, 2, 0, 5, 0, 4) - 5) < 1e-12, "segment: beyond the second end");
	double poly[9] = {0, 0, 0, 2, 0, 0, 2, 2, 0};
	CHECK(fabs(dist(MODEL_POLYLINE, poly, 3, 0, 3, 1, 0) - 1) < 1e-12, "polyline: nearest to the second segment");
	double line[6] = {0, 0, 0, 0, 0, 5};
	CHECK(fabs(dist(MODEL_LINE, line, 2, 0, 3, 4, -100) - 5) < 1e-12, "infinite line (direction normalised)");
	double plane[6] = {0, 0, 1, 0, 0, 2};
	CHECK(fabs(dist(MODEL_PLANE, plane, 2, 0, 7, -3, -2) - 3) < 1e-12, "plane: unsigned distance");
	double disk[6] = {0, 0, 0, 0, 0, 1};
	CHECK(fabs(dist(MODEL_DISK, disk, 2, 1, 0.5, 0, 2) - 2) < 1e-12, "disk: above the disk");
	CHECK(fabs(dist(MODEL_DISK, disk, 2, 1, 4, 0, 4) - 5) < 1e-12, "disk: beyond the rim");

	double vor[9] = {1, 0, 0, -1, 0, 0, 0, 3, 0};
	CHECK(fabs(dist(MODEL_VORONOI, vor, 3, 0, 0.3, 0, 0) - 0.3) < 1e-12, "voronoi: (d2 - d1)/2 = distance to the bisector on the line of two nuclei");
	CHECK(dist(MODEL_VORONOI, vor, 3, 0, 0.3, 0.2, 5) < 0.3, "voronoi: below the distance to the bisector elsewhere (an estimate from below)");
	{
		model_shape_t *s = shape1(MODEL_VORONOI, vor, 3, 0);
		s->c.c0 = 0.05;
		s->user_box = 1;
		memcpy(s->box, (double[]){-2, -2, -2, 2, 4, 2}, sizeof s->box);
		const char *w;
		char e[128];
		double kerr = 0, r = model_prepare(s, e, sizeof e, &w) == 0 ? lip_ratio(s, &kerr) : 9;
		CHECK(s->lip == 1 && r <= 1 + 1e-9 && kerr < 1e-4, "voronoi walls: L = 1 holds (worst %.4f), float kernel agrees (%.2g)", r, kerr);
		model_free(s);
	}

	{
		/* weighted nuclei: points (+-1,0,0) with weights 0 and 0.5, a segment far away:
		 * the face is at x = 0.25 on the axis, so from (0.3,0,0) the estimate is 0.05 */
		double ab[18] = {1, 0, 0, 1, 0, 0, -1, 0, 0, -1, 0, 0, 0, 5, 0, 3, 6, 1}, wt[3] = {0, 0.5, 0.2};
		model_shape_t *s = model_new();
		CHECK(model_add_nuclei(s, 1, ab, wt, 3, err, sizeof err) == 0, "weighted point and segment nuclei");
		double q[3] = {0.3, 0, 0};
		CHECK(fabs(model_eval(s, q) - 0.05) < 1e-12, "weighted Voronoi: distance to the shifted face (%g)", model_eval(s, q));
		s->user_box = 1;
		memcpy(s->box, (double[]){-2, -2, -2, 2, 6, 2}, sizeof s->box);
		const char *w;
		double kerr = 0, r = model_prepare(s, err, sizeof err, &w) == 0 ? lip_ratio(s, &kerr) : 9;
		CHECK(s->lip == 1 && r <= 1 + 1e-9 && kerr < 1e-4, "weighted segment/point nuclei: L = 1 holds (worst %.4f), float agrees (%.2g)", r, kerr);
		double g[3], h = 1e-6, pa[3] = {0.3 + h, 0.1, 0.2}, pb[3] = {0.3 - h, 0.1, 0.2}, pc[3] = {0.3, 0.1, 0.2};
		model_grad(s, pc, g);
		CHECK(fabs(g[0] - (model_eval(s, pa) - model_eval(s, pb)) / (2 * h)) < 1e-5, "weighted Voronoi gradient matches differences");
		CHECK(model_add_nuclei(s, 1, ab, wt, 1, err, sizeof err) < 0, "one nucleus is refused");
		model_free(s);
	}

	/* another shape as a distance: |f| / L */
	{
		model_shape_t *ball = shape1(MODEL_POINT, (double[]){0, 0, 0}, 1, 0);
		ball->c.c0 = 1;
		CHECK(model_prepare(ball, err, sizeof err, &warn) == 0 && ball->has_lip && ball->lip == 1, "unit ball has L = 1");
		model_shape_t *s = model_new();
		CHECK(model_add(s, MODEL_SHAPE, 2, NULL, 0, 0, ball, err, sizeof err) == 0, "shape element");
		double p[3] = {3, 0, 4};
		CHECK(fabs(model_eval(s, p) - 8) < 1e-12, "2 * distance to the unit sphere from (3,0,4) = 8");
		model_free(s);
		model_free(ball);
	}

	/* transforms: a translated, scaled and rotated point-sphere */
	{
		model_shape_t *s = shape1(MODEL_POINT, (double[]){0, 0, 0}, 1, 0);
		s->c.c0 = 1;
		model_scale(s, 2, 2, 2);
		model_rotate(s, 2, 90);
		model_translate(s, 5, 0, 0);
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0, "prepare a transformed sphere");
		double on[3] = {5, 2, 0}, centre[3] = {5, 0, 0};
		CHECK(fabs(model_eval(s, on)) < 1e-12, "surface point of the radius-2 sphere at (5,0,0)");
		CHECK(fabs(model_eval(s, centre) + 1) < 1e-12, "centre value -1 (setup frame)");
		CHECK(fabs(s->lip - 0.5) < 1e-12, "L = 1/scale = 0.5 (f is measured in setup units)");
		CHECK(s->bounded && fabs(s->centre[0] - 5) < 1e-9 && s->radius >= 2 && s->radius < 2.01, "bounding sphere follows the transform (r %g)", s->radius);
		double g[3];
		model_grad(s, on, g);
		CHECK(fabs(g[0]) < 1e-9 && fabs(g[1] - 0.5) < 1e-9, "gradient (0, 0.5, 0) at the top");
		model_free(s);
	}

	/* the trifocal: L = 3, bounded, not empty; c below the minimum: empty */
	{
		double foci[9] = {1, 0, 0, -1, 0, 0, 0, 1.2, 0.3};
		model_shape_t *s = model_new();
		for (int i = 0; i < 3; i++)
			model_add(s, MODEL_POINT, 1, foci + 3 * i, 1, 0, NULL, err, sizeof err);
		s->c.c0 = 3.6;
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && s->lip == 3 && s->bounded && !warn, "trifocal: L = sum |w| = 3");
		CHECK(!model_is_empty(s), "trifocal with c = 3.6 is not empty");
		s->c.c0 = 2.5; /* the minimum of the sum is about 2.93 */
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && warn && strstr(warn, "empty"), "c = 2.5 < min: empty with a warning");
		model_free(s);
	}

	/* Lipschitz bounds never violated, for every element kind and parameter kind */
	{
		srand(11);
		const char *names[] = {"points+segment const", "disk+line noise", "polyline expr", "plane+point expr scaled", "shape + point"};
		for (int c = 0; c < 5; c++) {
			model_shape_t *s = model_new(), *ball = NULL;
			expr_t *e = NULL;
			char ee[64];
			size_t pos;
			switch (c) {
			case 0:
				model_add(s, MODEL_POINTS, 0.7, (double[]){0, 0, 0, 1, 1, 0}, 2, 0, NULL, err, sizeof err);
				model_add(s, MODEL_SEGMENT, 1.3, (double[]){-1, 0, 0, 1, 0.5, 0}, 2, 0, NULL, err, sizeof err);
				s->c.c0 = 3;
				break;
			case 1:
				model_add(s, MODEL_DISK, 1, (double[]){0, 0, 0, 0, 1, 0}, 2, 1, NULL, err, sizeof err);
				model_add(s, MODEL_LINE, 0.5, (double[]){0, 0, 0, 1, 1, 0}, 2, 0, NULL, err, sizeof err);
				s->c.kind = MODEL_C_NOISE;
				s->c.c0 = 1.5;
				s->c.amp = 0.3;
				s->c.freq = 4;
				s->c.seed = 3;
				s->user_box = 1;
				memcpy(s->box, (double[]){-2, -2, -2, 2, 2, 2}, sizeof s->box);
				break;
			case 2:
				model_add(s, MODEL_POLYLINE, 1, (double[]){0, 0, 0, 1, 0, 0, 1, 1, 1}, 3, 0, NULL, err, sizeof err);
				expr_compile("1 + 0.3*sin(5*x) + 0.2*y", &e, ee, sizeof ee, &pos);
				s->c.kind = MODEL_C_EXPR;
				s->c.expr = e;
				break;
			case 3:
				model_add(s, MODEL_PLANE, 1, (double[]){0, 0, 0, 0, 1, 0}, 2, 0, NULL, err, sizeof err);
				model_add(s, MODEL_POINT, -0.5, (double[]){0, 1, 0}, 1, 0, NULL, err, sizeof err);
				expr_compile("0.5 + 0.1*x*z", &e, ee, sizeof ee, &pos);
				s->c.kind = MODEL_C_EXPR;
				s->c.expr = e;
				model_scale(s, 1, 0.5, 2);
				model_rotate(s, 0, 30);
				s->user_box = 1;
				memcpy(s->box, (double[]){-2, -2, -2, 2, 2, 2}, sizeof s->box);
				break;
			default:
				ball = shape1(MODEL_SEGMENT, (double[]){0, 0, 0, 1, 0, 0}, 2, 0);
				ball->c.c0 = 0.5;
				model_prepare(ball, err, sizeof err, &warn);
				model_add(s, MODEL_SHAPE, 1, NULL, 0, 0, ball, err, sizeof err);
				model_add(s, MODEL_POINT, 1, (double[]){0, 1, 0}, 1, 0, NULL, err, sizeof err);
				s->c.c0 = 2;
				s->user_box = 1;
				memcpy(s->box, (double[]){-3, -3, -3, 3, 3, 3}, sizeof s->box);
			}
			int ok = model_prepare(s, err, sizeof err, &warn) == 0;
			if (!ok)
				printf("# %s\n", err);
			double kerr = 0, r = ok && s->has_lip ? lip_ratio(s, &kerr) : 9;
			CHECK(ok && s->has_lip && r <= 1.0 + 1e-9, "%s: |f(p)-f(q)| <= L|p-q| (worst ratio %.4f, L %.3f)", names[c], r, s->lip);
			CHECK(ok && kerr < 1e-4, "%s: float kernel agrees with double (rel %.2g)", names[c], kerr);
			model_free(s);
			model_free(ball);
		}
	}

	/* no bound: mandelbrot parameter -> has_lip 0 with a warning; unbounded without a box: error */
	{
		model_shape_t *s = shape1(MODEL_PLANE, (double[]){0, 0, 0, 0, 1, 0}, 2, 0);
		s->c.kind = MODEL_C_MANDEL;
		s->c.amp = 1;
		s->c.maxit = 20;
		CHECK(model_prepare(s, err, sizeof err, &warn) < 0 && strstr(err, "bound"), "an unbounded shape without a box is an error");
		s->user_box = 1;
		memcpy(s->box, (double[]){-2, -1, -2, 2, 1, 2}, sizeof s->box);
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && !s->has_lip && warn, "mandelbrot: no Lipschitz bound, a warning");
		model_free(s);
	}
	/* mandelbrot 'revolve': the value depends on x and sqrt(y^2+z^2) only, and on the plane z = 0
	 * it is the flat set; 'smooth': continuous (no jump of a whole count between close points),
	 * maxit inside the set; a shape without elements is f = -c */
	{
		model_shape_t *s = model_new();
		s->c.kind = MODEL_C_MANDEL;
		s->c.c0 = -0.2;
		s->c.amp = 1;
		s->c.maxit = 40;
		s->c.u[0] = 1;
		s->c.v[1] = 1;
		s->c.smooth = s->c.revolve = 1;
		s->user_box = 1;
		memcpy(s->box, (double[]){-2.1, -1.3, -1.3, 0.6, 1.3, 1.3}, sizeof s->box);
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && !s->has_lip, "no elements, mandelbrot parameter: accepted, no bound");
		int sym = 1, cont = 1;
		for (int i = 0; i < 200; i++) {
			double x = -2.1 + 2.7 * urand(), r = 1.2 * urand(), a = 6.283185307179586 * urand();
			double p1[3] = {x, r, 0}, p2[3] = {x, r * cos(a), r * sin(a)};
			if (fabs(model_eval(s, p1) - model_eval(s, p2)) > 1e-9)
				sym = 0;
			double p3[3] = {x + 1e-7, r, 0};
			double f1 = model_eval(s, p1), f3 = model_eval(s, p3);
			if (f1 > -0.79 && fabs(f1 - f3) > 0.5 / 40)
				cont = 0;
		}
		CHECK(sym, "revolve: f(x, r cos a, r sin a) = f(x, r, 0)");
		CHECK(cont, "smooth: points 1e-7 apart differ by less than half a count");
		CHECK(fabs(model_eval(s, (double[]){-0.1, 0, 0}) - (0.2 - 1)) < 1e-12, "inside the set (c = -0.1): f = -(c0 + amp)");
		double far = model_eval(s, (double[]){0.5, 1.2, 0.3});
		CHECK(far > 0 && far < 0.2, "outside: 0 < f = 0.2 - mu/40 < 0.2 (got %g)", far);
		double on = model_eval(s, (double[]){0.5, 0.5, 0}), flat;
		s->c.revolve = 0;
		flat = model_eval(s, (double[]){0.5, 0.5, 0});
		CHECK(on == flat, "on the plane z = 0 (y >= 0) revolve is the flat set");
		s->c.smooth = 0;
		double n = model_eval(s, (double[]){0.5, 0.5, 0}) - 0.2;
		CHECK(fabs(n * 40 - floor(n * 40 + 0.5)) < 1e-9, "without smooth the count is whole");
		s->c.kind = MODEL_C_CONST;
		CHECK(model_prepare(s, err, sizeof err, &warn) < 0 && strstr(err, "element"), "no elements and a constant c: error");
		model_free(s);
	}
	/* degenerate input */
	{
		model_shape_t *s = model_new();
		CHECK(model_add(s, MODEL_POINT, NAN, (double[]){0, 0, 0}, 1, 0, NULL, err, sizeof err) < 0, "NaN weight refused");
		CHECK(model_add(s, MODEL_POINT, 1, (double[]){0, NAN, 0}, 1, 0, NULL, err, sizeof err) < 0, "NaN coordinate refused");
		CHECK(model_add(s, MODEL_LINE, 1, (double[]){0, 0, 0, 0, 0, 0}, 2, 0, NULL, err, sizeof err) < 0, "zero line direction refused");
		CHECK(model_add(s, MODEL_DISK, 1, (double[]){0, 0, 0, 0, 0, 1}, 2, -1, NULL, err, sizeof err) < 0, "negative radius refused");
		CHECK(model_scale(s, 0, 1, 1) < 0, "zero scale refused");
		CHECK(model_prepare(s, err, sizeof err, &warn) < 0, "a shape with no element is an error");
		model_free(s);
	}
	return UNIT_DONE();
}
