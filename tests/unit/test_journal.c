/* test_journal.c: the job journal's restore string gives back the modal state of a hand-made
 * HP-GL job (SP, IP, SC, IW, VS, LT, PW, SI, DI, the position, PR, the pen down) wherever the cut
 * falls: for every byte the device may have acknowledged, the journal's point and its restore
 * are checked two ways. The restore holds the last value of each modal command before the point,
 * as the job set it; and through the HP-GL reader, the part before the point plus restore + the
 * rest on a fresh plotter draw the segments of the whole job, each once (SC and IP change where
 * they fall, so a restore without them draws elsewhere). And on the plotter that still holds
 * the cut-off part (the sender killed mid-number), the bytes before the cut plus the resumed
 * bytes read cleanly with the HP-GL reader (no malformed number, no odd coordinate count) and
 * draw every segment of the job (a few again, none wrong). */
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_read.h"
#include "hpgl/hpgl_link.h"
#include "io/journal.h"
#include "unit.h"

/* Every modal command changes after the first strokes, and again later, between strokes drawn
 * with PD and PR, across a pen change and a second page. (IP comes before SC each time: the HP-GL
 * reader keeps a scaling computed when SC came, where a plotter rescales to a later IP.) */
static const char job[] =
	"IN;SP1;IP0,0,4000,4000;SC0,100,0,100;PU10,10;PD20,10,20,20;"
	"VS10;LT2,4;PW0.5;SI0.2,0.3;DI1,0;IW0,0,5000,5000;PU30,30;PD40,30,40,40;"
	"SP2;IP100,100,4100,4100;SC0,200,0,200;LT;PU50,50;PR;PD10,0,0,10,-10,0;PA;"
	"VS20;PW0.35;SI0.1,0.15;DI0,1;PU70,70;PD80,70,80,80,90,90;"
	"PG;SP3;LT1;PU5,5;PD15,5,15,15;";

static const char *const modal[] = { "IP", "SC", "IW", "VS", "LT", "PW", "SI", "DI", "SP" };

static int cmp_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The segments of HP-GL text (n bytes), one "pen x,y x,y" string each (malloc'd, *nseg of
 * them). A text cut after a comma is closed as hpgl-segments does. */
static char **segments(const char *txt, size_t n, int *nseg)
{
	char *buf = malloc(n + 2), err[256];
	memcpy(buf, txt, n);
	while (n > 0 && buf[n - 1] == ',')
		n--;
	buf[n++] = ';';
	hpgl_doc_t d;
	memset(&d, 0, sizeof d);
	hpgl_read_mem(buf, n, "job", &d, err, sizeof err);
	size_t cap = 16, k = 0;
	char **v = malloc(cap * sizeof *v);
	for (size_t s = 0; s < d.nstrokes; s++)
		for (size_t i = 1; i < d.strokes[s].n; i++) {
			const hpgl_rpt_t *a = &d.pts[d.strokes[s].start + i - 1], *b = a + 1;
			if (a->x > b->x || (a->x == b->x && a->y > b->y)) {
				const hpgl_rpt_t *t = a;
				a = b;
				b = t;
			}
			if (k == cap)
				v = realloc(v, (cap *= 2) * sizeof *v);
			v[k] = malloc(96);
			snprintf(v[k++], 96, "%d %.3f,%.3f %.3f,%.3f", d.strokes[s].pen, a->x, a->y, b->x, b->y);
		}
	hpgl_doc_free(&d);
	free(buf);
	*nseg = (int)k;
	return v;
}

/* Two lists of segments merged and sorted into one newline-joined string. */
static char *joined(char **a, int na, char **b, int nb)
{
	char **v = malloc(((size_t)na + (size_t)nb + 1) * sizeof *v);
	memcpy(v, a, (size_t)na * sizeof *v);
	if (nb)
		memcpy(v + na, b, (size_t)nb * sizeof *v);
	qsort(v, (size_t)(na + nb), sizeof *v, cmp_str);
	size_t len = 1;
	for (int i = 0; i < na + nb; i++)
		len += strlen(v[i]) + 1;
	char *s = malloc(len), *p = s;
	*p = 0;
	for (int i = 0; i < na + nb; i++) {
		p += sprintf(p, "%s\n", v[i]);
		free(v[i]);
	}
	free(v);
	free(a);
	free(b);
	return s;
}

/* The text of the last command mn ("SC0,200,0,200") that ends at or before byte at, or "". */
static void last_set(const char *mn, size_t at, char *out, size_t len)
{
	out[0] = 0;
	for (size_t k = 0; k + 2 <= at; k++) {
		if (job[k] != mn[0] || job[k + 1] != mn[1] || (k > 0 && job[k - 1] != ';'))
			continue;
		size_t e = k + 2;
		while (job[e] && job[e] != ';')
			e++;
		if (e < at)
			snprintf(out, len, "%.*s;", (int)(e - k), job + k);
	}
}

