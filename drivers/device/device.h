/* device.h: the Locus device interface: one operations table per device, and the replay loop.
 *
 * A device is a table of operations (dev_ops_t) plus capability flags; dev_play() reads a meta
 * file and drives any device, filling in what the device leaves out:
 *
 *  - A RASTER device (DEV_CAP_RASTER) implements only write_band (and optionally begin_page /
 *    end_page / open / close): the framework scan-converts every statement exactly per spec §5
 *    in horizontal bands and hands over finished rows, top row first, 24-bit RGB. The band
 *    height is dev_device_t.band_rows (0 = whole page when it fits dev_device_t.mem_budget). Multi-band pages
 *    are spooled to a temporary file and replayed per band, so memory stays bounded.
 *  - A VECTOR device receives paths: fill_path / stroke_path get the flattened path (arcs as
 *    chords, §5.4) and the raw elements (for devices with native arcs, DEV_CAP_ARCS), with the
 *    state in force. Text is expanded to a stroked path unless DEV_CAP_TEXT is set; image rows
 *    become put_span calls when put_image_row is NULL; spans become filled rectangles when
 *    put_span is NULL; clear becomes a filled page rectangle when clear is NULL. What the
 *    device cannot do (DEV_CAP_ONLY with FILL, DASH, WIDTH) the framework builds from §5.3's
 *    pieces: dash pieces, stroke outlines, hatch lines.
 *
 * Rows: a raster device's bands count rows from the TOP (render_band_t.y0 = 0 is the top row);
 * put_span and put_image_row take the meta file's pixel coordinates, rows from the BOTTOM
 * (y = 0 is the bottom row), like every path coordinate a vector device gets.
 *
 * Drivers write through a borrowed transport (transport.h) and never print or exit: every
 * operation returns 0 or a negative META_E* / DEV_E* code after dev_error() recorded a message.
 * To add a device: one file defining a const dev_ops_t, an entry in registry.c, and (for its
 * own program) a thin drivers/main-NAME.c. See docs/drivers.md.
 */
#ifndef LOCUS_DEVICE_H
#define LOCUS_DEVICE_H

#include <stddef.h>
#include <stdint.h>
#include "locus_meta.h"
#include "geom/scan.h"
#include "io/transport.h"
#include "device/writer.h"
#include "render/band.h"

/* Capability flags. */
#define DEV_CAP_RASTER  0x01   /* framework renders; device gets finished bands */
#define DEV_CAP_VECTOR  0x02   /* device gets paths */
#define DEV_CAP_ARCS    0x04   /* vector device draws arcs and circles natively (uses elems) */
#define DEV_CAP_TEXT    0x08   /* vector device draws the text statement itself */
#define DEV_CAP_FILL    0x10   /* vector device fills polygons (fill_path) */
#define DEV_CAP_DASH    0x20   /* vector device dashes natively (stroke_path gets the dash) */
#define DEV_CAP_WIDTH   0x40   /* vector device draws lines of any width natively */
/* With DEV_CAP_ONLY, the three flags above are ALL the vector device can do, and the framework
 * supplies the rest: without DEV_CAP_DASH, stroke_path gets the dash pieces (§5.3) as open
 * subpaths and no dash; without DEV_CAP_WIDTH, a stroke wider than one pixel reaches fill_path
 * as its §5.3 pieces (convex, counter-clockwise, filled non-zero: their union is the stroke) and
 * thinner strokes reach stroke_path; without DEV_CAP_FILL, fill_path is never called: a fill
 * goes to the device's hatch op if it has one, else it becomes its outline plus hatch lines
 * through the pixel centres one line width apart (scan_hatch), stroked with stroke_path.
 * Without DEV_CAP_ONLY a vector device is taken to do all three (as devices written before the
 * flags were honoured expect). */
#define DEV_CAP_ONLY    0x80

/* Extra error code for device failures (besides META_E*). */
#define DEV_EDEVICE (-20)

/* One page as announced by the `page` and `size` statements. For a raster device with a raster
 * of its own (dev_device_t.raster_width), width x height is that raster (what its bands hold)
 * and model_width x model_height the page as the file gave it; otherwise they are equal. */
typedef struct {
	unsigned width, height;     /* pixels */
	int has_size;               /* 1 if a size statement gave the physical size */
	meta_fix_t width_mm, height_mm;
	unsigned index;             /* 0-based page number in the file */
	unsigned model_width, model_height;  /* the `page` statement's W H */
} dev_page_t;

/* The graphics state in force (spec §1, §4). Dash normalised to an even count (≤ 32). */
typedef struct {
	meta_rgb_t colour;
	meta_fix_t width;
	int64_t dash[2 * META_MAX_DASH];
	size_t ndash;
	int cap, join, rule;
	meta_fix_t miter_limit;
	meta_fix_t line_width;      /* the width §5.3 draws: max(width, 1000), never below a pixel */
} dev_state_t;

/* A raw path element as written in the meta file (for devices with native arcs). */
typedef struct {
	meta_op_t op;               /* META_MOVE, META_DRAW, META_ARC, META_CIRCLE, META_CLOSE */
	meta_fix_t f[5];
} dev_elem_t;

