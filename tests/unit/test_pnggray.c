/* test_pnggray.c - the plain grey PNG decoder over zlib: on PNGs this test
 * encodes itself (every filter type alone and mixed from row to row, 8 and
 * 16 bits, odd widths, IDAT cut into 1-byte and empty chunks) it must give
 * the samples encoded, as libpng does; on everything it does not take (bad
 * filter types, CRCs, Adler-32, too few or too many rows, other chunks,
 * bytes after IEND, a small zlib window, interlacing, colour, too many
 * pixels) it declines, and fct_image_read then answers as libpng alone. */
#include "check.h"
#include "pngref.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/rng.h"
#include "io/image.h"
#include "io/pnggray.h"

/* A growing byte buffer. */
struct buf {
	unsigned char *b;
	size_t n;
};

static void put(struct buf *o, const void *p, size_t n)
{
	o->b = realloc(o->b, o->n + n + 1);
	if (!o->b)
		abort();
	if (n)   /* p may be NULL then (IEND's data) */
		memcpy(o->b + o->n, p, n);
	o->n += n;
}

static void put32(struct buf *o, uint32_t v)
{
	unsigned char b[4] = { (unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8),
	                       (unsigned char)v };
	put(o, b, 4);
}

static void chunk(struct buf *o, const char *type, const unsigned char *data, size_t n)
{
	put32(o, (uint32_t)n);
	size_t at = o->n;
	put(o, type, 4);
	put(o, data, n);
	put32(o, (uint32_t)crc32(0, o->b + at, (uInt)n + 4));
}

/* The spec's predictor, written out as it says. */
static int spec_paeth(int a, int b, int c)
{
	int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
	if (pa <= pb && pa <= pc)
		return a;
	return pb <= pc ? b : c;
}

/* What to encode and how. */
struct spec {
	int w, h, bits;
	int filter;          /* 0-4 every row, 5: row y's is y % 5, 6: (4 y + 1) % 5 */
	size_t split;        /* IDAT chunk size (0: one chunk); with it, an empty IDAT too */
	int rows;            /* rows put into the stream (0: h) */
	int window_bits;     /* zlib's (0: 15) */
	int bad_filter_row;  /* row bad_filter_row - 1's filter byte 5 (0: none) */
	int interlace, ctype;
	int text;            /* a tEXt chunk before IDAT */
	int trailing;        /* bytes after IEND */
	int second_stream;   /* another zlib stream after the first in IDAT */
	int flip_adler, flip_idat_crc;
};

static int filter_of(const struct spec *s, int y)
{
	if (y + 1 == s->bad_filter_row)
		return 5;
	return s->filter < 5 ? s->filter : s->filter == 5 ? y % 5 : (4 * y + 1) % 5;
}

