/* scene_shape.c: the scene language's shape blocks: elements, weights and measures, the defining parameter, nuclei, colour and material. */
#include "scene_int.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef scene_tok_t tok_t;

static scene_obj_t *find(scene_t *sc, const tok_t *t)
{
	for (size_t i = 0; i < sc->nobjs; i++)
		if (strlen(sc->objs[i].name) == t->len && !memcmp(sc->objs[i].name, t->s, t->len))
			return &sc->objs[i];
	return NULL;
}

/* The optional end of an element line: "weight W", "power P", "metric lp P" or
 * "metric aniso AX AY AZ", in any order (measure != NULL: power and metric allowed). */
typedef struct {
	double pw, mp[3];
	int metric;
	scene_tok_t at;            /* the first power/metric word, for messages */
	expr_t *wexpr;             /* a weight expression in x, y, z (owned until handed on) */
	scene_tok_t wat;
} measure_t;

/* 1 when the token uses x, y or z as an identifier (a position-varying weight). */
static int uses_xyz(const tok_t *t)
{
	for (size_t i = 0; i < t->len; i++) {
		char c = t->s[i];
		int before = i > 0 && (isalnum((unsigned char)t->s[i - 1]) || t->s[i - 1] == '_' || t->s[i - 1] == '.');
		int after = i + 1 < t->len && (isalnum((unsigned char)t->s[i + 1]) || t->s[i + 1] == '_');
		if ((c == 'x' || c == 'y' || c == 'z') && !before && !after)
			return 1;
	}
	return 0;
}

/* "weight EXPR" with x, y, z: compile the token (t replaced by its value). */
static int weight_expr(scene_lex_t *lx, const tok_t *t, expr_t **out)
{
	char src[1024], e[200], msg[300];
	size_t at = 0;
	if (scene_subst_t(t->s, t->len, lx->t, src, sizeof src) < 0)
		return scene_lex_error(lx, t->line, t->col, "expected a weight expression of at most 200 bytes");
	if (expr_compile(src, out, e, sizeof e, &at) < 0) {
		snprintf(msg, sizeof msg, "%s (in the weight '%.*s')", e, (int)(t->len > 60 ? 60 : t->len), t->s);
		return scene_lex_error(lx, t->line, t->col, msg);
	}
	return 0;
}

static int opt_suffix(scene_lex_t *lx, double *w, measure_t *ms)
{
	tok_t t;
	*w = 1;
	if (ms) {
		memset(ms, 0, sizeof *ms);
		ms->pw = 1;
	}
	int seen_w = 0;
	while (scene_lex_tok(lx, &t)) {
		if (scene_tok_is(&t, "weight") && !seen_w) {
			seen_w = 1;
			size_t save = lx->pos;
			tok_t v;
			if (ms && scene_lex_tok(lx, &v) && uses_xyz(&v)) {
				ms->wat = v;
				if (weight_expr(lx, &v, &ms->wexpr) < 0)
					return -1;
				continue;
			}
			lx->pos = save;
			if (scene_lex_number(lx, w, "a weight") < 0)
				return -1;
		} else if (ms && scene_tok_is(&t, "power")) {
			if (!ms->at.len)
				ms->at = t;
			if (scene_lex_number(lx, &ms->pw, "a power") < 0)
				return -1;
		} else if (ms && scene_tok_is(&t, "metric")) {
			tok_t k;
			if (!ms->at.len)
				ms->at = t;
			scene_lex_tok(lx, &k);
			if (scene_tok_is(&k, "lp")) {
				ms->metric = MODEL_LP;
				if (scene_lex_number(lx, &ms->mp[0], "the p of the Lp metric") < 0)
					return -1;
			} else if (scene_tok_is(&k, "aniso")) {
				ms->metric = MODEL_ANISO;
				if (scene_lex_numbers(lx, ms->mp, 3, "an anisotropic weight AX AY AZ") < 0)
					return -1;
			} else if (scene_tok_is(&k, "euclidean")) {
				ms->metric = MODEL_EUCLID;
			} else {
				return scene_lex_expected(lx, &k, "lp P, aniso AX AY AZ or euclidean");
			}
		} else {
			return scene_lex_expected(lx, &t, ms ? "'weight', 'power', 'metric' or the end of the line" : "'weight' or the end of the line");
		}
	}
	return 0;
}

