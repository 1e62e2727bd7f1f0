/* test_image.c - PNG, PFM and PNM reading, PNG and PFM writing: bit-exact round trips,
 * hand-made PFM bytes, fixtures written by an independent encoder
 * (tests/data/img_gen.py, zlib only), real depth maps checked against values
 * decoded by a separate Python decoder, and the error messages.  JPEG:
 * fixtures from tests/data/jpg_gen.py checked against Pillow's decode (its
 * own libjpeg-turbo) and against colours known by construction.  PNM:
 * hand-made bytes in every variant (P2, P3, P5, P6; 8 and 16 bits). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/image.h"

/* Read an image from bytes in memory (fmemopen: no file descriptor, so the
 * reader takes the pipe path). */
static int read_mem(struct fct_image *img, const void *bytes, size_t n,
                    enum fct_image_format *fmt, struct fct_err *err)
{
	FILE *f = fmemopen((void *)bytes, n, "rb");
	if (!f)
		return fct_fail(err, "fmemopen failed");
	int rc = fct_image_read_stream(img, f, "mem", fmt, err);
	fclose(f);
	return rc;
}

/* Write with fn into a malloc'd buffer. */
static unsigned char *write_mem(int (*fn)(const struct fct_image *, FILE *, struct fct_err *),
                                const struct fct_image *img, size_t *n, struct fct_err *err)
{
	char *buf = NULL;
	FILE *f = open_memstream(&buf, n);
	if (!f)
		return NULL;
	int rc = fn(img, f, err);
	fclose(f);
	if (rc) {
		free(buf);
		return NULL;
	}
	return (unsigned char *)buf;
}

