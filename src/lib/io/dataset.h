/* dataset.h - an RGB-D sequence's folder as its dataset lays it out, read
 * into depth frames, their colour images and their poses (the files that
 * tsdfuse and viewtex take as operands, --image and --poses):
 *
 *   7-Scenes seq-NN   frame-NNNNNN.depth.png, frame-NNNNNN.color.png (or
 *                     .color.jpg), frame-NNNNNN.pose.txt: the frames in
 *                     the order of their names, a pose file each
 *   TUM RGB-D         depth.txt and rgb.txt ("timestamp file" per line,
 *                     '#' comments) and groundtruth.txt: each depth frame
 *                     with the colour image nearest in time, and the
 *                     ground truth's pose nearest in time, each within
 *                     max_diff seconds (TUM's associate.py); frames
 *                     without either are left out
 *   Redwood / Open3D  depth/ and color/ (or image/ or rgb/), an image per
 *                     frame each (PNG or JPEG), paired in the order of
 *                     their names; the trajectory in trajectory.log,
 *                     scene/trajectory.log (where Open3D's reconstruction
 *                     system writes it) or the folder's one .log file;
 *                     camera_intrinsic.json (Open3D's intrinsics) when
 *                     there, else the PrimeSense camera Redwood used
 *
 * Paths are the folder joined to the names it holds. */
#ifndef FCT_DATASET_H
#define FCT_DATASET_H

#include <stddef.h>

#include "core/err.h"

struct fct_dataset {
	const char *layout;      /* "7-Scenes", "TUM" or "Redwood" */
	const char *camera;      /* the camera's name (camera.h): 7scenes, tum, tum1..3,
	                          * redwood; its depth units and noise */
	char *intrinsics;        /* the folder's intrinsics file (--camera's forms), whose
	                          * focal lengths and centre replace the named camera's;
	                          * NULL when it has none */
	size_t n;                /* frames */
	char **depth, **color;   /* n paths each */
	char **poses;            /* npose files: n (7-Scenes) or 1 (TUM) */
	size_t nposes;
	double max_diff;         /* TUM: the largest time difference matched (s) */
};

/* Read the folder dir into d (fct_dataset_free).  0, or -1 ("DIR: not a
 * 7-Scenes, TUM or Redwood sequence folder (...)", "DIR/rgb.txt:LINE: ...", a
 * frame without its colour image or pose, no frame). */
int fct_dataset_read(struct fct_dataset *d, const char *dir, double max_diff, struct fct_err *err);
void fct_dataset_free(struct fct_dataset *d);

#endif
