/* quant_int.h: internals shared by quant_build.c and quant_map.c (histogram layout, nearest search). */
#ifndef LOCUS_QUANT_INT_H
#define LOCUS_QUANT_INT_H

#include "quant/quant.h"

#define QBINS (1u << 18)
#define QMIXED (1u << 24)       /* qbin_t.first: the bin holds more than one 24-bit colour */

/* One DAC colour of the histogram. */
typedef struct {
	uint32_t count;
	uint32_t first;             /* the first 24-bit colour seen, | QMIXED once another came */
	uint64_t sum[3];            /* exact 8-bit values summed */
} qbin_t;

#define QXSLOTS (1u << 17)      /* the exact-colour table: open addressing ... */
#define QXMAX (1u << 16)        /* ... for at most this many colours */

struct quant_hist {
	qbin_t *bin;                /* QBINS */
	void *map_base;             /* the mapping holding bin (bins_new), or NULL: bin is calloc's */
	size_t map_len;
	uint32_t *used;             /* keys of the bins in use, in the order first seen */
	size_t nused;
	unsigned long npix;
	/* quant_hist_exact(): the exact 24-bit colours (| QMIXED marks a used slot) and counts */
	uint32_t *xkey, *xcount;
	size_t nx;
	int xstate;                 /* 0 none counted, 1 valid, -1 too many colours */
};

/* A colour to quantise: a bin's (or an exact colour's) mean and its pixels. */
typedef struct {
	double c[3];                /* mean 8-bit colour of the bin */
	double w;                   /* pixels */
} qcol_t;

/* Lloyd passes (at most passes) over the n weighted colours: entries [fixed, k) of means move to
 * the mean of the colours nearest to them, those below fixed stay; an entry left with no colour
 * moves to the colour of the largest weighted error; with grid (6 or 8), every entry is held at
 * the nearest colour a DAC of that many bits shows. Stops when the entries move less than 0.01
 * levels on average (grid: less than half a level in all). 0, or <0 when out of memory. */
int quant_kmeans(const qcol_t *col, size_t n, double (*means)[3], size_t fixed, size_t k, int passes,
		unsigned grid);

/* The bin of an 8-bit colour. */
static inline uint32_t quant_key(unsigned r, unsigned g, unsigned b)
{
	return (uint32_t)(quant_dac6(r) << 12 | quant_dac6(g) << 6 | quant_dac6(b));
}

/* 1 if the bin is flat for the histogram's threshold. */
static inline int quant_bin_flat(const quant_hist_t *h, const qbin_t *q, unsigned long thr)
{
	(void)h;
	return q->count >= thr && !(q->first & QMIXED);
}

/* Nearest-entry search: entries sorted by r + g + b, searched outwards from the nearest sum
 * with the sum's distance as the bound. Units: 8-bit values times 4. */
typedef struct {
	unsigned n;
	int c[QUANT_MAX][3];
	int key[QUANT_MAX];         /* r + g + b */
	uint8_t pos[QUANT_MAX];     /* where index k sits in the sorted order */
	uint8_t idx[QUANT_MAX];
} qnear_t;

/* Fill q with n colours (units of 1/4 of an 8-bit step), remembering their indices. */
void quant_near_init(qnear_t *q, const int (*col)[3], unsigned n);
/* Index (as given to quant_near_init) of the entry nearest to (r, g, b) in the same units. */
unsigned quant_near_find(const qnear_t *q, int r, int g, int b);
/* The same, starting from the guess hint (an index, or -1 for none): same answer, faster when
 * the guess is near (k-means: the entry of the pass before). */
unsigned quant_near_find_from(const qnear_t *q, int r, int g, int b, int hint);
/* The nearest entry (as quant_near_find: ties to the lowest index) and the squared distances
 * to it (*d1) and to the nearest of all the other entries (*d2; -1 when there is no other). */
unsigned quant_near_find2(const qnear_t *q, int r, int g, int b, long *d1, long *d2);
/* The candidates of grid cells, cell after cell: entry indices and each one's squared distance
 * to its cell (quant_map's nearest search and the k-means cells below). */
typedef struct {
	uint8_t *e;
	int32_t *d;
	size_t n, cap;
} qpool_t;
/* Append the entries e < n with dmin[e] <= bound, sorted by dmin (ties by index), at
 * p->e + *start, p->d + *start. Returns how many, or -1 out of memory. */
long quant_pool_add(qpool_t *p, const int32_t *dmin, unsigned n, int32_t bound, size_t *start);
/* Free the pool's arrays. */
void quant_pool_free(qpool_t *p);

/* Exact nearest and second-nearest entries through the cells of a 4-level grid (k-means:
 * every pass asks thousands of colours, most in a few hundred cells): a cell's candidates
 * are the entries no farther from it than the second least farthest-corner distance of any
 * entry, sorted by their distance to the cell, built on first use. */
typedef struct qcells qcells_t;
/* A new set of cells (about 100 KiB); NULL when out of memory. */
qcells_t *quant_cells_new(void);
/* Free it (NULL is fine). */
void quant_cells_free(qcells_t *c);
/* Forget every cell: the entries are now col[0..n) (search units, 0..1020 a channel). */
void quant_cells_reset(qcells_t *c, const int (*col)[3], unsigned n);
/* As quant_near_find2 for the entries of the last reset (q holding the same entries serves
 * when a cell cannot be built: out of memory). */
unsigned quant_cells_find2(qcells_t *c, const qnear_t *q, int r, int g, int b, long *d1, long *d2);
/* The palette's entries in search units (8-bit values shown by the DAC, times 4). */
void quant_near_palette(qnear_t *q, const quant_palette_t *pal);

#endif
