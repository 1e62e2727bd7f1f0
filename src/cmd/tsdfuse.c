/* tsdfuse - several registered range-image meshes fused into one surface:
 * Sun, Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor
 * Scenes Using a Mobile Range Scanner", sec. 3: Hilton's true signed
 * distance in a sparse volume, confidence-weighted averaging, optional
 * space carving, marching cubes, and level-set curvature flow. */
#include <getopt.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "cli.h"
#include "depthmesh.h"
#include "depthsmooth.h"
#include "fuse.h"
#include "geom.h"
#include "header.h"
#include "image.h"
#include "mcubes.h"
#include "meshio.h"
#include "path.h"
#include "poses.h"
#include "rangegrid.h"
#include "viewcolor.h"

static const char usage[] =
	"usage: tsdfuse [-aqv] [-o file] [--voxel size] [--trunc n] [--bbox x0,y0,z0,x1,y1,z1]\n"
	"               [--carve] [--weight constant | incidence | depth2]\n"
	"               [--curvature-flow iter] [--min-weight w] [--projective]\n"
	"               [-K fx,fy,cx,cy | name | --camera file] [--depth-scale s]\n"
	"               [--baseline b] [--doffs d] [--noise model | file] [--smooth px]\n"
	"               [--poses file ...] [--max-difference s]\n"
	"               [--color] [--image file ...] [--conf file] [--threads n] [view ...]\n"
	"Fuse registered views (meshes carrying their camera and pose comments, depth\n"
	"images with -K and --poses, or the range-grid scans of a --conf file) by\n"
	"the true signed distance to each view's surface, and extract the surface.\n"
	"  -a                 write ascii PLY\n"
	"  -K fx,fy,cx,cy     camera of the depth-image views (or a dataset name)\n"
	"      --baseline b   the depth images hold disparities: depth = b * fx /\n"
	"                     (disparity + doffs)\n"
	"      --camera file  camera of the depth images from a file: Open3D intrinsic\n"
	"                     JSON, a 3x3 K, a camera line, Middlebury's calib.txt\n"
	"      --doffs d      disparity offset (Middlebury; default 0 or calib.txt's)\n"
	"  -o file            output file (default standard output)\n"
	"  -q                 quiet\n"
	"  -v                 progress per view, then figures on stderr\n"
	"      --bbox x0,y0,z0,x1,y1,z1\n"
	"                     fuse and extract only inside this box (metres); tiles\n"
	"                     sharing faces join without cracks\n"
	"      --carve        space carving: close occlusion holes (watertight rooms)\n"
	"      --color        vertex colour from the views' images (TextureFile\n"
	"                     comments, --image); unseen vertices are grey 128\n"
	"      --conf file    Stanford/VRIP .conf naming range-grid PLY scans\n"
	"      --curvature-flow iter\n"
	"                     level-set mean-curvature steps after fusion (default 0)\n"
	"      --depth-scale s\n"
	"                     PNG depth units per metre (default 1000, or the -K name's)\n"
	"      --image file   colour image of the depth-image views, in their order\n"
	"                     (repeated; implies --color)\n"
	"      --max-difference s\n"
	"                     TUM trajectory: a depth image's pose is the nearest in\n"
	"                     time to the timestamp in its name, within s (default 0.02)\n"
	"      --min-weight w extract only voxels of at least this weight (default 0)\n"
	"      --noise model  the depth images' noise: none, kinect[:F,B[,SD[,STEP]]],\n"
	"                     tof[:A,B], poly:A,B,C, stereo:FB,SD[,DOFFS], or a file\n"
	"                     holding a line \"noise ...\"; smooths and meshes them\n"
	"                     with it and weighs true distance by it (default: kinect\n"
	"                     for a -K dataset name, else none)\n"
	"      --poses file   camera-to-world poses of the depth images: one file of\n"
	"                     them all (TUM trajectory, Redwood .log, KITTI poses,\n"
	"                     stacked 4x4), or a 4x4 or 3x4 file per image (repeated)\n"
	"      --projective   Curless-Levoy depth difference instead of true distance\n"
	"      --smooth px    half-width of the noise-aware smoothing of depth images\n"
	"                     with a noise model (default 2; 0: none)\n"
	"      --threads n    threads (default 0: one per processor)\n"
	"      --trunc n      band half-width in voxels (default 3)\n"
	"      --voxel size   voxel size in metres (default 0.01)\n"
	"      --weight w     confidence of a view: constant (default), incidence\n"
	"                     (cosine of the viewing angle), depth2 (1/depth^2)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

/* Voxel indices from the origin each way (fuse.c's 21-bit block keys). */
#define VOXEL_RANGE (1 << 23)

