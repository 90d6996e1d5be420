/* mesh_out.c: meshes written as binary STL, binary PLY and Wavefront OBJ, solids as Gmsh MSH 2.2 (mesh.h), in a buffered stream of bytes. */
#include "mesh.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 64 KiB output buffer over the caller's write function. */
typedef struct {
	mesh_write_fn wr;
	void *user;
	unsigned char buf[1 << 16];
	size_t n;
	int failed;
} out_t;

static void flush(out_t *o)
{
	if (o->n && !o->failed && o->wr(o->user, o->buf, o->n) < 0)
		o->failed = 1;
	o->n = 0;
}

static void put(out_t *o, const void *p, size_t n)
{
	const unsigned char *c = p;
	while (n) {
		if (o->n == sizeof o->buf)
			flush(o);
		size_t k = sizeof o->buf - o->n < n ? sizeof o->buf - o->n : n;
		memcpy(o->buf + o->n, c, k);
		o->n += k;
		c += k;
		n -= k;
	}
}

/* Little-endian 32-bit words and IEEE floats, whatever the host's order. */
static void put_u32(out_t *o, uint32_t v)
{
	unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
	put(o, b, 4);
}

static void put_f32(out_t *o, double d)
{
	float f = (float)d;
	uint32_t v;
	memcpy(&v, &f, 4);
	put_u32(o, v);
}

static void printf_out(out_t *o, const char *fmt, double a, double b, double c)
{
	char line[128];
	int n = snprintf(line, sizeof line, fmt, a, b, c);
	put(o, line, (size_t)n);
}

int mesh_format_of(const char *name)
{
	static const char *sfx[] = {".stl", ".ply", ".obj", ".msh"};
	size_t n = strlen(name);
	if (n < 5 || name[n - 5] == '/')
		return -1;   /* a suffix needs a name before it */
	for (int f = 0; f < 4; f++) {
		int same = 1;
		for (int i = 0; i < 4; i++)
			if (tolower((unsigned char)name[n - 4 + i]) != sfx[f][i])
				same = 0;
		if (same)
			return f;
	}
	return -1;
}

static void write_stl(out_t *o, const mesh_t *m, const char *name)
{
	/* the 80-byte header must not begin with "solid" (readers take that for ASCII STL) */
	char head[80];
	memset(head, 0, sizeof head);
	snprintf(head, sizeof head, "Locus mesh of %.50s, binary STL", name);
	put(o, head, sizeof head);
	put_u32(o, (uint32_t)m->nt);
	for (size_t i = 0; i < m->nt; i++) {
		/* the normal of the facet as readers see it: from the single-precision vertices */
		double p[3][3];
		for (int j = 0; j < 3; j++)
			for (int k = 0; k < 3; k++)
				p[j][k] = (float)m->v[3 * m->t[3 * i + j] + k];
		double u[3], w[3], n[3];
		for (int j = 0; j < 3; j++) {
			u[j] = p[1][j] - p[0][j];
			w[j] = p[2][j] - p[0][j];
		}
		n[0] = u[1] * w[2] - u[2] * w[1];
		n[1] = u[2] * w[0] - u[0] * w[2];
		n[2] = u[0] * w[1] - u[1] * w[0];
		double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
		for (int j = 0; j < 3; j++)
			put_f32(o, l > 0 ? n[j] / l : 0);
		for (int j = 0; j < 3; j++)
			for (int k = 0; k < 3; k++)
				put_f32(o, p[j][k]);
		put(o, "\0\0", 2);   /* attribute byte count */
	}
}

static void write_ply(out_t *o, const mesh_t *m, const char *name)
{
	char head[512];
	int n = snprintf(head, sizeof head,
		"ply\nformat binary_little_endian 1.0\ncomment Locus mesh of %.200s\n"
		"element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
		"element face %zu\nproperty list uchar int vertex_indices\nend_header\n", name, m->nv, m->nt);
	for (char *c = head; *c; c++)
		if (*c == '\r')
			*c = ' ';   /* a name cannot break the header's lines */
	put(o, head, (size_t)n);
	for (size_t i = 0; i < 3 * m->nv; i++)
		put_f32(o, m->v[i]);
	for (size_t i = 0; i < m->nt; i++) {
		put(o, "\3", 1);
		for (int j = 0; j < 3; j++)
			put_u32(o, m->t[3 * i + j]);
	}
}

