/* model.h: distance-based implicit shapes f(P) = sum w_i d(P, A_i) - c(P), with Lipschitz bounds and 8-wide kernels.
 *
 * Elements A_i (extended distance d(P, A), the Euclidean distance to the
 * nearest point of the set A; every d is 1-Lipschitz):
 *   point, finite point set (min over the points), segment, polyline (min over
 *   its segments), infinite line, plane (unsigned distance), planar disk
 *   (sqrt(h^2 + max(rho - r, 0)^2)), and another shape S, for which the
 *   estimate |f_S(P)| / L_S is used (never above the true distance to the
 *   surface of S, and 1-Lipschitz), and the faces of an extended, additively
 *   weighted 3D Voronoi tessellation of point and segment nuclei: with
 *   e_i = d(P, N_i) - w_i and e1 <= e2 the two smallest, the estimate
 *   (e2 - e1) / 2 (never more than the distance to the face between the two
 *   nearest nuclei, 1-Lipschitz; the locus (e2 - e1)/2 = c is a wall of half
 *   thickness about c around every face).
 *
 * The defining parameter c(P) is one of
 *   constant              bound G_c = 0
 *   expression in x,y,z   G_c from expr_bound() over the object's box
 *   noise                 c0 + amp * noise(freq * P): seeded value noise with
 *                         smoothstep trilinear interpolation, values in
 *                         [-1, 1], |grad noise| <= 3*sqrt(3), so
 *                         G_c = 3*sqrt(3)*|amp|*freq
 *   mandelbrot            c0 + amp * n(P)/maxit, n = escape count of
 *                         z <- z^2 + (u(P) + i v(P)) with u, v affine in P:
 *                         piecewise constant, no bound (bracketing fallback);
 *                         `smooth`: n is the continuous escape count
 *                         n + 1 - log2(ln|z_n|) (bail-out |z| > 1000, in
 *                         [0, maxit]), whose level sets are the set's
 *                         equipotentials; `revolve`: u, v read the point
 *                         (x, sqrt(y^2+z^2), 0), so the picture in the
 *                         (u, v) plane is turned about the x axis into a
 *                         solid of revolution (the thesis' figure 5.10)
 *   another shape         c0 + amp * f_S(P): G_c = |amp| * L_S
 *
 * Coordinates: elements and the parameter live in the object's SETUP frame;
 * translate/rotate/scale move the object to its ACTUAL position (M, applied
 * in call order). f_actual(P) = f_setup(M^-1 P), so
 *   L = ||M^-1|| * (sum |w_i| over setup elements + G_c) + sum |w_j| (shape elements)
 * where ||M^-1|| <= product of 1/min|scale| over the scale steps.
 *
 * A shape without elements is f = -c(P) (only for a parameter that is not a
 * constant): the solid is where the defining parameter is positive.
 *
 * The shape is f < 0 inside (for positive weights) and f = 0 on its surface.
 */
#ifndef LOCUS_MODEL_H
#define LOCUS_MODEL_H

#include <stddef.h>
#include "expr.h"

/* Element kinds. */
enum { MODEL_POINT, MODEL_POINTS, MODEL_SEGMENT, MODEL_POLYLINE, MODEL_LINE,
       MODEL_PLANE, MODEL_DISK, MODEL_SHAPE, MODEL_VORONOI, MODEL_CSG,
       MODEL_CIRCLE, MODEL_TRIANGLE, MODEL_POLYGON, MODEL_BOX };
/* Constructive combinations (MODEL_CSG elements) of two shapes A, B with the normalised
 * signed estimates a = f_A/L_A, b = f_B/L_B (each 1-Lipschitz, negative inside):
 *   union min(a, b), intersection max(a, b), difference max(a, -b), and the smooth blend
 *   min(a, b) - k h^2 / 4 with h = max(k - |a - b|, 0) / k (radius k > 0): its gradient is a
 *   convex combination of the two, so it is 1-Lipschitz too, and it lies within k/4 below
 *   min(a, b) (the blend fills the crease where the surfaces meet, up to k apart). */
enum { MODEL_UNION, MODEL_INTERSECTION, MODEL_DIFFERENCE, MODEL_BLEND };
/* Parameter kinds. */
enum { MODEL_C_CONST, MODEL_C_EXPR, MODEL_C_NOISE, MODEL_C_MANDEL, MODEL_C_SHAPE };

