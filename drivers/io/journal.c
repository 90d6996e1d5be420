/* journal.c: the job journal of a device link: the registered language's tracker (io/lang.h)
 * over the acknowledged bytes finds the checkpoints; the journal keeps the last one's offset, a
 * check sum of the job up to it and the language's restore, in a small text file. */
#include <errno.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "io/journal.h"
#include "io/lang.h"

struct jn {
	char *path, *name;
	const io_lang_t *lang;      /* the registered language: its tracker finds the checkpoints */
	void *tr;                   /* that tracker */
	unsigned long long off, safe;
	uint64_t hash, safe_hash;
	/* resuming */
	int skipping;
	unsigned long long skip_to;
	uint64_t want_hash;
	unsigned long long held_to;   /* resuming: the device had the job up to here (acked) */
	char closer[4096 + 800];      /* resuming: what ends the device's partial command, + restore */
	/* the job's language: 0 not looked at yet, 1 the registered one, -1 refused */
	int lang_ok;
	int created;                /* jn_create made the file (removed again when refused) */
};

static uint64_t fnv(uint64_t h, const unsigned char *p, size_t n)
{
	for (size_t k = 0; k < n; k++)
		h = (h ^ p[k]) * 0x100000001b3ULL;
	return h;
}

/* The job's next n bytes: the check sum, and the last checkpoint the tracker finds in them. */
static void feed(jn_t *j, const unsigned char *p, size_t n)
{
	size_t k = j->lang->track(j->tr, p, n);
	if (k) {
		j->hash = fnv(j->hash, p, k);
		j->safe = j->off + k;
		j->safe_hash = j->hash;
	}
	j->hash = fnv(j->hash, p + k, n - k);
	j->off += n;
}

static int save(jn_t *j, const char *state)
{
	char tmp[4200], restore[768];
	if (snprintf(tmp, sizeof tmp, "%s.tmp", j->path) >= (int)sizeof tmp)
		return -1;
	j->lang->restore(j->tr, restore, sizeof restore);
	FILE *f = fopen(tmp, "w");
	if (!f)
		return -1;
	fprintf(f, "LOCUS-JOURNAL 1\nname %s\nstate %s\nacked %llu\nsafe %llu\nhash %016" PRIx64
		"\npage %lu\ncommand %lu\nrestore %s\n", j->name, state, j->off, j->safe, j->safe_hash,
		j->lang->page(j->tr), j->lang->command(j->tr), restore);
	if (fclose(f) != 0 || rename(tmp, j->path) != 0) {
		remove(tmp);
		return -1;
	}
	return 0;
}

static jn_t *alloc(const char *path, const char *name, char *err, size_t errlen)
{
	const io_lang_t *lang = io_lang();
	if (!lang) {
		snprintf(err, errlen, "%s: a job journal needs the language of the job's checkpoints, and "
			"this program registers none", path);
		errno = EINVAL;
		return NULL;
	}
	jn_t *j = calloc(1, sizeof *j);
	if (j) {
		j->lang = lang;
		j->path = strdup(path);
		j->name = strdup(name);
		j->tr = lang->track_new();
		j->hash = j->safe_hash = 0xcbf29ce484222325ULL;
		if (j->path && j->name && j->tr)
			return j;
		if (j->tr)
			lang->track_free(j->tr);
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
		else if (!strncmp(line, "restore ", 8))
			have |= 1 << 2;   /* (the restore sent is the job's own, made again at the point) */ else if (!strncmp(line, "state ", 6))
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
	const char *what = "";
	if (j->lang_ok)
		return j->lang_ok > 0 ? 0 : -1;
	int r = j->lang->sniff(p, n, &what);
	if (r >= 0) {
		j->lang_ok = r;
		return 0;   /* the language's own, or nothing but blanks yet */
	}
	j->lang_ok = -1;
	snprintf(err, errlen, "%s: a job journal keeps %s jobs only, and this job is %s: it cannot be "
		"resumed mid-document; nothing was sent: send it again without --journal (a failed job is "
		"then sent again whole)", j->name, j->lang->name, what);
	return -1;
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
	if (j->off < j->skip_to) {
		k = j->skip_to - j->off < n ? (size_t)(j->skip_to - j->off) : n;
		feed(j, b, k);
	}
	if (j->off == j->skip_to) {
		if (j->hash != j->want_hash) {
			snprintf(err, errlen, "the job differs from the journaled one before byte %llu: resume with "
				"the same input and options", j->skip_to);
			return -1;
		}
		if (j->safe != j->skip_to) {
			snprintf(err, errlen, "the journal's point, byte %llu, is not a point where this job can go on "
				"(%s): not this job's journal", j->skip_to, j->lang->checkpoint_words);
			return -1;
		}
		/* the restore is the job's own state at the point (the tracker has just read the job up
		 * to it), not the file's line: a journal edited or damaged cannot send anything else;
		 * led by what ends the command the device may hold unfinished (the device had the job
		 * up to held_to, the journal's acked count, past the point) */
		size_t held = j->held_to > j->off ? (size_t)(j->held_to - j->off) : 0;
		j->skipping = 0;
		j->lang->resume(j->tr, b + k, n - k, held, j->closer, sizeof j->closer);
		*restore = j->closer;
	}
	return (long)k;
}

int jn_ack(jn_t *j, const void *p, size_t n)
{
	const unsigned char *b = p;
	feed(j, b, n);
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
	unsigned long page = j->lang->page(j->tr);
	if (resume_cmd[0]) {
		snprintf(buf, len, "page %lu, command %lu (byte %llu of the job) reached; resume with: %s",
			page ? page : 1, j->lang->command(j->tr), j->safe, resume_cmd);
		return;
	}
	char name[600];
	const char *q = strstr(j->name, "journal=");
	if (q)
		snprintf(name, sizeof name, "%.*sresume=%s", (int)(q - j->name), j->name, q + 8);
	else
		snprintf(name, sizeof name, "%s", j->name);
	snprintf(buf, len, "page %lu, command %lu (byte %llu of the job) reached; resume with -o '%s'",
		page ? page : 1, j->lang->command(j->tr), j->safe, name);
}

int jn_close(jn_t *j, int done)
{
	int rc = 0;
	if (!j)
		return 0;
	if (j->lang_ok < 0) {
		if (j->created)
			remove(j->path);   /* refused before a byte went: no journal to resume */
	} else if (done)
		rc = save(j, "done");
	else if (!j->skipping)
		rc = save(j, "interrupted");   /* even at 0: a failed job is never left "running" */
	j->lang->track_free(j->tr);
	free(j->path);
	free(j->name);
	free(j);
	return rc;
}
