/* import_svg_out.c: SVG import's back end: dashes split, pens by layer or colour, -O dedupe,
 * --stats before and after, and the page written as meta. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "hpgl/hpgl.h"
#include "hpgl/pathopt.h"
#include "import/svg_import.h"
#include "geom/scan.h"

#define PATH_POINTS 900000   /* points per meta path at most (the meta-language allows 10^6) */

/* ---- dashes (SVG's dash offset, which the meta-language's dash has not) ---- */

typedef struct {
	svg_geom_t *o;
	int open;
} piece_t;

static void piece_pt(piece_t *p, svg_pt_t a)
{
	if (!p->open) {
		svg_geom_t *o = p->o;
		svg_mat_t id = o->m;
		o->m = (svg_mat_t){ 1, 0, 0, 1, 0, 0 };
		svg_geom_move(o, a.x, a.y);
		o->m = id;
		p->open = 1;
	} else {
		svg_mat_t id = p->o->m;
		p->o->m = (svg_mat_t){ 1, 0, 0, 1, 0, 0 };
		svg_geom_line(p->o, a.x, a.y);
		p->o->m = id;
	}
}

int svg_dash_split(svg_geom_t *g, const double *dash, int n, double offset)
{
	double period = 0;
	for (int i = 0; i < n; i++)
		period += dash[i];
	if (!(period > 0) || !isfinite(period))
		return 0;
	svg_geom_t o = { .tol = g->tol, .m = g->m };
	piece_t p = { &o, 0 };
	for (size_t s = 0; s < g->nsub; s++) {
		size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n;
		double off = fmod(offset, period);
		if (off < 0)
			off += period;
		int k = 0;
		while (off >= dash[k]) {
			off -= dash[k];
			k = (k + 1) % n;
		}
		double rest = dash[k] - off;
		int on = k % 2 == 0;
		p.open = 0;
		size_t m = b - a + (g->closed[s] ? 1 : 0);
		if (on && b > a)
			piece_pt(&p, g->pt[a]);
		long guard = 0;
		for (size_t i = 1; i < m; i++) {
			svg_pt_t P = g->pt[a + i - 1], Q = g->pt[i < b - a ? a + i : a];
			double L = hypot(Q.x - P.x, Q.y - P.y), t = 0;
			while (t + rest < L && guard++ < 50000000) {
				t += rest;
				svg_pt_t B = { P.x + (Q.x - P.x) * t / L, P.y + (Q.y - P.y) * t / L };
				if (on) {
					piece_pt(&p, B);
					p.open = 0;
				} else {
					p.open = 0;
					piece_pt(&p, B);
				}
				on = !on;
				k = (k + 1) % n;
				rest = dash[k];
			}
			rest -= L - t;
			if (on)
				piece_pt(&p, Q);
		}
	}
	if (o.oom) {
		svg_geom_free(&o);
		return -1;
	}
	o.limit = g->limit;
	svg_geom_free(g);
	*g = o;
	return 0;
}

/* ---- pens ---- */

static const hpgl_pen_t *pen_slot(const hpgl_pens_t *c, int pen)
{
	for (size_t k = 0; k < c->n; k++)
		if (c->pen[k].slot == pen)
			return &c->pen[k];
	return c->n ? &c->pen[(size_t)(pen - 1) % c->n] : NULL;
}

/* The pen --pen gives key ("LAYER=N" or "#rrggbb=N"), or 0. */
static int pen_given(const svgimp_opts_t *o, const char *key)
{
	for (int i = 0; i < o->npen_map; i++) {
		const char *eq = strrchr(o->pen_map[i], '=');
		if (eq && (size_t)(eq - o->pen_map[i]) == strlen(key) && !strncmp(o->pen_map[i], key, strlen(key)))
			return atoi(eq + 1);
	}
	return 0;
}

