/* filmhdr.c: DPX 2.0 (SMPTE ST 268) and Cineon 4.5 headers, and rows packed as they describe. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "film/filmenc.h"

#define DPX_GENERIC 1664     /* file + image + orientation headers */
#define DPX_INDUSTRY 384     /* film + television headers */
#define CIN_GENERIC 1024
#define CIN_INDUSTRY 1024

typedef struct {
	uint8_t *b;
	int le;
} hdr_t;

static void u8(hdr_t *h, size_t off, unsigned v) { h->b[off] = (uint8_t)v; }

static void u16(hdr_t *h, size_t off, unsigned v)
{
	h->b[off + (h->le ? 0 : 1)] = (uint8_t)v;
	h->b[off + (h->le ? 1 : 0)] = (uint8_t)(v >> 8);
}

static void u32(hdr_t *h, size_t off, uint32_t v)
{
	for (int k = 0; k < 4; k++)
		h->b[off + (size_t)(h->le ? k : 3 - k)] = (uint8_t)(v >> (8 * k));
}

static void r32(hdr_t *h, size_t off, double v)
{
	float f = (float)v;
	uint32_t u;
	memcpy(&u, &f, 4);
	u32(h, off, u);
}

/* a text field of n bytes, NUL padded (the value is cut to n - 1 bytes) */
static void str(hdr_t *h, size_t off, size_t n, const char *s)
{
	memset(h->b + off, 0, n);
	size_t k = s ? strlen(s) : 0;
	memcpy(h->b + off, s, k < n ? k : n - 1);
}

static int channels(const film_frame_t *f)
{
	return f->channel >= 0 || f->planar ? 1 : 3;
}

size_t film_row_bytes(const film_frame_t *f)
{
	size_t n = (size_t)f->width * (size_t)channels(f);
	if (f->kind == FILM_DPX16)
		return n * 2;                       /* no padding: ImageMagick and OpenImageIO read none */
	return (n + 2) / 3 * 4;                 /* three 10-bit samples per 32-bit word */
}

static unsigned elements(const film_frame_t *f)
{
	return f->planar ? 3 : 1;
}

uint64_t film_file_size(const film_frame_t *f)
{
	uint64_t s = FILM_HEADER_SIZE + (uint64_t)film_row_bytes(f) * f->height * elements(f);
	return s > 0xFFFFFFFFu ? 0 : s;
}

/* "2026:12:01:19:05:00" of t (UTC), into 20 bytes */
static void stamp(int64_t t, const char *fmt, char *out, size_t n)
{
	time_t tt = (time_t)t;
	struct tm tm;
	if (!gmtime_r(&tt, &tm) || !strftime(out, n, fmt, &tm))
		out[0] = 0;
}

uint32_t film_timecode(unsigned frame, double rate)
{
	unsigned fps = rate >= 1 ? (unsigned)(rate + 0.5) : 1;
	unsigned long long f = frame % (24ull * 3600 * fps);
	unsigned v[4] = { (unsigned)(f / fps / 3600), (unsigned)(f / fps / 60 % 60), (unsigned)(f / fps % 60),
		(unsigned)(f % fps) };
	uint32_t tc = 0;
	for (int k = 0; k < 4; k++)
		tc = tc << 8 | (uint32_t)(v[k] / 10 % 10) << 4 | (uint32_t)(v[k] % 10);
	return tc;
}

