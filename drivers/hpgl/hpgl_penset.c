/* hpgl_penset.c: per-pen settings (speed, force, acceleration, a pause before the pen) and the
 * pens to pause before, as profile files, device options and locus-hpgl's options give them. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/hpgl.h"

static int pnum(const char *v, double lo, double hi, double *out)
{
	char *e;
	errno = 0;
	double x = strtod(v, &e);
	if (e == v || *e || errno || !(x > lo && x <= hi))
		return -1;
	*out = x;
	return 0;
}

int hpgl_penset_items(const char *items, hpgl_penset_t *one, char *err, size_t errlen)
{
	char buf[256];
	if (strlen(items) >= sizeof buf) {
		snprintf(err, errlen, "pen settings too long: '%.40s...'", items);
		return -1;
	}
	snprintf(buf, sizeof buf, "%s", items);
	int n = 0;
	for (char *t = strtok(buf, ",; \t"); t; t = strtok(NULL, ",; \t"), n++) {
		char *eq = strchr(t, '=');
		const char *v = eq ? eq + 1 : NULL;
		if (eq)
			*eq = 0;
		int bad = 0;
		if (!strcmp(t, "pause")) {
			if (!v || !strcmp(v, "yes"))
				one->pause = 1;
			else if (!strcmp(v, "no"))
				one->pause = 0;
			else
				bad = 1;
		} else if (!v) {
			bad = 1;
		} else if (!strcmp(t, "speed")) {
			bad = pnum(v, 0, 1000, &one->speed);
		} else if (!strcmp(t, "force")) {
			bad = pnum(v, 0, 1000, &one->force);
		} else if (!strcmp(t, "accel")) {
			bad = pnum(v, 0, 1000, &one->accel);
		} else {
			snprintf(err, errlen, "pen settings: unknown setting '%s' (speed=CM/S, force=F, accel=A, pause)", t);
			return -1;
		}
		if (bad) {
			snprintf(err, errlen, "pen settings: %s%s%s: expected %s", t, v ? "=" : "", v ? v : "",
				!strcmp(t, "pause") ? "pause, pause=yes or pause=no" : "KEY=NUMBER, a number above 0 and at most 1000");
			return -1;
		}
	}
	if (!n) {
		snprintf(err, errlen, "pen settings: expected speed=CM/S, force=F, accel=A or pause, not '%s'", items);
		return -1;
	}
	return 0;
}

/* A pen number 1 .. HPGL_MAX_PENS at s (the whole of it up to end). */
static int slot_of(const char *s, const char *end, long *slot)
{
	char num[16];
	if (end - s <= 0 || end - s >= (long)sizeof num)
		return -1;
	memcpy(num, s, (size_t)(end - s));
	num[end - s] = 0;
	char *e;
	errno = 0;
	*slot = strtol(num, &e, 10);
	return e == num || *e || errno || *slot < 1 || *slot > HPGL_MAX_PENS ? -1 : 0;
}

int hpgl_penset_parse(const char *spec, hpgl_penset_t *set, char *err, size_t errlen)
{
	char buf[1024];
	if (strlen(spec) >= sizeof buf) {
		snprintf(err, errlen, "pen: settings too long");
		return -1;
	}
	snprintf(buf, sizeof buf, "%s", spec);
	char *save = NULL;
	for (char *t = strtok_r(buf, "/ \t\n", &save); t; t = strtok_r(NULL, "/ \t\n", &save)) {
		char *colon = strchr(t, ':');
		long slot;
		if (!colon || slot_of(t, colon, &slot)) {
			snprintf(err, errlen, "pen: expected N:speed=V,force=F,accel=A,pause with a pen number N "
				"from 1 to %d, not '%.60s'", HPGL_MAX_PENS, t);
			return -1;
		}
		char e2[200];
		if (hpgl_penset_items(colon + 1, &set[slot], e2, sizeof e2)) {
			snprintf(err, errlen, "pen %ld: %s", slot, e2);
			return -1;
		}
	}
	return 0;
}

int hpgl_pause_parse(const char *spec, hpgl_penset_t *set, int *all, char *err, size_t errlen)
{
	const char *s = spec;
	if (!strcmp(spec, "all") || !strcmp(spec, "none")) {
		*all = spec[0] == 'a';
		if (!*all)
			for (int k = 0; k <= HPGL_MAX_PENS; k++)
				set[k].pause = 0;
		return 0;
	}
	int n = 0;
	while (*s) {
		const char *e = s + strcspn(s, ",; \t");
		long slot;
		if (e > s) {
			if (slot_of(s, e, &slot)) {
				snprintf(err, errlen, "pause: expected pen numbers from 1 to %d (2,3), all or none, not '%s'",
					HPGL_MAX_PENS, spec);
				return -1;
			}
			set[slot].pause = 1;
			n++;
		}
		s = *e ? e + 1 : e;
	}
	if (!n) {
		snprintf(err, errlen, "pause: expected pen numbers (2,3), all or none, not '%s'", spec);
		return -1;
	}
	return 0;
}

int hpgl_penset_check(const hpgl_profile_t *prof, const hpgl_penset_t *set, char *err, size_t errlen)
{
	for (int k = 1; k <= HPGL_MAX_PENS; k++) {
		if (set[k].force > 0 && !prof->has_fs) {
			snprintf(err, errlen, "pen %d: force=%g: profile %s has no FS (force select); a profile file with "
				"force-select = yes says that a plotter has it", k, set[k].force, prof->name);
			return -1;
		}
		if (set[k].accel > 0 && !prof->has_as) {
			snprintf(err, errlen, "pen %d: accel=%g: profile %s has no AS (acceleration select); a profile file "
				"with accel-select = yes says that a plotter has it", k, set[k].accel, prof->name);
			return -1;
		}
	}
	return 0;
}
