/* gen_depth - bench inputs for dm2mesh.
 *   gen_depth W H       a W x H 16-bit depth PNG (millimetres) on stdout: a
 *                       wall 3 m away seen at an angle, with a box standing
 *                       out 0.5 m from it (discontinuities), 1 mm noise and
 *                       2% of pixels without data
 *   gen_depth -p N      N random sparse points "u v x y z" on the same scene,
 *                       seen by a 640x480 camera with f = 525
 * The camera of the depth image is -K F,F,(W-1)/2,(H-1)/2 with F = 0.8 W. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "io/image.h"
#include "core/rng.h"

/* Depth in metres along the ray (x, y, 1) of normalised image coordinates. */
static double scene_depth(double x, double y)
{
	double wall = 3 / (1 + 0.3 * x);
	if (fabs(x) < 0.15 && fabs(y) < 0.15)
		return wall - 0.5;
	return wall;
}

int main(int argc, char **argv)
{
	fct_cli_init("gen_depth");
	struct fct_rng rng;
	struct fct_err err;
	fct_rng_seed(&rng, 12345);
	if (argc == 3 && !strcmp(argv[1], "-p")) {
		long n = fct_opt_long("N", argv[2], 1, 100000000);
		for (long i = 0; i < n; i++) {
			double u = fct_rng_uniform(&rng) * 639, v = fct_rng_uniform(&rng) * 479;
			double x = (u - 319.5) / 525, y = (v - 239.5) / 525, z = scene_depth(x, y);
			printf("%.4f %.4f %.6f %.6f %.6f\n", u, v, x * z, y * z, z);
		}
		return fflush(stdout) ? 1 : 0;
	}
	if (argc != 3)
		fct_usage_error("usage: gen_depth W H | gen_depth -p N");
	int w = (int)fct_opt_long("W", argv[1], 1, 65536), h = (int)fct_opt_long("H", argv[2], 1, 65536);
	struct fct_image img;
	if (fct_image_alloc(&img, w, h, 1, FCT_PIX_U16, &err))
		fct_die_err(&err);
	uint16_t *px = img.data;
	double f = 0.8 * w;
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			double z = scene_depth((i - (w - 1) / 2.0) / f, (j - (h - 1) / 2.0) / f);
			z += 0.001 * fct_rng_normal(&rng);
			px[(size_t)j * w + i] = fct_rng_uniform(&rng) < 0.02 ? 0 : (uint16_t)lround(z * 1000);
		}
	if (fct_png_write(&img, stdout, &err))
		fct_die_err(&err);
	fct_image_free(&img);
	return 0;
}
