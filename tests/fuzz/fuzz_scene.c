/* fuzz_scene.c: libFuzzer harness of the scene parser with a tiny render: errors are one line at name:line:col, and what renders is a valid meta file. */
#include "fuzz.h"
#include "scene.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define MAX_PIXELS (24 * 24)

/* Occurrences of word in text. */
static unsigned count(const char *text, const char *word)
{
	unsigned n = 0;
	for (const char *p = text; (p = strstr(p, word)); p += strlen(word))
		n++;
	return n;
}

/* 1 when the parsed scene is cheap enough to render within the harness' time. */
static int tiny(const scene_t *s)
{
	if ((uint64_t)s->cam.nxpix * s->cam.nypix > MAX_PIXELS || s->nrenders > 4 || s->nobjs > 8)
		return 0;
	for (size_t i = 0; i < s->nrenders; i++) {
		const scene_render_t *r = &s->renders[i];
		if (r->supersample > 2 || r->depth > 5 || r->slices > 8 || r->resolution > 24 || r->nlevels > 16
				|| r->nnuclei > 32 || (r->kind == SCENE_RAYTRACE && (r->step < 0.1 || r->accuracy < 1e-4)))
			return 0;
		if (r->has_inset && (uint64_t)r->inset[2] * r->inset[3] > MAX_PIXELS)
			return 0;
	}
	for (size_t i = 0; i < s->nobjs; i++)
		if (!s->objs[i].shape)
			return 0;
	return 1;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	char err[1024];
	scene_t *s = NULL;
	if (size > 8192)
		return 0;
	char *text = malloc(size + 1);
	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = 0;
#if FUZZ_GUARDS
	/* pending (w-bounds): no limit yet on shape nesting: distance-to twelve levels deep costs
	 * about 3^depth per evaluation, twenty levels never finish parsing */
	if (count(text, "distance-to") > 3 || count(text, "c shape") > 3) {
		free(text);
		return 0;
	}
#else
	(void)count;
#endif
	if (scene_parse(text, "in", &s, err, sizeof err) < 0) {
		FUZZ_ASSERT(fuzz_one_line(err), "error not one line: '%s'", err);
		FUZZ_ASSERT(!strncmp(err, "in:", 3), "error does not name the file: '%s'", err);
		free(text);
		return 0;
	}
	FUZZ_ASSERT(s, "parse succeeded without a scene");
	for (size_t i = 0; i < s->nwarnings; i++)
		FUZZ_ASSERT(fuzz_one_line(s->warnings[i]), "warning not one line: '%s'", s->warnings[i]);
	if (tiny(s)) {
		fuzz_buf_t out = { 0 };
		meta_writer_t *w = meta_writer_new(fuzz_buf_write, &out, META_ENC_BINARY);
		scene_opts_t o = { 1, NULL, NULL };
		scene_stats_t st;
		FUZZ_ASSERT(w, "out of memory");
		int rc = scene_render(s, w, &o, &st, err, sizeof err);
		int rcw = meta_writer_close(w);
		if (rc < 0) {
			FUZZ_ASSERT(fuzz_one_line(err), "render error not one line: '%s'", err);
		} else {
			/* what the renderer wrote is a whole, valid meta file */
			FUZZ_ASSERT(rcw == 0, "render succeeded but the writer could not close the file");
			meta_reader_t *r = meta_reader_mem(out.p, out.n, "rendered");
			meta_cmd_t c;
			int rr;
			while ((rr = meta_read(r, &c)) > 0)
				;
			FUZZ_ASSERT(rr == 0, "the rendered meta file is refused: %s", meta_reader_error(r));
			meta_reader_free(r);
		}
		free(out.p);
	}
	scene_free(s);
	free(text);
	return 0;
}
