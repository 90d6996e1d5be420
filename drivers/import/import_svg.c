/* import_svg.c: SVG to meta: libxml2's tree walked with the cascade, shapes flattened to items. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/hash.h>
#include "util/grow.h"
#include "geom/scan.h"
#include "import/svg_import.h"

#define MAX_BYTES (64u << 20)   /* an SVG file larger than this is refused */
#define MAX_POINTS (1u << 24)   /* flattened points in the whole drawing */
#define MAX_VISITS 1000000      /* elements drawn, use references expanded */
#define MAX_USE_DEPTH 32
#define FONT_SIZE 16.0          /* px: the em of a drawing that sets no font-size */
#define SVG_NS "http://www.w3.org/2000/svg"

typedef struct { int kind; uint32_t rgb; double a; } paint_t;   /* kind 0 none, 1 colour; a its alpha */

/* The computed style an element hands its children. */
typedef struct {
	paint_t fill, stroke;
	double fill_op, stroke_op, opacity;
	int rule, cap, join, visible;
	double width, miter, dash[16], dashoff, font;
	int ndash;
	uint32_t color;
	int anchor;             /* text-anchor: 0 start, 1 middle, 2 end */
	int spacing;            /* letter-spacing or word-spacing other than normal (not drawn) */
} style_t;

/* The viewport lengths in percent refer to. */
typedef struct { double w, h; } vp_t;

typedef struct {
	svg_doc_t d;
	xmlDoc *doc;
	xmlHashTable *ids;
	svg_sheet_t *sheet;
	const char *warned[32];
	int nwarned;
	long visits;
	size_t points;
	int use_depth;
	xmlNode *stack[MAX_USE_DEPTH];
	int layer, inkscape_layers;
	int fatal;              /* -65 or -70 once a limit is passed */
	char *err;
	size_t errlen;
	svg_mat_t page;         /* root user space to page pixels */
	long style_line;        /* the first <style> element's line */
	svg_pt_t clip[16][4];   /* viewports of nested svg and symbol on the page (convex quads) */
	int nclip;
	char *transform;        /* what compute() found for the element it was last called on */
} st_t;

static void warn_kind(st_t *s, const char *kind, long line)
{
	for (int k = 0; k < s->nwarned; k++)
		if (!strcmp(s->warned[k], kind))
			return;
	if (s->nwarned < 32)
		s->warned[s->nwarned++] = kind;
	if (!s->d.o->quiet)
		fprintf(stderr, "%s:%ld: warning: %s; further ones not named\n", s->d.name, line, kind);
}

static void sheet_warn(void *u, const char *kind)
{
	st_t *s = u;
	warn_kind(s, kind, s->style_line);
}

static int is_svg(const xmlNode *n, const char *name)
{
	return n->type == XML_ELEMENT_NODE && (!n->ns || !strcmp((const char *)n->ns->href, SVG_NS)) &&
		(!name || !strcmp((const char *)n->name, name));
}

static char *prop(xmlNode *n, const char *name)
{
	return (char *)xmlGetProp(n, (const xmlChar *)name);
}

static char *href(xmlNode *n)
{
	char *v = (char *)xmlGetNsProp(n, (const xmlChar *)"href", (const xmlChar *)"http://www.w3.org/1999/xlink");
	return v ? v : prop(n, "href");
}

static xmlNode *by_ref(st_t *s, const char *ref)
{
	while (ref && isspace((unsigned char)*ref))
		ref++;
	if (!ref || *ref != '#')
		return NULL;
	char id[256];
	size_t n = strcspn(ref + 1, " \t\r\n)");
	if (n >= sizeof id)
		return NULL;
	memcpy(id, ref + 1, n);
	id[n] = 0;
	return xmlHashLookup(s->ids, (const xmlChar *)id);
}

/* ---- lengths ---- */

enum { AX_X, AX_Y, AX_D };

/* A length with its unit in user units (px); -1 when it is not one. */
static int length(const char *v, const vp_t *vp, int axis, double font, double *out)
{
	if (!v)
		return -1;
	const char *p = v;
	while (isspace((unsigned char)*p))
		p++;
	double x;
	if (svg_number(&p, &x))
		return -1;
	static const struct { const char *u; double f; } units[] = {
		{ "px", 1 }, { "mm", 96 / 25.4 }, { "cm", 96 / 2.54 }, { "in", 96 }, { "pt", 96 / 72.0 },
		{ "pc", 16 }, { "Q", 96 / 101.6 },
	};
	size_t ul = 0;
	while (isalpha((unsigned char)p[ul]) || p[ul] == '%')
		ul++;
	double f = 1;
	if (ul == 1 && *p == '%') {
		double ref = axis == AX_X ? vp->w : axis == AX_Y ? vp->h : sqrt((vp->w * vp->w + vp->h * vp->h) / 2);
		f = ref / 100;
	} else if (ul == 2 && !strncmp(p, "em", 2)) {
		f = font;
	} else if (ul == 2 && !strncmp(p, "ex", 2)) {
		f = font / 2;
	} else if (ul) {
		size_t k;
		for (k = 0; k < sizeof units / sizeof *units; k++)
			if (strlen(units[k].u) == ul && !strncmp(p, units[k].u, ul))
				break;
		if (k == sizeof units / sizeof *units)
			return -1;
		f = units[k].f;
	}
	p += ul;
	while (isspace((unsigned char)*p))
		p++;
	if (*p)
		return -1;
	*out = x * f;
	return 0;
}

static double attr_len(xmlNode *n, const char *name, const vp_t *vp, int axis, double font, double dflt)
{
	char *v = prop(n, name);
	double x = dflt;
	if (v && length(v, vp, axis, font, &x))
		x = dflt;
	xmlFree(v);
	return x;
}

/* ---- paint and style ---- */

static double opacity(const char *v, double dflt)
{
	const char *p = v;
	double x;
	while (isspace((unsigned char)*p))
		p++;
	if (svg_number(&p, &x))
		return dflt;
	if (*p == '%')
		x /= 100, p++;
	while (isspace((unsigned char)*p))
		p++;
	return *p ? dflt : fmin(fmax(x, 0), 1);
}

/* A gradient's colour for a flat fallback: the mean of its stops (following href), else grey. */
static uint32_t gradient_colour(st_t *s, xmlNode *g, double *alpha)
{
	*alpha = 1;
	for (int hop = 0; g && hop < 8; hop++) {
		double sum[3] = { 0, 0, 0 }, asum = 0;
		int n = 0;
		for (xmlNode *c = g->children; c; c = c->next) {
			if (!is_svg(c, "stop"))
				continue;
			char *sc = prop(c, "stop-color"), *st = prop(c, "style"), *so = prop(c, "stop-opacity");
			uint32_t rgb = 0;
			double a = 1, op = so ? opacity(so, 1) : 1;
			const char *src = sc;
			char *q = st ? strstr(st, "stop-color:") : NULL;
			if (q)
				src = q + 11;
			char buf[64] = "black";
			if (src) {
				size_t m = strcspn(src, ";");
				snprintf(buf, sizeof buf, "%.*s", (int)(m < 63 ? m : 63), src);
			}
			if (svg_colour(buf, &rgb, &a))
				rgb = 0, a = 1;
			for (int k = 0; k < 3; k++)
				sum[k] += (rgb >> (16 - 8 * k) & 255);
			asum += a * op;
			n++;
			xmlFree(sc);
			xmlFree(st);
			xmlFree(so);
		}
		if (n) {
			*alpha = asum / n;
			return (uint32_t)lround(sum[0] / n) << 16 | (uint32_t)lround(sum[1] / n) << 8 | (uint32_t)lround(sum[2] / n);
		}
		char *h = href(g);
		g = by_ref(s, h);
		xmlFree(h);
	}
	return 0x808080;
}

