/* test_film.c: film encoding: log curve, calibration files, DPX/Cineon header offsets, packing. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "film/filmenc.h"
#include "unit.h"

static uint32_t be32(const uint8_t *b, size_t o) { return (uint32_t)b[o] << 24 | (uint32_t)b[o + 1] << 16 | (uint32_t)b[o + 2] << 8 | b[o + 3]; }
static uint32_t le32(const uint8_t *b, size_t o) { return (uint32_t)b[o + 3] << 24 | (uint32_t)b[o + 2] << 16 | (uint32_t)b[o + 1] << 8 | b[o]; }
static unsigned be16(const uint8_t *b, size_t o) { return (unsigned)b[o] << 8 | b[o + 1]; }
static float bef(const uint8_t *b, size_t o) { uint32_t u = be32(b, o); float f; memcpy(&f, &u, 4); return f; }

static double srgb_encode(double x)
{
	return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

static void test_log(void)
{
	film_log_t p;
	char err[200];
	film_log_default(&p);
	CHECK(film_log_encode(&p, 0) == 95, "linear 0 is reference black 95");
	CHECK(film_log_encode(&p, 1) == 685, "linear 1 is reference white 685");
	CHECK(film_log_encode(&p, 100) == 1023 && film_log_encode(&p, -1) == 0, "clamped to 0..1023");
	/* 0.002 density per code, gamma 0.6: half the light is log10(2) * 0.6 / 0.002 codes lower,
	 * nearly (the black offset shifts it a little) */
	unsigned half = film_log_encode(&p, 0.5);
	CHECK(half >= 594 && half <= 596, "linear 0.5 is code %u (about 685 - 90.3)", half);
	int mono = 1, round = 1;
	for (int v = 1; v < 256; v++) {
		unsigned a = film_log_encode(&p, film_srgb_decode((unsigned)v - 1));
		unsigned b = film_log_encode(&p, film_srgb_decode((unsigned)v));
		mono &= a < b;
		round &= fabs(srgb_encode(film_log_decode(&p, b)) * 255 - v) <= 1.0;
	}
	CHECK(mono, "the curve increases: every 8-bit value of the picture gets a code of its own");
	CHECK(round, "every 8-bit value decodes back (log to linear to sRGB) within one code value");
	CHECK(film_srgb_decode(0) == 0 && film_srgb_decode(255) == 1 && fabs(film_srgb_decode(128) - 0.2158605) < 1e-6,
		"sRGB decoding of the picture's values");
	CHECK(fabs(film_log_decode(&p, 95)) < 1e-12 && fabs(film_log_decode(&p, 685) - 1) < 1e-12,
		"decode inverts the end points");
	p.white = 700;
	CHECK(film_log_encode(&p, 1) == 700, "white is adjustable");
	film_log_default(&p);
	p.display_gamma = 3.4;   /* twice the slope: half the codes between black and white are used */
	CHECK(film_log_encode(&p, 0) == 95 && film_log_encode(&p, 1) == 685, "display gamma keeps the end points");
	CHECK(film_log_encode(&p, 0.5) > half, "a higher display gamma lifts the mid-tones (%u)", film_log_encode(&p, 0.5));
	film_log_default(&p);
	p.black = 700;
	CHECK(film_log_check(&p, err, sizeof err) < 0 && strstr(err, "black"), "black above white refused: %s", err);
	film_log_default(&p);
	p.film_gamma = 0;
	CHECK(film_log_check(&p, err, sizeof err) < 0, "film gamma 0 refused: %s", err);
	film_log_default(&p);
	CHECK(film_log_check(&p, err, sizeof err) == 0, "the defaults pass");
}

static film_frame_t frame(int kind, unsigned w, unsigned h)
{
	film_frame_t f;
	memset(&f, 0, sizeof f);
	f.kind = kind;
	f.width = w;
	f.height = h;
	f.channel = -1;
	film_log_default(&f.log);
	f.creator = "test creator";
	f.time = 1700000000;   /* 2023-11-14 22:13:20 UTC */
	f.frame = 7;
	return f;
}

