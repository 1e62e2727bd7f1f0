/* image.c - PNG, JPEG and PFM reading, PNG and PFM writing (see image.h).
 *
 * The readers take the whole input into memory first, growing the buffer
 * only as bytes really arrive, and then decode from memory.  That gives the
 * exact input size even on a pipe, which is what bounds every allocation:
 * a lying header can never make us allocate more than about twice the bytes
 * it came with (PFM), what they can inflate to (PNG) or what their entropy
 * code can stand for (JPEG). */
#include "io/image.h"
#include "io/pnggray.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <jpeglib.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/numparse.h"
#include "core/path.h"

/* A PNG whose filtered rows need more bytes than its whole file times
 * FCT_DEFLATE_MAX_RATIO (pnggray.h) is lying about its size.  Palette and
 * sub-8-bit expansion can still multiply the pixel array by up to 32, as a
 * real file would. */
enum { CHUNK_MALLOC_MIN = 8 << 20 };

static const unsigned char png_magic[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };

static int host_is_le(void)
{
	const uint16_t one = 1;
	unsigned char b;
	memcpy(&b, &one, 1);
	return b == 1;
}

size_t fct_pix_size(enum fct_pix type)
{
	switch (type) {
	case FCT_PIX_U8: return 1;
	case FCT_PIX_U16: return 2;
	case FCT_PIX_F32: return 4;
	}
	abort();
}

const char *fct_pix_name(enum fct_pix type)
{
	switch (type) {
	case FCT_PIX_U8: return "u8";
	case FCT_PIX_U16: return "u16";
	case FCT_PIX_F32: return "f32";
	}
	abort();
}

const char *fct_image_format_name(enum fct_image_format fmt)
{
	switch (fmt) {
	case FCT_IMAGE_PNG: return "png";
	case FCT_IMAGE_PFM: return "pfm";
	case FCT_IMAGE_JPEG: return "jpeg";
	case FCT_IMAGE_PNM: return "pnm";
	}
	abort();
}

size_t fct_image_samples(const struct fct_image *img)
{
	return (size_t)img->width * (size_t)img->height * (size_t)img->channels;
}

/* Bytes of an image of this shape, or -1 (with a message) when the shape is
 * out of range. */
static int image_bytes(long width, long height, int channels, enum fct_pix type,
                       size_t *bytes, struct fct_err *err)
{
	if (width < 1 || height < 1)
		return fct_fail(err, "image size %ldx%ld: width and height must be positive",
		                width, height);
	if (width > FCT_IMAGE_MAX_SIDE || height > FCT_IMAGE_MAX_SIDE)
		return fct_fail(err, "image size %ldx%ld: a side is over %d pixels",
		                width, height, FCT_IMAGE_MAX_SIDE);
	if (channels < 1 || channels > 4)
		return fct_fail(err, "%d channels: must be 1 to 4", channels);
	size_t pixels = (size_t)width * (size_t)height;  /* < 2^48: no overflow */
	if (pixels > FCT_IMAGE_MAX_PIXELS)
		return fct_fail(err, "image size %ldx%ld: more than 2^31 pixels", width, height);
	if (fct_mul_size(pixels, (size_t)channels * fct_pix_size(type), bytes))
		return fct_fail(err, "image size %ldx%ld: too large for memory", width, height);
	return 0;
}

/* A decoder's check of a header's size against the caller's limit
 * (max_pixels, at most FCT_IMAGE_MAX_PIXELS) before it allocates: 0, or -1
 * with "image size WxH: ...". */
static int check_pixels(uint64_t width, uint64_t height, size_t max_pixels, struct fct_err *err)
{
	uint64_t n = width * height;   /* sides are below 2^32 */
	if (n > FCT_IMAGE_MAX_PIXELS)
		return fct_fail(err, "image size %llux%llu: more than 2^31 pixels",
		                (unsigned long long)width, (unsigned long long)height);
	if (n > max_pixels)
		return fct_fail(err, "image size %llux%llu: more than the %zu pixels allowed here",
		                (unsigned long long)width, (unsigned long long)height, max_pixels);
	return 0;
}

int fct_image_alloc(struct fct_image *img, int width, int height, int channels,
                    enum fct_pix type, struct fct_err *err)
{
	memset(img, 0, sizeof *img);
	size_t bytes;
	if (image_bytes(width, height, channels, type, &bytes, err))
		return -1;
	if (!(img->data = calloc(bytes, 1)))
		return fct_fail(err, "out of memory (%zu bytes for a %dx%d image)", bytes, width, height);
	img->width = width;
	img->height = height;
	img->channels = channels;
	img->type = type;
	return 0;
}

void fct_image_free(struct fct_image *img)
{
	if (!img)
		return;
	free(img->data);
	memset(img, 0, sizeof *img);
}

double fct_image_sample(const struct fct_image *img, size_t i)
{
	switch (img->type) {
	case FCT_PIX_U8: return ((const uint8_t *)img->data)[i];
	case FCT_PIX_U16: return ((const uint16_t *)img->data)[i];
	case FCT_PIX_F32: return ((const float *)img->data)[i];
	}
	abort();
}

