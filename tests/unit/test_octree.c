/* test_octree.c: octree conversion: leaves cover the surface, cubical prunes at least as well as spherical. */
#include "unit.h"
#include "oct.h"

#include <math.h>
#include <stdlib.h>

static int cmp_u64(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return x < y ? -1 : x > y;
}

static uint64_t cell_key(const double *p, const double *lo, double side, int depth)
{
	uint64_t n = 1u << depth, k = 0;
	for (int i = 0; i < 3; i++) {
		double u = (p[i] - lo[i]) / side * n;
		uint64_t c = u < 0 ? 0 : u >= n ? n - 1 : (uint64_t)u;
		k = k * n + c;
	}
	return k;
}

int main(void)
{
	char err[128];
	const char *warn;
	model_shape_t *s = model_new();
	double foci[9] = {1, 0, 0, -1, 0, 0, 0, 1.2, 0.3};
	for (int i = 0; i < 3; i++)
		model_add(s, MODEL_POINT, 1, foci + 3 * i, 1, 0, NULL, err, sizeof err);
	s->c.c0 = 3.6;
	model_prepare(s, err, sizeof err, &warn);
	const int depth = 6;
	oct_stats_t st[2];
	for (int test = 0; test < 2; test++) {
		oct_leaf_t *leaves;
		size_t n;
		CHECK(oct_build(s, depth, test, &leaves, &n, &st[test], err, sizeof err) == 0 && n > 0, "build depth %d (%s)", depth, test ? "cubical" : "spherical");
		CHECK(st[test].leaves == n && st[test].visited > n, "%s: %llu visited, %llu leaves", test ? "cubical" : "spherical",
		      (unsigned long long)st[test].visited, (unsigned long long)st[test].leaves);
		/* root cube as oct_build makes it */
		const double *b = s->box;
		double side = fmax(b[3] - b[0], fmax(b[4] - b[1], b[5] - b[2]));
		double lo[3] = {(b[0] + b[3] - side) / 2, (b[1] + b[4] - side) / 2, (b[2] + b[5] - side) / 2};
		uint64_t *keys = malloc(n * sizeof *keys);
		for (size_t i = 0; i < n; i++) {
			double c[3] = {leaves[i].c[0], leaves[i].c[1], leaves[i].c[2]};
			keys[i] = cell_key(c, lo, side, depth);
		}
		qsort(keys, n, sizeof *keys, cmp_u64);
		/* surface points by bisection along random directions from an inside point */
		srand(5);
		int missing = 0;
		double in[3] = {0, 0.4, 0.1};
		for (int k = 0; k < 3000; k++) {
			double d[3], len = 0;
			for (int j = 0; j < 3; j++) {
				d[j] = rand() / (double)RAND_MAX - 0.5;
				len += d[j] * d[j];
			}
			len = sqrt(len);
			double t0 = 0, t1 = 5;
			for (int it = 0; it < 60; it++) {
				double tm = (t0 + t1) / 2, p[3] = {in[0] + tm * d[0] / len, in[1] + tm * d[1] / len, in[2] + tm * d[2] / len};
				if (model_eval(s, p) < 0)
					t0 = tm;
				else
					t1 = tm;
			}
			double p[3] = {in[0] + t0 * d[0] / len, in[1] + t0 * d[1] / len, in[2] + t0 * d[2] / len};
			uint64_t key = cell_key(p, lo, side, depth);
			if (!bsearch(&key, keys, n, sizeof *keys, cmp_u64))
				missing++;
		}
		CHECK(missing == 0, "%s: all 3000 surface samples lie in a leaf (%d missing)", test ? "cubical" : "spherical", missing);
		free(keys);
		free(leaves);
	}
	CHECK(st[1].visited <= st[0].visited && st[1].leaves <= st[0].leaves, "cubical (exact point ranges) prunes at least as much as spherical");
	/* painter's faces: front faces only, sorted far to near */
	{
		oct_leaf_t *leaves;
		size_t n, nf = 0, cap = 0;
		oct_stats_t os;
		oct_build(s, 4, OCT_SPHERICAL, &leaves, &n, &os, err, sizeof err);
		cam_t cam = {.eye = {0, 0.3, -6}, .look = {0, 0.3, 0}, .up = {0, 1, 0}, .fov = 40, .nxpix = 64, .nypix = 48};
		cam_setup(&cam, err, sizeof err);
		rt_object_t mat = {s, {1, 0.5, 0}, RT_GOURAUD, 0.2, 0.8, 0, 1};
		rt_light_t light = {0, {0, 8, -6}, {1, 1, 1}, 0};
		oct_face_t *faces = NULL;
		CHECK(oct_faces(&cam, &mat, &light, 1, leaves, n, RT_CONSTANT, &faces, &nf, &cap) == 0 && nf > 100 && nf < n, "%zu visible, unshared faces for %zu leaves", nf, n);
		free(faces);
		free(leaves);
	}
	/* without a Lipschitz bound the octree refuses */
	{
		model_shape_t *m = model_new();
		model_add(m, MODEL_PLANE, 1, (double[]){0, 0, 0, 0, 1, 0}, 2, 0, NULL, err, sizeof err);
		m->c.kind = MODEL_C_MANDEL;
		m->c.amp = 1;
		m->c.maxit = 10;
		m->user_box = 1;
		memcpy(m->box, (double[]){-1, -1, -1, 1, 1, 1}, sizeof m->box);
		model_prepare(m, err, sizeof err, &warn);
		oct_leaf_t *leaves;
		size_t n;
		oct_stats_t os;
		CHECK(oct_build(m, 3, OCT_SPHERICAL, &leaves, &n, &os, err, sizeof err) < 0 && strstr(err, "Lipschitz"), "no bound: a clear error");
		model_free(m);
	}
	model_free(s);
	return UNIT_DONE();
}