/* Parse a paint value into *p; 0, or -1 when invalid (the property is then not set). */
static int paint(st_t *s, const char *v, const style_t *st, paint_t *p, long line)
{
	while (isspace((unsigned char)*v))
		v++;
	double a = 1;
	if (!strcasecmp(v, "none") || !strcasecmp(v, "transparent")) {
		p->kind = 0;
		return 0;
	}
	if (!strcasecmp(v, "currentColor")) {
		p->kind = 1, p->rgb = st->color, p->a = 1;
		return 0;
	}
	if (!strncmp(v, "url(", 4)) {
		xmlNode *r = by_ref(s, v + 4);
		const char *fb = strchr(v, ')');
		fb = fb ? fb + 1 : "";
		while (isspace((unsigned char)*fb))
			fb++;
		if (r && (is_svg(r, "linearGradient") || is_svg(r, "radialGradient"))) {
			warn_kind(s, "gradient paint (drawn in the mean of its stops' colours)", line);
			p->kind = 1, p->rgb = gradient_colour(s, r, &a), p->a = a;
			if (a == 0)
				p->kind = 0;
			return 0;
		}
		if (r && is_svg(r, "pattern"))
			warn_kind(s, "pattern paint (drawn in its fallback colour, else left out)", line);
		else
			warn_kind(s, "paint server this reader lacks or a missing reference (fallback colour, else none)", line);
		if (*fb)
			return paint(s, fb, st, p, line);
		p->kind = 0;
		return 0;
	}
	uint32_t rgb;
	if (svg_colour(v, &rgb, &a))
		return -1;
	p->kind = a > 0, p->rgb = rgb, p->a = a;
	return 0;
}

static int keyword(const char *v, const char *const *kw, int n)
{
	while (isspace((unsigned char)*v))
		v++;
	for (int k = 0; k < n; k++)
		if (!strcmp(v, kw[k]))
			return k;
	return -1;
}

/* The element's style from its parent's: cascade, then each property parsed or inherited. */
static void compute(st_t *s, xmlNode *el, const style_t *parent, const vp_t *vp, style_t *st,
		int *display, char **origin)
{
	char *v[SP_NPROP];
	svg_cascade(s->sheet, el, v);
	*st = *parent;
	st->opacity = parent->opacity;
	*display = 1;
	long line = xmlGetLineNo(el);
	for (int k = 0; k < SP_NPROP; k++)
		if (v[k] && !strcmp(v[k], "inherit")) {
			free(v[k]);
			v[k] = NULL;
		}
	if (v[SP_FONT_SIZE]) {
		double f;
		if (!length(v[SP_FONT_SIZE], vp, AX_D, parent->font, &f) && f > 0)
			st->font = f;
	}
	if (v[SP_COLOR]) {
		uint32_t rgb;
		double a;
		if (!svg_colour(v[SP_COLOR], &rgb, &a))
			st->color = rgb;
	}
	if (v[SP_FILL])
		paint(s, v[SP_FILL], st, &st->fill, line);
	if (v[SP_STROKE])
		paint(s, v[SP_STROKE], st, &st->stroke, line);
	if (v[SP_FILL_OPACITY])
		st->fill_op = opacity(v[SP_FILL_OPACITY], st->fill_op);
	if (v[SP_STROKE_OPACITY])
		st->stroke_op = opacity(v[SP_STROKE_OPACITY], st->stroke_op);
	if (v[SP_OPACITY])
		st->opacity *= opacity(v[SP_OPACITY], 1);
	static const char *const rules[] = { "evenodd", "nonzero" }, *const caps[] = { "butt", "round", "square" },
		*const joins[] = { "miter", "round", "bevel", "miter-clip", "arcs" },
		*const vis[] = { "visible", "hidden", "collapse" };
	int k;
	if (v[SP_FILL_RULE] && (k = keyword(v[SP_FILL_RULE], rules, 2)) >= 0)
		st->rule = k == 0 ? META_RULE_EVEN_ODD : META_RULE_NON_ZERO;
	if (v[SP_LINECAP] && (k = keyword(v[SP_LINECAP], caps, 3)) >= 0)
		st->cap = k == 0 ? META_CAP_BUTT : k == 1 ? META_CAP_ROUND : META_CAP_SQUARE;
	if (v[SP_LINEJOIN] && (k = keyword(v[SP_LINEJOIN], joins, 5)) >= 0)
		st->join = k == 1 ? META_JOIN_ROUND : k == 2 ? META_JOIN_BEVEL : META_JOIN_MITER;
	if (v[SP_VISIBILITY] && (k = keyword(v[SP_VISIBILITY], vis, 3)) >= 0)
		st->visible = k == 0;
	static const char *const anchors[] = { "start", "middle", "end" };
	if (v[SP_TEXT_ANCHOR] && (k = keyword(v[SP_TEXT_ANCHOR], anchors, 3)) >= 0)
		st->anchor = k;
	for (int p = SP_LETTER_SPACING; p <= SP_WORD_SPACING; p++)
		if (v[p]) {
			double sp;
			if (keyword(v[p], (const char *const[]){ "normal" }, 1) == 0)
				st->spacing = 0;
			else if (!length(v[p], vp, AX_D, st->font, &sp))
				st->spacing = sp != 0;
		}
	if (v[SP_DISPLAY] && keyword(v[SP_DISPLAY], (const char *const[]){ "none" }, 1) == 0)
		*display = 0;
	double x;
	if (v[SP_STROKE_WIDTH] && !length(v[SP_STROKE_WIDTH], vp, AX_D, st->font, &x) && x >= 0)
		st->width = x;
	if (v[SP_MITERLIMIT]) {
		const char *p = v[SP_MITERLIMIT];
		if (!svg_number(&p, &x) && !*p && x >= 1)
			st->miter = x;
	}
	if (v[SP_DASHOFFSET] && !length(v[SP_DASHOFFSET], vp, AX_D, st->font, &x))
		st->dashoff = x;
	if (v[SP_DASHARRAY]) {
		double d[32];
		int n = 0, bad = 0;
		char *p = v[SP_DASHARRAY];
		if (keyword(p, (const char *const[]){ "none" }, 1) == 0) {
			st->ndash = 0;
		} else {
			for (char *t = strtok(p, ", \t\r\n"); t; t = strtok(NULL, ", \t\r\n")) {
				if (n == 16 || length(t, vp, AX_D, st->font, &d[n]) || d[n] < 0)
					bad = 1;
				else
					n++;
			}
			if (!bad && n) {
				memcpy(st->dash, d, (size_t)n * sizeof *d);
				st->ndash = n;
			}
		}
	}
	if (v[SP_CLIP_PATH] && strncmp(v[SP_CLIP_PATH], "none", 4))
		warn_kind(s, "clip-path (drawn unclipped)", line);
	if (v[SP_MASK] && strncmp(v[SP_MASK], "none", 4))
		warn_kind(s, "mask (drawn unmasked)", line);
	if (v[SP_FILTER] && strncmp(v[SP_FILTER], "none", 4))
		warn_kind(s, "filter effect (drawn without it)", line);
	for (k = SP_MARKER_START; k <= SP_MARKER_END; k++)
		if (v[k] && strncmp(v[k], "none", 4))
			warn_kind(s, "markers (left out)", line);
	*origin = v[SP_TRANSFORM_ORIGIN];
	v[SP_TRANSFORM_ORIGIN] = NULL;
	s->transform = v[SP_TRANSFORM];   /* the attribute, or a sheet's or style's transform */
	v[SP_TRANSFORM] = NULL;
	for (k = 0; k < SP_NPROP; k++)
		free(v[k]);
}

