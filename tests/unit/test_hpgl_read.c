/* test_hpgl_read.c: the HP-GL reader on hand-written cases and on every file of the real corpus. */
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include "hpgl/read/hpgl_read.h"
#include "unit.h"

#define CORPUS "../shared/corpus/hpgl/"

static int rd(const char *s, hpgl_doc_t *d, char *err)
{
	return hpgl_read_mem(s, strlen(s), "t", d, err, 256);
}

static int near(double a, double b)
{
	return fabs(a - b) < 1e-6;
}

static void hand(void)
{
	hpgl_doc_t d;
	char err[256];
	int rc = rd("IN;SP1;PU0,0;PD100,0,100,100;PU;", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1 && d.strokes[0].n == 3 && d.strokes[0].pen == 1, "plain: one stroke of 3 points, pen 1");
	CHECK(d.nstrokes == 1 && d.strokes[0].cmd == 3 && d.strokes[0].offset == 13, "plain: the stroke's command index 3 at byte 13 (cmd %zu, byte %zu)",
		d.nstrokes ? d.strokes[0].cmd : 0, d.nstrokes ? d.strokes[0].offset : 0);
	CHECK(d.ncmds == 5 && near(hpgl_doc_length(&d, -1), 200), "plain: 5 commands, length 200");
	hpgl_doc_free(&d);

	rc = rd("in sp2 pa pu10,10 pd20,20", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1 && d.strokes[0].pen == 2 && near(d.pts[1].x, 20) && near(d.pts[0].y, 10),
		"lower case, blanks, no ';'");
	hpgl_doc_free(&d);

	rc = rd("INSP1PAPU100,0PRPD10,0,0,10PAPU0,0", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1 && d.strokes[0].n == 3 && near(d.pts[2].x, 110) && near(d.pts[2].y, 10),
		"no separators at all, PA/PR switching");
	hpgl_doc_free(&d);

	rc = rd("IN;\r\nSP1;\r\nPU 0 0;PD 5 , 5;\r\n", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1 && near(d.pts[1].x, 5), "CRLF and blanks around parameters");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PE7<=__s_;", &d, err);   /* absolute move to 0,0 (_ _), then +10,0 (s _) */
	CHECK(rc == 0 && d.nstrokes == 1 && d.hpgl2 && near(d.pts[1].x, 10) && near(d.pts[1].y, 0),
		"PE 7-bit: absolute move, relative draws (%s)", rc ? err : "");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PA100,100;CI50;", &d, err);
	int round = rc == 0 && d.nstrokes == 1 && d.strokes[0].n == 73;
	for (size_t i = 0; round && i < d.strokes[0].n; i++)
		round = fabs(hypot(d.pts[i].x - 100, d.pts[i].y - 100) - 50) < 1e-9;
	CHECK(round, "CI: 72 chords of 5 degrees at radius 50");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PA10,10;LBHello\003;DT#;LBab#;", &d, err);
	CHECK(rc == 0 && d.nlabels == 2 && !strcmp(d.labels[0].text, "Hello") && !strcmp(d.labels[1].text, "ab") &&
		near(d.labels[0].x, 10), "LB with ETX, DT changes the terminator");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PA0,0;PM0;PD100,0,100,100,0,100;PM2;FP;EP;", &d, err);
	CHECK(rc == 0 && d.nstrokes == 2 && d.strokes[0].kind == HPGL_RS_FILL && d.strokes[1].kind == HPGL_RS_EDGE &&
		d.strokes[0].n == 5, "PM/FP/EP: the polygon's contour, closed, as a fill and an edge");
	hpgl_doc_free(&d);

	rc = rd("IN;IP0,0,1000,1000;SC0,10,0,10;SP1;PA0,0;PD10,10;", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1 && near(d.pts[1].x, 1000) && near(d.pts[1].y, 1000), "SC scales user units by P1/P2");
	hpgl_doc_free(&d);

	/* a plotter keeps the user units on P1 and P2 when IP moves them: (10,10) lands on the new
	 * P2 (2000,3000), and after IP; on the default P2 (10603,7721) */
	rc = rd("IN;IP0,0,1000,1000;SC0,10,0,10;IP500,1000,2000,3000;SP1;PA0,0;PD10,10;IP;PU0,0;PD10,10;", &d, err);
	CHECK(rc == 0 && d.nstrokes == 2 && near(d.pts[0].x, 500) && near(d.pts[0].y, 1000) && near(d.pts[1].x, 2000)
		&& near(d.pts[1].y, 3000) && near(d.pts[2].x, 603) && near(d.pts[2].y, 521) && near(d.pts[3].x, 10603)
		&& near(d.pts[3].y, 7721), "IP after SC: the user units follow P1 and P2, IP; restores the defaults");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PA10,10;RA20,30;EA20,30;", &d, err);
	CHECK(rc == 0 && d.nstrokes == 2 && d.strokes[0].kind == HPGL_RS_FILL && d.strokes[1].n == 5 && near(d.pts[2].y, 30),
		"RA and EA rectangles");
	hpgl_doc_free(&d);

	rc = rd("\033.(\033.I81;;17:\033.N;19:IN;SP1;PD10,10;", &d, err);
	CHECK(rc == 0 && d.nescapes == 3 && d.nstrokes == 1, "device-control escapes skipped (%s)", rc ? err : "");
	hpgl_doc_free(&d);

	rc = rd("\033%-12345X@PJL ENTER LANGUAGE=HPGL2\n\033E\033%0BIN;SP1;PD1,1;\033%0A\033E", &d, err);
	CHECK(rc == 0 && d.nstrokes == 1, "PCL/PJL framing skipped (%s)", rc ? err : "");
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;PU;\032}}}\n", &d, err);
	CHECK(rc == 0 && d.trailing == 4, "trailing garbage tolerated and counted (%zu)", d.trailing);
	hpgl_doc_free(&d);

	rc = rd("IN;SP1;ZZ1,2;QQ;PD1,1;", &d, err);
	CHECK(rc == 0 && d.nunknown == 2 && !strcmp(d.unknown, "ZZ QQ"), "unknown commands skipped and listed ('%s')", d.unknown);
	hpgl_doc_free(&d);

	/* strict */
	rc = rd("IN;SP1;PD1,2,3;", &d, err);
	CHECK(rc < 0 && strstr(err, "byte 9") && strstr(err, "odd"), "odd coordinate count: %s", err);
	hpgl_doc_free(&d);
	rc = rd("IN;PA1,#2;", &d, err);
	CHECK(rc < 0 && strstr(err, "byte 7") && strstr(err, "0x23"), "a stray byte in parameters: %s", err);
	hpgl_doc_free(&d);
	rc = rd("IN;SP1;LBabc", &d, err);
	CHECK(rc < 0 && strstr(err, "not terminated"), "unterminated label: %s", err);
	hpgl_doc_free(&d);
	rc = rd("IN;3;SP1;", &d, err);
	CHECK(rc < 0 && strstr(err, "t: byte 3:"), "a stray byte before a command: %s", err);
	hpgl_doc_free(&d);
	rc = rd("IN;PE7<=__s", &d, err);
	CHECK(rc < 0 && strstr(err, "PE"), "PE data cut inside a pair: %s", err);
	hpgl_doc_free(&d);
	rc = rd("IN;PD-,3;", &d, err);
	CHECK(rc < 0 && strstr(err, "byte 5") && strstr(err, "malformed"), "malformed number: %s", err);
	hpgl_doc_free(&d);
}

