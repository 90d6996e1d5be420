/* test_mesh_out.c: the STL, PLY and OBJ writers byte by byte on a tetrahedron, write failures, and the wireframe's edge counts. */
#include "mesh.h"
#include "unit.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

typedef struct {
	unsigned char *b;
	size_t n, cap;
	size_t fail_after;       /* fail the write that would pass this many bytes (0: never) */
} buf_t;

static int wr(void *user, const void *p, size_t n)
{
	buf_t *b = user;
	if (b->fail_after && b->n + n > b->fail_after)
		return -1;
	if (b->n + n > b->cap) {
		b->cap = 2 * (b->n + n);
		b->b = realloc(b->b, b->cap);
	}
	memcpy(b->b + b->n, p, n);
	b->n += n;
	return 0;
}

static uint32_t u32(const unsigned char *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

static float f32(const unsigned char *p)
{
	uint32_t v = u32(p);
	float f;
	memcpy(&f, &v, 4);
	return f;
}

/* The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), wound outward: volume 1/6. */
static void tetra(mesh_t *m)
{
	static double v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
	static uint32_t t[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
	mesh_init(m);
	m->v = v;
	m->nv = 4;
	m->t = t;
	m->nt = 4;
}

int main(void)
{
	char err[200];
	mesh_t m;
	tetra(&m);
	double a, v;
	mesh_measure(&m, &a, &v);
	CHECK(fabs(v - 1.0 / 6) < 1e-15 && fabs(a - (1.5 + sqrt(3.0) / 2)) < 1e-12, "tetrahedron: volume %g, area %g", v, a);
	mesh_check_t k;
	CHECK(mesh_check(&m, &k) == 0 && k.edges == 6 && k.open_edges == 0 && k.bad_edges == 0, "tetrahedron is closed");

	/* STL: 80-byte header not starting with "solid", count, 4 facets of 50 bytes */
	buf_t b = {NULL, 0, 0, 0};
	CHECK(mesh_write(&m, MESH_STL, "t\x1b[2J.scene", wr, &b, err, sizeof err) == 0, "STL written");
	CHECK(b.n == 84 + 4 * 50 && memcmp(b.b, "solid", 5) != 0 && u32(b.b + 80) == 4, "STL: %zu bytes, count %u", b.n, u32(b.b + 80));
	CHECK(memchr(b.b, 0x1b, 80) == NULL, "STL header: control bytes of the name replaced");
	/* the first facet 0 2 1: normal -z, vertices (0,0,0) (0,1,0) (1,0,0) */
	const unsigned char *f = b.b + 84;
	CHECK(f32(f) == 0 && f32(f + 4) == 0 && f32(f + 8) == -1 && f32(f + 24) == 0 && f32(f + 28) == 1 && f32(f + 36) == 1
	      && f[48] == 0 && f[49] == 0, "STL facet 1: normal (%g %g %g), second vertex y %g", f32(f), f32(f + 4), f32(f + 8), f32(f + 28));
	/* the last facet 1 2 3: normal (1,1,1)/sqrt 3 */
	f = b.b + 84 + 150;
	CHECK(fabs(f32(f) - 1 / sqrt(3.0)) < 1e-7 && f32(f) == f32(f + 4) && f32(f + 4) == f32(f + 8), "STL facet 4: normal %g", f32(f));

	/* PLY: header, 4 vertices of 12 bytes, 4 faces of 13 */
	b.n = 0;
	CHECK(mesh_write(&m, MESH_PLY, "t.scene", wr, &b, err, sizeof err) == 0, "PLY written");
	const char *hdr = "ply\nformat binary_little_endian 1.0\ncomment Locus mesh of t.scene\nelement vertex 4\n"
		"property float x\nproperty float y\nproperty float z\nelement face 4\n"
		"property list uchar int vertex_indices\nend_header\n";
	size_t hl = strlen(hdr);
	CHECK(b.n == hl + 48 + 52 && memcmp(b.b, hdr, hl) == 0, "PLY header and size (%zu bytes)", b.n);
	CHECK(f32(b.b + hl + 12) == 1 && b.b[hl + 48] == 3 && u32(b.b + hl + 49) == 0 && u32(b.b + hl + 53) == 2
	      && u32(b.b + hl + 100 - 4) == 3, "PLY: vertex 1 x = 1, face 1 = 3 0 2 ..., last index 3");

	/* OBJ: exact text */
	b.n = 0;
	CHECK(mesh_write(&m, MESH_OBJ, "t.scene", wr, &b, err, sizeof err) == 0, "OBJ written");
	const char *obj = "# Locus mesh of t.scene: 4 vertices, 4 triangles, wound counter-clockwise seen from outside\n"
		"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
	CHECK(b.n == strlen(obj) && memcmp(b.b, obj, b.n) == 0, "OBJ text is exactly as expected");

	/* a failing write is reported */
	b.n = 0;
	b.fail_after = 10;
	CHECK(mesh_write(&m, MESH_STL, "t", wr, &b, err, sizeof err) < 0 && strstr(err, "write error"), "write failure: %s", err);
	CHECK(mesh_write(&m, 7, "t", wr, &b, err, sizeof err) < 0, "unknown format refused");
	free(b.b);

	/* wireframe: without hidden-line removal every edge once (6), with it only the front
	 * faces' edges: seen from far along +x+y+z only face 1 2 3 faces the eye (3 edges) */
	cam_t cam = {.eye = {5, 5, 5}, .look = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40, .nxpix = 100, .nypix = 100};
	CHECK(cam_setup(&cam, err, sizeof err) == 0, "camera");
	buf_t mb = {NULL, 0, 0, 0};
	meta_writer_t *w = meta_writer_new(wr, &mb, META_ENC_TEXT);
	uint64_t seg = 0;
	meta_page(w, 100, 100);
	CHECK(mesh_draw(w, &cam, &m, 0, 1, 0, 0, &seg, err, sizeof err) == 0 && seg == 6, "wireframe: %llu segments, all 6 edges once",
	      (unsigned long long)seg);
	seg = 0;
	CHECK(mesh_draw(w, &cam, &m, 1, 1, 0, 0, &seg, err, sizeof err) == 0 && seg == 3, "hidden lines removed: %llu segments (3)",
	      (unsigned long long)seg);
	meta_end_page(w);
	CHECK(meta_writer_close(w) == 0, "meta written");
	free(mb.b);
	return UNIT_DONE();
}
