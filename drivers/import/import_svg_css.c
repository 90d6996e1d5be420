/* import_svg_css.c: SVG colours, <style> sheets (selectors, specificity) and the property cascade. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <libxml/tree.h>
#include "util/grow.h"
#include "import/svg_import.h"

const char *const svg_prop_name[SP_NPROP] = {
	"fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity",
	"stroke-dasharray", "stroke-dashoffset", "stroke-linecap", "stroke-linejoin",
	"stroke-miterlimit", "color", "display", "visibility", "opacity", "font-size", "clip-path",
	"mask", "filter", "marker-start", "marker-mid", "marker-end", "transform-origin", "transform",
	"text-anchor", "letter-spacing", "word-spacing"
};

int svg_prop_find(const char *name, size_t len)
{
	for (int k = 0; k < SP_NPROP; k++)
		if (strlen(svg_prop_name[k]) == len && !strncasecmp(svg_prop_name[k], name, len))
			return k;
	return -1;
}

/* ---- colours: CSS's named colours, #rgb, #rrggbb (with alpha), rgb(), rgba(), hsl() ---- */

static const struct { const char *name; uint32_t rgb; } named[] = {
	{"aliceblue",0xf0f8ff},{"antiquewhite",0xfaebd7},{"aqua",0x00ffff},{"aquamarine",0x7fffd4},
	{"azure",0xf0ffff},{"beige",0xf5f5dc},{"bisque",0xffe4c4},{"black",0x000000},
	{"blanchedalmond",0xffebcd},{"blue",0x0000ff},{"blueviolet",0x8a2be2},{"brown",0xa52a2a},
	{"burlywood",0xdeb887},{"cadetblue",0x5f9ea0},{"chartreuse",0x7fff00},{"chocolate",0xd2691e},
	{"coral",0xff7f50},{"cornflowerblue",0x6495ed},{"cornsilk",0xfff8dc},{"crimson",0xdc143c},
	{"cyan",0x00ffff},{"darkblue",0x00008b},{"darkcyan",0x008b8b},{"darkgoldenrod",0xb8860b},
	{"darkgray",0xa9a9a9},{"darkgreen",0x006400},{"darkgrey",0xa9a9a9},{"darkkhaki",0xbdb76b},
	{"darkmagenta",0x8b008b},{"darkolivegreen",0x556b2f},{"darkorange",0xff8c00},
	{"darkorchid",0x9932cc},{"darkred",0x8b0000},{"darksalmon",0xe9967a},{"darkseagreen",0x8fbc8f},
	{"darkslateblue",0x483d8b},{"darkslategray",0x2f4f4f},{"darkslategrey",0x2f4f4f},
	{"darkturquoise",0x00ced1},{"darkviolet",0x9400d3},{"deeppink",0xff1493},{"deepskyblue",0x00bfff},
	{"dimgray",0x696969},{"dimgrey",0x696969},{"dodgerblue",0x1e90ff},{"firebrick",0xb22222},
	{"floralwhite",0xfffaf0},{"forestgreen",0x228b22},{"fuchsia",0xff00ff},{"gainsboro",0xdcdcdc},
	{"ghostwhite",0xf8f8ff},{"gold",0xffd700},{"goldenrod",0xdaa520},{"gray",0x808080},
	{"grey",0x808080},{"green",0x008000},{"greenyellow",0xadff2f},{"honeydew",0xf0fff0},
	{"hotpink",0xff69b4},{"indianred",0xcd5c5c},{"indigo",0x4b0082},{"ivory",0xfffff0},
	{"khaki",0xf0e68c},{"lavender",0xe6e6fa},{"lavenderblush",0xfff0f5},{"lawngreen",0x7cfc00},
	{"lemonchiffon",0xfffacd},{"lightblue",0xadd8e6},{"lightcoral",0xf08080},{"lightcyan",0xe0ffff},
	{"lightgoldenrodyellow",0xfafad2},{"lightgray",0xd3d3d3},{"lightgreen",0x90ee90},
	{"lightgrey",0xd3d3d3},{"lightpink",0xffb6c1},{"lightsalmon",0xffa07a},{"lightseagreen",0x20b2aa},
	{"lightskyblue",0x87cefa},{"lightslategray",0x778899},{"lightslategrey",0x778899},
	{"lightsteelblue",0xb0c4de},{"lightyellow",0xffffe0},{"lime",0x00ff00},{"limegreen",0x32cd32},
	{"linen",0xfaf0e6},{"magenta",0xff00ff},{"maroon",0x800000},{"mediumaquamarine",0x66cdaa},
	{"mediumblue",0x0000cd},{"mediumorchid",0xba55d3},{"mediumpurple",0x9370db},
	{"mediumseagreen",0x3cb371},{"mediumslateblue",0x7b68ee},{"mediumspringgreen",0x00fa9a},
	{"mediumturquoise",0x48d1cc},{"mediumvioletred",0xc71585},{"midnightblue",0x191970},
	{"mintcream",0xf5fffa},{"mistyrose",0xffe4e1},{"moccasin",0xffe4b5},{"navajowhite",0xffdead},
	{"navy",0x000080},{"oldlace",0xfdf5e6},{"olive",0x808000},{"olivedrab",0x6b8e23},
	{"orange",0xffa500},{"orangered",0xff4500},{"orchid",0xda70d6},{"palegoldenrod",0xeee8aa},
	{"palegreen",0x98fb98},{"paleturquoise",0xafeeee},{"palevioletred",0xdb7093},
	{"papayawhip",0xffefd5},{"peachpuff",0xffdab9},{"peru",0xcd853f},{"pink",0xffc0cb},
	{"plum",0xdda0dd},{"powderblue",0xb0e0e6},{"purple",0x800080},{"rebeccapurple",0x663399},
	{"red",0xff0000},{"rosybrown",0xbc8f8f},{"royalblue",0x4169e1},{"saddlebrown",0x8b4513},
	{"salmon",0xfa8072},{"sandybrown",0xf4a460},{"seagreen",0x2e8b57},{"seashell",0xfff5ee},
	{"sienna",0xa0522d},{"silver",0xc0c0c0},{"skyblue",0x87ceeb},{"slateblue",0x6a5acd},
	{"slategray",0x708090},{"slategrey",0x708090},{"snow",0xfffafa},{"springgreen",0x00ff7f},
	{"steelblue",0x4682b4},{"tan",0xd2b48c},{"teal",0x008080},{"thistle",0xd8bfd8},
	{"tomato",0xff6347},{"turquoise",0x40e0d0},{"violet",0xee82ee},{"wheat",0xf5deb3},
	{"white",0xffffff},{"whitesmoke",0xf5f5f5},{"yellow",0xffff00},{"yellowgreen",0x9acd32},
};

