/* filmdone.c: is a frame's file there and whole? (locus-film --skip-existing, docs/farm.md) */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "film/filmenc.h"
#include "image/image.h"

static uint32_t be32(const unsigned char *b)
{
	return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static uint32_t le32(const unsigned char *b)
{
	return (uint32_t)b[3] << 24 | (uint32_t)b[2] << 16 | (uint32_t)b[1] << 8 | b[0];
}

static long file_read(void *user, void *buf, size_t n)
{
	FILE *f = user;
	size_t k = fread(buf, 1, n, f);
	return k == 0 && ferror(f) ? -1 : (long)k;
}

/* An RLE frame: the image reader decodes it to its last row and finds nothing after it. */
static int rle_whole(FILE *f, const char *path, char *why, size_t n)
{
	img_reader_t *r = NULL;
	char err[300];
	if (img_reader_open(file_read, f, NULL, 0, path, &r, err, sizeof err)) {
		snprintf(why, n, "%s", err);
		return 0;
	}
	uint8_t *row = malloc((size_t)img_reader_width(r) * 3 + 1);
	int ok = row != NULL;
	for (unsigned y = 0; ok && y < img_reader_height(r); y++)
		ok = img_reader_row(r, row) == 0;
	ok = ok && img_reader_end(r) == 0;
	if (!ok)
		snprintf(why, n, "%s", row ? img_reader_error(r) : "out of memory");
	free(row);
	img_reader_free(r);
	return ok;
}

int film_file_complete(const char *path, long frame, char *why, size_t n)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		if (errno == ENOENT)
			return -1;
		snprintf(why, n, "%s: cannot open: %s", path, strerror(errno));
		return 0;
	}
	struct stat sb;
	unsigned char h[FILM_HEADER_SIZE];
	int ok = 0;
	if (fstat(fileno(f), &sb) || !S_ISREG(sb.st_mode)) {
		snprintf(why, n, "%s: not a regular file", path);
	} else if (sb.st_size >= 4 && fread(h, 1, 4, f) == 4 && !memcmp(h, DEV_RLE_MAGIC, 4)) {
		rewind(f);
		ok = rle_whole(f, path, why, n);
	} else if (sb.st_size < FILM_HEADER_SIZE || (rewind(f), fread(h, 1, sizeof h, f)) != sizeof h) {
		snprintf(why, n, "%s: %lld bytes, shorter than a DPX or Cineon header", path, (long long)sb.st_size);
	} else {
		/* DPX: "SDPX" in the file's byte order, the file size at 16, the frame position at 1712;
		 * Cineon (big-endian): its magic, the file size at 20, the frame position at 1068 */
		int dpx_be = be32(h) == 0x53445058, dpx_le = le32(h) == 0x53445058, cin = be32(h) == 0x802A5FD7;
		uint32_t (*rd)(const unsigned char *) = dpx_le ? le32 : be32;
		if (!dpx_be && !dpx_le && !cin) {
			snprintf(why, n, "%s: not a DPX, Cineon or RLE frame", path);
		} else {
			uint32_t size = rd(h + (cin ? 20 : 16)), pos = rd(h + (cin ? 1068 : 1712));
			if ((uint64_t)size != (uint64_t)sb.st_size)
				snprintf(why, n, "%s: its header says %lu bytes, the file has %lld", path, (unsigned long)size,
					(long long)sb.st_size);
			else if (frame >= 0 && pos != (uint32_t)frame)
				snprintf(why, n, "%s: holds frame %lu, not frame %ld", path, (unsigned long)pos, frame);
			else
				ok = 1;
		}
	}
	fclose(f);
	return ok;
}
