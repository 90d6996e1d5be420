/* diff_src.c: locus-diff's inputs: kinds sniffed, images streamed, meta pages rendered by a thread. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "diff/diff_src.h"

const char *const dsrc_kind_name[] = { "raster", "meta", "HP-GL", "PostScript", "PDF" };


static long src_read(void *user, void *buf, size_t n)
{
	dsrc_t *s = user;
	if (s->headpos < s->nhead) {
		size_t k = s->nhead - s->headpos < n ? s->nhead - s->headpos : n;
		memcpy(buf, s->head + s->headpos, k);
		s->headpos += k;
		return (long)k;
	}
	if (s->pipe) {
		size_t k = fread(buf, 1, n, s->pipe);
		if (k == 0 && ferror(s->pipe))
			return -1;
		return (long)k;
	}
	return io_read(s->t, buf, n);
}

static int status_of(int rc)
{
	return rc == META_ENOMEM || rc == -70 ? 70 : rc == META_EIO || rc == -74 ? 74 : 65;
}

static int cap_begin(dev_device_t *d, const dev_page_t *pg)
{
	dsrc_t *s = d->user;
	if (pg->index + 1 != s->want)
		return 0;
	pthread_mutex_lock(&s->mu);
	s->width = pg->width;
	s->height = pg->height;
	s->sized = 1;
	pthread_cond_broadcast(&s->cv);
	pthread_mutex_unlock(&s->mu);
	return 0;
}

/* Hand the band to the comparing thread and wait until it has taken every row. */
static int cap_band(dev_device_t *d, const render_band_t *b)
{
	dsrc_t *s = d->user;
	if (d->pages + 1 != s->want)
		return 0;
	pthread_mutex_lock(&s->mu);
	s->band = b;
	s->band_at = 0;
	pthread_cond_broadcast(&s->cv);
	while (s->band && !s->quit)
		pthread_cond_wait(&s->cv, &s->mu);
	int quit = s->quit;
	pthread_mutex_unlock(&s->mu);
	return quit ? dev_fail(d, DEV_EDEVICE, "comparison stopped") : 0;
}

static const dev_ops_t capture_ops = {
	.name = "capture", .description = "band-at-a-time capture", .caps = DEV_CAP_RASTER,
	.begin_page = cap_begin, .write_band = cap_band,
};

static void *player(void *arg)
{
	dsrc_t *s = arg;
	int rc = dev_play(s->mr, s->dev);
	pthread_mutex_lock(&s->mu);
	s->done = 1;
	if (rc && !s->quit) {
		snprintf(s->err, sizeof s->err, "%s", dev_error(s->dev));
		s->status = status_of(rc);
	} else if (!rc && !s->sized) {
		snprintf(s->err, sizeof s->err, "%s: has no page %u", s->name, s->want);
		s->status = 65;
	}
	s->band = NULL;
	pthread_cond_broadcast(&s->cv);
	pthread_mutex_unlock(&s->mu);
	return NULL;
}

/* Is the head HP-GL: blanks, then ESC or a two-letter command followed by a parameter, ';' or
 * another command? */
static int is_hpgl(const unsigned char *h, size_t n)
{
	size_t i = 0;
	while (i < n && ((h[i] < 32 && h[i] != 27) || h[i] == ' ' || h[i] == ';'))   /* blanks, ETX, ... */
		i++;
	if (i < n && h[i] == 27)
		return 1;
	if (i + 2 >= n)
		return 0;
	/* the commands a plot file starts with (the corpus: IN, BP, SP, PU, DF, ...) */
	static const char first[] = "IN DF SP PU PD PA PR IP SC BP PS PG LT VS CO RO IW SI DT LB PE "
		"CI AA NP PC PW WU MC CT FT PT ";
	char m[3] = { (char)(h[i] & ~32), (char)(h[i + 1] & ~32), 0 };
	int c = h[i + 2];
	if (!strstr(first, m) || ((strstr(first, m) - first) % 3) != 0)
		return 0;
	return c == ';' || c == '-' || c == '+' || c == '.' || c == ' ' || c == ',' || c == '\r' ||
		c == '\n' || (c >= '0' && c <= '9') || ((c | 32) >= 'a' && (c | 32) <= 'z');
}

