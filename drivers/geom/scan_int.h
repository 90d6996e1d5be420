/* scan_int.h: internals shared by scan.c, stroke.c, flatten.c and font.c (not public). */
#ifndef LOCUS_SCAN_INT_H
#define LOCUS_SCAN_INT_H
#include "geom/scan.h"

/* Scratch paths owned by the context. */
scan_path_t *scan_ctx_piece(scan_ctx_t *c);
scan_path_t *scan_ctx_dashed(scan_ctx_t *c);

/* Fill one contour of n points by rule; convex = 1 for a polygon known to be convex
 * (parallelograms, rectangles, triangles, discs): the same pixels, found without sorting
 * crossings. */
int scan_fill_piece(scan_ctx_t *c, const scan_band_t *b, const scan_pt_t *pts, size_t n, int rule,
		meta_rgb_t rgb, int convex);

/* What a dash walk reports to its user (dash.c). */
typedef struct {
	/* The part [ta, tb] (distance along it, thousandths, within [0, len]) of segment p -> q
	 * where pieces can be seen; return 0 when none can. Pieces outside it are not made. */
	int (*window)(void *user, scan_pt_t p, scan_pt_t q, double len, double *ta, double *tb);
	/* A finished piece: the first subpath of piece (1 or more points). Returns 0 or <0. */
	int (*piece)(void *user, scan_path_t *piece);
	void *user;
} scan_dasher_t;

/* The part of p -> q (length len) inside the box lo..hi, clipped by Liang-Barsky, as the
 * distances *ta..*tb along it widened by 16 thousandths for the rounding of the pieces' ends:
 * 1, or 0 when the segment misses the box. A dash walk's window (dash.c, stroke.c). */
int scan_clip_window(const double lo[2], const double hi[2], scan_pt_t p, scan_pt_t q, double len,
		double *ta, double *tb);

/* Walk one subpath of n points through the even dash list by §5.3, in closed form: the
 * boundaries on a segment are t_i = rest + (p[k+1] + ... + p[k+i]), so those outside the
 * window are skipped in O(1). dp is scratch for the piece being built. Returns 0 or <0. */
int scan_dash_walk(scan_path_t *dp, const int64_t *dash, size_t ndash, const scan_pt_t *pts, size_t n,
		int closed, const scan_dasher_t *w);
#endif
