/* oct_draw.c: octree leaves as shaded, projected cube faces painted far to near (painter's algorithm). */
#include "oct.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static meta_rgb_t shade(const rt_object_t *mat, const rt_light_t *lights, size_t nl, const double *n, const double *p)
{
	double c[3];
	for (int i = 0; i < 3; i++)
		c[i] = mat->colour[i] * mat->ambient;
	for (size_t k = 0; k < nl; k++) {
		const rt_light_t *l = &lights[k];
		double d[3], len = 0;
		for (int i = 0; i < 3; i++) {
			d[i] = l->directional ? l->pos[i] : l->pos[i] - p[i];
			len += d[i] * d[i];
		}
		len = sqrt(len);
		if (!(len > 0))
			continue;
		double nl_ = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / len;
		if (nl_ > 0)
			for (int i = 0; i < 3; i++)
				c[i] += l->colour[i] * mat->colour[i] * mat->diffuse * nl_;
	}
	unsigned v[3];
	for (int i = 0; i < 3; i++)
		v[i] = (unsigned)(fmin(fmax(c[i], 0), 1) * 255 + 0.5);
	return (meta_rgb_t)(v[0] << 16 | v[1] << 8 | v[2]);
}

/* Integer cell coordinates packed in a key (21 bits each; leaves of one build share h). */
static uint64_t leaf_key(const oct_leaf_t *l, int axis, int step)
{
	uint64_t k = 0;
	for (int i = 0; i < 3; i++) {
		double v = l->c[i] / (2.0 * l->h) - 0.5;
		v = v < -1e6 ? -1e6 : v > 1e6 ? 1e6 : v;   /* keys stay defined for absurd inputs */
		long long c = llround(v) + (i == axis ? step : 0);
		k = (k << 21) | ((uint64_t)(c + (1 << 20)) & 0x1fffff);
	}
	return k;
}

static int cmp_key(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return x < y ? -1 : x > y;
}

int oct_faces(const cam_t *cam, const rt_object_t *mat, const rt_light_t *lights, size_t nlights,
              const oct_leaf_t *leaves, size_t n, int shading,
              oct_face_t **faces, size_t *nfaces, size_t *cap)
{
	/* a face shared with another leaf is hidden: find neighbours by sorted keys */
	uint64_t *keys = malloc((n ? n : 1) * sizeof *keys);
	if (!keys)
		return -1;
	for (size_t i = 0; i < n; i++)
		keys[i] = leaf_key(&leaves[i], 0, 0);
	if (n)
		qsort(keys, n, sizeof *keys, cmp_key);
	for (size_t li = 0; li < n; li++) {
		const oct_leaf_t *l = &leaves[li];
		double c[3] = {l->c[0], l->c[1], l->c[2]}, h = l->h, g[3];
		if (shading == RT_GOURAUD) {
			model_grad(mat->shape, c, g);
			double len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
			double toeye = 0;
			for (int i = 0; i < 3; i++)
				toeye += (cam->projection == CAM_ORTHOGRAPHIC ? -cam->fwd[i] : cam->eye[i] - c[i]) * g[i];
			for (int i = 0; i < 3; i++)
				g[i] = len > 0 ? g[i] / len * (toeye < 0 ? -1 : 1) : -cam->fwd[i];
		}
		for (int axis = 0; axis < 3; axis++) {
			double view = cam->projection == CAM_ORTHOGRAPHIC ? -cam->fwd[axis] : cam->eye[axis] - c[axis];
			if (fabs(view) <= h && cam->projection != CAM_ORTHOGRAPHIC)
				continue;
			if (view == 0)
				continue;
			double sgn = view > 0 ? 1 : -1;
			uint64_t nk = leaf_key(l, axis, view > 0 ? 1 : -1);
			if (bsearch(&nk, keys, n, sizeof *keys, cmp_key))
				continue;
			if (*nfaces == *cap) {
				size_t nc = *cap ? 2 * *cap : 4096;
				oct_face_t *q = realloc(*faces, nc * sizeof *q);
				if (!q) {
					free(keys);
					return -1;
				}
				*faces = q;
				*cap = nc;
			}
			oct_face_t *f = &(*faces)[*nfaces];
			int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3, ok = 1;
			double fc[3];
			memcpy(fc, c, sizeof fc);
			fc[axis] += sgn * h;
			static const int us[4] = {-1, 1, 1, -1}, vs[4] = {-1, -1, 1, 1};
			for (int k = 0; k < 4 && ok; k++) {
				double q[3], px, py, depth;
				memcpy(q, fc, sizeof q);
				q[a1] += us[k] * h;
				q[a2] += vs[k] * h;
				ok = cam_project(cam, q, &px, &py, &depth) == 0;
				f->x[k] = (float)px;
				f->y[k] = (float)py;
			}
			if (!ok)
				continue;
			double d[3] = {fc[0] - cam->eye[0], fc[1] - cam->eye[1], fc[2] - cam->eye[2]};
			f->depth = (float)(cam->projection == CAM_ORTHOGRAPHIC
			                   ? d[0] * cam->fwd[0] + d[1] * cam->fwd[1] + d[2] * cam->fwd[2]
			                   : sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
			double nrm[3] = {0, 0, 0};
			nrm[axis] = sgn;
			f->rgb = shade(mat, lights, nlights, shading == RT_GOURAUD ? g : nrm, fc);
			(*nfaces)++;
		}
	}
	free(keys);
	return 0;
}

static int far_first(const void *a, const void *b)
{
	const oct_face_t *x = a, *y = b;
	if (x->depth != y->depth)
		return x->depth > y->depth ? -1 : 1;
	if (x->x[0] != y->x[0])
		return x->x[0] < y->x[0] ? -1 : 1;
	if (x->y[0] != y->y[0])
		return x->y[0] < y->y[0] ? -1 : 1;
	return x->rgb < y->rgb ? -1 : x->rgb > y->rgb;
}

int oct_draw(meta_writer_t *w, oct_face_t *faces, size_t n, double xoff)
{
	if (n == 0)
		return 0;
	qsort(faces, n, sizeof *faces, far_first);
	for (size_t i = 0; i < n; i++) {
		const oct_face_t *f = &faces[i];
		int rc = meta_colour(w, f->rgb);
		if (rc >= 0)
			rc = meta_fill(w);
		for (int k = 0; k < 4 && rc >= 0; k++)
			rc = k ? meta_draw(w, xoff + f->x[k], f->y[k]) : meta_move(w, xoff + f->x[k], f->y[k]);
		if (rc >= 0)
			rc = meta_end(w);
		if (rc < 0)
			return rc;
	}
	return 0;
}
