/* depthopts.c - the depth-image options of dm2mesh and planarize (see
 * depthopts.h). */
#include "cli/depthopts.h"

#include <math.h>
#include <string.h>

#include "cli/cli.h"
#include "depth/depthcode.h"
#include "io/header.h"

void fct_depth_opts_init(struct fct_depth_opts *o)
{
	memset(o, 0, sizeof *o);
	fct_depth_params_default(&o->depth);
}

/* The name of option c as a user types it. */
static const char *opt_name(int c)
{
	switch (c) {
	case 'K': return "-K";
	case 'j': return "-j";
	case FCT_DOPT_CAMERA: return "--camera";
	case FCT_DOPT_CYL: return "--cylindrical";
	case FCT_DOPT_SCALE: return "--depth-scale";
	case FCT_DOPT_BASELINE: return "--baseline";
	case FCT_DOPT_FOCAL: return "--focal";
	case FCT_DOPT_DOFFS: return "--doffs";
	case FCT_DOPT_RANGE: return "--range";
	case FCT_DOPT_STEP: return "--step";
	case FCT_DOPT_ANGLE: return "--max-angle";
	case FCT_DOPT_NOISE: return "--noise";
	case FCT_DOPT_POSE: return "--pose";
	case FCT_DOPT_CODE: return "--depth-code";
	default: return NULL;
	}
}

int fct_depth_opt(struct fct_depth_opts *o, int c, const char *arg)
{
	double r[2];
	switch (c) {
	case 'K': o->K = arg; break;
	case 'j': o->depth.grid.max_jump = fct_opt_double("-j", arg, 0, HUGE_VAL); break;
	case FCT_DOPT_CAMERA: o->camera_file = arg; break;
	case FCT_DOPT_CYL: o->cylindrical = arg; break;
	case FCT_DOPT_SCALE:
		o->depth.depth_scale = fct_opt_double("--depth-scale", arg, 1e-300, 1e300);
		o->depth.scale_float = o->scale_given = 1;
		break;
	case FCT_DOPT_BASELINE: o->depth.baseline = fct_opt_double("--baseline", arg, 1e-300, 1e300); break;
	case FCT_DOPT_FOCAL: o->focal = fct_opt_double("--focal", arg, 1e-300, 1e300); break;
	case FCT_DOPT_DOFFS:
		o->depth.doffs = fct_opt_double("--doffs", arg, -1e9, 1e9);
		o->doffs_given = 1;
		break;
	case FCT_DOPT_RANGE:
		fct_opt_doubles("--range", arg, r, 2);
		if (!(r[0] >= 0 && r[1] > r[0]))
			fct_usage_error("--range: expected 0 <= min < max");
		o->depth.min_depth = r[0], o->depth.max_depth = r[1];
		break;
	case FCT_DOPT_STEP: o->depth.step = (int)fct_opt_long("--step", arg, 1, 1 << 20); break;
	case FCT_DOPT_ANGLE:
		o->depth.grid.max_jump = tan(fct_opt_double("--max-angle", arg, 0, 89.999) * M_PI / 180);
		break;
	case FCT_DOPT_NOISE: o->noise = arg; break;
	case FCT_DOPT_POSE: o->pose_file = arg; break;
	case FCT_DOPT_IMAGE: o->image_file = arg; return 1;
	case FCT_DOPT_CODE: {
		struct fct_err err;
		if (fct_depth_code_parse(arg, &o->depth.code, &err))
			fct_usage_error("--depth-code: %s", err.msg);
		o->code_given = 1;
		break;
	}
	default: return 0;
	}
	if (!o->first && c != FCT_DOPT_NOISE)
		o->first = opt_name(c);
	return 1;
}

void fct_depth_opts_check(struct fct_depth_opts *o)
{
	if (o->focal > 0 && !(o->depth.baseline > 0))
		fct_usage_error("--focal is for disparities and needs --baseline");
	if (o->noise && fct_noise_names_model(o->noise)) {
		struct fct_err err;
		if (fct_noise_parse(&o->depth.noise, o->noise, &err))
			fct_usage_error("--%s", err.msg);
	}
}

