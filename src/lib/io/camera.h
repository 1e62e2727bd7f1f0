/* camera.h - the two camera models of DESIGN.md, poses, and the files and
 * names users give them in.
 *
 * Pinhole (OpenCV): x right, y down, z forward; pixel centres at integer
 * (u, v); depth is the camera-frame z.
 * Cylindrical: pixel centre u has angle theta = theta0 + 2 pi u / W, row v the
 * height h = (v - cy) / f; the ray is (sin theta, h, cos theta) and depth is
 * the distance rho from the vertical axis.
 *
 * In both models the point seen at (u, v) with depth d is d * ray(u, v), so
 * one back-projection serves both. */
#ifndef FCT_CAMERA_H
#define FCT_CAMERA_H

#include "core/err.h"

enum fct_camera_kind { FCT_CAMERA_NONE, FCT_CAMERA_PINHOLE, FCT_CAMERA_CYLINDRICAL };

struct fct_camera {
	enum fct_camera_kind kind;
	int width, height;       /* 0 when not known yet (a bare K matrix) */
	double fx, fy, cx, cy;   /* pinhole */
	double f, theta0;        /* cylindrical; cy is shared with pinhole */
};

/* The ray through pixel (u, v), scaled so that point = depth * ray. */
void fct_camera_ray(const struct fct_camera *cam, double u, double v, double ray[3]);

/* The lateral size of one pixel per unit depth: the geometric mean of the
 * horizontal and vertical pixel angles (1 / sqrt(fx fy) for a pinhole,
 * sqrt(2 pi / (W f)) for a cylinder); 0 without a camera or its width. */
double fct_camera_pixel_angle(const struct fct_camera *cam);

/* Pixel (u, v) and depth of camera-frame point p; 0 when p has none (behind
 * a pinhole camera, or on the cylinder's axis), 1 otherwise.  Cylindrical u is
 * in [-0.5, W - 0.5), wrapped around the seam. */
int fct_camera_project(const struct fct_camera *cam, const double p[3], double *u, double *v,
                       double *depth);

/* A texture coordinate scaled to pixels (s W or t H, pixel centres at
 * k + 0.5 in these units) within 1e-3 pixel of a centre is put on it:
 * dm2mesh's vertices sit on pixel centres but float s t miss them by up to
 * 1e-4 pixel, which turns three vertices on one image line into a sliver. */
double fct_snap_pixel_centre(double x);

/* Parse the text of a camera comment after "camera": "pinhole W H fx fy cx cy"
 * or "cylindrical W H f cy theta0".  0 or -1 (message set). */
int fct_camera_parse(const char *text, struct fct_camera *cam, struct fct_err *err);
/* The same text, numbers in %.17g (at most 256 bytes with the terminator). */
void fct_camera_format(const struct fct_camera *cam, char *buf, size_t size);

/* A camera by dataset name (tum, tum1, tum2, tum3, redwood, primesense,
 * kinect, icl-nuim, 7scenes): 0, or -1 for an unknown name.  *depth_scale
 * gets the dataset's depth units per metre. */
int fct_camera_named(const char *name, struct fct_camera *cam, double *depth_scale);
/* The names fct_camera_named knows, blank-separated. */
const char *fct_camera_names(void);

/* The dataset camera of fct_camera_named whose intrinsics are cam's (a
 * pinhole of 640 x 480, or of no size yet, with fx fy cx cy within 1%),
 * preferring one whose depth scale is not_scale's other (several datasets
 * share one K): its name, or NULL.  *depth_scale (may be NULL) gets its
 * depth units per metre.  Knowing the sensor tells which depths are
 * plausible (fct_depth_implausible). */
const char *fct_camera_known(const struct fct_camera *cam, double not_scale, double *depth_scale);

/* What a stereo calibration adds to the camera: disparity d (pixels) is
 * depth = baseline * f / (d + doffs). */
struct fct_stereo {
	double baseline;         /* metres; 0: not a stereo calibration */
	double doffs;            /* pixels: the difference of the two cameras' cx */
};

/* Read an intrinsics file: Open3D's PinholeCameraIntrinsic JSON, a 3x3 K
 * matrix as text (width and height then stay 0), a camera line as in the
 * header comment (with or without "comment camera" before it), or a
 * Middlebury stereo calib.txt (cam0=[fx 0 cx; 0 fy cy; 0 0 1], doffs,
 * baseline in millimetres, width, height), whose baseline and doffs go to
 * stereo (may be NULL; zero for the other forms).  0 or -1. */
int fct_camera_read_stereo(struct fct_camera *cam, struct fct_stereo *stereo, const char *path,
                           struct fct_err *err);
/* fct_camera_read_stereo without the stereo part. */
int fct_camera_read_file(const char *path, struct fct_camera *cam, struct fct_err *err);

/* The whole of a small text file (at most 64 KB: a camera, pose or noise
 * file), NUL-terminated, malloc'd; NULL with a message naming path when it
 * cannot be read, is larger or holds a NUL byte. */
char *fct_read_small_text(const char *path, struct fct_err *err);

/* Poses: camera-to-world as a row-major 3x4 matrix [R | t]. */

/* Read a pose file: a 4x4 or 3x4 matrix as text (12 or 16 numbers, as the
 * 7-Scenes and Redwood pose files), or a "pose r11 ... t3" line (with or
 * without "comment").  R must be a rotation (to 1e-3).  0 or -1. */
int fct_pose_read_file(const char *path, double pose[12], struct fct_err *err);
/* 0 when R of pose is a rotation to within tol, -1 otherwise (message set). */
int fct_pose_check(const double pose[12], double tol, struct fct_err *err);
/* out = R p + t (out may be p).  Inline: passes over every vertex of a
 * view call it. */
static inline void fct_pose_apply(const double pose[12], const double p[3], double out[3])
{
	double x = p[0], y = p[1], z = p[2];
	for (int i = 0; i < 3; i++)
		out[i] = pose[4 * i] * x + pose[4 * i + 1] * y + pose[4 * i + 2] * z + pose[4 * i + 3];
}
/* The inverse pose: [R^T | -R^T t] when R is a rotation to rounding, else
 * the inverse of the 3x4 matrix as it is (a pose whose R has drifted off
 * a rotation, as 7-Scenes' have, still maps its points back). */
void fct_pose_invert(const double pose[12], double inv[12]);

/* The rotation of unit quaternion (x, y, z, w) as the R of pose (t = 0). */
void fct_quat_pose(double x, double y, double z, double w, double pose[12]);

#endif
