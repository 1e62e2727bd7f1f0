/* test_depthcode.c - datasets' depth encodings: the names, and each code
 * decoded against values worked by hand (SUN RGB-D's rotation both sides
 * of 8.192 m, where it wraps; NYU's raw Kinect codes by its toolbox's
 * formula). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "depth/depthcode.h"

static void test_names(void)
{
	struct fct_err err;
	unsigned c = 99;
	CHECK(fct_depth_code_parse("none", &c, &err) == 0 && c == 0);
	CHECK(fct_depth_code_parse("nyu", &c, &err) == 0 && c == (FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW));
	CHECK(fct_depth_code_parse("sun", &c, &err) == 0 && c == FCT_DEPTH_ROTATE);
	CHECK(fct_depth_code_parse("swap,kinect-raw", &c, &err) == 0 &&
	      c == (FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW));
	CHECK(fct_depth_code_parse("kinect", &c, &err) == -1);
	CHECK_STR(err.msg, "\"kinect\" is not a depth code (none swap rotate kinect-raw nyu sun)");
	CHECK(fct_depth_code_parse("swap,", &c, &err) == -1);
	CHECK_STR(err.msg, "\"\" is not a depth code (none swap rotate kinect-raw nyu sun)");
	CHECK_INT(fct_depth_code_named("nyu"), FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW);
	CHECK_INT(fct_depth_code_named("7scenes"), 0);
	CHECK_INT(fct_depth_code_named(NULL), 0);
}

static void image16(struct fct_image *img, const uint16_t *v, int n)
{
	struct fct_err err;
	CHECK(fct_image_alloc(img, n, 1, 1, FCT_PIX_U16, &err) == 0);
	memcpy(img->data, v, (size_t)n * sizeof *v);
}

static void test_decode(void)
{
	struct fct_err err;
	struct fct_image img;
	/* swap: 0x07d0 (2000) stored the other way round */
	image16(&img, (const uint16_t[]){ 0xd007, 0x0100 }, 2);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_SWAP, &err) == 0);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 2000, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 1, 0);
	fct_image_free(&img);
	/* rotate: 2700 mm is stored as 2700 * 8 = 21600; 9870 mm, past 8191,
	 * as (9870 << 3 & 0xffff) | 9870 >> 13 = 13424 | 1 */
	image16(&img, (const uint16_t[]){ 21600, 13425, 0 }, 3);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_ROTATE, &err) == 0);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 2700, 0);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 9870, 0);
	CHECK_NEAR(fct_image_get(&img, 2, 0, 0), 0, 0);
	fct_image_free(&img);
	/* kinect-raw: 839 -> 351.3 / 253.5 = 1.38580 m (NYU's nearest), 1057
	 * -> 9.8958 m; 1091 -> 234.2 m; 1092 and 2047 no data */
	image16(&img, (const uint16_t[]){ 839, 1057, 1091, 1092, 2047 }, 5);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_KINECT_RAW, &err) == 0);
	CHECK_INT(img.type, FCT_PIX_F32);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 351.3 / 253.5, 1e-6);
	CHECK_NEAR(fct_image_get(&img, 1, 0, 0), 351.3 / 35.5, 1e-5);
	CHECK_NEAR(fct_image_get(&img, 2, 0, 0), 234.2, 1e-4);
	CHECK_NEAR(fct_image_get(&img, 3, 0, 0), 0, 0);
	CHECK_NEAR(fct_image_get(&img, 4, 0, 0), 0, 0);
	fct_image_free(&img);
	/* nyu: 839 written little-endian and read as the format says */
	image16(&img, (const uint16_t[]){ (uint16_t)(839 >> 8 | 839 << 8) }, 1);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW, &err) == 0);
	CHECK_NEAR(fct_image_get(&img, 0, 0, 0), 351.3 / 253.5, 1e-6);
	fct_image_free(&img);
	/* no code: nothing happens, whatever the image */
	CHECK(fct_image_alloc(&img, 2, 2, 3, FCT_PIX_U8, &err) == 0);
	CHECK(fct_depth_decode(&img, 0, &err) == 0);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_ROTATE, &err) == -1);
	CHECK_STR(err.msg, "a depth code needs a one-channel 16-bit image, not 3 channels of u8");
	fct_image_free(&img);
	CHECK(fct_image_alloc(&img, 2, 2, 1, FCT_PIX_F32, &err) == 0);
	CHECK(fct_depth_decode(&img, FCT_DEPTH_SWAP, &err) == -1);
	CHECK_STR(err.msg, "a depth code needs a one-channel 16-bit image, not 1 channel of f32");
	fct_image_free(&img);
}

int main(void)
{
	test_names();
	test_decode();
	CHECK_DONE();
}
