/* fuseopts.h - the options of a depth-image fusion that tsdfuse and
 * roommodel share: their getopt_long entries and parsing, and the camera,
 * depth units and noise model they resolve.  One table, so that both
 * programs fuse depth images the same way (tsdfuse(1) documents every
 * option; each program's --help says what it takes).
 *
 * Like cli.h this is command-line layer, for mains only: a usage error
 * prints "prog: ..." and exits 2, an unreadable camera or noise file prints
 * one line and exits 1.
 *
 * Short option: -K (put "K:" in the program's optstring). */
#ifndef FCT_FUSEOPTS_H
#define FCT_FUSEOPTS_H

#include <getopt.h>

#include "io/camera.h"
#include "depth/depthmesh.h"
#include "depth/depthsmooth.h"
#include "fusion/fuse.h"

/* getopt_long codes of the long options, above any program's own and
 * depthopts.h's. */
enum {
	FCT_FOPT_CAMERA = 0x1100, FCT_FOPT_SCALE, FCT_FOPT_NOISE, FCT_FOPT_SMOOTH, FCT_FOPT_POSES,
	FCT_FOPT_IMAGE, FCT_FOPT_MAXDIFF, FCT_FOPT_VOXEL, FCT_FOPT_TRUNC, FCT_FOPT_THREADS,
	FCT_FOPT_CODE
};

/* The long options' entries, for a program's struct option table. */
#define FCT_FUSE_LONGOPTS \
	{"camera", required_argument, NULL, FCT_FOPT_CAMERA}, \
	{"depth-scale", required_argument, NULL, FCT_FOPT_SCALE}, \
	{"noise", required_argument, NULL, FCT_FOPT_NOISE}, \
	{"smooth", required_argument, NULL, FCT_FOPT_SMOOTH}, \
	{"poses", required_argument, NULL, FCT_FOPT_POSES}, \
	{"image", required_argument, NULL, FCT_FOPT_IMAGE}, \
	{"max-difference", required_argument, NULL, FCT_FOPT_MAXDIFF}, \
	{"voxel", required_argument, NULL, FCT_FOPT_VOXEL}, \
	{"trunc", required_argument, NULL, FCT_FOPT_TRUNC}, \
	{"threads", required_argument, NULL, FCT_FOPT_THREADS}, \
	{"depth-code", required_argument, NULL, FCT_FOPT_CODE}

struct fct_fuse_opts {
	const char *K, *camera, *noise;
	const char **poses, **images;   /* --poses and --image files, in order */
	size_t nposes, nimages;
	int scale_given, code_given;
	double depth_scale;             /* --depth-scale (default 1000) */
	unsigned code;                  /* --depth-code (depthcode.h) */
	double voxel, voxel_min, voxel_max;   /* --voxel and its bounds */
	double trunc;                   /* --trunc: the band in voxels (default 3) */
	double max_diff;                /* --max-difference (default 0.02 s) */
	struct fct_depth_smooth smooth; /* --smooth */
	int exact;                      /* tsdfuse --exact: depth images searched at every pixel */
	struct fct_fuse_params fp;      /* --threads; band set by fct_fuse_opts_check */
};

/* The defaults, with the program's voxel size and --voxel's bounds; room
 * for the repeated options of a command line of argc words (exit 1 when
 * out of memory). */
void fct_fuse_opts_init(struct fct_fuse_opts *o, int argc, double voxel, double voxel_min,
                        double voxel_max);
void fct_fuse_opts_free(struct fct_fuse_opts *o);

/* Take getopt_long's c (with optarg arg) when it is a fusion option ('K' or
 * a FCT_FOPT_ code): 1, or 0 when it is the program's own. */
int fct_fuse_opt(struct fct_fuse_opts *o, int c, const char *arg);

/* After the options: the band (--trunc voxels of --voxel) and the
 * smoothing's voxel set, a --noise that names a model parsed (a usage error
 * "--noise: ..." when malformed). */
void fct_fuse_opts_check(struct fct_fuse_opts *o);

/* The depth images' camera (-K or --camera; kind NONE without either) and
 * depth parameters: units (--depth-scale, else -K's dataset's, else 1000 per
 * metre), depth code (--depth-code, else -K's dataset's), focal length, no texture coordinates, the noise (--noise's model
 * or file, else -K's dataset's, else none).  stereo (may be NULL): a stereo
 * calibration's baseline and doffs, for the program to apply. */
void fct_fuse_opts_depth(const struct fct_fuse_opts *o, struct fct_camera *cam,
                         struct fct_depth_params *dp, struct fct_stereo *stereo);

#endif