static void test_dpx_header(void)
{
	uint8_t h[FILM_HEADER_SIZE];
	char err[200];
	film_frame_t f = frame(FILM_DPX10, 64, 43);
	CHECK(film_header(&f, h, err, sizeof err) == 0, "DPX header written");
	CHECK(!memcmp(h, "SDPX", 4), "0: magic SDPX");
	CHECK(be32(h, 4) == 2048, "4: image data offset 2048");
	CHECK(!strcmp((char *)h + 8, "V2.0"), "8: version V2.0");
	CHECK(be32(h, 16) == 2048 + 64 * 43 * 4, "16: file size %u", be32(h, 16));
	CHECK(film_file_size(&f) == 2048 + 64 * 43 * 4, "film_file_size agrees");
	CHECK(be32(h, 24) == 1664 && be32(h, 28) == 384, "24, 28: generic and industry header sizes");
	CHECK(!strcmp((char *)h + 136, "2023:11:14:22:13:20Z"), "136: time stamp '%s'", (char *)h + 136);
	CHECK(!strcmp((char *)h + 160, "test creator"), "160: creator");
	CHECK(be32(h, 660) == 0xFFFFFFFFu, "660: not encrypted");
	CHECK(be16(h, 768) == 0 && be16(h, 770) == 1, "768: orientation left-right top-bottom; 770: one element");
	CHECK(be32(h, 772) == 64 && be32(h, 776) == 43, "772, 776: pixels per line, lines");
	CHECK(be32(h, 780) == 0, "780: element 0 unsigned");
	CHECK(h[800] == 50 && h[801] == 1 && h[802] == 1 && h[803] == 10, "800-803: RGB, printing density, 10 bits");
	CHECK(be16(h, 804) == 1 && be16(h, 806) == 0, "804: packing method A, 806: no encoding");
	CHECK(be32(h, 808) == 2048, "808: element data offset");
	CHECK(be32(h, 784) == 0 && be32(h, 792) == 1023 && fabs(bef(h, 796) - 2.046) < 1e-6, "reference codes and densities");
	CHECK(h[852 + 20] == 0xFF, "element 1 undefined");
	CHECK(be32(h, 1628) == 1 && be32(h, 1632) == 1, "1628: pixel aspect 1:1");
	CHECK(be32(h, 1712) == 7, "1712: frame position");
	CHECK(bef(h, 1952) == 95 && bef(h, 1964) == 685, "1952, 1964: black and white level");
	f.little_endian = 1;
	film_header(&f, h, err, sizeof err);
	CHECK(!memcmp(h, "XPDS", 4) && le32(h, 4) == 2048 && le32(h, 772) == 64 && h[800] == 50,
		"little-endian: magic XPDS and every number swapped");
	CHECK(le32(h, 16) == 2048 + 64 * 43 * 4, "little-endian file size");
	f = frame(FILM_DPX16, 65, 3);
	film_header(&f, h, err, sizeof err);
	CHECK(h[801] == 2 && h[803] == 16 && be16(h, 804) == 0, "16-bit: linear, 16 bits, packed");
	CHECK(film_row_bytes(&f) == 390 && be32(h, 16) == 2048 + 390 * 3, "16-bit rows of an odd width unpadded (390 bytes)");
	f = frame(FILM_DPX10, 64, 43);
	f.planar = 1;
	film_header(&f, h, err, sizeof err);
	size_t row = (64 + 2) / 3 * 4;
	CHECK(be16(h, 770) == 3 && h[800] == 1 && h[872] == 2 && h[944] == 3, "planar: three elements R, G, B");
	CHECK(be32(h, 808) == 2048 && be32(h, 880) == 2048 + row * 43 && be32(h, 952) == 2048 + 2 * row * 43,
		"planar: element offsets one plane apart");
	CHECK(be32(h, 16) == 2048 + 3 * row * 43, "planar: file size");
	f = frame(FILM_DPX16, 32768, 32768);
	CHECK(film_file_size(&f) == 0 && film_header(&f, h, err, sizeof err) < 0, "over 4 GiB refused: %s", err);
	f = frame(FILM_DPX10, 0, 10);
	CHECK(film_header(&f, h, err, sizeof err) < 0, "empty frame refused: %s", err);
}