static void dpx_element(hdr_t *h, const film_frame_t *f, size_t off, int ch, uint32_t data)
{
	static const unsigned desc_of[3] = { 1, 2, 3 };   /* red, green, blue */
	int log = f->kind != FILM_DPX16;
	u32(h, off + 0, 0);                               /* data sign: unsigned */
	if (log) {
		u32(h, off + 4, 0);                           /* reference low code, quantity */
		r32(h, off + 8, 0.0);
		u32(h, off + 12, 1023);                       /* reference high code, density */
		r32(h, off + 16, 1023 * f->log.density);
	} else {
		u32(h, off + 4, 0);
		r32(h, off + 8, 0.0);
		u32(h, off + 12, 65535);
		r32(h, off + 16, 1.0);
	}
	u8(h, off + 20, ch < 0 ? 50 : desc_of[ch]);       /* descriptor: RGB, or R / G / B */
	u8(h, off + 21, log ? 1 : 2);                     /* transfer: printing density / linear */
	u8(h, off + 22, log ? 1 : 2);                     /* colorimetric: printing density / n.a. */
	u8(h, off + 23, log ? 10 : 16);                   /* bit depth */
	u16(h, off + 24, log ? 1 : 0);                    /* packing: method A / packed */
	u16(h, off + 26, 0);                              /* encoding: none */
	u32(h, off + 28, data);                           /* offset to data */
	u32(h, off + 32, 0);                              /* end-of-line padding */
	u32(h, off + 36, 0);                              /* end-of-image padding */
	str(h, off + 40, 32, ch < 0 ? "RGB" : ch == 0 ? "red separation" : ch == 1 ?
		"green separation" : "blue separation");
}

static int dpx_header(const film_frame_t *f, uint8_t *buf)
{
	hdr_t h = { buf, f->little_endian };
	uint32_t size = (uint32_t)film_file_size(f);
	uint32_t elem_bytes = (uint32_t)(film_row_bytes(f) * f->height);
	char t[32];
	memset(buf, 0xFF, FILM_HEADER_SIZE);               /* undefined numbers: all ones */
	/* file information header */
	u32(&h, 0, 0x53445058);                           /* "SDPX" in the file's byte order */
	u32(&h, 4, FILM_HEADER_SIZE);
	str(&h, 8, 8, "V2.0");
	u32(&h, 16, size);
	u32(&h, 20, 1);                                   /* ditto key: new frame */
	u32(&h, 24, DPX_GENERIC);
	u32(&h, 28, DPX_INDUSTRY);
	u32(&h, 32, 0);                                   /* no user data */
	str(&h, 36, 100, "");                             /* file name: not known per page */
	stamp(f->time, "%Y:%m:%d:%H:%M:%SZ", t, sizeof t);
	str(&h, 136, 24, t);
	str(&h, 160, 100, f->creator);
	str(&h, 260, 200, "");                            /* project */
	str(&h, 460, 200, "");                            /* copyright */
	memset(buf + 664, 0, 104);                        /* reserved; 660: no encryption (all ones) */
	/* image information header */
	u16(&h, 768, 0);                                  /* orientation: left to right, top to bottom */
	u16(&h, 770, (unsigned)elements(f));
	u32(&h, 772, f->width);
	u32(&h, 776, f->height);
	for (unsigned e = 0; e < 8; e++) {
		size_t off = 780 + 72 * (size_t)e;
		if (e < elements(f))
			dpx_element(&h, f, off, f->planar ? (int)e : f->channel, FILM_HEADER_SIZE + e * elem_bytes);
		else
			str(&h, off + 40, 32, "");
	}
	memset(buf + 1356, 0, 52);                        /* reserved */
	/* image orientation header */
	u32(&h, 1408, 0);                                 /* x, y offset */
	u32(&h, 1412, 0);
	r32(&h, 1416, f->width / 2.0);                    /* x, y centre */
	r32(&h, 1420, f->height / 2.0);
	u32(&h, 1424, f->width);                          /* original size */
	u32(&h, 1428, f->height);
	str(&h, 1432, 100, "");                           /* source file name */
	str(&h, 1532, 24, "");                            /* source time */
	str(&h, 1556, 32, "");                            /* input device */
	str(&h, 1588, 32, "");                            /* serial number */
	u32(&h, 1628, 1);                                 /* pixel aspect 1:1 */
	u32(&h, 1632, 1);
	if (f->width_mm > 0 && f->height_mm > 0) {
		r32(&h, 1636, f->width_mm);                   /* scanned size, mm */
		r32(&h, 1640, f->height_mm);
	}
	memset(buf + 1644, 0, 20);
	/* motion-picture film header */
	str(&h, 1664, 2, "");
	str(&h, 1666, 2, "");
	str(&h, 1668, 2, "");
	str(&h, 1670, 6, "");
	str(&h, 1676, 4, "");
	str(&h, 1680, 32, "");                            /* format */
	u32(&h, 1712, f->frame);                          /* frame position in the sequence */
	/* 1716 sequence length: not known to one node of a farm (undefined) */
	u32(&h, 1720, 1);                                 /* held count: each frame shown once */
	if (f->frame_rate > 0)
		r32(&h, 1724, f->frame_rate);                 /* frame rate of the original, fps */
	str(&h, 1732, 32, "");                            /* frame id */
	str(&h, 1764, 100, "");                           /* slate */
	memset(buf + 1864, 0, 56);
	/* television header: the time code and rate of the sequence, and the reference codes, where DPX
	 * readers look for them */
	if (f->frame_rate > 0) {
		u32(&h, 1920, film_timecode(f->frame, f->frame_rate));   /* SMPTE time code, BCD */
		u32(&h, 1924, 0);                             /* user bits */
		u8(&h, 1928, 0);                              /* interlace: none (progressive frames) */
		u8(&h, 1929, 0);                              /* field number: none */
		r32(&h, 1940, f->frame_rate);                 /* temporal sampling rate, Hz */
	}
	if (f->kind != FILM_DPX16) {
		r32(&h, 1952, f->log.black);                  /* black level */
		r32(&h, 1964, f->log.white);                  /* white level */
	}
	memset(buf + 1972, 0, 76);
	return 0;
}