/* A pen number in a layer's label: "Pen 2", "2", "pen2 red" give 2. */
static int pen_in_label(const char *l)
{
	while (*l && !(*l >= '0' && *l <= '9'))
		l++;
	int v = atoi(l);
	return *l && v >= 1 && v <= HPGL_MAX_PENS ? v : 0;
}

static int assign_pens(svg_doc_t *d, hpgl_pens_t *car, char *err, size_t errlen)
{
	const svgimp_opts_t *o = d->o;
	const char *spec = o->carousel;
	if (!spec) {
		const hpgl_profile_t *p = hpgl_profile_find(o->profile ? o->profile : "7475a");
		spec = p ? p->pens : "1=black";
	}
	if (hpgl_pens_parse(spec, 0.3, car, err, errlen))
		return -64;
	for (int i = 0; i < o->npen_map; i++) {
		const char *eq = strrchr(o->pen_map[i], '=');
		int v = eq ? atoi(eq + 1) : 0;
		if (!eq || eq == o->pen_map[i] || v < 1 || v > HPGL_MAX_PENS) {
			snprintf(err, errlen, "pen: expected LAYER=N or #rrggbb=N with N 1..%d, found '%s'", HPGL_MAX_PENS, o->pen_map[i]);
			return -64;
		}
	}
	FILE *vf = stderr;
	if (o->pens_mode == SVGP_LAYER) {
		int used[HPGL_MAX_PENS + 2] = { 0 };
		int outside = pen_given(o, "-");
		for (int i = 0; i < d->nlayer; i++) {
			int p = pen_given(o, d->layer[i].label);
			if (!p)
				p = pen_in_label(d->layer[i].label);
			d->layer[i].pen = p;
			if (p)
				used[p] = 1;
		}
		int next = 1;
		for (int i = 0; i < d->nlayer; i++)
			if (!d->layer[i].pen) {
				while (next <= HPGL_MAX_PENS && used[next])
					next++;
				d->layer[i].pen = next <= HPGL_MAX_PENS ? next : 1;
				used[d->layer[i].pen] = 1;
			}
		for (size_t i = 0; i < d->n; i++)
			d->it[i].pen = d->it[i].layer >= 0 ? d->layer[d->it[i].layer].pen : outside ? outside : 1;
		if (o->verbose)
			for (int i = 0; i < d->nlayer; i++)
				fprintf(vf, "%s: layer \"%s\" (line %ld) -> pen %d\n", d->name, d->layer[i].label,
						d->layer[i].line, d->layer[i].pen);
	} else {
		uint32_t col[HPGL_MAX_PENS];
		int pen[HPGL_MAX_PENS], nc = 0;
		for (size_t i = 0; i < d->n; i++) {
			uint32_t c = d->it[i].src_rgb;
			int k;
			for (k = 0; k < nc; k++)
				if (col[k] == c)
					break;
			if (k == nc && nc < HPGL_MAX_PENS) {
				char key[16];
				snprintf(key, sizeof key, "#%06x", (unsigned)c);
				col[nc] = c;
				pen[nc] = pen_given(o, key);
				if (!pen[nc])
					pen[nc] = nc + 1;
				if (o->verbose)
					fprintf(vf, "%s: colour %s -> pen %d\n", d->name, key, pen[nc]);
				nc++;
			}
			d->it[i].pen = k < nc ? pen[k] : 1;
		}
	}
	for (size_t i = 0; i < d->n; i++) {
		const hpgl_pen_t *p = pen_slot(car, d->it[i].pen);
		if (p)
			d->it[i].rgb = p->rgb;
	}
	return 0;
}

/* ---- stats ---- */

typedef struct {
	double down_mm, up_mm, time_s;
	unsigned long lifts, changes;
} stats_t;

/* A text item's glyph strokes (docs/stroke-font.md, spec §5.5) into g, page pixels, y down:
 * what the pen draws, for --stats. 0, or -1 out of memory. */
