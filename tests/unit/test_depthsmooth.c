/* test_depthsmooth - the noise-aware smoothing of depth images
 * (depthsmooth.h): on a slanted plane under the kinect model's quantised
 * disparity noise the error to the plane falls by the factor the window's
 * weights give; a plane without noise stays that plane (inverse depth
 * averaged); across a depth step of 12 sigma no pixel takes the other
 * side's depth; no model, or radius 0, copies; bad input. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "depth/depthsmooth.h"
#include "scene/scene.h"

enum { W = 96, H = 72 };

/* A plane seen by a pinhole of focal 80 px: inverse depth affine in the
 * pixel, 1/z = a + b x + c y, from 2.2 m at the left to 3.4 m at the right
 * and tilted in y. */
static double plane_depth(size_t x, size_t y)
{
	return 1 / (1 / 2.2 + (1 / 3.4 - 1 / 2.2) * (double)x / (W - 1) + 0.01 * (double)y / (H - 1));
}

static struct fct_noise kinect(void)
{
	struct fct_noise nz;
	fct_noise_kinect(&nz);
	return nz;
}

static void test_plane_noise(void)
{
	static float truth[W * H], noisy[W * H], out[W * H];
	static double t[W * H], o[W * H];
	for (size_t y = 0; y < H; y++)
		for (size_t x = 0; x < W; x++)
			t[y * W + x] = plane_depth(x, y);
	struct fct_scene_noise sn = { 0 };
	sn.grazing = 90;
	sn.sensor = kinect();
	fct_depth_noise(&sn, 7, 0, t, NULL, NULL, o, (size_t)W * H, NULL);
	for (size_t i = 0; i < (size_t)W * H; i++)
		truth[i] = (float)t[i], noisy[i] = (float)o[i];
	struct fct_depth_smooth p;
	fct_depth_smooth_default(&p);
	struct fct_err err;
	struct fct_noise nz = kinect();
	CHECK(fct_depth_smooth(out, noisy, W, H, 1 / 80.0, &nz, &p, &err) == 0);
	/* Interior pixels (the full window): rms error to the plane in units
	 * of the model's sigma, before and after. */
	double e0 = 0, e1 = 0;
	size_t n = 0;
	for (size_t y = 2; y + 2 < H; y++)
		for (size_t x = 2; x + 2 < W; x++) {
			size_t i = y * W + x;
			double s = fct_noise_sigma(&nz, truth[i]);
			e0 += (noisy[i] - truth[i]) * (noisy[i] - truth[i]) / (s * s);
			e1 += (out[i] - truth[i]) * (out[i] - truth[i]) / (s * s);
			n++;
		}
	e0 = sqrt(e0 / (double)n), e1 = sqrt(e1 / (double)n);
	/* The noise is the model's; the spatial weights of the 5 x 5 window
	 * (s = 1.25 px) sum to 8.2 and their squares to 3.6, so their mean of
	 * independent samples has 0.23 of their deviation.  The range kernel
	 * leaves some more (0.32 here; one pass, 0.55). */
	CHECK_MSG(e0 > 0.85 && e0 < 1.15, "noisy rms %g sigma", e0);
	CHECK_MSG(e1 > 0.2 && e1 < 0.36, "smoothed rms %g sigma", e1);
	/* Without noise the plane stays: inverse depth is averaged, and it is
	 * affine over the window; only the range weights, which are not
	 * symmetric where depth changes faster than sigma per pixel (15 mm a
	 * pixel at 3 m here), move it, by a hundredth of sigma. */
	struct fct_noise kz = kinect();
	CHECK(fct_depth_smooth(out, truth, W, H, 1 / 80.0, &kz, &p, &err) == 0);
	double worst = 0;
	for (size_t y = 2; y + 2 < H; y++)
		for (size_t x = 2; x + 2 < W; x++) {
			size_t i = y * W + x;
			worst = fmax(worst, fabs(out[i] - truth[i]) / fct_noise_sigma(&kz, truth[i]));
		}
	CHECK_MSG(worst < 0.01, "plane moved by %g sigma", worst);
}

/* Two fronto-parallel planes 12 sigma apart (at 3 m: 0.154 m), the
 * nearer on the left half, with holes (no data): every pixel stays on its
 * plane exactly, holes stay holes, non-finite samples are no data. */
