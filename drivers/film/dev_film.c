/* dev_film.c: the film-recorder device: DPX 10-bit log, DPX 16-bit linear, Cineon, RLE frames. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "device/device.h"
#include "film/filmenc.h"
#include "image/image.h"

typedef struct {
	int kind;                   /* FILM_* or FILM_RLE; -1 until the first page (from the suffix) */
	int little_endian, channel, planar;
	film_log_t log;
	film_cal_t *cal;
	film_lut_t lut;
	int lut_ready;              /* lut built (on the first page, when the format is known) */
	int64_t time;
	double width_mm, height_mm;
	film_frame_t fr;            /* the page being written */
	uint8_t *row;               /* one packed row */
	FILE *spool[2];             /* planar: the green and blue planes until the red one is out */
	img_writer_t *rle;
	unsigned rows;              /* rows written on this page */
	double frame_rate;          /* fps, for the headers' rate and time code */
	long first_frame, frame_step;   /* the frame number of page k: first_frame + k x frame_step */
} film_t;

static const dev_option_t film_options[] = {
	{ "format", "dpx (10-bit log, default), dpx16 (16-bit linear), cineon, rle; default from the suffix" },
	{ "preset", "slide4k (4096x2730, default), slide8k, 2k, 4k, 6x7" },
	{ "size", "WxH: a custom frame size in pixels (instead of a preset)" },
	{ "endian", "big (default) or little: byte order of a DPX file" },
	DEV_FIT_OPTIONS,
	{ "white", "reference white code value (685)" },
	{ "black", "reference black code value (95)" },
	{ "density", "printing density per code value (0.002)" },
	{ "film-gamma", "negative film gamma (0.6)" },
	{ "display-gamma", "display gamma (1.7)" },
	{ "calibration", "FILE: per-channel calibration curve applied before encoding" },
	{ "channel", "r, g or b: write that separation alone as a single-channel frame" },
	{ "separations", "planar: the three separations as three image elements of one file" },
	{ "frame-rate", "frames per second written into each header with the time code (24)" },
	{ "first-frame", "frame number of the first page (default 1; locus-film: from the input's frame records)" },
	{ "frame-step", "frame numbers between pages (default 1)" },
	{ NULL, NULL }
};

int film_kind_by_name(const char *name)
{
	if (!strcmp(name, "dpx")) return FILM_DPX10;
	if (!strcmp(name, "dpx16")) return FILM_DPX16;
	if (!strcmp(name, "cineon") || !strcmp(name, "cin")) return FILM_CINEON;
	if (!strcmp(name, "rle")) return FILM_RLE;
	return -1;
}

int film_kind_by_suffix(const char *path)
{
	const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
	if (!dot || (slash && dot < slash))
		return -1;
	if (!strcmp(dot, ".dpx") || !strcmp(dot, ".DPX")) return FILM_DPX10;
	if (!strcmp(dot, ".cin") || !strcmp(dot, ".CIN")) return FILM_CINEON;
	if (!strcmp(dot, ".rle")) return FILM_RLE;
	return -1;
}

int film_parse_size(const char *s, unsigned *w, unsigned *h)
{
	char *e;
	if (*s < '1' || *s > '9')
		return -1;
	unsigned long a = strtoul(s, &e, 10);
	if (*e != 'x' || e[1] < '1' || e[1] > '9')
		return -1;
	unsigned long b = strtoul(e + 1, &e, 10);
	if (*e || a > META_MAX_DIM || b > META_MAX_DIM)
		return -1;
	*w = (unsigned)a;
	*h = (unsigned)b;
	return 0;
}

static int real_option(dev_device_t *d, const char *key, double *v)
{
	char buf[64], *e;
	if (!dev_option(d, key, buf, sizeof buf))
		return 0;
	errno = 0;
	double x = strtod(buf, &e);
	if (!buf[0] || *e || errno || !isfinite(x))
		return dev_fail(d, DEV_EUSAGE, "film option %s needs a number, not '%s'", key, buf);
	*v = x;
	return 0;
}

