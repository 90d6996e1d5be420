/* rt_march.c: marching 8 rays at once against one shape (certified sphere tracing, regula falsi, bracketing fallback). */
#include "rt_int.h"

#include <math.h>
#include <string.h>

enum { S_IDLE, S_INIT, S_MARCH, S_BRACKET };

/* Clip the ray to the object's region: box and (if bounded) sphere. */
static int clip(const model_shape_t *s, const double *o, const double *d, double *t0, double *t1)
{
	double a = *t0, b = *t1;
	for (int i = 0; i < 3; i++) {
		double lo = s->box[i], hi = s->box[3 + i];
		if (d[i] == 0) {
			if (o[i] < lo || o[i] > hi)
				return 0;
			continue;
		}
		double u = (lo - o[i]) / d[i], v = (hi - o[i]) / d[i];
		if (u > v) {
			double w = u;
			u = v;
			v = w;
		}
		a = fmax(a, u);
		b = fmin(b, v);
	}
	if (s->bounded) {
		double oc[3] = {o[0] - s->centre[0], o[1] - s->centre[1], o[2] - s->centre[2]};
		double bb = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
		double cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - s->radius * s->radius;
		double disc = bb * bb - cc;
		if (disc < 0)
			return 0;
		double q = sqrt(disc);
		a = fmax(a, -bb - q);
		b = fmin(b, -bb + q);
	}
	*t0 = a;
	*t1 = b;
	return a <= b;
}

void rt_march8(const model_shape_t *s, rt_packet_t *pk, int shadow, uint64_t *evals, uint64_t *lanes)
{
	int state[8];
	double t[8], f[8], sstep[8], tlo[8], flo[8], thi[8], fhi[8], t0[8], t1[8], tt[8];
	int side[8], iters[8];
	double L = s->has_lip ? s->lip : 0;
	int any = 0;
	for (int k = 0; k < 8; k++) {
		pk->thit[k] = INFINITY;
		state[k] = S_IDLE;
		if (!pk->active[k])
			continue;
		t0[k] = pk->tmin[k];
		t1[k] = pk->tmax[k];
		if (!clip(s, pk->o[k], pk->d[k], &t0[k], &t1[k]))
			continue;
		state[k] = S_INIT;
		iters[k] = 0;
		side[k] = 0;
		any = 1;
	}
	float x[8], y[8], z[8], val[8];
	while (any) {
		int n = 0;
		for (int k = 0; k < 8; k++) {
			double u;
			switch (state[k]) {
			case S_INIT: u = t0[k]; break;
			case S_MARCH: u = t[k] + sstep[k]; break;
			case S_BRACKET:
				u = tlo[k] + (thi[k] - tlo[k]) * flo[k] / (flo[k] - fhi[k]);
				if (!(u > tlo[k] && u < thi[k]))
					u = 0.5 * (tlo[k] + thi[k]);
				break;
			default: u = 0; break;
			}
			tt[k] = u;
			if (state[k] != S_IDLE)
				n++;
			const double *o = pk->o[k], *d = pk->d[k];
			if (state[k] == S_IDLE) {
				x[k] = (float)o[0];
				y[k] = (float)o[1];
				z[k] = (float)o[2];
			} else {
				x[k] = (float)(o[0] + u * d[0]);
				y[k] = (float)(o[1] + u * d[1]);
				z[k] = (float)(o[2] + u * d[2]);
			}
		}
		model_eval8(s, x, y, z, val);
		*evals += (uint64_t)n;
		*lanes += 8;
		any = 0;
		for (int k = 0; k < 8; k++) {
			if (state[k] == S_IDLE)
				continue;
			double v = val[k], u = tt[k];
			double fp = pk->fa[k] + pk->fb[k] * u;
			double eps = pk->acc * fp, emin = 0.05 * fp;
			if (v != v)
				v = L > 0 ? emin * L : 1;  /* NaN: no information, move on by the minimum step */
			if (++iters[k] > 4000) {
				state[k] = S_IDLE;
				continue;
			}
			if (state[k] == S_INIT) {
				if (v <= 0) {
					pk->thit[k] = u;
					state[k] = S_IDLE;
					continue;
				}
				t[k] = u;
				f[k] = v;
				state[k] = S_MARCH;
				sstep[k] = L > 0 ? fmax(v / L, emin) : pk->step * fp;
			} else if (state[k] == S_MARCH) {
				if (v <= 0) {
					if (shadow) {
						pk->thit[k] = u;
						state[k] = S_IDLE;
						continue;
					}
					tlo[k] = t[k];
					flo[k] = f[k];
					thi[k] = u;
					fhi[k] = v;
					state[k] = S_BRACKET;
				} else if (L <= 0 || (f[k] + v) / L >= sstep[k] * (1 - 1e-9) || sstep[k] <= emin * 1.0001) {
					double m = (v - f[k]) / sstep[k];
					t[k] = u;
					f[k] = v;
					if (u > t1[k]) {
						state[k] = S_IDLE;
						continue;
					}
					if (L <= 0) {
						sstep[k] = pk->step * fp;
					} else {
						double safe = v / L, sg;
						if (m < 0)
							sg = 1.05 * v / -m;
						else if (m < L)
							sg = 0.9 * 2 * v / (L - m);
						else
							sg = safe;
						sstep[k] = fmax(fmax(safe, fmin(sg, 16 * safe)), emin);
					}
				} else {
					sstep[k] = fmax(f[k] / L, emin);
				}
			} else {
				if (fabs(v) < eps * (L > 0 ? L : 1) || thi[k] - tlo[k] < eps) {
					pk->thit[k] = u;
					state[k] = S_IDLE;
					continue;
				}
				if (v > 0) {
					tlo[k] = u;
					flo[k] = v;
					if (side[k] == 1)
						fhi[k] *= 0.5;
					side[k] = 1;
				} else {
					thi[k] = u;
					fhi[k] = v;
					if (side[k] == -1)
						flo[k] *= 0.5;
					side[k] = -1;
				}
				if (thi[k] - tlo[k] < eps) {
					pk->thit[k] = 0.5 * (tlo[k] + thi[k]);
					state[k] = S_IDLE;
					continue;
				}
			}
			any = 1;
		}
	}
}
