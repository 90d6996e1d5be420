/* fuzz_resume.c: libFuzzer harness of the job journal's resume over real HP-GL jobs: the input is
 * HP-GL, imported (locus-meta import) and replayed through the HP-GL device; the job that makes
 * is journaled as far as a cut the input's first two bytes choose, and resumed. The pen-down
 * segments of the job before the journal's safe point plus those of the resumed rest (its
 * restore, the command closer left out as a fresh plotter ignores it) are the whole job's, each
 * as often; and on a plotter that still holds the bytes before the cut, those bytes plus the
 * resumed ones read cleanly with the HP-GL reader and draw every segment of the job. */
#include <unistd.h>
#include "fuzz.h"
#include "device/device.h"
#include "hpgl/hpgl_link.h"
#include "hpgl/read/hpgl_read.h"
#include "io/journal.h"
#include "import/meta_import.h"
#include "io/transport.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define MAX_PIXELS (400 * 400)
#define MAX_WORK 100000.0
#define MAX_JOB (1 << 20)

extern const dev_ops_t dev_hpgl_ops;

static int cmp_line(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The sorted pen-down segments of HP-GL text p (n bytes), one "pen x,y x,y" each, as a list
 * *out of *nout strings; -1 when the reader refuses the text (strict), else 0. A text that ends
 * after a comma is closed as hpgl-segments does. */
static int segs(const char *p, size_t n, char ***out, size_t *nout)
{
	char *buf = malloc(n + 2), err[300];
	FUZZ_ASSERT(buf, "out of memory");
	memcpy(buf, p, n);
	while (n > 0 && buf[n - 1] == ',')
		n--;
	buf[n++] = ';';
	hpgl_doc_t d;
	memset(&d, 0, sizeof d);
	int rc = hpgl_read_mem(buf, n, "job", &d, err, sizeof err);
	size_t k = 0, cap = 0;
	char **v = NULL;
	for (size_t s = 0; !rc && s < d.nstrokes; s++)
		for (size_t i = 1; i < d.strokes[s].n; i++) {
			const hpgl_rpt_t *a = &d.pts[d.strokes[s].start + i - 1], *b = a + 1;
			if (a->x > b->x || (a->x == b->x && a->y > b->y)) {
				const hpgl_rpt_t *t = a;
				a = b;
				b = t;
			}
			if (k == cap) {
				cap = cap ? cap * 2 : 64;
				v = realloc(v, cap * sizeof *v);
				FUZZ_ASSERT(v, "out of memory");
			}
			v[k] = malloc(112);
			FUZZ_ASSERT(v[k], "out of memory");
			snprintf(v[k++], 112, "%d %.3f,%.3f %.3f,%.3f", d.strokes[s].pen, a->x, a->y, b->x, b->y);
		}
	hpgl_doc_free(&d);
	free(buf);
	if (k)
		qsort(v, k, sizeof *v, cmp_line);
	*out = v;
	*nout = k;
	return rc ? -1 : 0;
}

static void free_segs(char **v, size_t n)
{
	for (size_t k = 0; k < n; k++)
		free(v[k]);
	free(v);
}

/* Merge two sorted lists into a new sorted one (the strings are shared). */
static char **merge(char **a, size_t na, char **b, size_t nb)
{
	char **v = malloc((na + nb + 1) * sizeof *v);
	FUZZ_ASSERT(v, "out of memory");
	size_t i = 0, j = 0, k = 0;
	while (i < na || j < nb)
		v[k++] = j >= nb || (i < na && strcmp(a[i], b[j]) <= 0) ? a[i++] : b[j++];
	return v;
}

/* The HP-GL device's job for meta file m (n bytes) in *job, or -1 (a refused file). */
static int make_job(const char *m, size_t n, char **job, size_t *njob)
{
	char path[96], err[600];
	snprintf(path, sizeof path, "/tmp/locus-fuzz-resume-%ld.hpgl", (long)getpid());
	meta_reader_t *r = meta_reader_mem(m, n, "in");
	io_transport_t *t = io_open_write(path, err, sizeof err);
	FUZZ_ASSERT(r && t, "cannot start: %s", err);
	dev_device_t *d = dev_new(&dev_hpgl_ops, t);
	FUZZ_ASSERT(d, "out of memory");
	int rc = dev_play(r, d);
	io_close_err(t, rc < 0 ? IO_ABORT : IO_COMMIT, err, sizeof err);
	dev_free(d);
	meta_reader_free(r);
	if (rc < 0)
		return -1;
	FILE *f = fopen(path, "rb");
	FUZZ_ASSERT(f, "the job file is missing");
	fuzz_buf_t b = { 0 };
	char tmp[4096];
	size_t got;
	while ((got = fread(tmp, 1, sizeof tmp, f)) > 0 && b.n < MAX_JOB)
		FUZZ_ASSERT(!fuzz_buf_write(&b, tmp, got), "out of memory");
	fclose(f);
	unlink(path);
	*job = b.p;
	*njob = b.n;
	return b.n ? 0 : -1;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	hpgl_link_register();
	if (size < 3 || size > 32768)
		return 0;
	unsigned pick = (unsigned)data[0] << 8 | data[1];
	fuzz_buf_t m = { 0 };
	meta_writer_t *w = meta_writer_new(fuzz_buf_write, &m, META_ENC_TEXT);
	if (!w)
		return 0;
	char err[700] = "";
	int rc = mimp_hpgl(data + 2, size - 2, "in", 1.0, w, err, sizeof err);
	if (meta_writer_close(w) || rc) {
		free(m.p);
		return 0;
	}
	double work = fuzz_work((const uint8_t *)m.p, m.n, MAX_PIXELS, NULL);
	char *job = NULL;
	size_t n = 0;
	if (work < 0 || work > MAX_WORK || make_job(m.p, m.n, &job, &n)) {
		free(m.p);
		return 0;
	}
	free(m.p);
	char **whole;
	size_t nwhole;
	if (n >= MAX_JOB || segs(job, n, &whole, &nwhole)) {
		free(job);   /* (the device's own output the reader refuses is fuzz_hpgl's matter) */
		return 0;
	}
	size_t cut = 1 + (size_t)pick * (n - 1) / 65536;
	char jpath[96];
	snprintf(jpath, sizeof jpath, "/tmp/locus-fuzz-resume-%ld.jnl", (long)getpid());
	jn_t *j = jn_create(jpath, "usb:03f0:0107?journal=x", err, sizeof err);
	FUZZ_ASSERT(j && !jn_ack(j, job, cut) && !jn_close(j, 0), "journal of a cut at %zu: %s", cut, err);
	j = jn_resume(jpath, "usb:03f0:0107?resume=x", err, sizeof err);
	FUZZ_ASSERT(j, "resume of a cut at %zu: %s", cut, err);
	FUZZ_ASSERT(!jn_language(j, job, n, err, sizeof err), "the device's job is not HP-GL to the journal: %s", err);
	const char *restore = NULL;
	long k = jn_skip(j, job, n, &restore, err, sizeof err);
	FUZZ_ASSERT(k >= 0 && (size_t)k <= cut && restore, "skip of a cut at %zu: %ld %s", cut, k, k < 0 ? err : "");
	size_t safe = (size_t)k, rl = strlen(restore);
	char *rs = strdup(restore);
	jn_close(j, 0);
	unlink(jpath);
	FUZZ_ASSERT(rs, "out of memory");
	/* a fresh plotter: the part before the point, then the restore (after the closer) + the rest */
	const char *fresh = strchr(rs, ';');
	fresh = fresh ? fresh + 1 : rs;
	size_t fl = strlen(fresh);
	char *second = malloc(fl + n - safe + 1), *held = malloc(cut + rl + n - safe + 1);
	FUZZ_ASSERT(second && held, "out of memory");
	memcpy(second, fresh, fl);
	memcpy(second + fl, job + safe, n - safe);
	char **a, **b;
	size_t na, nb;
	int ra = segs(job, safe, &a, &na), rb = segs(second, fl + n - safe, &b, &nb);
	FUZZ_ASSERT(!ra && !rb, "cut %zu, point %zu: a part does not read (restore '%s')", cut, safe, rs);
	char **parts = merge(a, na, b, nb);
	int same = na + nb == nwhole;
	for (size_t i = 0; same && i < nwhole; i++)
		same = !strcmp(parts[i], whole[i]);
	FUZZ_ASSERT(same, "cut %zu, point %zu, restore '%s': the parts draw %zu segments, the job %zu (or others)",
		cut, safe, rs, na + nb, nwhole);
	free(parts);
	/* the plotter that holds the cut: its bytes + the resumed ones read strictly, every segment there */
	memcpy(held, job, cut);
	memcpy(held + cut, rs, rl);
	memcpy(held + cut + rl, job + safe, n - safe);
	char **h;
	size_t nh;
	FUZZ_ASSERT(!segs(held, cut + rl + n - safe, &h, &nh), "cut %zu ('%.16s|%.16s'), restore '%s': the joined bytes do not read",
		cut, job + (cut > 16 ? cut - 16 : 0), job + cut, rs);
	size_t i = 0, q = 0;
	while (i < nwhole && q < nh) {
		int c = strcmp(whole[i], h[q]);
		if (c == 0)
			i++, q++;
		else if (c > 0)
			q++;
		else
			break;
	}
	FUZZ_ASSERT(i == nwhole, "cut %zu, restore '%s': the joined bytes miss segment '%s'", cut, rs, whole[i]);
	free_segs(h, nh);
	free_segs(a, na);
	free_segs(b, nb);
	free_segs(whole, nwhole);
	free(second);
	free(held);
	free(rs);
	free(job);
	return 0;
}
