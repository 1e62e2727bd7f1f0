/* depthopts.h - the depth-image options that dm2mesh and planarize share:
 * their getopt_long entries and parsing, the camera and noise model they
 * resolve once the image's size is known, and the header comments of the
 * mesh made from them.  One table, so that both programs read a depth image
 * the same way (dm2mesh(1) documents every option).
 *
 * Like cli.h this is command-line layer, for mains only: a usage error
 * prints "prog: ..." and exits 2, an unreadable camera, pose or noise file
 * prints one line and exits 1.
 *
 * Short options: -K and -j (put "j:K:" in the program's optstring). */
#ifndef FCT_DEPTHOPTS_H
#define FCT_DEPTHOPTS_H

#include <getopt.h>

#include "io/camera.h"
#include "depth/depthmesh.h"
#include "io/image.h"
#include "core/mesh.h"

/* getopt_long codes of the long options, above any program's own. */
enum {
	FCT_DOPT_CAMERA = 0x1000, FCT_DOPT_CYL, FCT_DOPT_SCALE, FCT_DOPT_BASELINE, FCT_DOPT_FOCAL,
	FCT_DOPT_DOFFS, FCT_DOPT_RANGE, FCT_DOPT_STEP, FCT_DOPT_ANGLE, FCT_DOPT_NOISE, FCT_DOPT_POSE,
	FCT_DOPT_IMAGE, FCT_DOPT_CODE
};

/* The long options' entries, for a program's struct option table. */
#define FCT_DEPTH_LONGOPTS \
	{"camera", required_argument, NULL, FCT_DOPT_CAMERA}, \
	{"cylindrical", required_argument, NULL, FCT_DOPT_CYL}, \
	{"depth-scale", required_argument, NULL, FCT_DOPT_SCALE}, \
	{"baseline", required_argument, NULL, FCT_DOPT_BASELINE}, \
	{"focal", required_argument, NULL, FCT_DOPT_FOCAL}, \
	{"doffs", required_argument, NULL, FCT_DOPT_DOFFS}, \
	{"range", required_argument, NULL, FCT_DOPT_RANGE}, \
	{"step", required_argument, NULL, FCT_DOPT_STEP}, \
	{"max-angle", required_argument, NULL, FCT_DOPT_ANGLE}, \
	{"noise", required_argument, NULL, FCT_DOPT_NOISE}, \
	{"pose", required_argument, NULL, FCT_DOPT_POSE}, \
	{"image", required_argument, NULL, FCT_DOPT_IMAGE}, \
	{"depth-code", required_argument, NULL, FCT_DOPT_CODE}

struct fct_depth_opts {
	const char *K, *camera_file, *cylindrical, *noise, *pose_file, *image_file;
	const char *first;         /* the first depth option given but --noise
	                              (a mesh takes that too), for messages */
	int scale_given, doffs_given, code_given;
	double focal;              /* --focal (0: the camera's) */
	int has_pose;
	double pose[12];           /* --pose, read by fct_depth_opts_read_pose */
	int double_xyz;            /* set by fct_depth_opts_finish: positions kept as double */
	struct fct_depth_params depth;
};

/* Everything off, the depth parameters at their defaults. */
void fct_depth_opts_init(struct fct_depth_opts *o);

/* Take getopt_long's c (with optarg arg) when it is a depth option ('K',
 * 'j' or a FCT_DOPT_ code): 1, or 0 when it is the program's own. */
int fct_depth_opt(struct fct_depth_opts *o, int c, const char *arg);

/* After the options: what they cannot mean together (--focal without
 * --baseline), a --noise model parsed.  Exit 2. */
void fct_depth_opts_check(struct fct_depth_opts *o);

/* --pose read into o->pose (exit 1 on a bad file); nothing without it. */
void fct_depth_opts_read_pose(struct fct_depth_opts *o);

/* The camera the options name (fct_opt_camera for -K and --camera); a
 * size-less camera takes width x height (0 for sparse points without an
 * image).  required: no camera is a usage error; else cam->kind stays
 * FCT_CAMERA_NONE.  A dataset name sets the depth scale unless
 * --depth-scale was given; a stereo calibration (Middlebury's calib.txt)
 * makes the image disparities with its baseline and doffs unless --baseline
 * or --doffs was given. */
void fct_depth_opts_camera(struct fct_depth_opts *o, struct fct_camera *cam, int width, int height,
                           int required);

/* For the depth image img (named name in messages): decoded by --depth-code
 * (else the code -K's dataset name implies; exit 1 when img cannot be so
 * decoded), the camera (required),
 * the focal length of disparities (--doffs without them is a usage error),
 * the noise model (--noise's, else the dataset's for a camera name) with the
 * unit of img's depth encoding; a warning when img's depths are implausible
 * for a known RGB-D camera (fct_depth_implausible: a wrong depth scale). */
void fct_depth_opts_resolve(struct fct_depth_opts *o, struct fct_camera *cam,
                            struct fct_image *img, const char *name);

/* The mesh made from the options: its vertices moved by the pose (kept as
 * double, o->double_xyz set, when float cannot hold world coordinates to
 * 1/100 of the nearest vertex's pixel footprint: fct_mesh_keep_precision),
 * and the camera, noise, pose and TextureFile (--image) comments.  0 or -1. */
int fct_depth_opts_finish(struct fct_depth_opts *o, struct fct_mesh *m,
                          const struct fct_camera *cam, struct fct_err *err);

#endif
