/* grow.h: a growable array's capacity, doubled until it holds `need` elements (drivers only). */
#ifndef LOCUS_GROW_H
#define LOCUS_GROW_H

#include <stdint.h>
#include <stdlib.h>

/* Make *p (of *cap elements of elem bytes) hold at least need elements: the capacity starts at
 * first and doubles. 0, or -1 when out of memory or the size would overflow (*p unchanged). */
static inline int dev_grow(void **p, size_t *cap, size_t need, size_t elem, size_t first)
{
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : first;
	while (n < need) {
		if (n > SIZE_MAX / 2)
			return -1;
		n *= 2;
	}
	if (elem && n > SIZE_MAX / elem)
		return -1;
	void *q = realloc(*p, n * elem);
	if (!q)
		return -1;
	*p = q;
	*cap = n;
	return 0;
}

#endif
