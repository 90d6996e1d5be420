/* import_svg_path.c: SVG path data, points lists and transform lists, flattened to page pixels. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "import/svg_import.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define MAX_SEG 100000   /* chords per curve at most */

svg_mat_t svg_mat_mul(svg_mat_t m, svg_mat_t n)
{
	svg_mat_t r = {
		n.a * m.a + n.c * m.b, n.b * m.a + n.d * m.b,
		n.a * m.c + n.c * m.d, n.b * m.c + n.d * m.d,
		n.a * m.e + n.c * m.f + n.e, n.b * m.e + n.d * m.f + n.f
	};
	return r;
}

static void skip_wsp(const char **s)
{
	while (**s == ' ' || **s == '\t' || **s == '\n' || **s == '\r' || **s == '\f')
		(*s)++;
}

static void skip_comma_wsp(const char **s)
{
	skip_wsp(s);
	if (**s == ',') {
		(*s)++;
		skip_wsp(s);
	}
}

/* SVG's number: sign, digits with an optional fraction, an optional exponent. */
int svg_number(const char **s, double *v)
{
	const char *p = *s;
	if (*p == '+' || *p == '-')
		p++;
	int digits = 0;
	while (isdigit((unsigned char)*p))
		p++, digits++;
	if (*p == '.') {
		p++;
		while (isdigit((unsigned char)*p))
			p++, digits++;
	}
	if (!digits)
		return -1;
	if ((*p == 'e' || *p == 'E') && (isdigit((unsigned char)p[1]) ||
			((p[1] == '+' || p[1] == '-') && isdigit((unsigned char)p[2])))) {
		p += 2;
		while (isdigit((unsigned char)*p))
			p++;
	}
	char buf[64];
	size_t len = (size_t)(p - *s);
	if (len >= sizeof buf)
		len = sizeof buf - 1;   /* absurdly long digit runs: the value is what strtod makes of 63 */
	memcpy(buf, *s, len);
	buf[len] = 0;
	*v = strtod(buf, NULL);
	if (!isfinite(*v))
		return -1;
	*s = p;
	return 0;
}

/* ---- transform lists ---- */

int svg_transform_parse(const char *s, svg_mat_t *out)
{
	svg_mat_t m = { 1, 0, 0, 1, 0, 0 };
	*out = m;
	skip_wsp(&s);
	while (*s) {
		static const char *const names[] = { "matrix", "translate", "scale", "rotate", "skewX", "skewY" };
		int k;
		size_t len = 0;
		for (k = 0; k < 6; k++) {
			len = strlen(names[k]);
			if (!strncmp(s, names[k], len))
				break;
		}
		if (k == 6)
			return -1;
		s += len;
		skip_wsp(&s);
		if (*s++ != '(')
			return -1;
		double v[6];
		int n = 0;
		skip_wsp(&s);
		while (*s != ')') {
			if (n == 6 || svg_number(&s, &v[n]))
				return -1;
			n++;
			skip_comma_wsp(&s);
		}
		s++;
		svg_mat_t t = { 1, 0, 0, 1, 0, 0 };
		switch (k) {
		case 0:
			if (n != 6)
				return -1;
			t = (svg_mat_t){ v[0], v[1], v[2], v[3], v[4], v[5] };
			break;
		case 1:
			if (n != 1 && n != 2)
				return -1;
			t.e = v[0], t.f = n == 2 ? v[1] : 0;
			break;
		case 2:
			if (n != 1 && n != 2)
				return -1;
			t.a = v[0], t.d = n == 2 ? v[1] : v[0];
			break;
		case 3: {
			if (n != 1 && n != 3)
				return -1;
			double r = v[0] * M_PI / 180, c = cos(r), si = sin(r);
			t = (svg_mat_t){ c, si, -si, c, 0, 0 };
			if (n == 3) {   /* translate(cx,cy) rotate translate(-cx,-cy) */
				t.e = v[1] - c * v[1] + si * v[2];
				t.f = v[2] - si * v[1] - c * v[2];
			}
			break;
		}
		default:
			if (n != 1)
				return -1;
			if (k == 4)
				t.c = tan(v[0] * M_PI / 180);
			else
				t.b = tan(v[0] * M_PI / 180);
		}
		m = svg_mat_mul(t, m);   /* later transforms apply first */
		skip_comma_wsp(&s);
	}
	*out = m;
	return 0;
}

/* ---- geometry ---- */

