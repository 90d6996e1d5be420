/* hpgl_emit.c: writes HP-GL and HP-GL/2 commands through the device writer (device/writer.h):
 * pen selection, polylines in the shortest of absolute and relative form (PE-encoded in HP-GL/2),
 * labels, native fills. The writer's byte count is the job offset pauses and resumes use. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device/writer.h"
#include "hpgl/hpgl.h"

enum { MODE_UNKNOWN, MODE_ABS, MODE_REL };

struct hpgl_emit {
	dev_writer_t w;             /* over out (first: it is large) */
	io_transport_t *out;        /* NULL: the bytes are counted, not kept */
	const hpgl_profile_t *prof;
	int pen;                    /* selected pen slot, -1 unknown */
	int mode;                   /* PA / PR in force */
	int known;                  /* 1 when the pen position is known */
	int32_t x, y;
	unsigned pe_pairs;          /* pairs in the open PE command, 0 = none open */
	int ft;                     /* 1 once FT1 is set for RA fills */
};

/* The sink of an emitter without an output: bytes are dropped (and counted by the writer). */
static int discard(void *user, const void *p, size_t n)
{
	(void)user;
	(void)p;
	(void)n;
	return 0;
}

hpgl_emit_t *hpgl_emit_new(io_transport_t *out, const hpgl_profile_t *prof)
{
	hpgl_emit_t *e = calloc(1, sizeof *e);
	if (!e)
		return NULL;
	dev_w_init(&e->w, out);
	if (!out)
		dev_w_set_sink(&e->w, discard, NULL);
	e->out = out;
	e->prof = prof;
	e->pen = -1;
	return e;
}

void hpgl_emit_free(hpgl_emit_t *e)
{
	free(e);
}

int hpgl_emit_flush(hpgl_emit_t *e)
{
	return dev_w_drain(&e->w) ? -1 : 0;
}

static inline int raw(hpgl_emit_t *e, const char *s, size_t n)
{
	return dev_w_write(&e->w, s, n) ? -1 : 0;
}

/* The end of a command: ';' and, for receivers that want it, a newline. */
static int term(hpgl_emit_t *e)
{
	return raw(e, e->prof->newline ? ";\n" : ";", e->prof->newline ? 2 : 1);
}

static int pe_close(hpgl_emit_t *e)
{
	if (!e->pe_pairs)
		return 0;
	e->pe_pairs = 0;
	return term(e);
}

int hpgl_emit_cmd(hpgl_emit_t *e, const char *fmt, ...)
{
	char s[512];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(s, sizeof s, fmt, ap);
	va_end(ap);
	if (n < 0 || (size_t)n >= sizeof s)
		return -1;
	if (pe_close(e) || raw(e, s, (size_t)n) || term(e))
		return -1;
	if (!strncmp(s, "IN", 2) || !strncmp(s, "DF", 2)) {
		e->mode = MODE_ABS;
		e->known = 0;
		e->ft = 0;
	}
	return 0;
}

int hpgl_emit_pen(hpgl_emit_t *e, int slot)
{
	if (slot == e->pen)
		return 0;
	e->pen = slot;
	return hpgl_emit_cmd(e, "SP%d", slot);
}

/* Characters of v in decimal, sign included. */
static size_t digits(int64_t v)
{
	uint64_t u = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
	size_t n = v < 0 ? 2 : 1;
	if (u >= 10000) {
		n += 4;
		u /= 10000;
	}
	while (u >= 10) {
		u /= 10;
		n++;
	}
	return n;
}

/* Text lengths of the pairs of pts[a..b) absolute (*labs) and relative to the point before
 * (*lrel), in one pass. */
static void list_lens(const popt_pt_t *pts, size_t a, size_t b, popt_pt_t before, unsigned max, size_t *labs,
                      size_t *lrel)
{
	size_t la = 0, lr = 0, pairs = 0, extra = 0;
	popt_pt_t at = before;
	for (size_t i = a; i < b; i++) {
		la += digits(pts[i].x) + digits(pts[i].y);
		lr += digits((int64_t)pts[i].x - at.x) + digits((int64_t)pts[i].y - at.y);
		if (++pairs == max) {
			extra += 2;                        /* another "PD" */
			pairs = 0;
		}
		at = pts[i];
	}
	size_t sep = 2 * (b > a ? b - a : 0);    /* "x,y," or "x,y;" */
	*labs = la + sep + extra;
	*lrel = lr + sep + extra;
}

/* Decimal digits of v written at s, backwards from their known length (no sprintf: it was a
 * third of the run time on large pages). Returns the length. */
static int put_num(char *s, int64_t v)
{
	int n = (int)digits(v), k = n;
	uint64_t u = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
	do {
		s[--k] = (char)('0' + u % 10);
		u /= 10;
	} while (u);
	if (v < 0)
		s[0] = '-';
	return n;
}