enum { OPT_VOXEL = 256, OPT_TRUNC, OPT_BBOX, OPT_CARVE, OPT_WEIGHT, OPT_FLOW, OPT_MINW,
       OPT_PROJ, OPT_SCALE, OPT_POSES, OPT_CONF, OPT_THREADS, OPT_VERSION, OPT_COLOR, OPT_IMAGE,
       OPT_CAMERA, OPT_BASELINE, OPT_DOFFS, OPT_MAXDIFF, OPT_NOISE, OPT_SMOOTH };

struct options {
	const char *out, *K, *camera, *conf, *noise;
	const char **poses, **images;
	size_t nposes, nimages;
	int color;
	int ascii, carve, flow, has_bbox, scale_given, doffs_given;
	double voxel, trunc, min_weight, bbox[6], depth_scale, baseline, doffs, max_diff;
	struct fct_noise depth_noise;
	struct fct_depth_smooth smooth;
	struct fct_fuse_params fp;
	char **views;
	size_t nviews;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"voxel", required_argument, NULL, OPT_VOXEL},
		{"trunc", required_argument, NULL, OPT_TRUNC},
		{"bbox", required_argument, NULL, OPT_BBOX},
		{"carve", no_argument, NULL, OPT_CARVE},
		{"weight", required_argument, NULL, OPT_WEIGHT},
		{"curvature-flow", required_argument, NULL, OPT_FLOW},
		{"min-weight", required_argument, NULL, OPT_MINW},
		{"projective", no_argument, NULL, OPT_PROJ},
		{"depth-scale", required_argument, NULL, OPT_SCALE},
		{"poses", required_argument, NULL, OPT_POSES},
		{"conf", required_argument, NULL, OPT_CONF},
		{"threads", required_argument, NULL, OPT_THREADS},
		{"color", no_argument, NULL, OPT_COLOR},
		{"image", required_argument, NULL, OPT_IMAGE},
		{"camera", required_argument, NULL, OPT_CAMERA},
		{"baseline", required_argument, NULL, OPT_BASELINE},
		{"doffs", required_argument, NULL, OPT_DOFFS},
		{"max-difference", required_argument, NULL, OPT_MAXDIFF},
		{"noise", required_argument, NULL, OPT_NOISE},
		{"smooth", required_argument, NULL, OPT_SMOOTH},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ahK:o:qv";
	int c;
	memset(o, 0, sizeof *o);
	o->voxel = 0.01;
	o->trunc = 3;
	o->depth_scale = 1000;
	o->max_diff = 0.02;
	fct_depth_smooth_default(&o->smooth);
	o->poses = calloc((size_t)argc + 1, sizeof *o->poses);
	o->images = calloc((size_t)argc + 1, sizeof *o->images);
	if (!o->poses || !o->images)
		fct_die(1, "out of memory");
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'K': o->K = optarg; break;
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("tsdfuse (facet) " FCT_VERSION); exit(0);
		case OPT_VOXEL: o->voxel = fct_opt_double("--voxel", optarg, 1e-6, 1e6); break;
		case OPT_TRUNC: o->trunc = fct_opt_double("--trunc", optarg, 1, 100); break;
		case OPT_BBOX:
			fct_opt_doubles("--bbox", optarg, o->bbox, 6);
			o->has_bbox = 1;
			for (int k = 0; k < 3; k++)
				if (!(o->bbox[k + 3] > o->bbox[k]))
					fct_usage_error("--bbox: the box has zero volume (need x0 < x1, y0 < y1, z0 < z1)");
			break;
		case OPT_CARVE: o->carve = 1; break;
		case OPT_WEIGHT:
			if (!strcmp(optarg, "constant"))
				o->fp.weight = FCT_FUSE_CONSTANT;
			else if (!strcmp(optarg, "incidence"))
				o->fp.weight = FCT_FUSE_INCIDENCE;
			else if (!strcmp(optarg, "depth2"))
				o->fp.weight = FCT_FUSE_DEPTH2;
			else
				fct_usage_error("--weight: \"%s\": expected constant, incidence or depth2", optarg);
			break;
		case OPT_FLOW: o->flow = (int)fct_opt_long("--curvature-flow", optarg, 0, 10000); break;
		case OPT_MINW: o->min_weight = fct_opt_double("--min-weight", optarg, 0, 1e30); break;
		case OPT_PROJ: o->fp.projective = 1; break;
		case OPT_SCALE:
			o->depth_scale = fct_opt_double("--depth-scale", optarg, 1e-300, 1e300);
			o->scale_given = 1;
			break;
		case OPT_POSES: o->poses[o->nposes++] = optarg; break;
		case OPT_CONF: o->conf = optarg; break;
		case OPT_THREADS: o->fp.threads = (int)fct_opt_long("--threads", optarg, 0, 64); break;
		case OPT_COLOR: o->color = 1; break;
		case OPT_IMAGE: o->images[o->nimages++] = optarg, o->color = 1; break;
		case OPT_CAMERA: o->camera = optarg; break;
		case OPT_BASELINE: o->baseline = fct_opt_double("--baseline", optarg, 1e-300, 1e300); break;
		case OPT_DOFFS:
			o->doffs = fct_opt_double("--doffs", optarg, -1e9, 1e9);
			o->doffs_given = 1;
			break;
		case OPT_MAXDIFF: o->max_diff = fct_opt_double("--max-difference", optarg, 0, 1e9); break;
		case OPT_NOISE: o->noise = optarg; break;
		case OPT_SMOOTH: o->smooth.radius = (int)fct_opt_long("--smooth", optarg, 0, 64); break;
		default: fct_bad_option(optstring, argv);
		}
	}
	o->views = argv + optind;
	o->nviews = (size_t)(argc - optind);
	if (!o->nviews && !o->conf)
		fct_usage_error("no views: give meshes, depth images or --conf");
	o->fp.band = o->trunc * o->voxel;
	o->smooth.voxel = o->voxel;
	if (o->noise && fct_noise_names_model(o->noise)) {
		struct fct_err err;
		if (fct_noise_parse(&o->depth_noise, o->noise, &err))
			fct_usage_error("--%s", err.msg);
	}
	/* Voxel indices are int32 (and the volume's blocks keep to 2^23 voxels
	 * each way): a box beyond overflowed them into an empty model. */
	for (int k = 0; o->has_bbox && k < 6; k++)
		if (!(fabs(o->bbox[k]) / o->voxel < VOXEL_RANGE))
			fct_usage_error("--bbox: %g m is %.3g voxels of %g m from the origin: beyond the "
			                "volume's %d (%g m at this voxel size)", o->bbox[k],
			                fabs(o->bbox[k]) / o->voxel, o->voxel, VOXEL_RANGE,
			                VOXEL_RANGE * o->voxel);
}