double fct_image_get(const struct fct_image *img, int x, int y, int c)
{
	size_t i = ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels + (size_t)c;
	return fct_image_sample(img, i);
}

/* ---- input ---------------------------------------------------------- */

/* head[0..n) (bytes already read) and the rest of f into *buf (malloc'd)
 * and *len.  A regular file's size sets the first allocation; otherwise the
 * buffer doubles as data arrives, so it never exceeds twice what was read. */
static int slurp(FILE *f, const char *name, const unsigned char *head, size_t n,
                 unsigned char **buf, size_t *len, struct fct_err *err)
{
	size_t cap = (1 << 16) + n;
	struct stat st;
	int fd = fileno(f);
	if (fd >= 0 && fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= 0) {
		long at = ftell(f);
		uint64_t rest = (uint64_t)st.st_size - (uint64_t)(at > 0 ? at : 0);
		/* One spare byte, so that reaching the end needs no growth. */
		if (rest < SIZE_MAX - 1 - n)
			cap = (size_t)rest + n + 1;
	}
	unsigned char *b = malloc(cap);
	if (!b)
		return fct_fail(err, "%s: out of memory (%zu bytes)", name, cap);
	memcpy(b, head, n);
	for (;;) {
		if (n == cap) {
			void *p = b;
			if (fct_grow(&p, &cap, n + 1, 1, err)) {
				free(b);
				fct_err_prefix(err, "%s: byte %zu", name, n);
				return -1;
			}
			b = p;
		}
		size_t got = fread(b + n, 1, cap - n, f);
		n += got;
		if (got == 0) {
			if (ferror(f)) {
				int e = errno;
				free(b);
				return fct_fail(err, "%s: byte %zu: %s", name, n,
				                e ? strerror(e) : "read error");
			}
			break;
		}
	}
	*buf = b;
	*len = n;
	return 0;
}

/* ---- PFM ------------------------------------------------------------- */

