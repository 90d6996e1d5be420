/* golden.h: an in-memory meta sink and the record-or-compare step of the byte-for-byte golden tests. */
#ifndef LOCUS_GOLDEN_H
#define LOCUS_GOLDEN_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "membuf.h"
#include "unit.h"

/* A failed golden: the output to a temporary file and locus-diff's report of the two (the first
 * differing statement of meta files; $BIN as tests/run.sh sets it, else bin). */
static void golden_report(const char *path, const membuf_t *m)
{
	char tmp[] = "/tmp/locus-golden-XXXXXX", cmd[1200];
	int fd = mkstemp(tmp);
	FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
	if (!f)
		return;
	int ok = fwrite(m->p, 1, m->n, f) == m->n;
	if (fclose(f) == 0 && ok) {
		const char *bin = getenv("BIN") ? getenv("BIN") : "bin";
		snprintf(cmd, sizeof cmd, "'%s/locus-diff' --semantic -v '%s' '%s' | sed 's/^/# /' >&2", bin, path, tmp);
		if (system(cmd) != 0)
			fprintf(stderr, "# (locus-diff could not compare them)\n");
	}
	remove(tmp);
}

/* With LOCUS_RECORD set, (re)write the golden file from the buffer (then look at it before
 * committing); otherwise check that the buffer equals the golden byte for byte. Frees the buffer. */
static void golden_check(const char *path, membuf_t *m)
{
	if (getenv("LOCUS_RECORD")) {
		FILE *f = fopen(path, "wb");
		CHECK(f && fwrite(m->p, 1, m->n, f) == m->n && fclose(f) == 0, "recorded %s (%zu bytes)", path, m->n);
	} else {
		FILE *f = fopen(path, "rb");
		char *want = malloc(m->n + 2);
		size_t n = f && want ? fread(want, 1, m->n + 1, f) : 0;
		if (f)
			fclose(f);
		CHECK(f != NULL, "golden %s is there", path);
		int same = n == m->n && memcmp(want, m->p, n) == 0;
		CHECK(same, "output equals %s (%zu bytes, golden %zu)", path, m->n, n);
		if (!same && f)
			golden_report(path, m);
		free(want);
	}
	free(m->p);
	m->p = NULL;
}
#endif