/* ---- emitting items ---- */

static uint32_t over_white(uint32_t rgb, double a)
{
	uint32_t r = 0;
	for (int sh = 16; sh >= 0; sh -= 8) {
		double c = ((rgb >> sh) & 255) * a + 255 * (1 - a);
		r |= (uint32_t)lround(c) << sh;
	}
	return r;
}

static int add_item(st_t *s, svg_item_t *it)
{
	if (dev_grow((void **)&s->d.it, &s->d.cap, s->d.n + 1, sizeof *s->d.it, 64))
		return -1;
	s->d.it[s->d.n++] = *it;
	return 0;
}


/* ---- clipping to nested viewports (convex quadrilaterals on the page) ---- */

static double side(const svg_pt_t *q, int k, svg_pt_t a)
{
	svg_pt_t p0 = q[k], p1 = q[(k + 1) % 4];
	double area = (q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[1].y - q[0].y) * (q[2].x - q[0].x);
	double c = (p1.x - p0.x) * (a.y - p0.y) - (p1.y - p0.y) * (a.x - p0.x);
	return area < 0 ? -c : c;   /* >= 0 inside */
}

/* g clipped to q: fills polygon by polygon (Sutherland-Hodgman), strokes segment by segment. */
static int clip_geom(svg_geom_t *g, const svg_pt_t *q, int fill)
{
	svg_geom_t o = { .tol = g->tol, .m = { 1, 0, 0, 1, 0, 0 }, .limit = g->limit };
	svg_pt_t *a = malloc((g->n * 2 + 16) * sizeof *a), *b = malloc((g->n * 2 + 16) * sizeof *b);
	if (!a || !b) {
		free(a), free(b);
		return -1;
	}
	for (size_t s = 0; s < g->nsub; s++) {
		size_t i0 = g->sub[s], i1 = s + 1 < g->nsub ? g->sub[s + 1] : g->n, n = i1 - i0;
		if (fill) {
			memcpy(a, g->pt + i0, n * sizeof *a);
			for (int k = 0; k < 4 && n; k++) {
				size_t m = 0;
				for (size_t i = 0; i < n; i++) {
					svg_pt_t c = a[i], p = a[(i + n - 1) % n];
					double sc = side(q, k, c), sp = side(q, k, p);
					if ((sc >= 0) != (sp >= 0)) {
						double t = sp / (sp - sc);
						b[m++] = (svg_pt_t){ p.x + t * (c.x - p.x), p.y + t * (c.y - p.y) };
					}
					if (sc >= 0)
						b[m++] = c;
				}
				svg_pt_t *t = a;
				a = b, b = t, n = m;
			}
			for (size_t i = 0; i < n; i++)
				i ? svg_geom_line(&o, a[i].x, a[i].y) : svg_geom_move(&o, a[i].x, a[i].y);
			if (n)
				svg_geom_close(&o);
			continue;
		}
		size_t m = n + (g->closed[s] && n > 1 ? 1 : 0);
		int open = 0, whole = 1;
		if (n == 1) {   /* a dot */
			int in = 1;
			for (int k = 0; k < 4; k++)
				in &= side(q, k, g->pt[i0]) >= 0;
			if (in) {
				svg_geom_move(&o, g->pt[i0].x, g->pt[i0].y);
				if (g->closed[s])
					svg_geom_close(&o);
			}
			continue;
		}
		size_t first = o.nsub;
		for (size_t j = 1; j < m; j++) {
			svg_pt_t P = g->pt[i0 + j - 1], Q = g->pt[j < n ? i0 + j : i0];
			double t0 = 0, t1 = 1;
			for (int k = 0; k < 4 && t0 <= t1; k++) {
				double sp = side(q, k, P), sq = side(q, k, Q);
				if (sp < 0 && sq < 0)
					t1 = -1;
				else if (sp < 0)
					t0 = fmax(t0, sp / (sp - sq));
				else if (sq < 0)
					t1 = fmin(t1, sp / (sp - sq));
			}
			if (t0 > t1) {
				open = 0, whole = 0;
				continue;
			}
			if (t0 > 0 || t1 < 1)
				whole = 0;
			if (!open || t0 > 0)
				svg_geom_move(&o, P.x + t0 * (Q.x - P.x), P.y + t0 * (Q.y - P.y));
			svg_geom_line(&o, P.x + t1 * (Q.x - P.x), P.y + t1 * (Q.y - P.y));
			open = t1 >= 1;
		}
		if (whole && g->closed[s] && o.nsub == first + 1) {
			o.n--;
			svg_geom_close(&o);
		}
	}
	free(a), free(b);
	if (o.oom) {
		svg_geom_free(&o);
		return -1;
	}
	svg_geom_free(g);
	*g = o;
	return 0;
}

static void push_clip(st_t *s, svg_mat_t m, double x, double y, double w, double h, xmlNode *el)
{
	char *ov = prop(el, "overflow"), *st = prop(el, "style");
	int visible = (ov && (!strcmp(ov, "visible") || !strcmp(ov, "auto"))) || (st && strstr(st, "overflow:visible"));
	xmlFree(ov);
	xmlFree(st);
	if (visible || s->nclip == 16)
		return;
	double px[4] = { x, x + w, x + w, x }, py[4] = { y, y, y + h, y + h };
	for (int k = 0; k < 4; k++)
		s->clip[s->nclip][k] = (svg_pt_t){ m.a * px[k] + m.c * py[k] + m.e, m.b * px[k] + m.d * py[k] + m.f };
	s->nclip++;
}

