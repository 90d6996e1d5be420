/* test_rt.c: ray-tracing accuracy against analytic silhouettes (sphere, two-foci ellipsoid), determinism, costs. */
#include "unit.h"
#include "rt.h"

#include <math.h>
#include <stdlib.h>

static model_shape_t *foci_shape(const double *f, int n, double c)
{
	model_shape_t *s = model_new();
	char err[128];
	const char *warn;
	for (int i = 0; i < n; i++)
		model_add(s, MODEL_POINT, 1, f + 3 * i, 1, 0, NULL, err, sizeof err);
	s->c.c0 = c;
	model_prepare(s, err, sizeof err, &warn);
	return s;
}

static rt_params_t params(const model_shape_t *s, rt_object_t *obj, cam_t cam)
{
	rt_params_t p;
	char err[128];
	memset(&p, 0, sizeof p);
	memset(obj, 0, sizeof *obj);
	obj->shape = s;
	obj->colour[0] = 1;
	obj->shading = RT_CONSTANT;
	cam_setup(&cam, err, sizeof err);
	p.cam = cam;
	p.objects = obj;
	p.nobjects = 1;
	p.accuracy = 1e-3;
	p.threads = 1;
	return p;
}

/* Render the sphere |P - (cx, cy, 0)| = r from eye and compare with the exact silhouette. */
static void sphere_silhouette(double cx, double cy, double r, const double *eye, double fov, int min_hits)
{
	char err[128];
	model_shape_t *s = foci_shape((double[]){cx, cy, 0}, 1, r);
	cam_t cam = {.eye = {eye[0], eye[1], eye[2]}, .look = {0, 0, 0}, .up = {0, 1, 0}, .fov = fov, .nxpix = 160, .nypix = 120};
	rt_object_t obj;
	rt_params_t p = params(s, &obj, cam);
	meta_rgb_t *img = malloc(160 * 120 * sizeof *img);
	rt_stats_t st;
	CHECK(rt_render(&p, img, &st, err, sizeof err) == 0, "render a sphere of radius %g", r);
	int differ = 0, far = 0, hits = 0;
	for (unsigned row = 0; row < 120; row++)
		for (unsigned i = 0; i < 160; i++) {
			double o[3], d[3];
			cam_ray(&p.cam, i + 0.5, 119 - row + 0.5, o, d);
			double oc[3] = {o[0] - cx, o[1] - cy, o[2]};
			double t = -(oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]);
			double q[3] = {oc[0] + t * d[0], oc[1] + t * d[1], oc[2] + t * d[2]};
			double delta = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
			int exact = delta < r, got = img[row * 160 + i] == 0xff0000;
			hits += got;
			if (exact != got) {
				differ++;
				if (fabs(delta - r) > 0.5 * cam_footprint(&p.cam, t))
					far++;
			}
		}
	CHECK(far == 0 && hits > min_hits, "sphere of radius %g: %d pixels differ, %d of them farther than half a pixel (%d hits)",
	      r, differ, far, hits);
	free(img);
	model_free(s);
}