static uint32_t be32(const unsigned char *p)
{
	return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Every PNG variant: 8/16 bits x 1..4 channels, through the writer and back,
 * with the written IHDR checked byte by byte. */
static void test_png_round_trips(void)
{
	static const int ctype[5] = { 0, 0, 4, 2, 6 };
	for (int t = 0; t < 2; t++) {
		enum fct_pix type = t ? FCT_PIX_U16 : FCT_PIX_U8;
		for (int ch = 1; ch <= 4; ch++) {
			struct fct_err err;
			struct fct_image img, back;
			CHECK(fct_image_alloc(&img, 5, 3, ch, type, &err) == 0);
			size_t n = fct_image_samples(&img);
			CHECK_INT(n, 15 * ch);
			for (size_t i = 0; i < n; i++) {
				/* Extremes and values whose two bytes differ. */
				unsigned v = (unsigned)(i * 2654435761u >> 7);
				if (t) {
					((uint16_t *)img.data)[i] = i == 0 ? 0 : i == 1 ? 65535 : (uint16_t)v;
				} else {
					((uint8_t *)img.data)[i] = i == 0 ? 0 : i == 1 ? 255 : (uint8_t)v;
				}
			}
			size_t len = 0;
			unsigned char *png = write_mem(fct_png_write, &img, &len, &err);
			CHECK(png != NULL);
			if (!png) {
				fct_image_free(&img);
				continue;
			}
			CHECK(len > 33 && !memcmp(png, "\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16));
			CHECK_INT(be32(png + 16), 5);
			CHECK_INT(be32(png + 20), 3);
			CHECK_INT(png[24], t ? 16 : 8);
			CHECK_INT(png[25], ctype[ch]);
			CHECK_INT(png[28], 0);  /* not interlaced */
			enum fct_image_format fmt = FCT_IMAGE_PFM;
			int rc = read_mem(&back, png, len, &fmt, &err);
			CHECK_MSG(rc == 0, "read back: %s", rc ? err.msg : "");
			if (!rc) {
				CHECK_INT(fmt, FCT_IMAGE_PNG);
				CHECK_INT(back.width, 5);
				CHECK_INT(back.height, 3);
				CHECK_INT(back.channels, ch);
				CHECK_INT(back.type, type);
				CHECK(!memcmp(back.data, img.data, n * fct_pix_size(type)));
				CHECK_NEAR(fct_image_get(&back, 0, 0, 0), 0, 0);
				CHECK_NEAR(fct_image_sample(&back, 1), t ? 65535 : 255, 0);
			}
			/* The writer is deterministic. */
			size_t len2 = 0;
			unsigned char *png2 = write_mem(fct_png_write, &img, &len2, &err);
			CHECK(png2 && len2 == len && !memcmp(png, png2, len));
			free(png2);
			free(png);
			fct_image_free(&back);
			fct_image_free(&img);
		}
	}
}

/* A grey PFM written by hand: little-endian, rows bottom first. */
static const unsigned char pfm_le_grey[] = {
	'P', 'f', '\n', '2', ' ', '2', '\n', '-', '1', '\n',
	0x00, 0x00, 0x40, 0x40,   /* 3.0  bottom row */
	0x00, 0x00, 0x80, 0x40,   /* 4.0 */
	0x00, 0x00, 0x80, 0x3f,   /* 1.0  top row */
	0x00, 0x00, 0x00, 0x40,   /* 2.0 */
};

/* A colour PFM by hand: big-endian (positive scale), 1x2. */
static const unsigned char pfm_be_rgb[] = {
	'P', 'F', '\n', '1', ' ', '2', '\n', '1', '.', '0', '\n',
	0xc0, 0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x00, 0x7f, 0xc0, 0x00, 0x00,  /* -2, .5, NaN */
	0x41, 0x20, 0x00, 0x00, 0x7f, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  /* 10, inf, 0 */
};

static void test_pfm_hand_made(void)
{
	struct fct_err err;
	struct fct_image img;
	enum fct_image_format fmt = FCT_IMAGE_PNG;
	CHECK(read_mem(&img, pfm_le_grey, sizeof pfm_le_grey, &fmt, &err) == 0);
	CHECK_INT(fmt, FCT_IMAGE_PFM);
	CHECK_INT(img.width, 2);
	CHECK_INT(img.height, 2);
	CHECK_INT(img.channels, 1);
	CHECK_INT(img.type, FCT_PIX_F32);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 1.0, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 2.0, 0);
	CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 3.0, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 1, 0), 4.0, 0);
	/* Writing gives back exactly the hand-made bytes. */
	size_t len = 0;
	unsigned char *out = write_mem(fct_pfm_write, &img, &len, &err);
	CHECK(out && len == sizeof pfm_le_grey && !memcmp(out, pfm_le_grey, len));
	free(out);
	fct_image_free(&img);

	CHECK(read_mem(&img, pfm_be_rgb, sizeof pfm_be_rgb, &fmt, &err) == 0);
	CHECK_INT(img.width, 1);
	CHECK_INT(img.height, 2);
	CHECK_INT(img.channels, 3);
	/* Top row is the second stored row. */
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 10.0, 0);
	CHECK(isinf(fct_image_get(&img, 0, 0, 1)) && fct_image_get(&img, 0, 0, 1) > 0);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 2), 0.0, 0);
	CHECK_NEAR(fct_image_get(&img, 0, 1, 0), -2.0, 0);
	CHECK_NEAR(fct_image_get(&img, 0, 1, 1), 0.5, 0);
	CHECK(isnan(fct_image_get(&img, 0, 1, 2)));
	/* Written back little-endian: same values, bit for bit (NaN included). */
	out = write_mem(fct_pfm_write, &img, &len, &err);
	CHECK(out && len == 10 + 24 && !memcmp(out, "PF\n1 2\n-1\n", 10));
	if (out && len == 34) {
		for (int i = 0; i < 6; i++) {
			const unsigned char *be = pfm_be_rgb + 11 + 4 * i, *le = out + 10 + 4 * i;
			CHECK(le[0] == be[3] && le[1] == be[2] && le[2] == be[1] && le[3] == be[0]);
		}
	}
	free(out);
	fct_image_free(&img);
}

/* Header whitespace: any blanks between fields, CR LF line ends, and a CR
 * whose next byte is data (an LF-valued first byte) told apart by size. */
static void test_pfm_whitespace(void)
{
	struct fct_err err;
	struct fct_image img;
	static const unsigned char blanks[] = "Pf  1\t1 \n -1 \x00\x00\xc0\x3f";  /* 1.5 */
	CHECK(read_mem(&img, blanks, sizeof blanks - 1, NULL, &err) == 0);
	CHECK_NEAR(img.data ? fct_image_get(&img, 0, 0, 0) : -1, 1.5, 0);
	fct_image_free(&img);
	static const unsigned char crlf[] = "Pf\r\n1 1\r\n-1\r\n\x00\x00\x20\x41";  /* 10 */
	CHECK(read_mem(&img, crlf, sizeof crlf - 1, NULL, &err) == 0);
	CHECK_NEAR(img.data ? fct_image_get(&img, 0, 0, 0) : -1, 10.0, 0);
	fct_image_free(&img);
	/* 0x0000000a little-endian is the denormal 10 * 2^-149. */
	static const unsigned char cr_then_lf_data[] = "Pf\n1 1\n-1\r\x0a\x00\x00\x00";
	CHECK(read_mem(&img, cr_then_lf_data, sizeof cr_then_lf_data - 1, NULL, &err) == 0);
	CHECK_NEAR(img.data ? fct_image_get(&img, 0, 0, 0) : -1, 10 * ldexp(1, -149), 0);
	fct_image_free(&img);
}