/* What each corpus file must give (a few facts checked by reading the files by eye). */
static const struct {
	const char *file;
	size_t min_strokes, min_labels;
	int hpgl2;
} expect[] = {
	{ "acad-designjet-XANADU2.plt", 20, 0, 1 },
	{ "hp2xx-acad.hp", 100, 0, 0 },
	{ "hp2xx-arcs.hp", 3, 0, 0 },
	{ "hp2xx-cp.hp", 1, 3, 0 },
	{ "hp2xx-fill.plt", 16, 10, 1 },
	{ "hp2xx-fwedges.plt", 5, 0, 0 },
	{ "hp2xx-la.hp", 3, 0, 1 },
	{ "hp2xx-lo.hp", 2, 2, 0 },
	{ "hp2xx-pm.hp", 2, 0, 1 },
	{ "hp2xx-pw.hpg", 10, 0, 1 },
	{ "hp2xx-symbols.hp", 2, 0, 0 },
	{ "hp2xx-ul.hp", 5, 3, 1 },
	{ "hp2xx-win_1.hp", 20, 5, 0 },
	{ "inkscape-hpgl_output-shapes.hpgl", 20, 0, 0 },
	{ "kicad-laser-B_Cu.plt", 50, 0, 1 },
	{ "plotutils-plot2hpgl.yout.hpgl", 20, 1, 1 },
	{ "vk2bea-RS-analyzer.hpgl", 50, 10, 0 },
};

