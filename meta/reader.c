/* reader.c: the streaming reader: its sources (callback, memory, file), encoding detection and
 * dispatch to the text or binary decoder, validation; the buffer and errors both decoders use are
 * in read_buf.c. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "meta_int.h"

static long fd_read(void *user, void *buf, size_t n)
{
	int fd = *(int *)user;
	for (;;) {
		ssize_t k = read(fd, buf, n);
		if (k >= 0 || errno != EINTR)
			return (long)k;
	}
}

static meta_reader_t *reader_alloc(const char *name)
{
	meta_reader_t *r = calloc(1, sizeof *r);
	if (!r)
		return NULL;
	r->fd = -1;
	r->str = malloc(META_MAX_STRING + 1);
	if (!r->str) {
		free(r);
		return NULL;
	}
	if (!name)
		name = "<input>";
	else if (strcmp(name, "-") == 0)
		name = "<stdin>";
	meta_fmt(r->name, sizeof r->name, "%s", name);
	return r;
}

meta_reader_t *meta_reader_new(meta_read_fn fn, void *user, const char *name)
{
	meta_reader_t *r = reader_alloc(name);
	if (!r)
		return NULL;
	r->fn = fn;
	r->user = user;
	r->cap = META_READ_CHUNK;
	r->buf = malloc(r->cap);
	if (!r->buf) {
		meta_reader_free(r);
		return NULL;
	}
	return r;
}

meta_reader_t *meta_reader_mem(const void *data, size_t len, const char *name)
{
	meta_reader_t *r = reader_alloc(name ? name : "<memory>");
	if (!r)
		return NULL;
	r->mem = data ? data : (const unsigned char *)"";
	r->buf = (unsigned char *)r->mem; /* never written: fill does not move memory input */
	r->cap = r->end = data ? len : 0;
	r->eof = 1;
	return r;
}

meta_reader_t *meta_reader_open(const char *path, char *err, size_t errlen)
{
	meta_reader_t *r;
	int fd = 0;
	if (strcmp(path, "-") != 0) {
		fd = open(path, O_RDONLY);
		if (fd < 0) {
			if (err && errlen)
				meta_fmt(err, errlen, "%s: cannot open: %s", path, strerror(errno));
			return NULL;
		}
	}
	r = meta_reader_new(fd_read, NULL, path);
	if (!r) {
		if (fd > 0)
			close(fd);
		if (err && errlen)
			meta_fmt(err, errlen, "%s: out of memory", path);
		errno = ENOMEM;   /* tells the caller this from a missing file (locus_meta.h) */
		return NULL;
	}
	r->fd = fd;
	r->user = &r->fd;
	return r;
}

void meta_reader_free(meta_reader_t *r)
{
	if (!r)
		return;
	if (r->fd > 0)
		close(r->fd);
	if (!r->mem)
		free(r->buf);
	free(r->runs);
	free(r->str);
	free(r);
}

static int start(meta_reader_t *r)
{
	while (r->end - r->pos < 1 && !r->eof)
		if (meta_rd_fill(r) < 0)
			return r->state;
	r->binary = r->end > r->pos && r->buf[r->pos] == meta_magic[0];
	r->state = 1;
	return r->binary ? meta_binary_header(r) : meta_text_header(r);
}

int meta_read(meta_reader_t *r, meta_cmd_t *cmd)
{
	char msg[400];
	int rc, where;
	if (r->state < 0)
		return r->state;
	if (r->state == 2)
		return 0;
	if (r->state == 0 && (rc = start(r)) < 0)
		return rc;
	rc = r->binary ? meta_read_binary(r, cmd) : meta_read_text(r, cmd);
	if (rc < 0)
		return rc;
	if (rc == 0) {
		if (meta_check_eof(&r->chk, msg, sizeof msg))
			return meta_rd_fail(r, META_ESTATE, r->binary ? r->base + r->end : 1, "%s", msg);
		r->state = 2;
		return 0;
	}
	rc = meta_check_cmd(&r->chk, cmd, &where, msg, sizeof msg);
	if (rc)
		return meta_rd_fail(r, rc, where < 0 ? r->opos[7] : r->opos[where], "%s", msg);
	return 1;
}

const char *meta_reader_error(const meta_reader_t *r)
{
	return r->state < 0 ? r->err : "";
}

int meta_reader_is_binary(const meta_reader_t *r)
{
	return r->binary;
}

uint64_t meta_reader_position(const meta_reader_t *r)
{
	return r->stmt_pos;
}