static void test_pfm_round_trips(void)
{
	for (int ch = 1; ch <= 3; ch += 2) {
		struct fct_err err;
		struct fct_image img, back;
		CHECK(fct_image_alloc(&img, 4, 3, ch, FCT_PIX_F32, &err) == 0);
		float *v = img.data;
		size_t n = fct_image_samples(&img);
		for (size_t i = 0; i < n; i++)
			v[i] = (float)i * 0.37f - 2.0f;
		v[1] = NAN;
		v[2] = -INFINITY;
		v[3] = -0.0f;
		size_t len = 0;
		unsigned char *out = write_mem(fct_pfm_write, &img, &len, &err);
		CHECK(out && len == 10 + n * 4);
		CHECK(out && !memcmp(out, ch == 3 ? "PF\n4 3\n-1\n" : "Pf\n4 3\n-1\n", 10));
		if (out && read_mem(&back, out, len, NULL, &err) == 0) {
			CHECK_INT(back.channels, ch);
			CHECK(!memcmp(back.data, img.data, n * 4));
			fct_image_free(&back);
		} else {
			CHECK_MSG(0, "PFM round trip: %s", err.msg);
		}
		free(out);
		fct_image_free(&img);
	}
}

static int read_path(struct fct_image *img, const char *path)
{
	struct fct_err err;
	int rc = fct_image_read_file(img, path, NULL, &err);
	CHECK_MSG(rc == 0, "%s: %s", path, rc ? err.msg : "");
	return rc;
}

