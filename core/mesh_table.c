/* mesh_table.c: the meshes' hash table from 64-bit keys to 64-bit values (open addressing, grown at half full). */
#include "mesh_int.h"

#include <stdlib.h>
#include <string.h>

static uint64_t mix(uint64_t k)
{
	k ^= k >> 33;
	k *= 0xff51afd7ed558ccdULL;
	k ^= k >> 33;
	k *= 0xc4ceb9fe1a85ec53ULL;
	return k ^ (k >> 33);
}

void mesh_table_free(mesh_table_t *t)
{
	free(t->e);
	memset(t, 0, sizeof *t);
}

/* Slot of key (k + 1) in t: the one holding it, or the free one where it goes. */
static size_t slot(const mesh_table_t *t, uint64_t k)
{
	size_t i = mix(k) & (t->cap - 1);
	while (t->e[i].key && t->e[i].key != k)
		i = (i + 1) & (t->cap - 1);
	return i;
}

static int table_grow(mesh_table_t *t)
{
	size_t cap = t->cap ? 2 * t->cap : 4096;
	mesh_table_t g = {calloc(cap, sizeof *g.e), t->n, cap};
	if (!g.e)
		return -1;
	for (size_t i = 0; i < t->cap; i++)
		if (t->e[i].key)
			g.e[slot(&g, t->e[i].key)] = t->e[i];
	free(t->e);
	*t = g;
	return 0;
}

int mesh_table_get(mesh_table_t *t, uint64_t k, uint64_t *val, size_t *at)
{
	if (2 * (t->n + 1) > t->cap && table_grow(t) < 0)
		return -1;
	size_t i = slot(t, k + 1);
	*at = i;
	if (t->e[i].key) {
		*val = t->e[i].val;
		return 1;
	}
	return 0;
}

void mesh_table_put(mesh_table_t *t, size_t at, uint64_t k, uint64_t val)
{
	t->e[at].key = k + 1;
	t->e[at].val = val;
	t->n++;
}
