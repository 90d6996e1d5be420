/* rt_march.c: marching 8 rays at once against one shape (certified sphere tracing, regula falsi, bracketing fallback). */
#include "rt_int.h"

#include <math.h>
#include <string.h>

enum { M_MARCH = 0, M_BRACKET = 1, M_DONE = 2 };

static float minf(float a, float b) { return a < b ? a : b; }
static float maxf(float a, float b) { return a > b ? a : b; }

/* Clip the 8 rays to the object's region (box and, if bounded, sphere):
 * [a, b] per lane, empty when a > b; on[k] = 1 when the entry a lies on the
 * bounding sphere. Branch-free so that it vectorises. */
static void clip8(const model_shape_t *s, const rt_packet_t *pk, float *restrict a, float *restrict b,
                  float *restrict on)
{
	const float bx0 = (float)s->box[0], by0 = (float)s->box[1], bz0 = (float)s->box[2];
	const float bx1 = (float)s->box[3], by1 = (float)s->box[4], bz1 = (float)s->box[5];
	const float cx = (float)s->centre[0], cy = (float)s->centre[1], cz = (float)s->centre[2];
	const float r2 = s->bounded ? (float)(s->radius * s->radius) : 0.0f, sph = s->bounded ? 1.0f : 0.0f;
	for (int k = 0; k < RT_LANES; k++) {
		float lo = pk->tmin[k], hi = pk->tmax[k];
		float ix = 1.0f / pk->dx[k], iy = 1.0f / pk->dy[k], iz = 1.0f / pk->dz[k];
		float u0 = (bx0 - pk->ox[k]) * ix, u1 = (bx1 - pk->ox[k]) * ix;
		float v0 = (by0 - pk->oy[k]) * iy, v1 = (by1 - pk->oy[k]) * iy;
		float w0 = (bz0 - pk->oz[k]) * iz, w1 = (bz1 - pk->oz[k]) * iz;
		lo = maxf(lo, minf(u0, u1));
		hi = minf(hi, maxf(u0, u1));
		lo = maxf(lo, minf(v0, v1));
		hi = minf(hi, maxf(v0, v1));
		lo = maxf(lo, minf(w0, w1));
		hi = minf(hi, maxf(w0, w1));
		float ox = pk->ox[k] - cx, oy = pk->oy[k] - cy, oz = pk->oz[k] - cz;
		float bb = ox * pk->dx[k] + oy * pk->dy[k] + oz * pk->dz[k];
		float disc = bb * bb - (ox * ox + oy * oy + oz * oz - r2);
		float q = sqrtf(maxf(disc, 0.0f));
		float slo = disc >= 0.0f ? -bb - q : INFINITY, shi = disc >= 0.0f ? -bb + q : -INFINITY;
		on[k] = sph > 0 && slo >= lo ? 1.0f : 0.0f;
		lo = sph > 0 ? maxf(lo, slo) : lo;
		hi = sph > 0 ? minf(hi, shi) : hi;
		/* NaN (a zero direction component with the origin on a slab face) counts as empty */
		a[k] = lo == lo ? lo : INFINITY;
		b[k] = hi == hi ? hi : -INFINITY;
	}
}

/* The per-lane update after one evaluation: branch-free selects so that gcc
 * can vectorise the 8 lanes. */