static int cineon_header(const film_frame_t *f, uint8_t *buf)
{
	hdr_t h = { buf, 0 };                             /* Cineon is big-endian */
	static const unsigned desig[3] = { 1, 2, 3 };     /* red, green, blue */
	int nch = channels(f);
	char t[32];
	memset(buf, 0xFF, FILM_HEADER_SIZE);
	/* file information */
	u32(&h, 0, 0x802A5FD7);
	u32(&h, 4, FILM_HEADER_SIZE);
	u32(&h, 8, CIN_GENERIC);
	u32(&h, 12, CIN_INDUSTRY);
	u32(&h, 16, 0);
	u32(&h, 20, (uint32_t)film_file_size(f));
	str(&h, 24, 8, "V4.5");
	str(&h, 32, 100, "");
	stamp(f->time, "%Y:%m:%d", t, sizeof t);
	str(&h, 132, 12, t);
	stamp(f->time, "%H:%M:%SZ", t, sizeof t);
	str(&h, 144, 12, t);
	memset(buf + 156, 0, 36);
	/* image information */
	u8(&h, 192, 0);                                   /* orientation: left to right, top to bottom */
	u8(&h, 193, (unsigned)nch);
	u16(&h, 194, 0);
	for (int c = 0; c < 8; c++) {
		size_t off = 196 + 28 * (size_t)c;
		if (c >= nch)
			continue;
		int ch = f->channel >= 0 ? f->channel : c;
		u8(&h, off, 0);                               /* designator: universal metric */
		u8(&h, off + 1, desig[ch]);
		u8(&h, off + 2, 10);                          /* bits per sample */
		u8(&h, off + 3, 0);
		u32(&h, off + 4, f->width);
		u32(&h, off + 8, f->height);
		r32(&h, off + 12, 0.0);                       /* minimum code and density */
		r32(&h, off + 16, 0.0);
		r32(&h, off + 20, 1023.0);                    /* maximum code and density */
		r32(&h, off + 24, 1023 * f->log.density);
	}
	str(&h, 452, 200, f->creator);                    /* label */
	memset(buf + 652, 0, 28);
	/* image data format */
	u8(&h, 680, 0);                                   /* interleave: by pixel */
	u8(&h, 681, 5);                                   /* packing: 32-bit words, left justified */
	u8(&h, 682, 0);                                   /* unsigned */
	u8(&h, 683, 0);                                   /* positive image */
	u32(&h, 684, 0);                                  /* end-of-line padding */
	u32(&h, 688, 0);                                  /* end-of-channel padding */
	memset(buf + 692, 0, 20);
	/* image origination */
	u32(&h, 712, 0);
	u32(&h, 716, 0);
	str(&h, 720, 100, "");
	stamp(f->time, "%Y:%m:%d", t, sizeof t);
	str(&h, 820, 12, t);
	stamp(f->time, "%H:%M:%SZ", t, sizeof t);
	str(&h, 832, 12, t);
	str(&h, 844, 64, f->creator);                     /* input device */
	str(&h, 908, 32, "");
	str(&h, 940, 32, "");
	memset(buf + 984, 0, 40);
	/* motion-picture industry header */
	u32(&h, 1068, f->frame);                          /* frame position */
	if (f->frame_rate > 0)
		r32(&h, 1072, f->frame_rate);                 /* frame rate, fps (Cineon has no time code) */
	str(&h, 1036, 32, "");
	str(&h, 1076, 32, "");
	str(&h, 1108, 200, "");
	memset(buf + 1308, 0, 740);
	return 0;
}

