/* pnggray.h - the plain grey PNG of a depth camera decoded over zlib alone.
 *
 * A 640x480 16-bit depth frame took dm2mesh about 3 ms to read through
 * libpng, 1 ms of it in libpng's Paeth unfiltering of 2-byte pixels, which
 * reads each byte's left neighbour back from memory (bench/NOTES.md).  The
 * files depth cameras write are the simplest PNGs there are: IHDR, IDAT
 * chunks, IEND.  This decoder takes those and nothing else; whatever it
 * does not take (another chunk, colour, interlacing, a bad CRC, a zlib
 * stream with a small window or that fails or does not end with the last
 * row) is left to libpng, which gives the same samples or the error.  So
 * for any file this returns 1 on, libpng would give the same bytes. */
#ifndef FCT_PNGGRAY_H
#define FCT_PNGGRAY_H

#include <stddef.h>

#include "io/image.h"

/* Deflate cannot compress better than 1032:1 (a 258-byte match costs at
 * least 2 bits), so a PNG whose filtered rows need more bytes than its whole
 * file times this is lying about its size. */
#define FCT_DEFLATE_MAX_RATIO 1032

/* Decode the PNG file buf[0..len) into img (one channel, FCT_PIX_U8 or
 * FCT_PIX_U16 in the host's byte order, data from malloc) if it is an 8-
 * or 16-bit grey, non-interlaced PNG made of IHDR, IDAT and IEND alone,
 * with every CRC right and one zlib stream (32 KB window) that inflates to
 * exactly its filtered rows, of at most max_pixels pixels: 1.  Else 0 and
 * img untouched (out of memory included): the caller decodes with libpng. */
int fct_png_gray_decode(struct fct_image *img, const unsigned char *buf, size_t len,
                        size_t max_pixels);

#endif
