/* mesh_draw.c: a mesh drawn as a meta wireframe: every edge once, optionally only those of faces turned to the eye. */
#include "mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One use of an edge by a triangle: the edge as (low << 32 | high) and whether the triangle faces the eye. */
typedef struct {
	uint64_t key;
	int front;
} half_t;

static int by_key(const void *a, const void *b)
{
	uint64_t x = ((const half_t *)a)->key, y = ((const half_t *)b)->key;
	return x < y ? -1 : x > y;
}

/* Does triangle t (wound counter-clockwise from outside) face the eye? */
static int faces_eye(const cam_t *cam, const mesh_t *m, const uint32_t *t)
{
	const double *p = m->v + 3 * t[0], *q = m->v + 3 * t[1], *r = m->v + 3 * t[2];
	double u[3], w[3], n[3], v[3];
	for (int i = 0; i < 3; i++) {
		u[i] = q[i] - p[i];
		w[i] = r[i] - p[i];
	}
	n[0] = u[1] * w[2] - u[2] * w[1];
	n[1] = u[2] * w[0] - u[0] * w[2];
	n[2] = u[0] * w[1] - u[1] * w[0];
	for (int i = 0; i < 3; i++)
		v[i] = cam->projection == CAM_ORTHOGRAPHIC ? -cam->fwd[i] : cam->eye[i] - (p[i] + q[i] + r[i]) / 3;
	return n[0] * v[0] + n[1] * v[1] + n[2] * v[2] > 0;
}

int mesh_draw(meta_writer_t *w, const cam_t *cam, const mesh_t *m, int hidden, double width,
              meta_rgb_t colour, double xoff, uint64_t *segments, char *err, size_t errlen)
{
	half_t *h = malloc((3 * m->nt + 1) * sizeof *h);
	double *xy = malloc((2 * m->nv + 1) * sizeof *xy);
	unsigned char *vis = malloc(m->nv + 1);
	int rc = 0;
	if (!h || !xy || !vis) {
		snprintf(err, errlen, "out of memory for the wireframe of %zu triangles", m->nt);
		rc = -1;
		goto done;
	}
	for (size_t i = 0; i < m->nv; i++) {
		double d;
		vis[i] = cam_project(cam, m->v + 3 * i, &xy[2 * i], &xy[2 * i + 1], &d) == 0;
	}
	size_t n = 0;
	for (size_t i = 0; i < m->nt; i++) {
		const uint32_t *t = m->t + 3 * i;
		int front = !hidden || faces_eye(cam, m, t);
		for (int j = 0; j < 3; j++) {
			uint32_t a = t[j], b = t[(j + 1) % 3];
			h[n].key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
			h[n++].front = front;
		}
	}
	qsort(h, n, sizeof *h, by_key);
	if (meta_colour(w, colour) < 0 || meta_width(w, width) < 0)
		goto werr;
	size_t in_path = 0;
	for (size_t i = 0; i < n;) {
		size_t j = i;
		int front = 0;
		for (; j < n && h[j].key == h[i].key; j++)
			front |= h[j].front;
		uint32_t a = (uint32_t)(h[i].key >> 32), b = (uint32_t)h[i].key;
		i = j;
		if (!front || !vis[a] || !vis[b])
			continue;   /* a hidden edge, or one behind the eye */
		if (in_path == 0 && meta_stroke(w) < 0)
			goto werr;
		if (meta_move(w, xoff + xy[2 * a], xy[2 * a + 1]) < 0 || meta_draw(w, xoff + xy[2 * b], xy[2 * b + 1]) < 0)
			goto werr;
		(*segments)++;
		/* paths of at most 1024 segments, so that no device has to hold a huge one */
		if (++in_path == 1024) {
			if (meta_end(w) < 0)
				goto werr;
			in_path = 0;
		}
	}
	if (in_path && meta_end(w) < 0)
		goto werr;
	goto done;
werr:
	snprintf(err, errlen, "%s", meta_writer_error(w));
	rc = -1;
done:
	free(h);
	free(xy);
	free(vis);
	return rc;
}