int film_header(const film_frame_t *f, uint8_t *buf, char *err, size_t errlen)
{
	if (f->width == 0 || f->height == 0) {
		snprintf(err, errlen, "a frame of %ux%u pixels is empty", f->width, f->height);
		return -1;
	}
	if (!film_file_size(f)) {
		snprintf(err, errlen, "a %ux%u frame does not fit the 4 GiB a %s file can hold", f->width,
			f->height, f->kind == FILM_CINEON ? "Cineon" : "DPX");
		return -1;
	}
	if (f->kind == FILM_CINEON && f->little_endian) {
		snprintf(err, errlen, "Cineon files are big-endian only");
		return -1;
	}
	if (f->kind == FILM_CINEON && f->planar) {
		snprintf(err, errlen, "planar separations are written as DPX only");
		return -1;
	}
	if (f->planar && f->channel >= 0) {
		snprintf(err, errlen, "a planar file holds all three channels, not one");
		return -1;
	}
	return f->kind == FILM_CINEON ? cineon_header(f, buf) : dpx_header(f, buf);
}

static void put32(uint8_t *o, uint32_t w, int le)
{
	for (int k = 0; k < 4; k++)
		o[le ? k : 3 - k] = (uint8_t)(w >> (8 * k));
}

void film_pack_row(const film_frame_t *f, const film_lut_t *lut, const uint8_t *rgb, int ch,
		uint8_t *out)
{
	unsigned w = f->width;
	int le = f->kind != FILM_CINEON && f->little_endian;
	if (f->kind == FILM_DPX16) {
		size_t k = 0;
		for (unsigned x = 0; x < w; x++)
			for (int c = 0; c < 3; c++) {
				if (ch >= 0 && c != ch)
					continue;
				unsigned v = lut->code[c][rgb[3 * (size_t)x + (size_t)c]];
				out[k + (le ? 0 : 1)] = (uint8_t)v;
				out[k + (le ? 1 : 0)] = (uint8_t)(v >> 8);
				k += 2;
			}
		return;
	}
	if (ch < 0) {
		const uint16_t *r = lut->code[0], *g = lut->code[1], *b = lut->code[2];
		for (unsigned x = 0; x < w; x++, rgb += 3, out += 4)
			put32(out, (uint32_t)r[rgb[0]] << 22 | (uint32_t)g[rgb[1]] << 12 | (uint32_t)b[rgb[2]] << 2, le);
		return;
	}
	/* one channel: three samples to a word, the first in bits 11-2, the next in 21-12, 31-22; a row
	 * ends on a word boundary (ImageMagick 6.9 and OpenImageIO read a last part-filled word as 0) */
	const uint16_t *t = lut->code[ch];
	for (unsigned x = 0; x < w; x += 3, out += 4) {
		uint32_t word = 0;
		for (unsigned j = 0; j < 3; j++)
			if (x + j < w)
				word |= (uint32_t)t[rgb[3 * (size_t)(x + j) + (size_t)ch]] << (2 + 10 * j);
		put32(out, word, le);
	}
}
