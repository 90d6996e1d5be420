/* rt_int.h: internal interface between the ray tracer's packet marcher and its renderer. */
#ifndef LOCUS_RT_INT_H
#define LOCUS_RT_INT_H

#include <stdint.h>
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
} rt_packet_t;

/* March the active rays against s. shadow != 0 stops at the first sample
 * with f <= 0 (any hit is enough). Adds evaluations (active lanes) to *evals
 * and 8 per kernel call to *lanes. */
void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes);

#endif