/* A path handed to a vector device. */
typedef struct {
	const scan_path_t *flat;    /* flattened: subpaths of points in thousandths */
	const dev_elem_t *elems;    /* the raw elements */
	size_t nelems;
} dev_path_t;

/* A text statement (for DEV_CAP_TEXT devices). */
typedef struct {
	meta_fix_t x, y, size, angle;
	const char *str;
	size_t len;
} dev_text_t;

/* Finished rows for a raster device (render_band_t): render/band.h. */

typedef struct dev dev_device_t;

/* One device option a driver accepts as -O key=value (dev_ops_t.option_list). */
typedef struct {
	const char *key;
	const char *help;           /* one line: the values and the default */
} dev_option_t;

/* The largest anti-aliasing factor (dev_device_t.antialias). */
#define DEV_AA_MAX 16

/* How a model page is mapped onto a device raster of its own (dev_device_t.fit): ASPECT keeps
 * the page's shape and centres it, with letterbox bars where it does not reach; FILL keeps the
 * shape and covers the whole raster, cropping the page's excess evenly on both sides; STRETCH
 * maps the page onto the whole raster, each axis scaled on its own. */
enum { DEV_FIT_ASPECT = 0, DEV_FIT_FILL = 1, DEV_FIT_STRETCH = 2 };

/* The mapping of a model page onto a device raster (docs/drivers.md, "Rendering at the
 * device's resolution"). Model point (x, y) in pixels lies at device point (ox + x*sx,
 * oy + y*sy) in device pixels, both y up; the model page covers device pixels
 * [ox, ox + pw) x [oy, oy + ph), which may extend past the raster when cropped. */
typedef struct {
	unsigned width, height;     /* the device raster */
	unsigned model_w, model_h;  /* the model page */
	int64_t ox, oy;             /* device pixel of the page's bottom-left corner */
	int64_t pw, ph;             /* the page's size in whole device pixels */
	double sx, sy;              /* device pixels per model pixel: pw / model_w, ph / model_h */
	double wscale;              /* line widths scale by this: sqrt(sx * sy) */
	int identity;               /* 1: device pixels are the model's (no mapping at all) */
} dev_map_t;

/* Compute the mapping of a model_w x model_h page onto a dev_w x dev_h raster of pixels of
 * shape pixel_aspect (width / height of one device pixel; 0 = square) by fit (DEV_FIT_*). A
 * dev_w or dev_h of 0 gives the identity. Returns 0, or DEV_EUSAGE for an unknown fit or a
 * non-finite or non-positive aspect. Programs use it too (a framebuffer maps a mode onto the
 * screen's resolution by the same rules). */
int dev_fit_map(dev_map_t *m, unsigned model_w, unsigned model_h, unsigned dev_w, unsigned dev_h,
		double pixel_aspect, int fit);
/* The fit named by s ("aspect", "fill", "stretch"), or -1. For --fit / -O fit=. */
int dev_fit_by_name(const char *s);
/* For a device with a raster of its own: read the -O keys `fit` (aspect|fill|stretch) and
 * `letterbox` (#rrggbb) into d->fit and d->letterbox (defaults: aspect, black), to be called
 * from its open(). Returns 0 or DEV_EUSAGE with a one-line message. Declare the keys by putting
 * DEV_FIT_OPTIONS in the device's option_list. */
int dev_fit_options(dev_device_t *d);
#define DEV_FIT_OPTIONS \
	{ "fit", "aspect (keep the shape, letterbox bars; default), fill (crop) or stretch" }, \
	{ "letterbox", "#rrggbb colour of the bars with fit=aspect (default #000000)" }

/* The operations table. Any member may be NULL (a default or nothing is used). */
typedef struct dev_ops {
	const char *name;           /* registry name, e.g. "png" */
	const char *description;    /* one line for `locus-play -l` */
	const char *extension;      /* default output suffix, e.g. ".png" */
	unsigned caps;              /* DEV_CAP_* */
	/* Informational: how many colours the device shows at once (0 = 24-bit). The framework
	 * hands every device 24-bit colour and reduces nothing: a palette device quantises in
	 * write_band, a pen plotter maps colours to pens in its own ops. */
	unsigned colours;
	size_t priv_size;           /* bytes of zeroed private state allocated for dev->priv */
	const dev_option_t *option_list; /* the -O keys it accepts, {NULL} terminated; NULL: none */
	int (*open)(dev_device_t *d);
	int (*begin_page)(dev_device_t *d, const dev_page_t *pg);
	int (*write_band)(dev_device_t *d, const render_band_t *band);             /* raster */
	/* vector: paint the whole page (pg: its size in pixels, and the physical size if given) */
	int (*clear)(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb);
	int (*stroke_path)(dev_device_t *d, const dev_path_t *p, const dev_state_t *st);
	int (*fill_path)(dev_device_t *d, const dev_path_t *p, const dev_state_t *st);
	int (*text)(dev_device_t *d, const dev_text_t *t, const dev_state_t *st);
	/* vector, without DEV_CAP_FILL (DEV_CAP_ONLY): hatch the polygon p (rule in st) itself */
	int (*hatch)(dev_device_t *d, const dev_path_t *p, const dev_state_t *st);
	/* pixels n from (x, y), y from the bottom; clipped to the page (x + n <= width) */
	int (*put_span)(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb);
	/* one image row at page row y (from the bottom) from x; the runs clipped to the page */
	int (*put_image_row)(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns);
	int (*end_page)(dev_device_t *d, const dev_page_t *pg);
	int (*close)(dev_device_t *d);
	/* optional: a comment line of the meta file (text without '#', len bytes), after open */
	int (*comment)(dev_device_t *d, const char *text, size_t len);
} dev_ops_t;