static int text_strokes(const svg_item_t *it, svg_geom_t *g)
{
	double u = it->tsize / 6, a = it->tangle * M_PI / 180, ca = cos(a), sa = sin(a), pen = 0;
	const unsigned char *t = (const unsigned char *)it->text;
	size_t len = strlen(it->text), k = 0;
	g->m = (svg_mat_t){ 1, 0, 0, 1, 0, 0 };
	g->tol = 1;
	while (k < len) {
		uint32_t cp;
		k += meta_utf8_next(t + k, len - k, &cp);
		double adv;
		const char *src = scan_glyph_source(cp >= 0x20 && cp <= 0x7e ? (int)cp : -1, &adv);
		int first = 1;
		for (const char *p = src; *p;) {
			char *e;
			double gx = strtod(p, &e);
			if (e == p) {   /* ';' starts a polyline, blanks part points */
				first |= *p == ';';
				p++;
				continue;
			}
			p = e + (*e == ',');
			double gy = strtod(p, &e);
			p = e;
			double U = (pen + gx) * u, V = gy * u;
			double x = it->tx + U * ca - V * sa, y = it->ty - (U * sa + V * ca);
			if ((first ? svg_geom_move(g, x, y) : svg_geom_line(g, x, y)) < 0 || g->oom)
				return -1;
			first = 0;
		}
		pen += adv;
	}
	return 0;
}

static void measure(const svg_doc_t *d, stats_t *st)
{
	const hpgl_profile_t *prof = hpgl_profile_find(d->o->profile ? d->o->profile : "7475a");
	if (!prof)
		prof = hpgl_profile_builtin(0);
	memset(st, 0, sizeof *st);
	hpgl_time_t t = { 0 };
	double k = 40 / d->px_per_mm;   /* plotter units per pixel */
	svg_pt_t at = { 0, d->ph };
	long last = -1;
	popt_pt_t *pp = NULL;
	size_t pcap = 0;
	for (size_t i = 0; i < d->n; i++) {
		const svg_item_t *it = &d->it[i];
		svg_geom_t tg = { 0 };
		if (it->kind == SVGI_TEXT && (!(fabs(it->tx) < 1e6 && fabs(it->ty) < 1e6 && it->tsize < 1e6) ||
				text_strokes(it, &tg) < 0 || !tg.nsub)) {
			svg_geom_free(&tg);
			continue;   /* off the meta file's range, out of memory, or only spaces */
		}
		if (!it->g.nsub && !tg.nsub)
			continue;   /* nothing left to draw (cut away, or a white fill that only hides) */
		long pen = d->o->pens_mode ? it->pen : (long)it->rgb;
		if (pen != last && last != -1)
			st->changes++;
		last = pen;
		const svg_geom_t *g = it->kind == SVGI_TEXT ? &tg : &it->g;
		for (size_t s = 0; s < g->nsub; s++) {
			size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n, n = b - a + (g->closed[s] ? 1 : 0);
			if (dev_grow((void **)&pp, &pcap, n, sizeof *pp, 256))
				continue;
			for (size_t j = 0; j < n; j++) {
				svg_pt_t q = g->pt[j < b - a ? a + j : a];
				pp[j].x = (int32_t)lround(q.x * k);
				pp[j].y = (int32_t)lround((d->ph - q.y) * k);
			}
			double travel = hypot(g->pt[a].x - at.x, g->pt[a].y - at.y);
			hpgl_time_add(&t, prof, travel * k, pp, n);
			at = g->pt[n - 1 < b - a ? a + n - 1 : a];
			st->lifts++;
		}
		svg_geom_free(&tg);
	}
	free(pp);
	st->down_mm = t.down_mm, st->up_mm = t.up_mm;
	st->time_s = t.down_s + t.up_s + t.lift_s + (double)st->changes * prof->t_change;
}