typedef struct model_shape model_shape_t;

/* One element with its weight. p holds np points of 3 doubles: POINT 1,
 * POINTS n, SEGMENT 2, POLYLINE n >= 2, LINE point + direction, PLANE point +
 * normal, DISK centre + normal (radius r), CIRCLE centre + normal (radius r: the
 * ring, d = sqrt(h^2 + (rho - r)^2)), TRIANGLE 3 corners and POLYGON n >= 3 corners
 * of a planar filled polygon (d = |h| over it, else the distance to its nearest edge;
 * the unit normal is kept after the corners), BOX two opposite corners of an
 * axis-aligned solid box (d = 0 inside). The last four take the scalar path in the
 * 8-wide kernel. */
typedef struct {
	int kind;
	double w;
	double *p;
	size_t np;
	double r;
	float *pf;                 /* float copy (directions normalised) for the 8-wide kernel */
	double *nw;                /* MODEL_VORONOI: the additive weight of each segment's nucleus */
	double *nm;                /* MODEL_VORONOI: 1 / the multiplicative weight (e = d/M - W) */
	int *grp;                  /* MODEL_VORONOI: the nucleus of each segment (polyline nuclei: runs) */
	const model_shape_t *shape; /* MODEL_SHAPE; MODEL_CSG: A */
	const model_shape_t *shape2; /* MODEL_CSG: B */
	int op;                    /* MODEL_CSG: MODEL_UNION ... MODEL_BLEND (r: the blend radius k) */
	/* the distance measure (model_set_measure): d^pw of the distance in the metric */
	double pw;                 /* power >= 1 (1: plain distance) */
	int metric;                /* MODEL_EUCLID, MODEL_LP (mp[0] = p >= 1), MODEL_ANISO (mp = a_x a_y a_z > 0) */
	double mp[3];
	int measured;              /* pw != 1 or a metric: the scalar path, bound lipm */
	double lipm;               /* set by model_prepare: Lipschitz bound of the measure over the region */
	double dmax;               /* set by model_prepare: the measure's largest value over the region */
	expr_t *wexpr;             /* a weight that varies with the setup point (owned; w is then unused) */
} model_elem_t;
/* Metrics of point elements: Euclidean; Lp, (sum |v_j|^p)^(1/p), within
 * 3^max(0, 1/p - 1/2) of the Euclidean length (its Lipschitz bound); weighted anisotropic
 * sqrt(sum a_j v_j^2), Lipschitz sqrt(max a_j). A power pw >= 1 of a measure bounded by D over
 * the region is Lipschitz pw D^(pw - 1) times the measure's bound (model_prepare takes D from
 * the setup box's corners). */
enum { MODEL_EUCLID, MODEL_LP, MODEL_ANISO };

/* The defining parameter. */
typedef struct {
	int kind;
	double c0;                 /* constant, or base value of noise/mandelbrot/shape */
	expr_t *expr;              /* MODEL_C_EXPR (owned) */
	double amp, freq;          /* noise, mandelbrot and shape amplitude; noise frequency */
	unsigned seed;             /* noise */
	double u[4], v[4];         /* mandelbrot: u = u0 x + u1 y + u2 z + u3, v likewise */
	int maxit;                 /* mandelbrot iterations */
	int smooth;                /* mandelbrot: continuous escape count instead of n */
	int revolve;               /* mandelbrot: the maps read (x, sqrt(y^2+z^2), 0): the set turned about x */
	int stepping;              /* mandelbrot: no distance estimate (the earlier stepping and bisecting, for comparison) */
	int julia;                 /* the Julia process z <- z^2 + k from z = u + iv instead (kind MODEL_C_MANDEL) */
	double k[2];               /* julia: the constant k */
	const model_shape_t *shape; /* MODEL_C_SHAPE */
} model_param_t;

