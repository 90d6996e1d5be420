/* dash.c: the §5.3 dash walk in closed form: boundaries found by arithmetic, pieces made only
 * where they can be seen, so the work is bounded by what a band or page can show. */
#include <string.h>
#include "geom/scan_int.h"

/* The pattern, with its prefix sums for the closed form. */
typedef struct {
	const int64_t *p;
	size_t n;                        /* even, >= 2 */
	int64_t period;                  /* p[0] + ... + p[n-1] */
	int64_t cum[2 * META_MAX_DASH + 1];
} pattern_t;

/* S(k, i) = p[k+1] + ... + p[k+i] (indices mod n): the pattern after entry k, i entries. */
static int64_t sum_after(const pattern_t *pt, size_t k, int64_t i)
{
	int64_t q = i / (int64_t)pt->n, r = i % (int64_t)pt->n;
	size_t a = (k + 1) % pt->n;
	int64_t s = q * pt->period;
	if (a + (size_t)r <= pt->n)
		s += pt->cum[a + (size_t)r] - pt->cum[a];
	else
		s += pt->period - pt->cum[a] + pt->cum[a + (size_t)r - pt->n];
	return s;
}

/* Boundary i of a segment entered with (k, rest): t_i = rest + S(k, i), one rounding. */
static double t_at(const pattern_t *pt, size_t k, double rest, int64_t i)
{
	return rest + (double)sum_after(pt, k, i);
}

/* The first i >= 0 with t_i >= x (strict = 0) or t_i > x (strict = 1); t_i grows with i. */
static int64_t first_from(const pattern_t *pt, size_t k, double rest, double x, int strict)
{
	double d = (x - rest) / (double)pt->period;
	int64_t i = 0;
	if (d > 2)
		i = ((int64_t)(d > 4e15 ? 4e15 : d) - 1) * (int64_t)pt->n;   /* t_i < x there */
	for (;; i++) {
		double t = t_at(pt, k, rest, i);
		if (strict ? t > x : t >= x)
			return i;
	}
}

/* Append (x, y) to the piece: a move when it is empty. */
static int add(scan_path_t *dp, int64_t x, int64_t y)
{
	return dp->nsubs ? scan_path_draw(dp, x, y) : scan_path_move(dp, x, y);
}