static double mesh_area(const struct fct_mesh *m)
{
	double a = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *v = &m->fvert[m->fstart[f]];
		for (uint32_t k = 2; k < fct_face_size(m, f); k++) {
			double l = fct_triangle_area2(&m->xyz[3 * (size_t)v[0]], &m->xyz[3 * (size_t)v[k - 1]],
			                              &m->xyz[3 * (size_t)v[k]]);
			if (isfinite(l))
				a += l / 2;
		}
	}
	return a;
}

static double machine_bytes(void)
{
	long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
	return pages > 0 && size > 0 ? (double)pages * (double)size : 4e9;
}

/* Everything one view needs: its mesh, camera and pose, with --color its
 * colour image (malloc'd path, NULL for none), and for a depth image fused
 * with --projective the depths of its mesh's pixels (view.depth). */
struct loaded {
	struct fct_mesh mesh;
	struct fct_fuse_view view;
	char name[512];
	int depth_image;
	char *image;
	float *depth;
};

/* Load view number idx (operands first, then the .conf scans); dpose is
 * the pose of a depth image. */
static void load_view(struct options *o, size_t idx, const struct fct_conf *conf,
                      const double *dpose, const struct fct_camera *dcam,
                      const struct fct_depth_params *dp, struct loaded *L)
{
	struct fct_err err;
	memset(&L->view, 0, sizeof L->view);
	if (idx >= o->nviews) {
		const struct fct_conf_scan *s = &conf->scans[idx - o->nviews];
		snprintf(L->name, sizeof L->name, "%s", s->path);
		struct fct_mesh raw;
		if (fct_mesh_read_file(&raw, s->path, NULL, &err))
			fct_die_err(&err);
		double step;
		int rc = fct_range_grid_mesh(&L->mesh, &raw, NULL, &step, &err);
		fct_mesh_free(&raw);
		if (rc) {
			fct_err_prefix(&err, "%s", s->path);
			fct_die_err(&err);
		}
		for (size_t v = 0; v < L->mesh.nv; v++)
			fct_pose_apply(s->pose, &L->mesh.xyz[3 * v], &L->mesh.xyz[3 * v]);
		memcpy(L->view.pose, s->pose, sizeof s->pose);
		L->view.cam.kind = FCT_CAMERA_NONE;
		L->view.ortho_step = step;
	} else if (dpose) {
		const char *path = o->views[idx];
		snprintf(L->name, sizeof L->name, "%s", path);
		struct fct_image img;
		if (fct_image_read_file(&img, path, NULL, &err))
			fct_die_err(&err);
		struct fct_camera cam = *dcam;
		if (cam.width == 0)
			cam.width = img.width, cam.height = img.height;
		if (cam.width != img.width || cam.height != img.height)
			fct_die(1, "%s: image is %dx%d, the camera %dx%d", path, img.width, img.height,
			        cam.width, cam.height);
		static int warned;      /* a wrong depth scale, once for all views */
		char why[300];
		if (!warned && fct_depth_implausible(why, sizeof why, &img, &cam, dp)) {
			fct_warn("%s: %s", path, why);
			warned = 1;
		}
		int rc = fct_fuse_depth_view(&L->view, &L->mesh, o->fp.projective ? &L->depth : NULL,
		                             &img, &cam, dp, &o->smooth, dpose, &err);
		fct_image_free(&img);
		if (rc) {
			fct_err_prefix(&err, "%s", path);
			fct_die_err(&err);
		}
		L->depth_image = 1;
	} else {
		const char *path = o->views[idx];
		snprintf(L->name, sizeof L->name, "%s", fct_path_display(path));
		if (fct_mesh_read_file(&L->mesh, path, NULL, &err))
			fct_die_err(&err);
		int c = fct_header_camera(&L->mesh, &L->view.cam, &err);
		if (c < 0) {
			fct_err_prefix(&err, "%s", L->name);
			fct_die_err(&err);
		}
		if (c == 0)
			fct_die(1, "%s: no camera comment: tsdfuse needs each view's camera (dm2mesh writes it)", L->name);
		c = fct_header_pose(&L->mesh, L->view.pose, &err);
		if (c < 0) {
			fct_err_prefix(&err, "%s", L->name);
			fct_die_err(&err);
		}
		if (c == 0)
			fct_die(1, "%s: no pose comment: tsdfuse needs each view's camera-to-world pose (dm2mesh --pose)", L->name);
		if (fct_pose_check(L->view.pose, 1e-3, &err)) {
			fct_err_prefix(&err, "%s: pose", L->name);
			fct_die_err(&err);
		}
		if (o->color && fct_header_texture_count(&L->mesh)) {
			/* On disk a TextureFile is relative to its mesh's folder. */
			char *dir = fct_path_dir(path, &err);
			if (!dir || !(L->image = fct_path_join(dir, fct_header_texture(&L->mesh, 0), &err)))
				fct_die_err(&err);
			free(dir);
		}
	}
	if (L->mesh.nf == 0)
		fct_die(1, "%s: empty view (no faces)", L->name);
	for (size_t v = 0; v < L->mesh.nv; v++)
		if (!(isfinite(L->mesh.xyz[3 * v]) && isfinite(L->mesh.xyz[3 * v + 1]) &&
		      isfinite(L->mesh.xyz[3 * v + 2])))
			fct_die(1, "%s: vertex %zu is not finite", L->name, v);
	L->view.mesh = &L->mesh;
	/* A view's noise, where its mesh carries it (a depth image meshed
	 * with a model here, or dm2mesh's mesh of one): the fusion weighs by
	 * it (fuse.h). */
	struct fct_prop *sp = fct_elem_find(&L->mesh.vertex, "sigma");
	L->view.sigma = sp && sp->type == FCT_FLOAT32 ? sp->data : NULL;
}