static void test_cineon_header(void)
{
	uint8_t h[FILM_HEADER_SIZE];
	char err[200];
	film_frame_t f = frame(FILM_CINEON, 64, 43);
	CHECK(film_header(&f, h, err, sizeof err) == 0, "Cineon header written");
	CHECK(be32(h, 0) == 0x802A5FD7u && be32(h, 4) == 2048, "0: magic, 4: image offset");
	CHECK(be32(h, 8) == 1024 && be32(h, 12) == 1024, "8, 12: header lengths");
	CHECK(be32(h, 20) == 2048 + 64 * 43 * 4, "20: file size");
	CHECK(!strcmp((char *)h + 24, "V4.5"), "24: version");
	CHECK(!strcmp((char *)h + 132, "2023:11:14") && !strcmp((char *)h + 144, "22:13:20Z"), "132, 144: date and time");
	CHECK(h[192] == 0 && h[193] == 3, "192: orientation, 193: three channels");
	CHECK(h[196] == 0 && h[197] == 1 && h[225] == 2 && h[253] == 3, "channel designators R, G, B");
	CHECK(h[198] == 10 && be32(h, 200) == 64 && be32(h, 204) == 43, "10 bits, pixels, lines");
	CHECK(bef(h, 216) == 1023 && fabs(bef(h, 220) - 2.046) < 1e-6, "maximum code and density");
	CHECK(h[680] == 0 && h[681] == 5 && h[682] == 0 && h[683] == 0, "680-683: pixel interleave, packing 5, unsigned, positive");
	CHECK(be32(h, 1068) == 7, "1068: frame position");
	f.little_endian = 1;
	CHECK(film_header(&f, h, err, sizeof err) < 0, "little-endian Cineon refused: %s", err);
	f.little_endian = 0;
	f.channel = 2;
	film_header(&f, h, err, sizeof err);
	CHECK(h[193] == 1 && h[197] == 3 && be32(h, 20) == 2048 + 22 * 4 * 43, "a blue separation: one channel, designator 3");
	f.channel = -1;
	f.planar = 1;
	CHECK(film_header(&f, h, err, sizeof err) < 0, "planar Cineon refused: %s", err);
}

static void test_pack(void)
{
	film_lut_t lut;
	film_log_t p;
	film_log_default(&p);
	for (int c = 0; c < 3; c++)
		for (int v = 0; v < 256; v++)
			lut.code[c][v] = (uint16_t)(v * 4 + c);   /* codes that show which channel they came from */
	const uint8_t rgb[12] = { 1, 2, 3, 10, 20, 30, 100, 110, 120, 255, 254, 253 };
	uint8_t out[64];
	film_frame_t f = frame(FILM_DPX10, 4, 1);
	film_pack_row(&f, &lut, rgb, -1, out);
	CHECK(be32(out, 0) == ((4u << 22) | (9u << 12) | (14u << 2)), "RGB word: R 31-22, G 21-12, B 11-2");
	CHECK(be32(out, 12) == ((1020u << 22) | (1017u << 12) | (1014u << 2)), "last pixel");
	f.little_endian = 1;
	film_pack_row(&f, &lut, rgb, -1, out);
	CHECK(le32(out, 0) == ((4u << 22) | (9u << 12) | (14u << 2)), "little-endian word");
	f = frame(FILM_DPX10, 4, 1);
	f.channel = 1;
	CHECK(film_row_bytes(&f) == 8, "one channel of 4: two words");
	film_pack_row(&f, &lut, rgb, 1, out);
	CHECK(be32(out, 0) == ((441u << 22) | (81u << 12) | (9u << 2)) && be32(out, 4) == 1017u << 2,
		"one channel: first sample in 11-2, then 21-12, 31-22; a last part word from the bottom");
	f = frame(FILM_DPX16, 4, 1);
	CHECK(film_row_bytes(&f) == 24, "16-bit row of 4");
	film_pack_row(&f, &lut, rgb, -1, out);
	CHECK(be16(out, 0) == 4 && be16(out, 2) == 9 && be16(out, 22) == 1014, "16-bit big-endian samples R, G, B");
	film_lut_build(&lut, FILM_DPX16, &p, NULL);
	CHECK(lut.code[0][255] == 65535 && lut.code[2][128] == 14146 && lut.code[1][0] == 0, "16-bit linear table (%u)", lut.code[2][128]);
	film_lut_build(&lut, FILM_DPX10, &p, NULL);
	CHECK(lut.code[0][0] == 95 && lut.code[1][255] == 685 && lut.code[2][128] == 490, "10-bit log table (%u)", lut.code[2][128]);
}

