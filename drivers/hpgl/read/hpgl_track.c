/* hpgl_track.c: the byte-at-a-time HP-GL tracker of a job going to a device (hpgl_track.h):
 * checkpoints, the modal state there, and the HP-GL that restores it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_lex.h"
#include "hpgl/read/hpgl_track.h"

/* Modal commands replayed on resume, in the order they are sent (IP before SC). */
static const char *const modal_cmds[] = { "IP", "SC", "IW", "VS", "LT", "PW", "SI", "DI" };
#define NMODAL (sizeof modal_cmds / sizeof modal_cmds[0])

typedef struct {
	double pen;                 /* SP's number as sent (a double: any number the job gives) */
	int pendown, relative, pos_known;
	double x, y;
	char modal[NMODAL][64];
	char cmd[3];                /* the command a mid-command checkpoint lies in */
	int mid;
	unsigned long pages, cmds;
} hstate_t;

struct hpgl_track {
	hstate_t st, safe_st;
	char mn[3];
	int nmn, in_label;
	char num[32];
	int nnum, nargs;
	double args[2];
	char text[64];
	size_t ntext;
};

/* The restore's room, and so what a resume prefix keeps for it. */
enum { RESTORE_MAX = 768 };

static int positional(const char *m)
{
	return hpgl_lex_coord(m) >= 0;
}

hpgl_track_t *hpgl_track_new(void)
{
	hpgl_track_t *k = calloc(1, sizeof *k);
	if (k) {
		k->st.pos_known = 1;
		k->safe_st = k->st;
	}
	return k;
}

void hpgl_track_free(hpgl_track_t *k)
{
	free(k);
}

/* A checkpoint after the current byte, where the position is known. 1 when there is one. */
static int boundary(hpgl_track_t *j, int mid)
{
	if (!j->st.pos_known)
		return 0;   /* after an arc or a label: no exact restart point until the next PA */
	j->safe_st = j->st;
	j->safe_st.mid = mid;
	memcpy(j->safe_st.cmd, j->mn, sizeof j->mn);
	return 1;
}

/* A number ended: a coordinate pair moves the pen; returns 1 when a pair completed. */
static int end_number(hpgl_track_t *j)
{
	if (!j->nnum)
		return 0;
	double v = hpgl_lex_value((const unsigned char *)j->num, (size_t)j->nnum);
	j->nnum = 0;
	if (!strcmp(j->mn, "SP")) {
		j->st.pen = v;   /* no cast: an SP parameter out of int's range was undefined behaviour */
		return 0;
	}
	if (!positional(j->mn))
		return 0;
	j->args[j->nargs++] = v;
	if (j->nargs < 2)
		return 0;
	j->nargs = 0;
	if (j->st.relative) {
		j->st.x += j->args[0];
		j->st.y += j->args[1];
	} else {
		j->st.x = j->args[0];
		j->st.y = j->args[1];
		j->st.pos_known = 1;
	}
	return 1;
}

static void end_command(hpgl_track_t *j)
{
	end_number(j);
	if (j->nmn == 2) {
		size_t n = j->ntext < sizeof j->text ? j->ntext : sizeof j->text - 1;
		while (n > 2 && !(hpgl_lex_digit((unsigned char)j->text[n - 1]) || j->text[n - 1] == '.'))
			n--;   /* the terminator, or the next command's first letter */
		j->text[n] = 0;
		for (size_t k = 0; k < NMODAL; k++)
			if (!strcmp(j->mn, modal_cmds[k]))
				snprintf(j->st.modal[k], sizeof j->st.modal[k], "%s", j->text);
		j->st.cmds++;
	}
	j->nmn = 0;
	j->mn[0] = 0;
	j->nargs = 0;
	j->ntext = 0;
}

/* The mnemonic is complete: the state it sets at once. */
static void start_command(hpgl_track_t *j)
{
	const char *m = j->mn;
	if (!strcmp(m, "PU"))
		j->st.pendown = 0;
	else if (!strcmp(m, "PD"))
		j->st.pendown = 1;
	else if (!strcmp(m, "PA"))
		j->st.relative = 0;
	else if (!strcmp(m, "PR"))
		j->st.relative = 1;
	else if (!strcmp(m, "LB"))
		j->in_label = 1;
	else if (!strcmp(m, "PG"))
		j->st.pages++;
	else if (!strcmp(m, "IN")) {
		unsigned long pages = j->st.pages + 1, cmds = j->st.cmds;
		memset(&j->st, 0, sizeof j->st);
		j->st.pos_known = 1;
		j->st.pages = pages;
		j->st.cmds = cmds;
	}
	if (!strcmp(m, "AA") || !strcmp(m, "AR") || !strcmp(m, "PE") || !strcmp(m, "LB") || !strcmp(m, "BZ"))
		j->st.pos_known = 0;
}

int hpgl_track_byte(hpgl_track_t *j, unsigned char c)
{
	if (j->ntext < sizeof j->text)
		j->text[j->ntext++] = (char)c;
	if (j->in_label) {
		if (c == HPGL_LEX_TERM_DEFAULT) {   /* (DT is not followed here) */
			j->in_label = 0;
			end_command(j);
		}
		return 0;
	}
	if (hpgl_lex_letter(c)) {
		if (j->nmn == 2) {
			end_command(j);
			j->text[0] = (char)c;
			j->ntext = 1;
		}
		j->mn[j->nmn++] = hpgl_lex_upper(c);
		j->mn[j->nmn] = 0;
		if (j->nmn == 2)
			start_command(j);
		return 0;
	}
	if (hpgl_lex_numchar(c)) {
		if (j->nnum + 1 < (int)sizeof j->num)
			j->num[j->nnum++] = (char)c;
		return 0;
	}
	if (c == ';') {
		end_command(j);
		return boundary(j, 0);
	}
	int pair = end_number(j);
	if (pair && c == ',' && j->nmn == 2)
		return boundary(j, 1);   /* within PU/PD/PA/PR, after a whole pair */
	return 0;
}