static void put(svg_geom_t *g, double ux, double uy)
{
	if (g->oom)
		return;
	if (g->limit && g->n >= g->limit) {
		g->oom = 2;
		return;
	}
	if (dev_grow((void **)&g->pt, &g->cap, g->n + 1, sizeof *g->pt, 64)) {
		g->oom = 1;
		return;
	}
	g->pt[g->n].x = g->m.a * ux + g->m.c * uy + g->m.e;
	g->pt[g->n].y = g->m.b * ux + g->m.d * uy + g->m.f;
	g->n++;
}

int svg_geom_move(svg_geom_t *g, double x, double y)
{
	if (g->oom)
		return -1;
	if (dev_grow((void **)&g->sub, &g->subcap, g->nsub + 1, sizeof *g->sub, 16) ||
			!(g->closed = realloc(g->closed, g->subcap ? g->subcap : 1))) {
		g->oom = 1;
		return -1;
	}
	g->sub[g->nsub] = g->n;
	g->closed[g->nsub++] = 0;
	put(g, x, y);
	return g->oom ? -1 : 0;
}

int svg_geom_line(svg_geom_t *g, double x, double y)
{
	if (!g->nsub)
		return svg_geom_move(g, x, y);
	size_t n0 = g->n - g->sub[g->nsub - 1];
	double px = g->m.a * x + g->m.c * y + g->m.e, py = g->m.b * x + g->m.d * y + g->m.f;
	if (n0 >= 2 && g->pt[g->n - 1].x == px && g->pt[g->n - 1].y == py)
		return 0;   /* a repeated point (a zero-length subpath keeps its two, a dot) */
	put(g, x, y);
	return g->oom ? -1 : 0;
}

void svg_geom_close(svg_geom_t *g)
{
	if (g->nsub)
		g->closed[g->nsub - 1] = 1;
}

void svg_geom_free(svg_geom_t *g)
{
	free(g->pt);
	free(g->sub);
	free(g->closed);
	g->pt = NULL, g->sub = NULL, g->closed = NULL;
	g->n = g->cap = g->nsub = g->subcap = 0;
}

/* The largest stretch the map gives a length (its larger singular value). */
static double mat_norm(svg_mat_t m)
{
	double p = m.a * m.a + m.b * m.b + m.c * m.c + m.d * m.d;
	double q = m.a * m.d - m.b * m.c;
	double s = p * p / 4 - q * q;
	return sqrt(p / 2 + sqrt(s > 0 ? s : 0));
}

/* Chords for a curve whose second derivative is at most acc (pixels): uniform steps keep the
 * chord error under acc / (8 n^2) <= tol. */
static long chords(double acc, double tol)
{
	double n = ceil(sqrt(acc / (8 * tol)));
	return n < 1 || !isfinite(n) ? (isfinite(n) ? 1 : MAX_SEG) : n > MAX_SEG ? MAX_SEG : (long)n;
}

void svg_geom_cubic(svg_geom_t *g, double x0, double y0, double x1, double y1, double x2,
		double y2, double x3, double y3)
{
	double k = mat_norm(g->m);
	double ax = x0 - 2 * x1 + x2, ay = y0 - 2 * y1 + y2, bx = x1 - 2 * x2 + x3, by = y1 - 2 * y2 + y3;
	double acc = 6 * k * fmax(hypot(ax, ay), hypot(bx, by));
	long n = chords(acc, g->tol);
	for (long i = 1; i <= n; i++) {
		double t = (double)i / n, u = 1 - t;
		double b0 = u * u * u, b1 = 3 * u * u * t, b2 = 3 * u * t * t, b3 = t * t * t;
		svg_geom_line(g, b0 * x0 + b1 * x1 + b2 * x2 + b3 * x3, b0 * y0 + b1 * y1 + b2 * y2 + b3 * y3);
	}
}

void svg_geom_quad(svg_geom_t *g, double x0, double y0, double x1, double y1, double x2, double y2)
{
	double acc = 2 * mat_norm(g->m) * hypot(x0 - 2 * x1 + x2, y0 - 2 * y1 + y2);
	long n = chords(acc, g->tol);
	for (long i = 1; i <= n; i++) {
		double t = (double)i / n, u = 1 - t;
		svg_geom_line(g, u * u * x0 + 2 * u * t * x1 + t * t * x2, u * u * y0 + 2 * u * t * y1 + t * t * y2);
	}
}