/* The solid as Gmsh MSH 2.2 ASCII: every vertex a node (1-based, full double precision), every
 * tetrahedron an element of type 4 (4-node tetrahedron) with physical and elementary tag 1. */
static void write_msh(out_t *o, const mesh_t *m)
{
	char line[160];
	int n = snprintf(line, sizeof line, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%zu\n", m->nv);
	put(o, line, (size_t)n);
	for (size_t i = 0; i < m->nv; i++) {
		n = snprintf(line, sizeof line, "%zu %.17g %.17g %.17g\n", i + 1, m->v[3 * i], m->v[3 * i + 1], m->v[3 * i + 2]);
		put(o, line, (size_t)n);
	}
	n = snprintf(line, sizeof line, "$EndNodes\n$Elements\n%zu\n", m->ntet);
	put(o, line, (size_t)n);
	for (size_t i = 0; i < m->ntet; i++) {
		const uint32_t *t = m->tet + 4 * i;
		n = snprintf(line, sizeof line, "%zu 4 2 1 1 %lu %lu %lu %lu\n", i + 1, (unsigned long)t[0] + 1,
		             (unsigned long)t[1] + 1, (unsigned long)t[2] + 1, (unsigned long)t[3] + 1);
		put(o, line, (size_t)n);
	}
	put(o, "$EndElements\n", 13);
}

static void write_obj(out_t *o, const mesh_t *m, const char *name)
{
	char head[300];
	int n = snprintf(head, sizeof head, "# Locus mesh of %.200s: %zu vertices, %zu triangles, wound "
		"counter-clockwise seen from outside\n", name, m->nv, m->nt);
	put(o, head, (size_t)n);
	for (size_t i = 0; i < m->nv; i++)
		printf_out(o, "v %.9g %.9g %.9g\n", (float)m->v[3 * i], (float)m->v[3 * i + 1], (float)m->v[3 * i + 2]);
	for (size_t i = 0; i < m->nt; i++)
		printf_out(o, "f %.0f %.0f %.0f\n", m->t[3 * i] + 1.0, m->t[3 * i + 1] + 1.0, m->t[3 * i + 2] + 1.0);
}

int mesh_write(const mesh_t *m, int format, const char *name, mesh_write_fn wr, void *user,
               char *err, size_t errlen)
{
	char safe[200];
	size_t k = 0;
	for (const char *c = name; *c && k + 1 < sizeof safe; c++)
		safe[k++] = (unsigned char)*c < 32 || *c == 127 ? '?' : *c;   /* no control bytes in headers */
	safe[k] = 0;
	if (format == MESH_STL && m->nt > UINT32_MAX) {
		snprintf(err, errlen, "binary STL holds at most 2^32 - 1 triangles");
		return -1;
	}
	if (format == MESH_MSH && m->ntet == 0) {
		snprintf(err, errlen, "the solid has no tetrahedra (extract it with want_solid)");
		return -1;
	}
	if (format < MESH_STL || format > MESH_MSH) {
		snprintf(err, errlen, "unknown mesh format %d", format);
		return -1;
	}
	out_t *o = malloc(sizeof *o);   /* 64 KiB: not on the stack */
	if (!o) {
		snprintf(err, errlen, "out of memory for the output buffer");
		return -1;
	}
	o->wr = wr;
	o->user = user;
	o->n = 0;
	o->failed = 0;
	if (format == MESH_STL)
		write_stl(o, m, safe);
	else if (format == MESH_PLY)
		write_ply(o, m, safe);
	else if (format == MESH_OBJ)
		write_obj(o, m, safe);
	else
		write_msh(o, m);
	flush(o);
	int failed = o->failed;
	free(o);
	if (failed) {
		snprintf(err, errlen, "write error");
		return -1;
	}
	return 0;
}