static void print_stats(const svg_doc_t *d, const char *when, const stats_t *s)
{
	FILE *f = d->o->stats_out ? d->o->stats_out : stderr;
	if (d->o->json)
		fprintf(f, "{\"when\":\"%s\",\"pen_down_mm\":%.1f,\"pen_up_mm\":%.1f,\"lifts\":%lu,\"pen_changes\":%lu,\"plot_s\":%.1f,\"profile\":\"%s\"}\n",
				when, s->down_mm, s->up_mm, s->lifts, s->changes, s->time_s, d->o->profile ? d->o->profile : "7475a");
	else
		fprintf(f, "%s: %s: pen-down %.1f mm, pen-up %.1f mm, %lu lifts, %lu pen changes, plot time %.1f s (%s, file order)\n",
				d->name, when, s->down_mm, s->up_mm, s->lifts, s->changes, s->time_s, d->o->profile ? d->o->profile : "7475a");
}

/* ---- writing ---- */

typedef struct {
	meta_writer_t *w;
	long rgb, cap, join, rule;
	double width, miter;
	double ph;
	int clamped;
} wst_t;

static int coord(wst_t *s, double v, double *out)
{
	if (v > 1e6 || v < -1e6 || !isfinite(v)) {
		s->clamped = 1;
		v = !isfinite(v) ? 0 : v > 0 ? 1e6 : -1e6;
	}
	*out = v;
	return 0;
}

static int write_item(wst_t *s, const svg_item_t *it)
{
	meta_writer_t *w = s->w;
	int r = 0;
	if ((long)it->rgb != s->rgb && (r = meta_colour(w, it->rgb)) < 0)
		return r;
	s->rgb = it->rgb;
	if (it->kind == SVGI_TEXT) {   /* drawn with the colour and width; cap, join, dashes its own */
		double wd = fmin(it->width, 1e6), x, y;
		if (wd != s->width && (r = meta_width(w, wd)) < 0)
			return r;
		s->width = wd;
		coord(s, it->tx, &x);
		coord(s, s->ph - it->ty, &y);
		double a = fmod(it->tangle, 360);
		return meta_text(w, x, y, isfinite(it->tsize) ? fmin(it->tsize, 1e6) : 0, isfinite(a) ? a : 0, it->text);
	}
	if (it->kind == SVGI_FILL) {
		if (it->rule != s->rule && (r = meta_fill_rule(w, it->rule)) < 0)
			return r;
		s->rule = it->rule;
	} else {
		double wd = fmin(it->width, 1e6);
		if (wd != s->width && (r = meta_width(w, wd)) < 0)
			return r;
		s->width = wd;
		if (it->cap != s->cap && (r = meta_cap(w, it->cap)) < 0)
			return r;
		s->cap = it->cap;
		if (it->join != s->join && (r = meta_join(w, it->join)) < 0)
			return r;
		s->join = it->join;
		double ml = fmin(it->miter, 1e6);
		if (ml != s->miter && (r = meta_miter_limit(w, ml)) < 0)
			return r;
		s->miter = ml;
	}
	const svg_geom_t *g = &it->g;
	if (it->kind == SVGI_FILL && g->n > PATH_POINTS)
		return -65;
	size_t count = 0;
	if ((r = it->kind == SVGI_FILL ? meta_fill(w) : meta_stroke(w)) < 0)
		return r;
	for (size_t sp = 0; sp < g->nsub; sp++) {
		size_t a = g->sub[sp], b = sp + 1 < g->nsub ? g->sub[sp + 1] : g->n;
		for (size_t i = a; i < b; i++) {
			double x, y;
			coord(s, g->pt[i].x, &x);
			coord(s, s->ph - g->pt[i].y, &y);
			if (count >= PATH_POINTS) {   /* a long stroke goes on in a new path */
				if ((r = meta_end(w)) < 0 || (r = meta_stroke(w)) < 0)
					return r;
				count = 0;
				if (i > a) {
					double px, py;
					coord(s, g->pt[i - 1].x, &px);
					coord(s, s->ph - g->pt[i - 1].y, &py);
					if ((r = meta_move(w, px, py)) < 0)
						return r;
					count++;
				}
			}
			r = i == a || count == 0 ? meta_move(w, x, y) : meta_draw(w, x, y);
			if (r < 0)
				return r;
			count++;
		}
		if (g->closed[sp] && (r = meta_close(w)) < 0)
			return r;
	}
	return meta_end(w);
}