static int opt_weight(scene_lex_t *lx, double *w)
{
	return opt_suffix(lx, w, NULL);
}

static int add_elem(scene_lex_t *lx, model_shape_t *m, int kind, const double *p, size_t np,
                    double r, const model_shape_t *other, const tok_t *at)
{
	double w;
	measure_t ms;
	char e[200], msg[256];
	ms.wexpr = NULL;
	if (opt_suffix(lx, &w, kind == MODEL_SHAPE ? NULL : &ms) < 0) {
		expr_free(ms.wexpr);
		return -1;
	}
	if (model_add(m, kind, w, p, np, r, other, e, sizeof e) < 0) {
		expr_free(ms.wexpr);
		snprintf(msg, sizeof msg, "expected %s", e);
		return scene_lex_error(lx, at->line, at->col, msg);
	}
	if (ms.wexpr && model_set_weight_expr(m, ms.wexpr, e, sizeof e) < 0) {
		snprintf(msg, sizeof msg, "expected %s", e);
		return scene_lex_error(lx, ms.wat.line, ms.wat.col, msg);
	}
	if (kind != MODEL_SHAPE && (ms.pw != 1 || ms.metric != MODEL_EUCLID)
	    && model_set_measure(m, ms.pw, ms.metric, ms.mp, e, sizeof e) < 0) {
		snprintf(msg, sizeof msg, "expected %s", e);
		return scene_lex_error(lx, ms.at.line, ms.at.col, msg);
	}
	return 0;
}

/* A list of points: numbers in threes up to 'weight' or the end of the line. */
static int point_list(scene_lex_t *lx, double **pts, size_t *np)
{
	static const char *const stop[] = {"weight", NULL};
	size_t n;
	double *p;
	if (scene_lex_points(lx, 3, stop, 0, NULL, &p, &n) < 0)
		return -1;
	if (n == 0 || n % 3) {
		free(p);
		return scene_lex_error(lx, lx->line, 1, "expected coordinates in groups of three (x y z)");
	}
	*pts = p;
	*np = n / 3;
	return 0;
}

