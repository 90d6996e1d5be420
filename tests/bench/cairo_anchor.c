/* cairo_anchor.c: the benchmark anchor "what a C programmer would write": a meta file drawn with cairo. */
/*
 * Usage: cairo_anchor [-s image|ps|pdf] [-a none|default] [-o OUT] IN
 *   -s   the cairo surface: image (ARGB32 raster written as binary PPM, or PNG when OUT ends in
 *        .png), ps (PostScript) or pdf (PDF). Default image.
 *   -a   antialiasing: none (CAIRO_ANTIALIAS_NONE, what a raster device shows) or default.
 *        Default none.
 *   -o   output file (default stdout; PS and PDF surfaces need a file).
 * IN is a Locus meta file (text or binary, "-" for stdin), read with the meta reader. Each
 * path becomes one cairo_stroke or cairo_fill with the meta state (colour, width at least 1
 * pixel, caps, joins, miter limit, dashes, fill rule), spans and image runs become rectangles,
 * y is flipped to the meta-language's bottom-left origin; PS and PDF pages are at 96 pixels
 * per inch (0.75 pt a pixel) unless the page has a size statement. Text is not drawn (the
 * benchmark workloads have none). Only the first page of an image surface is written.
 * The drawing is what the workloads need, written plainly, as the anchor figures were taken.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cairo.h>
#include <cairo-pdf.h>
#include <cairo-ps.h>
#include "locus_meta.h"

enum { S_IMAGE, S_PS, S_PDF };

static void rgb(cairo_t *cr, meta_rgb_t c)
{
	cairo_set_source_rgb(cr, (c >> 16 & 255) / 255.0, (c >> 8 & 255) / 255.0, (c & 255) / 255.0);
}

/* Write an ARGB32 surface as binary PPM. */
static int write_ppm(cairo_surface_t *s, FILE *f)
{
	int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
	int stride = cairo_image_surface_get_stride(s);
	const unsigned char *p = cairo_image_surface_get_data(s);
	unsigned char *row = malloc((size_t)w * 3);
	if (!row)
		return -1;
	fprintf(f, "P6\n%d %d\n255\n", w, h);
	for (int y = 0; y < h; y++) {
		const uint32_t *q = (const uint32_t *)(p + (size_t)y * stride);
		for (int x = 0; x < w; x++) {
			row[3 * x] = (unsigned char)(q[x] >> 16);
			row[3 * x + 1] = (unsigned char)(q[x] >> 8);
			row[3 * x + 2] = (unsigned char)q[x];
		}
		fwrite(row, 1, (size_t)w * 3, f);
	}
	free(row);
	return ferror(f) ? -1 : 0;
}