/* The camera, depth and noise parameters of the depth-image operands. */
static void depth_params(struct options *o, struct fct_camera *dcam, struct fct_depth_params *dp)
{
	double scale;
	struct fct_stereo stereo;
	fct_opt_camera(dcam, &scale, &stereo, o->K, o->camera);
	if (scale > 0 && !o->scale_given)
		o->depth_scale = scale;
	fct_depth_params_default(dp);
	dp->texcoords = 0;
	dp->depth_scale = o->depth_scale;
	dp->scale_float = o->scale_given;
	/* disparities: from --baseline, or a stereo calibration's */
	dp->baseline = o->baseline > 0 ? o->baseline : stereo.baseline;
	dp->doffs = o->doffs_given ? o->doffs : stereo.doffs;
	dp->focal = dcam->fx;
	if (o->doffs_given && !(dp->baseline > 0))
		fct_usage_error("--doffs is for disparities and needs --baseline");
	/* Their noise: --noise's (a model, or a file holding one), else the
	 * one -K's dataset name implies; none without. */
	struct fct_err err;
	dp->noise = o->depth_noise;
	if (o->noise && !fct_noise_names_model(o->noise) && fct_noise_read_file(o->noise, &dp->noise, &err))
		fct_die_err(&err);
	if (!o->noise && o->K)
		fct_noise_named(o->K, &dp->noise);
}

/* The volume holds voxels to 2^23 from the origin each way (fuse.c's block
 * keys): say whether the views' span or their offset is beyond. */
static _Noreturn void too_far(double vox, double lo, double hi)
{
	double span = (hi - lo) / vox, off = fmax(fabs(lo), fabs(hi));
	if (span < VOXEL_RANGE)
		fct_die(1, "--voxel %g: the views lie %g m from the origin, %.3g voxels: beyond the "
		        "volume's %d each way (their span, %g m, fits: move the poses nearer the origin)",
		        vox, off, off / vox, VOXEL_RANGE, hi - lo);
	fct_die(1, "--voxel %g: the views span %g m, %.3g voxels: beyond the volume's %d each way",
	        vox, hi - lo, span, VOXEL_RANGE);
}