/* Draw the geometry made by fn with the element's fill and stroke. */
static void draw(st_t *s, xmlNode *el, const style_t *st, svg_mat_t m,
		int (*fn)(st_t *, xmlNode *, svg_geom_t *, const vp_t *, double), const vp_t *vp)
{
	if (!st->visible || s->fatal)
		return;
	double fa = st->fill_op * st->opacity * st->fill.a, sa = st->stroke_op * st->opacity * st->stroke.a;
	int want_fill = st->fill.kind && fa > 0, want_stroke = st->stroke.kind && sa > 0 && st->width > 0;
	if (!want_fill && !want_stroke)
		return;
	double det = fabs(m.a * m.d - m.b * m.c), k = sqrt(det);
	svg_geom_t g = { .tol = s->d.o->tol_mm * s->d.px_per_mm, .m = m, .limit = MAX_POINTS - s->points };
	int bad = fn(s, el, &g, vp, st->font);
	if (g.oom) {
		svg_geom_free(&g);
		s->fatal = g.oom == 2 ? -65 : -70;
		if (g.oom == 2)
			snprintf(s->err, s->errlen, "%s:%ld:1: expected a drawing of at most %u points once flattened, found more",
					s->d.name, xmlGetLineNo(el), MAX_POINTS);
		else
			snprintf(s->err, s->errlen, "locus-meta: out of memory importing %s", s->d.name);
		return;
	}
	if (bad)
		warn_kind(s, "path data with an error (drawn up to it)", xmlGetLineNo(el));
	s->points += g.n;
	int area = 0;
	for (size_t i = 0; i < g.nsub; i++)
		area |= (i + 1 < g.nsub ? g.sub[i + 1] : g.n) - g.sub[i] >= 3;
	if (!area && want_fill && !want_stroke)
		g.nsub = 0;
	want_fill &= area;
	if (!g.nsub) {
		svg_geom_free(&g);
		return;
	}
	svg_item_t it = { .layer = s->layer, .miter = st->miter, .cap = st->cap, .join = st->join,
		.rule = st->rule };
	if (want_fill) {
		it.kind = SVGI_FILL;
		it.stroked = want_stroke;
		it.src_rgb = st->fill.rgb;
		it.rgb = over_white(st->fill.rgb, fa);
		it.g = g;
		if (want_stroke) {   /* the stroke gets its own copy */
			svg_geom_t c = g;
			c.pt = malloc(g.n * sizeof *g.pt);
			c.sub = malloc(g.nsub * sizeof *g.sub);
			c.closed = malloc(g.nsub);
			if (!c.pt || !c.sub || !c.closed) {
				svg_geom_free(&c);
				want_stroke = 0;
				it.stroked = 0;
			} else {
				memcpy(c.pt, g.pt, g.n * sizeof *g.pt);
				memcpy(c.sub, g.sub, g.nsub * sizeof *g.sub);
				memcpy(c.closed, g.closed, g.nsub);
				c.cap = g.n, c.subcap = g.nsub;
				g = c;
			}
		}
		for (int c = 0; c < s->nclip && !s->fatal; c++)
			if (clip_geom(&it.g, s->clip[c], 1))
				s->fatal = -70;
		if (s->fatal || add_item(s, &it)) {
			svg_geom_free(&it.g);
			s->fatal = -70;
		}
	}
	if (want_stroke && !s->fatal) {
		it.kind = SVGI_STROKE;
		it.stroked = 0;
		it.src_rgb = st->stroke.rgb;
		it.rgb = over_white(st->stroke.rgb, sa);
		it.width = st->width * k;
		for (int c = 0; c < s->nclip && !s->fatal; c++)
			if (clip_geom(&g, s->clip[c], 0))
				s->fatal = -70;
		if (st->ndash && !s->fatal) {
			double dash[32], sum = 0;
			int n = st->ndash;
			for (int i = 0; i < n; i++)
				dash[i] = dash[i + n] = st->dash[i] * k, sum += st->dash[i];
			if (n % 2)
				n *= 2;
			if (sum > 0 && svg_dash_split(&g, dash, n, st->dashoff * k))
				s->fatal = -70;
		}
		it.g = g;
		if (s->fatal || add_item(s, &it)) {
			svg_geom_free(&it.g);
			s->fatal = -70;
		}
	} else if (!want_fill) {
		svg_geom_free(&g);
	}
}

/* ---- shapes ---- */

static int g_path(st_t *s, xmlNode *el, svg_geom_t *g, const vp_t *vp, double font)
{
	(void)s, (void)vp, (void)font;
	char *d = prop(el, "d");
	int r = d ? svg_path_data(g, d) : 0;
	xmlFree(d);
	return r > 0;
}

static int g_rect(st_t *s, xmlNode *el, svg_geom_t *g, const vp_t *vp, double font)
{
	(void)s;
	double x = attr_len(el, "x", vp, AX_X, font, 0), y = attr_len(el, "y", vp, AX_Y, font, 0);
	double w = attr_len(el, "width", vp, AX_X, font, 0), h = attr_len(el, "height", vp, AX_Y, font, 0);
	double rx = attr_len(el, "rx", vp, AX_X, font, -1), ry = attr_len(el, "ry", vp, AX_Y, font, -1);
	if (w <= 0 || h <= 0)
		return 0;
	if (rx < 0 && ry < 0)
		rx = ry = 0;
	else if (rx < 0)
		rx = ry;
	else if (ry < 0)
		ry = rx;
	rx = fmin(rx, w / 2), ry = fmin(ry, h / 2);
	if (rx <= 0 || ry <= 0) {
		svg_geom_move(g, x, y);
		svg_geom_line(g, x + w, y);
		svg_geom_line(g, x + w, y + h);
		svg_geom_line(g, x, y + h);
	} else {
		svg_geom_move(g, x + rx, y);
		svg_geom_line(g, x + w - rx, y);
		svg_geom_arc(g, x + w - rx, y, rx, ry, 0, 0, 1, x + w, y + ry);
		svg_geom_line(g, x + w, y + h - ry);
		svg_geom_arc(g, x + w, y + h - ry, rx, ry, 0, 0, 1, x + w - rx, y + h);
		svg_geom_line(g, x + rx, y + h);
		svg_geom_arc(g, x + rx, y + h, rx, ry, 0, 0, 1, x, y + h - ry);
		svg_geom_line(g, x, y + ry);
		svg_geom_arc(g, x, y + ry, rx, ry, 0, 0, 1, x + rx, y);
	}
	svg_geom_close(g);
	return 0;
}

static int g_ellipse(st_t *s, xmlNode *el, svg_geom_t *g, const vp_t *vp, double font)
{
	(void)s;
	double cx = attr_len(el, "cx", vp, AX_X, font, 0), cy = attr_len(el, "cy", vp, AX_Y, font, 0);
	double rx, ry;
	if (!strcmp((const char *)el->name, "circle")) {
		rx = ry = attr_len(el, "r", vp, AX_D, font, 0);
	} else {
		rx = attr_len(el, "rx", vp, AX_X, font, -1), ry = attr_len(el, "ry", vp, AX_Y, font, -1);
		if (rx < 0)
			rx = ry;
		if (ry < 0)
			ry = rx;
	}
	if (rx > 0 && ry > 0)
		svg_geom_ellipse(g, cx, cy, rx, ry);
	return 0;
}