static int parse_param(scene_lex_t *lx, scene_t *sc, model_shape_t *m)
{
	tok_t t, rest;
	size_t save = lx->pos;
	model_param_t *c = &m->c;
	expr_free(c->expr);
	memset(c, 0, sizeof *c);
	scene_lex_tok(lx, &t);
	if (scene_tok_is(&t, "noise")) {
		double v[4];
		c->kind = MODEL_C_NOISE;
		if (scene_lex_numbers(lx, v, 4, "noise BASE AMPLITUDE FREQUENCY SEED") < 0)
			return -1;
		if (v[2] <= 0 || v[3] < 0 || v[3] != floor(v[3]) || v[3] > 4294967295.0)
			return scene_lex_error(lx, t.line, t.col, "expected a positive frequency and a whole seed >= 0");
		c->c0 = v[0];
		c->amp = v[1];
		c->freq = v[2];
		c->seed = (unsigned)v[3];
		return scene_lex_eol(lx);
	}
	if (scene_tok_is(&t, "mandelbrot") || scene_tok_is(&t, "julia")) {
		double v[3];
		c->kind = MODEL_C_MANDEL;
		c->julia = t.s[0] == 'j';
		if (scene_lex_numbers(lx, v, 3, c->julia ? "julia BASE AMPLITUDE ITERATIONS" : "mandelbrot BASE AMPLITUDE ITERATIONS") < 0
		    || (c->julia && scene_lex_numbers(lx, c->k, 2, "the constant k (real and imaginary part)") < 0)
		    || scene_lex_numbers(lx, c->u, 4, "the u map (4 numbers)") < 0
		    || scene_lex_numbers(lx, c->v, 4, "the v map (4 numbers)") < 0)
			return -1;
		if (v[2] < 1 || v[2] > 100000 || v[2] != floor(v[2]))
			return scene_lex_error(lx, t.line, t.col, "expected 1..100000 whole iterations");
		c->c0 = v[0];
		c->amp = v[1];
		c->maxit = (int)v[2];
		tok_t f;
		while (scene_lex_tok(lx, &f)) {
			int *flag = scene_tok_is(&f, "smooth") ? &c->smooth : scene_tok_is(&f, "revolve") ? &c->revolve
			          : scene_tok_is(&f, "stepping") ? &c->stepping : NULL;
			if (!flag || *flag)
				return scene_lex_expected(lx, &f, "'smooth', 'revolve', 'stepping' or the end of the line");
			*flag = 1;
		}
		return 0;
	}
	if (scene_tok_is(&t, "shape")) {
		tok_t n;
		scene_lex_tok(lx, &n);
		scene_obj_t *o = find(sc, &n);
		if (!o)
			return scene_lex_expected(lx, &n, "the name of a shape or object defined above");
		if (!o->shape->has_lip)
			return scene_lex_expected(lx, &n, "a shape with a Lipschitz bound");
		c->kind = MODEL_C_SHAPE;
		c->shape = o->shape;
		char e[200], msg[256];
		if (model_check_nesting(m, e, sizeof e) < 0) {
			snprintf(msg, sizeof msg, "expected %s", e);
			return scene_lex_error(lx, n.line, n.col, msg);
		}
		if (scene_lex_number(lx, &c->c0, "a base value") < 0 || scene_lex_number(lx, &c->amp, "an amplitude") < 0)
			return -1;
		return scene_lex_eol(lx);
	}
	lx->pos = save;
	scene_lex_rest(lx, &rest);
	if (rest.len == 0)
		return scene_lex_expected(lx, &rest, "a value, an expression in x, y, z, noise, mandelbrot, julia or shape");
	int timed = scene_uses_t(rest.s, rest.len);
	size_t srclen = timed ? 26 * rest.len + 1 : rest.len + 1;   /* each t becomes (%.17g) */
	char *src = malloc(srclen), e[200], msg[300];
	if (!src)
		return scene_lex_error(lx, rest.line, rest.col, "out of memory");
	if (timed)
		scene_subst_t(rest.s, rest.len, lx->t, src, srclen);
	else {
		memcpy(src, rest.s, rest.len);
		src[rest.len] = 0;
	}
	size_t at = 0;
	if (expr_compile(src, &c->expr, e, sizeof e, &at) < 0) {
		free(src);
		snprintf(msg, sizeof msg, "%s%s", e, timed ? " (in the expression with t replaced by its value)" : "");
		return scene_lex_error(lx, rest.line, timed ? rest.col : rest.col + (unsigned)at, msg);
	}
	free(src);
	if (expr_is_constant(c->expr)) {
		c->c0 = expr_eval(c->expr, 0, 0, 0);
		expr_free(c->expr);
		c->expr = NULL;
		c->kind = MODEL_C_CONST;
		if (!isfinite(c->c0))
			return scene_lex_error(lx, rest.line, rest.col, "expected a finite defining parameter");
	} else {
		c->kind = MODEL_C_EXPR;
	}
	return 0;
}

/* `nucleus` lines of an object, gathered into one Voronoi element at its end: segments (a
 * point is a segment of equal ends), each with its nucleus' number, additive and
 * multiplicative weight. */
typedef struct {
	double *ab, *wt, *fac;
	int *grp;
	size_t n, cap;
	int ngroups;
	unsigned line, col;
} nuclei_t;

