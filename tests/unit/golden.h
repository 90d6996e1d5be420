/* golden.h: an in-memory meta sink and the record-or-compare step of the byte-for-byte golden tests. */
#ifndef LOCUS_GOLDEN_H
#define LOCUS_GOLDEN_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "membuf.h"
#include "unit.h"

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
		CHECK(n == m->n && memcmp(want, m->p, n) == 0, "output equals %s (%zu bytes, golden %zu)", path, m->n, n);
		free(want);
	}
	free(m->p);
	m->p = NULL;
}
#endif