static int clamp255(double v)
{
	return v < 0 ? 0 : v > 255 ? 255 : (int)lround(v);
}

static double hue(double p, double q, double t)
{
	t -= floor(t);
	return t < 1.0 / 6 ? p + (q - p) * 6 * t : t < 0.5 ? q : t < 2.0 / 3 ? p + (q - p) * (2.0 / 3 - t) * 6 : p;
}

int svg_colour(const char *s, uint32_t *rgb, double *alpha)
{
	while (isspace((unsigned char)*s))
		s++;
	size_t len = strlen(s);
	while (len && isspace((unsigned char)s[len - 1]))
		len--;
	*alpha = 1;
	if (s[0] == '#') {
		unsigned v[8];
		size_t n = len - 1;
		if (n != 3 && n != 4 && n != 6 && n != 8)
			return -1;
		for (size_t i = 0; i < n; i++) {
			char c = s[1 + i];
			if (!isxdigit((unsigned char)c))
				return -1;
			v[i] = (unsigned)(isdigit((unsigned char)c) ? c - '0' : (tolower((unsigned char)c) - 'a' + 10));
		}
		if (n <= 4) {
			*rgb = (v[0] * 17) << 16 | (v[1] * 17) << 8 | v[2] * 17;
			if (n == 4)
				*alpha = v[3] * 17 / 255.0;
		} else {
			*rgb = (v[0] * 16 + v[1]) << 16 | (v[2] * 16 + v[3]) << 8 | (v[4] * 16 + v[5]);
			if (n == 8)
				*alpha = (v[6] * 16 + v[7]) / 255.0;
		}
		return 0;
	}
	int hsl = !strncasecmp(s, "hsl", 3);
	if (!strncasecmp(s, "rgb", 3) || hsl) {
		const char *p = s + 3;
		if (*p == 'a' || *p == 'A')
			p++;
		if (*p++ != '(')
			return -1;
		double c[4] = { 0, 0, 0, 1 };
		int n = 0;
		for (;;) {
			while (isspace((unsigned char)*p) || *p == ',' || *p == '/')
				p++;
			if (*p == ')' || n == 4)
				break;
			if (svg_number(&p, &c[n]))
				return -1;
			if (*p == '%') {
				p++;
				c[n] = n == 3 || hsl ? c[n] / 100 : c[n] * 2.55;
			} else if (hsl && n == 0 && !strncasecmp(p, "deg", 3)) {
				p += 3;
			}
			n++;
		}
		if (*p != ')' || n < 3)
			return -1;
		if (hsl) {
			double h = c[0] / 360, sat = fmin(fmax(c[1], 0), 1), l = fmin(fmax(c[2], 0), 1);
			double q = l < 0.5 ? l * (1 + sat) : l + sat - l * sat, pp = 2 * l - q;
			c[0] = 255 * hue(pp, q, h + 1.0 / 3), c[1] = 255 * hue(pp, q, h), c[2] = 255 * hue(pp, q, h - 1.0 / 3);
		}
		*rgb = (uint32_t)clamp255(c[0]) << 16 | (uint32_t)clamp255(c[1]) << 8 | (uint32_t)clamp255(c[2]);
		*alpha = fmin(fmax(c[3], 0), 1);
		return 0;
	}
	for (size_t k = 0; k < sizeof named / sizeof *named; k++)
		if (strlen(named[k].name) == len && !strncasecmp(named[k].name, s, len)) {
			*rgb = named[k].rgb;
			return 0;
		}
	return -1;
}

