/* filmlog.c: the linear-to-log printing-density curve, the 8-bit to code-value tables, presets. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "film/filmenc.h"

const film_preset_t film_presets[] = {
	{ "slide4k", 4096, 2730, 36.0, 24.0, "35 mm slide, 4096 lines on the long side (3:2)" },
	{ "slide8k", 8192, 5460, 36.0, 24.0, "35 mm slide, 8192 lines on the long side (3:2)" },
	{ "2k", 2048, 1556, 24.89, 18.67, "35 mm full aperture, 2K (Cineon / DPX scan size)" },
	{ "4k", 4096, 3112, 24.89, 18.67, "35 mm full aperture, 4K" },
	{ "6x7", 4096, 3300, 69.5, 56.0, "120 roll film 6x7 (69.5 x 56 mm image), 4096 on the long side" },
	{ NULL, 0, 0, 0, 0, NULL }
};

const film_preset_t *film_preset_find(const char *name)
{
	for (const film_preset_t *p = film_presets; p->name; p++)
		if (strcmp(p->name, name) == 0)
			return p;
	return NULL;
}

void film_log_default(film_log_t *p)
{
	p->white = 685;
	p->black = 95;
	p->density = 0.002;
	p->film_gamma = 0.6;
	p->display_gamma = 1.7;
}

int film_log_check(const film_log_t *p, char *err, size_t errlen)
{
	const char *why = NULL;
	if (!(p->black >= 0 && p->black < p->white))
		why = "reference black must be at least 0 and below reference white";
	else if (!(p->white <= 1023))
		why = "reference white must be at most 1023";
	else if (!(p->density > 0 && p->density <= 0.01))
		why = "density per code value must be in (0, 0.01]";
	else if (!(p->film_gamma > 0 && p->film_gamma <= 10))
		why = "film gamma must be in (0, 10]";
	else if (!(p->display_gamma > 0 && p->display_gamma <= 10))
		why = "display gamma must be in (0, 10]";
	if (why) {
		snprintf(err, errlen, "%s", why);
		return -1;
	}
	return 0;
}

/* log10 of linear light per code value */
static double slope(const film_log_t *p)
{
	return p->density / p->film_gamma * (p->display_gamma / 1.7);
}

/* the linear light of reference black relative to reference white */
static double offset(const film_log_t *p)
{
	return pow(10.0, (p->black - p->white) * slope(p));
}

unsigned film_log_encode(const film_log_t *p, double linear)
{
	double k = slope(p), off = offset(p);
	double e = linear * (1 - off) + off;
	if (!(e > 0))
		return 0;
	double c = p->white + log10(e) / k;
	if (!(c > 0))
		return 0;
	if (c >= 1023)
		return 1023;
	return (unsigned)floor(c + 0.5);
}

double film_log_decode(const film_log_t *p, unsigned code)
{
	double k = slope(p), off = offset(p);
	return (pow(10.0, ((double)code - p->white) * k) - off) / (1 - off);
}

double film_srgb_decode(unsigned v)
{
	double c = v / 255.0;
	return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

void film_lut_build(film_lut_t *lut, int kind, const film_log_t *log, const film_cal_t *cal)
{
	for (int ch = 0; ch < 3; ch++)
		for (int v = 0; v < 256; v++) {
			double x = film_srgb_decode((unsigned)v);
			if (cal)
				x = film_cal_apply(cal, ch, x);
			if (kind == FILM_DPX16)
				lut->code[ch][v] = (uint16_t)floor(x * 65535 + 0.5);
			else
				lut->code[ch][v] = (uint16_t)film_log_encode(log, x);
		}
}
