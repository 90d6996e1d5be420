/* test_oct_de.c: the octree of distance-estimated shapes (Mandelbrot, Julia): every finest cell whose samples change sign is a leaf, and the mesh of it is closed. */
#include "unit.h"
#include "mesh.h"
#include "oct.h"
#include "scene.h"

#include <math.h>
#include <stdlib.h>

#define DEPTH 5

static const char *mandel_scene =
	"object mandel\n"
	"  c mandelbrot -0.2 1 40 1 0 0 0 0 1 0 0 smooth revolve\n"
	"  bound -2.1 -1.3 -1.3 0.6 1.3 1.3\n"
	"end\n"
	"render octree\n  depth 5\nend\n";
static const char *julia_scene =
	"object basilica\n"
	"  c julia -0.15 1 40 -1 0 1 0 0 0 0 1 0 0 smooth revolve\n"
	"  bound -1.7 -0.8 -0.8 1.7 0.8 0.8\n"
	"end\n"
	"render octree\n  depth 5\nend\n";

static int cmp_key(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return x < y ? -1 : x > y;
}

static void check_shape(const char *text, const char *what)
{
	char err[300];
	scene_t *sc = NULL;
	if (scene_parse(text, what, &sc, err, sizeof err) < 0) {
		CHECK(0, "%s: scene: %s", what, err);
		return;
	}
	const model_shape_t *s = sc->objs[0].shape;
	CHECK(s->de && !s->has_lip, "%s: a distance-estimated shape without a Lipschitz bound", what);
	for (int test = OCT_SPHERICAL; test <= OCT_CUBICAL; test++) {
		oct_leaf_t *lv = NULL;
		size_t n = 0;
		oct_stats_t st;
		int rc = oct_build(s, DEPTH, test, &lv, &n, &st, err, sizeof err);
		CHECK(rc == 0 && n > 100, "%s: octree (%s test) built: %zu leaves of %llu cells visited%s%s", what,
		      test ? "cubical" : "spherical", n, (unsigned long long)st.visited, rc ? ": " : "", rc ? err : "");
		if (rc < 0)
			continue;
		/* the leaves as integer cell keys on the finest grid */
		const double *r = s->root;
		double side = fmax(r[3] - r[0], fmax(r[4] - r[1], r[5] - r[2])), cell = side / (1 << DEPTH), lo[3];
		for (int i = 0; i < 3; i++)
			lo[i] = (r[i] + r[3 + i]) / 2 - side / 2;
		uint64_t *keys = malloc(n * sizeof *keys);
		for (size_t k = 0; k < n; k++) {
			uint64_t key = 0;
			for (int i = 0; i < 3; i++)
				key = key << 16 | (uint64_t)floor((lv[k].c[i] - lo[i]) / cell);
			keys[k] = key;
		}
		qsort(keys, n, sizeof *keys, cmp_key);
		/* every finest cell: 3^3 samples in double; a sign change means the surface crosses it */
		size_t crossing = 0, missed = 0, N = (size_t)1 << DEPTH;
		for (uint64_t a = 0; a < N; a++)
			for (uint64_t b = 0; b < N; b++)
				for (uint64_t c = 0; c < N; c++) {
					int neg = 0, pos = 0;
					for (int k = 0; k < 27; k++) {
						double p[3] = {lo[0] + (a + 0.5 * (k % 3)) * cell, lo[1] + (b + 0.5 * (k / 3 % 3)) * cell,
						               lo[2] + (c + 0.5 * (k / 9)) * cell};
						double f = model_eval(s, p);
						neg += f < 0;
						pos += f > 0;
					}
					if (!neg || !pos)
						continue;
					crossing++;
					uint64_t key = a << 32 | b << 16 | c;
					missed += bsearch(&key, keys, n, sizeof *keys, cmp_key) == NULL;
				}
		CHECK(crossing > 100 && missed == 0, "%s (%s): every one of %zu cells that the surface crosses is a leaf (%zu missing)",
		      what, test ? "cubical" : "spherical", crossing, missed);
		free(keys);
		free(lv);
	}
	/* the same shape polygonised on the estimate: closed and consistently oriented */
	mesh_t m;
	mesh_init(&m);
	mesh_stats_t mst;
	memset(&mst, 0, sizeof mst);
	int rc = mesh_extract(s, DEPTH, &m, &mst, err, sizeof err);
	mesh_check_t mc;
	memset(&mc, 0, sizeof mc);
	if (rc == 0)
		mesh_check(&m, &mc);
	CHECK(rc == 0 && m.nt > 100 && mc.open_edges == 0 && mc.bad_edges == 0, "%s: mesh of %zu triangles, %zu open and %zu wrongly oriented edges%s%s",
	      what, m.nt, mc.open_edges, mc.bad_edges, rc ? ": " : "", rc ? err : "");
	rc = mesh_simplify(&m, s, 0, 0, 1e-3, NULL, err, sizeof err);
	CHECK(rc < 0 && strstr(err, "tolerance 0"), "%s: coarsening is refused: %s", what, err);
	mesh_free(&m);
	scene_free(sc);
}

int main(void)
{
	check_shape(mandel_scene, "mandelbrot");
	check_shape(julia_scene, "julia");
	return UNIT_DONE();
}
