/* rt_int.h: internal interface between the ray tracer's packet marcher and its renderer. */
#ifndef LOCUS_RT_INT_H
#define LOCUS_RT_INT_H

#include <stdint.h>
#include "camera.h"
#include "model.h"

/* Rays marched together: two groups of 8 (model_eval8 calls) whose
 * independent dependency chains the processor overlaps. */
#define RT_LANES 16

/* RT_LANES rays marched together, structure of arrays in float (what the
 * kernels take). The pixel footprint at parameter t is fa + fb * t world
 * units; acc is the hit tolerance in footprints and step the
 * bracketing-fallback step in footprints. */
typedef struct {
	float ox[RT_LANES], oy[RT_LANES], oz[RT_LANES], dx[RT_LANES], dy[RT_LANES], dz[RT_LANES];
	float tmin[RT_LANES], tmax[RT_LANES];
	float fa[RT_LANES], fb[RT_LANES];
	int active[RT_LANES];
	float acc, step;
	float thit[RT_LANES];           /* out: hit parameter, INFINITY when none */
	float side[RT_LANES];           /* out: the sign of f on the side the ray came from (0: unknown) */
	double o[3][RT_LANES], d[3][RT_LANES]; /* the same rays in double (for rt_march1) */
} rt_packet_t;

/* What the marchers trace for s: f with its Lipschitz bound, or for a distance-estimated shape
 * (s->de) the estimate itself with bound 1; 0 when neither (the bracketing fallback). */
static inline double rt_bound(const model_shape_t *s)
{
	return s->de ? 1.0 : s->has_lip ? s->lip : 0.0;
}
static inline void rt_eval8(const model_shape_t *s, const float *x, const float *y, const float *z, float *out)
{
	if (s->de)
		model_de8(s, x, y, z, out);
	else
		model_eval8(s, x, y, z, out);
}

/* grad f at p for a shape whose kernel takes the points-and-segments fast path (s->fast_points):
 * model_grad's twin for those shapes, the same double operations in the same order (so the same
 * bits) without its general dispatch. Any other shape goes to model_grad. */
void rt_grad(const model_shape_t *s, const double p[3], double g[3]);

/* March the active rays against s. shadow != 0 stops at the first sample
 * with f <= 0 (any hit is enough). Adds evaluations (active lanes) to *evals
 * and 8 per kernel call to *lanes. */
void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes);

/* 1 when the float marcher cannot resolve s in this view to `accuracy` pixels (far eye, large
 * coordinates, narrow field of view): the object is then marched by rt_march1. */
int rt_needs_double(const cam_t *c, const model_shape_t *s, double accuracy);

/* March one ray o + t d (d unit, double precision throughout) against s over [tmin, tmax]; the
 * pixel footprint at t is fa + fb t, acc the hit tolerance and step the bracketing step in
 * footprints. Returns the hit parameter (INFINITY: none); *side = the sign of f where the ray
 * came from (0 when it starts on the surface). shadow != 0 stops at the first f <= 0. Adds the
 * evaluations to *evals. */
double rt_march1(const model_shape_t *s, const double *o, const double *d, double tmin, double tmax,
                 double fa, double fb, double acc, double step, int shadow, int *side, uint64_t *evals);

#endif
