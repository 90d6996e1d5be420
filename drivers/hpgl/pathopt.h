/* pathopt.h: pen-plotter path optimisation: merge paths whose ends meet, simplify, order by
 * nearest end (with reversal) through a spatial grid, then improve by 2-opt within a time
 * budget. Works on integer points (plotter units) of one pen's paths; memory is the paths
 * themselves plus a few words per path.
 */
#ifndef LOCUS_PATHOPT_H
#define LOCUS_PATHOPT_H

#include <stddef.h>
#include <stdint.h>

/* An integer point. */
typedef struct {
	int32_t x, y;
} popt_pt_t;

/* A path: n points from pts[start]; closed paths return to their first point (the point is
 * not repeated) and are never merged; they may start at any of their vertices. */
typedef struct {
	size_t start, n;
	int closed;
} popt_path_t;

/* A set of paths, and after popt_optimise the order to draw them. */
typedef struct {
	popt_pt_t *pts;
	size_t npts, cappts;
	popt_path_t *paths;
	size_t npaths, cappaths;
	size_t *order;              /* after popt_optimise/popt_keep_order: path indices in drawing order */
	unsigned char *rev;         /* per order entry: 1 to draw the path backwards */
} popt_set_t;

/* What to do. */
typedef struct {
	int merge;                  /* join paths whose ends lie within merge_tol */
	double merge_tol;           /* plotter units */
	double simplify_tol;        /* Douglas-Peucker tolerance, plotter units; 0: duplicates only */
	int reorder;                /* nearest-end ordering with reversal */
	double budget_s;            /* 2-opt work budget in seconds of a reference core (pathopt.c: counted in moves, so deterministic; 0: no 2-opt) */
	int window;                 /* 2-opt neighbourhood (positions ahead), 0 = default 64 */
} popt_opts_t;

/* What it did: pen-up travel from the start point in plotter units. */
typedef struct {
	double travel_before;       /* in the input order */
	double travel_greedy;       /* after merging and nearest-end ordering */
	double travel_after;        /* after 2-opt */
	size_t paths_before, paths_after;
	double seconds;             /* wall time of popt_optimise */
	unsigned twoopt_passes;
} popt_stats_t;

/* Empty the set, keeping memory; free it. */
void popt_reset(popt_set_t *s);
void popt_free(popt_set_t *s);
/* Add a path of n >= 1 points. Returns 0 or -1 (out of memory). */
int popt_add(popt_set_t *s, const popt_pt_t *pts, size_t n, int closed);
/* Keep the input order (order = 0, 1, ...; nothing reversed). 0 or -1. */
int popt_keep_order(popt_set_t *s);
/* Optimise the set for a pen starting at start. Rewrites paths (merging, simplifying) and sets
 * order/rev. 0 or -1 (out of memory). */
int popt_optimise(popt_set_t *s, popt_pt_t start, const popt_opts_t *o, popt_stats_t *st);
/* Pen-up travel of the set in its current order from start (plotter units). */
double popt_travel(const popt_set_t *s, popt_pt_t start);
/* First and last point of the k-th path in drawing order (reversal applied). */
void popt_ends(const popt_set_t *s, size_t k, popt_pt_t *first, popt_pt_t *last);
/* Write the k-th path in drawing order into out (n points, plus the first again for a closed
 * path: out needs paths[order[k]].n + 1 slots). Returns the count written. */
size_t popt_get(const popt_set_t *s, size_t k, popt_pt_t *out);

#endif