static int nucleus_line(scene_lex_t *lx, nuclei_t *nu, const tok_t *kw)
{
	double v[3 * 256];
	size_t save;
	tok_t t;
	int k = 0;
	for (;;) {
		save = lx->pos;
		if (!scene_lex_tok(lx, &t) || scene_tok_is(&t, "weight") || scene_tok_is(&t, "factor")) {
			lx->pos = save;   /* leave 'weight' / 'factor' (or the end) for below */
			break;
		}
		lx->pos = save;
		if (k == (int)(sizeof v / sizeof v[0]))
			return scene_lex_error(lx, kw->line, kw->col, "expected a polyline nucleus of at most 256 points");
		if (scene_lex_number(lx, &v[k], "a nucleus coordinate") < 0)
			return -1;
		k++;
	}
	if (k < 3 || k % 3)
		return scene_lex_error(lx, kw->line, kw->col, "expected nucleus X Y Z (a point), X1 Y1 Z1 X2 Y2 Z2 (a segment) or more"
		                       " points (a polyline), then optionally 'weight W' and 'factor M'");
	double w = 0, m = 1;
	int seen_w = 0, seen_m = 0;
	while (scene_lex_tok(lx, &t)) {
		if (scene_tok_is(&t, "weight") && !seen_w) {
			seen_w = 1;
			if (scene_lex_number(lx, &w, "a nucleus weight") < 0)
				return -1;
		} else if (scene_tok_is(&t, "factor") && !seen_m) {
			seen_m = 1;
			if (scene_lex_number(lx, &m, "a multiplicative weight") < 0)
				return -1;
			if (!(m > 0))
				return scene_lex_error(lx, t.line, t.col, "expected a multiplicative weight above 0 (e = d/M - W)");
		} else {
			return scene_lex_expected(lx, &t, "'weight', 'factor' or the end of the line");
		}
	}
	size_t npts = (size_t)k / 3, nseg = npts == 1 ? 1 : npts - 1;
	while (nu->n + nseg > nu->cap) {
		size_t cap = nu->cap ? 2 * nu->cap : 8;
		double *ab = realloc(nu->ab, 6 * cap * sizeof *ab);
		if (ab)
			nu->ab = ab;
		double *wt = realloc(nu->wt, cap * sizeof *wt);
		if (wt)
			nu->wt = wt;
		double *fc = realloc(nu->fac, cap * sizeof *fc);
		if (fc)
			nu->fac = fc;
		int *gr = realloc(nu->grp, cap * sizeof *gr);
		if (gr)
			nu->grp = gr;
		if (!ab || !wt || !fc || !gr)
			return scene_lex_error(lx, kw->line, kw->col, "out of memory");
		nu->cap = cap;
	}
	if (nu->n == 0) {
		nu->line = kw->line;
		nu->col = kw->col;
	}
	for (size_t q = 0; q < nseg; q++) {
		const double *a = v + 3 * q, *b = npts == 1 ? a : a + 3;
		memcpy(nu->ab + 6 * nu->n, a, 3 * sizeof *a);
		memcpy(nu->ab + 6 * nu->n + 3, b, 3 * sizeof *b);
		nu->wt[nu->n] = w;
		nu->fac[nu->n] = m;
		nu->grp[nu->n] = nu->ngroups;
		nu->n++;
	}
	nu->ngroups++;
	return 0;
}

static int parse_body_inner(scene_lex_t *lx, scene_t *sc, scene_obj_t *o, nuclei_t *nu);

static int parse_body(scene_lex_t *lx, scene_t *sc, scene_obj_t *o)
{
	nuclei_t nu;
	memset(&nu, 0, sizeof nu);
	int rc = parse_body_inner(lx, sc, o, &nu);
	free(nu.ab);
	free(nu.wt);
	free(nu.fac);
	free(nu.grp);
	return rc;
}