void fct_depth_opts_read_pose(struct fct_depth_opts *o)
{
	struct fct_err err;
	if (o->pose_file) {
		if (fct_pose_read_file(o->pose_file, o->pose, &err))
			fct_die_err(&err);
		o->has_pose = 1;
	}
}

void fct_depth_opts_camera(struct fct_depth_opts *o, struct fct_camera *cam, int width, int height,
                           int required)
{
	int given = !!o->K + !!o->camera_file + !!o->cylindrical;
	memset(cam, 0, sizeof *cam);
	if (given > 1)
		fct_usage_error("-K, --camera and --cylindrical exclude each other");
	if (o->K || o->camera_file) {
		double scale;
		struct fct_stereo st;
		fct_opt_camera(cam, &scale, &st, o->K, o->camera_file);
		if (scale > 0 && !o->scale_given)
			o->depth.depth_scale = scale;
		/* a stereo calibration (Middlebury) makes the image disparities */
		if (st.baseline > 0 && !(o->depth.baseline > 0))
			o->depth.baseline = st.baseline;
		if (st.baseline > 0 && !o->doffs_given)
			o->depth.doffs = st.doffs;
	} else if (o->cylindrical) {
		fct_opt_cylindrical(o->cylindrical, width, height, cam);
	} else if (required) {
		fct_usage_error("no camera: give -K, --camera or --cylindrical");
	}
	if (cam->kind != FCT_CAMERA_NONE && cam->width == 0)
		cam->width = width, cam->height = height;
}

/* The noise model: --noise's (a model parsed with the options, or a file),
 * else the one a dataset's camera name implies; the unit of the image's
 * depth encoding when the model gives none. */
static void resolve_noise(struct fct_depth_opts *o, const struct fct_image *img)
{
	struct fct_noise *nz = &o->depth.noise;
	struct fct_err err;
	if (o->noise && !fct_noise_names_model(o->noise) && fct_noise_read_file(o->noise, nz, &err))
		fct_die_err(&err);
	if (!o->noise && o->K)
		fct_noise_named(o->K, nz);
	fct_depth_noise_unit(&o->depth, img);
}

void fct_depth_opts_resolve(struct fct_depth_opts *o, struct fct_camera *cam,
                            struct fct_image *img, const char *name)
{
	struct fct_err err;
	if (!o->code_given && o->K)
		o->depth.code = fct_depth_code_named(o->K);
	if (fct_depth_decode(img, o->depth.code, &err))
		fct_die_err_at(&err, "%s", name);
	fct_depth_opts_camera(o, cam, img->width, img->height, 1);
	if (o->doffs_given && !(o->depth.baseline > 0))
		fct_usage_error("--doffs is for disparities and needs --baseline");
	if (o->depth.baseline > 0)
		o->depth.focal = o->focal > 0 ? o->focal
		               : cam->kind == FCT_CAMERA_CYLINDRICAL ? cam->f : cam->fx;
	resolve_noise(o, img);
	char why[300];
	if (fct_depth_implausible(why, sizeof why, img, cam, &o->depth))
		fct_warn("%s: %s", name, why);
}

int fct_depth_opts_finish(struct fct_depth_opts *o, struct fct_mesh *m,
                          const struct fct_camera *cam, struct fct_err *err)
{
	o->double_xyz = 0;
	if (o->has_pose) {
		/* float holds world coordinates to 1/100 of the nearest vertex's
		 * pixel footprint, or they are written as double */
		double near = HUGE_VAL;
		for (size_t v = 0; v < m->nv; v++) {
			near = fmin(near, hypot(hypot(m->xyz[3 * v], m->xyz[3 * v + 1]), m->xyz[3 * v + 2]));
			fct_pose_apply(o->pose, &m->xyz[3 * v], &m->xyz[3 * v]);
		}
		o->double_xyz = fct_mesh_keep_precision(m, 0.01 * near * o->depth.step *
		                                           fct_camera_pixel_angle(cam));
	}
	if (fct_header_set_camera(m, cam, err) || fct_header_set_noise(m, &o->depth.noise, err) ||
	    (o->has_pose && fct_header_set_pose(m, o->pose, err)) ||
	    (o->image_file && fct_header_set_texture(m, 0, o->image_file, err)))
		return -1;
	return 0;
}