/* The samples' filtered rows deflated, then the PNG around them. */
static struct buf encode(const struct spec *spec, const uint16_t *samples)
{
	struct spec full = *spec, *s = &full;
	s->rows = s->rows ? s->rows : s->h;
	s->window_bits = s->window_bits ? s->window_bits : 15;
	size_t bpp = (size_t)s->bits / 8, rb = (size_t)s->w * bpp;
	unsigned char *raw = calloc((size_t)s->rows + 1, rb + 1), *zero = calloc(1, rb + 1);
	struct buf filt = { NULL, 0 }, png = { NULL, 0 };
	for (int y = 0; y < s->rows; y++) {
		unsigned char *r = raw + (size_t)(y + 1) * (rb + 1), *p = y ? r - (rb + 1) : zero;
		for (int x = 0; x < s->w; x++) {
			unsigned v = samples[((size_t)y % (size_t)s->h) * (size_t)s->w + (size_t)x];
			if (s->bits == 16)
				r[2 * x] = (unsigned char)(v >> 8), r[2 * x + 1] = (unsigned char)v;
			else
				r[x] = (unsigned char)v;
		}
		int f = filter_of(s, y);
		unsigned char *row = malloc(rb + 1);
		row[0] = (unsigned char)f;
		for (size_t i = 0; i < rb; i++) {
			int a = i >= bpp ? r[i - bpp] : 0, b = p[i], c = i >= bpp ? p[i - bpp] : 0;
			int pred = f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) >> 1 : f == 4 ? spec_paeth(a, b, c) : 0;
			row[1 + i] = (unsigned char)(r[i] - pred);
		}
		put(&filt, row, rb + 1);
		free(row);
	}
	z_stream z;
	memset(&z, 0, sizeof z);
	if (deflateInit2(&z, 6, Z_DEFLATED, s->window_bits, 8, Z_DEFAULT_STRATEGY) != Z_OK)
		abort();
	size_t cap = deflateBound(&z, filt.n) + 64;
	unsigned char *zbuf = malloc(2 * cap);
	z.next_in = filt.b, z.avail_in = (uInt)filt.n, z.next_out = zbuf, z.avail_out = (uInt)cap;
	if (deflate(&z, Z_FINISH) != Z_STREAM_END)
		abort();
	size_t zn = cap - z.avail_out;
	deflateEnd(&z);
	if (s->flip_adler)
		zbuf[zn - 1] ^= 1;
	if (s->second_stream) {
		uLongf more = (uLongf)cap;
		compress(zbuf + zn, &more, (const Bytef *)"x", 1);
		zn += more;
	}

	static const unsigned char magic[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
	put(&png, magic, 8);
	unsigned char ihdr[13] = { 0, 0, 0, 0, 0, 0, 0, 0, (unsigned char)s->bits,
	                           (unsigned char)s->ctype, 0, 0, (unsigned char)s->interlace };
	for (int i = 0; i < 4; i++)
		ihdr[i] = (unsigned char)((uint32_t)s->w >> (24 - 8 * i)),
		ihdr[4 + i] = (unsigned char)((uint32_t)s->h >> (24 - 8 * i));
	chunk(&png, "IHDR", ihdr, 13);
	if (s->text)
		chunk(&png, "tEXt", (const unsigned char *)"Comment\0test_pnggray", 21);
	size_t step = s->split ? s->split : zn;
	for (size_t at = 0; at < zn; at += step) {
		chunk(&png, "IDAT", zbuf + at, zn - at < step ? zn - at : step);
		if (s->split && at == 0)
			chunk(&png, "IDAT", zbuf, 0);
	}
	if (s->flip_idat_crc)
		png.b[33 + 8 + (s->split && s->split < zn ? s->split : zn)] ^= 1;
	chunk(&png, "IEND", NULL, 0);
	for (int i = 0; i < s->trailing; i++)
		put(&png, "!", 1);
	free(zbuf);
	free(filt.b);
	free(raw);
	free(zero);
	return png;
}

static int same_samples(const struct fct_image *img, const uint16_t *samples, int w, int h, int bits)
{
	if (img->width != w || img->height != h || img->channels != 1 ||
	    img->type != (bits == 16 ? FCT_PIX_U16 : FCT_PIX_U8))
		return 0;
	for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
		if ((bits == 16 ? ((const uint16_t *)img->data)[i] : ((const unsigned char *)img->data)[i]) !=
		    samples[i])
			return 0;
	return 1;
}

static int read_mem(struct fct_image *img, const struct buf *png, struct fct_err *err)
{
	FILE *f = fmemopen(png->b, png->n, "rb");
	if (!f)
		return fct_fail(err, "fmemopen failed");
	int rc = fct_image_read_stream(img, f, "mem", NULL, err);
	fclose(f);
	return rc;
}