/* A view that changed no voxel: say why, where it can be seen. */
static void warn_unused(const struct loaded *L, int has_bbox)
{
	const double *t = &L->view.pose[3];
	double near = HUGE_VAL;
	if (L->view.cam.kind != FCT_CAMERA_NONE)
		for (size_t v = 0; v < L->mesh.nv; v++) {
			const double *p = &L->mesh.xyz[3 * v];
			near = fmin(near, hypot(hypot(p[0] - t[0], p[1] - t[4]), p[2] - t[8]));
		}
	if (near > 1e6 && near < HUGE_VAL)
		fct_warn("%s: the view adds nothing: its camera is %.3g m from its nearest point", L->name,
		         near);
	else
		fct_warn("%s: the view adds nothing%s", L->name, has_bbox ? " inside --bbox" : "");
}

/* The views, read one at a time: each is loaded, used and freed before
 * the next (memory bounded by the volume, not the number of views), in as
 * many passes as the options need: the box carving needs first, the
 * fusion, and with --color the colour after extraction. */
struct views {
	struct options *o;
	const struct fct_conf *conf;
	const struct fct_camera *dcam;
	const struct fct_depth_params *dp;
	size_t n;
	size_t *image;           /* per view: 1 + its --image, 0 for none */
	size_t *depth;           /* per view: 1 + its place among the depth images, 0 for none */
	size_t ndepth;
	double *dposes;          /* 12 per depth image */
	double read_s;           /* time spent reading them */
};

/* The depth images among the operands get the --image files in order. */
static void views_init(struct views *vs, struct options *o, const struct fct_conf *conf)
{
	vs->o = o, vs->conf = conf;
	vs->n = o->nviews + conf->n;
	vs->image = calloc(vs->n ? vs->n : 1, sizeof *vs->image);
	vs->depth = calloc(vs->n ? vs->n : 1, sizeof *vs->depth);
	if (!vs->image || !vs->depth)
		fct_die(1, "out of memory");
	size_t nimage = 0;
	for (size_t i = 0; i < o->nviews; i++)
		if (fct_path_is_image(o->views[i])) {
			vs->depth[i] = ++vs->ndepth;
			vs->image[i] = nimage < o->nimages ? ++nimage : (nimage++, 0);
		}
	if (o->nimages && o->nimages != nimage)
		fct_usage_error("%zu depth views but %zu --image files", nimage, o->nimages);
}

/* The poses of the depth images among the operands (vs->depth), 12 per
 * image in operand order (poses.h matches them to --poses), into
 * vs->dposes (NULL when there are none). */
static void depth_poses(struct views *vs, const struct fct_camera *dcam)
{
	const struct options *o = vs->o;
	struct fct_err err;
	const char **frames = calloc(vs->ndepth + 1, sizeof *frames);
	if (!frames)
		fct_die(1, "out of memory");
	for (size_t i = 0; i < o->nviews; i++)
		if (vs->depth[i])
			frames[vs->depth[i] - 1] = o->views[i];
	size_t n = vs->ndepth;
	vs->dposes = NULL;
	if (n == 0 && o->nposes)
		fct_usage_error("--poses is for depth images, and no view is one");
	if (n > 0) {
		if (dcam->kind == FCT_CAMERA_NONE)
			fct_usage_error("%s: a depth image needs -K or --camera", frames[0]);
		if (!o->nposes)
			fct_usage_error("%s: a depth image needs --poses", frames[0]);
		if (o->nposes > 1 && o->nposes != n)
			fct_usage_error("%zu depth images but %zu --poses files (give one per image, or one "
			                "file of them all)", n, o->nposes);
		struct fct_frame_poses_stats st;
		if (!(vs->dposes = fct_alloc_array(n, 12 * sizeof *vs->dposes, &err)) ||
		    fct_frame_poses(vs->dposes, &st, o->poses, o->nposes, frames, n, o->max_diff, &err))
			fct_die_err(&err);
		static const char *const by[] = { "files", "order", "timestamp", "frame number" };
		fct_report("poses", "%s", fct_traj_format_name(st.format));
		fct_report("poses_matched_by", "%s", by[st.match]);
		if (st.match == FCT_MATCH_STAMP)
			fct_report("poses_max_difference_s", "%.6f", st.max_diff);
	}
	free(frames);
}

static void view_open(struct views *vs, size_t i, struct loaded *L)
{
	double t = fct_now();
	struct fct_err err;
	memset(L, 0, sizeof *L);
	load_view(vs->o, i, vs->conf, vs->depth[i] ? &vs->dposes[12 * (vs->depth[i] - 1)] : NULL,
	          vs->dcam, vs->dp, L);
	if (L->depth_image && vs->image[i] && !(L->image = fct_strdup(vs->o->images[vs->image[i] - 1], &err)))
		fct_die_err(&err);
	vs->read_s += fct_now() - t;
}

static void view_close(struct loaded *L)
{
	fct_mesh_free(&L->mesh);
	free(L->depth);
	free(L->image);
	memset(L, 0, sizeof *L);
}