static int g_line(st_t *s, xmlNode *el, svg_geom_t *g, const vp_t *vp, double font)
{
	(void)s;
	svg_geom_move(g, attr_len(el, "x1", vp, AX_X, font, 0), attr_len(el, "y1", vp, AX_Y, font, 0));
	svg_geom_line(g, attr_len(el, "x2", vp, AX_X, font, 0), attr_len(el, "y2", vp, AX_Y, font, 0));
	return 0;
}

static int g_poly(st_t *s, xmlNode *el, svg_geom_t *g, const vp_t *vp, double font)
{
	(void)s, (void)vp, (void)font;
	char *p = prop(el, "points");
	int r = p ? svg_points(g, p, !strcmp((const char *)el->name, "polygon")) : 0;
	xmlFree(p);
	return r;
}

/* ---- structure ---- */

/* viewBox + preserveAspectRatio into the map from the box to the viewport x, y, w, h. */
static int viewbox(xmlNode *el, double x, double y, double w, double h, svg_mat_t *m, vp_t *vp)
{
	char *vb = prop(el, "viewBox");
	double v[4];
	int n = 0;
	const char *p = vb;
	while (p && n < 4) {
		while (isspace((unsigned char)*p) || *p == ',')
			p++;
		if (svg_number(&p, &v[n]))
			break;
		n++;
	}
	xmlFree(vb);
	*m = (svg_mat_t){ 1, 0, 0, 1, x, y };
	vp->w = w, vp->h = h;
	if (n != 4 || v[2] <= 0 || v[3] <= 0)
		return n == 4 ? -1 : 0;   /* a zero or negative viewBox disables the element */
	char *par = prop(el, "preserveAspectRatio");
	const char *a = par ? par : "xMidYMid";
	while (isspace((unsigned char)*a))
		a++;
	double sx = w / v[2], sy = h / v[3];
	if (strncmp(a, "none", 4)) {
		int slice = strstr(a, "slice") != NULL;
		double sc = slice ? fmax(sx, sy) : fmin(sx, sy);
		double ax = strstr(a, "xMin") ? 0 : strstr(a, "xMax") ? 1 : 0.5;
		double ay = strstr(a, "YMin") ? 0 : strstr(a, "YMax") ? 1 : 0.5;
		sx = sy = sc;
		x += ax * (w - v[2] * sc);
		y += ay * (h - v[3] * sc);
	}
	xmlFree(par);
	*m = (svg_mat_t){ sx, 0, 0, sy, x - v[0] * sx, y - v[1] * sy };
	vp->w = v[2], vp->h = v[3];
	return 0;
}

static int passes_conditions(xmlNode *el)
{
	char *ext = prop(el, "requiredExtensions"), *lang = prop(el, "systemLanguage");
	int ok = !ext;
	if (ok && lang) {
		ok = 0;
		for (char *t = strtok(lang, ", \t"); t; t = strtok(NULL, ", \t"))
			if (!strncasecmp(t, "en", 2) && (t[2] == 0 || t[2] == '-'))
				ok = 1;
	}
	xmlFree(ext);
	xmlFree(lang);
	return ok;
}

static void walk(st_t *s, xmlNode *el, const style_t *parent, svg_mat_t m, const vp_t *vp);

static void children(st_t *s, xmlNode *el, const style_t *st, svg_mat_t m, const vp_t *vp)
{
	for (xmlNode *c = el->children; c && !s->fatal; c = c->next)
		walk(s, c, st, m, vp);
}

/* A layer begins at an Inkscape layer group, or at a top-level group when there is none. */
static int layer_of(st_t *s, xmlNode *el)
{
	char *mode = (char *)xmlGetNsProp(el, (const xmlChar *)"groupmode",
			(const xmlChar *)"http://www.inkscape.org/namespaces/inkscape");
	int is = mode && !strcmp(mode, "layer");
	xmlFree(mode);
	if (!is && (s->inkscape_layers || el->parent != xmlDocGetRootElement(s->doc)))
		return -1;
	char *label = (char *)xmlGetNsProp(el, (const xmlChar *)"label",
			(const xmlChar *)"http://www.inkscape.org/namespaces/inkscape");
	if (!label)
		label = prop(el, "id");
	svg_layer_t *q = realloc(s->d.layer, (size_t)(s->d.nlayer + 1) * sizeof *q);
	if (!q) {
		xmlFree(label);
		return -1;
	}
	s->d.layer = q;
	char buf[32];
	snprintf(buf, sizeof buf, "layer %d", s->d.nlayer);
	q[s->d.nlayer].label = strdup(label ? label : buf);
	q[s->d.nlayer].pen = 0;
	q[s->d.nlayer].line = xmlGetLineNo(el);
	xmlFree(label);
	return s->d.nlayer++;
}

/* ---- text: meta text statements in the stroke font ---- */

#define CAP_PER_EM 0.7          /* capital height of a font-size (an em): Helvetica's 0.72, DejaVu's 0.73 */
#define TEXT_MAX 4000           /* bytes of one text statement (the meta-language takes 4096) */

/* The state of one <text> element's layout, in its user units. */
typedef struct {
	st_t *s;
	svg_mat_t m;
	const vp_t *vp;
	double x, y;            /* the current text position */
	int anchor;             /* the text-anchor of the chunk's first element */
	size_t first;           /* the chunk's first item */
	double adv;             /* the chunk's advance so far */
	int space;              /* the last character laid out was a space (or none yet) */
	double last_sp;         /* the advance of the trailing space of the last segment, else 0 */
	long last_it;           /* that segment's item, or -1 */
	long line;
} text_t;

/* The chunk ends: its items shifted by its text-anchor along the baseline. */
static void text_chunk_end(text_t *t)
{
	double sh = t->anchor == 1 ? -t->adv / 2 : t->anchor == 2 ? -t->adv : 0;
	for (size_t i = t->first; i < t->s->d.n; i++)
		if (t->s->d.it[i].kind == SVGI_TEXT)
			t->s->d.it[i].tx += t->m.a * sh, t->s->d.it[i].ty += t->m.b * sh;
	t->first = t->s->d.n;
	t->adv = 0;
}

/* The first value of a list of lengths (x, y, dx, dy): 0 and *out, or -1 when absent or bad
 * (SVG: an invalid list is as if not given). More than one value: a warning. */
static int first_len(text_t *t, xmlNode *el, const char *name, int axis, double font, double *out)
{
	char *v = prop(el, name);
	if (!v)
		return -1;
	char *p = v;
	while (isspace((unsigned char)*p))
		p++;
	size_t n = strcspn(p, " \t\r\n,");
	char *rest = p + n;
	while (*rest && (isspace((unsigned char)*rest) || *rest == ','))
		rest++;
	if (*rest)
		warn_kind(t->s, "per-character text positions (first value only)", xmlGetLineNo(el));
	p[n] = 0;
	int r = length(p, t->vp, axis, font, out);
	xmlFree(v);
	return r;
}

