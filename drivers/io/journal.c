/* journal.c: the job journal of a device link: an HP-GL tracker over the acknowledged bytes
 * (resumable boundaries, modal state, a check sum of the prefix) written to a small text file. */
#include <errno.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "io/journal.h"

/* Modal commands replayed on resume, in the order they are sent (IP before SC). */
static const char *const modal_cmds[] = { "IP", "SC", "IW", "VS", "LT", "PW", "SI", "DI" };
#define NMODAL (sizeof modal_cmds / sizeof modal_cmds[0])

typedef struct {
	double pen;                 /* SP's number as sent (a double: any number the job gives) */
	int pendown, relative, pos_known;
	double x, y;
	char modal[NMODAL][64];
	char cmd[3];                /* the command a mid-command boundary lies in */
	int mid;
	unsigned long pages, cmds;
} hstate_t;

struct jn {
	char *path, *name;
	hstate_t st, safe_st;
	unsigned long long off, safe;
	uint64_t hash, safe_hash;
	/* the parser */
	char mn[3];
	int nmn, in_label;
	char num[32];
	int nnum, nargs;
	double args[2];
	char text[64];
	size_t ntext;
	/* resuming */
	int skipping;
	unsigned long long skip_to;
	uint64_t want_hash;
	char restore[768];
	unsigned long long held_to;   /* resuming: the device had the job up to here (acked) */
	char closer[4096 + 800];      /* resuming: what ends the device's partial command, + restore */
	/* the job's language: 0 not looked at yet, 1 HP-GL, -1 refused */
	int lang;
	int created;                /* jn_create made the file (removed again when refused) */
};

static int positional(const char *m)
{
	return !strcmp(m, "PU") || !strcmp(m, "PD") || !strcmp(m, "PA") || !strcmp(m, "PR");
}

static void boundary(jn_t *j, unsigned long long at, int mid)
{
	if (!j->st.pos_known)
		return;   /* after an arc or a label: no exact restart point until the next PA */
	j->safe = at;
	j->safe_hash = j->hash;
	j->safe_st = j->st;
	j->safe_st.mid = mid;
	memcpy(j->safe_st.cmd, j->mn, sizeof j->mn);
}