/* A number as HP-GL writes it: no exponent (an 'e' would be read as a mnemonic). */
static const char *hnum(char *b, size_t n, double v)
{
	if (v != v || v > 1e38 || v < -1e38)
		snprintf(b, n, "%.0f", v != v ? 0.0 : v > 0 ? 1e38 : -1e38);   /* (no such number is read) */
	else if (v >= 1e9 || v <= -1e9)
		snprintf(b, n, "%.0f", v);
	else if (v < 1e-4 && v > -1e-4)
		snprintf(b, n, "%.6f", v);
	else
		snprintf(b, n, "%.10g", v);   /* no exponent between 1e-4 and 1e9 */
	return b;
}

void hpgl_track_restore(const hpgl_track_t *k, char *buf, size_t len)
{
	const hstate_t *s = &k->safe_st;
	char a[48], b[48];
	size_t n = 0;
#define PUT(...) do { int w_ = snprintf(buf + n, n < len ? len - n : 0, __VA_ARGS__); if (w_ > 0) n += (size_t)w_; } while (0)
	if (s->pen > 0)
		PUT("SP%s;", hnum(a, sizeof a, s->pen));
	for (size_t m = 0; m < NMODAL; m++)
		if (s->modal[m][0])
			PUT("%s;", s->modal[m]);
	PUT("PU;PA%s,%s;", hnum(a, sizeof a, s->x), hnum(b, sizeof b, s->y));
	if (s->relative)
		PUT("PR;");
	if (s->pendown)
		PUT("PD;");
	if (s->mid)
		PUT("%s", s->cmd);
#undef PUT
	if (n >= len && len)
		buf[len - 1] = 0;
}

/* The restore, led by what ends the command the device may hold unfinished. The device had the
 * job up to held bytes past the checkpoint where the job goes on: a number, a coordinate pair,
 * a mnemonic or a label may be half there ("PD...,-11,-1,-"). A lone terminator would leave a
 * malformed number or an odd coordinate count, which a plotter reports as an error or completes
 * into a stroke to a wrong point; ESC.K would discard its buffer (what it has not drawn yet),
 * and IN would throw away state the restore does not replay. So the partial command is finished
 * with the job's own next bytes, up to where the command may end (after a whole pair, the end of
 * a label, before the next mnemonic), then ';': the device draws what the job would have drawn
 * there, and the restore brings it back to the checkpoint (those few strokes are drawn twice,
 * never a wrong one). With nothing held past the checkpoint the closer is the ';' alone
 * (harmless after a command or a whole pair); when the job's bytes at hand do not reach an end
 * within 4096 bytes (a longer label), the ';' too. */
void hpgl_track_resume(const hpgl_track_t *j, const unsigned char *rest, size_t len, size_t held,
	char *out, size_t outlen)
{
	char restore[RESTORE_MAX];
	size_t k = 0, end = 0;
	int found = 0;
	hpgl_track_restore(j, restore, sizeof restore);
	hpgl_track_t *c = malloc(sizeof *c);
	if (c && held <= len) {
		*c = *j;
		for (k = 0; k < held; k++)
			hpgl_track_byte(c, rest[k]);
		for (; k <= len && k < held + 4096; k++) {
			int letter = k < len && hpgl_lex_letter(rest[k]);
			/* the command may end here: nothing half-read, a positional command's pairs whole */
			if (!c->in_label && c->nnum == 0
				&& (c->nmn == 0 || (c->nmn == 2 && (letter || (positional(c->mn) && c->nargs == 0
					&& (k == held || rest[k - 1] == ',')))))) {
				found = 1;
				end = k;
				break;
			}
			if (k == len)
				break;
			hpgl_track_byte(c, rest[k]);
		}
	}
	free(c);
	size_t n = 0;
	if (found && end > held && outlen > RESTORE_MAX + 2 && end - held < outlen - RESTORE_MAX - 2) {
		memcpy(out, rest + held, end - held);
		n = end - held;
	}
	snprintf(out + n, outlen - n, ";%s", restore);
}

unsigned long hpgl_track_page(const hpgl_track_t *k)
{
	return k->safe_st.pages;
}

unsigned long hpgl_track_command(const hpgl_track_t *k)
{
	return k->safe_st.cmds;
}

int hpgl_sniff(const unsigned char *b, size_t n, const char **what)
{
	size_t k = 0;
	while (k < n && (b[k] == ' ' || b[k] == '\t' || b[k] == '\r' || b[k] == '\n'))
		k++;
	if (k == n)
		return 0;   /* nothing but blanks yet */
	unsigned c = b[k], d = k + 1 < n ? b[k + 1] : 0;
	/* HP-GL begins with a mnemonic, a ';', or a device-control escape ESC . */
	if (hpgl_lex_letter((unsigned char)c) || c == ';' || (c == 27 && (d == '.' || d == 0)))
		return 1;
	*what = n - k >= 5 && !memcmp(b + k, "%PDF-", 5) ? "a PDF document"
		: n - k >= 2 && !memcmp(b + k, "%!", 2) ? "a PostScript document"
		: c == 27 ? "a printer-language job (PCL or an escape sequence)" : "not HP-GL (a raster or binary job)";
	return -1;
}