/* One text node's characters at the current position in the element's style. */
static void text_segment(text_t *t, const char *raw, const style_t *st)
{
	st_t *s = t->s;
	size_t n = strlen(raw), k = 0;
	char *b = malloc(n + 1);
	if (!b) {
		s->fatal = -70;
		snprintf(s->err, s->errlen, "locus-meta: out of memory importing %s", s->d.name);
		return;
	}
	/* xml:space default: newlines removed, tabs are spaces, spaces collapsed, none leading */
	for (const char *p = raw; *p; p++) {
		char c = *p == '\t' ? ' ' : *p;
		if (c == '\n' || c == '\r')
			continue;
		if (c == ' ' && t->space)
			continue;
		t->space = c == ' ';
		if (k < TEXT_MAX)
			b[k++] = c;
	}
	while (k == TEXT_MAX && k > 0 && ((unsigned char)b[k - 1] & 0xc0) == 0x80)
		k--;    /* not in the middle of a UTF-8 sequence */
	if (k == TEXT_MAX && k > 0 && ((unsigned char)b[k - 1] & 0xc0) == 0xc0)
		k--;
	b[k] = 0;
	if (!k) {
		free(b);
		return;
	}
	double cap = CAP_PER_EM * st->font, u = cap / 6;
	double adv = scan_text_advance(b, k) * u;
	t->last_sp = b[k - 1] == ' ' ? scan_text_advance(" ", 1) * u : 0;
	t->last_it = -1;
	svg_mat_t m = t->m;
	double fa = st->fill_op * st->opacity * st->fill.a, sa = st->stroke_op * st->opacity * st->stroke.a;
	int want_fill = st->fill.kind && fa > 0, want_stroke = st->stroke.kind && sa > 0 && st->width > 0;
	if (st->visible && (want_fill || want_stroke) && !s->fatal) {
		double sx = hypot(m.a, m.b), sy = hypot(m.c, m.d), det = m.a * m.d - m.b * m.c;
		double sc = sqrt(fabs(det));
		if (!(det > 0) || fabs(sx - sy) > 1e-9 * (sx + sy) || fabs(m.a * m.c + m.b * m.d) > 1e-9 * sx * sy)
			warn_kind(s, "text under a skew, mirror or non-uniform scale (drawn along its baseline at the mean scale, unskewed and unmirrored)", t->line);
		svg_item_t it = { .kind = SVGI_TEXT, .layer = s->layer, .cap = META_CAP_ROUND, .join = META_JOIN_ROUND,
			.miter = st->miter, .rule = st->rule, .text = b, .tadv = adv };
		it.tx = m.a * t->x + m.c * t->y + m.e;
		it.ty = m.b * t->x + m.d * t->y + m.f;
		it.tsize = cap * sc;
		it.tangle = atan2(-m.b, m.a) * 180 / M_PI;
		if (want_stroke) {   /* the stroke's colour is the pen; else the fill's, as plotter users expect */
			it.src_rgb = st->stroke.rgb;
			it.rgb = over_white(st->stroke.rgb, sa);
			it.width = st->width * sc;
		} else {
			it.src_rgb = st->fill.rgb;
			it.rgb = over_white(st->fill.rgb, fa);
			it.width = it.tsize / 10;
		}
		if (add_item(s, &it)) {
			free(b);
			s->fatal = -70;
			snprintf(s->err, s->errlen, "locus-meta: out of memory importing %s", s->d.name);
			return;
		}
		t->last_it = (long)s->d.n - 1;
	} else {
		free(b);
	}
	t->x += adv;
	t->adv += adv;
}

/* A text or tspan element: its position, then its content in order. */
static void text_run(text_t *t, xmlNode *el, const style_t *st)
{
	st_t *s = t->s;
	long line = xmlGetLineNo(el);
	double x, y, dx, dy;
	int hx = !first_len(t, el, "x", AX_X, st->font, &x), hy = !first_len(t, el, "y", AX_Y, st->font, &y);
	if (hx || hy) {   /* an absolute position starts a new chunk */
		text_chunk_end(t);
		t->anchor = st->anchor;
		if (hx)
			t->x = x;
		if (hy)
			t->y = y;
	}
	if (!first_len(t, el, "dx", AX_X, st->font, &dx))
		t->x += dx;
	if (!first_len(t, el, "dy", AX_Y, st->font, &dy))
		t->y += dy;
	static const char *const unsup[] = { "rotate", "textLength", "lengthAdjust" };
	for (size_t k = 0; k < sizeof unsup / sizeof *unsup; k++)
		if (xmlHasProp(el, (const xmlChar *)unsup[k]))
			warn_kind(s, "text rotate, textLength or lengthAdjust (drawn without them)", line);
	if (st->spacing)
		warn_kind(s, "letter-spacing or word-spacing (text drawn without them)", line);
	for (xmlNode *c = el->children; c && !s->fatal; c = c->next) {
		if (c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE) {
			if (c->content)
				text_segment(t, (const char *)c->content, st);
		} else if (is_svg(c, "tspan") || is_svg(c, "a")) {
			if (++s->visits > MAX_VISITS) {
				snprintf(s->err, s->errlen, "%s:%ld:1: expected at most %d elements drawn (use references included), found more",
						s->d.name, xmlGetLineNo(c), MAX_VISITS);
				s->fatal = -65;
				return;
			}
			style_t cst;
			int display;
			char *origin = NULL;
			compute(s, c, st, t->vp, &cst, &display, &origin);
			free(origin);
			free(s->transform);
			s->transform = NULL;
			if (display)
				text_run(t, c, &cst);
		} else if (is_svg(c, "textPath")) {
			warn_kind(s, "textPath (left out)", xmlGetLineNo(c));
		}
	}
}

static void draw_text(st_t *s, xmlNode *el, const style_t *st, svg_mat_t m, const vp_t *vp)
{
	text_t t = { .s = s, .m = m, .vp = vp, .anchor = st->anchor, .first = s->d.n, .space = 1, .last_it = -1,
		.line = xmlGetLineNo(el) };
	text_run(&t, el, st);
	if (s->fatal)
		return;
	if (t.space && t.last_sp > 0) {   /* no trailing space */
		t.adv -= t.last_sp;
		if (t.last_it >= 0) {
			svg_item_t *it = &s->d.it[t.last_it];
			size_t k = strlen(it->text);
			if (k > 1)
				it->text[k - 1] = 0, it->tadv -= t.last_sp;
		}
	}
	text_chunk_end(&t);
	warn_kind(s, "text drawn in the stroke font (font-family, weight and style not followed)", t.line);
}

