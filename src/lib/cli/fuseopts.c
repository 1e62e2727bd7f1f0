/* fuseopts.c - the depth-image fusion options of tsdfuse and roommodel (see
 * fuseopts.h). */
#include "cli/fuseopts.h"

#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "depth/depthcode.h"
#include "io/noise.h"

void fct_fuse_opts_init(struct fct_fuse_opts *o, int argc, double voxel, double voxel_min,
                        double voxel_max)
{
	memset(o, 0, sizeof *o);
	o->voxel = voxel, o->voxel_min = voxel_min, o->voxel_max = voxel_max;
	o->trunc = 3;
	o->depth_scale = 1000;
	o->max_diff = 0.02;
	fct_depth_smooth_default(&o->smooth);
	o->poses = calloc((size_t)argc + 1, sizeof *o->poses);
	o->images = calloc((size_t)argc + 1, sizeof *o->images);
	if (!o->poses || !o->images)
		fct_die(1, "out of memory");
}

void fct_fuse_opts_free(struct fct_fuse_opts *o)
{
	free(o->poses);
	free(o->images);
	o->poses = o->images = NULL;
}

int fct_fuse_opt(struct fct_fuse_opts *o, int c, const char *arg)
{
	switch (c) {
	case 'K': o->K = arg; break;
	case FCT_FOPT_CAMERA: o->camera = arg; break;
	case FCT_FOPT_SCALE:
		o->depth_scale = fct_opt_double("--depth-scale", arg, 1e-300, 1e300);
		o->scale_given = 1;
		break;
	case FCT_FOPT_NOISE: o->noise = arg; break;
	case FCT_FOPT_SMOOTH: o->smooth.radius = (int)fct_opt_long("--smooth", arg, 0, 64); break;
	case FCT_FOPT_POSES: o->poses[o->nposes++] = arg; break;
	case FCT_FOPT_IMAGE: o->images[o->nimages++] = arg; break;
	case FCT_FOPT_MAXDIFF: o->max_diff = fct_opt_double("--max-difference", arg, 0, 1e9); break;
	case FCT_FOPT_VOXEL: o->voxel = fct_opt_double("--voxel", arg, o->voxel_min, o->voxel_max); break;
	case FCT_FOPT_TRUNC: o->trunc = fct_opt_double("--trunc", arg, 1, 100); break;
	case FCT_FOPT_THREADS: o->fp.threads = (int)fct_opt_long("--threads", arg, 0, 64); break;
	case FCT_FOPT_CODE: {
		struct fct_err err;
		if (fct_depth_code_parse(arg, &o->code, &err))
			fct_usage_error("--depth-code: %s", err.msg);
		o->code_given = 1;
		break;
	}
	default: return 0;
	}
	return 1;
}

/* A --noise that names a model, parsed: a usage error when malformed. */
static void parse_noise_model(struct fct_noise *noise, const char *arg)
{
	struct fct_err err;
	if (fct_noise_parse(noise, arg, &err))
		fct_usage_error("--%s", err.msg);
}

void fct_fuse_opts_check(struct fct_fuse_opts *o)
{
	o->fp.band = o->trunc * o->voxel;
	o->smooth.voxel = o->voxel;
	if (o->noise && fct_noise_names_model(o->noise)) {
		struct fct_noise model;
		parse_noise_model(&model, o->noise);
	}
}

void fct_fuse_opts_depth(const struct fct_fuse_opts *o, struct fct_camera *cam,
                         struct fct_depth_params *dp, struct fct_stereo *stereo)
{
	double named_scale;
	fct_opt_camera(cam, &named_scale, stereo, o->K, o->camera);
	fct_depth_params_default(dp);
	dp->texcoords = 0;
	dp->depth_scale = o->scale_given || !(named_scale > 0) ? o->depth_scale : named_scale;
	dp->scale_float = o->scale_given;
	dp->code = o->code_given ? o->code : fct_depth_code_named(o->K);
	dp->focal = cam->fx;
	/* The noise: --noise's (a model, or a file holding one), else the one
	 * -K's dataset name implies; none without. */
	struct fct_err err;
	if (o->noise && fct_noise_names_model(o->noise))
		parse_noise_model(&dp->noise, o->noise);
	else if (o->noise && fct_noise_read_file(o->noise, &dp->noise, &err))
		fct_die_err(&err);
	else if (!o->noise && o->K)
		fct_noise_named(o->K, &dp->noise);
}