/* ---- style sheets ---- */

/* One compound selector: type (or NULL for any), id, classes, attribute tests, :first-child. */
typedef struct {
	char *type, *id;
	char *cls[8];
	int ncls;
	char *attr[4], *aval[4];
	char aop[4];    /* 0 present, '=', '~', '^', '$', '*', '|' */
	int nattr;
	int first_child;
	char comb;      /* how it relates to the compound on its right: ' ', '>', '+', or 0 (last) */
} compound_t;

typedef struct {
	compound_t *c;
	int n;
	unsigned spec;  /* ids << 16 | classes/attributes << 8 | types */
	size_t order;
	char *decl;     /* the declaration block's text */
} rule_t;

struct svg_sheet {
	rule_t *r;
	size_t n, cap, order;
};

static char *dupn(const char *s, size_t n)
{
	char *p = malloc(n + 1);
	if (p) {
		memcpy(p, s, n);
		p[n] = 0;
	}
	return p;
}

static void free_rule(rule_t *r)
{
	for (int i = 0; i < r->n; i++) {
		compound_t *c = &r->c[i];
		free(c->type), free(c->id);
		for (int k = 0; k < c->ncls; k++)
			free(c->cls[k]);
		for (int k = 0; k < c->nattr; k++)
			free(c->attr[k]), free(c->aval[k]);
	}
	free(r->c);
	free(r->decl);
}

void svg_sheet_free(svg_sheet_t *s)
{
	if (!s)
		return;
	for (size_t i = 0; i < s->n; i++)
		free_rule(&s->r[i]);
	free(s->r);
	free(s);
}

static int ident_char(char c)
{
	return isalnum((unsigned char)c) || c == '-' || c == '_' || (unsigned char)c >= 0x80 || c == '\\';
}

