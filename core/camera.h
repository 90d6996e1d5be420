/* camera.h: the observer and the ABSOLUTE -> OBSERVER -> WINDOW -> VIEWPORT mapping (thesis section 1.4).
 *
 * Handedness: by default the thesis' LEFT-handed system (section 1.2: x to
 * the right, y up, z away from the viewer). The OBSERVER frame has its origin
 * at the eye; forward = normalize(look - eye), right = normalize(up x forward),
 * upv = forward x right (with the default eye on -z looking at the origin, +x
 * is on the right of the picture, as in the thesis and in POV-Ray).
 * handedness = CAM_RIGHT_HANDED gives the mirror image: right = normalize(
 * forward x up), upv = right x forward (+x on the left in that view). On the
 * picture, right points to the right and upv up.
 *
 * WINDOW: perspective projection onto the plane at distance 1 in front of the
 * eye; the window is centred on the origin of the WINDOW system, horiz =
 * 2 tan(fov/2) wide (fov = horizontal field of view) and vert = horiz *
 * nypix / nxpix high. Orthographic projection uses parallel rays along
 * forward and a window of horiz = `window` world units (default: the width
 * the perspective window would have at the look-at point).
 * VIEWPORT: nxpix x nypix pixels counted from the bottom left; the window
 * point (x, y) lies in pixel (floor((2x + horiz) nxpix / (2 horiz)),
 * floor((2y + vert) nypix / (2 vert))), and pixel (i, j) is sampled at its
 * centre (i + 0.5, j + 0.5).
 */
#ifndef LOCUS_CAMERA_H
#define LOCUS_CAMERA_H

enum { CAM_PERSPECTIVE, CAM_ORTHOGRAPHIC };
/* Handedness of the ABSOLUTE system (the zero value is the thesis' left-handed one). */
enum { CAM_LEFT_HANDED = 0, CAM_RIGHT_HANDED = 1 };

typedef struct {
	double eye[3], look[3], up[3];
	double fov;          /* horizontal field of view, degrees (perspective) */
	double window;       /* orthographic window width in world units (0: derived) */
	int projection;      /* CAM_PERSPECTIVE or CAM_ORTHOGRAPHIC */
	int handedness;      /* CAM_LEFT_HANDED (default) or CAM_RIGHT_HANDED */
	unsigned nxpix, nypix;
	/* derived by cam_setup: */
	double fwd[3], right[3], upv[3];
	double horiz, vert;  /* window size (perspective: at distance 1) */
} cam_t;

/* Derive the frame and window. Returns 0, or -1 with a message when eye ==
 * look, up is parallel to the view direction, fov is not in (0, 180) or a
 * value is not finite. */
int cam_setup(cam_t *c, char *err, unsigned long errlen);

/* The ray through viewport point (px, py) (pixel units, e.g. i + 0.5):
 * origin o and unit direction d in the ABSOLUTE frame. */
void cam_ray(const cam_t *c, double px, double py, double o[3], double d[3]);

/* Project the ABSOLUTE point p to viewport coordinates; *depth is the
 * distance along forward. Returns -1 when p is behind the eye (perspective). */
int cam_project(const cam_t *c, const double p[3], double *px, double *py, double *depth);

/* Size in world units of one pixel at distance t along a ray. */
double cam_footprint(const cam_t *c, double t);

/* A copy of c with the eye moved by `offset` along right (stereo eyes). */
cam_t cam_shifted(const cam_t *c, double offset);

#endif