int film_source_time(int64_t *t, char *err, size_t errlen)
{
	const char *s = getenv("SOURCE_DATE_EPOCH");
	if (!s) {
		*t = (int64_t)time(NULL);
		return 0;
	}
	char *e;
	errno = 0;
	long long v = strtoll(s, &e, 10);
	if (!*s || *e || errno || v < 0 || v > 253402300799LL) {
		snprintf(err, errlen, "SOURCE_DATE_EPOCH must be seconds since 1970, not '%s'", s);
		return -1;
	}
	*t = v;
	return 0;
}

static int f_open(dev_device_t *d)
{
	film_t *f = d->priv;
	char buf[1024], err[512];
	f->kind = -1;
	f->channel = -1;
	film_log_default(&f->log);
	if (dev_option(d, "format", buf, sizeof buf) && (f->kind = film_kind_by_name(buf)) < 0)
		return dev_fail(d, DEV_EUSAGE, "unknown film format '%s' (dpx, dpx16, cineon or rle)", buf);
	const film_preset_t *p = film_preset_find("slide4k");
	unsigned w = p->width, h = p->height;
	f->width_mm = p->width_mm;
	f->height_mm = p->height_mm;
	if (dev_option(d, "preset", buf, sizeof buf)) {
		if (!(p = film_preset_find(buf)))
			return dev_fail(d, DEV_EUSAGE, "unknown film preset '%s' (slide4k, slide8k, 2k, 4k, 6x7)", buf);
		w = p->width;
		h = p->height;
		f->width_mm = p->width_mm;
		f->height_mm = p->height_mm;
	}
	if (dev_option(d, "size", buf, sizeof buf)) {
		if (film_parse_size(buf, &w, &h))
			return dev_fail(d, DEV_EUSAGE, "film size '%s' is not WxH with each side 1 to %d pixels",
				buf, META_MAX_DIM);
		f->width_mm = f->height_mm = 0;
	}
	d->raster_width = w;
	d->raster_height = h;
	d->pixel_aspect = 0;
	int rc = dev_fit_options(d);
	if (rc)
		return rc;
	if (dev_option(d, "endian", buf, sizeof buf)) {
		if (strcmp(buf, "big") && strcmp(buf, "little"))
			return dev_fail(d, DEV_EUSAGE, "endian must be big or little, not '%s'", buf);
		f->little_endian = buf[0] == 'l';
	}
	rc = real_option(d, "white", &f->log.white);
	if (!rc) rc = real_option(d, "black", &f->log.black);
	if (!rc) rc = real_option(d, "density", &f->log.density);
	if (!rc) rc = real_option(d, "film-gamma", &f->log.film_gamma);
	if (!rc) rc = real_option(d, "display-gamma", &f->log.display_gamma);
	if (rc)
		return rc;
	if (film_log_check(&f->log, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "film log parameters: %s", err);
	if (dev_option(d, "channel", buf, sizeof buf)) {
		if (!strcmp(buf, "r")) f->channel = 0;
		else if (!strcmp(buf, "g")) f->channel = 1;
		else if (!strcmp(buf, "b")) f->channel = 2;
		else return dev_fail(d, DEV_EUSAGE, "channel must be r, g or b, not '%s'", buf);
	}
	if (dev_option(d, "separations", buf, sizeof buf)) {
		if (strcmp(buf, "planar"))
			return dev_fail(d, DEV_EUSAGE, "separations=%s: only 'planar' is a device option "
				"(locus-film --separations writes three files)", buf);
		f->planar = 1;
	}
	if (f->planar && f->channel >= 0)
		return dev_fail(d, DEV_EUSAGE, "separations=planar and channel= exclude each other");
	if (dev_option(d, "calibration", buf, sizeof buf)) {
		rc = film_cal_load(buf, &f->cal, err, sizeof err);
		if (rc) {
			rc = dev_fail(d, rc == -70 ? META_ENOMEM : META_ESYNTAX, "%s", err);
			d->reader_error = 1;    /* the message names its file: not to be prefixed with the input's */
			return rc;
		}
	}
	if (f->kind >= 0 && f->kind != FILM_RLE) {   /* an impossible frame is refused before any page */
		film_frame_t fr = { .kind = f->kind, .width = w, .height = h, .channel = f->channel,
			.planar = f->planar };
		if (!film_file_size(&fr))
			return dev_fail(d, DEV_EUSAGE, "a %ux%u frame does not fit the 4 GiB a %s file can hold",
				w, h, f->kind == FILM_CINEON ? "Cineon" : "DPX");
	}
	if (film_source_time(&f->time, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	f->frame_rate = 24;
	if ((rc = real_option(d, "frame-rate", &f->frame_rate)))
		return rc;
	if (!(f->frame_rate > 0 && f->frame_rate <= 1000))
		return dev_fail(d, DEV_EUSAGE, "frame-rate must be above 0 and at most 1000 frames a second, not %g",
			f->frame_rate);
	double v = 1;
	if ((rc = real_option(d, "first-frame", &v)))
		return rc;
	if (v < 0 || v > 9999999 || v != floor(v))
		return dev_fail(d, DEV_EUSAGE, "first-frame must be a frame number 0 to 9999999, not %g", v);
	f->first_frame = (long)v;
	v = 1;
	if ((rc = real_option(d, "frame-step", &v)))
		return rc;
	if (v < 1 || v > 9999999 || v != floor(v))
		return dev_fail(d, DEV_EUSAGE, "frame-step must be 1 to 9999999, not %g", v);
	f->frame_step = (long)v;
	return 0;
}

static int f_begin(dev_device_t *d, const dev_page_t *pg)
{
	film_t *f = d->priv;
	char err[256];
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "film: no output");
	if (f->kind < 0) {
		int k = io_is_std(d->out) ? -1 : film_kind_by_suffix(io_name(d->out));
		f->kind = k < 0 ? FILM_DPX10 : k;
	}
	f->rows = 0;
	if (f->kind == FILM_RLE) {
		if (f->channel >= 0 || f->planar)
			return dev_fail(d, DEV_EUSAGE, "the RLE format holds 24-bit RGB frames, not separations");
		f->rle = img_writer_new(IMG_FMT_RLE, d->out, pg->width, pg->height, err, sizeof err);
		return f->rle ? 0 : dev_fail(d, dev_code_of_errno(errno), "%s", err);
	}
	if (f->kind == FILM_CINEON && f->little_endian)
		return dev_fail(d, DEV_EUSAGE, "Cineon files are big-endian only (endian=little is for DPX)");
	if (f->kind == FILM_CINEON && f->planar)
		return dev_fail(d, DEV_EUSAGE, "planar separations are written as DPX only (for Cineon, "
			"--separations writes three files)");
	film_frame_t *fr = &f->fr;
	memset(fr, 0, sizeof *fr);
	fr->kind = f->kind;
	fr->little_endian = f->little_endian;
	fr->width = pg->width;
	fr->height = pg->height;
	fr->channel = f->channel;
	fr->planar = f->planar;
	fr->log = f->log;
	fr->creator = "Locus film recorder driver (locus-film)";
	fr->time = f->time;
	fr->frame = (unsigned)(f->first_frame + (long)pg->index * f->frame_step);
	fr->frame_rate = f->frame_rate;
	if (pg->width == d->raster_width && pg->height == d->raster_height) {
		fr->width_mm = f->width_mm;
		fr->height_mm = f->height_mm;
	}
	uint8_t hdr[FILM_HEADER_SIZE];
	if (film_header(fr, hdr, err, sizeof err))
		return dev_fail(d, META_ELIMIT, "%s", err);
	if (!f->lut_ready)
		film_lut_build(&f->lut, f->kind, &f->log, f->cal);
	f->lut_ready = 1;
	free(f->row);
	f->row = malloc(film_row_bytes(fr));
	if (!f->row)
		return dev_fail(d, META_ENOMEM, "out of memory");
	for (int k = 0; k < 2 && f->planar; k++)
		if (!(f->spool[k] = tmpfile()))
			return dev_fail(d, META_EIO, "cannot create a temporary file for a separation: %s",
				strerror(errno));
	if (io_write(d->out, hdr, sizeof hdr))
		return dev_fail(d, META_EIO, "%s", io_error(d->out));
	return 0;
}

static int f_band(dev_device_t *d, const render_band_t *b)
{
	film_t *f = d->priv;
	if (f->rle) {
		if (img_writer_rows(f->rle, b->pix, b->stride, b->nrows))
			return dev_fail(d, dev_code_of_errno(img_writer_errno(f->rle)), "%s", img_writer_error(f->rle));
		f->rows += b->nrows;
		return 0;
	}
	size_t n = film_row_bytes(&f->fr);
	for (unsigned k = 0; k < b->nrows; k++) {
		const uint8_t *src = b->pix + (size_t)k * b->stride;
		film_pack_row(&f->fr, &f->lut, src, f->planar ? 0 : f->channel, f->row);
		if (io_write(d->out, f->row, n))
			return dev_fail(d, META_EIO, "%s", io_error(d->out));
		for (int s = 0; s < 2 && f->planar; s++) {
			film_pack_row(&f->fr, &f->lut, src, s + 1, f->row);
			if (fwrite(f->row, 1, n, f->spool[s]) != n)
				return dev_fail(d, META_EIO, "writing a separation's temporary file failed");
		}
	}
	f->rows += b->nrows;
	return 0;
}

static void drop_spools(film_t *f)
{
	for (int k = 0; k < 2; k++)
		if (f->spool[k]) {
			fclose(f->spool[k]);
			f->spool[k] = NULL;
		}
}

static int f_end(dev_device_t *d, const dev_page_t *pg)
{
	film_t *f = d->priv;
	int rc = 0;
	if (f->rows != pg->height)
		rc = dev_fail(d, DEV_EDEVICE, "film: %u rows written of %u", f->rows, pg->height);
	if (f->rle) {
		if (!rc && img_writer_finish(f->rle))
			rc = dev_fail(d, dev_code_of_errno(img_writer_errno(f->rle)), "%s", img_writer_error(f->rle));
		else if (!rc)
			f->rle = NULL;          /* finished and freed */
		img_writer_abort(f->rle);
		f->rle = NULL;
		return rc;
	}
	for (int s = 0; s < 2 && f->planar && !rc; s++) {
		uint8_t buf[65536];
		size_t n;
		if (fflush(f->spool[s]) || fseek(f->spool[s], 0, SEEK_SET))
			rc = dev_fail(d, META_EIO, "reading a separation's temporary file failed");
		while (!rc && (n = fread(buf, 1, sizeof buf, f->spool[s])) > 0)
			if (io_write(d->out, buf, n))
				rc = dev_fail(d, META_EIO, "%s", io_error(d->out));
		if (!rc && ferror(f->spool[s]))
			rc = dev_fail(d, META_EIO, "reading a separation's temporary file failed");
	}
	drop_spools(f);
	return rc;
}

static int f_close(dev_device_t *d)
{
	film_t *f = d->priv;
	img_writer_abort(f->rle);
	f->rle = NULL;
	drop_spools(f);
	free(f->row);
	f->row = NULL;
	film_cal_free(f->cal);
	f->cal = NULL;
	return 0;
}

const dev_ops_t dev_film_ops = {
	.name = "film", .description = "film recorder frames: DPX 10-bit log (default), DPX 16-bit, Cineon, RLE",
	.extension = ".dpx", .caps = DEV_CAP_RASTER, .priv_size = sizeof(film_t),
	.option_list = film_options,
	.open = f_open, .begin_page = f_begin, .write_band = f_band, .end_page = f_end, .close = f_close,
};