static void walk(st_t *s, xmlNode *el, const style_t *parent, svg_mat_t m, const vp_t *vp)
{
	if (el->type != XML_ELEMENT_NODE || !is_svg(el, NULL) || s->fatal)
		return;
	if (++s->visits > MAX_VISITS) {
		snprintf(s->err, s->errlen, "%s:%ld:1: expected at most %d elements drawn (use references included), found more",
				s->d.name, xmlGetLineNo(el), MAX_VISITS);
		s->fatal = -65;
		return;
	}
	const char *name = (const char *)el->name;
	long line = xmlGetLineNo(el);
	static const char *const skip[] = { "defs", "symbol", "linearGradient", "radialGradient", "pattern",
		"clipPath", "mask", "marker", "filter", "style", "title", "desc", "metadata", "script", "font",
		"stop", "view", "cursor", "animate", "set", "animateTransform", "animateMotion" };
	for (size_t k = 0; k < sizeof skip / sizeof *skip; k++)
		if (!strcmp(name, skip[k]))
			return;
	if (!passes_conditions(el))
		return;
	style_t st;
	int display;
	char *origin = NULL;
	compute(s, el, parent, vp, &st, &display, &origin);
	char *tr = s->transform;
	s->transform = NULL;
	if (!display) {
		free(origin);
		free(tr);
		return;
	}
	/* transform, about transform-origin */
	if (tr) {
		svg_mat_t t;
		svg_transform_parse(tr, &t);   /* an invalid list is the identity */
		if (origin) {
			double ox = 0, oy = 0;
			char a[64] = "", b[64] = "";
			sscanf(origin, "%63s %63s", a, b);
			const char *kx = a, *ky = b[0] ? b : "center";
			if (!strcmp(kx, "top") || !strcmp(kx, "bottom")) {
				const char *sw = kx;
				kx = b[0] ? b : "center", ky = sw;
			}
			ox = !strcmp(kx, "left") ? 0 : !strcmp(kx, "center") ? vp->w / 2 : !strcmp(kx, "right") ? vp->w :
				(length(kx, vp, AX_X, st.font, &ox) ? 0 : ox);
			oy = !strcmp(ky, "top") ? 0 : !strcmp(ky, "center") ? vp->h / 2 : !strcmp(ky, "bottom") ? vp->h :
				(length(ky, vp, AX_Y, st.font, &oy) ? 0 : oy);
			t = svg_mat_mul(svg_mat_mul((svg_mat_t){ 1, 0, 0, 1, -ox, -oy }, t), (svg_mat_t){ 1, 0, 0, 1, ox, oy });
		}
		m = svg_mat_mul(t, m);
		free(tr);
	}
	free(origin);
	int saved_layer = s->layer;
	if (!strcmp(name, "g") || !strcmp(name, "a")) {
		if (!strcmp(name, "g")) {
			int l = layer_of(s, el);
			if (l >= 0)
				s->layer = l;
		}
		children(s, el, &st, m, vp);
	} else if (!strcmp(name, "switch")) {
		for (xmlNode *c = el->children; c; c = c->next)
			if (is_svg(c, NULL) && passes_conditions(c)) {
				walk(s, c, &st, m, vp);
				break;
			}
	} else if (!strcmp(name, "svg")) {
		double x = attr_len(el, "x", vp, AX_X, st.font, 0), y = attr_len(el, "y", vp, AX_Y, st.font, 0);
		double w = attr_len(el, "width", vp, AX_X, st.font, vp->w), h = attr_len(el, "height", vp, AX_Y, st.font, vp->h);
		svg_mat_t v;
		vp_t nvp;
		if (w > 0 && h > 0 && !viewbox(el, x, y, w, h, &v, &nvp)) {
			int nc = s->nclip;
			push_clip(s, m, x, y, w, h, el);
			children(s, el, &st, svg_mat_mul(v, m), &nvp);
			s->nclip = nc;
		}
	} else if (!strcmp(name, "use")) {
		char *h = href(el);
		xmlNode *r = by_ref(s, h);
		xmlFree(h);
		int cycle = 0;
		for (int k = 0; k < s->use_depth; k++)
			cycle |= s->stack[k] == r;
		for (xmlNode *p = el->parent; r && p; p = p->parent)
			cycle |= p == r;
		if (!r || cycle || s->use_depth == MAX_USE_DEPTH || r == el) {
			warn_kind(s, "use without a target, or a reference cycle (left out)", line);
		} else {
			double x = attr_len(el, "x", vp, AX_X, st.font, 0), y = attr_len(el, "y", vp, AX_Y, st.font, 0);
			svg_mat_t mm = svg_mat_mul((svg_mat_t){ 1, 0, 0, 1, x, y }, m);
			s->stack[s->use_depth++] = r;
			if (is_svg(r, "symbol") || is_svg(r, "svg")) {
				double w = attr_len(el, "width", vp, AX_X, st.font, -1), hh = attr_len(el, "height", vp, AX_Y, st.font, -1);
				if (w < 0)
					w = attr_len(r, "width", vp, AX_X, st.font, vp->w);
				if (hh < 0)
					hh = attr_len(r, "height", vp, AX_Y, st.font, vp->h);
				svg_mat_t v;
				vp_t nvp;
				style_t sst;
				int disp;
				char *o2 = NULL;
				compute(s, r, &st, vp, &sst, &disp, &o2);
				free(o2);
				free(s->transform);
				s->transform = NULL;
				if (disp && w > 0 && hh > 0 && !viewbox(r, 0, 0, w, hh, &v, &nvp)) {
					char *t2 = prop(r, "transform");
					svg_mat_t t = { 1, 0, 0, 1, 0, 0 };
					if (t2 && is_svg(r, "symbol"))
						svg_transform_parse(t2, &t);
					xmlFree(t2);
					int nc = s->nclip;
					push_clip(s, svg_mat_mul(t, mm), 0, 0, w, hh, r);
					children(s, r, &sst, svg_mat_mul(svg_mat_mul(v, t), mm), &nvp);
					s->nclip = nc;
				}
			} else {
				walk(s, r, &st, mm, vp);
			}
			s->use_depth--;
		}
	} else if (!strcmp(name, "path")) {
		draw(s, el, &st, m, g_path, vp);
	} else if (!strcmp(name, "rect")) {
		draw(s, el, &st, m, g_rect, vp);
	} else if (!strcmp(name, "circle") || !strcmp(name, "ellipse")) {
		draw(s, el, &st, m, g_ellipse, vp);
	} else if (!strcmp(name, "line")) {
		draw(s, el, &st, m, g_line, vp);
	} else if (!strcmp(name, "polyline") || !strcmp(name, "polygon")) {
		draw(s, el, &st, m, g_poly, vp);
	} else if (!strcmp(name, "text")) {
		draw_text(s, el, &st, m, vp);
	} else if (!strcmp(name, "image")) {
		warn_kind(s, "raster image (left out)", line);
	} else if (!strcmp(name, "foreignObject")) {
		warn_kind(s, "foreignObject (left out)", line);
	} else {
		warn_kind(s, "unknown SVG element (left out)", line);
	}
	s->layer = saved_layer;
}

/* ---- the document ---- */

int svgimp_is(const void *buf, size_t n)
{
	const unsigned char *p = buf;
	size_t i = 0;
	if (n >= 3 && p[0] == 0xef && p[1] == 0xbb && p[2] == 0xbf)
		i = 3;
	while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' || p[i] == '\n'))
		i++;
	return i < n && p[i] == '<';
}