/* Open path and read its first bytes to tell its kind; 0 or an exit status with s->err. */
int dsrc_sniff(dsrc_t *s, const char *path, unsigned page)
{
	memset(s, 0, sizeof *s);
	s->name = strcmp(path, "-") ? path : "<stdin>";
	s->want = page;
	if (!(s->t = io_open_read(path, s->err, sizeof s->err)))
		return 66;
	while (s->nhead < sizeof s->head) {
		long n = io_read(s->t, s->head + s->nhead, sizeof s->head - s->nhead);
		if (n < 0) {
			snprintf(s->err, sizeof s->err, "%s", io_error(s->t));
			return 74;
		}
		if (n == 0)
			break;
		s->nhead += (size_t)n;
	}
	const unsigned char *h = s->head;
	size_t n = s->nhead;
	struct stat sb;
	if ((n >= 10 && memcmp(h, "LOCUS-META", 10) == 0) || (n >= 4 && memcmp(h, "\x8bLMB", 4) == 0))
		s->kind = DSRC_META;
	else if (n >= 5 && memcmp(h, "%PDF-", 5) == 0)
		s->kind = DSRC_PDF;
	else if ((n >= 2 && memcmp(h, "%!", 2) == 0) || (n >= 4 && memcmp(h, "\xC5\xD0\xD3\xC6", 4) == 0))
		s->kind = DSRC_PS;
	else if (img_reader_sniff(h, n))
		s->kind = DSRC_RASTER;
	else if (is_hpgl(h, n))
		s->kind = DSRC_HPGL;
	else if (strcmp(path, "-") && !stat(path, &sb) && S_ISREG(sb.st_mode) &&
			img_rd_fbdump_mode((uint64_t)sb.st_size) >= 0)
		s->kind = DSRC_RASTER, s->dump = (uint64_t)sb.st_size;   /* headerless: told by its size */
	else
		s->kind = DSRC_RASTER;   /* the image reader names what it expected */
	return 0;
}

/* Read the whole input into memory (*buf, malloc'd); 0 or an exit status. */
int dsrc_slurp(dsrc_t *s, unsigned char **buf, size_t *len)
{
	size_t cap = 1 << 16, n = 0;
	unsigned char *b = malloc(cap);
	for (;;) {
		if (b && n == cap) {
			unsigned char *q = cap < ((size_t)1 << 40) ? realloc(b, cap * 2) : NULL;
			if (!q)
				free(b);
			b = q;
			cap *= 2;
		}
		if (!b) {
			snprintf(s->err, sizeof s->err, "out of memory reading %s", s->name);
			return 70;
		}
		long k = src_read(s, b + n, cap - n);
		if (k < 0) {
			free(b);
			snprintf(s->err, sizeof s->err, "%s", io_error(s->t));
			return 74;
		}
		if (k == 0)
			break;
		n += (size_t)k;
	}
	*buf = b;
	*len = n;
	return 0;
}

/* --render: Ghostscript turns page s->want of the input into a PPM read from a pipe; the input
 * reaches it on its standard input (a PDF is written to a temporary file first, which gs needs
 * to seek in). 0 or an exit status. */