/* A device instance. Fields before priv are set by the caller (dev_new + options). */
struct dev {
	const dev_ops_t *ops;
	io_transport_t *out;        /* borrowed: the caller opens and closes it */
	const char *options;        /* device-specific "key=value,..." or NULL */
	unsigned band_rows;         /* raster: rows per band, 0 = automatic */
	size_t mem_budget;          /* raster: bytes a page buffer may take (automatic banding) */
	/* A raster device with a raster of its own (framebuffer modes, film frames) sets these in
	 * its open(): the framework then maps each model page onto raster_width x raster_height
	 * device pixels of the given shape (pixel_aspect = width / height of one pixel, 0 = square)
	 * as `fit` says, and bands and pages reach the device at that size. 0 x 0 = the model
	 * page's own pixels (locus-raster). */
	unsigned raster_width, raster_height;
	double pixel_aspect;
	int fit;                    /* DEV_FIT_* */
	meta_rgb_t letterbox;       /* the bars' colour with DEV_FIT_ASPECT */
	/* Raster, set by the program (--antialias): 0 or 1 = exact, the reference (default);
	 * k = 2 .. DEV_AA_MAX: anti-aliased, each device pixel the mean in linear light of a k x k
	 * grid of exact samples (the page rendered by §5 at k times the resolution, as a device
	 * raster of k*w x k*h, then averaged). docs/drivers.md, "Anti-aliasing". dev_play() also
	 * takes it from the framework's own device option antialias=K in d->options. */
	unsigned antialias;
	/* Set by a device's open() when this instance can do less or more than ops->caps says
	 * (a profile without native fills, an option that ignores dashes): its DEV_CAP_* (with
	 * DEV_CAP_ONLY), which the framework then honours instead; 0: ops->caps. */
	unsigned caps;
	void *priv;                 /* ops->priv_size zeroed bytes for the driver */
	void *user;                 /* free for the program */
	/* Optional program hook, called before the device's begin_page (end = 0) and after its
	 * end_page (end = 1): lets a program give each page its own transport (d->out). */
	int (*on_page)(dev_device_t *d, const dev_page_t *pg, int end);
	/* filled by dev_play */
	const dev_page_t *page;     /* the page being replayed (NULL outside pages) */
	unsigned pages;             /* pages replayed so far */
	unsigned bands;             /* bands of the last page */
	int reader_error;           /* 1: err is the reader's message (it names the file) */
	char err[512];
};

/* Create a device instance over the ops table and a borrowed transport (may be NULL for
 * devices that write nothing). Returns NULL when out of memory. */
dev_device_t *dev_new(const dev_ops_t *ops, io_transport_t *out);
/* Free the instance (does not close the transport). */
void dev_free(dev_device_t *d);
/* Record an error message (printf style) and return code. For drivers and the framework. */
int dev_fail(dev_device_t *d, int code, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 3, 4)))
#endif
	;
/* The last error message, one line. */
const char *dev_error(const dev_device_t *d);
/* The instance's capabilities: d->caps when its open() set them, else d->ops->caps. */
unsigned dev_caps(const dev_device_t *d);
/* The code for dev_fail of a failure whose cause is the errno e (a writer's, a transport's):
 * META_ENOMEM for ENOMEM (a program's exit 70), else META_EIO (74). */
int dev_code_of_errno(int e);

/* Replay a whole meta stream onto the device: open, pages, close. Returns 0, or <0 with
 * dev_error() set: a reader error verbatim ("f.meta:3:1: ...", reader_error = 1), a failure of
 * the device or the framework with the place of the statement ("line 12: ..." or
 * "byte 1042: ..."). */
int dev_play(meta_reader_t *r, dev_device_t *d);

/* Device options (options.c). The value of key in d->options copied into buf (NULL when the
 * key is absent or the value does not fit). */
const char *dev_option(const dev_device_t *d, const char *key, char *buf, size_t n);
/* 0 when every key in d->options is in d->ops->option_list, else DEV_EUSAGE with a one-line
 * message naming the unknown key and the known ones. dev_play() calls it before open(). */
int dev_check_options(dev_device_t *d);
#define DEV_EUSAGE (-21)

/* The device registry (registry.c): NULL-terminated list, and lookup by name. */
extern const dev_ops_t *const dev_registry[];
const dev_ops_t *dev_find(const char *name);

#endif