/* Steps for sweep radians of an ellipse whose largest radius on the page is r pixels. */
static long arc_steps(double sweep, double r, double tol)
{
	if (r <= tol)
		return 1;
	double step = 2 * acos(1 - tol / r);
	double n = ceil(fabs(sweep) / step);
	return n < 1 ? 1 : n > MAX_SEG ? MAX_SEG : (long)n;
}

static void ell_points(svg_geom_t *g, double cx, double cy, double rx, double ry, double phi,
		double t0, double dt, int first)
{
	double r = fmax(rx, ry) * mat_norm(g->m);
	long n = arc_steps(dt, r, g->tol);
	double cp = cos(phi), sp = sin(phi);
	for (long i = first ? 0 : 1; i <= n; i++) {
		double t = t0 + dt * i / n, x = rx * cos(t), y = ry * sin(t);
		if (i == 0)
			svg_geom_move(g, cx + cp * x - sp * y, cy + sp * x + cp * y);
		else
			svg_geom_line(g, cx + cp * x - sp * y, cy + sp * x + cp * y);
	}
}

void svg_geom_ellipse(svg_geom_t *g, double cx, double cy, double rx, double ry)
{
	ell_points(g, cx, cy, rx, ry, 0, 0, 2 * M_PI, 1);
	svg_geom_close(g);
}

static double vec_angle(double ux, double uy, double vx, double vy)
{
	double a = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
	return a;
}

/* SVG 1.1 implementation notes F.6.5 and F.6.6. */
void svg_geom_arc(svg_geom_t *g, double x0, double y0, double rx, double ry, double phi_deg,
		int large, int sweep, double x, double y)
{
	if (x0 == x && y0 == y)
		return;
	rx = fabs(rx), ry = fabs(ry);
	if (rx == 0 || ry == 0) {
		svg_geom_line(g, x, y);
		return;
	}
	double phi = fmod(phi_deg, 360) * M_PI / 180, cp = cos(phi), sp = sin(phi);
	double dx = (x0 - x) / 2, dy = (y0 - y) / 2;
	double x1 = cp * dx + sp * dy, y1 = -sp * dx + cp * dy;
	double lambda = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
	if (lambda > 1) {
		rx *= sqrt(lambda);
		ry *= sqrt(lambda);
	}
	double num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
	double den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
	double co = num > 0 && den > 0 ? sqrt(num / den) : 0;
	if (large == sweep)
		co = -co;
	double cxp = co * rx * y1 / ry, cyp = -co * ry * x1 / rx;
	double cx = cp * cxp - sp * cyp + (x0 + x) / 2, cy = sp * cxp + cp * cyp + (y0 + y) / 2;
	double t1 = vec_angle(1, 0, (x1 - cxp) / rx, (y1 - cyp) / ry);
	double dt = vec_angle((x1 - cxp) / rx, (y1 - cyp) / ry, (-x1 - cxp) / rx, (-y1 - cyp) / ry);
	if (!sweep && dt > 0)
		dt -= 2 * M_PI;
	else if (sweep && dt < 0)
		dt += 2 * M_PI;
	ell_points(g, cx, cy, rx, ry, phi, t1, dt, 0);
	/* land exactly on the end point */
	if (!g->oom && g->n) {
		g->pt[g->n - 1].x = g->m.a * x + g->m.c * y + g->m.e;
		g->pt[g->n - 1].y = g->m.b * x + g->m.d * y + g->m.f;
	}
}

/* ---- path data ---- */

static int flag(const char **s, int *f)
{
	skip_comma_wsp(s);
	if (**s != '0' && **s != '1')
		return -1;
	*f = **s - '0';
	(*s)++;
	return 0;
}

static int nums(const char **s, double *v, int n)
{
	for (int i = 0; i < n; i++) {
		skip_comma_wsp(s);
		if (svg_number(s, &v[i]))
			return -1;
	}
	return 0;
}