/* Fixtures from tests/data/img_gen.py, whose values are written there. */
static void test_fixtures(void)
{
	struct fct_image img;
	if (!read_path(&img, "tests/data/img_grey16.png")) {
		static const double want[6] = { 0, 1000, 65535, 258, 0, 4660 };
		CHECK_INT(img.type, FCT_PIX_U16);
		for (int i = 0; i < 6; i++)
			CHECK_NEAR(fct_image_sample(&img, (size_t)i), want[i], 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_adam7.png")) {
		int ok = img.width == 5 && img.height == 5 && img.channels == 1;
		for (int y = 0; ok && y < 5; y++)
			for (int x = 0; x < 5; x++)
				ok &= fct_image_get(&img, x, y, 0) == 10 * y + x;
		CHECK_MSG(ok, "interlaced PNG: pixel (x, y) is 10y+x");
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_pal2.png")) {
		/* Palette 2-bit indices 0,1,2 / 2,1,0, entry 1 half transparent. */
		CHECK_INT(img.channels, 4);
		CHECK_INT(img.type, FCT_PIX_U8);
		CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 40, 0);
		CHECK_NEAR(fct_image_get(&img, 1, 0, 2), 60, 0);
		CHECK_NEAR(fct_image_get(&img, 1, 0, 3), 128, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 70, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 1, 3), 255, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_grey1.png")) {
		static const int bits[9] = { 1, 0, 1, 1, 0, 0, 1, 0, 1 };
		CHECK_INT(img.width, 9);
		CHECK_INT(img.type, FCT_PIX_U8);
		for (int x = 0; x < 9; x++)
			CHECK_NEAR(fct_image_get(&img, x, 0, 0), bits[x] * 255, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_grey4.png")) {
		CHECK_NEAR(fct_image_get(&img, 2, 0, 0), 7 * 17, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 17, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_rgba16.png")) {
		CHECK_INT(img.channels, 4);
		CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 40000, 0);
		CHECK_NEAR(fct_image_get(&img, 1, 0, 2), 513, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 0, 3), 65535, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_ga8.png")) {
		CHECK_INT(img.channels, 2);
		CHECK_NEAR(fct_image_get(&img, 0, 1, 1), 128, 0);
		CHECK_NEAR(fct_image_get(&img, 1, 1, 1), 64, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_depth.pfm")) {
		CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 1.5, 0);
		CHECK(isnan(fct_image_get(&img, 2, 0, 0)));
		CHECK(isinf(fct_image_get(&img, 0, 1, 0)));
		CHECK_NEAR(fct_image_get(&img, 2, 1, 0), -1.0, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/img_rgb_be.pfm")) {
		CHECK_NEAR(fct_image_get(&img, 1, 0, 2), 6, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 7, 0);
		fct_image_free(&img);
	}
}

/* path (of size n) gets the file rel of the shared real data, from the
 * top folder of a checkout beside it or at its usual place; -1 (the test
 * skipped with a message) when it is not there. */
static int find_real(char *path, size_t n, const char *rel)
{
	const char *roots[] = { "../shared/data/", "/work/shared/data/" };
	for (int i = 0; i < 2; i++) {
		snprintf(path, n, "%s%s", roots[i], rel);
		FILE *f = fopen(path, "rb");
		if (f) {
			fclose(f);
			return 0;
		}
	}
	fprintf(stderr, "test_image: %s not found, skipped\n", rel);
	return -1;
}

/* The pixel (x, y) of an 8-bit image, channels 0..2 (or the grey value). */
static void check_rgb(const struct fct_image *img, int x, int y, int r, int g, int b)
{
	int want[3] = { r, g, b };
	for (int c = 0; c < img->channels; c++)
		CHECK_MSG(fct_image_get(img, x, y, c) == want[c], "pixel (%d, %d) channel %d: %g, want %d",
		          x, y, c, fct_image_get(img, x, y, c), want[c]);
}

static double image_sum(const struct fct_image *img)
{
	double s = 0;
	for (size_t i = 0; i < fct_image_samples(img); i++)
		s += fct_image_sample(img, i);
	return s;
}

/* A 64x48 piece of the 7-Scenes frame (jpegtran's lossless crop, 4:2:0):
 * sums and pixels as Pillow decodes them; the same coefficients written
 * progressive, arithmetic-coded and with a restart marker per MCU decode to
 * the same bytes; CMYK and greyscale; flat tiles of known colour. */
static void test_jpeg_fixtures(void)
{
	struct fct_image img, other;
	struct fct_err err;
	enum fct_image_format fmt = FCT_IMAGE_PNG;
	if (fct_image_read_file(&img, "tests/data/jpg_7scenes.jpg", &fmt, &err)) {
		CHECK_MSG(0, "%s", err.msg);
		return;
	}
	CHECK_INT(fmt, FCT_IMAGE_JPEG);
	CHECK_STR(fct_image_format_name(fmt), "jpeg");
	CHECK_INT(img.width, 64);
	CHECK_INT(img.height, 48);
	CHECK_INT(img.channels, 3);
	CHECK_INT(img.type, FCT_PIX_U8);
	CHECK_NEAR(image_sum(&img), 1864122, 0);
	check_rgb(&img, 0, 0, 236, 212, 176);
	check_rgb(&img, 31, 20, 220, 201, 161);
	check_rgb(&img, 63, 47, 228, 213, 180);
	check_rgb(&img, 10, 40, 234, 220, 193);
	static const char *const same[] = { "tests/data/jpg_7scenes_prog.jpg",
	                                    "tests/data/jpg_7scenes_arith.jpg",
	                                    "tests/data/jpg_7scenes_restart.jpg" };
	for (int i = 0; i < 3; i++) {
		if (read_path(&other, same[i]))
			continue;
		CHECK_MSG(other.width == 64 && other.height == 48 && other.channels == 3 &&
		          !memcmp(other.data, img.data, fct_image_samples(&img)),
		          "%s decodes to the same pixels as the baseline file", same[i]);
		fct_image_free(&other);
	}
	if (!read_path(&other, "tests/data/jpg_cmyk.jpg")) {
		CHECK_INT(other.channels, 3);
		CHECK_NEAR(image_sum(&other), 1864160, 0);
		check_rgb(&other, 0, 0, 236, 211, 176);
		check_rgb(&other, 31, 20, 220, 201, 161);
		/* Pillow's CMYK of the RGB piece, at quality 95: within 3 levels. */
		double worst = 0;
		for (size_t i = 0; i < fct_image_samples(&img); i++)
			worst = fmax(worst, fabs(fct_image_sample(&img, i) - fct_image_sample(&other, i)));
		CHECK_NEAR(worst, 3, 0);
		fct_image_free(&other);
	}
	fct_image_free(&img);
	if (!read_path(&img, "tests/data/jpg_grey.jpg")) {
		CHECK_INT(img.channels, 1);
		CHECK_NEAR(image_sum(&img), 641732, 0);
		CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 215, 0);
		CHECK_NEAR(fct_image_get(&img, 31, 20, 0), 202, 0);
		fct_image_free(&img);
	}
	if (!read_path(&img, "tests/data/jpg_tiles.jpg")) {
		/* 8x8 tiles red, green / blue, (200, 150, 50) at quality 100, 4:4:4. */
		static const int colour[4][3] = { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 },
		                                  { 200, 150, 50 } };
		double worst = 0;
		for (int y = 0; y < 16; y++)
			for (int x = 0; x < 16; x++)
				for (int c = 0; c < 3; c++)
					worst = fmax(worst, fabs(fct_image_get(&img, x, y, c) -
					                         colour[(y / 8) * 2 + x / 8][c]));
		CHECK_MSG(worst <= 1, "flat tiles decode within 1 level of their colour (%g)", worst);
		fct_image_free(&img);
	}
}