static void corpus(void)
{
	size_t n = sizeof expect / sizeof expect[0], seen = 0;
	for (size_t k = 0; k < n; k++) {
		char path[512], err[256];
		snprintf(path, sizeof path, CORPUS "%s", expect[k].file);
		FILE *f = fopen(path, "rb");
		if (!f) {
			CHECK(0, "corpus file %s is there", path);
			continue;
		}
		hpgl_doc_t d;
		int rc = hpgl_read_stream(f, path, &d, err, sizeof err);
		fclose(f);
		CHECK(rc == 0 && d.nstrokes >= expect[k].min_strokes && d.nlabels >= expect[k].min_labels &&
			d.hpgl2 == expect[k].hpgl2, "%s: %zu commands, %zu strokes (%.0f pu), %zu labels, hpgl2 %d, "
			"skipped '%s', %zu escapes, %zu trailing bytes%s%s", expect[k].file, d.ncmds, d.nstrokes,
			hpgl_doc_length(&d, -1), d.nlabels, d.hpgl2, d.unknown, d.nescapes, d.trailing, rc ? ": " : "", rc ? err : "");
		hpgl_doc_free(&d);
	}
	/* every file of the corpus is in the table */
	DIR *dir = opendir(CORPUS);
	struct dirent *e;
	size_t unlisted = 0;
	while (dir && (e = readdir(dir))) {
		if (e->d_name[0] == '.' || !strcmp(e->d_name, "README.md"))
			continue;
		seen++;
		int found = 0;
		for (size_t k = 0; k < n; k++)
			found |= !strcmp(expect[k].file, e->d_name);
		if (!found) {
			unlisted++;
			printf("# corpus file %s is not in the table\n", e->d_name);
		}
	}
	if (dir)
		closedir(dir);
	CHECK(seen == n && unlisted == 0, "every corpus file is read (%zu files, %zu in the table)", seen, n);
}

/* Mutations of every corpus file (bytes changed, inserted, the file cut) never crash the reader
 * (the suite also runs under ASan/UBSan): each read succeeds or names a byte offset. */
static void mutations(void)
{
	uint64_t rng = 0x2545F4914F6CDD1DULL;
	size_t n = sizeof expect / sizeof expect[0], runs = 0, bad = 0, errors = 0;
	for (size_t k = 0; k < n; k++) {
		char path[512], err[256];
		snprintf(path, sizeof path, CORPUS "%s", expect[k].file);
		FILE *f = fopen(path, "rb");
		if (!f)
			continue;
		static unsigned char buf[1 << 17], mut[(1 << 17) + 16];
		size_t len = fread(buf, 1, sizeof buf, f);
		fclose(f);
		for (int m = 0; m < 60; m++) {
			memcpy(mut, buf, len);
			size_t ml = len;
			for (int e = 0; e < 1 + m % 4; e++) {
				rng ^= rng << 13;
				rng ^= rng >> 7;
				rng ^= rng << 17;
				size_t at = ml ? (size_t)(rng % ml) : 0;
				switch ((rng >> 32) % 4) {
				case 0: mut[at] = (unsigned char)(rng >> 40); break;           /* any byte */
				case 1: mut[at] = "0123456789,;.-PUDAEC\033\003"[(rng >> 40) % 22]; break;
				case 2: ml = at; break;                                          /* cut */
				default:                                                         /* insert */
					if (ml < sizeof mut - 1) {
						memmove(mut + at + 1, mut + at, ml - at);
						mut[at] = (unsigned char)(rng >> 48);
						ml++;
					}
				}
			}
			hpgl_doc_t d;
			int rc = hpgl_read_mem(mut, ml, "m", &d, err, sizeof err);
			runs++;
			if (rc) {
				errors++;
				if (!strstr(err, "m: byte "))
					bad++;
			}
			hpgl_doc_free(&d);
		}
	}
	CHECK(runs > 0 && bad == 0, "%zu mutated corpus files read without a crash; %zu refused, each naming a byte offset",
		runs, errors);
}

int main(void)
{
	hand();
	DIR *dir = opendir(CORPUS);
	if (!dir) {   /* one line, counted by tests/run.sh; the hand-written cases still run */
		printf("SKIP test_hpgl_read: the corpus files and their mutations: " CORPUS " is absent (files made by other "
		       "programs; CI lays ../shared beside the clone)\n");
		return UNIT_DONE();
	}
	closedir(dir);
	corpus();
	mutations();
	return UNIT_DONE();
}