int svg_path_data(svg_geom_t *g, const char *d)
{
	const char *s = d;
	double cx = 0, cy = 0, sx = 0, sy = 0;   /* current point, subpath start */
	double qx = 0, qy = 0;                   /* last control point for S/T */
	char prev = 0, cmd = 0;
	skip_wsp(&s);
	if (*s != 'M' && *s != 'm')
		return *s ? 1 : 0;
	while (*s && !g->oom) {
		skip_wsp(&s);
		if (!*s)
			break;
		if (isalpha((unsigned char)*s) && *s != 'e' && *s != 'E') {
			cmd = *s++;
			if (!strchr("MmZzLlHhVvCcSsQqTtAa", cmd))
				return 1;
		} else if (!cmd || cmd == 'Z' || cmd == 'z') {
			return 1;   /* numbers after Z without a command */
		} else {
			skip_comma_wsp(&s);
		}
		int rel = islower((unsigned char)cmd), up = toupper((unsigned char)cmd);
		double ox = rel ? cx : 0, oy = rel ? cy : 0, v[7];
		int fl, fs;
		const char *at = s;
		switch (up) {
		case 'Z':
			svg_geom_close(g);
			cx = sx, cy = sy;
			break;
		case 'M':
			if (nums(&s, v, 2))
				return 1;
			cx = sx = ox + v[0], cy = sy = oy + v[1];
			svg_geom_move(g, cx, cy);
			cmd = rel ? 'l' : 'L';   /* further pairs are lines */
			break;
		case 'L': case 'T':
			if (nums(&s, v, 2))
				return 1;
			if (prev == 'Z' || prev == 'z')
				svg_geom_move(g, cx, cy);
			if (up == 'T') {
				double px = cx, py = cy;
				if (strchr("QqTt", prev))
					px = 2 * cx - qx, py = 2 * cy - qy;
				svg_geom_quad(g, cx, cy, px, py, ox + v[0], oy + v[1]);
				qx = px, qy = py;
			} else {
				svg_geom_line(g, ox + v[0], oy + v[1]);
			}
			cx = ox + v[0], cy = oy + v[1];
			break;
		case 'H': case 'V':
			if (nums(&s, v, 1))
				return 1;
			if (prev == 'Z' || prev == 'z')
				svg_geom_move(g, cx, cy);
			if (up == 'H')
				cx = ox + v[0];
			else
				cy = oy + v[0];
			svg_geom_line(g, cx, cy);
			break;
		case 'C': case 'S': case 'Q': {
			int k = up == 'C' ? 6 : 4;
			if (nums(&s, v, k))
				return 1;
			if (prev == 'Z' || prev == 'z')
				svg_geom_move(g, cx, cy);
			double x1, y1, x2, y2, x, y;
			if (up == 'S') {
				x1 = cx, y1 = cy;
				if (strchr("CcSs", prev))
					x1 = 2 * cx - qx, y1 = 2 * cy - qy;
				x2 = ox + v[0], y2 = oy + v[1], x = ox + v[2], y = oy + v[3];
			} else if (up == 'Q') {
				x1 = x2 = ox + v[0], y1 = y2 = oy + v[1], x = ox + v[2], y = oy + v[3];
			} else {
				x1 = ox + v[0], y1 = oy + v[1], x2 = ox + v[2], y2 = oy + v[3], x = ox + v[4], y = oy + v[5];
			}
			if (up == 'Q')
				svg_geom_quad(g, cx, cy, x1, y1, x, y);
			else
				svg_geom_cubic(g, cx, cy, x1, y1, x2, y2, x, y);
			qx = x2, qy = y2;
			cx = x, cy = y;
			break;
		}
		case 'A':
			if (nums(&s, v, 3) || flag(&s, &fl) || flag(&s, &fs) || nums(&s, v + 3, 2))
				return 1;
			if (prev == 'Z' || prev == 'z')
				svg_geom_move(g, cx, cy);
			svg_geom_arc(g, cx, cy, v[0], v[1], v[2], fl, fs, ox + v[3], oy + v[4]);
			cx = ox + v[3], cy = oy + v[4];
			break;
		}
		(void)at;
		prev = cmd == 'l' && up == 'M' ? 'm' : cmd == 'L' && up == 'M' ? 'M' : cmd;
		if (up == 'M')
			prev = rel ? 'm' : 'M';
		skip_wsp(&s);
	}
	return g->oom ? -1 : 0;
}

int svg_points(svg_geom_t *g, const char *s, int close)
{
	double v[2];
	int n = 0, bad = 0;
	skip_wsp(&s);
	while (*s) {
		if (nums(&s, v, 2)) {
			bad = 1;
			break;
		}
		if (n++ == 0)
			svg_geom_move(g, v[0], v[1]);
		else
			svg_geom_line(g, v[0], v[1]);
		skip_comma_wsp(&s);
	}
	if (close && n)
		svg_geom_close(g);
	return bad;
}
