/* rt.c: the ray-tracing renderer: packets of pixels, shading with shadows, adaptive supersampling, threads. */
#include "rt.h"
#include "rt_int.h"

#include <math.h>
#include <pthread.h>
#ifdef __AVX__
#include <immintrin.h>
#include "rt_points8.h"
#endif
#include <stddef.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct {
	const rt_params_t *p;
	const unsigned char *dbl; /* per object: 1 = marched in double precision (rt_march1) */
	meta_rgb_t *img;
	const meta_rgb_t *src;   /* supersampling pass: the first-pass picture */
	int pass;
	atomic_uint next_row;
	atomic_uint rows_done;
	atomic_uint workers_done;
} job_t;

typedef struct {
	job_t *job;
	rt_stats_t st;
} worker_t;

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* One channel 0..1 to 0..255, rounded; branch-free (x * 255 + 0.5 lies in [0.5, 255.5], where the
 * signed conversion truncates as the unsigned one did; NaN gives 0). */
static inline unsigned to_byte(double c)
{
	double x = c > 0 ? c : 0;
	x = x < 1 ? x : 1;
	return (unsigned)(int)(x * 255 + 0.5);
}

static inline meta_rgb_t to_rgb(const double *c)
{
	return (meta_rgb_t)(to_byte(c[0]) << 16 | to_byte(c[1]) << 8 | to_byte(c[2]));
}