static const char *cal_err(const char *text)
{
	static char err[300];
	film_cal_t *c = NULL;
	err[0] = 0;
	if (film_cal_parse(text, strlen(text), "cal.txt", &c, err, sizeof err) == 0)
		snprintf(err, sizeof err, "accepted");
	film_cal_free(c);
	return err;
}

static void test_cal(void)
{
	const char *good = "# measured on the recorder\nlocus-film-calibration 1\n"
		"0 0 0 0\n0.5 0.25 0.5 0.75  # a comment\n1 1 1 1\n";
	film_cal_t *c = NULL;
	char err[300];
	CHECK(film_cal_parse(good, strlen(good), "cal.txt", &c, err, sizeof err) == 0, "a good file loads");
	CHECK(fabs(film_cal_apply(c, 0, 0.5) - 0.25) < 1e-12 && fabs(film_cal_apply(c, 2, 0.25) - 0.375) < 1e-12,
		"piecewise linear per channel");
	CHECK(film_cal_apply(c, 1, 1) == 1 && film_cal_apply(c, 0, 0) == 0, "end points");
	film_lut_t a, b;
	film_log_t p;
	film_log_default(&p);
	film_lut_build(&a, FILM_DPX10, &p, c);
	film_lut_build(&b, FILM_DPX10, &p, NULL);
	CHECK(a.code[0][128] < b.code[0][128] && a.code[1][128] == b.code[1][128] && a.code[2][128] > b.code[2][128],
		"the curve is applied before encoding");
	film_cal_free(c);
	const char *resp = "locus-film-calibration 1\nkind response\n0 0 0 0\n0.5 0.25 0.5 0.75\n1 1 1 1\n";
	CHECK(film_cal_parse(resp, strlen(resp), "r.txt", &c, err, sizeof err) == 0, "a response curve loads");
	CHECK(fabs(film_cal_apply(c, 0, 0.25) - 0.5) < 1e-12 && fabs(film_cal_apply(c, 2, 0.75) - 0.5) < 1e-12,
		"a response is inverted: send 0.5 to get 0.25 on red");
	film_cal_free(c);
	CHECK_STR(cal_err(""), "cal.txt:1:1: expected 'locus-film-calibration 1', found an empty file", "empty file");
	CHECK_STR(cal_err("P6\n"), "cal.txt:1:1: expected 'locus-film-calibration 1' as the first line, found 'P6'", "not a curve");
	CHECK_STR(cal_err("locus-film-calibration 2\n"), "cal.txt:1:24: expected version 1, found '2'", "version");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 x 0.5\n1 1 1 1\n"),
		"cal.txt:3:9: expected a number for green, found 'x'", "bad number");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 1.5 0.5\n1 1 1 1\n"),
		"cal.txt:3:9: green value 1.5 is outside [0, 1]", "out of range");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 0.5\n1 1 1 1\n"),
		"cal.txt:3:12: expected a number for blue, found 'end of line'", "three numbers");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 0.5 0.5 0.5\n1 1 1 1\n"),
		"cal.txt:3:17: expected the end of the line after four numbers, found '0.5'", "five numbers");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0.0000000000000000000000000000000000000000000001\n1 1 1 1\n"),
		"cal.txt:2:7: expected a number for blue, found '0.00000000000000000000000000000'", "a number too long to be read");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0# comment\n1 1 1 1 # end\n"), "accepted", "comments after numbers");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 nan\n1 1 1 1\n"),
		"cal.txt:2:7: expected a number for blue, found 'nan'", "nan");
	CHECK_STR(cal_err("locus-film-calibration 1\n0.1 0 0 0\n1 1 1 1\n"),
		"cal.txt:2:1: the first point must have input 0", "first input");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 0.5 0.5\n0.5 0.6 0.6 0.6\n1 1 1 1\n"),
		"cal.txt:4:1: inputs must increase from point to point", "increasing inputs");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 0.4 0.5\n0.7 0.6 0.3 0.6\n1 1 1 1\n"),
		"cal.txt:4:1: the green correction must not decrease", "monotone");
	CHECK_STR(cal_err("locus-film-calibration 1\nkind response\n0 0 0 0\n0.5 0.5 0 0.5\n1 1 1 1\n"),
		"cal.txt:4:1: the green response must increase (a recorder's response has to be invertible)", "invertible");
	CHECK_STR(cal_err("locus-film-calibration 1\n0 0 0 0\n0.5 0.5 0.5 0.5\n"),
		"cal.txt:3:1: the curve must end with a point at input 1 (it has 2 points)", "last input");
	CHECK_STR(cal_err("locus-film-calibration 1\nkind linear\n"),
		"cal.txt:2:6: expected 'correction' or 'response' after 'kind', found 'linear'", "kind");
	CHECK(film_cal_load("/nonexistent/cal.txt", &c, err, sizeof err) == -66, "missing file: %s", err);
}