/* The views' extent: the box of their vertices and their area. */
struct extent {
	double lo[3], hi[3], area;
	size_t n;
};

static void extent_add(struct extent *e, const struct fct_mesh *m)
{
	e->n++;
	e->area += mesh_area(m);
	for (size_t v = 0; v < m->nv; v++)
		for (int k = 0; k < 3; k++) {
			double x = m->xyz[3 * v + k];
			e->lo[k] = x < e->lo[k] ? x : e->lo[k];
			e->hi[k] = x > e->hi[k] ? x : e->hi[k];
		}
}

/* The voxels the views reach (within --bbox), clo..chi, and the memory
 * the volume needs for them: the band around their surface in blocks (at
 * most their box's), and the carving bitsets.  Dies when that is more
 * than the machine has, or the voxels overflow the indices. */
static double volume_box(const struct options *o, const struct extent *e, int32_t clo[3], int32_t chi[3])
{
	double vox = o->voxel, band = o->fp.band, lo[3], hi[3];
	for (int k = 0; k < 3; k++) {
		lo[k] = e->lo[k], hi[k] = e->hi[k];
		if (o->has_bbox) {
			lo[k] = fmax(lo[k], o->bbox[k] - 3 * vox);
			hi[k] = fmin(hi[k], o->bbox[k + 3] + 3 * vox);
		}
	}
	double bs = 8 * vox, bbox_blocks = 1;
	for (int k = 0; k < 3; k++)
		bbox_blocks *= fmax(hi[k] - lo[k], 0) / bs + 3;
	double band_blocks = 2 * e->area / (bs * bs) * (1 + 2 * band / bs) + 27.0 * (double)e->n;
	double est = fmin(band_blocks, bbox_blocks) * (double)fct_voxgrid_block_bytes(0);
	for (int k = 0; k < 3; k++) {
		double a = floor((lo[k] - band) / vox) - 2, b = ceil((hi[k] + band) / vox) + 2;
		if (!(fabs(a) < VOXEL_RANGE && fabs(b) < VOXEL_RANGE))
			too_far(vox, lo[k], hi[k]);
		clo[k] = (int32_t)a, chi[k] = (int32_t)b;
	}
	if (o->carve)
		est += (double)fct_carve_bytes(clo, chi);
	double have = machine_bytes();
	if (est > 0.8 * have)
		fct_die(1, "--voxel %g: needs about %.1f GB, the machine has %.1f GB", vox, est / 1e9, have / 1e9);
	return est;
}

/* --color: each vertex of out gets the weighted average colour of the
 * views that see it (viewcolor.h), grey 128 when none does.  The views
 * are read again, one with its range image and colour image at a time. */
static void color_vertices(struct views *vs, struct fct_mesh *out, size_t *ncolor)
{
	struct fct_err err;
	struct fct_viewcolor acc;
	if (fct_viewcolor_init(&acc, out->nv, &err))
		fct_die_err(&err);
	struct fct_viewcolor_params cp = { vs->o->fp.band, vs->o->fp.weight, 4 };
	*ncolor = 0;
	for (size_t i = 0; i < vs->n; i++) {
		struct loaded L;
		view_open(vs, i, &L);
		if (L.image && L.view.cam.kind != FCT_CAMERA_NONE) {
			++*ncolor;
			struct fct_range_image ri;
			struct fct_image img;
			size_t seen;
			if (fct_range_image_make(&ri, &L.view, (size_t)1 << 26, &err)) {
				fct_err_prefix(&err, "%s", L.name);
				fct_die_err(&err);
			}
			if (fct_image_read_file(&img, L.image, NULL, &err))
				fct_die_err(&err);
			int rc = fct_viewcolor_add(&acc, out, &ri, &img, &cp, &seen, &err);
			fct_image_free(&img);
			fct_range_image_free(&ri);
			if (rc) {
				fct_err_prefix(&err, "%s", L.name);
				fct_die_err(&err);
			}
			if (fct_verbose)
				fprintf(stderr, "tsdfuse: colour from %s: %zu vertices seen\n", L.name, seen);
		}
		view_close(&L);
	}
	if (!*ncolor)
		fct_warn("--color: no view has a colour image (TextureFile comment or --image): "
		         "every vertex gets the fallback grey");
	static const uint8_t grey[3] = { 128, 128, 128 };
	struct fct_viewcolor_stats st;
	if (fct_viewcolor_write(&acc, out, grey, &st, &err))
		fct_die_err(&err);
	fct_viewcolor_free(&acc);
	fct_report("colored_vertices", "%zu", st.colored);
	fct_report("uncolored_vertices", "%zu", st.unseen);
	fct_report("views_per_vertex", "%.2f", st.views_per_vertex);
}

/* Fuse the views into g, one at a time; with carving, each view's range
 * image goes into it as soon as the view is fused.  Without it, the
 * views' extent is gathered here (carving needs it before: pre, or NULL)
 * and the memory checked as it grows. */