static void update8(float *restrict mode, float *restrict t, float *restrict f, float *restrict s,
                    float *restrict lo, float *restrict flo, float *restrict hi, float *restrict fhi,
                    float *restrict side, float *restrict hit, const float *restrict u,
                    const float *restrict val, const float *restrict fa, const float *restrict fb,
                    const float *restrict t1, const float *restrict smin, float L, float invL,
                    float nolip, float acc, float step, float shadow, float strict)
{
	for (int k = 0; k < RT_LANES; k++) {
		float uk = u[k], v = val[k];
		float fp = fa[k] + fb[k] * uk, emin = 0.05f * fp;
		/* the tolerance never goes below what float positions can resolve */
		float eps = maxf(acc * fp, 2e-6f * (fabsf(uk) + 1.0f));
		v = v == v ? v : emin * (nolip > 0 ? 1.0f : L);
		float inm = mode[k] == M_MARCH ? 1.0f : 0.0f, inb = mode[k] == M_BRACKET ? 1.0f : 0.0f;
		/* march */
		float beyond = uk >= t1[k] ? 1.0f : 0.0f;  /* the sample is at the region's exit */
		float cross_raw = v <= 0.0f ? 1.0f : 0.0f;
		float c1 = (f[k] + v) * invL >= s[k] * 0.999999f ? 1.0f : 0.0f;
		float c2 = s[k] <= emin * 1.0001f ? 1.0f : 0.0f;
		float cert = maxf(nolip, maxf(c1, c2));
		/* strict: a sign change counts only when the ball outside at t and the ball inside at
		 * the sample overlap (one crossing between them); a long proposal that lands inside
		 * past a thin gap is rejected like an uncertified step */
		float c3 = (f[k] - v) * invL >= s[k] * 0.999999f - emin ? 1.0f : 0.0f;
		float cross_ok = maxf(1.0f - strict, maxf(shadow, maxf(nolip, maxf(c3, c2))));
		float cross = cross_raw * cross_ok;
		/* slope m = (v - f)/s; secant step -1.05 v/m when falling, the largest step two
		 * overlapping balls allow, 2 * 0.9 v/(L - m), when rising: one division */
		float dv = v - f[k];
		float den = dv < 0.0f ? -dv * (1.0f / 1.05f) : (L * s[k] - dv) * (1.0f / 1.8f);
		float safe = v * invL;
		float sg = den > 0.0f ? v * s[k] / den : safe;
		/* a distance estimate is not Lipschitz: its slope says little about the next ball, so
		 * a rising ray grows its step by at most 1.5x */
		float capk = strict > 0 ? 1.5f : 16.0f;
		sg = maxf(maxf(safe, minf(sg, capk * safe)), emin);
		sg = nolip > 0 ? maxf(step * fp, smin[k]) : sg;
		float rej = maxf(f[k] * invL, emin);
		float m_brk = inm * cross * (1.0f - shadow);   /* march -> bracket */
		float m_shd = inm * cross * shadow;            /* shadow ray blocked */
		float m_out = inm * (1.0f - cross_raw) * beyond * cert;          /* certified to the exit: a miss */
		float m_acc = inm * (1.0f - cross_raw) * (1.0f - beyond) * cert; /* step accepted */
		float m_rej = inm * (1.0f - cross) * (1.0f - (1.0f - cross_raw) * cert);
		/* bracket */
		float cv1 = fabsf(v) < eps * (nolip > 0 ? 1.0f : L) ? 1.0f : 0.0f;
		float cv2 = hi[k] - lo[k] < eps ? 1.0f : 0.0f;
		float conv = maxf(cv1, cv2);
		float pos = v > 0.0f ? 1.0f : 0.0f;
		float b_hit = inb * conv;
		float b_lo = inb * (1.0f - conv) * pos, b_hi = inb * (1.0f - conv) * (1.0f - pos);
		/* new state */
		float nlo = m_brk > 0 ? t[k] : (b_lo > 0 ? uk : lo[k]);
		float nflo = m_brk > 0 ? f[k] : (b_lo > 0 ? v : (b_hi > 0 && side[k] < 0 ? 0.5f * flo[k] : flo[k]));
		float nhi = m_brk > 0 ? uk : (b_hi > 0 ? uk : hi[k]);
		float nfhi = m_brk > 0 ? v : (b_hi > 0 ? v : (b_lo > 0 && side[k] > 0 ? 0.5f * fhi[k] : fhi[k]));
		side[k] = m_brk > 0 ? 0.0f : (b_lo > 0 ? 1.0f : (b_hi > 0 ? -1.0f : side[k]));
		lo[k] = nlo;
		flo[k] = nflo;
		hi[k] = nhi;
		fhi[k] = nfhi;
		float narrow = inb * (1.0f - b_hit) * (nhi - nlo < eps ? 1.0f : 0.0f);
		hit[k] = (m_shd > 0 || b_hit > 0) ? uk : (narrow > 0 ? 0.5f * (nlo + nhi) : hit[k]);
		t[k] = m_acc > 0 ? uk : t[k];
		f[k] = m_acc > 0 ? v : f[k];
		s[k] = m_acc > 0 ? sg : (m_rej > 0 ? rej : s[k]);
		float done = m_shd + m_out + b_hit + narrow;
		mode[k] = done > 0 ? (float)M_DONE : (m_brk > 0 ? (float)M_BRACKET : mode[k]);
	}
}