int dsrc_ghostscript(dsrc_t *s, unsigned dpi)
{
	unsigned char *buf;
	size_t n;
	int st = dsrc_slurp(s, &buf, &n);
	if (st)
		return st;
	char tmp[] = "/tmp/locus-diff-XXXXXX";
	int fd = mkstemp(tmp);
	if (fd < 0 || write(fd, buf, n) != (ssize_t)n) {
		free(buf);
		if (fd >= 0)
			close(fd), unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot write a temporary copy of %s: %s", s->name, strerror(errno));
		return 74;
	}
	free(buf);
	close(fd);
	int p[2];
	if (pipe(p)) {
		unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot make a pipe: %s", strerror(errno));
		return 70;
	}
	char res[32], first[32], last[32], out[] = "-sOutputFile=-";
	snprintf(res, sizeof res, "-r%u", dpi);
	snprintf(first, sizeof first, "-dFirstPage=%u", s->want);
	snprintf(last, sizeof last, "-dLastPage=%u", s->want);
	s->pid = fork();
	if (s->pid == 0) {
		dup2(p[1], 1);
		close(p[0]);
		close(p[1]);
		int nul = open("/dev/null", O_WRONLY);
		if (nul >= 0)
			dup2(nul, 2);
		char *argv[] = { "gs", "-q", "-dSAFER", "-dBATCH", "-dNOPAUSE", "-sDEVICE=ppmraw", res,
			first, last, "-dEPSCrop", out, tmp, NULL };
		execvp("gs", argv);
		_exit(127);
	}
	close(p[1]);
	if (s->pid < 0) {
		close(p[0]);
		unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot start Ghostscript: %s", strerror(errno));
		return 70;
	}
	s->pipe = fdopen(p[0], "rb");
	/* gs has the file open once it writes its first byte; the name can go at the end */
	snprintf(s->tmp, sizeof s->tmp, "%s", tmp);
	s->nhead = s->headpos = 0;
	if (!s->pipe) {
		close(p[0]);
		snprintf(s->err, sizeof s->err, "out of memory");
		return 70;
	}
	return 0;
}

/* Start reading the picture of s: 0 or an exit status with the message in s->err. */
int dsrc_open(dsrc_t *s, unsigned band_rows, size_t budget)
{
	if (s->kind == DSRC_META) {
		s->meta = 1;
		s->mr = meta_reader_new(src_read, s, s->name);
		s->dev = s->mr ? dev_new(&capture_ops, NULL) : NULL;
		if (!s->dev) {
			snprintf(s->err, sizeof s->err, "out of memory");
			return 70;
		}
		s->dev->user = s;
		s->dev->band_rows = band_rows;
		if (budget)
			s->dev->mem_budget = budget;
		if (pthread_mutex_init(&s->mu, NULL) || pthread_cond_init(&s->cv, NULL) ||
				pthread_create(&s->thr, NULL, player, s)) {
			snprintf(s->err, sizeof s->err, "cannot start a thread to render %s", s->name);
			return 70;
		}
		s->started = 1;
		pthread_mutex_lock(&s->mu);
		while (!s->sized && !s->done)
			pthread_cond_wait(&s->cv, &s->mu);
		int st = s->sized ? 0 : s->status ? s->status : 70;
		pthread_mutex_unlock(&s->mu);
		return st;
	}
	int rc = s->dump ? img_rd_open_fbdump(src_read, s, NULL, 0, s->name, s->dump, &s->img, s->err, sizeof s->err)
		: img_reader_open(src_read, s, NULL, 0, s->name, &s->img, s->err, sizeof s->err);
	if (rc)
		return status_of(rc);
	s->width = img_reader_width(s->img);
	s->height = img_reader_height(s->img);
	s->row = malloc((size_t)s->width * 3);
	if (!s->row) {
		snprintf(s->err, sizeof s->err, "out of memory");
		return 70;
	}
	return 0;
}

/* The next row (top first) in *row, valid until the next call; 0 or an exit status. */
int dsrc_row(dsrc_t *s, const uint8_t **row)
{
	if (!s->meta) {
		int rc = img_reader_row(s->img, s->row);
		if (rc) {
			snprintf(s->err, sizeof s->err, "%s", img_reader_error(s->img));
			return status_of(rc);
		}
		*row = s->row;
		return 0;
	}
	pthread_mutex_lock(&s->mu);
	if (s->band && s->band_at >= s->band->nrows) {
		s->band = NULL;   /* every row of it taken: let the player go on */
		pthread_cond_broadcast(&s->cv);
	}
	while (!s->band && !s->done)
		pthread_cond_wait(&s->cv, &s->mu);
	int st = 0;
	if (s->band)
		*row = s->band->pix + (size_t)s->band_at++ * s->band->stride;
	else
		st = s->status ? s->status : 70;
	if (st == 70 && !s->err[0])
		snprintf(s->err, sizeof s->err, "%s: the page ended early", s->name);
	pthread_mutex_unlock(&s->mu);
	return st;
}

