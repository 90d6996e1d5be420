/* quant_pal.c: the fixed palettes (VGA power-on, EGA 16, 6x6x6 cube, grey) and palette files. */
#include <stdio.h>
#include <string.h>
#include "quant/quant.h"

/* ---- fixed palettes ----------------------------------------------------------------- */

/* The 16 colours of the EGA/VGA text and 16-colour modes, as 6-bit DAC values. */
static const uint8_t ega16[16][3] = {
	{ 0, 0, 0 }, { 0, 0, 42 }, { 0, 42, 0 }, { 0, 42, 42 }, { 42, 0, 0 }, { 42, 0, 42 },
	{ 42, 21, 0 }, { 42, 42, 42 }, { 21, 21, 21 }, { 21, 21, 63 }, { 21, 63, 21 },
	{ 21, 63, 63 }, { 63, 21, 21 }, { 63, 21, 63 }, { 63, 63, 21 }, { 63, 63, 63 },
};

/* The grey ramp of the VGA BIOS palette, entries 16..31. */
static const uint8_t vga_grey[16] = { 0, 5, 8, 11, 14, 17, 20, 24, 28, 32, 36, 40, 45, 50, 56, 63 };

/* The five levels of each block of 24 hues (intensity high/medium/low x saturation). */
static const uint8_t vga_levels[9][5] = {
	{ 0, 16, 31, 47, 63 }, { 31, 39, 47, 55, 63 }, { 45, 49, 54, 58, 63 },
	{ 0, 7, 14, 21, 28 }, { 14, 17, 21, 24, 28 }, { 20, 22, 24, 26, 28 },
	{ 0, 4, 8, 12, 16 }, { 8, 10, 12, 14, 16 }, { 11, 12, 13, 15, 16 },
};

/* One hue of the 24-step cycle blue, magenta, red, yellow, green, cyan, back to blue. */
static void vga_hue(const uint8_t *L, int i, uint8_t *rgb)
{
	int r, g, b;
	if (i <= 4)       r = i, g = 0, b = 4;
	else if (i <= 8)  r = 4, g = 0, b = 8 - i;
	else if (i <= 12) r = 4, g = i - 8, b = 0;
	else if (i <= 16) r = 16 - i, g = 4, b = 0;
	else if (i <= 20) r = 0, g = 4, b = i - 16;
	else              r = 0, g = 24 - i, b = 4;
	rgb[0] = L[r], rgb[1] = L[g], rgb[2] = L[b];
}

int quant_fixed_by_name(const char *name)
{
	static const char *const names[] = { "vga", "ega", "cube", "grey" };
	for (int k = 0; k < 4; k++)
		if (strcmp(name, names[k]) == 0)
			return k;
	if (strcmp(name, "gray") == 0)
		return QUANT_FIXED_GREY;
	return -1;
}

int quant_fixed(int which, unsigned ncolours, quant_palette_t *pal, char *err, size_t errlen)
{
	memset(pal, 0, sizeof *pal);
	switch (which) {
	case QUANT_FIXED_VGA:
		if (ncolours != 256)
			break;
		memcpy(pal->dac, ega16, sizeof ega16);
		for (int k = 0; k < 16; k++)
			memset(pal->dac[16 + k], vga_grey[k], 3);
		for (int blk = 0; blk < 9; blk++)
			for (int i = 0; i < 24; i++)
				vga_hue(vga_levels[blk], i, pal->dac[32 + blk * 24 + i]);
		pal->n = 256;            /* 248..255 stay black */
		return 0;
	case QUANT_FIXED_EGA:
		if (ncolours != 16)
			break;
		memcpy(pal->dac, ega16, sizeof ega16);
		pal->n = 16;
		return 0;
	case QUANT_FIXED_CUBE:
		if (ncolours != 256)
			break;
		for (int k = 0; k < 216; k++) {
			pal->dac[k][0] = (uint8_t)(k / 36 * 63 / 5);
			pal->dac[k][1] = (uint8_t)(k / 6 % 6 * 63 / 5);
			pal->dac[k][2] = (uint8_t)(k % 6 * 63 / 5);
		}
		pal->n = 256;            /* 216..255 black */
		return 0;
	case QUANT_FIXED_GREY: {
		unsigned n = ncolours < 64 ? ncolours : 64;
		for (unsigned k = 0; k < n; k++)
			memset(pal->dac[k], (int)((k * 63 + (n - 1) / 2) / (n - 1)), 3);
		pal->n = ncolours;       /* any rest black */
		return 0;
	}
	}
	snprintf(err, errlen, "the %s palette does not fit a mode of %u colours",
		which == QUANT_FIXED_VGA ? "vga" : which == QUANT_FIXED_EGA ? "ega" :
		which == QUANT_FIXED_CUBE ? "cube" : "grey", ncolours);
	return -1;
}

