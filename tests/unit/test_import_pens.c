/* test_import_pens.c: `locus-meta import`'s HP-GL pens from a profile's carousel where the file
 * sets no PC colour or PW width (mimp_hpgl_pens), the file's own settings winning. */
#include <stdlib.h>
#include "hpgl/hpgl.h"
#include "import/meta_import.h"
#include "membuf.h"
#include "unit.h"

/* Import the HP-GL text with the pens; the meta text (NUL-terminated, the caller frees) or NULL. */
static char *import(const char *hpgl, const char *pens, int *rc, char *err, size_t errlen)
{
	membuf_t m = { 0 };
	meta_writer_t *w = meta_writer_new(membuf_write, &m, META_ENC_TEXT);
	*rc = mimp_hpgl_pens(hpgl, strlen(hpgl), "t.hpgl", 4.0, pens, w, err, errlen);
	meta_writer_close(w);
	membuf_write(&m, "", 1);
	return m.p;
}

/* 1 when the text has the whole line. */
static int has_line(const char *t, const char *line)
{
	size_t n = strlen(line);
	for (const char *p = t; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
		if (!strncmp(p, line, n) && (p[n] == '\n' || p[n] == 0))
			return 1;
	return 0;
}

int main(void)
{
	char err[300];
	int rc;
	/* pen 1: the carousel's colour and width (1 mm = 4 pixels); pen 2: the file's PW 0.5 mm
	 * (2 pixels) over the carousel's 0.25 mm, the carousel's red (the profiles' ink red, #d02020);
	 * pen 3: the file's PC over the carousel's blue, the spec's default width (0.3 mm: 1.2 pixels) */
	const char *f = "IN;SP1;PA0,0;PD4000,0;SP2;PW0.5,2;PU0,1000;PD4000,1000;"
		"SP3;PC3,1,2,3;PU0,2000;PD4000,2000;";
	char *t = import(f, "1=#102030:1mm,2=red:0.25mm,3=blue", &rc, err, sizeof err);
	CHECK(rc == 0, "import with a carousel: %d %s", rc, rc ? err : "");
	CHECK(t && has_line(t, "colour #102030") && has_line(t, "width 4"), "pen 1: the carousel's colour and 1 mm");
	CHECK(t && has_line(t, "colour #d02020") && has_line(t, "width 2"), "pen 2: the carousel's red, the file's PW 0.5 mm");
	CHECK(t && has_line(t, "colour #010203") && has_line(t, "width 1.2") && !has_line(t, "colour #0000ff"),
		"pen 3: the file's PC, the default width");
	free(t);
	/* without a carousel: hp2xx's colours and HP-GL/2's 0.35 mm (the file has PW: HP-GL/2) */
	t = import(f, NULL, &rc, err, sizeof err);
	CHECK(rc == 0 && t && has_line(t, "width 1.4") && !has_line(t, "width 4") && has_line(t, "colour #ff0000"),
		"no carousel: the defaults");
	free(t);
	/* a built-in profile's carousel: the 7475A's pen 5 is magenta (hp2xx's pen 5 is cyan) */
	const hpgl_profile_t *p = hpgl_profile_find("7475a");
	t = import("IN;SP5;PA0,0;PD4000,0;", p ? p->pens : "", &rc, err, sizeof err);
	CHECK(p && rc == 0 && t && has_line(t, "colour #ff00ff"), "7475A profile: pen 5 magenta");
	free(t);
	/* a bad carousel: 64, one line about the pens */
	t = import("IN;SP1;PD1,1;", "1=nosuchcolour", &rc, err, sizeof err);
	CHECK(rc == -64 && !strncmp(err, "pens: ", 6) && !strchr(err, '\n'), "bad pens: -64 '%s'", err);
	free(t);
	return UNIT_DONE();
}
