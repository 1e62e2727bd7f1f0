/* fuzz_points - libFuzzer target: any bytes, read as dm2mesh --points input
 * (text lines or PLY), triangulated by Delaunay and cut by the jump and
 * edge tests, then freed.  A crash, leak, sanitizer report, hang or huge
 * allocation is a bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "depth/sparsemesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size == 0)
		return 0;
	FILE *f = fmemopen((void *)data, size, "rb");
	if (!f)
		return 0;
	struct fct_image_points pts;
	struct fct_err err;
	if (fct_image_points_read_stream(&pts, f, "fuzz", &err) == 0) {
		struct fct_camera cam = { FCT_CAMERA_PINHOLE, 64, 48, 50, 50, 32, 24, 0, 0 };
		struct fct_sparse_params p = { 10, size & 1 ? 1.0 : 1e300 };
		struct fct_mesh m;
		if (fct_sparse_mesh(&m, &pts, &cam, &p, NULL, &err) == 0)
			fct_mesh_free(&m);
		fct_image_points_free(&pts);
	}
	fclose(f);
	return 0;
}
