/* fuzz_depth - libFuzzer target: any bytes, read as a depth image, meshed
 * through a pinhole or a cylindrical camera of the image's size (dm2mesh's
 * path; every other size with the kinect noise model, and of those every
 * other smoothed first as tsdfuse smooths it; the size's next bits a depth
 * code to decode it by first), then freed.  A crash, leak,
 * sanitizer report or huge allocation is a bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "depth/depthcode.h"
#include "depth/depthmesh.h"
#include "depth/depthsmooth.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size == 0)
		return 0;
	FILE *f = fmemopen((void *)data, size, "rb");
	if (!f)
		return 0;
	struct fct_image img;
	struct fct_err err;
	int read = fct_image_read_stream(&img, f, "fuzz", NULL, &err) == 0;
	if (read && fct_depth_decode(&img, (unsigned)(size >> 3) & 7, &err)) {
		fct_image_free(&img);
		read = 0;
	}
	if (read) {
		struct fct_camera cam = { FCT_CAMERA_PINHOLE, img.width, img.height, 50, 50,
		                          img.width / 2.0, img.height / 2.0, 0, 0 };
		if (size & 1)
			cam.kind = FCT_CAMERA_CYLINDRICAL, cam.f = img.width / 6.28;
		struct fct_depth_params p;
		fct_depth_params_default(&p);
		p.step = 1 + (int)(size % 3);
		if (size & 2)   /* sigma and the jump test's noise term */
			fct_noise_kinect(&p.noise);
		struct fct_image sm;
		if ((size & 6) == 6) {   /* smoothed in units of that noise, for 4 cm voxels */
			struct fct_depth_smooth sp;
			fct_depth_smooth_default(&sp);
			sp.voxel = 0.04;
			if (fct_depth_smooth_image(&sm, &img, &cam, &p, &sp, &err) == 0) {
				fct_image_free(&img);
				img = sm;
			}
		}
		struct fct_mesh m;
		if (fct_depth_mesh(&m, &img, &cam, &p, NULL, &err) == 0)
			fct_mesh_free(&m);
		fct_image_free(&img);
	}
	fclose(f);
	return 0;
}