static int is_space(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* The next whitespace-separated token of a fmt ("PFM" or "PNM") header at
 * *pos, copied NUL-terminated into tok (of size cap); *at gets its offset.
 * With comments, a '#' at a token's start runs to the end of its line
 * (netpbm's comments).  Fails at the end of input or on a token too long
 * to be a number. */
static int header_token(const unsigned char *b, size_t len, size_t *pos, char *tok, size_t cap,
                        size_t *at, const char *name, const char *fmt, int comments,
                        const char *what, struct fct_err *err)
{
	size_t p = *pos;
	for (;;) {
		while (p < len && is_space(b[p]))
			p++;
		if (!(comments && p < len && b[p] == '#'))
			break;
		while (p < len && b[p] != '\n' && b[p] != '\r')
			p++;
	}
	*at = p;
	if (p == len)
		return fct_fail(err, "%s: byte %zu: %s header: unexpected end of file before the %s",
		                name, p, fmt, what);
	size_t n = 0;
	while (p < len && !is_space(b[p])) {
		if (n + 1 == cap)
			return fct_fail(err, "%s: byte %zu: %s header: the %s is not a number",
			                name, *at, fmt, what);
		tok[n++] = (char)b[p++];
	}
	tok[n] = 0;
	*pos = p;
	return 0;
}

/* The decimal digits at the start of tok as *v, read until they run out or
 * *v passes most (which stops it from overflowing); what follows them. */
static const char *leading_decimal(const char *tok, long most, long *v)
{
	*v = 0;
	for (; *tok >= '0' && *tok <= '9' && *v <= most; tok++)
		*v = *v * 10 + (*tok - '0');
	return tok;
}

/* A plain decimal integer of a fmt header in [1, most]. */
static int header_count(const char *tok, size_t at, const char *name, const char *fmt,
                        const char *what, long most, long *out, struct fct_err *err)
{
	long v;
	const char *s = leading_decimal(tok, most, &v);
	if (v > most)
		return fct_fail(err, "%s: byte %zu: %s header: %s %s is over %ld",
		                name, at, fmt, what, tok, most);
	if (*s || s == tok)
		return fct_fail(err, "%s: byte %zu: %s header: %s \"%s\" is not a positive integer",
		                name, at, fmt, what, tok);
	if (v == 0)
		return fct_fail(err, "%s: byte %zu: %s header: %s is 0", name, at, fmt, what);
	*out = v;
	return 0;
}

static void swap4(unsigned char *p, size_t n)
{
	for (size_t i = 0; i + 4 <= n; i += 4) {
		unsigned char t = p[i];
		p[i] = p[i + 3];
		p[i + 3] = t;
		t = p[i + 1];
		p[i + 1] = p[i + 2];
		p[i + 2] = t;
	}
}

/* Decode the PFM in buf (taking ownership of buf, which becomes the pixel
 * array): "PF" or "Pf", width, height, scale, one whitespace byte (CR LF
 * accepted), then exactly width*height*channels floats, bottom row first.
 * With header_only, img gets the shape and no data (buf is freed). */
static int pfm_decode(struct fct_image *img, unsigned char *buf, size_t len, const char *name,
                      size_t max_pixels, int header_only, struct fct_err *err)
{
	int channels = buf[1] == 'F' ? 3 : 1;
	size_t pos = 2, at, wat;
	char tok[64];
	long w, h;
	double scale;
	if (header_token(buf, len, &pos, tok, sizeof tok, &wat, name, "PFM", 0, "width", err) ||
	    header_count(tok, wat, name, "PFM", "width", FCT_IMAGE_MAX_SIDE, &w, err) ||
	    header_token(buf, len, &pos, tok, sizeof tok, &at, name, "PFM", 0, "height", err) ||
	    header_count(tok, at, name, "PFM", "height", FCT_IMAGE_MAX_SIDE, &h, err) ||
	    header_token(buf, len, &pos, tok, sizeof tok, &at, name, "PFM", 0, "scale", err))
		goto fail;
	{
		const char *end = fct_parse_double(tok, &scale);
		if (!end || *end || !isfinite(scale) || scale == 0) {
			fct_fail(err, "%s: byte %zu: PFM header: scale \"%s\" is not a nonzero number",
			         name, at, tok);
			goto fail;
		}
	}
	size_t need;
	if (image_bytes(w, h, channels, FCT_PIX_F32, &need, err) ||
	    check_pixels((uint64_t)w, (uint64_t)h, max_pixels, err)) {
		fct_err_prefix(err, "%s: byte %zu: PFM header", name, wat);
		goto fail;
	}
	if (pos == len) {
		fct_fail(err, "%s: byte %zu: PFM header: unexpected end of file after the scale",
		         name, pos);
		goto fail;
	}
	/* The header ends with one whitespace byte; a CR LF pair counts as one
	 * when the size says the LF is not the first data byte. */
	size_t data = pos + 1;
	if (buf[pos] == '\r' && data < len && buf[data] == '\n' && len - data != need)
		data++;
	if (len - data != need) {
		fct_fail(err, "%s: byte %zu: PFM header says %ldx%ld with %d channel%s (%zu bytes) "
		         "but %zu bytes follow", name, data, w, h, channels,
		         channels > 1 ? "s" : "", need, len - data);
		goto fail;
	}
	img->width = (int)w;
	img->height = (int)h;
	img->channels = channels;
	img->type = FCT_PIX_F32;
	if (header_only) {
		free(buf);
		return 0;
	}
	memmove(buf, buf + data, need);
	unsigned char *shrunk = realloc(buf, need);
	if (shrunk)
		buf = shrunk;
	/* Rows are stored bottom to top: turn them over in place. */
	size_t row = (size_t)w * (size_t)channels * 4;
	for (long y = 0; y < h / 2; y++) {
		unsigned char *a = buf + (size_t)y * row, *b = buf + (size_t)(h - 1 - y) * row;
		for (size_t i = 0; i < row; i++) {
			unsigned char t = a[i];
			a[i] = b[i];
			b[i] = t;
		}
	}
	if ((scale < 0) != host_is_le())
		swap4(buf, need);
	img->data = buf;
	return 0;
fail:
	free(buf);
	memset(img, 0, sizeof *img);
	return -1;
}

/* ---- PNM (netpbm) ----------------------------------------------------- */

/* Decode the PGM or PPM in buf (freed here): "P5"/"P6" (binary) or
 * "P2"/"P3" (ASCII) for grey/RGB, width, height and maxval (1 to 65535)
 * with '#' comments between them, then the samples: after one whitespace
 * byte exactly width*height*channels of them in binary, one byte each when
 * maxval is below 256, else two, most significant first (the format's
 * order); in ASCII decimal numbers apart, nothing but whitespace after.
 * Samples keep their values (not rescaled to the type's range) and may not
 * exceed maxval.  With header_only, img gets the shape and no data. */
static int pnm_decode(struct fct_image *img, unsigned char *buf, size_t len, const char *name,
                      size_t max_pixels, int header_only, struct fct_err *err)
{
	int ascii = buf[1] == '2' || buf[1] == '3';
	int channels = buf[1] == '3' || buf[1] == '6' ? 3 : 1;
	size_t pos = 2, at, wat;
	char tok[64];
	long w, h, maxval;
	unsigned char *data = NULL;
	if (header_token(buf, len, &pos, tok, sizeof tok, &wat, name, "PNM", 1, "width", err) ||
	    header_count(tok, wat, name, "PNM", "width", FCT_IMAGE_MAX_SIDE, &w, err) ||
	    header_token(buf, len, &pos, tok, sizeof tok, &at, name, "PNM", 1, "height", err) ||
	    header_count(tok, at, name, "PNM", "height", FCT_IMAGE_MAX_SIDE, &h, err) ||
	    header_token(buf, len, &pos, tok, sizeof tok, &at, name, "PNM", 1, "maxval", err) ||
	    header_count(tok, at, name, "PNM", "maxval", 65535, &maxval, err))
		goto fail;
	enum fct_pix type = maxval < 256 ? FCT_PIX_U8 : FCT_PIX_U16;
	size_t need, n = (size_t)w * (size_t)h * (size_t)channels;
	if (image_bytes(w, h, channels, type, &need, err) ||
	    check_pixels((uint64_t)w, (uint64_t)h, max_pixels, err)) {
		fct_err_prefix(err, "%s: byte %zu: PNM header", name, wat);
		goto fail;
	}
	if (pos == len) {
		fct_fail(err, "%s: byte %zu: PNM header: unexpected end of file after the maxval",
		         name, pos);
		goto fail;
	}
	size_t first = pos + 1;
	/* A blank and a digit at least per ASCII sample: more samples than
	 * that cannot be there. */
	if (ascii ? n > (len - pos) / 2 : len - first != need) {
		fct_fail(err, "%s: byte %zu: PNM header says %ldx%ld with %d channel%s (%zu %s) "
		         "but %zu bytes follow", name, first, w, h, channels, channels > 1 ? "s" : "",
		         ascii ? n : need, ascii ? "samples" : "bytes", len - first);
		goto fail;
	}
	img->width = (int)w;
	img->height = (int)h;
	img->channels = channels;
	img->type = type;
	if (header_only) {
		free(buf);
		return 0;
	}
	if (!(data = malloc(need))) {
		fct_fail(err, "%s: out of memory (%zu bytes for a %ldx%ld image)", name, need, w, h);
		goto fail;
	}
	for (size_t i = 0; i < n; i++) {
		long v;
		if (ascii) {
			if (header_token(buf, len, &pos, tok, sizeof tok, &at, name, "PNM", 0, "sample", err))
				goto fail;
			if (*leading_decimal(tok, maxval, &v) && v <= maxval) {
				fct_fail(err, "%s: byte %zu: PNM sample %zu \"%s\" is not a number",
				         name, at, i, tok);
				goto fail;
			}
		} else {
			at = first + i * fct_pix_size(type);
			v = type == FCT_PIX_U8 ? buf[at] : (long)buf[at] << 8 | buf[at + 1];
		}
		if (v > maxval) {
			fct_fail(err, "%s: byte %zu: PNM sample %zu is over the maxval %ld", name, at, i, maxval);
			goto fail;
		}
		if (type == FCT_PIX_U8)
			data[i] = (unsigned char)v;
		else
			((uint16_t *)(void *)data)[i] = (uint16_t)v;
	}
	if (ascii) {
		while (pos < len && is_space(buf[pos]))
			pos++;
		if (pos < len) {
			fct_fail(err, "%s: byte %zu: PNM: more than the %zu samples of its header",
			         name, pos, n);
			goto fail;
		}
	}
	free(buf);
	img->data = data;
	return 0;
fail:
	free(data);
	free(buf);
	memset(img, 0, sizeof *img);
	return -1;
}

/* ---- PNG ------------------------------------------------------------- */

/* What the libpng callbacks share with the code that called libpng.  It
 * lives in the caller's frame, not in the frame that calls setjmp, so its
 * changes survive the longjmp. */
struct png_state {
	const unsigned char *buf;   /* reading: the whole file */
	size_t len, pos;
	size_t at;                  /* offset the error is reported at */
	int own;                    /* msg is ours, not libpng's */
	char msg[512];
	char warn[256];             /* last warning since the last read */
};

static void png_on_error(png_structp png, png_const_charp msg)
{
	struct png_state *s = png_get_error_ptr(png);
	if (!s->own) {
		s->at = s->pos;
		/* libpng explains "Invalid IHDR data" in warnings just before. */
		if (s->warn[0] && strcmp(s->warn, msg))
			snprintf(s->msg, sizeof s->msg, "libpng: %s (%s)", msg, s->warn);
		else
			snprintf(s->msg, sizeof s->msg, "libpng: %s", msg);
	}
	png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
	struct png_state *s = png_get_error_ptr(png);
	snprintf(s->warn, sizeof s->warn, "%s", msg);
}

/* Fail from inside libpng's protected region with our own message. */
static void png_fail(png_structp png, struct png_state *s, size_t at, const char *fmt, ...)
	__attribute__((format(printf, 4, 5), noreturn));
static void png_fail(png_structp png, struct png_state *s, size_t at, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(s->msg, sizeof s->msg, fmt, ap);
	va_end(ap);
	s->own = 1;
	s->at = at;
	png_error(png, s->msg);
}

static void png_read_mem(png_structp png, png_bytep out, size_t n)
{
	struct png_state *s = png_get_io_ptr(png);
	s->warn[0] = 0;
	if (n > s->len - s->pos)
		png_fail(png, s, s->len, "unexpected end of file");
	memcpy(out, s->buf + s->pos, n);
	s->pos += n;
}

/* Walk the chunk headers and refuse a chunk whose declared length runs past
 * the end of the file: libpng allocates a chunk's declared length before it
 * reads it (sPLT, unknown chunks), so 30 bytes could ask for 2 GB. */
static int png_check_chunks(const unsigned char *b, size_t len, const char *name,
                            struct fct_err *err)
{
	size_t pos = 8;
	while (len - pos >= 8) {
		uint32_t n = (uint32_t)b[pos] << 24 | (uint32_t)b[pos + 1] << 16 |
		             (uint32_t)b[pos + 2] << 8 | b[pos + 3];
		const unsigned char *t = b + pos + 4;
		int named = 1;
		for (int i = 0; i < 4; i++)
			named &= (t[i] >= 'A' && t[i] <= 'Z') || (t[i] >= 'a' && t[i] <= 'z');
		if (n > len - pos - 8 || len - pos - 8 - n < 4)
			return fct_fail(err, "%s: byte %zu: chunk %.4s declares %lu bytes, "
			                "past the end of the file (%zu bytes)", name, pos,
			                named ? (const char *)t : "(bad name)", (unsigned long)n, len);
		if (!memcmp(t, "IEND", 4))
			break;
		pos += (size_t)n + 12;
	}
	return 0;
}

/* Decode the PNG in s->buf into img (whose data is set only on success;
 * with header_only, img gets the shape and no data). */
static int png_decode(struct fct_image *img, struct png_state *s, const char *name,
                      size_t max_pixels, int header_only, struct fct_err *err)
{
	if (png_check_chunks(s->buf, s->len, name, err))
		return -1;
	/* A depth camera's plain grey PNG without libpng's slower unfiltering;
	 * anything else, errors included, through libpng. */
	if (!header_only && fct_png_gray_decode(img, s->buf, s->len, max_pixels))
		return 0;
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, s, png_on_error,
	                                         png_on_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info) {
		png_destroy_read_struct(&png, NULL, NULL);
		return fct_fail(err, "%s: out of memory", name);
	}
	/* Changed after setjmp and needed after longjmp: volatile. */
	unsigned char *volatile data = NULL;
	png_bytep *volatile rows = NULL;
	if (setjmp(png_jmpbuf(png))) {
		free(rows);
		free(data);
		png_destroy_read_struct(&png, &info, NULL);
		return fct_fail(err, "%s: byte %zu: %s", name, s->at, s->msg);
	}
	png_set_read_fn(png, s, png_read_mem);
	png_set_user_limits(png, FCT_IMAGE_MAX_SIDE, FCT_IMAGE_MAX_SIDE);
	/* Caps what libpng inflates ancillary chunks (iCCP, zTXt) to; 8 MiB
	 * leaves room for a real colour profile in a small file. */
	png_set_chunk_malloc_max(png, s->len > CHUNK_MALLOC_MIN ? s->len : CHUNK_MALLOC_MIN);
	png_read_info(png, info);

	png_uint_32 w, h;
	int depth, ctype, interlace;
	png_get_IHDR(png, info, &w, &h, &depth, &ctype, &interlace, NULL, NULL);
	/* Width and height sit at byte 16, in IHDR. */
	struct fct_err big;
	if (check_pixels(w, h, max_pixels, &big))
		png_fail(png, s, 16, "%s", big.msg);
	/* The filtered rows, one filter byte each, that IDAT must inflate to. */
	uint64_t raw = ((uint64_t)w * png_get_channels(png, info) * (uint64_t)depth + 7) / 8 + 1;
	if (raw * h > (uint64_t)s->len * FCT_DEFLATE_MAX_RATIO)
		png_fail(png, s, 16, "image size %lux%lu needs %llu bytes of pixel data, "
		         "more than %zu bytes of PNG can hold", (unsigned long)w,
		         (unsigned long)h, (unsigned long long)(raw * h), s->len);

	if (ctype == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (ctype == PNG_COLOR_TYPE_GRAY && depth < 8)
		png_set_expand_gray_1_2_4_to_8(png);
	if (png_get_valid(png, info, PNG_INFO_tRNS))
		png_set_tRNS_to_alpha(png);
	if (depth == 16 && host_is_le())
		png_set_swap(png);
	png_set_interlace_handling(png);
	png_read_update_info(png, info);

	int channels = png_get_channels(png, info);
	int bits = png_get_bit_depth(png, info);
	size_t rowbytes = png_get_rowbytes(png, info);
	if ((bits != 8 && bits != 16) || channels < 1 || channels > 4 ||
	    rowbytes != (size_t)w * (size_t)channels * (size_t)(bits / 8))
		abort();  /* the transformations above guarantee this */
	if (header_only) {
		png_destroy_read_struct(&png, &info, NULL);
		img->width = (int)w;
		img->height = (int)h;
		img->channels = channels;
		img->type = bits == 16 ? FCT_PIX_U16 : FCT_PIX_U8;
		return 0;
	}
	data = malloc(rowbytes * h);
	rows = malloc(h * sizeof *rows);
	if (!data || !rows)
		png_fail(png, s, s->pos, "out of memory (%zu bytes)", rowbytes * h);
	for (png_uint_32 y = 0; y < h; y++)
		rows[y] = data + (size_t)y * rowbytes;
	png_read_image(png, rows);
	png_read_end(png, NULL);

	png_destroy_read_struct(&png, &info, NULL);
	free(rows);
	img->width = (int)w;
	img->height = (int)h;
	img->channels = channels;
	img->type = bits == 16 ? FCT_PIX_U16 : FCT_PIX_U8;
	img->data = data;
	return 0;
}

/* ---- JPEG ------------------------------------------------------------ */

/* Huffman coding spends at least one bit on each 8x8 block of a component
 * in a scan (progressive DC scans; sequential ones spend two, DC and EOB),
 * so a JPEG of N bytes stands for at most 512 N pixels at full resolution.
 * A header claiming more is lying, or arithmetic-coded with a compression
 * beyond what any photograph reaches; both are refused before libjpeg
 * allocates anything for the image (a progressive file's coefficients, the
 * output). */
enum { JPEG_MAX_PIXELS_PER_BYTE = 512 };

/* libjpeg's error manager with the jump back into jpeg_decode and the
 * message it carries there. */
struct jpeg_state {
	struct jpeg_error_mgr mgr;
	jmp_buf jump;
	char msg[JMSG_LENGTH_MAX + 16];
};

/* libjpeg's error_exit calls exit(); ours keeps the message and jumps back. */
static void jpeg_on_error(j_common_ptr cinfo)
{
	struct jpeg_state *s = (struct jpeg_state *)cinfo->err;
	char text[JMSG_LENGTH_MAX];
	cinfo->err->format_message(cinfo, text);
	snprintf(s->msg, sizeof s->msg, "libjpeg: %s", text);
	longjmp(s->jump, 1);
}

/* libjpeg warns of corrupt or truncated data and goes on with grey or
 * zero coefficients; a warning is an error here, as a bad CRC is for PNG
 * (turbojpeg's TJFLAG_STOPONWARNING).  Trace messages are dropped. */
static void jpeg_on_message(j_common_ptr cinfo, int level)
{
	if (level < 0)
		jpeg_on_error(cinfo);
}

/* One row of CMYK to RGB as Pillow converts it: R = (255-C)(255-K)/255 and
 * so on, rounded; Adobe's files (Photoshop's) store the inks inverted. */
static void cmyk_to_rgb(unsigned char *rgb, const unsigned char *cmyk, size_t n, int inverted)
{
	for (size_t i = 0; i < n; i++, cmyk += 4, rgb += 3) {
		unsigned k = inverted ? cmyk[3] : 255u - cmyk[3];   /* 255 - ink */
		for (int c = 0; c < 3; c++) {
			unsigned ink = inverted ? 255u - cmyk[c] : cmyk[c];
			unsigned t = ink * k + 128;
			rgb[c] = (unsigned char)(k - ((t >> 8) + t) / 256);
		}
	}
}

/* The byte libjpeg has reached in buf: at the end of the data it reads
 * from a buffer of its own (a fake EOI), which counts as len. */
static size_t jpeg_offset(const struct jpeg_decompress_struct *cinfo, const unsigned char *buf,
                          size_t len)
{
	if (!cinfo->src)
		return 0;
	uintptr_t p = (uintptr_t)cinfo->src->next_input_byte, b = (uintptr_t)buf;
	return p >= b && p - b <= len ? (size_t)(p - b) : len;
}

/* Decode the JPEG in buf[0..len) into img: 1 channel for greyscale, 3 (RGB)
 * otherwise, CMYK and YCCK converted to RGB; header_only gives the shape
 * and no data.  Errors name the byte libjpeg had reached. */
static int jpeg_decode(struct fct_image *img, const unsigned char *buf, size_t len,
                       const char *name, size_t max_pixels, int header_only,
                       struct fct_err *err)
{
	struct jpeg_decompress_struct cinfo;
	struct jpeg_state s;
	/* Changed after setjmp and needed after longjmp: volatile. */
	unsigned char *volatile data = NULL, *volatile cmyk = NULL;
	memset(&cinfo, 0, sizeof cinfo);
	cinfo.err = jpeg_std_error(&s.mgr);
	s.mgr.error_exit = jpeg_on_error;
	s.mgr.emit_message = jpeg_on_message;
	s.msg[0] = 0;
	if (setjmp(s.jump)) {
		size_t at = jpeg_offset(&cinfo, buf, len);
		jpeg_destroy_decompress(&cinfo);
		free(data);
		free(cmyk);
		return fct_fail(err, "%s: byte %zu: %s", name, at, s.msg);
	}
	jpeg_create_decompress(&cinfo);
	jpeg_mem_src(&cinfo, buf, (unsigned long)len);
	jpeg_read_header(&cinfo, TRUE);

	size_t at = jpeg_offset(&cinfo, buf, len);
	uint64_t w = cinfo.image_width, h = cinfo.image_height;
	struct fct_err big;
	int fail = check_pixels(w, h, max_pixels, &big);
	if (!fail && w * h > (uint64_t)len * JPEG_MAX_PIXELS_PER_BYTE)
		fail = fct_fail(&big, "image size %llux%llu: more pixels than %zu bytes of JPEG "
		                "can code (at most %d a byte)", (unsigned long long)w,
		                (unsigned long long)h, len, JPEG_MAX_PIXELS_PER_BYTE);
	int inverted = cinfo.saw_Adobe_marker;
	switch (cinfo.jpeg_color_space) {
	case JCS_GRAYSCALE: cinfo.out_color_space = JCS_GRAYSCALE; break;
	case JCS_CMYK: case JCS_YCCK: cinfo.out_color_space = JCS_CMYK; break;
	case JCS_RGB: case JCS_YCbCr: cinfo.out_color_space = JCS_RGB; break;
	default:
		if (!fail)
			fail = fct_fail(&big, "%d components of unknown colour space",
			                cinfo.num_components);
	}
	if (fail) {
		jpeg_destroy_decompress(&cinfo);
		return fct_fail(err, "%s: byte %zu: %s", name, at, big.msg);
	}
	int channels = cinfo.out_color_space == JCS_GRAYSCALE ? 1 : 3;
	img->width = (int)w;
	img->height = (int)h;
	img->channels = channels;
	img->type = FCT_PIX_U8;
	if (header_only) {
		jpeg_destroy_decompress(&cinfo);
		return 0;
	}
	jpeg_start_decompress(&cinfo);
	if (cinfo.output_width != w || cinfo.output_height != h ||
	    cinfo.output_components != (cinfo.out_color_space == JCS_CMYK ? 4 : channels))
		abort();  /* no scaling was asked for */
	size_t row = (size_t)w * (size_t)channels;
	if (!(data = malloc(row * (size_t)h)) ||
	    (cinfo.out_color_space == JCS_CMYK && !(cmyk = malloc(4 * (size_t)w)))) {
		snprintf(s.msg, sizeof s.msg, "out of memory (%zu bytes)", row * (size_t)h);
		longjmp(s.jump, 1);
	}
	while (cinfo.output_scanline < cinfo.output_height) {
		unsigned char *out = data + (size_t)cinfo.output_scanline * row;
		JSAMPROW rows[1] = { cmyk ? cmyk : out };
		jpeg_read_scanlines(&cinfo, rows, 1);
		if (cmyk)
			cmyk_to_rgb(out, cmyk, (size_t)w, inverted);
	}
	jpeg_finish_decompress(&cinfo);
	jpeg_destroy_decompress(&cinfo);
	free(cmyk);
	img->data = data;
	return 0;
}

/* ---- reading: detection ---------------------------------------------- */

int fct_image_magic(const unsigned char *head, size_t n)
{
	if (n >= 8 && !memcmp(head, png_magic, 8))
		return FCT_IMAGE_PNG;
	if (n >= 3 && head[0] == 'P' && (head[1] == 'F' || head[1] == 'f') && is_space(head[2]))
		return FCT_IMAGE_PFM;
	/* SOI, then the first marker's 0xFF. */
	if (n >= 3 && head[0] == 0xff && head[1] == 0xd8 && head[2] == 0xff)
		return FCT_IMAGE_JPEG;
	/* PGM and PPM, binary and ASCII ("P5", "P6", "P2", "P3"). */
	if (n >= 3 && head[0] == 'P' && strchr("2356", head[1]) && head[1] && is_space(head[2]))
		return FCT_IMAGE_PNM;
	return -1;
}

/* The reader behind every entry point: detect, take in the rest, decode
 * (or only read the header), refusing more than max_pixels. */
static int read_image(struct fct_image *img, FILE *f, const char *name, size_t max_pixels,
                      int header_only, enum fct_image_format *fmt, struct fct_err *err)
{
	memset(img, 0, sizeof *img);
	/* Look at the first bytes before taking in the whole input, so that a
	 * file that is no image is refused without reading it all. */
	unsigned char head[8];
	size_t n = fread(head, 1, sizeof head, f);
	if (n < sizeof head && ferror(f))
		return fct_fail(err, "%s: byte %zu: %s", name, n, strerror(errno));
	if (n == 0)
		return fct_fail(err, "%s: empty input, not a PNG, JPEG, PFM or PNM image", name);
	int png = !memcmp(head, png_magic, n < 8 ? n : 8);
	int pfm = fct_image_magic(head, n) == FCT_IMAGE_PFM;
	int jpeg = fct_image_magic(head, n) == FCT_IMAGE_JPEG;
	int pnm = fct_image_magic(head, n) == FCT_IMAGE_PNM;
	if (png && n < 8)
		return fct_fail(err, "%s: byte %zu: PNG signature: unexpected end of file", name, n);
	if (!png && !pfm && !jpeg && !pnm)
		return fct_fail(err, "%s: not a PNG, JPEG, PFM or PNM image", name);
	if (max_pixels > FCT_IMAGE_MAX_PIXELS)
		max_pixels = FCT_IMAGE_MAX_PIXELS;

	unsigned char *buf = NULL;
	size_t len = 0;
	if (slurp(f, name, head, n, &buf, &len, err))
		return -1;

	int rc;
	if (pfm) {
		rc = pfm_decode(img, buf, len, name, max_pixels, header_only, err);
	} else if (pnm) {
		rc = pnm_decode(img, buf, len, name, max_pixels, header_only, err);
	} else if (jpeg) {
		rc = jpeg_decode(img, buf, len, name, max_pixels, header_only, err);
		free(buf);
	} else {
		struct png_state s;
		memset(&s, 0, sizeof s);
		s.buf = buf;
		s.len = len;
		rc = png_decode(img, &s, name, max_pixels, header_only, err);
		free(buf);
	}
	if (rc) {
		memset(img, 0, sizeof *img);
		return -1;
	}
	if (fmt)
		*fmt = pfm ? FCT_IMAGE_PFM : pnm ? FCT_IMAGE_PNM : jpeg ? FCT_IMAGE_JPEG : FCT_IMAGE_PNG;
	return 0;
}

/* Open path (or stdin) and read it with read_image. */
static int read_image_file(struct fct_image *img, const char *path, size_t max_pixels,
                           int header_only, enum fct_image_format *fmt, struct fct_err *err)
{
	if (fct_path_is_std(path))
		return read_image(img, stdin, "<stdin>", max_pixels, header_only, fmt, err);
	memset(img, 0, sizeof *img);
	FILE *f = fopen(path, "rb");
	if (!f)
		return fct_fail(err, "%s: %s", path, strerror(errno));
	int rc = read_image(img, f, path, max_pixels, header_only, fmt, err);
	fclose(f);
	return rc;
}

int fct_image_read_stream(struct fct_image *img, FILE *f, const char *name,
                          enum fct_image_format *fmt, struct fct_err *err)
{
	return read_image(img, f, name, FCT_IMAGE_MAX_PIXELS, 0, fmt, err);
}

int fct_image_read_file(struct fct_image *img, const char *path,
                        enum fct_image_format *fmt, struct fct_err *err)
{
	return read_image_file(img, path, FCT_IMAGE_MAX_PIXELS, 0, fmt, err);
}

int fct_image_read_file_max(struct fct_image *img, const char *path, size_t max_pixels,
                            enum fct_image_format *fmt, struct fct_err *err)
{
	return read_image_file(img, path, max_pixels, 0, fmt, err);
}

int fct_image_probe_file(struct fct_image *img, const char *path,
                         enum fct_image_format *fmt, struct fct_err *err)
{
	return read_image_file(img, path, FCT_IMAGE_MAX_PIXELS, 1, fmt, err);
}

/* ---- writing ---------------------------------------------------------- */

static void png_write_file(png_structp png, png_bytep p, size_t n)
{
	FILE *f = png_get_io_ptr(png);
	if (fwrite(p, 1, n, f) != n)
		png_error(png, "write error");
}

static void png_flush_file(png_structp png)
{
	(void)png;  /* the caller flushes when it is done */
}

/* Encode img through libpng with rows already pointing into its data. */
static int png_encode(const struct fct_image *img, FILE *f, png_bytep *rows,
                      struct png_state *s, struct fct_err *err)
{
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, s, png_on_error,
	                                          png_on_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info) {
		png_destroy_write_struct(&png, NULL);
		return fct_fail(err, "PNG: out of memory");
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_write_struct(&png, &info);
		if (ferror(f))
			return fct_fail(err, "writing PNG: %s", strerror(errno));
		return fct_fail(err, "writing PNG: %s", s->msg);
	}
	static const int ctypes[5] = { 0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
	                               PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };
	png_set_write_fn(png, f, png_write_file, png_flush_file);
	png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height,
	             img->type == FCT_PIX_U16 ? 16 : 8, ctypes[img->channels],
	             PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_write_info(png, info);
	if (img->type == FCT_PIX_U16 && host_is_le())
		png_set_swap(png);
	png_write_image(png, rows);
	png_write_end(png, NULL);
	png_destroy_write_struct(&png, &info);
	return 0;
}

int fct_png_write(const struct fct_image *img, FILE *f, struct fct_err *err)
{
	size_t bytes;
	if (img->type != FCT_PIX_U8 && img->type != FCT_PIX_U16)
		return fct_fail(err, "PNG holds 8- or 16-bit integer samples, not %s",
		                fct_pix_name(img->type));
	if (image_bytes(img->width, img->height, img->channels, img->type, &bytes, err))
		return -1;
	size_t rowbytes = bytes / (size_t)img->height;
	png_bytep *rows = malloc((size_t)img->height * sizeof *rows);
	if (!rows)
		return fct_fail(err, "out of memory");
	/* libpng copies each row before transforming it, so the cast is safe. */
	for (int y = 0; y < img->height; y++)
		rows[y] = (png_bytep)img->data + (size_t)y * rowbytes;
	struct png_state s;
	memset(&s, 0, sizeof s);
	int rc = png_encode(img, f, rows, &s, err);
	free(rows);
	if (!rc && ferror(f))
		return fct_fail(err, "writing PNG: %s", strerror(errno));
	return rc;
}

int fct_pfm_write(const struct fct_image *img, FILE *f, struct fct_err *err)
{
	size_t bytes;
	if (img->type != FCT_PIX_F32 || (img->channels != 1 && img->channels != 3))
		return fct_fail(err, "PFM holds float samples with 1 or 3 channels, not %s with %d",
		                fct_pix_name(img->type), img->channels);
	if (image_bytes(img->width, img->height, img->channels, img->type, &bytes, err))
		return -1;
	size_t row = bytes / (size_t)img->height;
	/* Always little-endian (scale -1), so output does not depend on the host. */
	int le = host_is_le();
	unsigned char *tmp = le ? NULL : malloc(row);
	if (!le && !tmp)
		return fct_fail(err, "out of memory");
	fprintf(f, "P%c\n%d %d\n-1\n", img->channels == 3 ? 'F' : 'f', img->width, img->height);
	for (int y = img->height - 1; y >= 0; y--) {
		const unsigned char *src = (const unsigned char *)img->data + (size_t)y * row;
		if (!le) {
			memcpy(tmp, src, row);
			swap4(tmp, row);
			src = tmp;
		}
		if (fwrite(src, 1, row, f) != row)
			break;
	}
	free(tmp);
	if (ferror(f))
		return fct_fail(err, "writing PFM: %s", strerror(errno));
	return 0;
}