/* Parse one selector (no commas) from s..e into r; -1 when it uses what this reader lacks. */
static int parse_selector(const char *s, const char *e, rule_t *r)
{
	int cap = 0;
	char comb = ' ';
	for (;;) {
		int ws = 0;
		while (s < e && isspace((unsigned char)*s))
			s++, ws = 1;
		if (s < e && (*s == '>' || *s == '+' || *s == '~')) {
			if (*s == '~')
				return -1;
			comb = *s++;
			while (s < e && isspace((unsigned char)*s))
				s++;
		} else if (ws && r->n) {
			comb = ' ';
		}
		if (s >= e)
			break;
		if (r->n == cap) {
			cap = cap ? cap * 2 : 4;
			compound_t *q = realloc(r->c, (size_t)cap * sizeof *q);
			if (!q)
				return -2;
			r->c = q;
		}
		compound_t *c = &r->c[r->n++];
		memset(c, 0, sizeof *c);
		if (r->n > 1)
			r->c[r->n - 2].comb = comb;
		int any = 0;
		while (s < e && !isspace((unsigned char)*s) && *s != '>' && *s != '+' && *s != '~') {
			const char *p = s;
			if (*s == '*') {
				s++, any = 1;
			} else if (ident_char(*s)) {
				while (s < e && ident_char(*s))
					s++;
				if (!(c->type = dupn(p, (size_t)(s - p))))
					return -2;
				r->spec += 1, any = 1;
			} else if (*s == '#' || *s == '.') {
				s++;
				while (s < e && ident_char(*s))
					s++;
				char *v = dupn(p + 1, (size_t)(s - p - 1));
				if (!v)
					return -2;
				if (*p == '#') {
					free(c->id);
					c->id = v;
					r->spec += 1 << 16;
				} else if (c->ncls < 8) {
					c->cls[c->ncls++] = v;
					r->spec += 1 << 8;
				} else {
					free(v);
					return -1;
				}
				any = 1;
			} else if (*s == '[') {
				const char *q = memchr(s, ']', (size_t)(e - s));
				if (!q || c->nattr == 4)
					return -1;
				s++;
				while (s < q && isspace((unsigned char)*s))
					s++;
				const char *a = s;
				while (s < q && ident_char(*s))
					s++;
				int k = c->nattr++;
				c->attr[k] = dupn(a, (size_t)(s - a));
				c->aop[k] = 0;
				c->aval[k] = NULL;
				while (s < q && isspace((unsigned char)*s))
					s++;
				if (s < q) {
					if (*s != '=' && s + 1 < q && s[1] == '=')
						c->aop[k] = *s++;
					else if (*s == '=')
						c->aop[k] = '=';
					else
						return -1;
					s++;
					while (s < q && isspace((unsigned char)*s))
						s++;
					const char *v = s, *ve = q;
					while (ve > v && isspace((unsigned char)ve[-1]))
						ve--;
					if (ve > v && (*v == '"' || *v == '\'') && ve[-1] == *v)
						v++, ve--;
					c->aval[k] = dupn(v, (size_t)(ve - v));
				}
				if (!c->attr[k])
					return -2;
				s = q + 1;
				r->spec += 1 << 8;
				any = 1;
			} else if (*s == ':') {
				s++;
				const char *q = s;
				while (s < e && ident_char(*s))
					s++;
				if ((size_t)(s - q) == 11 && !strncmp(q, "first-child", 11))
					c->first_child = 1;
				else
					return -1;
				r->spec += 1 << 8;
				any = 1;
			} else {
				return -1;
			}
		}
		if (!any)
			return -1;
	}
	return r->n ? 0 : -1;
}

