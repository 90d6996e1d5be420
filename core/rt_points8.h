/* rt_points8.h: the points-and-segments distance kernel of 8 lanes in vector registers (model_eval8's
 * fast path, s->fast_points), inline so that the packet marcher keeps its state in registers around
 * it. AVX builds only. */
#ifndef LOCUS_RT_POINTS8_H
#define LOCUS_RT_POINTS8_H

#ifdef __AVX__
#include <immintrin.h>
#include "model.h"

typedef float vf8 __attribute__((vector_size(32)));
typedef int vi8 __attribute__((vector_size(32)));

static inline vf8 vsplat(float x) { return (vf8){x, x, x, x, x, x, x, x}; }
static inline vf8 vsqrt(vf8 a) { return (vf8)_mm256_sqrt_ps((__m256)a); }
/* m ? a : b lane by lane (m all ones or zero) */
static inline vf8 vsel(vi8 m, vf8 a, vf8 b) { return (vf8)(((vi8)a & m) | ((vi8)b & ~m)); }

/* f at the 8 points (qx, qy, qz) of a shape with s->fast_points: the same float operations in the
 * same order, lane by lane, as the general path of model_kernel.c */
static inline __attribute__((always_inline)) vf8 rt_points8v(const model_shape_t *s, vf8 qx, vf8 qy, vf8 qz)
{
	vf8 sum = vsplat(0.0f);
	qx = qx + s->mf[3];
	qy = qy + s->mf[7];
	qz = qz + s->mf[11];
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		const float *a = e->pf, w = (float)e->w;
		vf8 px = qx - a[0], py = qy - a[1], pz = qz - a[2];
		if (e->kind != MODEL_POINT) {   /* segment8 */
			const float bx = a[3], by = a[4], bz = a[5];
			vf8 h = (px * bx + py * by + pz * bz) * a[6];
			vf8 hc = vsel(h < 0.0f, vsplat(0.0f), vsel(h > 1.0f, vsplat(1.0f), h));
			px = px - hc * bx;
			py = py - hc * by;
			pz = pz - hc * bz;
		}
		sum = sum + w * vsqrt(px * px + py * py + pz * pz);
	}
	return sum - (float)s->c.c0;
}
#endif

#endif