/* The whole 7-Scenes frame the piece was cut from: Pillow's sums and
 * pixels, and the piece equal to the frame's pixels away from its border
 * (where chroma upsampling sees different neighbours). */
static void test_jpeg_real(void)
{
	char path[512];
	if (find_real(path, sizeof path, "7scenes_redkitchen/frames/frame-000000.color.jpg"))
		return;
	struct fct_image img, piece;
	if (read_path(&img, path))
		return;
	CHECK_INT(img.width, 640);
	CHECK_INT(img.height, 480);
	CHECK_NEAR(image_sum(&img), 103947374, 0);
	check_rgb(&img, 320, 240, 236, 212, 174);
	check_rgb(&img, 0, 0, 76, 82, 82);
	check_rgb(&img, 639, 479, 36, 31, 35);
	check_rgb(&img, 100, 400, 130, 142, 158);
	if (!read_path(&piece, "tests/data/jpg_7scenes.jpg")) {
		int differ = 0;
		for (int y = 2; y < 46; y++)
			for (int x = 2; x < 62; x++)
				for (int c = 0; c < 3; c++)
					differ += fct_image_get(&piece, x, y, c) !=
					          fct_image_get(&img, 320 + x, 240 + y, c);
		CHECK_INT(differ, 0);
		fct_image_free(&piece);
	}
	fct_image_free(&img);
}

/* The header alone, and a caller's limit applied before decoding. */
static void test_probe_and_limit(void)
{
	static const struct { const char *path; int w, h, ch; enum fct_pix type; } probe[] = {
		{ "tests/data/jpg_7scenes.jpg", 64, 48, 3, FCT_PIX_U8 },
		{ "tests/data/jpg_grey.jpg", 64, 48, 1, FCT_PIX_U8 },
		{ "tests/data/jpg_cmyk.jpg", 64, 48, 3, FCT_PIX_U8 },
		{ "tests/data/img_pal2.png", 3, 2, 4, FCT_PIX_U8 },
		{ "tests/data/img_grey16.png", 3, 2, 1, FCT_PIX_U16 },
		{ "tests/data/img_rgb_be.pfm", 2, 2, 3, FCT_PIX_F32 },
	};
	struct fct_image img;
	struct fct_err err;
	for (size_t i = 0; i < sizeof probe / sizeof probe[0]; i++) {
		int rc = fct_image_probe_file(&img, probe[i].path, NULL, &err);
		CHECK_MSG(rc == 0 && img.data == NULL && img.width == probe[i].w &&
		          img.height == probe[i].h && img.channels == probe[i].ch &&
		          img.type == probe[i].type, "probe %s: %s", probe[i].path, rc ? err.msg : "");
	}
	CHECK(fct_image_probe_file(&img, "tests/bad/img_jpeg_huge.jpg", NULL, &err) == -1);
	CHECK(fct_image_probe_file(&img, "tests/bad/img_lying.pfm", NULL, &err) == -1);

	CHECK(fct_image_read_file_max(&img, "tests/data/jpg_7scenes.jpg", 3071, NULL, &err) == -1);
	CHECK_STR(err.msg, "tests/data/jpg_7scenes.jpg: byte 623: image size 64x48: "
	          "more than the 3071 pixels allowed here");
	CHECK(img.data == NULL);
	CHECK(fct_image_read_file_max(&img, "tests/data/jpg_7scenes.jpg", 3072, NULL, &err) == 0);
	fct_image_free(&img);
	CHECK(fct_image_read_file_max(&img, "tests/data/img_grey8.png", 5, NULL, &err) == -1);
	CHECK_STR(err.msg, "tests/data/img_grey8.png: byte 16: image size 3x2: "
	          "more than the 5 pixels allowed here");
	CHECK(fct_image_read_file_max(&img, "tests/data/img_depth.pfm", 5, NULL, &err) == -1);
	CHECK_STR(err.msg, "tests/data/img_depth.pfm: byte 3: PFM header: image size 3x2: "
	          "more than the 5 pixels allowed here");
}