int main(void)
{
	const char *dir = getenv("T");
	char path[512], err[512];
	hpgl_link_register();   /* the journal's checkpoints are HP-GL's */
	snprintf(path, sizeof path, "%s/test_journal.jnl", dir && dir[0] ? dir : "/tmp");
	size_t n = strlen(job);
	int nwhole;
	char **wv = segments(job, n, &nwhole);
	char *whole = joined(wv, nwhole, NULL, 0);
	int bad_text = 0, bad_draw = 0, bad_join = 0, cuts = 0, points = 0;
	char join_bad[1400] = "";
	unsigned long long last_safe = ~0ULL;
	char first_bad[1400] = "", draw_bad[1400] = "";
	for (size_t cut = 1; cut < n; cut++) {
		jn_t *j = jn_create(path, "usb:03f0:0107?journal=x", err, sizeof err);
		if (!j || jn_ack(j, job, cut) || jn_close(j, 0)) {
			CHECK(0, "journal for a cut at %zu: %s", cut, err);
			break;
		}
		j = jn_resume(path, "usb:03f0:0107?resume=x", err, sizeof err);
		if (!j) {
			CHECK(0, "resume of a cut at %zu: %s", cut, err);
			break;
		}
		const char *restore = NULL;
		long k = jn_skip(j, job, n, &restore, err, sizeof err);
		char rest[1024];
		snprintf(rest, sizeof rest, "%s", restore ? restore : "");
		jn_close(j, 0);
		if (k < 0 || !restore) {
			CHECK(0, "skip of a cut at %zu: %s", cut, k < 0 ? err : "no restore");
			break;
		}
		size_t safe = (size_t)k;
		cuts++;
		if (safe != last_safe)
			points++;
		last_safe = safe;
		/* the text: each modal command as last set before the point */
		for (size_t m = 0; m < sizeof modal / sizeof modal[0]; m++) {
			char want[128];
			last_set(modal[m], safe, want, sizeof want);
			if (!strcmp(modal[m], "SP") && want[0])
				want[strlen(want) - 1] = 0;   /* "SP2": the pen is given as its number */
			if (want[0] && !strstr(rest, want)) {
				if (!bad_text++)
					snprintf(first_bad, sizeof first_bad, "cut %zu, point %zu: no %s in '%s'", cut, safe, want, rest);
			}
		}
		/* the plotter that holds the cut: job[0, cut) + restore + job[safe, n) reads strictly */
		size_t rl0 = strlen(rest);
		char *held = malloc(cut + rl0 + n - safe + 1), jerr[256];
		memcpy(held, job, cut);
		memcpy(held + cut, rest, rl0);
		memcpy(held + cut + rl0, job + safe, n - safe);
		hpgl_doc_t hd;
		memset(&hd, 0, sizeof hd);
		int rr = hpgl_read_mem(held, cut + rl0 + n - safe, "joined", &hd, jerr, sizeof jerr);
		hpgl_doc_free(&hd);
		int nh;
		char **hv = segments(held, cut + rl0 + n - safe, &nh);
		char *hs = joined(hv, nh, NULL, 0);
		/* every segment of the whole is there (the joined list, sorted, holds the whole's) */
		int missing = 0;
		for (char *w = whole, *e; *w; w = e + 1) {
			e = strchr(w, '\n');
			char line[128];
			snprintf(line, sizeof line, "\n%.*s\n", (int)(e - w), w);
			char *big = malloc(strlen(hs) + 2);
			sprintf(big, "\n%s", hs);
			if (!strstr(big, line))
				missing++;
			free(big);
		}
		if (rr || missing) {
			if (!bad_join++)
				snprintf(join_bad, sizeof join_bad, "cut %zu ('%.20s|'), restore '%s': %s%d segments missing",
					cut, job + (cut > 20 ? cut - 20 : 0), rest, rr ? jerr : "", missing);
		}
		free(hs);
		free(held);
		/* the drawing: prefix, then restore + rest on a fresh plotter (which takes the closer of
		 * the held command, up to the restore's first ';', as stray bytes: left out here) */
		const char *fresh = strchr(rest, ';');
		fresh = fresh ? fresh + 1 : rest;
		size_t rl = strlen(fresh);
		char *second = malloc(rl + n - safe + 1);
		memcpy(second, fresh, rl);
		memcpy(second + rl, job + safe, n - safe);
		int na, nb;
		char **a = segments(job, safe, &na), **b = segments(second, rl + n - safe, &nb);
		char *parts = joined(a, na, b, nb);
		if (strcmp(parts, whole)) {
			if (!bad_draw++)
				snprintf(draw_bad, sizeof draw_bad, "cut %zu, point %zu, restore '%s': the parts draw otherwise", cut, safe, rest);
		}
		free(parts);
		free(second);
	}
	CHECK(cuts == (int)n - 1 && points > 20, "a journal for each of the %d cuts (%d distinct resume points)", cuts, points);
	CHECK(bad_text == 0, "the restore gives back IP SC IW VS LT PW SI DI and the pen as last set before the point%s%s",
		bad_text ? ": " : "", first_bad);
	CHECK(bad_draw == 0, "the part before the point plus restore and the rest draw the whole job's %d segments once, at every cut%s%s",
		nwhole, bad_draw ? ": " : "", draw_bad);
	/* numbers out of int's range: SP's went through (int) (undefined; UBSan under SANITIZE=1),
	 * and the restore wrote 1e+20, which HP-GL reads as a mnemonic */
	{
		static const char big[] = "IN;SP123456789012345678901;PU;PA100000000000000000000,-3;";
		jn_t *jb = jn_create(path, "usb:03f0:0107?journal=x", err, sizeof err);
		int okb = jb && !jn_ack(jb, big, sizeof big - 1) && !jn_close(jb, 0);
		char line[1024] = "";
		FILE *f = okb ? fopen(path, "r") : NULL;
		while (f && fgets(line, sizeof line, f))
			if (!strncmp(line, "restore ", 8))
				break;
		if (f)
			fclose(f);
		CHECK(okb && strstr(line, "SP1234567890123456") && strstr(line, "PA100000000000000000000,-3;") && !strchr(line + 8, 'e') && !strchr(line + 8, 'E'),
			"huge SP and PA numbers: the restore writes them whole, no exponent: %s", line);
	}
	CHECK(bad_join == 0, "with the cut part still in the plotter, the joined bytes read cleanly (strict) and draw every segment, at every cut%s%s",
		bad_join ? ": " : "", join_bad);
	free(whole);
	remove(path);
	return UNIT_DONE();
}
