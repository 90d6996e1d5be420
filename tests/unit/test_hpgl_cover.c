/* test_hpgl_cover.c: every stroke of a meta file is drawn exactly once by locus-hpgl, whatever the
 * optimiser did: the HP-GL read back (hpgl_read) holds exactly the meta file's segments, each
 * end rounded to the nearest plotter unit (so within half a unit), plus only the short bridges
 * the merge tolerance allows. */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <unistd.h>
#include "device/device.h"
#include "hpgl/hpgl.h"
#include "hpgl/read/hpgl_read.h"
#include "unit.h"

extern const dev_ops_t dev_hpgl_ops;

/* An undirected segment of integer ends, smaller end first. */
typedef struct {
	int32_t a[2], b[2];
} seg_t;

typedef struct {
	seg_t *s;
	size_t n, cap;
} segs_t;

static void add_seg(segs_t *v, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
	if (x0 == x1 && y0 == y1)
		return;
	if (v->n == v->cap) {
		v->cap = v->cap ? 2 * v->cap : 1024;
		v->s = realloc(v->s, v->cap * sizeof *v->s);
	}
	int swap = x0 > x1 || (x0 == x1 && y0 > y1);
	v->s[v->n++] = swap ? (seg_t){ { x1, y1 }, { x0, y0 } } : (seg_t){ { x0, y0 }, { x1, y1 } };
}

static int seg_cmp(const void *p, const void *q)
{
	return memcmp(p, q, sizeof(seg_t)) < 0 ? -1 : memcmp(p, q, sizeof(seg_t)) > 0;
}

/* Walk the sorted multisets: segments wanted and not drawn, drawn and not wanted (short ones
 * are merge bridges). */
static void compare(const segs_t *want, const segs_t *got, size_t *missing, size_t *extra, size_t *bridges)
{
	size_t i = 0, j = 0;
	*missing = *extra = *bridges = 0;
	while (i < want->n || j < got->n) {
		int c = i == want->n ? 1 : j == got->n ? -1 : seg_cmp(&want->s[i], &got->s[j]);
		if (c == 0) {
			i++;
			j++;
		} else if (c < 0) {
			(*missing)++;
			i++;
		} else {
			const seg_t *s = &got->s[j++];
			if (hypot(s->b[0] - s->a[0], s->b[1] - s->a[1]) <= 2.0)   /* merge tolerance 0.05 mm */
				(*bridges)++;
			else
				(*extra)++;
		}
	}
}

/* The recorder: a vector device that maps the strokes exactly as the HP-GL device does. */
typedef struct {
	hpgl_profile_t prof;
	hpgl_pens_t pens;
	hpgl_map_t map;
	segs_t *out;
} rec_t;

static int rec_piece(void *user, const hpgl_dpt_t *p, size_t n, int closed)
{
	rec_t *r = user;
	for (size_t i = 0; i + 1 < n + (closed ? 1 : 0); i++) {
		hpgl_dpt_t a = p[i], b = p[(i + 1) % n];
		add_seg(r->out, (int32_t)lround(a.x), (int32_t)lround(a.y), (int32_t)lround(b.x), (int32_t)lround(b.y));
	}
	return 0;
}

static int rec_model(void *user, const hpgl_dpt_t *p, size_t n, int closed)
{
	rec_t *r = user;
	hpgl_dpt_t *m = malloc(n * sizeof *m);
	for (size_t i = 0; i < n; i++)
		hpgl_map_point(&r->map, (int64_t)p[i].x, (int64_t)p[i].y, &m[i].x, &m[i].y);
	int rc = hpgl_clip_poly(m, n, closed, r->map.clip, rec_piece, r);
	free(m);
	return rc;
}

static int rec_begin(dev_device_t *d, const dev_page_t *pg)
{
	rec_t *r = d->user;
	hpgl_place_t pl = { r->prof.paper, 0, 0, 1, 1.0 };
	char err[128];
	return hpgl_map_page(&r->prof, &pl, pg->width, pg->height, pg->has_size ? pg->width_mm / 1000.0 : 0,
		pg->has_size ? pg->height_mm / 1000.0 : 0, &r->map, err, sizeof err);
}

static int rec_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	rec_t *r = d->user;
	if (hpgl_pens_pick(&r->pens, st->colour) < 0)   /* paper: not drawn */
		return 0;
	const scan_path_t *f = p->flat;   /* dashed by the framework, as for the HP-GL device */
	for (size_t s = 0; s < f->nsubs; s++) {
		const scan_subpath_t *sp = &f->subs[s];
		if (sp->n < 2)
			continue;
		hpgl_dpt_t *t = malloc(sp->n * sizeof *t);
		for (size_t i = 0; i < sp->n; i++)
			t[i] = (hpgl_dpt_t){ (double)f->pts[sp->start + i].x, (double)f->pts[sp->start + i].y };
		rec_model(r, t, sp->n, sp->closed);
		free(t);
	}
	return 0;
}

static const dev_ops_t rec_ops = {
	.name = "rec", .caps = DEV_CAP_VECTOR | DEV_CAP_WIDTH | DEV_CAP_FILL | DEV_CAP_ONLY,
	.begin_page = rec_begin, .stroke_path = rec_stroke,
};

