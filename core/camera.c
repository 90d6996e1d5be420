/* camera.c: observer frame, rays through pixels and projection of points to the viewport. */
#include "camera.h"

#include <math.h>
#include <stdio.h>

static void cross(const double *a, const double *b, double *c)
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm(double *a)
{
	double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
	if (l > 0)
		for (int i = 0; i < 3; i++)
			a[i] /= l;
	return l;
}

int cam_setup(cam_t *c, char *err, unsigned long errlen)
{
	for (int i = 0; i < 3; i++)
		if (!isfinite(c->eye[i]) || !isfinite(c->look[i]) || !isfinite(c->up[i])) {
			snprintf(err, errlen, "finite eye, look-at and up vectors");
			return -1;
		}
	for (int i = 0; i < 3; i++)
		c->fwd[i] = c->look[i] - c->eye[i];
	double dist = norm(c->fwd);
	if (!(dist > 0)) {
		snprintf(err, errlen, "an eye position different from the look-at point");
		return -1;
	}
	if (c->handedness == CAM_RIGHT_HANDED)
		cross(c->fwd, c->up, c->right);
	else
		cross(c->up, c->fwd, c->right);
	if (!(norm(c->right) > 1e-9 * (1 + sqrt(c->up[0] * c->up[0] + c->up[1] * c->up[1] + c->up[2] * c->up[2])))) {
		snprintf(err, errlen, "an up vector not parallel to the viewing direction");
		return -1;
	}
	if (c->handedness == CAM_RIGHT_HANDED)
		cross(c->right, c->fwd, c->upv);
	else
		cross(c->fwd, c->right, c->upv);
	if (!(c->fov > 0 && c->fov < 180)) {
		snprintf(err, errlen, "a field of view between 0 and 180 degrees");
		return -1;
	}
	if (c->nxpix < 1 || c->nypix < 1 || c->nxpix > 32768 || c->nypix > 32768) {
		snprintf(err, errlen, "a viewport of 1..32768 pixels each way");
		return -1;
	}
	c->horiz = 2 * tan(c->fov * 3.14159265358979323846 / 360);
	if (c->projection == CAM_ORTHOGRAPHIC)
		c->horiz = c->window > 0 ? c->window : c->horiz * dist;
	if (!(c->window >= 0) || !isfinite(c->window)) {
		snprintf(err, errlen, "a positive window width");
		return -1;
	}
	c->vert = c->horiz * c->nypix / c->nxpix;
	return 0;
}

void cam_ray(const cam_t *c, double px, double py, double o[3], double d[3])
{
	double x = (px / c->nxpix - 0.5) * c->horiz, y = (py / c->nypix - 0.5) * c->vert;
	if (c->projection == CAM_ORTHOGRAPHIC) {
		for (int i = 0; i < 3; i++) {
			o[i] = c->eye[i] + x * c->right[i] + y * c->upv[i];
			d[i] = c->fwd[i];
		}
		return;
	}
	for (int i = 0; i < 3; i++) {
		o[i] = c->eye[i];
		d[i] = c->fwd[i] + x * c->right[i] + y * c->upv[i];
	}
	norm(d);
}

int cam_project(const cam_t *c, const double p[3], double *px, double *py, double *depth)
{
	double v[3] = {p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2]};
	double z = v[0] * c->fwd[0] + v[1] * c->fwd[1] + v[2] * c->fwd[2];
	double x = v[0] * c->right[0] + v[1] * c->right[1] + v[2] * c->right[2];
	double y = v[0] * c->upv[0] + v[1] * c->upv[1] + v[2] * c->upv[2];
	*depth = z;
	if (c->projection == CAM_PERSPECTIVE) {
		if (!(z > 1e-9))
			return -1;
		x /= z;
		y /= z;
	}
	*px = (x / c->horiz + 0.5) * c->nxpix;
	*py = (y / c->vert + 0.5) * c->nypix;
	return 0;
}

double cam_footprint(const cam_t *c, double t)
{
	if (c->projection == CAM_ORTHOGRAPHIC)
		return c->horiz / c->nxpix;
	return t * c->horiz / c->nxpix;
}

cam_t cam_shifted(const cam_t *c, double offset)
{
	cam_t s = *c;
	for (int i = 0; i < 3; i++)
		s.eye[i] += offset * c->right[i];
	return s;
}