int main(int argc, char **argv)
{
	const char *in = NULL, *out = "-";
	int surf = S_IMAGE, aa = CAIRO_ANTIALIAS_NONE;
	for (int k = 1; k < argc; k++) {
		if (!strcmp(argv[k], "-s") && k + 1 < argc) {
			k++;
			surf = !strcmp(argv[k], "ps") ? S_PS : !strcmp(argv[k], "pdf") ? S_PDF : S_IMAGE;
			if (surf == S_IMAGE && strcmp(argv[k], "image")) {
				fprintf(stderr, "cairo_anchor: unknown surface '%s' (image, ps or pdf)\n", argv[k]);
				return 64;
			}
		} else if (!strcmp(argv[k], "-a") && k + 1 < argc) {
			k++;
			aa = !strcmp(argv[k], "default") ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE;
		} else if (!strcmp(argv[k], "-o") && k + 1 < argc) {
			out = argv[++k];
		} else if (!strcmp(argv[k], "--help")) {
			printf("usage: cairo_anchor [-s image|ps|pdf] [-a none|default] [-o OUT] IN\n");
			return 0;
		} else if (!in) {
			in = argv[k];
		} else {
			fprintf(stderr, "cairo_anchor: usage: cairo_anchor [-s image|ps|pdf] [-a none|default] [-o OUT] IN\n");
			return 64;
		}
	}
	if (!in)
		in = "-";
	if (surf != S_IMAGE && !strcmp(out, "-")) {
		fprintf(stderr, "cairo_anchor: PS and PDF surfaces need -o FILE\n");
		return 64;
	}
	char err[512];
	meta_reader_t *r = meta_reader_open(in, err, sizeof err);
	if (!r) {
		fprintf(stderr, "cairo_anchor: %s\n", err);
		return 66;
	}
	cairo_surface_t *s = NULL;
	cairo_t *cr = NULL;
	meta_cmd_t c;
	int rc, kind = 0, pages = 0, status = 0;
	double dash[2 * 16];
	unsigned W = 0, H = 0, img_x = 0, img_y = 0, img_h = 0, img_row = 0;
	meta_rgb_t colour = 0;
	while ((rc = meta_read(r, &c)) > 0) {
		switch (c.op) {
		case META_PAGE:
			W = c.u[0], H = c.u[1];
			break;
		case META_SIZE:
		case META_COMMENT:
			break;
		default:
			break;
		}
		if (c.op == META_PAGE || c.op == META_SIZE || c.op == META_COMMENT)
			continue;
		if (!cr) {   /* the page's first statement: now its size is known */
			double pw = W * 0.75, ph = H * 0.75;
			if (!s) {
				s = surf == S_PS ? cairo_ps_surface_create(out, pw, ph)
					: surf == S_PDF ? cairo_pdf_surface_create(out, pw, ph)
					: cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)W, (int)H);
			} else if (surf == S_PS) {
				cairo_ps_surface_set_size(s, pw, ph);
			} else if (surf == S_PDF) {
				cairo_pdf_surface_set_size(s, pw, ph);
			}
			cr = cairo_create(s);
			cairo_set_antialias(cr, aa);
			double k = surf == S_IMAGE ? 1 : 0.75;
			cairo_translate(cr, 0, H * k);
			cairo_scale(cr, k, -k);
			cairo_rectangle(cr, 0, 0, W, H);
			cairo_set_source_rgb(cr, 1, 1, 1);
			cairo_fill(cr);
			colour = 0;
			cairo_set_line_width(cr, 1);
			cairo_set_miter_limit(cr, 10);
		}
		switch (c.op) {
		case META_CLEAR:
			rgb(cr, c.rgb);
			cairo_paint(cr);
			break;
		case META_END_PAGE:
			if (surf != S_IMAGE)
				cairo_show_page(cr);
			cairo_destroy(cr);
			cr = NULL;
			pages++;
			break;
		case META_COLOUR: colour = c.rgb; break;
		case META_WIDTH: cairo_set_line_width(cr, c.f[0] < 1000 ? 1 : c.f[0] / 1000.0); break;
		case META_CAP:
			cairo_set_line_cap(cr, c.k == META_CAP_ROUND ? CAIRO_LINE_CAP_ROUND :
				c.k == META_CAP_SQUARE ? CAIRO_LINE_CAP_SQUARE : CAIRO_LINE_CAP_BUTT);
			break;
		case META_JOIN:
			cairo_set_line_join(cr, c.k == META_JOIN_ROUND ? CAIRO_LINE_JOIN_ROUND :
				c.k == META_JOIN_BEVEL ? CAIRO_LINE_JOIN_BEVEL : CAIRO_LINE_JOIN_MITER);
			break;
		case META_MITER_LIMIT: cairo_set_miter_limit(cr, c.f[0] / 1000.0); break;
		case META_FILL_RULE:
			cairo_set_fill_rule(cr, c.k == META_RULE_EVEN_ODD ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING);
			break;
		case META_DASH:
			for (size_t k = 0; k < c.nlist && k < 16; k++)
				dash[k] = c.list[k] / 1000.0;
			cairo_set_dash(cr, dash, (int)(c.nlist < 16 ? c.nlist : 16), 0);
			break;
		case META_STROKE: case META_FILL: kind = c.op; cairo_new_path(cr); break;
		case META_MOVE: cairo_move_to(cr, c.f[0] / 1000.0, c.f[1] / 1000.0); break;
		case META_DRAW: cairo_line_to(cr, c.f[0] / 1000.0, c.f[1] / 1000.0); break;
		case META_CLOSE: cairo_close_path(cr); break;
		case META_ARC: {
			double a0 = c.f[3] / 180000.0 * M_PI, a1 = (c.f[3] + (double)c.f[4]) / 180000.0 * M_PI;
			if (c.f[4] >= 0)
				cairo_arc(cr, c.f[0] / 1000.0, c.f[1] / 1000.0, c.f[2] / 1000.0, a0, a1);
			else
				cairo_arc_negative(cr, c.f[0] / 1000.0, c.f[1] / 1000.0, c.f[2] / 1000.0, a0, a1);
			break;
		}
		case META_CIRCLE:
			cairo_new_sub_path(cr);
			cairo_arc(cr, c.f[0] / 1000.0, c.f[1] / 1000.0, c.f[2] / 1000.0, 0, 2 * M_PI);
			cairo_close_path(cr);
			break;
		case META_END:
			rgb(cr, colour);
			if (kind == META_FILL)
				cairo_fill(cr);
			else
				cairo_stroke(cr);
			break;
		case META_SPAN:
			rgb(cr, c.rgb);
			cairo_rectangle(cr, c.u[0], c.u[1], c.u[2], 1);
			cairo_fill(cr);
			break;
		case META_IMAGE:
			img_x = c.u[0], img_y = c.u[1], img_h = c.u[3], img_row = 0;
			break;
		case META_ROW: {
			double x = img_x, y = img_y + img_h - 1 - img_row++;
			for (size_t k = 0; k < c.nruns; k++) {
				rgb(cr, c.runs[k].rgb);
				cairo_rectangle(cr, x, y, c.runs[k].count, 1);
				cairo_fill(cr);
				x += c.runs[k].count;
			}
			break;
		}
		default:
			break;
		}
	}
	if (rc < 0) {
		fprintf(stderr, "%s\n", meta_reader_error(r));
		status = 65;
	}
	if (cr)
		cairo_destroy(cr);
	if (s && surf == S_IMAGE && status == 0 && pages) {
		cairo_surface_flush(s);
		size_t n = strlen(out);
		if (n > 4 && !strcmp(out + n - 4, ".png")) {
			if (cairo_surface_write_to_png(s, out) != CAIRO_STATUS_SUCCESS)
				status = 74;
		} else {
			FILE *f = strcmp(out, "-") ? fopen(out, "wb") : stdout;
			if (!f || write_ppm(s, f) || (f != stdout && fclose(f)))
				status = 74;
		}
	}
	if (s) {
		cairo_surface_finish(s);
		if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS && status == 0)
			status = 74;
		cairo_surface_destroy(s);
	}
	meta_reader_free(r);
	if (status == 74)
		fprintf(stderr, "cairo_anchor: %s: write failed\n", out);
	return status;
}
