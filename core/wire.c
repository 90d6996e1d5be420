/* wire.c: wireframes as projected cross-section contours (marching squares per slice via contour.h). */
#include "wire.h"
#include "contour.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
	meta_writer_t *w;
	const cam_t *cam;
	int axis;
	double level;            /* the slice coordinate */
	double lo[3], step[3];   /* grid index -> world */
	double xoff;
	uint64_t *segments;
	int rc;
} slice_t;

static int polyline(void *user, unsigned level, const contour_point_t *p, size_t n, int closed)
{
	slice_t *s = user;
	(void)level;
	int a1 = (s->axis + 1) % 3, a2 = (s->axis + 2) % 3;
	int rc = meta_stroke(s->w);
	for (size_t i = 0; i < n && rc >= 0; i++) {
		double q[3], px, py, depth;
		q[s->axis] = s->level;
		q[a1] = s->lo[a1] + p[i].x * s->step[a1];
		q[a2] = s->lo[a2] + p[i].y * s->step[a2];
		if (cam_project(s->cam, q, &px, &py, &depth) < 0) {
			rc = 0;
			break;   /* behind the eye: the rest of this line is not drawn */
		}
		rc = i ? meta_draw(s->w, s->xoff + px, py) : meta_move(s->w, s->xoff + px, py);
	}
	if (rc >= 0 && closed)
		rc = meta_close(s->w);
	if (rc >= 0)
		rc = meta_end(s->w);
	*s->segments += n - 1 + (closed ? 1 : 0);
	s->rc = rc;
	return rc < 0 ? -1 : 0;
}

int wire_draw(meta_writer_t *w, const cam_t *cam, const model_shape_t *s, int axis, int slices,
              int res, double width, meta_rgb_t colour, double xoff, uint64_t *segments,
              char *err, size_t errlen)
{
	if (res < 4 || slices < 1 || axis < 0 || axis > 2) {
		snprintf(err, errlen, "expected slices >= 1, resolution >= 4 and an axis x, y or z");
		return -1;
	}
	size_t nres = (size_t)res, npts = nres * nres;
	float *z = malloc((npts + 8) * sizeof *z);
	if (!z) {
		snprintf(err, errlen, "out of memory for a %d x %d slice", res, res);
		return -1;
	}
	slice_t sl;
	memset(&sl, 0, sizeof sl);
	sl.w = w;
	sl.cam = cam;
	sl.axis = axis;
	sl.xoff = xoff;
	sl.segments = segments;
	int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3, rc = 0;
	for (int i = 0; i < 3; i++) {
		sl.lo[i] = s->box[i];
		sl.step[i] = (s->box[3 + i] - s->box[i]) / (res - 1);
	}
	if (meta_colour(w, colour) < 0 || meta_width(w, width) < 0) {
		free(z);
		snprintf(err, errlen, "%s", meta_writer_error(w));
		return -1;
	}
	for (int k = 0; k < slices && rc == 0; k++) {
		sl.level = s->box[axis] + (k + 0.5) * (s->box[3 + axis] - s->box[axis]) / slices;
		float x[3][8], out[8];
		for (size_t i0 = 0; i0 < npts; i0 += 8) {
			for (size_t k8 = 0; k8 < 8; k8++) {
				size_t i = i0 + k8 < npts ? i0 + k8 : npts - 1;
				x[axis][k8] = (float)sl.level;
				x[a1][k8] = (float)(sl.lo[a1] + (double)(i % nres) * sl.step[a1]);
				x[a2][k8] = (float)(sl.lo[a2] + (double)(i / nres) * sl.step[a2]);
			}
			model_eval8(s, x[0], x[1], x[2], out);
			for (size_t k8 = 0; k8 < 8 && i0 + k8 < npts; k8++)
				z[i0 + k8] = out[k8];
		}
		contour_grid_t g;
		memset(&g, 0, sizeof g);
		g.z = z;
		g.nx = g.ny = (unsigned)res;
		g.m[1] = 1;
		g.m[5] = 1;
		double level0 = 0;
		if (contour_extract(&g, &level0, 1, polyline, &sl, NULL) < 0) {
			snprintf(err, errlen, "%s", sl.rc < 0 ? meta_writer_error(w) : contour_error());
			rc = -1;
		}
	}
	free(z);
	return rc;
}