static void fuse_views(struct views *vs, struct fct_voxgrid *g, struct fct_carving *carving,
                       struct extent *e, int pre, struct fct_fuse_stats *st, double *fuse_s, double *carve_s)
{
	struct options *o = vs->o;
	struct fct_err err;
	for (size_t i = 0; i < vs->n; i++) {
		struct loaded L;
		view_open(vs, i, &L);
		if (!pre) {
			int32_t clo[3], chi[3];
			extent_add(e, &L.mesh);
			volume_box(o, e, clo, chi);
		}
		double tv = fct_now();
		size_t before = st->voxels;
		if (fct_fuse_view(g, &L.view, &o->fp, st, &err)) {
			fct_err_prefix(&err, "%s", L.name);
			fct_die_err(&err);
		}
		if (st->voxels == before)
			warn_unused(&L, o->has_bbox);
		double dt = fct_now() - tv;
		*fuse_s += dt;
		if (fct_verbose)
			fprintf(stderr, "tsdfuse: view %zu/%zu %s: %zu faces, %.1f ms\n", i + 1, vs->n, L.name,
			        L.mesh.nf, 1e3 * dt);
		if (carving) {
			double tc = fct_now();
			struct fct_range_image ri;
			double vox = o->voxel;
			if (L.view.cam.kind == FCT_CAMERA_NONE && L.view.ortho_step < vox / 2)
				L.view.ortho_step = vox / 2;
			if (fct_range_image_make(&ri, &L.view, (size_t)1 << 26, &err)) {
				fct_err_prefix(&err, "%s", L.name);
				fct_die_err(&err);
			}
			fct_carving_add(carving, &ri);
			fct_range_image_free(&ri);
			*carve_s += fct_now() - tc;
		}
		view_close(&L);
	}
}

#ifdef __GLIBC__
/* Keep freed memory for reuse instead of faulting fresh pages in:
 * - each view allocates and frees arrays of several MB (its mesh, normals,
 *   projections, cells); glibc would give them back to the kernel and
 *   fault them in afresh, zeroed, for the next view;
 * - marching cubes' output can reuse the last view's memory only if that
 *   memory is one free run.  The small allocations made while a view is
 *   read (header strings, element tables) come from the top of the heap
 *   when no free chunk is below, between a view's arrays, and once freed
 *   they stay in glibc's per-thread cache, which never coalesces.  A block
 *   freed now, below everything else, serves those small allocations
 *   instead.
 * The measurements are in bench/NOTES.md. */
static void *volatile heap_pin;         /* holds the pool out of the top chunk */

static void keep_freed_memory(void)
{
	mallopt(M_MMAP_THRESHOLD, 32 << 20);
	mallopt(M_TRIM_THRESHOLD, 1 << 30);
	void *volatile small_pool = malloc(256 << 10);
	heap_pin = malloc(16);
	free(small_pool);
}
#endif