static void collect(st_t *s, xmlNode *n, char **css, size_t *len)
{
	for (; n; n = n->next) {
		if (n->type != XML_ELEMENT_NODE)
			continue;
		xmlChar *id = xmlGetProp(n, (const xmlChar *)"id");
		if (id) {
			xmlHashAddEntry(s->ids, id, n);   /* the first of a repeated id wins */
			xmlFree(id);
		}
		if (is_svg(n, "style")) {
			char *type = prop(n, "type");
			if (!s->style_line)
				s->style_line = xmlGetLineNo(n);
			if (!type || !*type || !strcmp(type, "text/css")) {
				xmlChar *t = xmlNodeGetContent(n);
				size_t tl = t ? strlen((char *)t) : 0;
				char *q = realloc(*css, *len + tl + 2);
				if (q) {
					memcpy(q + *len, t ? (char *)t : "", tl);
					*len += tl;
					q[(*len)++] = '\n';
					q[*len] = 0;
					*css = q;
				}
				xmlFree(t);
			}
			xmlFree(type);
		}
		if (is_svg(n, "g")) {
			char *mode = (char *)xmlGetNsProp(n, (const xmlChar *)"groupmode",
					(const xmlChar *)"http://www.inkscape.org/namespaces/inkscape");
			if (mode && !strcmp(mode, "layer"))
				s->inkscape_layers = 1;
			xmlFree(mode);
		}
		collect(s, n->children, css, len);
	}
}

int svgimp_import(const void *buf, size_t n, const char *name, const svgimp_opts_t *o,
		meta_writer_t *w, char *err, size_t errlen)
{
	if (n > MAX_BYTES) {
		snprintf(err, errlen, "%s:1:1: expected an SVG file of at most %u bytes, found %zu bytes", name, MAX_BYTES, n);
		return -65;
	}
	xmlParserCtxt *ctx = xmlNewParserCtxt();
	if (!ctx) {
		snprintf(err, errlen, "locus-meta: out of memory importing %s", name);
		return -70;
	}
	xmlDoc *doc = xmlCtxtReadMemory(ctx, buf, (int)n, name, NULL, XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
	if (!doc) {
		const xmlError *e = xmlCtxtGetLastError(ctx);
		char msg[400] = "malformed XML";
		if (e && e->message) {
			snprintf(msg, sizeof msg, "%s", e->message);
			for (char *p = msg; *p; p++)
				if (*p == '\n' || *p == '\r')
					*p = 0;
		}
		snprintf(err, errlen, "%s:%d:%d: %s", name, e ? e->line : 0, e ? e->int2 : 0, msg);
		xmlFreeParserCtxt(ctx);
		return -65;
	}
	xmlFreeParserCtxt(ctx);
	xmlNode *root = xmlDocGetRootElement(doc);
	if (!root || !is_svg(root, "svg")) {
		snprintf(err, errlen, "%s:%ld:1: expected an <svg> root element, found <%s>", name,
				root ? xmlGetLineNo(root) : 1L, root ? (const char *)root->name : "nothing");
		xmlFreeDoc(doc);
		return -65;
	}
	st_t s = { .doc = doc, .err = err, .errlen = errlen, .layer = -1 };
	s.d.name = name, s.d.o = o;
	s.ids = xmlHashCreate(64);
	char *css = NULL;
	size_t clen = 0;
	collect(&s, root, &css, &clen);
	if (css) {
		s.sheet = svg_sheet_parse(NULL, css, sheet_warn, &s);
		free(css);
	}
	/* the page: the root's width and height (default: the viewBox's size, else 100 px) */
	vp_t v0 = { 100, 100 };
	svg_mat_t vb;
	vp_t vbvp;
	int have_vb = 0;
	{
		char *t = prop(root, "viewBox");
		have_vb = t != NULL;
		xmlFree(t);
	}
	double vw = 100, vh = 100;
	if (have_vb && !viewbox(root, 0, 0, 1, 1, &vb, &vbvp))
		vw = vbvp.w, vh = vbvp.h;
	double sw = -1, sh = -1;
	char *ws = prop(root, "width"), *hs = prop(root, "height");
	if (ws && !strchr(ws, '%'))
		length(ws, &v0, AX_X, FONT_SIZE, &sw);
	if (hs && !strchr(hs, '%'))
		length(hs, &v0, AX_Y, FONT_SIZE, &sh);
	xmlFree(ws);
	xmlFree(hs);
	if (sw <= 0 && sh > 0)
		sw = sh * vw / vh;
	else if (sh <= 0 && sw > 0)
		sh = sw * vh / vw;
	if (sw <= 0 || sh <= 0)
		sw = vw, sh = vh;
	s.d.wmm = sw * 25.4 / 96, s.d.hmm = sh * 25.4 / 96;
	s.d.px_per_mm = o->dpi / 25.4;
	double pw = s.d.wmm * s.d.px_per_mm, ph = s.d.hmm * s.d.px_per_mm;
	double big = fmax(pw, ph);
	if (big > 32768)
		s.d.px_per_mm *= 32768 / big, pw = s.d.wmm * s.d.px_per_mm, ph = s.d.hmm * s.d.px_per_mm;
	s.d.pw = (unsigned)fmax(1, fmin(32768, ceil(pw - 1e-6)));
	s.d.ph = (unsigned)fmax(1, fmin(32768, ceil(ph - 1e-6)));
	s.d.W = pw, s.d.H = ph;
	double k = s.d.px_per_mm * 25.4 / 96;   /* page pixels per CSS px */
	svg_mat_t rm;
	vp_t vp;
	int rc = 0;
	if (viewbox(root, 0, 0, sw, sh, &rm, &vp) == 0) {
		rm = svg_mat_mul(rm, (svg_mat_t){ k, 0, 0, k, 0, 0 });
		style_t st = { .fill = { 1, 0, 1 }, .stroke = { 0, 0, 1 }, .fill_op = 1, .stroke_op = 1, .opacity = 1,
			.rule = META_RULE_NON_ZERO, .cap = META_CAP_BUTT, .join = META_JOIN_MITER, .visible = 1,
			.width = 1, .miter = 4, .font = FONT_SIZE, .color = 0 };
		int display;
		char *origin = NULL;
		style_t rs;
		compute(&s, root, &st, &vp, &rs, &display, &origin);
		free(origin);
		free(s.transform);
		s.transform = NULL;
		s.page = rm;
		if (display)
			children(&s, root, &rs, rm, &vp);
	}
	rc = s.fatal;
	if (!rc)
		rc = svg_doc_write(&s.d, w, err, errlen);
	for (size_t i = 0; i < s.d.n; i++)
		svg_geom_free(&s.d.it[i].g), free(s.d.it[i].text);
	free(s.d.it);
	for (int i = 0; i < s.d.nlayer; i++)
		free(s.d.layer[i].label);
	free(s.d.layer);
	svg_sheet_free(s.sheet);
	xmlHashFree(s.ids, NULL);
	xmlFreeDoc(doc);
	return rc;
}
