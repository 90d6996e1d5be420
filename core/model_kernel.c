/* model_kernel.c: the 8-points-at-once float evaluator of a shape (branch-free loops that gcc vectorises). */
#include "model.h"

#include <math.h>
#include <string.h>
#ifdef __AVX__
#include <immintrin.h>
#endif

typedef float v8[8];

static void point8(const float *restrict a, const float *restrict x, const float *restrict y, const float *restrict z, float *restrict d)
{
	for (int k = 0; k < 8; k++) {
		float dx = x[k] - a[0], dy = y[k] - a[1], dz = z[k] - a[2];
		d[k] = sqrtf(dx * dx + dy * dy + dz * dz);
	}
}

/* f: a, b-a, 1/|b-a|^2 */
static void segment8(const float *restrict f, const float *restrict x, const float *restrict y, const float *restrict z, float *restrict d)
{
	const float ax = f[0], ay = f[1], az = f[2], bx = f[3], by = f[4], bz = f[5], il = f[6];
	/* two loops with the clamp on integer conditions: gcc vectorises both with AVX2 as well (one
	 * loop with the two float selects it leaves scalar there); the same values */
	float hc[8];
	for (int k = 0; k < 8; k++) {
		float px = x[k] - ax, py = y[k] - ay, pz = z[k] - az;
		float h = (px * bx + py * by + pz * bz) * il;
		int below = h < 0.0f, above = h > 1.0f;
		hc[k] = below ? 0.0f : above ? 1.0f : h;
	}
	for (int k = 0; k < 8; k++) {
		float px = x[k] - ax, py = y[k] - ay, pz = z[k] - az;
		px -= hc[k] * bx;
		py -= hc[k] * by;
		pz -= hc[k] * bz;
		d[k] = sqrtf(px * px + py * py + pz * pz);
	}
}

/* Infinite line (a, u), plane (n, offset) or disk (c, n, r); f as laid out by model_add. */
static void plane_line_disk8(int kind, const float *restrict f, const float *restrict x,
                             const float *restrict y, const float *restrict z, float *restrict d)
{
	const float a0 = f[0], a1 = f[1], a2 = f[2], n0 = f[3], n1 = f[4], n2 = f[5], r = f[6];
	if (kind == MODEL_PLANE) {
		for (int k = 0; k < 8; k++)
			d[k] = fabsf(x[k] * a0 + y[k] * a1 + z[k] * a2 - n0);
		return;
	}
	for (int k = 0; k < 8; k++) {
		float px = x[k] - a0, py = y[k] - a1, pz = z[k] - a2;
		float h = px * n0 + py * n1 + pz * n2;
		px -= h * n0;
		py -= h * n1;
		pz -= h * n2;
		float rho2 = px * px + py * py + pz * pz;
		if (kind == MODEL_LINE) {
			d[k] = sqrtf(rho2);
		} else {
			float o = sqrtf(rho2) - r;
			o = o > 0.0f ? o : 0.0f;
			d[k] = sqrtf(h * h + o * o);
		}
	}
}

static void elem8(const model_elem_t *e, const v8 x, const v8 y, const v8 z,
                  const v8 ax, const v8 ay, const v8 az, v8 d)
{
	const float *f = e->pf;
	v8 t;
	if (e->measured) {   /* powers and metrics: the scalar double path, lane by lane */
		for (int k = 0; k < 8; k++)
			d[k] = (float)model_elem_measure(e, (double[]){x[k], y[k], z[k]});
		return;
	}
	switch (e->kind) {
	case MODEL_POINT:
		point8(f, x, y, z, d);
		break;
	case MODEL_POINTS:
		point8(f, x, y, z, d);
		for (size_t i = 1; i < e->np; i++) {
			point8(f + 3 * i, x, y, z, t);
			for (int k = 0; k < 8; k++)
				d[k] = t[k] < d[k] ? t[k] : d[k];
		}
		break;
	case MODEL_SEGMENT:
		segment8(f, x, y, z, d);
		break;
	case MODEL_VORONOI: {
		/* two smallest of d(P, N_k) - w_k over the nuclei (segments; points have b = a) */
		v8 d2;
		for (int k = 0; k < 8; k++) {
			d[k] = INFINITY;
			d2[k] = INFINITY;
		}
		v8 cur;
		for (size_t i = 0; i <= e->np; i++) {
			/* a segment that starts a nucleus folds the previous one into the two smallest */
			if (i == e->np || f[10 * i + 9] == 0.0f) {
				if (i > 0)
					for (int k = 0; k < 8; k++) {
						float v = cur[k], a = d[k], b = d2[k];
						d2[k] = v < a ? a : (v < b ? v : b);
						d[k] = v < a ? v : a;
					}
				if (i == e->np)
					break;
				for (int k = 0; k < 8; k++)
					cur[k] = INFINITY;
			}
			const float *g = f + 10 * i, wk = g[7], im = g[8];
			segment8(g, x, y, z, t);
			for (int k = 0; k < 8; k++) {
				float v = t[k] * im - wk;
				cur[k] = v < cur[k] ? v : cur[k];
			}
		}
		for (int k = 0; k < 8; k++)
			d[k] = 0.5f * (d2[k] - d[k]);
		break;
	}
	case MODEL_POLYLINE:
		segment8(f, x, y, z, d);
		for (size_t i = 1; i + 1 < e->np; i++) {
			segment8(f + 7 * i, x, y, z, t);
			for (int k = 0; k < 8; k++)
				d[k] = t[k] < d[k] ? t[k] : d[k];
		}
		break;
	case MODEL_LINE:
	case MODEL_DISK:
	case MODEL_PLANE:
		plane_line_disk8(e->kind, f, x, y, z, d);
		break;
	case MODEL_CIRCLE:
	case MODEL_TRIANGLE:
	case MODEL_POLYGON:
	case MODEL_BOX:
		/* the scalar double path, lane by lane */
		for (int k = 0; k < 8; k++)
			d[k] = (float)model_elem_distance(e, (double[]){x[k], y[k], z[k]});
		break;
	case MODEL_CSG: {
		v8 b;
		model_eval8(e->shape, ax, ay, az, d);
		model_eval8(e->shape2, ax, ay, az, b);
		const float ia = (float)(1.0 / e->shape->lip), ib = (float)(1.0 / e->shape2->lip), kk = (float)e->r;
		for (int k = 0; k < 8; k++) {
			float a = d[k] * ia, c = b[k] * ib;
			switch (e->op) {
			case MODEL_UNION: d[k] = a < c ? a : c; break;
			case MODEL_INTERSECTION: d[k] = a > c ? a : c; break;
			case MODEL_DIFFERENCE: d[k] = a > -c ? a : -c; break;
			default: {
				float h = kk - fabsf(a - c);
				h = h > 0.0f ? h / kk : 0.0f;
				d[k] = (a < c ? a : c) - kk * h * h * 0.25f;
			}
			}
		}
		break;
	}
	default: {
		model_eval8(e->shape, ax, ay, az, d);
		float il = (float)(1.0 / e->shape->lip);
		for (int k = 0; k < 8; k++)
			d[k] = fabsf(d[k]) * il;
	}
	}
}

