/* regress.c: replays every seed (fixtures/fuzz/HARNESS/) and regression input (fixtures/fuzz/regress/HARNESS-*) through its harness in the normal build; one "ok" line each harness and input. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int fuzz_entry_meta_text(const uint8_t *data, size_t size);
int fuzz_entry_meta_binary(const uint8_t *data, size_t size);
int fuzz_entry_raster(const uint8_t *data, size_t size);
int fuzz_entry_scene(const uint8_t *data, size_t size);
int fuzz_entry_image(const uint8_t *data, size_t size);
int fuzz_entry_hpgl(const uint8_t *data, size_t size);
int fuzz_entry_plotmeta(const uint8_t *data, size_t size);
int fuzz_entry_imgread(const uint8_t *data, size_t size);
int fuzz_entry_vector(const uint8_t *data, size_t size);
int fuzz_entry_vecdash(const uint8_t *data, size_t size);
int fuzz_entry_resume(const uint8_t *data, size_t size);
int fuzz_entry_journal(const uint8_t *data, size_t size);
int fuzz_entry_svg(const uint8_t *data, size_t size);

static const struct {
	const char *name;          /* harness name; regression files are named NAME-... */
	int (*entry)(const uint8_t *, size_t);
	const char *seeds[3];      /* seed directories replayed too */
} harness[] = {
	{ "meta_text", fuzz_entry_meta_text, { "fixtures/meta", "fixtures/fuzz/meta_text", NULL } },
	{ "meta_binary", fuzz_entry_meta_binary, { "fixtures/fuzz/meta_binary", NULL } },
	{ "raster", fuzz_entry_raster, { "fixtures/fuzz/raster", NULL } },
	{ "scene", fuzz_entry_scene, { "fixtures/fuzz/scene", NULL } },
	{ "image", fuzz_entry_image, { "fixtures/fuzz/image", NULL } },
	{ "hpgl", fuzz_entry_hpgl, { "fixtures/fuzz/hpgl", "fixtures/hpgl", NULL } },
	{ "plotmeta", fuzz_entry_plotmeta, { "fixtures/fuzz/plotmeta", "fixtures/import", NULL } },
	{ "imgread", fuzz_entry_imgread, { "fixtures/fuzz/imgread", NULL } },
	{ "vector", fuzz_entry_vector, { "fixtures/meta", "fixtures/fuzz/raster", NULL } },
	{ "vecdash", fuzz_entry_vecdash, { "fixtures/dash", "fixtures/fuzz/vecdash", NULL } },
	{ "resume", fuzz_entry_resume, { "fixtures/fuzz/resume", NULL } },
	{ "journal", fuzz_entry_journal, { "fixtures/fuzz/journal", NULL } },
	{ "svg", fuzz_entry_svg, { "fixtures/fuzz/svg", NULL } },
};
#define NH (sizeof harness / sizeof harness[0])

static int failed;

/* Run one file through one harness (a failed assertion aborts the program: run.sh counts it). */
static int replay(int h, const char *path)
{
	FILE *f = fopen(path, "rb");
	size_t cap = 1 << 16, n = 0, got;
	uint8_t *b = malloc(cap);
	if (!f || !b) {
		printf("not ok - %s: cannot read\n", path);
		failed = 1;
		free(b);
		if (f)
			fclose(f);
		return -1;
	}
	while ((got = fread(b + n, 1, cap - n, f)) > 0) {
		n += got;
		if (n == cap) {
			uint8_t *q = realloc(b, cap *= 2);
			if (!q)
				abort();
			b = q;
		}
	}
	fclose(f);
	fflush(stdout);
	harness[h].entry(b, n);
	free(b);
	return 0;
}

/* Replay every regular file of dir whose name starts with prefix ("" = all). Returns the count. */
static int replay_dir(int h, const char *dir, const char *prefix)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	char **names = NULL;
	size_t nn = 0, cap = 0;
	if (!d)
		return 0;
	while ((e = readdir(d))) {
		if (e->d_name[0] == '.' || strncmp(e->d_name, prefix, strlen(prefix)) || !strcmp(e->d_name, "README.md"))
			continue;
		if (nn == cap && !(names = realloc(names, (cap = cap * 2 + 16) * sizeof *names)))
			abort();
		names[nn++] = strdup(e->d_name);
	}
	closedir(d);
	for (size_t i = 0; i < nn; i++) {   /* a fixed order: sorted by insertion into place */
		for (size_t j = i; j > 0 && strcmp(names[j - 1], names[j]) > 0; j--) {
			char *t = names[j];
			names[j] = names[j - 1];
			names[j - 1] = t;
		}
	}
	for (size_t i = 0; i < nn; i++) {
		char path[1024];
		snprintf(path, sizeof path, "%s/%s", dir, names[i]);
		if (replay(h, path) == 0 && *prefix)
			printf("ok - regression input %s replays through %s without a finding\n", path, harness[h].name);
		free(names[i]);
	}
	free(names);
	return (int)nn;
}

int main(void)
{
	for (int h = 0; h < (int)NH; h++) {
		int n = 0;
		char prefix[64];
		for (int k = 0; harness[h].seeds[k]; k++)
			n += replay_dir(h, harness[h].seeds[k], "");
		printf("%s - %d seeds replay through the %s harness\n", n > 0 ? "ok" : "not ok", n, harness[h].name);
		failed |= n == 0;
		snprintf(prefix, sizeof prefix, "%s-", harness[h].name);
		replay_dir(h, "fixtures/fuzz/regress", prefix);
	}
	return failed;
}
