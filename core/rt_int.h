/* rt_int.h: internal interface between the ray tracer's packet marcher and its renderer. */
#ifndef LOCUS_RT_INT_H
#define LOCUS_RT_INT_H

#include <stdint.h>
#include "model.h"

/* Eight rays marched together. The pixel footprint at parameter t is
 * fa + fb * t world units; acc is the hit tolerance in footprints and step
 * the bracketing-fallback step in footprints. */
typedef struct {
	double o[8][3], d[8][3];
	double tmin[8], tmax[8];
	double fa[8], fb[8];
	int active[8];
	double acc, step;
	double thit[8];          /* out: hit parameter, INFINITY when none */
} rt_packet_t;

/* March the active rays against s. shadow != 0 stops at the first sample
 * with f <= 0 (any hit is enough). Adds evaluations (active lanes) to *evals
 * and 8 per kernel call to *lanes. */
void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes);

#endif