static struct spec plain(int w, int h, int bits)
{
	struct spec s = { w, h, bits, 5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
	return s;
}

/* Random samples with runs and ramps: plateaus and slopes as in depth. */
static void fill(uint16_t *v, int n, int bits, struct fct_rng *r)
{
	unsigned top = bits == 16 ? 65535 : 255, cur = 0;
	for (int i = 0; i < n; i++) {
		uint64_t k = fct_rng_below(r, 8);
		cur = k == 0 ? (unsigned)fct_rng_below(r, top + 1) : k == 1 ? 0 : k == 2 ? top
		    : k < 5 ? (cur + (unsigned)k) & top : cur;
		v[i] = (uint16_t)cur;
	}
}

/* s's PNG decoded by fct_png_gray_decode, libpng and fct_image_read, all
 * equal to the samples encoded: 1, or 0 with what went wrong on stderr. */
static int decodes_right(const struct spec *s, const uint16_t *samples)
{
	struct buf png = encode(s, samples);
	struct fct_image fast, ref = { 0, 0, 0, FCT_PIX_U8, NULL }, via = ref;
	struct fct_err err;
	int took = fct_png_gray_decode(&fast, png.b, png.n, 1 << 20);
	int ok = took == 1 && same_samples(&fast, samples, s->w, s->h, s->bits) &&
	         !png_ref_decode(&ref, png.b, png.n) && same_samples(&ref, samples, s->w, s->h, s->bits) &&
	         !read_mem(&via, &png, &err) && same_samples(&via, samples, s->w, s->h, s->bits);
	if (!ok)
		fprintf(stderr, "bits %d %dx%d filter %d split %zu: took %d\n", s->bits, s->w, s->h,
		        s->filter, s->split, took);
	if (took == 1)
		free(fast.data);
	free(png.b);
	free(ref.data);
	free(via.data);
	return ok;
}

static void test_encoded_decode(void)
{
	static const int widths[] = { 1, 2, 3, 5, 17, 64 }, heights[] = { 1, 2, 6 };
	static const size_t splits[] = { 0, 1, 7 };
	struct fct_rng r;
	fct_rng_seed(&r, 23);
	uint16_t *samples = malloc(3001 * 50 * sizeof *samples);
	int bad = 0, cases = 0;
	for (int bits = 8; bits <= 16; bits += 8)
		for (size_t wi = 0; wi < sizeof widths / sizeof *widths; wi++)
			for (size_t hi = 0; hi < sizeof heights / sizeof *heights; hi++)
				for (int filter = 0; filter <= 6; filter++)
					for (size_t si = 0; si < sizeof splits / sizeof *splits; si++) {
						struct spec s = plain(widths[wi], heights[hi], bits);
						s.filter = filter, s.split = splits[si];
						fill(samples, s.w * s.h, bits, &r);
						bad += !decodes_right(&s, samples);
						cases++;
					}
	/* Rows wider than the 64 KB zlib is given at a time, and rows that
	 * fill several such blocks, the last short (11 rows of 6001 bytes a
	 * block, 50 rows). */
	static const int big[][3] = { { 40000, 2, 8 }, { 33000, 3, 16 }, { 3000, 50, 16 }, { 3001, 50, 8 } };
	for (size_t k = 0; k < sizeof big / sizeof *big; k++)
		for (int filter = 4; filter <= 6; filter++) {
			struct spec s = plain(big[k][0], big[k][1], big[k][2]);
			s.filter = filter, s.split = filter == 6 ? 8192 : 0;
			fill(samples, s.w * s.h, s.bits, &r);
			bad += !decodes_right(&s, samples);
			cases++;
		}
	CHECK_INT(cases, 2 * 6 * 3 * 7 * 3 + 4 * 3);
	CHECK_INT(bad, 0);
	free(samples);
}

/* The decoder declines s, and fct_image_read answers as libpng alone: the
 * same samples or an error (one line, naming the input). */
static void check_declined(const char *what, const struct spec *s, size_t max_pixels)
{
	struct fct_rng r;
	fct_rng_seed(&r, 5);
	uint16_t samples[64 * 6];
	fill(samples, s->w * s->h, s->bits, &r);
	struct buf png = encode(s, samples);
	struct fct_image fast, ref, via;
	struct fct_err err;
	int took = fct_png_gray_decode(&fast, png.b, png.n, max_pixels);
	CHECK_MSG(took == 0, "%s: declined", what);
	if (took)
		free(fast.data);
	int ref_rc = png_ref_decode(&ref, png.b, png.n), via_rc = read_mem(&via, &png, &err);
	CHECK_MSG(ref_rc == via_rc, "%s: libpng %d, fct_image_read %d", what, ref_rc, via_rc);
	if (!ref_rc && !via_rc)
		CHECK_MSG(via.width == ref.width && via.height == ref.height && via.type == ref.type &&
		          !memcmp(via.data, ref.data, (size_t)ref.width * (size_t)ref.height *
		                  (ref.type == FCT_PIX_U16 ? 2 : 1)), "%s: libpng's samples", what);
	if (via_rc)
		CHECK_MSG(!strncmp(err.msg, "mem: ", 5) && !strchr(err.msg, '\n'), "%s: %s", what, err.msg);
	if (!ref_rc)
		free(ref.data);
	if (!via_rc)
		free(via.data);
	free(png.b);
}

static void test_declined(void)
{
	static const struct {
		const char *what;
		struct spec s;
		size_t max_pixels;
	} cases[] = {
		{ "filter type 5", { .w = 17, .h = 6, .bits = 16, .filter = 5, .bad_filter_row = 4 }, 1 << 20 },
		{ "a row short", { .w = 17, .h = 6, .bits = 16, .filter = 5, .rows = 5 }, 1 << 20 },
		{ "a row too many", { .w = 17, .h = 6, .bits = 16, .filter = 5, .rows = 7 }, 1 << 20 },
		{ "Adler-32", { .w = 17, .h = 6, .bits = 8, .filter = 5, .flip_adler = 1 }, 1 << 20 },
		{ "IDAT CRC", { .w = 17, .h = 6, .bits = 16, .filter = 5, .split = 7, .flip_idat_crc = 1 },
		  1 << 20 },
		{ "a second zlib stream", { .w = 17, .h = 6, .bits = 16, .filter = 5, .second_stream = 1 },
		  1 << 20 },
		{ "a tEXt chunk", { .w = 17, .h = 6, .bits = 16, .filter = 5, .text = 1 }, 1 << 20 },
		{ "bytes after IEND", { .w = 17, .h = 6, .bits = 16, .filter = 5, .trailing = 3 }, 1 << 20 },
		{ "a 512-byte window", { .w = 64, .h = 6, .bits = 16, .filter = 5, .window_bits = 9 }, 1 << 20 },
		{ "interlaced", { .w = 17, .h = 6, .bits = 16, .filter = 5, .interlace = 1 }, 1 << 20 },
		{ "grey and alpha", { .w = 17, .h = 6, .bits = 8, .filter = 5, .ctype = 4 }, 1 << 20 },
		{ "more pixels than allowed", { .w = 17, .h = 6, .bits = 16, .filter = 5 }, 17 * 6 - 1 },
	};
	for (size_t k = 0; k < sizeof cases / sizeof *cases; k++)
		check_declined(cases[k].what, &cases[k].s, cases[k].max_pixels);

	/* and the same file taken within the limit */
	struct fct_rng r;
	fct_rng_seed(&r, 5);
	uint16_t samples[17 * 6];
	fill(samples, 17 * 6, 16, &r);
	struct spec s = plain(17, 6, 16);
	struct buf png = encode(&s, samples);
	struct fct_image fast;
	CHECK_INT(fct_png_gray_decode(&fast, png.b, png.n, 17 * 6), 1);
	CHECK(same_samples(&fast, samples, 17, 6, 16));
	free(fast.data);
	free(png.b);
}

int main(void)
{
	test_encoded_decode();
	test_declined();
	CHECK_DONE();
}
