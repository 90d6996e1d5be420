/* rt.h: ray tracing of distance-based shapes: 8-ray packets, Lipschitz sphere tracing, shading, shadows, supersampling.
 *
 * Marching (per ray, 8 rays evaluated together by model_eval8):
 *   - the ray is clipped to the object's region (bounding sphere and box);
 *     when it enters the region inside the solid (f < 0) it marches on -f,
 *     so what is drawn is always the surface f = 0, never the clip box;
 *   - with a Lipschitz bound L, each accepted sample t certifies the ball of
 *     radius f(t)/L free of surface. A step s from t to t' is accepted only
 *     if the two balls overlap, f(t)/L + f(t')/L >= s (so the whole segment
 *     is certified), or if f(t') <= 0 (a sign change: bracketed). Steps
 *     are proposed from the measured slope (secant to the root, 1.05x, or
 *     the largest step two overlapping balls allow), never below f/L;
 *     a rejected proposal falls back to the plain sphere-tracing step f/L;
 *   - a sign change is refined by regula falsi (Illinois) to `accuracy`
 *     pixels; a ray that only grazes the surface (f/L tiny, no sign change)
 *     keeps stepping by 1/20 pixel so that the silhouette is decided by the
 *     sign of f, not by a tolerance;
 *   - without a Lipschitz bound (e.g. a Mandelbrot parameter) the ray is
 *     marched in fixed steps of `step_pixels` pixel footprints (but at least
 *     1/1000 of its path through the region, so no ray takes more than about
 *     1000 steps) and sign changes are bisected (the bracketing fallback).
 * Every evaluation of f is counted (rt_stats_t), per ray kind.
 *
 * Precision: an object that the float lanes cannot resolve to `accuracy` in
 * this view (far eye, large coordinates, narrow field: rt_needs_double) is
 * marched ray by ray in double precision with the same rules (rt_march1.c).
 *
 * Shading: RT_CONSTANT is the object colour, unlit; RT_GOURAUD ambient +
 * diffuse (Lambert); RT_PHONG adds specular highlights (reflection vector,
 * exponent `shininess`). Surfaces are two-sided: the normal grad f/|grad f|
 * is turned to the side the ray came from (the sign of f before the
 * crossing; the sign of N.V only for a ray that starts on the surface). A light with shadows casts a shadow ray
 * from the hit point (offset by half a pixel footprint along the normal)
 * that is marched like a primary ray against every object.
 *
 * Determinism: rows are handed out to threads dynamically but every pixel
 * is computed independently with the same operations, so the picture is the
 * same whatever the thread count.
 */
#ifndef LOCUS_RT_H
#define LOCUS_RT_H

#include <stddef.h>
#include <stdint.h>
#include "camera.h"
#include "locus_meta.h"
#include "model.h"

enum { RT_CONSTANT, RT_GOURAUD, RT_PHONG };

/* An object to draw: a prepared shape and its material. */
typedef struct {
	const model_shape_t *shape;
	double colour[3];          /* 0..1 */
	int shading;               /* RT_CONSTANT, RT_GOURAUD or RT_PHONG */
	double ambient, diffuse, specular, shininess;
} rt_object_t;

/* A light: a point at pos, or directional (pos is then the direction TOWARDS the light). */
typedef struct {
	int directional;
	double pos[3];
	double colour[3];
	int shadows;
} rt_light_t;

/* Called from the main thread with rows finished so far. */
typedef void (*rt_progress_fn)(void *user, unsigned done, unsigned total);

typedef struct {
	cam_t cam;                 /* set up with cam_setup */
	const rt_object_t *objects;
	size_t nobjects;
	const rt_light_t *lights;
	size_t nlights;
	double background[3];
	double accuracy;           /* hit tolerance in pixels (default 1e-3) */
	double step_pixels;        /* bracketing fallback step in pixels (default 0.5) */
	int supersample;           /* 0: off; N >= 2: N x N samples where neighbours differ */
	int refine;                /* reference mode: polish hits with double-precision Newton steps */
	double aa_threshold;       /* colour difference (0..255) that triggers supersampling */
	unsigned threads;          /* 0: number of online CPUs */
	rt_progress_fn progress;
	void *progress_user;
} rt_params_t;

/* What a render cost. */
typedef struct {
	uint64_t evals;            /* distance-function evaluations (active lanes) */
	uint64_t lane_evals;       /* 8 x model_eval8 calls (idle lanes included) */
	uint64_t primary_evals, shadow_evals, normal_evals, aa_evals;
	uint64_t hits;             /* primary rays that hit */
	uint64_t aa_pixels;        /* pixels supersampled */
} rt_stats_t;

/* Render the picture into img (nxpix * nypix colours 0xRRGGBB, TOP row
 * first, as meta image rows go). Returns 0, or -1 with a message. */
int rt_render(const rt_params_t *p, meta_rgb_t *img, rt_stats_t *st, char *err, size_t errlen);

/* Write img (top row first) as one meta image at viewport (x, y). */
int rt_write_image(meta_writer_t *w, const meta_rgb_t *img, unsigned width, unsigned height,
                   unsigned x, unsigned y);

#endif