/* random mutations of a good file: every result is a curve or one message naming a place */
static void test_cal_fuzz(void)
{
	const char *good = "locus-film-calibration 1\nkind response\n0 0 0 0\n0.25 0.2 0.3 0.25\n"
		"0.5 0.45 0.55 0.5 # mid\n1 1 1 1\n";
	size_t n = strlen(good);
	char buf[128], err[300];
	unsigned seed = 12345, bad_msgs = 0, accepted = 0, refused = 0;
	const char alphabet[] = "0123456789. \n#-ekx\t\r";
	for (int it = 0; it < 3000; it++) {
		memcpy(buf, good, n);
		size_t len = n;
		for (int m = 0; m < 1 + it % 4; m++) {
			seed = seed * 1103515245u + 12345u;
			size_t at = (seed >> 8) % len;
			seed = seed * 1103515245u + 12345u;
			int op = (int)((seed >> 8) % 3);
			char ch = alphabet[(seed >> 12) % (sizeof alphabet - 1)];
			if (op == 0)
				buf[at] = ch;
			else if (op == 1 && len > 1) {
				memmove(buf + at, buf + at + 1, len - at - 1);
				len--;
			} else if (len + 1 < sizeof buf) {
				memmove(buf + at + 1, buf + at, len - at);
				buf[at] = ch;
				len++;
			}
		}
		film_cal_t *c = NULL;
		if (film_cal_parse(buf, len, "f.cal", &c, err, sizeof err) == 0) {
			accepted++;
			for (int ch = 0; ch < 3; ch++)
				for (int v = 0; v <= 16; v++) {
					double y = film_cal_apply(c, ch, v / 16.0);
					if (!(y >= 0 && y <= 1))
						bad_msgs++;
				}
			film_cal_free(c);
		} else {
			refused++;
			if (strncmp(err, "f.cal:", 6) || strchr(err, '\n'))
				bad_msgs++;
		}
	}
	CHECK(bad_msgs == 0 && accepted > 0 && refused > 0, "3000 mutated files: %u curves in [0, 1], %u refused "
		"with one 'f.cal:LINE:COL:' line each", accepted, refused);
}

static void test_presets(void)
{
	const film_preset_t *p = film_preset_find("slide4k");
	CHECK(p && p->width == 4096 && p->height == 2730, "slide4k 4096x2730");
	p = film_preset_find("slide8k");
	CHECK(p && p->width == 8192 && p->height == 5460, "slide8k 8192x5460");
	p = film_preset_find("2k");
	CHECK(p && p->width == 2048 && p->height == 1556, "2k full aperture");
	p = film_preset_find("4k");
	CHECK(p && p->width == 4096 && p->height == 3112, "4k full aperture");
	CHECK(film_preset_find("6x7") && !film_preset_find("8x10"), "6x7 known, 8x10 not");
	unsigned w, h;
	CHECK(film_parse_size("64x43", &w, &h) == 0 && w == 64 && h == 43, "size 64x43");
	CHECK(film_parse_size("0x43", &w, &h) < 0 && film_parse_size("64x", &w, &h) < 0 &&
		film_parse_size("32769x2", &w, &h) < 0 && film_parse_size("64x43x", &w, &h) < 0, "bad sizes refused");
}

int main(void)
{
	test_log();
	test_dpx_header();
	test_cineon_header();
	test_pack();
	test_cal();
	test_cal_fuzz();
	test_presets();
	return UNIT_DONE();
}