static int parse_body_inner(scene_lex_t *lx, scene_t *sc, scene_obj_t *o, nuclei_t *nu)
{
	model_shape_t *m = o->shape;
	rt_object_t *mat = &o->mat;
	tok_t t;
	char msg[400];
	while (scene_lex_line(lx)) {
		scene_lex_tok(lx, &t);
		double v[8];
		if (scene_tok_is(&t, "end")) {
			if (scene_lex_eol(lx) < 0)
				return -1;
			if (nu->n) {
				char e2[200];
				if (model_add_nuclei2(m, 1, nu->ab, nu->wt, nu->fac, nu->grp, nu->n, e2, sizeof e2) < 0) {
					snprintf(msg, sizeof msg, "expected %s", e2);
					return scene_lex_error(lx, nu->line, nu->col, msg);
				}
			}
			char e[300];
			const char *w = NULL;
			if (o->through) {
				/* the thesis' section 6.4: the defining parameter predicted from a point of the
				 * surface, c = sum w_i d(P, A_i) there (after every element and transform) */
				double v = model_eval(m, o->through_p);
				if (!isfinite(v) || m->nel == 0) {
					snprintf(msg, sizeof msg, "expected distance elements before 'end' for 'c through' in '%s'", o->name);
					return scene_lex_error(lx, o->c_line, 3, msg);
				}
				m->c.c0 = v;
			}
			if (model_prepare(m, e, sizeof e, &w) < 0) {
				snprintf(msg, sizeof msg, "%s (in '%s')", e, o->name);
				return scene_lex_error(lx, o->line, o->col, msg);
			}
			if (w && strstr(w, "empty"))
				o->empty = 1;   /* warned at the end of the scene, if a 3D picture draws it */
			else if (w) {
				snprintf(msg, sizeof msg, "'%s': %s", o->name, w);
				scene_warn(sc, o->line, o->col, msg);
			}
			return 0;
		}
		if (scene_tok_is(&t, "point")) {
			if (scene_lex_numbers(lx, v, 3, "a coordinate") < 0 || add_elem(lx, m, MODEL_POINT, v, 1, 0, NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "points") || scene_tok_is(&t, "polyline") || scene_tok_is(&t, "voronoi")) {
			double *p = NULL;
			size_t np = 0;
			int kind = t.s[0] == 'v' ? MODEL_VORONOI : t.s[1] == 'o' && t.s[2] == 'i' ? MODEL_POINTS : MODEL_POLYLINE;
			if (point_list(lx, &p, &np) < 0)
				return -1;
			int rc = add_elem(lx, m, kind, p, np, 0, NULL, &t);
			free(p);
			if (rc < 0)
				return -1;
		} else if (scene_tok_is(&t, "segment") || scene_tok_is(&t, "line") || scene_tok_is(&t, "plane")) {
			int kind = t.s[0] == 's' ? MODEL_SEGMENT : t.s[0] == 'l' ? MODEL_LINE : MODEL_PLANE;
			if (scene_lex_numbers(lx, v, 6, "a coordinate") < 0 || add_elem(lx, m, kind, v, 2, 0, NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "circle")) {
			if (scene_lex_numbers(lx, v, 7, "circle CX CY CZ NX NY NZ RADIUS") < 0 || add_elem(lx, m, MODEL_CIRCLE, v, 2, v[6], NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "triangle")) {
			double tv[9];
			if (scene_lex_numbers(lx, tv, 9, "triangle X1 Y1 Z1 X2 Y2 Z2 X3 Y3 Z3") < 0 || add_elem(lx, m, MODEL_TRIANGLE, tv, 3, 0, NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "box")) {
			if (scene_lex_numbers(lx, v, 6, "box X0 Y0 Z0 X1 Y1 Z1") < 0 || add_elem(lx, m, MODEL_BOX, v, 2, 0, NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "polygon")) {
			double *p = NULL;
			size_t np = 0;
			if (point_list(lx, &p, &np) < 0)
				return -1;
			int rc = add_elem(lx, m, MODEL_POLYGON, p, np, 0, NULL, &t);
			free(p);
			if (rc < 0)
				return -1;
		} else if (scene_tok_is(&t, "disk")) {
			if (scene_lex_numbers(lx, v, 7, "disk CX CY CZ NX NY NZ RADIUS") < 0 || add_elem(lx, m, MODEL_DISK, v, 2, v[6], NULL, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "nucleus")) {
			if (nucleus_line(lx, nu, &t) < 0)
				return -1;
		} else if (scene_tok_is(&t, "distance-to")) {
			tok_t n;
			scene_lex_tok(lx, &n);
			scene_obj_t *other = find(sc, &n);
			if (!other || other == o)
				return scene_lex_expected(lx, &n, "the name of a shape or object defined above");
			if (add_elem(lx, m, MODEL_SHAPE, NULL, 0, 0, other->shape, &n) < 0)
				return -1;
		} else if (scene_tok_is(&t, "union") || scene_tok_is(&t, "intersection") || scene_tok_is(&t, "difference")
		           || scene_tok_is(&t, "blend")) {
			int op = t.s[0] == 'u' ? MODEL_UNION : t.s[0] == 'i' ? MODEL_INTERSECTION : t.s[0] == 'd' ? MODEL_DIFFERENCE : MODEL_BLEND;
			scene_obj_t *ab[2];
			tok_t n[2];
			for (int j = 0; j < 2; j++) {
				scene_lex_tok(lx, &n[j]);
				ab[j] = find(sc, &n[j]);
				if (!ab[j] || ab[j] == o)
					return scene_lex_expected(lx, &n[j], "the name of a shape or object defined above");
				if (!ab[j]->shape->has_lip)
					return scene_lex_expected(lx, &n[j], "a shape with a Lipschitz bound (Mandelbrot, Julia and unbounded expressions cannot be combined)");
			}
			double k = 0, w;
			char e2[200];
			if (op == MODEL_BLEND && scene_lex_number(lx, &k, "a blend radius") < 0)
				return -1;
			if (opt_weight(lx, &w) < 0)
				return -1;
			if (model_add_csg(m, w, op, ab[0]->shape, ab[1]->shape, k, e2, sizeof e2) < 0) {
				snprintf(msg, sizeof msg, "expected %s", e2);
				return scene_lex_error(lx, t.line, t.col, msg);
			}
		} else if (scene_tok_is(&t, "c")) {
			if (o->c_line) {
				snprintf(msg, sizeof msg, "expected one 'c' line per shape: '%s' has its defining parameter from line %u already"
				         " (delete one of them)", o->name, o->c_line);
				return scene_lex_error(lx, t.line, t.col, msg);
			}
			o->c_line = t.line;
			size_t save = lx->pos;
			tok_t th;
			if (scene_lex_tok(lx, &th) && scene_tok_is(&th, "through")) {
				if (scene_lex_numbers(lx, o->through_p, 3, "a point X Y Z on the surface") < 0)
					return -1;
				o->through = 1;
				expr_free(m->c.expr);
				memset(&m->c, 0, sizeof m->c);
			} else {
				lx->pos = save;
				if (parse_param(lx, sc, m) < 0)
					return -1;
			}
		} else if (scene_tok_is(&t, "translate")) {
			if (scene_lex_numbers(lx, v, 3, "a translation") < 0 || scene_lex_eol(lx) < 0)
				return -1;
			model_translate(m, v[0], v[1], v[2]);
		} else if (scene_tok_is(&t, "rotate")) {
			tok_t a;
			scene_lex_tok(lx, &a);
			int axis = scene_tok_is(&a, "x") ? 0 : scene_tok_is(&a, "y") ? 1 : scene_tok_is(&a, "z") ? 2 : -1;
			if (axis < 0)
				return scene_lex_expected(lx, &a, "an axis x, y or z");
			if (scene_lex_number(lx, v, "an angle in degrees") < 0 || scene_lex_eol(lx) < 0)
				return -1;
			model_rotate(m, axis, v[0]);
		} else if (scene_tok_is(&t, "scale")) {
			if (scene_lex_number(lx, &v[0], "a scale factor") < 0)
				return -1;
			size_t save = lx->pos;
			tok_t n;
			v[1] = v[2] = v[0];
			if (scene_lex_tok(lx, &n)) {
				lx->pos = save;
				if (scene_lex_numbers(lx, v + 1, 2, "a scale factor") < 0)
					return -1;
			}
			if (scene_lex_eol(lx) < 0)
				return -1;
			if (model_scale(m, v[0], v[1], v[2]) < 0)
				return scene_lex_error(lx, t.line, t.col, "expected non-zero scale factors");
		} else if (scene_tok_is(&t, "bound")) {
			if (scene_lex_numbers(lx, m->box, 6, "a bound corner coordinate") < 0 || scene_lex_eol(lx) < 0)
				return -1;
			for (int i = 0; i < 3; i++)
				if (!(m->box[i] < m->box[3 + i]))
					return scene_lex_error(lx, t.line, t.col, "expected bound X0 Y0 Z0 X1 Y1 Z1 with X0 < X1, Y0 < Y1, Z0 < Z1");
			m->user_box = 1;
		} else if (scene_tok_is(&t, "colour") || scene_tok_is(&t, "color")) {
			if (scene_parse_colour(lx, mat->colour) < 0)
				return -1;
		} else if (scene_tok_is(&t, "shading")) {
			tok_t a;
			scene_lex_tok(lx, &a);
			if (scene_tok_is(&a, "constant"))
				mat->shading = RT_CONSTANT;
			else if (scene_tok_is(&a, "gouraud"))
				mat->shading = RT_GOURAUD;
			else if (scene_tok_is(&a, "phong"))
				mat->shading = RT_PHONG;
			else
				return scene_lex_expected(lx, &a, "constant, gouraud or phong");
		} else if (scene_tok_is(&t, "ambient") || scene_tok_is(&t, "diffuse") || scene_tok_is(&t, "specular") || scene_tok_is(&t, "shininess")) {
			double *dst = t.s[0] == 'a' ? &mat->ambient : t.s[0] == 'd' ? &mat->diffuse : t.s[1] == 'p' ? &mat->specular : &mat->shininess;
			if (scene_lex_number(lx, dst, "a non-negative number") < 0)
				return -1;
			if (*dst < 0)
				return scene_lex_error(lx, t.line, t.col, "expected a non-negative material coefficient");
		} else {
			return scene_lex_expected(lx, &t, "an element (point points segment polyline line plane disk circle triangle polygon box voronoi nucleus distance-to union intersection difference blend), c, a transform, bound, colour, shading, a material coefficient or 'end'");
		}
		if (!lx->failed && scene_lex_eol(lx) < 0)
			return -1;
		if (lx->failed)
			return -1;
	}
	return scene_lex_expected(lx, &(tok_t){"", 0, lx->line, 1}, "'end' closing the shape");
}

int scene_parse_shape(scene_lex_t *lx, scene_t *sc, int drawn, const tok_t *kw)
{
	tok_t n;
	if (!scene_lex_tok(lx, &n) || n.len >= 64)
		return scene_lex_expected(lx, &n, "a name (at most 63 bytes)");
	if (find(sc, &n))
		return scene_lex_expected(lx, &n, "a name not used before");
	if (scene_lex_eol(lx) < 0)
		return -1;
	if (sc->nobjs == sc->cap) {
		size_t cap = sc->cap ? 2 * sc->cap : 8;
		scene_obj_t *q = realloc(sc->objs, cap * sizeof *q);
		if (!q)
			return scene_lex_error(lx, n.line, n.col, "out of memory");
		sc->objs = q;
		sc->cap = cap;
	}
	scene_obj_t *o = &sc->objs[sc->nobjs];
	memset(o, 0, sizeof *o);
	memcpy(o->name, n.s, n.len);
	o->drawn = drawn;
	o->line = kw->line;
	o->col = kw->col;
	o->shape = model_new();
	if (!o->shape)
		return scene_lex_error(lx, n.line, n.col, "out of memory");
	sc->nobjs++;
	rt_object_t *m = &o->mat;
	m->shape = o->shape;
	m->colour[0] = 0.9;
	m->colour[1] = 0.6;
	m->colour[2] = 0.2;
	m->shading = RT_PHONG;
	m->ambient = 0.15;
	m->diffuse = 0.75;
	m->specular = 0.5;
	m->shininess = 30;
	return parse_body(lx, sc, o);
}
