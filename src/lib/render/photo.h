/* photo.h - registered colour photographs: an image file seen by a pinhole
 * camera at a camera-to-world pose, as viewtex and its judge take them
 * (one camera for all, poses from poses.h).  The image is read only
 * when asked, one at a time, through the library's image reader (any
 * format it reads). */
#ifndef FCT_PHOTO_H
#define FCT_PHOTO_H

#include <stddef.h>

#include "io/camera.h"
#include "io/image.h"

struct fct_photo {
	const char *path;         /* the image file (not owned) */
	struct fct_camera cam;    /* width 0 until the image is read, when not given */
	double pose[12];          /* camera-to-world */
};

/* Photos of images[0..n) with camera cam (a pinhole; its size may be 0)
 * and poses from pose_files (fct_frame_poses: a file per image, or one
 * trajectory of any format by order, timestamp or frame number, TUM's
 * within 0.02 s).  *out is malloc'd (n
 * entries; its paths point into images).  0, or -1: not a pinhole with
 * positive focal lengths, a pose that is not a finite rotation ("IMAGE:
 * pose: ..."), what fct_frame_poses refuses. */
int fct_photos_make(struct fct_photo **out, const struct fct_camera *cam,
                    const char *const *images, size_t n, const char *const *pose_files,
                    size_t npose_files, struct fct_err *err);

/* Most pixels of a photo: 64 M (an 8K x 8K picture); its visibility
 * buffer takes 16 bytes a pixel. */
#define FCT_PHOTO_MAX_PIXELS ((size_t)1 << 26)

/* Read photo p's image as RGB U8 into rgb (set up here, fct_image_free),
 * and its camera fitted to the image into cam: a camera without a size
 * takes the image's; a camera of another size with the same aspect (to
 * 1%) is scaled to it, the field of view kept; any other is refused.
 * Sides are bounded by max_side, pixels by FCT_PHOTO_MAX_PIXELS.  0 or
 * -1 ("PATH: ..."). */
int fct_photo_read(const struct fct_photo *p, int max_side, struct fct_image *rgb,
                   struct fct_camera *cam, struct fct_err *err);

#endif
