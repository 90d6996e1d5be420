/* fuzz_journal.c: libFuzzer harness of arbitrary journal files through resume: the input is the
 * journal file. Resuming it is refused in one line naming the file, or it skips the journaled
 * bytes of a fixed HP-GL job (whose check sum it must match) and gives a restore; then the job's
 * bytes the plotter holds (up to the journal's acked count), the restore and the rest read
 * cleanly with the HP-GL reader, and the restore (after the closer of a held command) is
 * printable. */
#include <unistd.h>
#include "fuzz.h"
#include "hpgl/hpgl_link.h"
#include "hpgl/read/hpgl_read.h"
#include "io/journal.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

static const char job[] =
	"IN;SP1;IP0,0,4000,4000;SC0,100,0,100;PU10,10;PD20,10,20,20;VS10;LT2,4;PW0.5;SI0.2,0.3;"
	"DI1,0;IW0,0,5000,5000;PU30,30;PD40,30,40,40;SP2;PR;PD10,0,0,10,-10,0;PA;PU70,70;PD80,70,"
	"80,80,90,90;LBtext\003;PA5,5;PD15,5,15,15;PG;SP3;LT1;PU5,5;PD15,5,15,15;";

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	hpgl_link_register();
	char path[96], err[600];
	snprintf(path, sizeof path, "/tmp/locus-fuzz-journal-%ld.jnl", (long)getpid());
	FILE *f = fopen(path, "wb");
	FUZZ_ASSERT(f, "cannot write %s", path);
	fwrite(data, 1, size, f);
	fclose(f);
	size_t n = sizeof job - 1;
	jn_t *j = jn_resume(path, "tcp:127.0.0.1:9100?resume=x", err, sizeof err);
	if (!j) {
		FUZZ_ASSERT(fuzz_one_line(err) && !strncmp(err, path, strlen(path)), "refusal '%s'", err);
		unlink(path);
		return 0;
	}
	FUZZ_ASSERT(!jn_language(j, job, n, err, sizeof err), "the job is HP-GL: %s", err);
	const char *restore = NULL;
	size_t off = 0;
	long k = 0;
	/* the job in two pieces, as a transport's buffer may hand it over */
	size_t first = size ? data[0] % n + 1 : n;
	size_t piece_end = n;
	while (off < n && jn_skipping(j)) {
		size_t len = off < first ? first - off : n - off;
		piece_end = off + len;
		k = jn_skip(j, job + off, len, &restore, err, sizeof err);
		if (k < 0)
			break;
		off += (size_t)k;
		if (restore || (size_t)k < len)
			break;
	}
	if (k < 0) {
		FUZZ_ASSERT(fuzz_one_line(err), "skip error '%s'", err);
	} else if (restore) {
		size_t rl = strlen(restore);
		/* printable after the closer (which may end a label with its ETX) */
		const char *semi = strchr(restore, ';');
		for (size_t i = semi ? (size_t)(semi - restore) : 0; i < rl; i++)
			FUZZ_ASSERT(restore[i] >= 32 && restore[i] < 127, "the restore has byte 0x%02x", (unsigned char)restore[i]);
		/* the plotter holds the job up to the acked count, when the closer could be made: the
		 * job's bytes from the point to there at hand in the piece that ended the skip */
		unsigned long long acked = jn_held(j);
		if (acked < off || acked > piece_end)
			acked = off;
		if (restore[0] == ';' && acked > off)
			acked = off;   /* the held command's end was not at hand (beyond the piece): no closer */
		char *held = malloc((size_t)acked + rl + n - off + 2);
		FUZZ_ASSERT(held, "out of memory");
		memcpy(held, job, (size_t)acked);
		memcpy(held + acked, restore, rl);
		memcpy(held + acked + rl, job + off, n - off);
		hpgl_doc_t d;
		memset(&d, 0, sizeof d);
		int rc = hpgl_read_mem(held, (size_t)acked + rl + n - off, "joined", &d, err, sizeof err);
		hpgl_doc_free(&d);
		FUZZ_ASSERT(rc == 0, "point %zu, acked %llu, restore '%s': the joined bytes do not read: %s", off, acked, restore, err);
		free(held);
	}
	jn_close(j, 0);
	unlink(path);
	return 0;
}