/* A shape. Fill with the model_add_* and model_set_* calls, then model_prepare(). */
struct model_shape {
	model_elem_t *el;
	size_t nel, cap;
	model_param_t c;
	double m[12], minv[12];    /* setup->actual affine (3x4 row-major) and its inverse */
	double norm_m, norm_minv;  /* operator-norm bounds of their linear parts */
	float mf[12];              /* float copy of minv */
	int user_box;              /* box[] given by the user */
	double box[6];             /* actual-frame clip box: x0 y0 z0 x1 y1 z1 */
	double root[6];            /* octree root region: the user's box as given, else the clip box */
	/* set by model_prepare: */
	double lip;                /* Lipschitz bound of f in the actual frame (0 if none) */
	int has_lip;               /* 1 when lip is a valid bound inside box */
	int lip_local;             /* lip holds only inside box (a power above 1): no distance-to, CSG or cone outside it */
	int bounded;               /* 1 when the surface lies in the sphere below */
	double centre[3], radius;  /* bounding sphere (actual frame) */
	int fast_points;           /* points/segments only, constant c, translated frame: model_eval8's fast path */
	int de;                    /* model_de is a distance bound (elementless smooth Mandelbrot/Julia shape) */
	double de_m0, de_scale;    /* de: the level of the continuous count; 1 / (||u,v map|| ||M^-1||) */
	/* kept by model_add / model_check_nesting: */
	int nest;                  /* levels of shapes below this one (0: none) */
	double eval_cost, grad_cost; /* distance evaluations per point of model_eval, model_grad */
};

/* Work bounds: a shape refers to shapes (distance-to, c shape) at most MODEL_MAX_NEST deep,
 * and one evaluation of f and its gradient at a point costs at most MODEL_MAX_COST distance
 * evaluations (a shape that is the distance to another twice costs twice that one). Beyond
 * them the shape is refused before any work is done on it. */
#define MODEL_MAX_NEST 8
#define MODEL_MAX_COST 2048

/* A new empty shape (c = 0, identity transform), NULL when out of memory. */
model_shape_t *model_new(void);
/* Free a shape (not the shapes it refers to). */
void model_free(model_shape_t *s);

/* Add an element of weight w. pts: np points of 3 doubles as described above.
 * Returns 0, or -1 with a message in err for degenerate input (NaN, zero
 * direction, polyline with < 2 points, negative radius...). */
int model_add(model_shape_t *s, int kind, double w, const double *pts, size_t np, double r,
              const model_shape_t *shape, char *err, size_t errlen);

/* Add a weighted Voronoi element of n >= 2 nuclei: ab holds 6 numbers per
 * nucleus (both ends; equal for a point), wt the additive weights. Returns 0
 * or -1 with a message. (model_add with MODEL_VORONOI takes plain points.) */
int model_add_nuclei(model_shape_t *s, double w, const double *ab, const double *wt, size_t n,
                     char *err, size_t errlen);

/* Add a constructive element of weight w: op (MODEL_UNION ...) of shapes a and b, both with
 * a Lipschitz bound; k > 0 the blend radius (MODEL_BLEND). Its value is signed and
 * 1-Lipschitz in the ACTUAL frame (like a distance-to element, outside the transforms). Returns
 * 0 or -1 with a message. */
int model_add_csg(model_shape_t *s, double w, int op, const model_shape_t *a, const model_shape_t *b,
                  double k, char *err, size_t errlen);
/* The value of element e of s at the actual point p (setup point q): its distance, or for
 * MODEL_SHAPE |f|/L and for MODEL_CSG the signed combination. */
double model_elem_value(const model_elem_t *e, const double p[3], const double q[3]);

/* Give the last element added a distance measure: d^pw (pw >= 1) of its distance in the metric
 * (MODEL_LP and MODEL_ANISO for point and points elements only; mp as above). Returns 0 or -1
 * with a message ("expected ..." follows it). */
int model_set_measure(model_shape_t *s, double pw, int metric, const double mp[3], char *err, size_t errlen);
/* Give the last element added the position-varying weight w(q) = e (an expression in x, y, z of
 * the setup frame; the element owns it from here, also on failure). Such a shape needs a
 * `bound` box: its Lipschitz bound is max|w|·L_d + G_w·D over it (G_w from interval
 * arithmetic, D the largest distance). Returns 0 or -1 with a message. */
int model_set_weight_expr(model_shape_t *s, expr_t *e, char *err, size_t errlen);

/* The measure of a measured element at the setup point q (model_elem_distance otherwise). */
double model_elem_measure(const model_elem_t *e, const double q[3]);

/* Set every measured element's lipm for the setup-frame box lo..hi (model_prepare calls it). */
void model_measure_bounds(model_shape_t *s, const double *lo, const double *hi);