int scan_dash_walk(scan_path_t *dp, const int64_t *dash, size_t ndash, const scan_pt_t *pts, size_t n,
		int closed, const scan_dasher_t *w)
{
	pattern_t pt = { dash, ndash, 0, { 0 } };
	for (size_t k = 0; k < ndash; k++)
		pt.cum[k + 1] = pt.cum[k] + dash[k];
	pt.period = pt.cum[ndash];
	scan_path_reset(dp);
	size_t k = 0;
	double rest = (double)dash[0];
	int on = 1, rc = 0;
	size_t nseg = closed ? n : n - 1;
	for (size_t s = 0; s < nseg && rc == 0; s++) {
		scan_pt_t p = pts[s], q = pts[s + 1 == n ? 0 : s + 1];
		if (p.x == q.x && p.y == q.y)
			continue;
		double dx = (double)(q.x - p.x), dy = (double)(q.y - p.y);
		double len = sqrt(dx * dx + dy * dy);
		if (on && dp->nsubs == 0 && (rc = scan_path_move(dp, p.x, p.y)))
			break;
		int64_t m = first_from(&pt, k, rest, len, 0);   /* boundaries on the segment: t_i < len */
		double ta = 0, tb = len;
		int64_t ia = 0, ib = 0;
		if (w->window(w->user, p, q, len, &ta, &tb)) {
			ia = ta > 0 ? first_from(&pt, k, rest, ta, 0) : 0;
			ib = tb < len ? first_from(&pt, k, rest, tb, 1) : m;
			ia = ia > m ? m : ia;
			ib = ib > m ? m : ib < ia ? ia : ib;
		}
		/* boundaries before the window: the piece in progress ends at the first; a piece
		 * under way at the window's start began at the boundary before it */
		if (ia > 0) {
			if (on) {
				double f = t_at(&pt, k, rest, 0) / len;
				if ((rc = add(dp, p.x + scan_round(dx * f), p.y + scan_round(dy * f))) ||
						(rc = w->piece(w->user, dp)))
					break;
				scan_path_reset(dp);
			}
			if ((on ^ (int)(ia & 1)) && ia >= 1) {
				double f = t_at(&pt, k, rest, ia - 1) / len;
				if ((rc = scan_path_move(dp, p.x + scan_round(dx * f), p.y + scan_round(dy * f))))
					break;
			}
		}
		/* the boundaries in the window, one by one */
		for (int64_t i = ia; i < ib && rc == 0; i++) {
			double f = t_at(&pt, k, rest, i) / len;
			int64_t bx = p.x + scan_round(dx * f), by = p.y + scan_round(dy * f);
			if (on ^ (int)(i & 1)) {
				if (!(rc = add(dp, bx, by)))
					rc = w->piece(w->user, dp);
				scan_path_reset(dp);
			} else {
				scan_path_reset(dp);
				rc = scan_path_move(dp, bx, by);
			}
		}
		if (rc)
			break;
		/* after the window: a piece under way ends at the next boundary; later ones are out
		 * of sight, and one running on past q starts at q (its cap there cannot be seen) */
		if (ib < m) {
			if (on ^ (int)(ib & 1)) {
				double f = t_at(&pt, k, rest, ib) / len;
				if ((rc = add(dp, p.x + scan_round(dx * f), p.y + scan_round(dy * f))) ||
						(rc = w->piece(w->user, dp)))
					break;
			}
			scan_path_reset(dp);
		}
		double tm = t_at(&pt, k, rest, m);
		rest = tm - len;
		k = (k + (size_t)(m % (int64_t)ndash)) % ndash;
		on ^= (int)(m & 1);
		if (on && (rc = add(dp, q.x, q.y)))
			break;
	}
	if (rc == 0 && on && dp->nsubs)
		rc = w->piece(w->user, dp);
	scan_path_reset(dp);
	return rc;
}

int64_t scan_dash_period(const int64_t *dash, size_t ndash)
{
	int64_t s = 0;
	for (size_t k = 0; dash && k < ndash; k++)
		s += dash[k];
	return s;
}

/* ---- scan_dash_path: every piece, appended to a path ---- */

static int whole(void *user, scan_pt_t p, scan_pt_t q, double len, double *ta, double *tb)
{
	(void)user; (void)p; (void)q;
	*ta = 0;
	*tb = len;
	return 1;
}

static int append(void *user, scan_path_t *piece)
{
	scan_path_t *out = user;
	if (piece->nsubs == 0 || piece->subs[0].n < 2)
		return 0;
	const scan_pt_t *q = piece->pts + piece->subs[0].start;
	for (size_t k = 0; k < piece->subs[0].n; k++) {
		int rc = k ? scan_path_draw(out, q[k].x, q[k].y) : scan_path_move(out, q[k].x, q[k].y);
		if (rc)
			return rc;
	}
	return 0;
}

/* Copy subpath sub of p to out as it is. */
static int copy_sub(scan_path_t *out, const scan_path_t *p, const scan_subpath_t *sub)
{
	const scan_pt_t *q = p->pts + sub->start;
	for (size_t k = 0; k < sub->n; k++) {
		int rc = k ? scan_path_draw(out, q[k].x, q[k].y) : scan_path_move(out, q[k].x, q[k].y);
		if (rc)
			return rc;
	}
	if (sub->closed)
		out->subs[out->nsubs - 1].closed = 1;
	out->open = 0;
	return 0;
}

/* The part of p -> q inside the box (Liang-Barsky), widened by a few thousandths for the
 * rounding of the pieces' ends. */