/* The real depth maps in ../shared/data.  Expected values were decoded with
 * a separate Python PNG decoder (zlib only, CRCs checked). */
struct real_case {
	const char *path;
	int zeros;
	double sum, max;
	int px[3][3];   /* x, y, value */
};

static void test_real_depth(const struct real_case *rc)
{
	char path[512];
	if (find_real(path, sizeof path, rc->path))
		return;
	struct fct_image img;
	if (read_path(&img, path))
		return;
	CHECK_INT(img.width, 640);
	CHECK_INT(img.height, 480);
	CHECK_INT(img.channels, 1);
	CHECK_INT(img.type, FCT_PIX_U16);
	int zeros = 0;
	double sum = 0, max = 0;
	for (size_t i = 0; i < fct_image_samples(&img); i++) {
		double v = fct_image_sample(&img, i);
		zeros += v == 0;
		sum += v;
		max = v > max ? v : max;
	}
	CHECK_INT(zeros, rc->zeros);
	CHECK_NEAR(sum, rc->sum, 0);
	CHECK_NEAR(max, rc->max, 0);
	for (int k = 0; k < 3; k++)
		CHECK_NEAR(fct_image_get(&img, rc->px[k][0], rc->px[k][1], 0), rc->px[k][2], 0);
	fct_image_free(&img);
}

/* Netpbm by hand: 16-bit binary grey most significant byte first, 8-bit
 * binary RGB, ASCII grey and RGB with comments, values kept as stored. */
static void test_pnm_hand_made(void)
{
	struct fct_err err;
	struct fct_image img;
	enum fct_image_format fmt = FCT_IMAGE_PNG;
	static const unsigned char p5[] = "P5\n# a comment\n3 1 # after\n65535\n\x07\xd0\xff\xff\x00\x01";
	CHECK(read_mem(&img, p5, sizeof p5 - 1, &fmt, &err) == 0);
	CHECK_INT(fmt, FCT_IMAGE_PNM);
	CHECK_INT(img.width, 3);
	CHECK_INT(img.height, 1);
	CHECK_INT(img.channels, 1);
	CHECK_INT(img.type, FCT_PIX_U16);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 2000, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 65535, 0);
	CHECK_NEAR(fct_image_get(&img, 2, 0, 0), 1, 0);
	fct_image_free(&img);
	/* maxval 1023: still two bytes a sample; values not rescaled */
	static const unsigned char p5b[] = "P5 2 1 1023\n\x03\xff\x00\x07";
	CHECK(read_mem(&img, p5b, sizeof p5b - 1, NULL, &err) == 0);
	CHECK_INT(img.type, FCT_PIX_U16);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 1023, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 7, 0);
	fct_image_free(&img);
	static const unsigned char p6[] = "P6 1 2 255\n\x01\x02\x03\xfa\xfb\xfc";
	CHECK(read_mem(&img, p6, sizeof p6 - 1, &fmt, &err) == 0);
	CHECK_INT(fmt, FCT_IMAGE_PNM);
	CHECK_INT(img.channels, 3);
	CHECK_INT(img.type, FCT_PIX_U8);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 2), 3, 0);
	CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 250, 0);
	fct_image_free(&img);
	static const char p2[] = "P2\n2 2\n# maxval next\n4000\n0 1\n3999\t4000\n\n";
	CHECK(read_mem(&img, p2, sizeof p2 - 1, &fmt, &err) == 0);
	CHECK_INT(img.type, FCT_PIX_U16);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 1, 0);
	CHECK_NEAR(fct_image_get(&img, 0, 1, 0), 3999, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 1, 0), 4000, 0);
	fct_image_free(&img);
	static const char p3[] = "P3 1 1 255 10 20 30";
	CHECK(read_mem(&img, p3, sizeof p3 - 1, &fmt, &err) == 0);
	CHECK_INT(img.channels, 3);
	CHECK_INT(img.type, FCT_PIX_U8);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 1), 20, 0);
	fct_image_free(&img);
}