/* The general Voronoi element: n segments (ab: 6 numbers each, a point has both ends equal),
 * grouped into nuclei by grp (non-decreasing ids, a run of segments is a polyline nucleus;
 * NULL: one nucleus per segment), with additive weights wt and multiplicative weights fac
 * (NULL: 1) per segment (equal within a nucleus): e = d(P, N)/M - W, and the estimate
 * (e2 - e1)/2 of the two smallest over distinct nuclei, Lipschitz max(1/M). At least two
 * nuclei; M > 0. Returns 0 or -1 with a message. */
int model_add_nuclei2(model_shape_t *s, double w, const double *ab, const double *wt, const double *fac,
                      const int *grp, size_t n, char *err, size_t errlen);

/* Recompute s->nest and the costs from the elements and the parameter (the shapes referred
 * to must have theirs). Returns 0, or -1 with a message ("expected ..." follows it) when a
 * bound above is passed; err may be NULL. model_add calls it for shape elements; call it
 * after setting a MODEL_C_SHAPE parameter. */
int model_check_nesting(model_shape_t *s, char *err, size_t errlen);

/* Transforms, applied after the ones already given (SETUP -> ACTUAL). Angles in degrees. */
void model_translate(model_shape_t *s, double x, double y, double z);
void model_rotate(model_shape_t *s, int axis, double degrees);   /* axis 0 = x, 1 = y, 2 = z */
int model_scale(model_shape_t *s, double sx, double sy, double sz); /* -1 if a factor is 0 or not finite */

/* Derive the Lipschitz bound and the bounding region. Returns 0, or -1 with
 * a message when the shape cannot be drawn (no elements and a constant c, no region: an
 * unbounded shape needs a user box). Sets *warn (if non-NULL) to a warning
 * text or NULL. */
int model_prepare(model_shape_t *s, char *err, size_t errlen, const char **warn);

/* f at the actual-frame point p (double precision, the reference). */
double model_eval(const model_shape_t *s, const double p[3]);
/* f at 8 actual-frame points (float, vectorised). */
void model_eval8(const model_shape_t *s, const float *x, const float *y, const float *z, float *out);
/* Distance from the setup-frame point q to a (non-shape) element. */
double model_elem_distance(const model_elem_t *e, const double q[3]);
/* The point q of element e nearest to p (the setup frame); returns the distance |p - q|. */
double model_elem_nearest(const model_elem_t *e, const double *p, double *q);
/* Gradient of f at p (analytic for elements, central differences for c). */
void model_grad(const model_shape_t *s, const double p[3], double g[3]);

/* Distance estimate of an elementless shape whose parameter is a smooth Mandelbrot or Julia
 * process (s->de set by model_prepare): the sign of f, and a magnitude never above the distance
 * from p to the surface (the Douady-Hubbard potential with Koebe's quarter theorem, divided by
 * the norms of the (u, v) map and of M^-1). Inside the set (no escape) it is -1e-3 * de_scale:
 * a sign, not a bound. model_de8: the same at 8 float points. */
double model_de(const model_shape_t *s, const double p[3]);
void model_de8(const model_shape_t *s, const float *x, const float *y, const float *z, float *out);
/* 1 with *d = model_de(s, p) when that is a bound (the iteration escaped); 0 when it is only a
 * sign (inside the set) or undefined (NaN). */
int model_de_known(const model_shape_t *s, const double p[3], double *d);
/* The escape counts of the process c (kind MODEL_C_MANDEL) at nl <= 8 setup-frame points q
 * (x, y, z of each in turn), iterated together: n, or with smooth the continuous count
 * n + 1 - log2 ln|z_n| (bail-out |z|^2 > 1e6) kept in 0..maxit. */
void model_counts(const model_param_t *c, int nl, const double *q, int smooth, double *out);
/* The same for one point, scalar (the lanes' arithmetic: the same value). */
double model_count(const model_param_t *c, const double q[3], int smooth);
/* 1 with the level *m0 of the continuous count when c is a smooth process with a level inside
 * (0, maxit) (the surface is the equipotential count = m0). */
int model_de_level(const model_param_t *c, double *m0);

/* Value of the defining parameter at the actual point p (setup point q). */
double model_param(const model_shape_t *s, const double p[3], const double q[3]);

/* 1 when the Lipschitz cell test proves f > 0 everywhere in the clip region
 * (the shape is empty, e.g. c below the minimum of the sum). */
int model_is_empty(const model_shape_t *s);

/* Seeded value noise in [-1, 1] (see above). */
double model_noise(unsigned seed, double x, double y, double z);

#endif
