/* test_scene_hand.c: the thesis' left-handed system by default (a point at +x is drawn on the right), `handedness right` mirrors it. */
#include "unit.h"
#include "scene.h"

#include <math.h>
#include <stdlib.h>

/* Mean column of the red pixels of the scene's first object, ray traced (-1: none). */
static double red_column(const char *text, int *rows_top)
{
	scene_t *s;
	char err[512];
	if (scene_parse(text, "hand.scene", &s, err, sizeof err) < 0) {
		printf("# %s\n", err);
		return -1;
	}
	rt_params_t p;
	memset(&p, 0, sizeof p);
	p.cam = s->cam;
	p.objects = &s->objs[0].mat;
	p.nobjects = 1;
	p.accuracy = 1e-3;
	p.threads = 1;
	unsigned nx = s->cam.nxpix, ny = s->cam.nypix;
	meta_rgb_t *img = malloc((size_t)nx * ny * sizeof *img);
	double sum = 0, top = 0;
	long n = 0;
	if (img && rt_render(&p, img, NULL, err, sizeof err) == 0)
		for (unsigned r = 0; r < ny; r++)
			for (unsigned i = 0; i < nx; i++)
				if (img[(size_t)r * nx + i] == 0xff0000) {
					sum += i;
					top += r;
					n++;
				}
	free(img);
	scene_free(s);
	*rows_top = n ? (int)(top / n) : -1;
	return n ? sum / n : -1;
}

int main(void)
{
	/* a small sphere at +x (and +y), the thesis' default view: eye on -z looking at the origin */
	const char *left = "view\n  size 64 48\nend\nobject a\n  point 1.5 1 0\n  c 0.4\n  colour 1 0 0\n  shading constant\nend\n";
	const char *right = "view\n  size 64 48\n  handedness right\nend\nobject a\n  point 1.5 1 0\n  c 0.4\n  colour 1 0 0\n  shading constant\nend\n";
	int rl, rr;
	double cl = red_column(left, &rl), cr = red_column(right, &rr);
	CHECK(cl > 40, "left-handed (default): the sphere at +x is drawn right of the centre (mean column %.1f of 64)", cl);
	CHECK(rl >= 0 && rl < 20, "... and at +y above it (mean row %d from the top of 48)", rl);
	CHECK(cr >= 0 && cr < 24 && rr == rl, "handedness right: the mirror image, +x on the left (column %.1f), same height", cr);
	CHECK(cl >= 0 && cr >= 0 && fabs(cl + cr - 63) < 0.5, "the two pictures are mirror images (%.1f + %.1f = 63)", cl, cr);
	/* the frame: right = up x forward, up' = forward x right; projection agrees with the picture */
	scene_t *s;
	char err[256];
	CHECK(scene_parse(left, "hand.scene", &s, err, sizeof err) == 0, "parse");
	CHECK(s->cam.handedness == CAM_LEFT_HANDED && s->cam.right[0] > 0.99 && s->cam.upv[1] > 0.99, "left-handed frame: right = +x, up = +y");
	double px, py, depth;
	cam_project(&s->cam, (double[]){1, 0, 0}, &px, &py, &depth);
	CHECK(px > 32 && fabs(py - 24) < 1e-9, "the point (1, 0, 0) projects right of the centre (%.2f, %.2f)", px, py);
	scene_free(s);
	CHECK(scene_parse("view\n  handedness sideways\nend\n", "hand.scene", &s, err, sizeof err) < 0
	      && strstr(err, "hand.scene:2:14: expected left (the thesis' system, the default) or right, found 'sideways'"), "bad handedness: %s", err);
	return UNIT_DONE();
}