void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes)
{
	float mode[RT_LANES], t[RT_LANES], f[RT_LANES], st[RT_LANES], lo[RT_LANES], flo[RT_LANES], hi[RT_LANES], fhi[RT_LANES], side[RT_LANES], u[RT_LANES], t1[RT_LANES];
	float x[RT_LANES], y[RT_LANES], z[RT_LANES], val[RT_LANES];
	float L = (float)rt_bound(s), invL = L > 0 ? 1.0f / L : 0.0f, nolip = L > 0 ? 0.0f : 1.0f;
	int n = 0;
	for (int k = 0; k < RT_LANES; k++)
		n += pk->active[k] && pk->tmin[k] < INFINITY;
	if (!n) {   /* nothing to march (e.g. a cone found the object out of reach) */
		for (int k = 0; k < RT_LANES; k++)
			pk->thit[k] = INFINITY;
		return;
	}
	n = 0;
	float ca[RT_LANES], cb[RT_LANES], con[RT_LANES], sgn[RT_LANES], smin[RT_LANES];
	for (int k = 0; k < RT_LANES; k++)
		sgn[k] = 1;
	clip8(s, pk, ca, cb, con);
	for (int k = 0; k < RT_LANES; k++) {
		pk->thit[k] = INFINITY;
		pk->side[k] = 0;
		mode[k] = M_DONE;
		t[k] = f[k] = st[k] = lo[k] = flo[k] = hi[k] = fhi[k] = side[k] = 0;
		t1[k] = 0;
		u[k] = 0;
		smin[k] = 0;
		if (!pk->active[k])
			continue;
		if (!(ca[k] <= cb[k]))
			continue;
		mode[k] = M_MARCH;
		u[k] = ca[k];
		t1[k] = cb[k];
		n++;
	}
	if (!n)
		return;
	/* first sample at the region entry */
	for (int k = 0; k < RT_LANES; k++) {
		x[k] = pk->ox[k] + u[k] * pk->dx[k];
		y[k] = pk->oy[k] + u[k] * pk->dy[k];
		z[k] = pk->oz[k] + u[k] * pk->dz[k];
		if (s->de && mode[k] == M_DONE)
			x[k] = NAN;
	}
	for (int g = 0; g < RT_LANES; g += 8)
		rt_eval8(s, x + g, y + g, z + g, val + g);
	*evals += (uint64_t)n;
	*lanes += RT_LANES;
	for (int k = 0; k < RT_LANES; k++) {
		if (mode[k] != M_MARCH)
			continue;
		float fp = pk->fa[k] + pk->fb[k] * u[k], emin = 0.05f * fp, v = val[k];
		/* a ray that enters the region inside the solid looks for the surface as the
		 * sign change from negative to positive: march on -f. One that enters it on
		 * the surface (within the hit tolerance), or inside the solid through the
		 * bounding sphere (which holds the whole solid, so the two touch there: when
		 * the sphere is tight, as for a sphere, float rounding of the entry near the
		 * rim lands inside), hits there. */
		float eps = maxf(pk->acc * fp, 2e-6f * (fabsf(u[k]) + 1.0f));
		int touch = v < 0 && con[k] > 0;
		sgn[k] = v < 0 ? -1.0f : 1.0f;
		v *= sgn[k];
		if (v == v && (touch || v <= eps * (L > 0 ? L : 1.0f))) {
			pk->thit[k] = u[k];
			pk->side[k] = touch ? 1.0f : 0.0f;   /* touching the bounding sphere: entered from outside */
			mode[k] = M_DONE;
			n--;
			continue;
		}
		if (v != v)
			v = emin * (L > 0 ? L : 1);
		t[k] = u[k];
		f[k] = v;
		/* bracketing: at most about 1000 steps through the region, whatever its depth */
		smin[k] = (t1[k] - u[k]) * 1e-3f;
		st[k] = L > 0 ? maxf(v * invL, emin) : maxf(pk->step * fp, smin[k]);
	}
	int iter = 0;
	for (int k = 0; k < RT_LANES; k++)
		if (mode[k] == M_MARCH)
			pk->side[k] = sgn[k];
	while (n > 0 && iter++ < 4000) {
		for (int k = 0; k < RT_LANES; k++) {
			float rf = lo[k] + (hi[k] - lo[k]) * flo[k] / (flo[k] - fhi[k]);
			rf = (rf > lo[k] && rf < hi[k]) ? rf : 0.5f * (lo[k] + hi[k]);
			u[k] = mode[k] == M_BRACKET ? rf : minf(t[k] + st[k], t1[k]);  /* never past the exit */
			x[k] = pk->ox[k] + u[k] * pk->dx[k];
			y[k] = pk->oy[k] + u[k] * pk->dy[k];
			z[k] = pk->oz[k] + u[k] * pk->dz[k];
			if (s->de && mode[k] == M_DONE)
				x[k] = NAN;   /* model_de8 skips the lane (its value is not used) */
		}
		/* a group of 8 lanes whose rays are all done is not evaluated */
		for (int g = 0; g < RT_LANES; g += 8) {
			int busy = 0;
			for (int k = g; k < g + 8; k++)
				busy |= mode[k] != M_DONE;
			if (busy) {
				rt_eval8(s, x + g, y + g, z + g, val + g);
				*lanes += 8;
			}
		}
		*evals += (uint64_t)n;
		for (int k = 0; k < RT_LANES; k++)
			val[k] *= sgn[k];
		update8(mode, t, f, st, lo, flo, hi, fhi, side, pk->thit, u, val, pk->fa, pk->fb, t1, smin,
		        L, invL, nolip, pk->acc, pk->step, shadow ? 1.0f : 0.0f, s->de ? 1.0f : 0.0f);
		n = 0;
		for (int k = 0; k < RT_LANES; k++)
			n += mode[k] != M_DONE;
	}
}
