/* svg_render.c: render an SVG file to a PNG of W x H pixels with librsvg (loaded at run time,
 * since only its runtime library is installed here) on a cairo image surface; for t_svg.sh.
 * The document is fitted to the W x H viewport (rsvg_handle_render_document, librsvg 2.46 on),
 * so a viewBox of W x H draws at exactly one unit a pixel, as rsvg-convert draws it, whatever
 * the width and height in millimetres say (42.333mm is 159.9987 px at 96 dpi: at that size
 * librsvg and cairo resample an embedded image with a filter that mixes neighbouring rows). */
#include <cairo.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

/* The few librsvg / GObject entry points used, declared from their documented signatures. */
typedef struct {
	int width, height;
	double em, ex;
} rsvg_dim_t;
typedef void *(*new_from_data_fn)(const unsigned char *data, size_t len, void **error);
typedef int (*render_cairo_fn)(void *handle, cairo_t *cr);
typedef void (*get_dim_fn)(void *handle, rsvg_dim_t *dim);
typedef void (*unref_fn)(void *obj);
typedef struct {
	double x, y, width, height;
} rsvg_rect_t;
typedef int (*render_document_fn)(void *handle, cairo_t *cr, const rsvg_rect_t *viewport, void **error);

static unsigned char *slurp(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return NULL;
	size_t cap = 1 << 16, n = 0;
	unsigned char *b = malloc(cap);
	for (size_t k; b && (k = fread(b + n, 1, cap - n, f)) > 0;) {
		n += k;
		if (n == cap) {
			unsigned char *g = realloc(b, cap *= 2);
			if (!g) {
				free(b);
				b = NULL;
			}
			b = g;
		}
	}
	fclose(f);
	*len = n;
	return b;
}

int main(int argc, char **argv)
{
	if (argc != 5) {
		fprintf(stderr, "usage: svg_render IN.svg OUT.png W H\n");
		return 64;
	}
	void *lib = dlopen("librsvg-2.so.2", RTLD_NOW | RTLD_GLOBAL);
	if (!lib) {
		fprintf(stderr, "svg_render: librsvg-2.so.2 not found (%s)\n", dlerror());
		return 69;
	}
	new_from_data_fn from_data = (new_from_data_fn)dlsym(lib, "rsvg_handle_new_from_data");
	render_cairo_fn render = (render_cairo_fn)dlsym(lib, "rsvg_handle_render_cairo");
	get_dim_fn get_dim = (get_dim_fn)dlsym(lib, "rsvg_handle_get_dimensions");
	unref_fn unref = (unref_fn)dlsym(RTLD_DEFAULT, "g_object_unref");
	render_document_fn render_doc = (render_document_fn)dlsym(lib, "rsvg_handle_render_document");
	if (!from_data || !render || !get_dim || !unref) {
		fprintf(stderr, "svg_render: librsvg lacks the entry points used\n");
		return 69;
	}
	size_t len;
	unsigned char *data = slurp(argv[1], &len);
	if (!data) {
		fprintf(stderr, "svg_render: cannot read %s\n", argv[1]);
		return 66;
	}
	void *err = NULL, *h = from_data(data, len, &err);
	free(data);
	if (!h) {
		fprintf(stderr, "svg_render: %s: librsvg refused the file\n", argv[1]);
		return 65;
	}
	int w = atoi(argv[3]), ht = atoi(argv[4]);
	rsvg_dim_t dim;
	get_dim(h, &dim);
	cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, ht);
	cairo_t *cr = cairo_create(s);
	cairo_set_source_rgb(cr, 1, 1, 1);
	cairo_paint(cr);
	int ok;
	if (render_doc) {
		rsvg_rect_t vp = { 0, 0, w, ht };
		ok = render_doc(h, cr, &vp, &err);
	} else {
		if (dim.width > 0 && dim.height > 0)
			cairo_scale(cr, (double)w / dim.width, (double)ht / dim.height);
		ok = render(h, cr);
	}
	cairo_destroy(cr);
	int rc = ok && cairo_surface_write_to_png(s, argv[2]) == CAIRO_STATUS_SUCCESS ? 0 : 74;
	cairo_surface_destroy(s);
	unref(h);
	if (rc)
		fprintf(stderr, "svg_render: rendering or writing %s failed\n", argv[2]);
	return rc;
}