/* A number ended: a coordinate pair moves the pen; returns 1 when a pair completed. */
static int end_number(jn_t *j)
{
	if (!j->nnum)
		return 0;
	j->num[j->nnum] = 0;
	double v = strtod(j->num, NULL);
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

static void end_command(jn_t *j)
{
	end_number(j);
	if (j->nmn == 2) {
		size_t n = j->ntext < sizeof j->text ? j->ntext : sizeof j->text - 1;
		while (n > 2 && !((j->text[n - 1] >= '0' && j->text[n - 1] <= '9') || j->text[n - 1] == '.'))
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
static void start_command(jn_t *j)
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

static void feed(jn_t *j, unsigned char c)
{
	unsigned long long at = j->off++;
	j->hash = (j->hash ^ c) * 0x100000001b3ULL;
	if (j->ntext < sizeof j->text)
		j->text[j->ntext++] = (char)c;
	if (j->in_label) {
		if (c == 3) {
			j->in_label = 0;
			end_command(j);
		}
		return;
	}
	if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')) {
		if (j->nmn == 2) {
			end_command(j);
			j->text[0] = (char)c;
			j->ntext = 1;
		}
		j->mn[j->nmn++] = (char)(c & ~0x20);
		j->mn[j->nmn] = 0;
		if (j->nmn == 2)
			start_command(j);
		return;
	}
	if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') {
		if (j->nnum + 1 < (int)sizeof j->num)
			j->num[j->nnum++] = (char)c;
		return;
	}
	if (c == ';') {
		end_command(j);
		boundary(j, at + 1, 0);
		return;
	}
	int pair = end_number(j);
	if (pair && c == ',' && j->nmn == 2)
		boundary(j, at + 1, 1);   /* within PU/PD/PA/PR, after a whole pair */
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

static void make_restore(const hstate_t *s, char *buf, size_t len)
{
	char a[48], b[48];
	size_t n = 0;
#define PUT(...) do { int w_ = snprintf(buf + n, n < len ? len - n : 0, __VA_ARGS__); if (w_ > 0) n += (size_t)w_; } while (0)
	if (s->pen > 0)
		PUT("SP%s;", hnum(a, sizeof a, s->pen));
	for (size_t k = 0; k < NMODAL; k++)
		if (s->modal[k][0])
			PUT("%s;", s->modal[k]);
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

static int save(jn_t *j, const char *state)
{
	char tmp[4200], restore[768];
	if (snprintf(tmp, sizeof tmp, "%s.tmp", j->path) >= (int)sizeof tmp)
		return -1;
	make_restore(&j->safe_st, restore, sizeof restore);
	FILE *f = fopen(tmp, "w");
	if (!f)
		return -1;
	fprintf(f, "LOCUS-JOURNAL 1\nname %s\nstate %s\nacked %llu\nsafe %llu\nhash %016" PRIx64
		"\npage %lu\ncommand %lu\nrestore %s\n", j->name, state, j->off, j->safe, j->safe_hash,
		j->safe_st.pages, j->safe_st.cmds, restore);
	if (fclose(f) != 0 || rename(tmp, j->path) != 0) {
		remove(tmp);
		return -1;
	}
	return 0;
}

static jn_t *alloc(const char *path, const char *name, char *err, size_t errlen)
{
	jn_t *j = calloc(1, sizeof *j);
	if (j) {
		j->path = strdup(path);
		j->name = strdup(name);
		j->hash = j->safe_hash = 0xcbf29ce484222325ULL;
		j->st.pos_known = 1;
		j->safe_st = j->st;
		if (j->path && j->name)
			return j;
		free(j->path);
		free(j->name);
		free(j);
	}
	snprintf(err, errlen, "%s: out of memory", path);
	errno = ENOMEM;
	return NULL;
}

jn_t *jn_create(const char *path, const char *name, char *err, size_t errlen)
{
	jn_t *j = alloc(path, name, err, errlen);
	if (j)
		j->created = 1;
	if (j && save(j, "running")) {
		snprintf(err, errlen, "%s: cannot write the job journal: %s", path, strerror(errno));
		jn_close(j, 0);
		return NULL;
	}
	return j;
}

jn_t *jn_resume(const char *path, const char *name, char *err, size_t errlen)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		snprintf(err, errlen, "%s: cannot read the job journal: %s", path, strerror(errno));
		return NULL;
	}
	jn_t *j = alloc(path, name, err, errlen);
	char line[1024], state[32] = "";
	int have = 0, lineno = 0, bad = 0;
	while (j && fgets(line, sizeof line, f)) {
		lineno++;
		line[strcspn(line, "\n")] = 0;
		if (lineno == 1)
			bad |= strcmp(line, "LOCUS-JOURNAL 1") != 0;
		else if (!strncmp(line, "acked ", 6))
			sscanf(line + 6, "%llu", &j->held_to);
		else if (!strncmp(line, "safe ", 5))
			have |= (sscanf(line + 5, "%llu", &j->skip_to) == 1) << 0;
		else if (!strncmp(line, "hash ", 5))
			have |= (sscanf(line + 5, "%" SCNx64, &j->want_hash) == 1) << 1;
		else if (!strncmp(line, "restore ", 8)) {
			snprintf(j->restore, sizeof j->restore, "%.700s", line + 8);
			have |= 1 << 2;
		} else if (!strncmp(line, "state ", 6))
			snprintf(state, sizeof state, "%.30s", line + 6);
	}
	fclose(f);
	if (!j)
		return NULL;
	if (bad || have != 7) {
		snprintf(err, errlen, "%s:%d: not a Locus job journal (expected LOCUS-JOURNAL 1 with safe, hash "
			"and restore lines)", path, bad ? 1 : lineno);
		jn_close(j, 0);
		return NULL;
	}
	if (!strcmp(state, "done")) {
		snprintf(err, errlen, "%s: that job was delivered whole: nothing to resume", path);
		jn_close(j, 0);
		return NULL;
	}
	j->skipping = 1;
	return j;
}

int jn_language(jn_t *j, const void *p, size_t n, char *err, size_t errlen)
{
	const unsigned char *b = p;
	size_t k = 0;
	if (j->lang)
		return j->lang > 0 ? 0 : -1;
	while (k < n && (b[k] == ' ' || b[k] == '\t' || b[k] == '\r' || b[k] == '\n'))
		k++;
	if (k == n)
		return 0;   /* nothing but blanks yet */
	unsigned c = b[k], d = k + 1 < n ? b[k + 1] : 0;
	/* HP-GL begins with a mnemonic, a ';', or a device-control escape ESC . */
	if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == ';' || (c == 27 && (d == '.' || d == 0))) {
		j->lang = 1;
		return 0;
	}
	const char *what = n - k >= 5 && !memcmp(b + k, "%PDF-", 5) ? "a PDF document"
		: n - k >= 2 && !memcmp(b + k, "%!", 2) ? "a PostScript document"
		: c == 27 ? "a printer-language job (PCL or an escape sequence)" : "not HP-GL (a raster or binary job)";
	j->lang = -1;
	snprintf(err, errlen, "%s: a job journal keeps HP-GL jobs only, and this job is %s: it cannot be "
		"resumed mid-document; nothing was sent: send it again without --journal (a failed job is "
		"then sent again whole)", j->name, what);
	return -1;
}