void rt_grad(const model_shape_t *s, const double p[3], double g[3])
{
	if (!s->fast_points) {
		model_grad(s, p, g);
		return;
	}
	/* model_grad: q = minv p (apply), the sum of w (q - near) / d over the elements whose
	 * distance d is positive (model_elem_nearest for a point and a segment), then
	 * g = minv^T gs + ga with ga = 0 (nothing but points and segments) */
	const double *m = s->minv;
	double q[3], gs[3] = {0, 0, 0};
	for (int i = 0; i < 3; i++)
		q[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		const double *a = e->p;
		double c[3], d;
		if (e->kind == MODEL_POINT) {
			double v[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
			d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
			memcpy(c, a, sizeof c);
		} else {   /* MODEL_SEGMENT: seg_nearest */
			const double *b = a + 3;
			double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
			double pa[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
			double l2 = ba[0] * ba[0] + ba[1] * ba[1] + ba[2] * ba[2];
			double h = l2 > 0 ? (pa[0] * ba[0] + pa[1] * ba[1] + pa[2] * ba[2]) / l2 : 0;
			h = h < 0 ? 0 : h > 1 ? 1 : h;
			for (int j = 0; j < 3; j++)
				c[j] = a[j] + h * ba[j];
			double v[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
			d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
		}
		if (d > 0)
			for (int j = 0; j < 3; j++)
				gs[j] += e->w * (q[j] - c[j]) / d;
	}
	for (int j = 0; j < 3; j++)
		g[j] = m[j] * gs[0] + m[4 + j] * gs[1] + m[8 + j] * gs[2] + 0.0;
}

#ifdef __AVX__
typedef double vd4 __attribute__((vector_size(32)));
typedef long long vl4 __attribute__((vector_size(32)));

/* m ? a : b lane by lane (m all ones or zero) */
static inline vd4 dsel(vl4 m, vd4 a, vd4 b) { return (vd4)(((vl4)a & m) | ((vl4)b & ~m)); }
static inline vd4 dsplat(double x) { return (vd4){x, x, x, x}; }
static inline vd4 dsqrt(vd4 a) { return (vd4)_mm256_sqrt_pd((__m256d)a); }

/* rt_grad at 4 points at once (p: x, y, z of each) for a fast_points shape: rt_grad's double
 * operations lane by lane, in the same order (so the same bits). */
static void grad4(const model_shape_t *s, const double p[3][4], double g[3][4])
{
	const double *m = s->minv;
	vd4 p0, p1, p2, q[3], gs[3] = {dsplat(0), dsplat(0), dsplat(0)};
	memcpy(&p0, p[0], sizeof p0);
	memcpy(&p1, p[1], sizeof p1);
	memcpy(&p2, p[2], sizeof p2);
	for (int i = 0; i < 3; i++)
		q[i] = m[i * 4] * p0 + m[i * 4 + 1] * p1 + m[i * 4 + 2] * p2 + m[i * 4 + 3];
	for (size_t i = 0; i < s->nel; i++) {
		const model_elem_t *e = &s->el[i];
		const double *a = e->p;
		vd4 c[3], d;
		if (e->kind == MODEL_POINT) {
			vd4 v[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
			d = dsqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
			for (int j = 0; j < 3; j++)
				c[j] = dsplat(a[j]);
		} else {
			const double *b = a + 3;
			double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
			vd4 pa[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
			double l2 = ba[0] * ba[0] + ba[1] * ba[1] + ba[2] * ba[2];
			vd4 h = l2 > 0 ? (pa[0] * ba[0] + pa[1] * ba[1] + pa[2] * ba[2]) / l2 : dsplat(0);
			h = dsel(h < 0, dsplat(0), dsel(h > 1, dsplat(1), h));
			for (int j = 0; j < 3; j++)
				c[j] = a[j] + h * ba[j];
			vd4 v[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
			d = dsqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
		}
		vl4 pos = d > 0;
		for (int j = 0; j < 3; j++)
			gs[j] = dsel(pos, gs[j] + e->w * (q[j] - c[j]) / d, gs[j]);
	}
	for (int j = 0; j < 3; j++) {
		vd4 r = m[j] * gs[0] + m[4 + j] * gs[1] + m[8 + j] * gs[2] + 0.0;
		memcpy(g[j], &r, sizeof r);
	}
}
#endif

/* The gradients N[k] at the hit points P[k] of the lanes in mask (obj[k]: the object hit). Four
 * at a time when they all hit one point-and-segment shape (and the processor has AVX), else one
 * by one; the same bits either way. */
static void normals(const rt_params_t *p, uint32_t mask, const int *obj, double P[][3], double N[][3])
{
#ifdef __AVX__
	int o = -1, same = 1, idx[RT_LANES], n = 0;
	for (int k = 0; k < RT_LANES; k++)
		if (mask >> k & 1) {
			same &= o < 0 || obj[k] == o;
			o = obj[k];
			idx[n++] = k;
		}
	const model_shape_t *s = p->objects[o].shape;
	if (same && s->fast_points) {
		for (int b = 0; b < n; b += 4) {
			double pp[3][4], g[3][4];
			for (int l = 0; l < 4; l++)   /* a short batch repeats its last point */
				for (int i = 0; i < 3; i++)
					pp[i][l] = P[idx[b + l < n ? b + l : n - 1]][i];
			grad4(s, pp, g);
			for (int l = 0; l < 4 && b + l < n; l++)
				for (int i = 0; i < 3; i++)
					N[idx[b + l]][i] = g[i][l];
		}
		return;
	}
#endif
	for (int k = 0; k < RT_LANES; k++)
		if (mask >> k & 1)
			rt_grad(p->objects[obj[k]].shape, P[k], N[k]);
}

/* Reference mode: polish a hit point P found in float with Newton steps on the
 * double-precision f along the ray (direction -V), staying within two pixel
 * footprints of the float answer. */
static void refine_hit(const model_shape_t *s, double *P, const double *V, double fp, rt_stats_t *st)
{
	double Q[3] = {P[0], P[1], P[2]}, moved = 0;
	for (int it = 0; it < 6; it++) {
		double f = model_eval(s, Q), g[3];
		st->primary_evals++;
		if (fabs(f) < 1e-13)
			break;
		model_grad(s, Q, g);
		st->primary_evals++;
		double slope = -(g[0] * V[0] + g[1] * V[1] + g[2] * V[2]);
		if (!(fabs(slope) > 1e-12))
			return;
		double dt = -f / slope;
		moved += dt;
		if (!(fabs(moved) <= 2 * fp))
			return;   /* not converging near the float hit: keep it */
		for (int i = 0; i < 3; i++)
			Q[i] -= dt * V[i];
	}
	memcpy(P, Q, sizeof Q);
}

_Static_assert(RT_LANES <= 32, "trace8's hit mask holds a packet");

/* Trace up to RT_LANES rays (active[k]) and shade them into col; returns the mask of the lanes
 * that hit something (the others are the background colour). */
static uint32_t trace8(const rt_params_t *p, const unsigned char *dbl, rt_packet_t *pk, double col[RT_LANES][3],
                   rt_stats_t *st, const float *tstart, size_t stride)
{
	double best[RT_LANES];
	int obj[RT_LANES], side[RT_LANES];
	uint64_t lanes = 0;
	for (int k = 0; k < RT_LANES; k++) {
		best[k] = INFINITY;
		obj[k] = -1;
		for (int i = 0; i < 3; i++)
			col[k][i] = p->background[i];
	}
	for (size_t i = 0; i < p->nobjects; i++) {
		uint64_t ev = 0;
		if (dbl[i]) {
			for (int k = 0; k < RT_LANES; k++) {
				if (!pk->active[k])
					continue;
				double o[3] = {pk->o[0][k], pk->o[1][k], pk->o[2][k]}, d[3] = {pk->d[0][k], pk->d[1][k], pk->d[2][k]};
				int sd;
				double th = rt_march1(p->objects[i].shape, o, d, 0, INFINITY, pk->fa[k], pk->fb[k], pk->acc, pk->step, 0, &sd, &ev);
				if (th < best[k]) {
					best[k] = th;
					obj[k] = (int)i;
					side[k] = sd;
				}
			}
			st->primary_evals += ev;
			continue;
		}
		if (tstart) {
			if (tstart[i * stride] == INFINITY)
				continue;   /* the packet's cone misses the object: no lane can hit it */
			for (int k = 0; k < RT_LANES; k++)
				pk->tmin[k] = tstart[i * stride];
		}
		rt_march8(p->objects[i].shape, pk, 0, &ev, &lanes);
		st->primary_evals += ev;
		for (int k = 0; k < RT_LANES; k++)
			if (pk->active[k] && pk->thit[k] < best[k]) {
				best[k] = pk->thit[k];
				obj[k] = (int)i;
				side[k] = (int)pk->side[k];
			}
	}
	uint32_t mask = 0;
	for (int k = 0; k < RT_LANES; k++)
		mask |= (uint32_t)(pk->active[k] && obj[k] >= 0) << k;
	if (!mask) {   /* all background: nothing to shade */
		st->lane_evals += lanes;
		return 0;
	}
	double P[RT_LANES][3], N[RT_LANES][3], V[RT_LANES][3];
	const float *pko[3] = {pk->ox, pk->oy, pk->oz}, *pkd[3] = {pk->dx, pk->dy, pk->dz};
	int hit[RT_LANES];
	for (int k = 0; k < RT_LANES; k++) {
		hit[k] = mask >> k & 1;
		if (!hit[k])
			continue;
		st->hits++;
		const rt_object_t *ob = &p->objects[obj[k]];
		for (int i = 0; i < 3; i++) {
			P[k][i] = dbl[obj[k]] ? pk->o[i][k] + best[k] * pk->d[i][k] : pko[i][k] + best[k] * pkd[i][k];
			V[k][i] = dbl[obj[k]] ? -pk->d[i][k] : -pkd[i][k];
		}
		if (p->refine && ob->shape->has_lip)
			refine_hit(ob->shape, P[k], V[k], (pk->fa[k] + pk->fb[k] * best[k]), st);
	}
	normals(p, mask, obj, P, N);
	for (int k = 0; k < RT_LANES; k++) {
		if (!hit[k])
			continue;
		const rt_object_t *ob = &p->objects[obj[k]];
		st->normal_evals++;
		double l = sqrt(dot(N[k], N[k]));
		if (l > 0)
			for (int i = 0; i < 3; i++)
				N[k][i] /= l;
		else
			memcpy(N[k], V[k], sizeof N[k]);
		/* the normal faces the side the ray came from: grad(side * f) points back along the
		 * ray by construction, also at the rim where N.V is about 0 and its computed sign is
		 * noise; only a ray that started on the surface (side 0) uses the two-sided rule */
		if (side[k] ? side[k] < 0 : dot(N[k], V[k]) < 0)
			for (int i = 0; i < 3; i++)
				N[k][i] = -N[k][i];
		double a = ob->shading == RT_CONSTANT ? 1 : ob->ambient;
		for (int i = 0; i < 3; i++)
			col[k][i] = ob->colour[i] * a;
	}
	for (size_t li = 0; li < p->nlights; li++) {
		const rt_light_t *lt = &p->lights[li];
		double Ld[RT_LANES][3], dist[RT_LANES];
		rt_packet_t sp;
		/* the float lanes only: the double rays are read only for lanes set below */
		memset(&sp, 0, offsetof(rt_packet_t, o));
		sp.acc = pk->acc;
		sp.step = pk->step;
		int need = 0;
		for (int k = 0; k < RT_LANES; k++) {
			if (!hit[k] || p->objects[obj[k]].shading == RT_CONSTANT)
				continue;
			for (int i = 0; i < 3; i++)
				Ld[k][i] = lt->directional ? lt->pos[i] : lt->pos[i] - P[k][i];
			dist[k] = sqrt(dot(Ld[k], Ld[k]));
			if (!(dist[k] > 0))
				continue;
			for (int i = 0; i < 3; i++)
				Ld[k][i] /= dist[k];
			if (lt->directional)
				dist[k] = INFINITY;
			if (dot(N[k], Ld[k]) <= 0)
				continue;
			sp.active[k] = 1;
			need = 1;
			double fp = pk->fa[k] + pk->fb[k] * best[k];
			for (int i = 0; i < 3; i++) {
				sp.o[i][k] = P[k][i] + 0.5 * fp * N[k][i];
				sp.d[i][k] = Ld[k][i];
			}
			sp.ox[k] = (float)sp.o[0][k];
			sp.oy[k] = (float)sp.o[1][k];
			sp.oz[k] = (float)sp.o[2][k];
			sp.dx[k] = (float)Ld[k][0];
			sp.dy[k] = (float)Ld[k][1];
			sp.dz[k] = (float)Ld[k][2];
			sp.tmin[k] = (float)(2 * fp);  /* skip 2 pixel footprints: the ray starts at the surface */
			sp.tmax[k] = (float)dist[k];
			sp.fa[k] = (float)fp;
			sp.fb[k] = 0;
		}
		if (need && lt->shadows) {
			for (size_t i = 0; i < p->nobjects; i++) {
				uint64_t ev = 0;
				if (dbl[i]) {
					for (int k = 0; k < RT_LANES; k++) {
						if (!sp.active[k])
							continue;
						double o[3] = {sp.o[0][k], sp.o[1][k], sp.o[2][k]}, d[3] = {sp.d[0][k], sp.d[1][k], sp.d[2][k]};
						int sd;
						if (rt_march1(p->objects[i].shape, o, d, sp.tmin[k], dist[k], sp.fa[k], 0, sp.acc, sp.step, 1, &sd, &ev) < INFINITY)
							sp.active[k] = 0;
					}
					st->shadow_evals += ev;
					continue;
				}
				rt_march8(p->objects[i].shape, &sp, 1, &ev, &lanes);
				st->shadow_evals += ev;
				for (int k = 0; k < RT_LANES; k++)
					if (sp.active[k] && sp.thit[k] < INFINITY)
						sp.active[k] = 0;
			}
		}
		for (int k = 0; k < RT_LANES; k++) {
			if (!sp.active[k])
				continue;
			const rt_object_t *ob = &p->objects[obj[k]];
			double nl = dot(N[k], Ld[k]);
			double spec = 0;
			if (ob->shading == RT_PHONG) {
				double r[3];
				for (int i = 0; i < 3; i++)
					r[i] = 2 * nl * N[k][i] - Ld[k][i];
				double rv = dot(r, V[k]);
				if (rv > 0)
					spec = ob->specular * pow(rv, ob->shininess);
			}
			for (int i = 0; i < 3; i++)
				col[k][i] += lt->colour[i] * (ob->colour[i] * ob->diffuse * nl + spec);
		}
	}
	st->lane_evals += lanes;
	return mask;
}

static void setup_ray(const rt_params_t *p, rt_packet_t *pk, int k, double px, double py)
{
	double o[3], d[3];
	cam_ray(&p->cam, px, py, o, d);
	for (int i = 0; i < 3; i++) {
		pk->o[i][k] = o[i];
		pk->d[i][k] = d[i];
	}
	pk->ox[k] = (float)o[0];
	pk->oy[k] = (float)o[1];
	pk->oz[k] = (float)o[2];
	pk->dx[k] = (float)d[0];
	pk->dy[k] = (float)d[1];
	pk->dz[k] = (float)d[2];
	pk->active[k] = 1;
	pk->tmin[k] = 0;
	pk->tmax[k] = INFINITY;
	if (p->cam.projection == CAM_ORTHOGRAPHIC) {
		pk->fa[k] = (float)cam_footprint(&p->cam, 1);
		pk->fb[k] = 0;
	} else {
		pk->fa[k] = 0;
		pk->fb[k] = (float)cam_footprint(&p->cam, 1);
	}
}

/* Rays through the n <= RT_LANES viewport points (px0 + k * dpx, py), in float lanes. */
static void setup_rays8(const rt_params_t *p, rt_packet_t *pk, double px0, double dpx, double py, int n)
{
	const cam_t *c = &p->cam;
	float sx = (float)(c->horiz / c->nxpix), x0 = (float)(px0 / c->nxpix - 0.5) * (float)c->horiz;
	float y = (float)((py / c->nypix - 0.5) * c->vert), dx = (float)dpx * sx;
	float fw[3], rt[3], up[3], eye[3];
	for (int i = 0; i < 3; i++) {
		fw[i] = (float)c->fwd[i];
		rt[i] = (float)c->right[i];
		up[i] = (float)c->upv[i];
		eye[i] = (float)c->eye[i];
	}
	float fp = (float)cam_footprint(c, 1);
	/* one loop per projection, without selects in them, so that gcc vectorises either */
	if (c->projection == CAM_ORTHOGRAPHIC) {
		for (int k = 0; k < RT_LANES; k++) {
			float x = x0 + dx * (float)k;
			float ax = x * rt[0] + y * up[0], ay = x * rt[1] + y * up[1], az = x * rt[2] + y * up[2];
			pk->ox[k] = eye[0] + ax;
			pk->oy[k] = eye[1] + ay;
			pk->oz[k] = eye[2] + az;
			pk->dx[k] = fw[0];
			pk->dy[k] = fw[1];
			pk->dz[k] = fw[2];
			pk->fa[k] = fp;
			pk->fb[k] = 0.0f;
		}
	} else {
		for (int k = 0; k < RT_LANES; k++) {
			float x = x0 + dx * (float)k;
			float ax = x * rt[0] + y * up[0], ay = x * rt[1] + y * up[1], az = x * rt[2] + y * up[2];
			float vx = fw[0] + ax, vy = fw[1] + ay, vz = fw[2] + az;
			float il = 1.0f / sqrtf(vx * vx + vy * vy + vz * vz);
			pk->ox[k] = eye[0];
			pk->oy[k] = eye[1];
			pk->oz[k] = eye[2];
			pk->dx[k] = vx * il;
			pk->dy[k] = vy * il;
			pk->dz[k] = vz * il;
			pk->fa[k] = 0.0f;
			pk->fb[k] = fp;
		}
	}
	for (int k = 0; k < RT_LANES; k++) {
		pk->tmin[k] = 0;
		pk->tmax[k] = INFINITY;
		pk->active[k] = k < n;
	}
}

static void init_packet(const rt_params_t *p, rt_packet_t *pk)
{
	memset(pk, 0, offsetof(rt_packet_t, o));   /* the double rays are set where they are used */
	pk->acc = (float)(p->accuracy > 0 ? p->accuracy : 1e-3);
	pk->step = (float)(p->step_pixels > 0 ? p->step_pixels : 0.5);
}

/* Cone tracing ahead of the packets: for each packet of a row, the cone from
 * the eye around its middle ray that holds all its rays (radius rr per unit
 * distance). A point P on the axis at distance t is at least f(P)/L - rr*t
 * from the surface, so every ray of the packet may start at the t where that
 * bound first drops below half the cone radius; a cone that leaves the region
 * with room to spare lets the whole packet skip the object. Eight cones are
 * evaluated together. out[q] = start parameter, INFINITY = nothing to hit. */
static void cone_starts(const rt_params_t *p, const model_shape_t *s, unsigned j, unsigned npk,
                        float *out, rt_stats_t *st)
{
	const cam_t *c = &p->cam;
	int ortho = c->projection == CAM_ORTHOGRAPHIC;
	double fp = cam_footprint(c, 1), rr = (RT_LANES / 2 + 0.75) * fp * 1.05;
	const double *b = s->box;
	double bc[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
	double half = 0.5 * sqrt((b[3] - b[0]) * (b[3] - b[0]) + (b[4] - b[1]) * (b[4] - b[1]) + (b[5] - b[2]) * (b[5] - b[2]));
	if (s->bounded)
		half = fmin(half, s->radius + sqrt((bc[0] - s->centre[0]) * (bc[0] - s->centre[0]) + (bc[1] - s->centre[1]) * (bc[1] - s->centre[1])
		                                   + (bc[2] - s->centre[2]) * (bc[2] - s->centre[2])));
	for (unsigned g = 0; g < npk; g += 8) {
		float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8], t[8], tfar[8], x[8], y[8], z[8], v[8];
		int live[8], n = 0;
		for (int k = 0; k < 8; k++) {
			unsigned q = g + k < npk ? g + k : npk - 1;
			double o[3], d[3];
			cam_ray(c, q * (double)RT_LANES + RT_LANES / 2.0, j + 0.5, o, d);
			ox[k] = (float)o[0];
			oy[k] = (float)o[1];
			oz[k] = (float)o[2];
			dx[k] = (float)d[0];
			dy[k] = (float)d[1];
			dz[k] = (float)d[2];
			double oc[3] = {o[0] - bc[0], o[1] - bc[1], o[2] - bc[2]};
			double oc2 = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2];
			tfar[k] = (float)(sqrt(oc2) + half);
			t[k] = 0;
			live[k] = g + k < npk && rt_bound(s) > 0 && !s->lip_local;
			if (live[k] && s->de) {
				/* a distance estimate steps a quarter of the way through empty space: the cone
				 * starts where its axis enters the region's sphere and box grown by the cone's
				 * widest radius (before that no ray of the packet is in the region), and a cone
				 * that misses them skips the object (a Lipschitz bound gets there in a step
				 * or two: its cones start at the eye, as their pictures were recorded) */
				double R = half + (ortho ? rr : rr * (double)tfar[k]);
				double bb = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2], disc = bb * bb - (oc2 - R * R);
				if (!(disc >= 0) || -bb + sqrt(disc) < 0) {
					out[g + k] = INFINITY;
					live[k] = 0;
					continue;
				}
				double t0 = fmax(0.0, -bb - sqrt(disc)), t1 = -bb + sqrt(disc), rc = R - half;
				for (int i = 0; i < 3; i++) {   /* and the box grown by the same radius */
					double a = (b[i] - rc - o[i]) / d[i], z = (b[3 + i] + rc - o[i]) / d[i];
					if (a == a && z == z) {
						t0 = fmax(t0, fmin(a, z));
						t1 = fmin(t1, fmax(a, z));
					}
				}
				if (!(t0 <= t1)) {
					out[g + k] = INFINITY;
					live[k] = 0;
					continue;
				}
				t[k] = (float)t0;
			}
			n += live[k];
			if (g + k < npk)
				out[g + k] = 0;
		}
		for (int it = 0; n > 0 && it < 64; it++) {
			for (int k = 0; k < 8; k++) {
				x[k] = ox[k] + t[k] * dx[k];
				y[k] = oy[k] + t[k] * dy[k];
				z[k] = oz[k] + t[k] * dz[k];
			}
#ifdef __AVX__
			if (s->fast_points && !s->de) {   /* the kernel inline: model_eval8's fast path, the same bits */
				vf8 X, Y, Z, V;
				memcpy(&X, x, sizeof X);
				memcpy(&Y, y, sizeof Y);
				memcpy(&Z, z, sizeof Z);
				V = rt_points8v(s, X, Y, Z);
				memcpy(v, &V, sizeof V);
			} else
#endif
				rt_eval8(s, x, y, z, v);
			st->primary_evals += (uint64_t)n;
			st->lane_evals += 8;
			n = 0;
			for (int k = 0; k < 8; k++) {
				if (!live[k])
					continue;
				double r = ortho ? rr : rr * t[k], dd = v[k] / rt_bound(s) - r;
				if (!(dd >= 0.5 * r)) {
					out[g + k] = t[k];       /* near something (or inside, or NaN): start here */
					live[k] = 0;
				} else if (t[k] + dd > tfar[k]) {
					out[g + k] = INFINITY;   /* the whole cone misses the region */
					live[k] = 0;
				} else {
					t[k] = (float)(t[k] + dd);
					n++;
				}
			}
		}
		for (int k = 0; k < 8; k++)
			if (live[k])
				out[g + k] = t[k];
	}
}

/* Rays of the packet in double precision as well (cam_ray: the reference set-up). */
static void double_rays(const rt_params_t *p, rt_packet_t *pk, double px0, double dpx, double py)
{
	for (int k = 0; k < RT_LANES; k++) {
		double o[3], d[3];
		cam_ray(&p->cam, px0 + k * dpx, py, o, d);
		for (int i = 0; i < 3; i++) {
			pk->o[i][k] = o[i];
			pk->d[i][k] = d[i];
		}
	}
}

static void render_row(const rt_params_t *p, const unsigned char *dbl, meta_rgb_t *row, unsigned r, rt_stats_t *st)
{
	unsigned nx = p->cam.nxpix, j = p->cam.nypix - 1 - r, npk = (nx + RT_LANES - 1) / RT_LANES;
	rt_packet_t pk;
	double col[RT_LANES][3];
	float *start = malloc((p->nobjects * npk + 1) * sizeof *start);
	const meta_rgb_t bg = to_rgb(p->background);
	int any = 0;
	for (size_t i = 0; i < p->nobjects; i++)
		any |= dbl[i];
	for (size_t i = 0; start && i < p->nobjects; i++)
		if (!dbl[i])
			cone_starts(p, p->objects[i].shape, j, npk, start + i * npk, st);
	for (unsigned x0 = 0, q = 0; x0 < nx; x0 += RT_LANES, q++) {
		init_packet(p, &pk);
		setup_rays8(p, &pk, x0 + 0.5, 1.0, j + 0.5, nx - x0 < RT_LANES ? (int)(nx - x0) : RT_LANES);
		if (any)
			double_rays(p, &pk, x0 + 0.5, 1.0, j + 0.5);
		uint32_t hit = trace8(p, dbl, &pk, col, st, start ? start + q : NULL, npk);
		for (int k = 0; k < RT_LANES && x0 + k < nx; k++)
			row[x0 + k] = hit >> k & 1 ? to_rgb(col[k]) : bg;
	}
	free(start);
}

static int differs(meta_rgb_t a, meta_rgb_t b, double th)
{
	for (int s = 0; s < 24; s += 8) {
		int d = (int)((a >> s) & 255) - (int)((b >> s) & 255);
		if (d > th || -d > th)
			return 1;
	}
	return 0;
}

static void supersample_row(const rt_params_t *p, const unsigned char *dbl, const meta_rgb_t *src, meta_rgb_t *row,
                            unsigned r, rt_stats_t *st)
{
	unsigned nx = p->cam.nxpix, ny = p->cam.nypix, j = ny - 1 - r, n = (unsigned)p->supersample;
	double th = p->aa_threshold > 0 ? p->aa_threshold : 8;
	for (unsigned i = 0; i < nx; i++) {
		meta_rgb_t c = src[(size_t)r * nx + i];
		int need = (i > 0 && differs(c, src[(size_t)r * nx + i - 1], th))
		        || (i + 1 < nx && differs(c, src[(size_t)r * nx + i + 1], th))
		        || (r > 0 && differs(c, src[(size_t)(r - 1) * nx + i], th))
		        || (r + 1 < ny && differs(c, src[(size_t)(r + 1) * nx + i], th));
		if (!need)
			continue;
		st->aa_pixels++;
		double sum[3] = {0, 0, 0}, col[RT_LANES][3];
		rt_packet_t pk;
		uint64_t before = st->primary_evals + st->shadow_evals;
		for (unsigned s0 = 0; s0 < n * n; s0 += RT_LANES) {
			init_packet(p, &pk);
			for (unsigned k = 0; k < RT_LANES && s0 + k < n * n; k++) {
				unsigned a = (s0 + k) % n, b = (s0 + k) / n;
				setup_ray(p, &pk, (int)k, i + (a + 0.5) / n, j + (b + 0.5) / n);
			}
			trace8(p, dbl, &pk, col, st, NULL, 0);
			for (unsigned k = 0; k < RT_LANES && s0 + k < n * n; k++)
				for (int q = 0; q < 3; q++)
					sum[q] += col[k][q];
		}
		st->aa_evals += st->primary_evals + st->shadow_evals - before;
		for (int q = 0; q < 3; q++)
			sum[q] /= n * n;
		row[i] = to_rgb(sum);
	}
}

static void *worker(void *arg)
{
	worker_t *w = arg;
	job_t *job = w->job;
	const rt_params_t *p = job->p;
	unsigned ny = p->cam.nypix, nx = p->cam.nxpix;
	for (;;) {
		unsigned r = atomic_fetch_add(&job->next_row, 1);
		if (r >= ny)
			break;
		if (job->pass == 0)
			render_row(p, job->dbl, job->img + (size_t)r * nx, r, &w->st);
		else
			supersample_row(p, job->dbl, job->src, job->img + (size_t)r * nx, r, &w->st);
		atomic_fetch_add(&job->rows_done, 1);
	}
	atomic_fetch_add(&job->workers_done, 1);
	return NULL;
}

static int run_pass(job_t *job, unsigned nthreads, rt_stats_t *st, char *err, size_t errlen)
{
	const rt_params_t *p = job->p;
	pthread_t tid[64];
	worker_t ws[64];
	atomic_store(&job->next_row, 0);
	atomic_store(&job->rows_done, 0);
	atomic_store(&job->workers_done, 0);
	unsigned started = 0;
	for (unsigned i = 0; i < nthreads; i++) {
		memset(&ws[i], 0, sizeof ws[i]);
		ws[i].job = job;
		if (i > 0 && pthread_create(&tid[i], NULL, worker, &ws[i]) != 0)
			break;
		started++;
	}
	if (started < nthreads && started == 0) {
		snprintf(err, errlen, "cannot start worker threads");
		return -1;
	}
	if (started == 1 || !p->progress) {
		worker(&ws[0]);
	} else {
		/* thread 0's share is done by an extra worker so this thread can report */
		pthread_t extra;
		if (pthread_create(&extra, NULL, worker, &ws[0]) != 0)
			worker(&ws[0]);
		else {
			while (atomic_load(&job->workers_done) < started) {
				p->progress(p->progress_user, atomic_load(&job->rows_done), p->cam.nypix);
				struct timespec ts = {0, 50000000};
				nanosleep(&ts, NULL);
			}
			pthread_join(extra, NULL);
		}
	}
	for (unsigned i = 1; i < started; i++)
		pthread_join(tid[i], NULL);
	if (p->progress)
		p->progress(p->progress_user, p->cam.nypix, p->cam.nypix);
	for (unsigned i = 0; i < started; i++) {
		const rt_stats_t *s = &ws[i].st;
		st->lane_evals += s->lane_evals;
		st->primary_evals += s->primary_evals;
		st->shadow_evals += s->shadow_evals;
		st->normal_evals += s->normal_evals;
		st->aa_evals += s->aa_evals;
		st->hits += s->hits;
		st->aa_pixels += s->aa_pixels;
	}
	return 0;
}

int rt_needs_double(const cam_t *c, const model_shape_t *s, double accuracy)
{
	/* the float marcher's limits in pixels: positions carry about 2 ulps of the largest
	 * coordinate (eye or region), its hit tolerance is at least 2e-6 of the ray parameter */
	double S = 0, R, cen[3];
	for (int i = 0; i < 3; i++) {
		S = fmax(S, fabs(c->eye[i]));
		S = fmax(S, fmax(fabs(s->box[i]), fabs(s->box[3 + i])));
		cen[i] = (s->box[i] + s->box[3 + i]) / 2;
	}
	R = 0.5 * sqrt((s->box[3] - s->box[0]) * (s->box[3] - s->box[0]) + (s->box[4] - s->box[1]) * (s->box[4] - s->box[1])
	               + (s->box[5] - s->box[2]) * (s->box[5] - s->box[2]));
	if (s->bounded && s->radius < R) {
		R = s->radius;
		memcpy(cen, s->centre, sizeof cen);
	}
	double v[3] = {c->eye[0] - cen[0], c->eye[1] - cen[1], c->eye[2] - cen[2]};
	double dist = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	double tnear = fmax(dist - R, 1e-3 + 0.1 * dist), tfar = dist + R;
	double err_pos = 2.4e-7 * S / cam_footprint(c, tnear);
	double err_tol = 2e-6 * (tfar + 1) / cam_footprint(c, tfar);
	double limit = 4 * (accuracy > 0 ? accuracy : 1e-3);
	return !(err_pos <= limit && err_tol <= limit);
}

int rt_render(const rt_params_t *p, meta_rgb_t *img, rt_stats_t *st, char *err, size_t errlen)
{
	rt_stats_t local;
	if (!st)
		st = &local;
	memset(st, 0, sizeof *st);
	unsigned nthreads = p->threads;
	if (nthreads == 0) {
		long n = sysconf(_SC_NPROCESSORS_ONLN);
		nthreads = n > 0 ? (unsigned)n : 1;
	}
	if (nthreads > 64)
		nthreads = 64;
	job_t job;
	memset(&job, 0, sizeof job);
	job.p = p;
	job.img = img;
	unsigned char *dbl = calloc(p->nobjects + 1, 1);
	if (!dbl) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	for (size_t i = 0; i < p->nobjects; i++)
		dbl[i] = rt_needs_double(&p->cam, p->objects[i].shape, p->accuracy);
	job.dbl = dbl;
	int rc0 = run_pass(&job, nthreads, st, err, errlen);
	if (rc0 < 0 || p->supersample < 2)
		free(dbl);
	if (rc0 < 0)
		return -1;
	if (p->supersample >= 2) {
		size_t n = (size_t)p->cam.nxpix * p->cam.nypix;
		meta_rgb_t *copy = malloc(n * sizeof *copy);
		if (!copy) {
			free(dbl);
			snprintf(err, errlen, "out of memory for supersampling");
			return -1;
		}
		memcpy(copy, img, n * sizeof *copy);
		job.src = copy;
		job.pass = 1;
		int rc = run_pass(&job, nthreads, st, err, errlen);
		free(copy);
		free(dbl);
		if (rc < 0)
			return -1;
	}
	st->evals = st->primary_evals + st->shadow_evals + st->normal_evals;
	return 0;
}

int rt_write_image(meta_writer_t *w, const meta_rgb_t *img, unsigned width, unsigned height,
                   unsigned x, unsigned y)
{
	int rc = meta_image(w, x, y, width, height);
	for (unsigned r = 0; rc >= 0 && r < height; r++)
		rc = meta_row_pixels(w, img + (size_t)r * width, width);
	return rc < 0 ? rc : 0;
}
