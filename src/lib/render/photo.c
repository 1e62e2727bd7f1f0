/* photo.c - registered colour photographs; see photo.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/photo.h"
#include "render/raster.h"
#include "io/poses.h"

int fct_photos_make(struct fct_photo **out, const struct fct_camera *cam,
                    const char *const *images, size_t n, const char *const *pose_files,
                    size_t npose_files, struct fct_err *err)
{
	*out = NULL;
	if (cam->kind != FCT_CAMERA_PINHOLE || !(cam->fx > 0 && cam->fy > 0) ||
	    !isfinite(cam->fx + cam->fy + cam->cx + cam->cy))
		return fct_fail(err, "the photos' camera must be a pinhole with positive focal lengths");
	struct fct_photo *p = fct_alloc_array(n, sizeof *p, err);
	double *poses = fct_alloc_array(n, 12 * sizeof *poses, err);
	if (!p || !poses ||
	    fct_frame_poses(poses, NULL, pose_files, npose_files, images, n, 0.02, err)) {
		free(p);
		free(poses);
		return -1;
	}
	for (size_t i = 0; i < n; i++) {
		p[i].path = images[i];
		p[i].cam = *cam;
		memcpy(p[i].pose, poses + 12 * i, sizeof p[i].pose);
		if (fct_pose_check(p[i].pose, 1e-3, err)) {
			fct_err_prefix(err, "%s", images[i]);
			free(p);
			free(poses);
			return -1;
		}
	}
	free(poses);
	*out = p;
	return 0;
}

int fct_photo_read(const struct fct_photo *p, int max_side, struct fct_image *rgb,
                   struct fct_camera *cam, struct fct_err *err)
{
	struct fct_image raw;
	memset(rgb, 0, sizeof *rgb);
	if (fct_image_read_file(&raw, p->path, NULL, err))
		return -1;
	int W = raw.width, H = raw.height;
	*cam = p->cam;
	int rc = 0;
	if (W > max_side || H > max_side || (size_t)W * (size_t)H > FCT_PHOTO_MAX_PIXELS) {
		rc = fct_fail(err, "%s: image of %dx%d pixels: larger than %d on a side or %zu in all",
		              p->path, W, H, max_side, (size_t)FCT_PHOTO_MAX_PIXELS);
	} else if (cam->width <= 0 || cam->height <= 0) {
		cam->width = W, cam->height = H;
	} else if (cam->width != W || cam->height != H) {
		double a = (double)cam->width / cam->height, b = (double)W / H;
		if (!(fabs(a / b - 1) <= 0.01)) {
			rc = fct_fail(err, "%s: image is %dx%d, the camera %dx%d (another aspect)", p->path,
			              W, H, cam->width, cam->height);
		} else {
			/* The same field of view at the image's size, as
			 * fct_view_from_camera draws it. */
			double sx = (double)W / cam->width, sy = (double)H / cam->height;
			cam->fx *= sx, cam->fy *= sy;
			cam->cx = (cam->cx + 0.5) * sx - 0.5, cam->cy = (cam->cy + 0.5) * sy - 0.5;
			cam->width = W, cam->height = H;
		}
	}
	static const unsigned char black[3] = { 0, 0, 0 };
	if (!rc && fct_image_to_rgb8(&raw, black, rgb, err)) {
		fct_err_prefix(err, "%s", p->path);
		rc = -1;
	}
	fct_image_free(&raw);
	return rc;
}