int main(int argc, char **argv)
{
	fct_cli_init("tsdfuse");
#ifdef __GLIBC__
	keep_freed_memory();
#endif
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	struct fct_conf conf = { 0 };
	if (o.conf && fct_conf_read(&conf, o.conf, &err))
		fct_die_err(&err);
	for (size_t i = 0; i < conf.nskipped; i++)
		if (fct_verbose)
			fprintf(stderr, "tsdfuse: %s:%ld: skipped \"%s\" (vrip fuses bmesh lines only)\n",
			        o.conf, conf.skipped[i].line, conf.skipped[i].text);
	fct_report("conf_skipped", "%zu", conf.nskipped);
	struct fct_camera dcam;
	struct fct_depth_params dp;
	depth_params(&o, &dcam, &dp);
	struct views vs = { .dcam = &dcam, .dp = &dp };
	views_init(&vs, &o, &conf);
	depth_poses(&vs, &dcam);
	size_t nv = vs.n;
	double t0 = fct_now();
	struct extent e = { { HUGE_VAL, HUGE_VAL, HUGE_VAL }, { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL }, 0, 0 };
	if (o.carve)            /* the carving box first: the views' extent */
		for (size_t i = 0; i < nv; i++) {
			struct loaded L;
			view_open(&vs, i, &L);
			extent_add(&e, &L.mesh);
			view_close(&L);
		}
	double reread_s = vs.read_s;
	vs.read_s = 0;
	int32_t clo[3] = { 0, 0, 0 }, chi[3] = { 0, 0, 0 };
	double est = o.carve ? volume_box(&o, &e, clo, chi) : 0;
	double vox = o.voxel, band = o.fp.band, have = machine_bytes();
	struct fct_voxgrid *g = fct_voxgrid_new(vox, 0, &err);
	if (!g)
		fct_die_err(&err);
	fct_voxgrid_set_limit(g, (size_t)(0.85 * have));
	if (o.has_bbox) {
		o.fp.has_clip = 1;
		for (int k = 0; k < 3; k++) {
			o.fp.clip_lo[k] = (int32_t)ceil(o.bbox[k] / vox) - 2;
			o.fp.clip_hi[k] = (int32_t)ceil(o.bbox[k + 3] / vox) + 2;
			clo[k] = clo[k] > o.fp.clip_lo[k] ? clo[k] : o.fp.clip_lo[k];
			chi[k] = chi[k] < o.fp.clip_hi[k] ? chi[k] : o.fp.clip_hi[k];
		}
	}
	struct fct_carving carving;
	if (o.carve && fct_carving_init(&carving, clo, chi, vox, &err))
		fct_die_err(&err);

	struct fct_fuse_stats st = { 0 };
	double fuse_s = 0, carve_s = 0;
	fuse_views(&vs, g, o.carve ? &carving : NULL, &e, o.carve, &st, &fuse_s, &carve_s);
	double read_s = vs.read_s;
	if (!o.carve)
		est = volume_box(&o, &e, clo, chi);
	fct_report("memory_estimate_mb", "%.1f", est / 1048576);
	size_t ncarved = 0;
	if (o.carve) {
		double tc = fct_now();
		float mark = o.min_weight > 0 ? (float)o.min_weight : 1e-3f;
		if (fct_carving_finish(&carving, g, band, mark, &ncarved, &err))
			fct_die_err(&err);
		fct_carving_free(&carving);
		carve_s += fct_now() - tc;
	}
	double flow_s = 0;
	if (o.flow) {
		double tf = fct_now();
		if (fct_curvature_flow(g, o.flow, band, &err))
			fct_die_err(&err);
		flow_s = fct_now() - tf;
	}
	struct rusage ru;   /* ru_maxrss: kilobytes on Linux and the BSDs */
	long faults0 = getrusage(RUSAGE_SELF, &ru) ? 0 : ru.ru_minflt;
	double tm = fct_now();
	struct fct_mesh out;
	int32_t mlo[3], mhi[3];
	for (int k = 0; k < 3; k++) {
		mlo[k] = (int32_t)ceil(o.bbox[k] / vox);
		mhi[k] = (int32_t)ceil(o.bbox[k + 3] / vox);
	}
	if (fct_mcubes_stats(&out, g, (float)o.min_weight, o.has_bbox ? mlo : NULL,
	                     o.has_bbox ? mhi : NULL, o.fp.threads, NULL, &err))
		fct_die_err(&err);
	double mc_s = fct_now() - tm, color_s = 0;
	/* The pages marching cubes faulted in: its output where the memory
	 * the views freed does not hold it (bench/NOTES.md). */
	long mc_faults = getrusage(RUSAGE_SELF, &ru) ? 0 : ru.ru_minflt - faults0;
	size_t nblocks = fct_voxgrid_count(g), gbytes = fct_voxgrid_bytes(g), ncolor = 0;
	fct_voxgrid_free(g);    /* before the colour pass reads the views again */
	if (o.color) {
		double tc = fct_now(), r0 = vs.read_s;
		color_vertices(&vs, &out, &ncolor);
		reread_s += vs.read_s - r0;
		color_s = fct_now() - tc;
	}
	fct_report("views", "%zu", nv);
	fct_report("view_faces", "%zu", st.faces);
	fct_report("voxels_updated", "%zu", st.voxels);
	fct_report("border_skipped", "%zu", st.border);
	fct_report("blocks", "%zu", nblocks);
	fct_report("memory_mb", "%.1f", (double)gbytes / 1048576);
	if (fct_header_add_provenance(&out, "tsdfuse", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&out, o.out, o.ascii, &err))
		fct_die_err(&err);
	fct_report("carved", "%zu", ncarved);
	fct_report("vertices", "%zu", out.nv);
	fct_report("faces", "%zu", out.nf);
	fct_report("read_s", "%.4f", read_s);
	fct_report("reread_s", "%.4f", reread_s);
	fct_report("fuse_s", "%.4f", fuse_s);
	fct_report("ms_per_view", "%.2f", nv ? 1e3 * fuse_s / (double)nv : 0);
	fct_report("carve_s", "%.4f", carve_s);
	fct_report("flow_s", "%.4f", flow_s);
	fct_report("mcubes_s", "%.4f", mc_s);
	fct_report("mcubes_faults", "%ld", mc_faults);
	if (o.color) {
		fct_report("color_views", "%zu", ncolor);
		fct_report("color_s", "%.4f", color_s);
	}
	fct_report("total_s", "%.4f", fct_now() - t0);
	if (!getrusage(RUSAGE_SELF, &ru))
		fct_report("peak_rss_mb", "%.1f", (double)ru.ru_maxrss / 1024);
	fct_mesh_free(&out);
	free(vs.image);
	free(vs.depth);
	free(vs.dposes);
	free(o.poses);
	free(o.images);
	fct_conf_free(&conf);
	return 0;
}
