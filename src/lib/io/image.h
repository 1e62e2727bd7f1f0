/* image.h - raster images: PNG (through libpng; a plain 8- or 16-bit grey
 * one is read over zlib alone, pnggray.h) and PFM, read and written;
 * JPEG (through libjpeg-turbo) and netpbm's PGM and PPM read.
 *
 * An image is a flat array of samples: row-major, top row first, channels
 * interleaved, in the host's byte order, whatever order the file used.
 * Integer samples keep their stored values (a 16-bit depth PNG stays in its
 * units); only sub-8-bit grey is widened, to 8 bits with libpng's bit
 * replication (1-bit 1 -> 255).
 *
 * JPEG gives 8-bit samples: 1 channel for greyscale, else 3 (RGB), CMYK and
 * YCCK converted to RGB as Pillow does (Adobe's inverted inks recognised);
 * libjpeg's default, accurate integer IDCT and smooth chroma upsampling, so
 * the pixels equal those of Pillow or djpeg built on libjpeg-turbo.  The
 * Exif orientation is not applied (RGB-D frames are stored as seen).
 *
 * Reading detects the format from the first bytes, never from the name:
 * the PNG signature, FF D8 FF (JPEG), "PF"/"Pf" followed by whitespace
 * (PFM, colour/grey), or "P5", "P6", "P2", "P3" followed by whitespace
 * (PGM and PPM, binary and ASCII; 16-bit samples most significant byte
 * first, as the format says; kept as stored, not scaled by the maxval).  Nothing is allocated beyond what the input's real
 * size justifies: a PNG's pixel data may not exceed what its compressed
 * bytes can inflate to, a JPEG may not claim more than 512 pixels per byte
 * of file (one bit per 8x8 block, the least Huffman coding spends; checked
 * before libjpeg allocates), and a PFM's or binary PNM's header must match
 * the number of bytes that follow it exactly (an ASCII PNM's may not claim
 * more samples than half its bytes).  A JPEG that libjpeg warns about (truncated,
 * corrupt entropy data) is refused, not filled in with grey.
 *
 * Errors follow err.h: "FILE: byte N: what", with libpng's and libjpeg's
 * own messages prefixed "libpng: " and "libjpeg: ". */
#ifndef FCT_IMAGE_H
#define FCT_IMAGE_H

#include <stddef.h>
#include <stdio.h>

#include "core/err.h"

enum fct_pix { FCT_PIX_U8, FCT_PIX_U16, FCT_PIX_F32 };

enum fct_image_format { FCT_IMAGE_PNG, FCT_IMAGE_PFM, FCT_IMAGE_JPEG, FCT_IMAGE_PNM };

struct fct_image {
	int width, height;
	int channels;       /* 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA */
	enum fct_pix type;
	void *data;         /* width*height*channels samples of type */
};

/* Largest side and sample count accepted (PNG: libpng's user limits). */
#define FCT_IMAGE_MAX_SIDE (1 << 24)
#define FCT_IMAGE_MAX_PIXELS ((size_t)1 << 31)

/* Bytes in one sample of type: 1, 2 or 4. */
size_t fct_pix_size(enum fct_pix type);
/* "u8", "u16", "f32". */
const char *fct_pix_name(enum fct_pix type);
/* "png", "pfm", "jpeg", "pnm". */
const char *fct_image_format_name(enum fct_image_format fmt);
/* The format whose signature the first n bytes of a file start with (a
 * PNG's 8 bytes, or 3: PFM's "Pf"/"PF" and a blank, JPEG's SOI and a
 * marker, PNM's "P2", "P3", "P5" or "P6" and a blank), or -1. */
int fct_image_magic(const unsigned char *head, size_t n);

/* Number of samples (width*height*channels) of a valid image. */
size_t fct_image_samples(const struct fct_image *img);

/* Allocate img's data (zeroed) for the given shape; img is set up here.
 * Fails on a side < 1 or > FCT_IMAGE_MAX_SIDE, channels outside 1..4, more
 * than FCT_IMAGE_MAX_PIXELS pixels, or out of memory. */
int fct_image_alloc(struct fct_image *img, int width, int height, int channels,
                    enum fct_pix type, struct fct_err *err);
/* Free img's data and clear it; img may be NULL or already freed. */
void fct_image_free(struct fct_image *img);

/* Read from path ("-" or NULL: stdin, named "<stdin>"); img is set up here
 * and owned by the caller (fct_image_free) on success, left empty on
 * failure.  fmt (may be NULL) gets the format read. */
int fct_image_read_file(struct fct_image *img, const char *path,
                        enum fct_image_format *fmt, struct fct_err *err);
/* The same from an open stream called name (left open, read to its end). */
int fct_image_read_stream(struct fct_image *img, FILE *f, const char *name,
                          enum fct_image_format *fmt, struct fct_err *err);
/* fct_image_read_file refusing, from the header and before decoding, an
 * image of more than max_pixels pixels ("image size WxH: more than N pixels
 * allowed here"): a program's stated bound on what it will hold. */
int fct_image_read_file_max(struct fct_image *img, const char *path, size_t max_pixels,
                            enum fct_image_format *fmt, struct fct_err *err);
/* The shape (width, height, channels, type) fct_image_read_file would give,
 * from the header alone: img->data stays NULL and nothing is decoded (the
 * file is read whole and checked as far as its header).  For callers that
 * must bound what several images add up to before decoding any. */
int fct_image_probe_file(struct fct_image *img, const char *path,
                         enum fct_image_format *fmt, struct fct_err *err);

/* Write a U8 or U16 image with 1..4 channels as PNG (no gamma, no time:
 * the same image gives the same bytes).  Does not flush or close f. */
int fct_png_write(const struct fct_image *img, FILE *f, struct fct_err *err);
/* Write an F32 image with 1 ("Pf") or 3 ("PF") channels as little-endian
 * PFM, rows bottom to top as the format stores them. */
int fct_pfm_write(const struct fct_image *img, FILE *f, struct fct_err *err);

/* Sample i of the flat array (0 <= i < fct_image_samples), as a double:
 * integers keep their stored value, floats their value (NaN included). */
double fct_image_sample(const struct fct_image *img, size_t i);
/* Sample of channel c at column x, row y (row 0 at the top). */
double fct_image_get(const struct fct_image *img, int x, int y, int c);

#endif
