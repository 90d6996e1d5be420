/* rt_int.h: internal interface between the ray tracer's packet marcher and its renderer. */
#ifndef LOCUS_RT_INT_H
#define LOCUS_RT_INT_H

#include <stdint.h>
#include "model.h"

/* Eight rays marched together, structure of arrays in float (what the
 * kernels take). The pixel footprint at parameter t is fa + fb * t world
 * units; acc is the hit tolerance in footprints and step the
 * bracketing-fallback step in footprints. */
typedef struct {
	float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8];
	float tmin[8], tmax[8];
	float fa[8], fb[8];
	int active[8];
	float acc, step;
	float thit[8];           /* out: hit parameter, INFINITY when none */
} rt_packet_t;

/* March the active rays against s. shadow != 0 stops at the first sample
 * with f <= 0 (any hit is enough). Adds evaluations (active lanes) to *evals
 * and 8 per kernel call to *lanes. */
void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes);

#endif