/* The restore, led by what ends the command the device may hold unfinished. The device had the
 * job up to held_to (the journal's acked count), past the safe point where the job goes on: a
 * number, a coordinate pair, a mnemonic or a label may be half there ("PD...,-11,-1,-"). A lone
 * terminator would leave a malformed number or an odd coordinate count, which a plotter reports
 * as an error or completes into a stroke to a wrong point; ESC.K would discard its buffer (what
 * it has not drawn yet), and IN would throw away state the restore does not replay. So the
 * partial command is finished with the job's own next bytes, up to where the command may end
 * (after a whole pair, the end of a label, before the next mnemonic), then ';': the device draws
 * what the job would have drawn there, and the restore brings it back to the safe point (those
 * few strokes are drawn twice, never a wrong one). rest (len bytes) is the job from the safe
 * point. With nothing held past the safe point the closer is the ';' alone (harmless after a
 * command or a whole pair); when the job's bytes at hand do not reach an end within 4096 bytes
 * (a longer label), the ';' too. */
static void make_closer(jn_t *j, const unsigned char *rest, size_t len)
{
	size_t held = j->held_to > j->off ? (size_t)(j->held_to - j->off) : 0, k = 0, end = 0;
	int found = 0;
	jn_t *c = malloc(sizeof *c);
	if (c && held <= len) {
		*c = *j;
		for (k = 0; k < held; k++)
			feed(c, rest[k]);
		for (; k <= len && k < held + 4096; k++) {
			int letter = k < len && ((rest[k] >= 'A' && rest[k] <= 'Z') || (rest[k] >= 'a' && rest[k] <= 'z'));
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
			feed(c, rest[k]);
		}
	}
	free(c);
	size_t n = 0;
	if (found && end > held && end - held < sizeof j->closer - sizeof j->restore - 2) {
		memcpy(j->closer, rest + held, end - held);
		n = end - held;
	}
	snprintf(j->closer + n, sizeof j->closer - n, ";%s", j->restore);
}

unsigned long long jn_held(const jn_t *j)
{
	return j->held_to;
}

int jn_skipping(const jn_t *j)
{
	return j->skipping;
}

long jn_skip(jn_t *j, const void *p, size_t n, const char **restore, char *err, size_t errlen)
{
	const unsigned char *b = p;
	size_t k = 0;
	*restore = NULL;
	while (k < n && j->off < j->skip_to)
		feed(j, b[k++]);
	if (j->off == j->skip_to) {
		if (j->hash != j->want_hash) {
			snprintf(err, errlen, "the job differs from the journaled one before byte %llu: resume with "
				"the same input and options", j->skip_to);
			return -1;
		}
		if (j->safe != j->skip_to) {
			snprintf(err, errlen, "the journal's point, byte %llu, is not a point where this job can go on "
				"(after a command or a whole coordinate pair): not this job's journal", j->skip_to);
			return -1;
		}
		/* the restore is the job's own state at the point (the tracker has just read the job up
		 * to it), not the file's line: a journal edited or damaged cannot send other HP-GL */
		make_restore(&j->safe_st, j->restore, sizeof j->restore);
		j->skipping = 0;
		make_closer(j, b + k, n - k);
		*restore = j->closer;
	}
	return (long)k;
}

int jn_ack(jn_t *j, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t k = 0; k < n; k++)
		feed(j, b[k]);
	return save(j, "running");
}

/* The program's resume command (jn_set_command), or "". */
static char resume_cmd[1024];

void jn_set_command(const char *cmd)
{
	snprintf(resume_cmd, sizeof resume_cmd, "%s", cmd ? cmd : "");
}

void jn_where(const jn_t *j, char *buf, size_t len)
{
	if (resume_cmd[0]) {
		snprintf(buf, len, "page %lu, command %lu (byte %llu of the job) reached; resume with: %s",
			j->safe_st.pages ? j->safe_st.pages : 1, j->safe_st.cmds, j->safe, resume_cmd);
		return;
	}
	char name[600];
	const char *q = strstr(j->name, "journal=");
	if (q)
		snprintf(name, sizeof name, "%.*sresume=%s", (int)(q - j->name), j->name, q + 8);
	else
		snprintf(name, sizeof name, "%s", j->name);
	snprintf(buf, len, "page %lu, command %lu (byte %llu of the job) reached; resume with -o '%s'",
		j->safe_st.pages ? j->safe_st.pages : 1, j->safe_st.cmds, j->safe, name);
}

int jn_close(jn_t *j, int done)
{
	int rc = 0;
	if (!j)
		return 0;
	if (j->lang < 0) {
		if (j->created)
			remove(j->path);   /* refused before a byte went: no journal to resume */
	} else if (done)
		rc = save(j, "done");
	else if (!j->skipping)
		rc = save(j, "interrupted");   /* even at 0: a failed job is never left "running" */
	free(j->path);
	free(j->name);
	free(j);
	return rc;
}