/* After the last row: the rest of the input must be good too. 0 or an exit status. */
int dsrc_finish(dsrc_t *s)
{
	if (!s->meta) {
		int rc = img_reader_end(s->img);
		if (rc)
			snprintf(s->err, sizeof s->err, "%s", img_reader_error(s->img));
		return rc ? status_of(rc) : 0;
	}
	pthread_mutex_lock(&s->mu);
	s->band = NULL;
	pthread_cond_broadcast(&s->cv);
	while (!s->done)
		pthread_cond_wait(&s->cv, &s->mu);
	int st = s->status;
	pthread_mutex_unlock(&s->mu);
	return st;
}

void dsrc_close(dsrc_t *s)
{
	if (s->started) {
		pthread_mutex_lock(&s->mu);
		s->quit = 1;
		pthread_cond_broadcast(&s->cv);
		pthread_mutex_unlock(&s->mu);
		pthread_join(s->thr, NULL);
		pthread_cond_destroy(&s->cv);
		pthread_mutex_destroy(&s->mu);
	}
	dev_free(s->dev);
	meta_reader_free(s->mr);
	img_reader_free(s->img);
	free(s->row);
	if (s->pipe) {
		fclose(s->pipe);
		int ws;
		waitpid(s->pid, &ws, 0);
	}
	if (s->tmp[0])
		unlink(s->tmp);
	if (s->t)
		io_close(s->t, IO_ABORT);
}

/* Print the error of a source: a bad-data message names the file and the place itself. */
int dsrc_fail(const dsrc_t *s, int st)
{
	if (st == 65)
		fprintf(stderr, "%s\n", s->err);
	else
		fprintf(stderr, "locus-diff: %s\n", s->err);
	return st;
}


/* Run argv (a program reading file in) with its standard output to file out; 0 when it exited 0
 * (or 3, qpdf's "succeeded with warnings"). */
static int run_to(char *const argv[], const char *out)
{
	pid_t pid = fork();
	if (pid == 0) {
		int fd = open(out, O_WRONLY | O_TRUNC);
		int nul = open("/dev/null", O_WRONLY);
		if (fd < 0 || nul < 0)
			_exit(127);
		dup2(fd, 1);
		dup2(nul, 2);
		execvp(argv[0], argv);
		_exit(127);
	}
	int ws;
	if (pid < 0 || waitpid(pid, &ws, 0) < 0)
		return -1;
	return WIFEXITED(ws) && (WEXITSTATUS(ws) == 0 || WEXITSTATUS(ws) == 3) ? 0 : -1;
}

int dsrc_qdf(unsigned char **buf, size_t *len)
{
	char in[] = "/tmp/locus-diff-pdf-XXXXXX", out[] = "/tmp/locus-diff-qdf-XXXXXX";
	int fi = mkstemp(in), fo = fi >= 0 ? mkstemp(out) : -1;
	int rc = -1;
	if (fi >= 0 && fo >= 0 && write(fi, *buf, *len) == (ssize_t)*len) {
		close(fi), close(fo);
		fi = fo = -1;
		char *argv[] = { "qpdf", "--qdf", "--object-streams=disable", in, "-", NULL };
		FILE *f = run_to(argv, out) == 0 ? fopen(out, "rb") : NULL;
		if (f) {
			size_t cap = 1 << 16, n = 0;
			unsigned char *b = malloc(cap);
			while (b) {
				size_t k = fread(b + n, 1, cap - n, f);
				n += k;
				if (n < cap)
					break;
				unsigned char *q = realloc(b, cap * 2);
				if (!q)
					free(b);
				b = q;
				cap *= 2;
			}
			if (b && !ferror(f) && n > 0) {
				free(*buf);
				*buf = b;
				*len = n;
				rc = 0;
			} else {
				free(b);
			}
			fclose(f);
		}
	}
	if (fi >= 0)
		close(fi);
	if (fo >= 0)
		close(fo);
	unlink(in);
	unlink(out);
	return rc;
}