svg_sheet_t *svg_sheet_parse(svg_sheet_t *sh, const char *text, void (*warn)(void *, const char *),
		void *user)
{
	if (!sh && !(sh = calloc(1, sizeof *sh)))
		return NULL;
	/* comments out first */
	char *t = strdup(text);
	if (!t)
		return sh;
	for (char *p = t; (p = strstr(p, "/*"));) {
		char *q = strstr(p + 2, "*/");
		size_t n = q ? (size_t)(q + 2 - p) : strlen(p);
		memset(p, ' ', n);
		p += n;
	}
	const char *s = t;
	while (*s) {
		while (isspace((unsigned char)*s))
			s++;
		if (!*s)
			break;
		if (*s == '@') {   /* at-rules: @import and the like skipped, a block skipped whole */
			const char *semi = strchr(s, ';'), *brace = strchr(s, '{');
			warn(user, !strncmp(s, "@import", 7) ? "CSS @import (external style sheet)" : "CSS at-rule");
			if (brace && (!semi || brace < semi)) {
				int depth = 0;
				for (s = brace; *s; s++) {
					if (*s == '{')
						depth++;
					else if (*s == '}' && --depth == 0) {
						s++;
						break;
					}
				}
			} else {
				s = semi ? semi + 1 : s + strlen(s);
			}
			continue;
		}
		const char *open = strchr(s, '{');
		if (!open)
			break;
		const char *close = strchr(open, '}');
		if (!close)
			close = open + strlen(open);
		/* each selector of the comma list is a rule of its own */
		const char *a = s;
		while (a < open) {
			const char *b = a;
			while (b < open && *b != ',')
				b++;
			rule_t r = { 0 };
			int rc = parse_selector(a, b, &r);
			if (rc == 0 && !dev_grow((void **)&sh->r, &sh->cap, sh->n + 1, sizeof *sh->r, 16)) {
				r.order = sh->order++;
				r.decl = dupn(open + 1, (size_t)(close - open - 1));
				sh->r[sh->n++] = r;
			} else {
				if (rc == -1)
					warn(user, "CSS selector this reader lacks (rule skipped)");
				free_rule(&r);
			}
			a = b + 1;
		}
		s = *close ? close + 1 : close;
	}
	free(t);
	return sh;
}

/* ---- matching ---- */

static int has_word(const char *list, const char *w)
{
	size_t n = strlen(w);
	for (const char *p = list; *p;) {
		while (isspace((unsigned char)*p))
			p++;
		const char *q = p;
		while (*q && !isspace((unsigned char)*q))
			q++;
		if ((size_t)(q - p) == n && n && !strncmp(p, w, n))
			return 1;
		p = q;
	}
	return 0;
}

static xmlNode *prev_el(xmlNode *n)
{
	for (n = n->prev; n && n->type != XML_ELEMENT_NODE; n = n->prev)
		;
	return n;
}

static int match_compound(const compound_t *c, xmlNode *el)
{
	if (c->type && strcmp((const char *)el->name, c->type))
		return 0;
	if (c->first_child && prev_el(el))
		return 0;
	int ok = 1;
	if (c->id) {
		xmlChar *v = xmlGetProp(el, (const xmlChar *)"id");
		ok = v && !strcmp((char *)v, c->id);
		xmlFree(v);
	}
	if (ok && c->ncls) {
		xmlChar *v = xmlGetProp(el, (const xmlChar *)"class");
		for (int k = 0; ok && k < c->ncls; k++)
			ok = v && has_word((char *)v, c->cls[k]);
		xmlFree(v);
	}
	for (int k = 0; ok && k < c->nattr; k++) {
		xmlChar *v = xmlGetProp(el, (const xmlChar *)c->attr[k]);
		const char *a = (const char *)v, *w = c->aval[k];
		size_t la = a ? strlen(a) : 0, lw = w ? strlen(w) : 0;
		switch (c->aop[k]) {
		case 0: ok = a != NULL; break;
		case '=': ok = a && !strcmp(a, w); break;
		case '~': ok = a && has_word(a, w); break;
		case '^': ok = a && lw && !strncmp(a, w, lw); break;
		case '$': ok = a && lw && la >= lw && !strcmp(a + la - lw, w); break;
		case '*': ok = a && lw && strstr(a, w); break;
		case '|': ok = a && !strncmp(a, w, lw) && (a[lw] == 0 || a[lw] == '-'); break;
		default: ok = 0;
		}
		xmlFree(v);
	}
	return ok;
}