static void test_step(void)
{
	static float in[W * H], out[W * H];
	struct fct_noise nz = kinect();
	double far = 3, near = far - 12 * fct_noise_sigma(&nz, far);
	for (size_t y = 0; y < H; y++)
		for (size_t x = 0; x < W; x++)
			in[y * W + x] = (float)(x < W / 2 ? near : far);
	in[10 * W + 10] = 0;
	in[11 * W + 60] = NAN;
	in[12 * W + 61] = INFINITY;
	in[13 * W + 62] = -1;
	struct fct_depth_smooth p;
	fct_depth_smooth_default(&p);
	struct fct_err err;
	CHECK(fct_depth_smooth(out, in, W, H, 1 / 80.0, &nz, &p, &err) == 0);
	size_t moved = 0;
	for (size_t y = 0; y < H; y++)
		for (size_t x = 0; x < W; x++) {
			size_t i = y * W + x;
			if (in[i] > 0 && in[i] < INFINITY)
				moved += fabs(out[i] - in[i]) > 1e-6 * in[i];
		}
	CHECK_INT(moved, 0);
	CHECK(out[10 * W + 10] == 0);
	CHECK(out[11 * W + 60] == 0);
	CHECK(out[12 * W + 61] == 0);
	CHECK(out[13 * W + 62] == 0);
}

/* No model, or radius 0: a copy (non-finite samples as 0); a range that
 * is not positive is refused. */
static void test_copy(void)
{
	float in[4] = { 1.5f, NAN, 2.5f, -3 }, out[4];
	struct fct_noise none = { .model = FCT_NOISE_UNKNOWN };
	struct fct_depth_smooth p;
	fct_depth_smooth_default(&p);
	struct fct_err err;
	CHECK(fct_depth_smooth(out, in, 2, 2, 1 / 80.0, &none, &p, &err) == 0);
	CHECK(out[0] == 1.5f && out[1] == 0 && out[2] == 2.5f && out[3] == 0);
	struct fct_noise nz = kinect();
	p.radius = 0;
	CHECK(fct_depth_smooth(out, in, 2, 2, 1 / 80.0, &nz, &p, &err) == 0);
	CHECK(out[0] == 1.5f && out[1] == 0 && out[2] == 2.5f && out[3] == 0);
	p.radius = 2, p.range = 0;
	CHECK(fct_depth_smooth(out, in, 2, 2, 1 / 80.0, &nz, &p, &err) == -1);
	CHECK_STR(err.msg, "depth smoothing: range 0 is not positive");
}

/* A 16-bit PNG-like image in millimetres: smoothed into metres, and the
 * parameters then read those metres (no scale, no disparity) with the
 * model's unit set to the encoding's millimetre. */
static void test_image(void)
{
	struct fct_image img;
	struct fct_err err;
	CHECK(fct_image_alloc(&img, 8, 8, 1, FCT_PIX_U16, &err) == 0);
	for (int i = 0; i < 64; i++)
		((uint16_t *)img.data)[i] = (uint16_t)(2000 + (i % 3));
	((uint16_t *)img.data)[9] = 0;
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	fct_noise_kinect(&dp.noise);
	struct fct_depth_smooth p;
	fct_depth_smooth_default(&p);
	struct fct_image out;
	struct fct_camera cam = { .kind = FCT_CAMERA_PINHOLE, .width = 8, .height = 8, .fx = 80, .fy = 80, .cx = 3.5, .cy = 3.5 };
	CHECK(fct_depth_smooth_image(&out, &img, &cam, &dp, &p, &err) == 0);
	CHECK_INT(out.type, FCT_PIX_F32);
	CHECK_INT(out.width, 8);
	CHECK_NEAR(dp.noise.unit, 0.001, 1e-15);
	CHECK_INT(dp.scale_float, 0);
	CHECK_NEAR(fct_depth_at(&out, 3, 3, &dp), 2.001, 0.001);
	CHECK(fct_depth_at(&out, 1, 1, &dp) == 0);
	fct_image_free(&out);
	fct_image_free(&img);
}

int main(void)
{
	test_plane_noise();
	test_step();
	test_copy();
	test_image();
	CHECK_DONE();
}
