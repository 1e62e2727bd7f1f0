/* pngref.h - a PNG in memory decoded by libpng alone, as image.c's libpng
 * path does it (16-bit samples swapped to the host's order, interlacing
 * handled): the reference fct_png_gray_decode (io/pnggray.h) must equal.
 * Shared by test_pnggray and fuzz_pnggray. */
#ifndef FCT_PNGREF_H
#define FCT_PNGREF_H

#include <png.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"

struct png_ref_src {
	const unsigned char *buf;
	size_t len, pos;
};

static void png_ref_read(png_structp png, png_bytep out, size_t n)
{
	struct png_ref_src *s = png_get_io_ptr(png);
	if (n > s->len - s->pos)
		png_error(png, "unexpected end of file");
	memcpy(out, s->buf + s->pos, n);
	s->pos += n;
}

static void png_ref_error(png_structp png, png_const_charp msg)
{
	(void)msg;
	png_longjmp(png, 1);
}

static void png_ref_warning(png_structp png, png_const_charp msg)
{
	(void)png, (void)msg;
}

/* buf[0..len) decoded by libpng into img (8- or 16-bit samples, data from
 * malloc): 0, or -1 where libpng fails or the image is not grey. */
static int png_ref_decode(struct fct_image *img, const unsigned char *buf, size_t len)
{
	struct png_ref_src src = { buf, len, 0 };
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, png_ref_error,
	                                         png_ref_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	unsigned char *volatile data = NULL;
	png_bytep *volatile rows = NULL;
	if (!info || setjmp(png_jmpbuf(png))) {
		free(rows);
		free(data);
		png_destroy_read_struct(&png, &info, NULL);
		return -1;
	}
	png_set_read_fn(png, &src, png_ref_read);
	png_set_user_limits(png, FCT_IMAGE_MAX_SIDE, FCT_IMAGE_MAX_SIDE);
	png_read_info(png, info);
	png_uint_32 w, h;
	int bits, ctype, interlace;
	png_get_IHDR(png, info, &w, &h, &bits, &ctype, &interlace, NULL, NULL);
	const uint16_t one = 1;
	if (bits == 16 && *(const unsigned char *)&one == 1)
		png_set_swap(png);
	png_set_interlace_handling(png);
	png_read_update_info(png, info);
	size_t rowbytes = png_get_rowbytes(png, info);
	if (ctype != PNG_COLOR_TYPE_GRAY || png_get_channels(png, info) != 1 || (bits != 8 && bits != 16) ||
	    (uint64_t)rowbytes * h > (uint64_t)64 << 20)
		png_error(png, "not 8- or 16-bit grey, or too big");
	data = malloc(rowbytes * h);
	rows = malloc(h * sizeof *rows);
	if (!data || !rows)
		png_error(png, "out of memory");
	for (png_uint_32 y = 0; y < h; y++)
		rows[y] = data + (size_t)y * rowbytes;
	png_read_image(png, rows);
	png_read_end(png, NULL);
	png_destroy_read_struct(&png, &info, NULL);
	free(rows);
	img->width = (int)w, img->height = (int)h, img->channels = 1;
	img->type = bits == 16 ? FCT_PIX_U16 : FCT_PIX_U8;
	img->data = data;
	return 0;
}

#endif