int main(void)
{
	char err[128];
	/* 1. sphere, perspective: a pixel may differ from the exact answer only when its ray
	 * passes within half a pixel footprint of the tangent; also a small sphere seen from far
	 * (narrow view): the region is its own bounding sphere, so rays enter it on the surface */
	sphere_silhouette(0.1, 0.05, 1, (double[]){0.3, 0.2, -4}, 40, 1000);
	sphere_silhouette(0, 0, 0.09, (double[]){0, 0, -3}, 10, 2000);
	sphere_silhouette(0.3, 0.2, 0.09, (double[]){4, 5, -7.8}, 12, 100);
	/* 2. ellipsoid of revolution from two foci, orthographic along z: the silhouette is
	 * x^2/A^2 + y^2/B^2 = 1 with A = sum/2, B = sqrt(A^2 - a^2) */
	{
		double a = 0.8, A = 1.2, B = sqrt(A * A - a * a);
		model_shape_t *s = foci_shape((double[]){a, 0, 0, -a, 0, 0}, 2, 2 * A);
		cam_t cam = {.eye = {0, 0, -5}, .look = {0, 0, 0}, .up = {0, 1, 0}, .fov = 40, .window = 3.2,
		             .projection = CAM_ORTHOGRAPHIC, .nxpix = 200, .nypix = 150};
		rt_object_t obj;
		rt_params_t p = params(s, &obj, cam);
		meta_rgb_t *img = malloc(200 * 150 * sizeof *img);
		CHECK(rt_render(&p, img, NULL, err, sizeof err) == 0, "render an ellipsoid");
		int differ = 0, far = 0;
		double fp = cam_footprint(&p.cam, 1);
		for (unsigned r = 0; r < 150; r++)
			for (unsigned i = 0; i < 200; i++) {
				double x = ((i + 0.5) / 200 - 0.5) * p.cam.horiz, y = ((149 - r + 0.5) / 150 - 0.5) * p.cam.vert;
				double g = x * x / (A * A) + y * y / (B * B) - 1;
				double gx = 2 * x / (A * A), gy = 2 * y / (B * B);
				double dpix = fabs(g) / sqrt(gx * gx + gy * gy) / fp;
				int exact = g < 0, got = img[r * 200 + i] == 0xff0000;
				if (exact != got) {
					differ++;
					if (dpix > 0.5)
						far++;
				}
			}
		CHECK(far == 0, "two-foci ellipsoid silhouette: %d pixels differ, %d farther than half a pixel", differ, far);
		free(img);
		model_free(s);
	}
	/* 3. determinism across thread counts, Phong with shadows and supersampling; costs */
	{
		model_shape_t *s = foci_shape((double[]){1, 0, 0, -1, 0, 0, 0, 1.2, 0.3}, 3, 3.6);
		cam_t cam = {.eye = {0, 0.3, -6}, .look = {0, 0.3, 0}, .up = {0, 1, 0}, .fov = 40, .nxpix = 256, .nypix = 192};
		rt_object_t obj;
		rt_params_t p = params(s, &obj, cam);
		rt_light_t light = {0, {0, 8, -6}, {1, 1, 1}, 1};
		obj.shading = RT_PHONG;
		obj.ambient = 0.15;
		obj.diffuse = 0.75;
		obj.specular = 0.5;
		obj.shininess = 30;
		p.lights = &light;
		p.nlights = 1;
		size_t n = 256 * 192;
		meta_rgb_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
		rt_stats_t sa, sb;
		p.threads = 1;
		rt_render(&p, a, &sa, err, sizeof err);
		p.threads = 3;
		rt_render(&p, b, &sb, err, sizeof err);
		CHECK(!memcmp(a, b, n * sizeof *a) && sa.evals == sb.evals, "1 and 3 threads: identical pixels and counts");
		double epp = (double)sa.evals / n;
		CHECK(epp <= 12, "trifocal bench view at 256x192: %.2f evaluations per pixel (<= 12)", epp);
		CHECK(sa.shadow_evals > 0 && sa.hits > n / 10, "shadow rays were traced (%llu evals), %llu hits",
		      (unsigned long long)sa.shadow_evals, (unsigned long long)sa.hits);
		p.supersample = 3;
		p.threads = 1;
		rt_render(&p, a, &sa, err, sizeof err);
		p.threads = 2;
		rt_render(&p, b, &sb, err, sizeof err);
		CHECK(!memcmp(a, b, n * sizeof *a) && sa.aa_pixels > 100 && sa.aa_pixels < n / 4,
		      "adaptive supersampling: deterministic, %llu edge pixels resampled", (unsigned long long)sa.aa_pixels);
		free(a);
		free(b);
		model_free(s);
	}
	/* 3b. the trifocal silhouette against an independent double-precision reference:
	 * plain sphere tracing with model_eval, stopping at f < 1e-12 or a sign change */
	{
		model_shape_t *s = foci_shape((double[]){1, 0, 0, -1, 0, 0, 0, 1.2, 0.3}, 3, 3.6);
		cam_t cam = {.eye = {0, 0.3, -6}, .look = {0, 0.3, 0}, .up = {0, 1, 0}, .fov = 40, .nxpix = 256, .nypix = 192};
		rt_object_t obj;
		rt_params_t p = params(s, &obj, cam);
		size_t n = 256 * 192;
		meta_rgb_t *img = malloc(n * sizeof *img);
		rt_render(&p, img, NULL, err, sizeof err);
		int differ = 0, hits = 0;
		for (unsigned r = 0; r < 192; r++)
			for (unsigned i = 0; i < 256; i++) {
				double o[3], d[3], t = 0, prev = 0;
				cam_ray(&p.cam, i + 0.5, 191 - r + 0.5, o, d);
				int hit = 0;
				for (int it = 0; it < 200000 && t < 20; it++) {
					double q[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
					double f = model_eval(s, q);
					if (f < 1e-12) {
						hit = 1;
						break;
					}
					prev = t;
					t += f / s->lip;
				}
				(void)prev;
				hits += hit;
				differ += hit != (img[r * 256 + i] == 0xff0000);
			}
		CHECK(differ <= 1 && hits > 5000, "trifocal silhouette at 256x192: %d of %d hit pixels differ from the double reference", differ, hits);
		free(img);
		model_free(s);
	}
	/* 4. bracketing fallback (no Lipschitz bound): a plane displaced by floor() steps */
	{
		model_shape_t *s = model_new();
		const char *warn;
		char e2[64];
		size_t pos;
		model_add(s, MODEL_PLANE, 1, (double[]){0, 0, 0, 0, 1, 0}, 2, 0, NULL, err, sizeof err);
		expr_compile("1.5 + 0.25*floor(2*x)", &s->c.expr, e2, sizeof e2, &pos);
		s->c.kind = MODEL_C_EXPR;
		s->user_box = 1;
		memcpy(s->box, (double[]){-2, 0, -2, 2, 3, 2}, sizeof s->box);
		CHECK(model_prepare(s, err, sizeof err, &warn) == 0 && !s->has_lip, "floor(): no bound, bracketing");
		cam_t cam = {.eye = {0, 5, 0.01}, .look = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40, .nxpix = 64, .nypix = 48};
		rt_object_t obj;
		rt_params_t p = params(s, &obj, cam);
		rt_light_t light = {1, {0, 1, 0}, {1, 1, 1}, 0};
		obj.shading = RT_GOURAUD;
		obj.ambient = 0.2;
		obj.diffuse = 0.8;
		p.lights = &light;
		p.nlights = 1;
		meta_rgb_t *img = malloc(64 * 48 * sizeof *img);
		rt_stats_t st;
		CHECK(rt_render(&p, img, &st, err, sizeof err) == 0 && st.hits == 64 * 48, "every ray finds the stepped surface (%llu hits)",
		      (unsigned long long)st.hits);
		free(img);
		model_free(s);
	}
	return UNIT_DONE();
}