static int run_device(const char *meta, const dev_ops_t *ops, const char *opts, io_transport_t *out, void *user)
{
	char err[512];
	meta_reader_t *r = meta_reader_open(meta, err, sizeof err);
	if (!r)
		return -1;
	dev_device_t *d = dev_new(ops, out);
	d->options = opts;
	d->user = user;
	int rc = dev_play(r, d);
	if (rc)
		printf("# %s: %s\n", meta, dev_error(d));
	dev_free(d);
	meta_reader_free(r);
	return rc;
}

static void check(const char *meta, const char *profile, const char *extra)
{
	char opts[256], tmp[] = "/tmp/locus-cover-XXXXXX", err[512];
	snprintf(opts, sizeof opts, "profile=%s,fill=none,raster=skip,wide=single,text=strokes%s", profile, extra);
	int fd = mkstemp(tmp);
	if (fd < 0) {
		CHECK(0, "temporary file");
		return;
	}
	close(fd);
	io_transport_t *t = io_open_write(tmp, err, sizeof err);
	int rc = run_device(meta, &dev_hpgl_ops, opts, t, NULL);
	io_close(t, rc ? IO_ABORT : IO_COMMIT);
	segs_t want = { 0 }, got = { 0 };
	rec_t rec;
	memset(&rec, 0, sizeof rec);
	rec.prof = *hpgl_profile_find(profile);
	hpgl_pens_parse(rec.prof.pens, 0.3, &rec.pens, err, sizeof err);
	rec.out = &want;
	int rc2 = run_device(meta, &rec_ops, NULL, NULL, &rec);
	hpgl_doc_t doc;
	FILE *f = fopen(tmp, "rb");
	int rc3 = f ? hpgl_read_stream(f, tmp, &doc, err, sizeof err) : -1;
	if (f)
		fclose(f);
	unlink(tmp);
	if (rc || rc2 || rc3) {
		CHECK(0, "%s %s%s: device %d, recorder %d, reader %d (%s)", meta, profile, extra, rc, rc2, rc3, rc3 ? err : "");
		if (rc3 == 0)
			hpgl_doc_free(&doc);
		free(want.s);
		return;
	}
	int integral = 1;
	for (size_t k = 0; k < doc.nstrokes; k++) {
		const hpgl_rstroke_t *s = &doc.strokes[k];
		for (size_t i = 0; i + 1 < s->n; i++) {
			hpgl_rpt_t a = doc.pts[s->start + i], b = doc.pts[s->start + i + 1];
			integral &= a.x == floor(a.x) && a.y == floor(a.y);
			add_seg(&got, (int32_t)a.x, (int32_t)a.y, (int32_t)b.x, (int32_t)b.y);
		}
	}
	if (want.n)
		qsort(want.s, want.n, sizeof *want.s, seg_cmp);
	if (got.n)
		qsort(got.s, got.n, sizeof *got.s, seg_cmp);
	size_t missing, extra_n, bridges, m2, e2, b2;
	compare(&want, &got, &missing, &extra_n, &bridges);
	/* the comparison notices one segment lost and one drawn twice */
	if (got.n > 1) {
		got.n--;
		compare(&want, &got, &m2, &e2, &b2);
		got.n++;
		seg_t keep = got.s[0];
		got.s[0] = got.s[1];
		compare(&want, &got, &m2, &e2, &b2);
		got.s[0] = keep;
		CHECK(m2 == 1 && (e2 + b2) == 1, "%s %s%s: a segment drawn twice and one left out are both noticed", meta, profile, extra);
	}
	CHECK(integral && missing == 0 && extra_n == 0 && (want.n > 0 || got.n == 0),
		"%s %s%s: %zu meta segments drawn exactly once (%zu drawn, %zu missing, %zu extra, %zu short bridges)%s",
		meta, profile, extra, want.n, got.n, missing, extra_n, bridges, want.n ? "" : ": no strokes, nothing drawn");
	hpgl_doc_free(&doc);
	free(want.s);
	free(got.s);
}

static int name_cmp(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(void)
{
	/* every meta fixture of the project */
	static const char *const dirs[] = { "fixtures/meta", "fixtures/contour", "fixtures/render", "fixtures/voronoi" };
	char *names[256];
	size_t n = 0;
	for (size_t k = 0; k < sizeof dirs / sizeof dirs[0]; k++) {
		DIR *d = opendir(dirs[k]);
		struct dirent *e;
		while (d && (e = readdir(d)) && n < 256) {
			size_t len = strlen(e->d_name);
			if (len > 5 && !strcmp(e->d_name + len - 5, ".meta")) {
				names[n] = malloc(strlen(dirs[k]) + len + 2);
				sprintf(names[n++], "%s/%s", dirs[k], e->d_name);
			}
		}
		if (d)
			closedir(d);
	}
	qsort(names, n, sizeof *names, name_cmp);
	CHECK(n >= 15, "%zu meta fixtures found", n);
	for (size_t k = 0; k < n; k++) {
		check(names[k], "7475a", "");
		check(names[k], "hpgl2", "");
		check(names[k], "7550a", ",optimize=no");
		free(names[k]);
	}
	return UNIT_DONE();
}