int svg_dedupe(svg_doc_t *d, double tol);   /* import_svg_dedupe.c */

int svg_doc_write(svg_doc_t *d, meta_writer_t *w, char *err, size_t errlen)
{
	const svgimp_opts_t *o = d->o;
	hpgl_pens_t car;
	int r;
	if (o->pens_mode && (r = assign_pens(d, &car, err, errlen)) < 0)
		return r;
	stats_t before, after;
	if (o->stats)
		measure(d, &before);
	if (o->occlude && svg_occlude(d) < 0) {
		snprintf(err, errlen, "locus-meta: out of memory importing %s", d->name);
		return -70;
	}
	if (o->dedupe) {
		if (svg_dedupe(d, o->dedupe_mm * d->px_per_mm) < 0) {
			snprintf(err, errlen, "locus-meta: out of memory importing %s", d->name);
			return -70;
		}
	}
	if (o->stats) {
		measure(d, &after);
		print_stats(d, "before", &before);
		print_stats(d, o->occlude && o->dedupe ? "after occlude+dedupe" : o->occlude ? "after occlude"
				: o->dedupe ? "after dedupe" : "after (no -O)", &after);
	}
	wst_t s = { .w = w, .rgb = 0, .cap = META_CAP_BUTT, .join = META_JOIN_MITER, .rule = META_RULE_NON_ZERO,
		.width = 1, .miter = 10, .ph = d->ph };
	if ((r = meta_page(w, d->pw, d->ph)) < 0 || (r = meta_page_size_mm(w, d->pw / d->px_per_mm, d->ph / d->px_per_mm)) < 0)
		goto werr;
	char c[300];
	snprintf(c, sizeof c, "from %.200s: %.3f x %.3f mm, curves flattened to %.4f mm", d->name, d->wmm, d->hmm, o->tol_mm);
	for (char *p = c; *p; p++)
		if ((unsigned char)*p < 0x20)
			*p = '?';
	if ((r = meta_comment(w, c)) < 0)
		goto werr;
	if (o->pens_mode == SVGP_LAYER)
		for (int i = 0; i < d->nlayer; i++) {
			snprintf(c, sizeof c, "pen %d: layer \"%.200s\"", d->layer[i].pen, d->layer[i].label);
			for (char *p = c; *p; p++)
				if ((unsigned char)*p < 0x20 || *p == 0x7f)
					*p = '?';
			if ((r = meta_comment(w, c)) < 0)
				goto werr;
		}
	for (size_t i = 0; i < d->n; i++) {
		if (!d->it[i].g.nsub && d->it[i].kind != SVGI_TEXT)
			continue;
		if ((r = write_item(&s, &d->it[i])) < 0) {
			if (r == -65) {
				snprintf(err, errlen, "%s: a filled shape of more than %d points once flattened", d->name, PATH_POINTS);
				return -65;
			}
			goto werr;
		}
	}
	if ((r = meta_end_page(w)) < 0)
		goto werr;
	if (s.clamped)
		if (!o->quiet)
			fprintf(stderr, "%s: warning: coordinates beyond the meta file's range (1000000 pixels) were clamped\n", d->name);
	return 0;
werr:
	snprintf(err, errlen, "%s: %s", d->name, meta_writer_error(w) ? meta_writer_error(w) : "cannot write the meta file");
	return r == -70 ? -70 : -74;
}
