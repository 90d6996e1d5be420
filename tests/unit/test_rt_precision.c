/* test_rt_precision.c: precision at any eye distance and scale: far-eye and far-away spheres exact to the pixel, rim shading against the analytic sphere. */
#include "unit.h"
#include "rt.h"
#include "rt_int.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
	int differ, hits, shade_bad, worst;
	double far_px;
} result_t;

/* The unit-radius sphere |P - C| = r (one point element, optionally translated there from the
 * origin) seen from eye with a narrow view, Phong-lit by one directional light, against the
 * analytic sphere: silhouette (a pixel may differ only when its ray passes within 0.01
 * footprint of the tangent) and colour (every hit pixel within 2 levels of the analytic colour). */
static result_t sphere(const double *C, double r, int translated, const double *eye, double fov, unsigned nx, unsigned ny)
{
	result_t res = {0, 0, 0, 0, 0};
	char err[128];
	const char *warn;
	model_shape_t *s = model_new();
	double at[3] = {translated ? 0 : C[0], translated ? 0 : C[1], translated ? 0 : C[2]};
	model_add(s, MODEL_POINT, 1, at, 1, 0, NULL, err, sizeof err);
	s->c.c0 = r;
	if (translated)
		model_translate(s, C[0], C[1], C[2]);
	model_prepare(s, err, sizeof err, &warn);
	rt_object_t obj = {s, {0.9, 0.6, 0.2}, RT_PHONG, 0.15, 0.75, 0.5, 30};
	rt_light_t light = {1, {0.3, 0.8, -0.5}, {1, 1, 1}, 0};
	rt_params_t p;
	memset(&p, 0, sizeof p);
	p.cam = (cam_t){.eye = {eye[0], eye[1], eye[2]}, .look = {C[0], C[1], C[2]}, .up = {0, 1, 0}, .fov = fov, .nxpix = nx, .nypix = ny};
	cam_setup(&p.cam, err, sizeof err);
	p.objects = &obj;
	p.nobjects = 1;
	p.lights = &light;
	p.nlights = 1;
	p.accuracy = 1e-3;
	p.threads = 2;
	meta_rgb_t *img = malloc((size_t)nx * ny * sizeof *img);
	rt_render(&p, img, NULL, err, sizeof err);
	double L[3] = {0.3, 0.8, -0.5}, ll = sqrt(0.98);
	for (int i = 0; i < 3; i++)
		L[i] /= ll;
	for (unsigned row = 0; row < ny; row++)
		for (unsigned i = 0; i < nx; i++) {
			double o[3], d[3];
			cam_ray(&p.cam, i + 0.5, ny - 1 - row + 0.5, o, d);
			double oc[3] = {o[0] - C[0], o[1] - C[1], o[2] - C[2]};
			double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
			double q[3] = {oc[0] - b * d[0], oc[1] - b * d[1], oc[2] - b * d[2]};
			double delta = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
			meta_rgb_t got = img[(size_t)row * nx + i];
			int exact = delta < r, hit = got != 0;
			double fp = cam_footprint(&p.cam, -b);
			res.hits += hit;
			if (exact != hit) {
				res.differ++;
				res.far_px = fmax(res.far_px, fabs(delta - r) / fp);
			}
			if (!(exact && hit))
				continue;
			/* analytic hit, normal and Phong colour (rt.c's formula) */
			double t = -b - sqrt(fmax(r * r - delta * delta, 0)), N[3], V[3] = {-d[0], -d[1], -d[2]};
			for (int k = 0; k < 3; k++)
				N[k] = (oc[k] + t * d[k]) / r;
			double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2], col[3];
			for (int k = 0; k < 3; k++)
				col[k] = obj.colour[k] * obj.ambient;
			if (nl > 0) {
				double rv = 0;
				for (int k = 0; k < 3; k++)
					rv += (2 * nl * N[k] - L[k]) * V[k];
				double spec = rv > 0 ? obj.specular * pow(rv, obj.shininess) : 0;
				for (int k = 0; k < 3; k++)
					col[k] += obj.colour[k] * obj.diffuse * nl + spec;
			}
			int worst = 0;
			for (int k = 0; k < 3; k++) {
				int want = (int)(fmin(fmax(col[k], 0), 1) * 255 + 0.5), have = (int)(got >> (16 - 8 * k) & 255);
				worst = abs(want - have) > worst ? abs(want - have) : worst;
			}
			res.worst = worst > res.worst ? worst : res.worst;
			res.shade_bad += worst > 2;
		}
	free(img);
	model_free(s);
	return res;
}

int main(void)
{
	/* the far eye: a unit sphere 600 units away, fov 0.4 degrees */
	result_t a = sphere((double[]){0, 0, 0}, 1, 0, (double[]){200, 150, -545.3}, 0.4, 160, 120);
	CHECK(a.hits > 4000 && (a.differ == 0 || a.far_px < 1e-3), "far eye (600 units, fov 0.4): %d of %d hit pixels differ from the analytic silhouette, the farthest %.4f px from the rim",
	      a.differ, a.hits, a.far_px);
	CHECK(a.shade_bad == 0, "far eye: rim shading within 2 levels of the analytic Phong colour (%d pixels off, worst %d levels)", a.shade_bad, a.worst);
	/* a unit sphere at 10^5 units (a point element there), 50 units from the eye, fov 3 degrees:
	 * float positions there are 0.008 apart, half a pixel footprint */
	result_t b = sphere((double[]){1e5, 2e4, -3e4}, 1, 0, (double[]){1e5 + 20, 2e4 + 10, -3e4 - 45}, 3, 160, 120);
	CHECK(b.hits > 3000 && (b.differ == 0 || b.far_px < 1e-3), "sphere at 1e5 units, fov 3: %d of %d pixels differ, farthest %.4f px", b.differ, b.hits, b.far_px);
	CHECK(b.shade_bad == 0, "sphere at 1e5: shading within 2 levels (%d off, worst %d)", b.shade_bad, b.worst);
	/* the same moved there by translate, a narrower view from farther */
	result_t c = sphere((double[]){-1e5, 5e4, 1e5}, 1, 1, (double[]){-1e5 - 300, 5e4 + 100, 1e5 - 500}, 0.3, 128, 96);
	CHECK(c.hits > 2000 && (c.differ == 0 || c.far_px < 1e-3), "translated sphere at 1e5, eye 600 away, fov 0.3: %d of %d differ, farthest %.4f px", c.differ, c.hits, c.far_px);
	CHECK(c.shade_bad == 0, "translated sphere at 1e5: shading within 2 levels (%d off, worst %d)", c.shade_bad, c.worst);
	/* the usual view stays on the float kernels (what the benchmarks measure) */
	model_shape_t *s = model_new();
	char err[128];
	const char *warn;
	model_add(s, MODEL_POINT, 1, (double[]){0, 0, 0}, 1, 0, NULL, err, sizeof err);
	s->c.c0 = 1;
	model_prepare(s, err, sizeof err, &warn);
	cam_t cam = {.eye = {0, 0.3, -6}, .look = {0, 0.3, 0}, .up = {0, 1, 0}, .fov = 40, .nxpix = 1024, .nypix = 768};
	cam_setup(&cam, err, sizeof err);
	CHECK(!rt_needs_double(&cam, s, 1e-3), "the benchmark view at 1024x768 is marched in float");
	cam.eye[2] = -600;
	cam.fov = 0.4;
	cam_setup(&cam, err, sizeof err);
	CHECK(rt_needs_double(&cam, s, 1e-3), "the far eye is marched in double");
	model_free(s);
	return UNIT_DONE();
}