/* ---- palette files ------------------------------------------------------------------ */

static int hexval(int c)
{
	return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 :
		c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

int quant_parse_palette(const unsigned char *buf, size_t n, const char *name, unsigned ncolours,
		quant_palette_t *pal, char *err, size_t errlen)
{
	return quant_parse_palette_bits(buf, n, name, ncolours, 6, pal, err, errlen);
}

int quant_parse_palette_bits(const unsigned char *buf, size_t n, const char *name, unsigned ncolours,
		unsigned bits, quant_palette_t *pal, char *err, size_t errlen)
{
	memset(pal, 0, sizeof *pal);
	if (n > 0 && buf[0] != '#' && buf[0] != ';' && buf[0] != '/' && buf[0] != '\n' && buf[0] != ' ') {
		/* a raw DAC dump */
		if (n != 768) {
			snprintf(err, errlen, "%s: byte 0: expected 768 bytes of a raw DAC dump or lines of #rrggbb, got %zu bytes", name, n);
			return -1;
		}
		for (size_t k = 0; k < 768; k++)
			if (buf[k] > 63) {
				snprintf(err, errlen, "%s: byte %zu: DAC value %u above 63", name, k, buf[k]);
				return -1;
			}
		if (ncolours < 256) {
			snprintf(err, errlen, "%s: a 256-entry DAC dump does not fit a mode of %u colours", name, ncolours);
			return -1;
		}
		memcpy(pal->dac, buf, 768);
		pal->n = 256;
		return 0;
	}
	size_t pos = 0;
	unsigned line = 1;
	while (pos < n) {
		size_t end = pos;
		while (end < n && buf[end] != '\n')
			end++;
		size_t a = pos, b = end;
		while (a < b && (buf[a] == ' ' || buf[a] == '\t'))
			a++;
		while (b > a && (buf[b - 1] == ' ' || buf[b - 1] == '\t' || buf[b - 1] == '\r'))
			b--;
		int comment = a < b && (buf[a] == ';' || (buf[a] == '/' && a + 1 < b && buf[a + 1] == '/'));
		if (a < b && !comment) {
			int v[6] = { -1 };
			int good = b - a == 7 && buf[a] == '#';
			for (int k = 0; good && k < 6; k++)
				good = (v[k] = hexval(buf[a + 1 + k])) >= 0;
			if (!good) {
				snprintf(err, errlen, "%s:%u:%zu: expected #rrggbb", name, line, a - pos + 1);
				return -1;
			}
			if (pal->n == ncolours) {
				snprintf(err, errlen, "%s:%u:1: more than %u colours for this mode", name, line, ncolours);
				return -1;
			}
			for (int c = 0; c < 3; c++)
				pal->dac[pal->n][c] = (uint8_t)(bits == 8 ? (unsigned)(v[2 * c] * 16 + v[2 * c + 1]) :
					quant_dac6((unsigned)(v[2 * c] * 16 + v[2 * c + 1])));
			pal->n++;
		}
		pos = end + 1;
		line++;
	}
	if (pal->n == 0) {
		snprintf(err, errlen, "%s:1:1: expected #rrggbb lines, found no colour", name);
		return -1;
	}
	pal->bits = bits == 8 ? 8 : 6;
	return 0;
}