int scan_clip_window(const double lo[2], const double hi[2], scan_pt_t p, scan_pt_t q, double len,
		double *ta, double *tb)
{
	double a[2] = { (double)p.x, (double)p.y }, d[2] = { (double)(q.x - p.x), (double)(q.y - p.y) };
	double u0 = 0, u1 = 1;
	for (int k = 0; k < 2; k++) {
		if (d[k] == 0) {
			if (a[k] < lo[k] || a[k] > hi[k])
				return 0;
			continue;
		}
		double e0 = (lo[k] - a[k]) / d[k], e1 = (hi[k] - a[k]) / d[k];
		if (e0 > e1) {
			double t = e0; e0 = e1; e1 = t;
		}
		if (e0 > u0)
			u0 = e0;
		if (e1 < u1)
			u1 = e1;
	}
	if (u0 > u1)
		return 0;
	*ta = u0 * len - 16.0;
	*tb = u1 * len + 16.0;
	if (*ta < 0)
		*ta = 0;
	if (*tb > len)
		*tb = len;
	return 1;
}

static int in_box(void *user, scan_pt_t p, scan_pt_t q, double len, double *ta, double *tb)
{
	const double *box = user;   /* lo x, lo y, hi x, hi y */
	return scan_clip_window(box, box + 2, p, q, len, ta, tb);
}

typedef struct {
	double box[4];
	scan_path_t *out;
} boxed_t;

static int boxed_window(void *user, scan_pt_t p, scan_pt_t q, double len, double *ta, double *tb)
{
	return in_box(((boxed_t *)user)->box, p, q, len, ta, tb);
}

static int boxed_append(void *user, scan_path_t *piece)
{
	return append(((boxed_t *)user)->out, piece);
}

static int dash_path(const scan_path_t *p, const int64_t *dash, size_t ndash, scan_path_t *out,
		const double *box);

int scan_dash_path(const scan_path_t *p, const int64_t *dash, size_t ndash, scan_path_t *out)
{
	return dash_path(p, dash, ndash, out, NULL);
}

int scan_dash_path_box(const scan_path_t *p, const int64_t *dash, size_t ndash, int64_t x0, int64_t y0,
		int64_t x1, int64_t y1, scan_path_t *out)
{
	double box[4] = { (double)x0, (double)y0, (double)x1, (double)y1 };
	return dash_path(p, dash, ndash, out, box);
}

/* Every piece of p's dashes (within box when it is not NULL) appended to out. */
static int dash_path(const scan_path_t *p, const int64_t *dash, size_t ndash, scan_path_t *out,
		const double *box)
{
	int solid = !dash || ndash == 0 || scan_dash_period(dash, ndash) < SCAN_DASH_MIN_PERIOD;
	scan_path_t dp = { 0 };
	boxed_t bx = { { 0, 0, 0, 0 }, out };
	if (box)
		memcpy(bx.box, box, sizeof bx.box);
	scan_dasher_t w = box ? (scan_dasher_t){ boxed_window, boxed_append, &bx } : (scan_dasher_t){ whole, append, out };
	int rc = 0;
	for (size_t k = 0; k < p->nsubs && rc == 0; k++) {
		const scan_subpath_t *sub = &p->subs[k];
		const scan_pt_t *q = p->pts + sub->start;
		if (sub->n < 2 && !sub->closed)
			continue;   /* a lone move paints nothing */
		size_t same = 1;
		while (same < sub->n && q[same].x == q[0].x && q[same].y == q[0].y)
			same++;
		if (solid || same == sub->n)
			rc = copy_sub(out, p, sub);   /* solid, or a dot */
		else
			rc = scan_dash_walk(&dp, dash, ndash, q, sub->n, sub->closed, &w);
		out->open = 0;
	}
	scan_path_free(&dp);
	return rc < 0 ? rc : 0;
}