/* Error messages say where, and nothing is left allocated. */
static void check_error(const char *bytes, size_t n, const char *want)
{
	struct fct_err err;
	struct fct_image img;
	int rc = read_mem(&img, bytes, n, NULL, &err);
	CHECK(rc == -1);
	CHECK(img.data == NULL);
	if (rc)
		CHECK_STR(err.msg, want);
}

static void test_errors(void)
{
	check_error("hello", 5, "mem: not a PNG, JPEG, PFM or PNM image");
	check_error("P4 1 1\n\x80", 8, "mem: not a PNG, JPEG, PFM or PNM image");
	check_error("P5 2 1 255\n\x01", 12,
	            "mem: byte 11: PNM header says 2x1 with 1 channel (2 bytes) but 1 bytes follow");
	check_error("P5 100000 100000 255\n\x01", 22,
	            "mem: byte 3: PNM header: image size 100000x100000: more than 2^31 pixels");
	check_error("P5 2 1 0\n\x01\x01", 11, "mem: byte 7: PNM header: maxval is 0");
	check_error("P5 2 1 65536\n\x01\x01", 15, "mem: byte 7: PNM header: maxval 65536 is over 65535");
	check_error("P5 2 1 # no end", 15,
	            "mem: byte 15: PNM header: unexpected end of file before the maxval");
	check_error("P5 2 1 100\n\x01\xc8", 13, "mem: byte 12: PNM sample 1 is over the maxval 100");
	check_error("P5 1 1 1000\n\x03\xe9", 14, "mem: byte 12: PNM sample 0 is over the maxval 1000");
	check_error("P2 2 1 100 7 101", 16, "mem: byte 13: PNM sample 1 is over the maxval 100");
	check_error("P2 2 1 100 7 1x", 15, "mem: byte 13: PNM sample 1 \"1x\" is not a number");
	check_error("P2 2 1 100 7 8 9", 16, "mem: byte 15: PNM: more than the 2 samples of its header");
	check_error("P2 2 1 100 7   ", 15, "mem: byte 15: PNM header: unexpected end of file before the sample");
	check_error("P2 3000 3000 100 7 8", 20,
	            "mem: byte 17: PNM header says 3000x3000 with 1 channel (9000000 samples) but 3 bytes follow");
	check_error("\x89PNG", 4, "mem: byte 4: PNG signature: unexpected end of file");
	check_error("Pf\n2 1\n-1\n\0\0\0\0", 14,
	            "mem: byte 10: PFM header says 2x1 with 1 channel (8 bytes) but 4 bytes follow");
	check_error("Pf\n100000 100000\n-1\n\0\0\0\0", 24,
	            "mem: byte 3: PFM header: image size 100000x100000: more than 2^31 pixels");
	check_error("PF\n2 1\n-x\n", 10, "mem: byte 7: PFM header: scale \"-x\" is not a nonzero number");
	check_error("PF\n2 -1\n-1\n", 11, "mem: byte 5: PFM header: height \"-1\" is not a positive integer");
	check_error("PF\n2 1\n-1", 9, "mem: byte 9: PFM header: unexpected end of file after the scale");
	/* A PNG that declares 1000000x1000000 in 57 bytes. */
	static const unsigned char huge[] = {
		0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
		0x00, 0x0f, 0x42, 0x40, 0x00, 0x0f, 0x42, 0x40, 8, 0, 0, 0, 0, 0x79, 0x06, 0x67, 0xa1,
		0, 0, 0, 0, 'I', 'D', 'A', 'T', 0x35, 0xaf, 0x06, 0x1e,
		0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82,
	};
	check_error((const char *)huge, sizeof huge,
	            "mem: byte 16: image size 1000000x1000000: more than 2^31 pixels");

	struct fct_err err;
	struct fct_image img;
	CHECK(fct_image_alloc(&img, 0, 5, 1, FCT_PIX_U8, &err) == -1);
	CHECK_STR(err.msg, "image size 0x5: width and height must be positive");
	CHECK(fct_image_alloc(&img, 5, 5, 5, FCT_PIX_U8, &err) == -1);
	CHECK(fct_image_alloc(&img, 1 << 16, 1 << 16, 1, FCT_PIX_U8, &err) == -1);
	CHECK_STR(err.msg, "image size 65536x65536: more than 2^31 pixels");
	CHECK(img.data == NULL);
	fct_image_free(NULL);
	fct_image_free(&img);

	/* Writers refuse what their format cannot hold. */
	CHECK(fct_image_alloc(&img, 2, 2, 2, FCT_PIX_F32, &err) == 0);
	FILE *f = fopen("/dev/null", "wb");
	CHECK(f != NULL);
	if (f) {
		CHECK(fct_png_write(&img, f, &err) == -1);
		CHECK_STR(err.msg, "PNG holds 8- or 16-bit integer samples, not f32");
		CHECK(fct_pfm_write(&img, f, &err) == -1);
		CHECK_STR(err.msg, "PFM holds float samples with 1 or 3 channels, not f32 with 2");
		fclose(f);
	}
	fct_image_free(&img);
	CHECK(fct_image_read_file(&img, "tests/data/no-such-image.png", NULL, &err) == -1);
	CHECK_STR(err.msg, "tests/data/no-such-image.png: No such file or directory");
}