static int match_from(const rule_t *r, int i, xmlNode *el)
{
	if (!el || el->type != XML_ELEMENT_NODE || !match_compound(&r->c[i], el))
		return 0;
	if (i == 0)
		return 1;
	char comb = r->c[i - 1].comb;
	if (comb == '>')
		return match_from(r, i - 1, el->parent);
	if (comb == '+')
		return match_from(r, i - 1, prev_el(el));
	for (xmlNode *p = el->parent; p && p->type == XML_ELEMENT_NODE; p = p->parent)
		if (match_from(r, i - 1, p))
			return 1;
	return 0;
}

/* Apply the declarations of text at priority base (order within: later wins at equal key). */
static void apply_decls(const char *text, uint64_t base, char **val, uint64_t *key)
{
	const char *s = text;
	while (*s) {
		while (isspace((unsigned char)*s) || *s == ';')
			s++;
		const char *n = s;
		while (*s && *s != ':' && *s != ';')
			s++;
		if (*s != ':')
			continue;
		const char *ne = s;
		while (ne > n && isspace((unsigned char)ne[-1]))
			ne--;
		s++;
		while (isspace((unsigned char)*s))
			s++;
		const char *v = s;
		while (*s && *s != ';')
			s++;
		const char *ve = s;
		while (ve > v && isspace((unsigned char)ve[-1]))
			ve--;
		uint64_t k = base;
		const char *imp = NULL;
		for (const char *p = v; p < ve; p++)
			if (*p == '!' && ve - p >= 10 && !strncasecmp(p + 1, "important", 9))
				imp = p;
		if (imp) {
			k |= (uint64_t)1 << 62;
			ve = imp;
			while (ve > v && isspace((unsigned char)ve[-1]))
				ve--;
		}
		int p = svg_prop_find(n, (size_t)(ne - n));
		if (p < 0 || ve == v || k < key[p])
			continue;
		char *d = dupn(v, (size_t)(ve - v));
		if (d) {
			free(val[p]);
			val[p] = d;
			key[p] = k;
		}
	}
}

void svg_cascade(const svg_sheet_t *s, xmlNode *el, char **val)
{
	uint64_t key[SP_NPROP];
	for (int k = 0; k < SP_NPROP; k++)
		val[k] = NULL, key[k] = 0;
	/* presentation attributes: the lowest origin */
	for (xmlAttr *a = el->properties; a; a = a->next) {
		int p = svg_prop_find((const char *)a->name, strlen((const char *)a->name));
		if (p < 0 || p == SP_TRANSFORM_ORIGIN || (a->ns && a->ns->prefix))
			continue;
		xmlChar *v = xmlNodeListGetString(el->doc, a->children, 1);
		if (v) {
			free(val[p]);
			val[p] = strdup((char *)v);
			key[p] = 1;
			xmlFree(v);
		}
	}
	xmlChar *to = xmlGetProp(el, (const xmlChar *)"transform-origin");
	if (to) {
		val[SP_TRANSFORM_ORIGIN] = strdup((char *)to);
		xmlFree(to);
	}
	/* sheet rules by specificity, then order */
	for (size_t i = 0; s && i < s->n; i++) {
		const rule_t *r = &s->r[i];
		if (match_from(r, r->n - 1, el))
			apply_decls(r->decl, (uint64_t)1 << 58 | (uint64_t)(r->spec & 0xffffff) << 24 | (r->order & 0xffffff), val, key);
	}
	xmlChar *st = xmlGetProp(el, (const xmlChar *)"style");
	for (char *p = (char *)st; p && (p = strstr(p, "/*"));) {   /* comments out */
		char *q = strstr(p + 2, "*/");
		size_t n = q ? (size_t)(q + 2 - p) : strlen(p);
		memset(p, ' ', n);
		p += n;
	}
	if (st) {
		apply_decls((char *)st, (uint64_t)1 << 60, val, key);
		xmlFree(st);
	}
}