/* Points and segments only, constant c, translated frame: the benchmarks'
 * case, with the same arithmetic as the general path below (same results). */
#ifdef __AVX__
/* The same in vector registers from end to end (rt_points8.h, which the packet marcher inlines too):
 * the same float operations in the same order, lane by lane. */
#include "rt_points8.h"

static void points8(const model_shape_t *s, const float *restrict x, const float *restrict y,
                    const float *restrict z, float *restrict out)
{
	vf8 qx, qy, qz;
	memcpy(&qx, x, sizeof qx);
	memcpy(&qy, y, sizeof qy);
	memcpy(&qz, z, sizeof qz);
	vf8 sum = rt_points8v(s, qx, qy, qz);
	memcpy(out, &sum, sizeof sum);
}
#else
static void points8(const model_shape_t *s, const float *restrict x, const float *restrict y,
                    const float *restrict z, float *restrict out)
{
	const float tx = s->mf[3], ty = s->mf[7], tz = s->mf[11], c = (float)s->c.c0;
	float qx[8], qy[8], qz[8], sum[8];
	for (int k = 0; k < 8; k++) {
		qx[k] = x[k] + tx;
		qy[k] = y[k] + ty;
		qz[k] = z[k] + tz;
		sum[k] = 0;
	}
	for (size_t i = 0; i < s->nel; i++) {
		const float *a = s->el[i].pf, w = (float)s->el[i].w;
		const float ax = a[0], ay = a[1], az = a[2];
		if (s->el[i].kind == MODEL_POINT) {
			for (int k = 0; k < 8; k++) {
				float dx = qx[k] - ax, dy = qy[k] - ay, dz = qz[k] - az;
				sum[k] += w * sqrtf(dx * dx + dy * dy + dz * dz);
			}
			continue;
		}
		float d[8];
		segment8(a, qx, qy, qz, d);
		for (int k = 0; k < 8; k++)
			sum[k] += w * d[k];
	}
	for (int k = 0; k < 8; k++)
		out[k] = sum[k] - c;
}
#endif

/* Any shape (model_eval8 without its fast path; kept out of line so that the fast path does not
 * pay for this one's stack frame). */
static __attribute__((noinline)) void eval8_any(const model_shape_t *s, const float *x, const float *y,
                                                const float *z, float *out)
{
	v8 qx, qy, qz, d, sum;
	const float *m = s->mf;
	for (int k = 0; k < 8; k++) {
		qx[k] = m[0] * x[k] + m[1] * y[k] + m[2] * z[k] + m[3];
		qy[k] = m[4] * x[k] + m[5] * y[k] + m[6] * z[k] + m[7];
		qz[k] = m[8] * x[k] + m[9] * y[k] + m[10] * z[k] + m[11];
		sum[k] = 0;
	}
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		elem8(e, qx, qy, qz, x, y, z, d);
		if (e->wexpr) {   /* a weight that varies with the setup point */
			v8 wv;
			expr_eval8(e->wexpr, qx, qy, qz, wv);
			for (int k = 0; k < 8; k++)
				sum[k] += wv[k] * d[k];
			continue;
		}
		float w = (float)e->w;
		for (int k = 0; k < 8; k++)
			sum[k] += w * d[k];
	}
	switch (s->c.kind) {
	case MODEL_C_CONST: {
		float c = (float)s->c.c0;
		for (int k = 0; k < 8; k++)
			out[k] = sum[k] - c;
		break;
	}
	case MODEL_C_EXPR:
		expr_eval8(s->c.expr, qx, qy, qz, d);
		for (int k = 0; k < 8; k++)
			out[k] = sum[k] - d[k];
		break;
	default:
		for (int k = 0; k < 8; k++) {
			double p[3] = {x[k], y[k], z[k]}, q[3] = {qx[k], qy[k], qz[k]};
			out[k] = sum[k] - (float)model_param(s, p, q);
		}
	}
}

void model_eval8(const model_shape_t *s, const float *x, const float *y, const float *z, float *out)
{
	if (s->fast_points)
		points8(s, x, y, z, out);
	else
		eval8_any(s, x, y, z, out);
}