static void test_bad_files(void)
{
	/* One of each family as regular files (tests/cmd/imginfo.sh runs all). */
	static const char *const bad[][2] = {
		{ "tests/bad/img_cut_idat.png", "byte 33: chunk IDAT declares 16 bytes, past the end" },
		{ "tests/bad/img_header_only.png", "byte 33: unexpected end of file" },
		{ "tests/bad/img_fuzz_1.png", "byte 33: chunk sPLT declares 1665684045 bytes" },
		{ "tests/bad/img_bad_crc.png", "byte 33: libpng: IHDR: CRC error" },
		{ "tests/bad/img_huge_rgba.png", "byte 16: image size 40000x40000 needs" },
		{ "tests/bad/img_lying.pfm", "byte 14: PFM header says 300x200" },
		{ "tests/bad/img_lying.pgm", "byte 17: PNM header says 300x200 with 1 channel (120000 bytes)" },
		{ "tests/bad/img_over_maxval.pgm", "byte 17: PNM sample 3 is over the maxval 255" },
		{ "tests/bad/img_empty.png", "empty input" },
		{ "tests/bad/img_jpeg_huge.jpg", "byte 623: image size 60000x60000: more than 2^31" },
		{ "tests/bad/img_jpeg_lying.jpg", "byte 623: image size 30000x30000: more pixels than "
		  "661 bytes of JPEG can code" },
		{ "tests/bad/img_jpeg_lying_prog.jpg", "byte 245: image size 40000x40000: more pixels" },
		{ "tests/bad/img_jpeg_truncated.jpg", "byte 659: libjpeg: Premature end of JPEG file" },
		{ "tests/bad/img_jpeg_corrupt.jpg", "byte 659: libjpeg: Corrupt JPEG data" },
		{ "tests/bad/img_jpeg_12bit.jpg", "byte 623: libjpeg: Unsupported JPEG data precision 12" },
		{ "tests/bad/img_jpeg_two_components.jpg", "byte 331: 2 components of unknown colour" },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		struct fct_err err;
		struct fct_image img;
		int rc = fct_image_read_file(&img, bad[i][0], NULL, &err);
		CHECK(rc == -1);
		size_t pl = strlen(bad[i][0]);
		CHECK_MSG(rc && !strncmp(err.msg, bad[i][0], pl) && !strncmp(err.msg + pl, ": ", 2) &&
		          !strncmp(err.msg + pl + 2, bad[i][1], strlen(bad[i][1])),
		          "%s: got \"%s\"", bad[i][0], err.msg);
	}
}

int main(void)
{
	test_png_round_trips();
	test_pfm_hand_made();
	test_pfm_whitespace();
	test_pfm_round_trips();
	test_pnm_hand_made();
	test_fixtures();
	test_jpeg_fixtures();
	test_jpeg_real();
	test_probe_and_limit();
	static const struct real_case redkitchen = {
		"7scenes_redkitchen/frames/frame-000000.depth.png", 33257, 526822367, 3493,
		{ { 320, 240, 1382 }, { 100, 400, 1828 }, { 500, 50, 2834 } },
	};
	static const struct real_case tum = {
		"rgbd_single_frames_formats/TUM_depth.png", 58950, 3074716315.0, 46655,
		{ { 320, 240, 10920 }, { 100, 400, 8880 }, { 500, 50, 12425 } },
	};
	test_real_depth(&redkitchen);
	test_real_depth(&tum);
	test_errors();
	test_bad_files();
	CHECK_DONE();
}