/* PU to pts[0], then PD along the rest; HP-GL. */
static int poly_hpgl(hpgl_emit_t *e, const popt_pt_t *pts, size_t n)
{
	unsigned max = e->prof->max_pairs ? e->prof->max_pairs : 32;
	popt_pt_t here = { e->x, e->y };
	/* choose the move's and the draws' forms: absolute or relative */
	size_t mabs = digits(pts[0].x) + digits(pts[0].y) + 1, mrel = SIZE_MAX;
	if (e->known)
		mrel = digits((int64_t)pts[0].x - here.x) + digits((int64_t)pts[0].y - here.y) + 1;
	size_t dabs, drel;
	list_lens(pts, 1, n, pts[0], max, &dabs, &drel);
	int best_m = 0, best_d = 0;
	size_t best = SIZE_MAX;
	for (int m = 0; m < 2; m++)
		for (int d = 0; d < 2; d++) {
			size_t cm = m ? mrel : mabs;
			if (cm == SIZE_MAX)
				continue;
			int mode = e->mode;
			size_t c = cm + (d ? drel : dabs);
			if ((m ? MODE_REL : MODE_ABS) != mode) {
				c += 3;
				mode = m ? MODE_REL : MODE_ABS;
			}
			if (n > 1 && (d ? MODE_REL : MODE_ABS) != mode)
				c += 3;
			if (c < best) {
				best = c;
				best_m = m;
				best_d = d;
			}
		}
	char s[64];
	int k;
	if ((best_m ? MODE_REL : MODE_ABS) != e->mode) {
		if (raw(e, best_m ? "PR" : "PA", 2) || term(e))
			return -1;
		e->mode = best_m ? MODE_REL : MODE_ABS;
	}
	s[0] = 'P';
	s[1] = 'U';
	k = 2;
	k += put_num(s + k, best_m ? (int64_t)pts[0].x - here.x : pts[0].x);
	s[k++] = ',';
	k += put_num(s + k, best_m ? (int64_t)pts[0].y - here.y : pts[0].y);
	if (raw(e, s, (size_t)k) || term(e))
		return -1;
	if (n > 1 && (best_d ? MODE_REL : MODE_ABS) != e->mode) {
		if (raw(e, best_d ? "PR" : "PA", 2) || term(e))
			return -1;
		e->mode = best_d ? MODE_REL : MODE_ABS;
	}
	popt_pt_t at = pts[0];
	unsigned pairs = 0;
	for (size_t i = 1; i < n; i++) {
		k = 0;
		if (pairs == 0) {
			s[0] = 'P';
			s[1] = 'D';
			k = 2;
		} else
			s[k++] = ',';
		k += put_num(s + k, best_d ? (int64_t)pts[i].x - at.x : pts[i].x);
		s[k++] = ',';
		k += put_num(s + k, best_d ? (int64_t)pts[i].y - at.y : pts[i].y);
		if (raw(e, s, (size_t)k))
			return -1;
		at = pts[i];
		if (++pairs == max || i + 1 == n) {
			if (term(e))
				return -1;
			pairs = 0;
		}
	}
	if (!e->prof->newline && raw(e, "\n", 1))
		return -1;
	return 0;
}

/* One PE number, 7-bit (base 32) encoding of an integer. */
static size_t pe_num(char *s, int64_t v)
{
	uint64_t u = v < 0 ? ((uint64_t)-v << 1) | 1 : (uint64_t)v << 1;
	size_t k = 0;
	while (u >= 32) {
		s[k++] = (char)(63 + (u & 31));
		u >>= 5;
	}
	s[k++] = (char)(95 + u);
	return k;
}

static int pe_open(hpgl_emit_t *e)
{
	if (e->pe_pairs)
		return 0;
	e->pe_pairs = 1;   /* counts from 1: the open command itself */
	return raw(e, "PE7", 3);
}

/* PE polyline: '<' before the pen-up move, '=' when it is absolute; pairs after it are pen-down
 * moves relative to the last point. A full command is closed and the next PE goes on drawing. */
