/* diff_meta.c: meta files compared statement by statement, text or binary against either. */
#include <stdlib.h>
#include <string.h>
#include "diff/diff.h"
#include "locus_meta.h"

/* Do two decoded statements say the same? */
static int same_cmd(const meta_cmd_t *a, const meta_cmd_t *b)
{
	if (a->op != b->op || memcmp(a->u, b->u, sizeof a->u) || memcmp(a->f, b->f, sizeof a->f) ||
			a->rgb != b->rgb || a->k != b->k || a->len != b->len || a->nlist != b->nlist ||
			a->nruns != b->nruns)
		return 0;
	if (a->len && memcmp(a->str, b->str, a->len))
		return 0;
	if (a->nlist && memcmp(a->list, b->list, a->nlist * sizeof *a->list))
		return 0;
	for (size_t k = 0; k < a->nruns; k++)
		if (a->runs[k].count != b->runs[k].count || a->runs[k].rgb != b->runs[k].rgb)
			return 0;
	return 1;
}

/* A statement as text (its keyword and operands, shortened), into buf. */
static void describe(const meta_cmd_t *c, char *buf, size_t n)
{
	size_t k = (size_t)snprintf(buf, n, "%s", meta_op_name(c->op));
	for (int i = 0; i < 5 && k < n; i++)
		if (c->f[i]) {
			char v[32];
			meta_fix_format(c->f[i], v);
			k += (size_t)snprintf(buf + k, n - k, " f%d=%s", i, v);
		}
	for (int i = 0; i < 4 && k < n; i++)
		if (c->u[i])
			k += (size_t)snprintf(buf + k, n - k, " u%d=%u", i, (unsigned)c->u[i]);
	if (k < n && (c->op == META_COLOUR || c->op == META_CLEAR || c->op == META_SPAN))
		k += (size_t)snprintf(buf + k, n - k, " #%06x", (unsigned)c->rgb);
	if (k < n && c->len)
		k += (size_t)snprintf(buf + k, n - k, " \"%.40s\"", c->str);
	if (k < n && c->nruns)
		snprintf(buf + k, n - k, " (%zu runs)", c->nruns);
}

int diff_meta(const void *a, size_t na, const char *aname, const void *b, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen)
{
	meta_reader_t *r[2] = { meta_reader_mem(a, na, aname), meta_reader_mem(b, nb, bname) };
	if (!r[0] || !r[1]) {
		meta_reader_free(r[0]);
		meta_reader_free(r[1]);
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	uint64_t count[2] = { 0, 0 }, pos[2] = { 0, 0 }, ndiff = 0, index = 0;
	unsigned page[2] = { 0, 0 }, fpage = 0;
	char desc[2][200] = { "(end)", "(end)" };
	int done[2] = { 0, 0 }, rc = 0, bin[2] = { 0, 0 };
	while (!done[0] || !done[1]) {
		meta_cmd_t c[2];
		int got[2];
		for (int k = 0; k < 2; k++) {
			got[k] = done[k] ? 0 : meta_read(r[k], &c[k]);
			if (got[k] < 0) {
				snprintf(err, errlen, "%s", meta_reader_error(r[k]));
				rc = -1;
				break;
			}
			if (got[k] == 0)
				done[k] = 1;
			else {
				count[k]++;
				page[k] += c[k].op == META_PAGE;
			}
		}
		if (rc)
			break;
		if (!got[0] && !got[1])
			break;
		if (got[0] && got[1] && same_cmd(&c[0], &c[1]))
			continue;
		if (ndiff++ == 0) {
			index = count[0] > count[1] ? count[0] : count[1];
			fpage = page[0];
			for (int k = 0; k < 2; k++) {
				bin[k] = meta_reader_is_binary(r[k]);
				pos[k] = got[k] ? meta_reader_position(r[k]) : 0;
				if (got[k])
					describe(&c[k], desc[k], sizeof desc[k]);
			}
		}
	}
	for (int k = 0; k < 2; k++)
		meta_reader_free(r[k]);
	if (rc)
		return -1;
	char where[2][48];
	for (int k = 0; k < 2; k++) {
		if (!strcmp(desc[k], "(end)"))
			snprintf(where[k], sizeof where[k], "its end");
		else
			snprintf(where[k], sizeof where[k], bin[k] ? "byte %llu" : "line %llu", (unsigned long long)pos[k]);
	}
	if (o->json) {
		fprintf(out, "{\"kind\":\"meta\",\"a\":");
		diff_json_str(out, aname);
		fprintf(out, ",\"b\":");
		diff_json_str(out, bname);
		fprintf(out, ",\"same\":%s,\"statements\":[%llu,%llu],\"differing\":%llu", ndiff ? "false" : "true",
			(unsigned long long)count[0], (unsigned long long)count[1], (unsigned long long)ndiff);
		if (ndiff) {
			fprintf(out, ",\"first\":{\"statement\":%llu,\"page\":%u,\"a_at\":", (unsigned long long)index, fpage);
			diff_json_str(out, where[0]);
			fprintf(out, ",\"b_at\":");
			diff_json_str(out, where[1]);
			fprintf(out, ",\"a\":");
			diff_json_str(out, desc[0]);
			fprintf(out, ",\"b\":");
			diff_json_str(out, desc[1]);
			fprintf(out, "}");
		}
		fprintf(out, "}\n");
	} else if (!ndiff) {
		fprintf(out, "%s %s: the same %llu statements\n", aname, bname, (unsigned long long)count[0]);
	} else {
		fprintf(out, "%s %s: %llu of %llu and %llu statements differ, the first (number %llu, page %u) at "
			"%s and %s\n", aname, bname, (unsigned long long)ndiff, (unsigned long long)count[0],
			(unsigned long long)count[1], (unsigned long long)index, fpage, where[0], where[1]);
		if (o->verbose)
			fprintf(out, "  A: %s\n  B: %s\n", desc[0], desc[1]);
	}
	return ndiff ? 1 : 0;
}
