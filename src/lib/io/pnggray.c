/* pnggray.c - the plain grey PNG decoded over zlib alone (see pnggray.h). */
#include "io/pnggray.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* About what one zlib call inflates (see fct_png_gray_decode). */
enum { ROW_BLOCK_BYTES = 64 << 10 };

static uint32_t be32(const unsigned char *b)
{
	return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* The chunk at pos of buf[0..len) if it is whole, of type `type`, no
 * longer than PNG's 2^31 - 1 bytes and its CRC right: its data length, else
 * -1. */
static long chunk_of(const unsigned char *buf, size_t len, size_t pos, const char *type)
{
	if (len - pos < 12 || memcmp(buf + pos + 4, type, 4))
		return -1;
	uint32_t n = be32(buf + pos);
	if (n > 0x7fffffffu || n > len - pos - 12)
		return -1;
	uLong crc = crc32(0, buf + pos + 4, (uInt)n + 4);
	return crc == be32(buf + pos + 8 + n) ? (long)n : -1;
}

/* The PNG predictor of a from the left, b above, c above left. */
static inline int paeth(int a, int b, int c)
{
	int pa = abs(b - c), pb = abs(a - c), pc = abs(a + b - 2 * c);
	int bc = pb <= pc ? b : c;
	return ((pa <= pb) & (pa <= pc)) ? a : bc;
}

/* The filters undone straight into the image: each row's predictions come
 * from the row above as the image holds it (zeros above the first), and a
 * pixel's left neighbour stays in registers (libpng reads each byte back
 * from the row it has just written, a store and a load in the chain from
 * pixel to pixel).  in is the row's filtered bytes, after its filter byte;
 * 0, or -1 for a filter type PNG does not have. */
static int unfilter8(unsigned char *out, const unsigned char *up, const unsigned char *in,
                     size_t w, int filter)
{
	int a = 0, c = 0;
	switch (filter) {
	case 0:
		memcpy(out, in, w);
		return 0;
	case 1:
		for (size_t i = 0; i < w; i++)
			out[i] = (unsigned char)(a = (in[i] + a) & 255);
		return 0;
	case 2:
		for (size_t i = 0; i < w; i++)
			out[i] = (unsigned char)(in[i] + up[i]);
		return 0;
	case 3:
		for (size_t i = 0; i < w; i++)
			out[i] = (unsigned char)(a = (in[i] + ((a + up[i]) >> 1)) & 255);
		return 0;
	case 4:
		for (size_t i = 0; i < w; i++) {
			int b = up[i];
			out[i] = (unsigned char)(a = (in[i] + paeth(a, b, c)) & 255);
			c = b;
		}
		return 0;
	default:
		return -1;
	}
}

/* The same for 16-bit samples (stored most significant byte first, the
 * filters working byte by byte), out and up in the host's byte order: a
 * pixel's high and low bytes are two lanes, h and l. */
static int unfilter16(uint16_t *out, const uint16_t *up, const unsigned char *in, size_t w,
                      int filter)
{
	int ah = 0, al = 0, ch = 0, cl = 0;
	switch (filter) {
	case 0:
		for (size_t i = 0; i < w; i++)
			out[i] = (uint16_t)(in[2 * i] << 8 | in[2 * i + 1]);
		return 0;
	case 1:
		for (size_t i = 0; i < w; i++) {
			ah = (in[2 * i] + ah) & 255, al = (in[2 * i + 1] + al) & 255;
			out[i] = (uint16_t)(ah << 8 | al);
		}
		return 0;
	case 2:
		for (size_t i = 0; i < w; i++)
			out[i] = (uint16_t)(((in[2 * i] + (up[i] >> 8)) & 255) << 8 |
			                    ((in[2 * i + 1] + up[i]) & 255));
		return 0;
	case 3:
		for (size_t i = 0; i < w; i++) {
			ah = (in[2 * i] + ((ah + (up[i] >> 8)) >> 1)) & 255;
			al = (in[2 * i + 1] + ((al + (up[i] & 255)) >> 1)) & 255;
			out[i] = (uint16_t)(ah << 8 | al);
		}
		return 0;
	case 4:
		for (size_t i = 0; i < w; i++) {
			int bh = up[i] >> 8, bl = up[i] & 255;
			ah = (in[2 * i] + paeth(ah, bh, ch)) & 255;
			al = (in[2 * i + 1] + paeth(al, bl, cl)) & 255;
			out[i] = (uint16_t)(ah << 8 | al);
			ch = bh, cl = bl;
		}
		return 0;
	default:
		return -1;
	}
}

/* Inflate the next `want` bytes of the IDAT chunks from *pos on into out:
 * 0, or -1 if the stream fails or ends first.  With out NULL (want 0) the
 * stream must end here, with no data after it in its chunk. */
static int inflate_into(z_stream *z, const unsigned char *buf, size_t len, size_t *pos,
                        unsigned char *out, size_t want)
{
	unsigned char spare;   /* where a byte past the end would go */
	z->next_out = out ? out : &spare;
	z->avail_out = out ? (uInt)want : 1;
	for (;;) {
		int rc = inflate(z, Z_NO_FLUSH);
		if (out && z->avail_out == 0)
			return 0;
		if (rc == Z_STREAM_END)
			return !out && z->avail_out == 1 && z->avail_in == 0 ? 0 : -1;
		if ((rc != Z_OK && rc != Z_BUF_ERROR) || z->avail_out == 0 || z->avail_in != 0)
			return -1;
		/* the chunk used up: the next must be IDAT */
		long n = chunk_of(buf, len, *pos, "IDAT");
		if (n < 0)
			return -1;
		z->next_in = (unsigned char *)buf + *pos + 8, z->avail_in = (uInt)n;
		*pos += (size_t)n + 12;
	}
}

int fct_png_gray_decode(struct fct_image *img, const unsigned char *buf, size_t len,
                        size_t max_pixels)
{
	static const unsigned char magic[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
	if (len < 8 || memcmp(buf, magic, 8) || chunk_of(buf, len, 8, "IHDR") != 13)
		return 0;
	const unsigned char *h = buf + 16;
	uint32_t w = be32(h), ht = be32(h + 4);
	int bits = h[8];
	/* grey, deflate, adaptive filters, not interlaced */
	if (w == 0 || ht == 0 || w > FCT_IMAGE_MAX_SIDE || ht > FCT_IMAGE_MAX_SIDE ||
	    (uint64_t)w * ht > max_pixels || (bits != 8 && bits != 16) || h[9] || h[10] || h[11] ||
	    h[12])
		return 0;
	size_t bpp = (size_t)bits / 8, rowbytes = (size_t)w * bpp;
	if ((uint64_t)(rowbytes + 1) * ht > (uint64_t)len * FCT_DEFLATE_MAX_RATIO)
		return 0;
	/* IDAT right after IHDR, its zlib stream's window 32 KB (CINFO 7):
	 * libpng inflates with the window a header declares, and whether a
	 * distance past a smaller one fails can depend on how the output is
	 * cut into calls, so such streams are left to libpng. */
	size_t pos = 33;
	if (chunk_of(buf, len, pos, "IDAT") < 1 || buf[pos + 8] != 0x78)
		return 0;
	/* Inflated a block of rows at a time: zlib's fast loop stops 258
	 * bytes short of the end of its output, and each call copies what it
	 * wrote into its window; one row a call (1281 bytes at 640x480) spent
	 * a fifth of the rows in the slow loop. */
	size_t inbytes = rowbytes + 1, block = ROW_BLOCK_BYTES / inbytes + 1;
	unsigned char *data = malloc(rowbytes * ht);
	unsigned char *in = fct_alloc_array(block, inbytes, NULL), *zeros = calloc(1, rowbytes);
	z_stream z;
	memset(&z, 0, sizeof z);
	int ok = data && in && zeros && inflateInit(&z) == Z_OK;
	for (uint32_t y = 0; ok && y < ht; y++) {
		size_t k = y % block;
		if (k == 0)
			ok = !inflate_into(&z, buf, len, &pos, in,
			                   inbytes * (ht - y < block ? ht - y : block));
		unsigned char *out = data + (size_t)y * rowbytes, *up = y ? out - rowbytes : zeros;
		const unsigned char *row = in + k * inbytes;
		ok = ok && !(bits == 8 ? unfilter8(out, up, row + 1, w, row[0])
		                       : unfilter16((uint16_t *)(void *)out, (const uint16_t *)(void *)up,
		                                    row + 1, w, row[0]));
	}
	ok = ok && !inflate_into(&z, buf, len, &pos, NULL, 0) && chunk_of(buf, len, pos, "IEND") == 0 &&
	     pos + 12 == len;
	inflateEnd(&z);
	free(in);
	free(zeros);
	if (!ok) {
		free(data);
		return 0;
	}
	img->width = (int)w, img->height = (int)ht, img->channels = 1;
	img->type = bits == 16 ? FCT_PIX_U16 : FCT_PIX_U8;
	img->data = data;
	return 1;
}