static int poly_pe(hpgl_emit_t *e, const popt_pt_t *pts, size_t n)
{
	unsigned max = e->prof->max_pairs ? e->prof->max_pairs : 256;
	char s[40];
	size_t k = 0;
	if (e->pe_pairs && e->pe_pairs + 2 > max && pe_close(e))
		return -1;
	if (pe_open(e))
		return -1;
	s[k++] = '<';
	char t[40];
	size_t rel = e->known ? pe_num(t, (int64_t)pts[0].x - e->x) + pe_num(t, (int64_t)pts[0].y - e->y) : SIZE_MAX;
	size_t abs = pe_num(t, pts[0].x) + pe_num(t, pts[0].y) + 1;
	if (rel <= abs) {
		k += pe_num(s + k, (int64_t)pts[0].x - e->x);
		k += pe_num(s + k, (int64_t)pts[0].y - e->y);
	} else {
		s[k++] = '=';
		k += pe_num(s + k, pts[0].x);
		k += pe_num(s + k, pts[0].y);
	}
	if (raw(e, s, k))
		return -1;
	e->pe_pairs++;
	for (size_t i = 1; i < n; i++) {
		if (e->pe_pairs >= max && (pe_close(e) || pe_open(e)))
			return -1;
		k = pe_num(s, (int64_t)pts[i].x - pts[i - 1].x);
		k += pe_num(s + k, (int64_t)pts[i].y - pts[i - 1].y);
		if (raw(e, s, k))
			return -1;
		e->pe_pairs++;
	}
	return 0;
}

int hpgl_emit_poly(hpgl_emit_t *e, const popt_pt_t *pts, size_t n)
{
	if (n == 0)
		return 0;
	int rc = e->prof->dialect == HPGL_DIALECT_2 ? poly_pe(e, pts, n) : poly_hpgl(e, pts, n);
	e->x = pts[n - 1].x;
	e->y = pts[n - 1].y;
	e->known = 1;
	return rc;
}

int hpgl_emit_label(hpgl_emit_t *e, int32_t x, int32_t y, double height_mm, double angle_deg,
		const char *s, size_t len)
{
	double a = angle_deg * M_PI / 180;
	popt_pt_t p = { x, y };
	char run[32], rise[32];
	snprintf(run, sizeof run, "%.4f", cos(a));
	snprintf(rise, sizeof rise, "%.4f", sin(a));
	if (hpgl_emit_poly(e, &p, 1) ||
			hpgl_emit_cmd(e, "DI%s,%s", run, rise) ||
			hpgl_emit_cmd(e, "SI%.3f,%.3f", height_mm * 0.1 * 0.75, height_mm * 0.1))
		return -1;
	if (pe_close(e) || raw(e, "LB", 2))
		return -1;
	for (size_t i = 0; i < len; i++) {
		char c = s[i] >= 0x20 && s[i] < 0x7f ? s[i] : '?';
		if (raw(e, &c, 1))
			return -1;
	}
	if (raw(e, "\003", 1) || (e->prof->newline && raw(e, "\n", 1)))
		return -1;
	e->known = 0;   /* the label moved the pen */
	return 0;
}

int hpgl_emit_fill(hpgl_emit_t *e, const popt_pt_t *pts, const size_t *starts, size_t ncont,
		size_t npts, int even_odd)
{
	(void)npts;
	if (e->prof->dialect != HPGL_DIALECT_2) {
		/* HP-GL: one axis-aligned rectangle, RA from a corner to the opposite one (FT1 solid) */
		if (ncont != 1 || starts[1] - starts[0] != 4)
			return -1;
		const popt_pt_t *c = pts + starts[0];
		if (hpgl_emit_poly(e, c, 1) || (!e->ft && hpgl_emit_cmd(e, "FT1")))
			return -1;
		/* RA is absolute whatever PA/PR say, but some readers (hp2xx) take it as relative under PR */
		if (e->mode != MODE_ABS && hpgl_emit_cmd(e, "PA"))
			return -1;
		e->mode = MODE_ABS;
		if (hpgl_emit_cmd(e, "RA%d,%d", c[2].x, c[2].y))
			return -1;
		e->ft = 1;
		return 0;
	}
	for (size_t k = 0; k < ncont; k++) {
		size_t s = starts[k], n = starts[k + 1] - s;
		if (n < 3)
			continue;
		popt_pt_t *c = malloc((n + 1) * sizeof *c);
		if (!c)
			return -1;
		memcpy(c, pts + s, n * sizeof *c);
		c[n] = c[0];
		if (hpgl_emit_cmd(e, k ? "PM1" : "PM0") || poly_hpgl(e, c, n + 1)) {
			free(c);
			return -1;
		}
		e->x = c[n].x;
		e->y = c[n].y;
		e->known = 1;
		free(c);
	}
	if (hpgl_emit_cmd(e, "PM2") || hpgl_emit_cmd(e, "FP%d", even_odd ? 0 : 1))
		return -1;
	return 0;
}

int hpgl_emit_raw(hpgl_emit_t *e, const char *s, size_t n)
{
	return pe_close(e) || raw(e, s, n) ? -1 : 0;
}

uint64_t hpgl_emit_bytes(const hpgl_emit_t *e)
{
	return e->w.pos;
}

const char *hpgl_emit_error(const hpgl_emit_t *e)
{
	return e->w.err && e->out && io_failed(e->out) ? io_error(e->out) : "";
}
