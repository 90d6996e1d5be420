/* unit.h: a tiny unit-test harness; each CHECK prints one "ok"/"not ok" line for tests/run.sh. */
#ifndef LOCUS_UNIT_H
#define LOCUS_UNIT_H
#include <stdio.h>
#include <string.h>

static int unit_failed;
static int unit_count;

#define CHECK(cond, ...) do { \
	unit_count++; \
	if (cond) { printf("ok - "); } \
	else { unit_failed++; printf("not ok - %s:%d: (%s) ", __FILE__, __LINE__, #cond); } \
	printf(__VA_ARGS__); printf("\n"); \
} while (0)

#define CHECK_STR(a, b, ...) CHECK(strcmp((a), (b)) == 0, __VA_ARGS__)

/* Return from main with this: non-zero when any check failed. */
#define UNIT_DONE() (fflush(stdout), unit_failed ? 1 : 0)
#endif
