/* test_rt_noise.c: the value-noise Lipschitz bound 2 sqrt(3) |AMP| FREQ holds, and the ray tracer's silhouettes on it match a tiny-step reference (and a bound too tight does not). */
#include "unit.h"
#include "rt.h"

#include <math.h>
#include <stdlib.h>

#define NX 160
#define NY 160

/* The gallery's rock: a sphere of radius 1.3 + 0.12 noise(3 P), seed 7. */
static model_shape_t *rock(void)
{
	char err[128];
	const char *warn;
	model_shape_t *s = model_new();
	double at[3] = {0, 0, 0};
	model_add(s, MODEL_POINT, 1, at, 1, 0, NULL, err, sizeof err);
	s->c.kind = MODEL_C_NOISE;
	s->c.c0 = 1.3;
	s->c.amp = 0.12;
	s->c.freq = 3;
	s->c.seed = 7;
	if (model_prepare(s, err, sizeof err, &warn) < 0) {
		printf("not ok - model_prepare: %s\n", err);
		exit(1);
	}
	return s;
}

static void camera(cam_t *c)
{
	char err[128];
	*c = (cam_t){.eye = {0, 1.5, -5}, .look = {0, 0, 0}, .up = {0, 1, 0}, .fov = 40, .nxpix = NX, .nypix = NY};
	cam_setup(c, err, sizeof err);
}

/* Hit or miss of each pixel's ray by the ray tracer with the shape's bound times lipk. */
static void traced(model_shape_t *s, double lipk, unsigned char *hit, uint64_t *evals)
{
	char err[128];
	double lip = s->lip;
	s->lip = lip * lipk;
	rt_object_t obj = {s, {0.7, 0.65, 0.55}, RT_PHONG, 0.3, 0.7, 0.2, 20};
	rt_light_t light = {1, {0.3, 0.8, -0.5}, {1, 1, 1}, 0};
	rt_params_t p;
	memset(&p, 0, sizeof p);
	camera(&p.cam);
	p.objects = &obj;
	p.nobjects = 1;
	p.lights = &light;
	p.nlights = 1;
	p.accuracy = 1e-3;
	p.threads = 2;
	rt_stats_t st;
	memset(&st, 0, sizeof st);
	meta_rgb_t *img = malloc((size_t)NX * NY * sizeof *img);
	rt_render(&p, img, &st, err, sizeof err);
	for (size_t i = 0; i < (size_t)NX * NY; i++)
		hit[i] = img[i] != 0;   /* black background; ambient 0.3 lights every hit */
	*evals = st.evals;
	free(img);
	s->lip = lip;
}

/* The reference: f in double every 1e-3 units along the ray through the bounding sphere (radius
 * 1.42 holds the surface); hit at the first sign change. The smallest |f| seen on a missing ray,
 * to tell a grazing ray from a wrong answer. */
static int reference(const model_shape_t *s, const cam_t *c, unsigned i, unsigned row, double *fmn)
{
	double o[3], d[3];
	cam_ray(c, i + 0.5, NY - 1 - row + 0.5, o, d);
	double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], cc = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1.45 * 1.45;
	*fmn = INFINITY;
	if (b * b - cc < 0)
		return 0;
	double t0 = -b - sqrt(b * b - cc), t1 = -b + sqrt(b * b - cc);
	for (double t = t0; t <= t1; t += 1e-3) {
		double p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
		double f = model_eval(s, p);
		if (f <= 0)
			return 1;
		*fmn = fmin(*fmn, f);
	}
	return 0;
}

int main(void)
{
	/* 1. the bound against the interpolant's steepest finite differences at 200k points */
	double worst = 0;
	unsigned r = 12345;
	for (int k = 0; k < 200000; k++) {
		double q[3], g2 = 0, h = 1e-6;
		for (int j = 0; j < 3; j++) {
			r = r * 1103515245u + 12345u;
			q[j] = (r >> 8) / 65536.0 - 128;
		}
		for (int j = 0; j < 3; j++) {
			double a[3] = {q[0], q[1], q[2]}, b[3] = {q[0], q[1], q[2]};
			a[j] += h;
			b[j] -= h;
			double gj = (model_noise(7, a[0], a[1], a[2]) - model_noise(7, b[0], b[1], b[2])) / (2 * h);
			g2 += gj * gj;
		}
		worst = fmax(worst, sqrt(g2));
	}
	CHECK(worst <= 2 * sqrt(3.0), "noise gradient at most 2 sqrt(3) = %.4f: steepest sampled %.4f", 2 * sqrt(3.0), worst);

	model_shape_t *s = rock();
	CHECK(fabs(s->lip - (1 + 2 * sqrt(3.0) * 0.12 * 3)) < 1e-12, "the rock's bound is 1 + 2 sqrt(3) 0.12 3 = %.6f (got %.6f)",
	      1 + 2 * sqrt(3.0) * 0.12 * 3, s->lip);

	/* 2. silhouettes: the tracer on the bound against the tiny-step reference; and the same
	 * tracer on 0.3 times the bound, which must be caught (half the bound still passes here:
	 * this f is steepest at about 0.9 of it, and the marcher bisects every sign change it sees) */
	cam_t c;
	camera(&c);
	unsigned char *ref = malloc(NX * NY), *got = malloc(NX * NY), *bad = malloc(NX * NY);
	double *fm = malloc(NX * NY * sizeof *fm);
	int nref = 0;
	for (unsigned row = 0; row < NY; row++)
		for (unsigned i = 0; i < NX; i++) {
			ref[row * NX + i] = (unsigned char)reference(s, &c, i, row, &fm[row * NX + i]);
			nref += ref[row * NX + i];
		}
	uint64_t ev_ok, ev_bad;
	traced(s, 1.0, got, &ev_ok);
	traced(s, 0.3, bad, &ev_bad);
	int differ = 0, grazing = 0, differ_bad = 0;
	for (int k = 0; k < NX * NY; k++) {
		/* a ray that the reference saw come within 1e-3 of the surface may go either way */
		int graze = !ref[k] && fm[k] < 1e-3;
		if (got[k] != ref[k])
			graze ? grazing++ : differ++;
		if (bad[k] != ref[k] && !graze)
			differ_bad++;
	}
	CHECK(nref > NX * NY / 4, "the reference hits %d of %d pixels", nref, NX * NY);
	CHECK(differ == 0, "silhouette on the bound: %d pixels differ from the tiny-step reference (%d grazing rays either way), %.2f evaluations per pixel",
	      differ, grazing, (double)ev_ok / (NX * NY));
	CHECK(differ_bad > 0, "the tracer on 0.3 times the bound (below the steepest slope of f sampled) is caught: %d pixels differ", differ_bad);
	free(ref);
	free(got);
	free(bad);
	free(fm);
	model_free(s);
	return UNIT_DONE();
}
