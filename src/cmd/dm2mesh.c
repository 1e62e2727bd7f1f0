/* dm2mesh - a depth map (or sparse points with image coordinates) to a
 * triangle mesh: Kang, Johnson and Szeliski, "Extraction of Concise and
 * Realistic 3-D Models from Real Data" (DEC CRL 95/7), sections 2 and 7:
 * points that carry image coordinates lie on a 2-D manifold parameterised by
 * them, so a planar triangulation of the image coordinates connects them --
 * the pixel grid for a dense map, the Delaunay triangulation for sparse
 * points. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "depthmesh.h"
#include "header.h"
#include "image.h"
#include "meshio.h"
#include "path.h"
#include "sparsemesh.h"

static const char usage[] =
	"usage: dm2mesh [-aqv] [-o file] [-K fx,fy,cx,cy | name] [--camera file]\n"
	"               [--cylindrical f,cy,theta0] [--depth-scale s] [--baseline b]\n"
	"               [--focal f] [--doffs d] [--range min,max] [--step n] [-j jump]\n"
	"               [--max-angle deg] [--min-faces n] [--noise model | file]\n"
	"               [--pose file] [--image file] [depth-image]\n"
	"       dm2mesh --points [-aqv] [-o file] [camera options] [--max-edge l]\n"
	"               [-j jump] [--pose file] [--image file] [points]\n"
	"Mesh a depth image (16- or 8-bit PNG, PFM) by its pixel grid, or sparse points\n"
	"with image coordinates by the Delaunay triangulation of those coordinates, in\n"
	"the camera frame (the world frame with --pose).\n"
	"  -a                 write ascii PLY\n"
	"  -K fx,fy,cx,cy     pinhole camera (pixels); or a dataset's camera by name:\n"
	"                     tum tum1 tum2 tum3 redwood primesense kinect icl-nuim\n"
	"                     7scenes (which also sets its depth scale)\n"
	"      --camera file  camera from a file: Open3D intrinsic JSON, a 3x3 K matrix,\n"
	"                     a line \"camera pinhole|cylindrical ...\", or Middlebury's\n"
	"                     calib.txt (then disparities with its baseline and doffs)\n"
	"      --cylindrical f,cy,theta0\n"
	"                     cylindrical panorama camera (depth = distance from the\n"
	"                     vertical axis); f and cy may be empty for W/(2 pi) and\n"
	"                     (H-1)/2\n"
	"      --depth-scale s\n"
	"                     PNG depth units per metre (default 1000; TUM 5000); given,\n"
	"                     it also divides PFM samples\n"
	"      --baseline b   the image holds disparities: depth = b * focal / disparity\n"
	"      --focal f      focal length for disparities (default the camera's)\n"
	"      --doffs d      disparity offset: depth = b * focal / (disparity + d)\n"
	"                     (Middlebury's doffs; default 0, or the calib.txt's)\n"
	"      --range min,max\n"
	"                     depths outside are no data (metres)\n"
	"      --step n       use every n-th pixel of every n-th row (default 1)\n"
	"  -j jump            cut a face where depth changes by more than jump times\n"
	"                     the pixel footprint per pixel (default 10)\n"
	"      --max-angle deg\n"
	"                     the same as a grazing angle: jump = tan(deg)\n"
	"      --min-faces n  drop connected pieces of fewer faces (default 8)\n"
	"      --noise model  the sensor's noise: none, kinect[:F,B[,SD[,STEP]]],\n"
	"                     tof[:A,B], poly:A,B,C, stereo:FB,SD[,DOFFS], or a file\n"
	"                     holding a line \"noise ...\" (mkscene's viewNN.noise);\n"
	"                     writes vertex property sigma and the noise comment\n"
	"                     (default: kinect for a dataset's camera name, else none)\n"
	"      --points       input is sparse points: lines \"u v x y z\", or PLY with\n"
	"                     vertex properties u v x y z\n"
	"      --max-edge l   drop Delaunay faces with a 3-D edge longer than l\n"
	"  -o file            output file (default standard output)\n"
	"      --pose file    camera-to-world pose (4x4 or 3x4 matrix, or a pose line):\n"
	"                     write world coordinates and the pose comment\n"
	"      --image file   the co-registered image, recorded as TextureFile (with\n"
	"                     --points, its size is the camera's when not given)\n"
	"  -q                 quiet\n"
	"  -v                 report counts, times and faces/s on stderr\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum {
	OPT_CAMERA = 256, OPT_CYL, OPT_SCALE, OPT_BASELINE, OPT_FOCAL, OPT_RANGE, OPT_STEP,
	OPT_ANGLE, OPT_MINFACES, OPT_NOISE, OPT_POINTS, OPT_MAXEDGE, OPT_POSE, OPT_IMAGE, OPT_VERSION,
	OPT_DOFFS
};

struct options {
	const char *out, *camera_file, *pose_file, *image_file, *input;
	const char *K, *cylindrical, *noise;
	int ascii, points, scale_given, doffs_given;
	double focal, max_edge;
	struct fct_depth_params depth;
};

/* The camera the options name; width and height of a size-less camera come
 * from the image (w, h; 0 for sparse points without a size). */
static void resolve_camera(struct options *o, struct fct_camera *cam, int w, int h)
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
		fct_opt_cylindrical(o->cylindrical, w, h, cam);
	} else if (!o->points) {
		fct_usage_error("no camera: give -K, --camera or --cylindrical");
	}
	if (cam->kind != FCT_CAMERA_NONE && cam->width == 0)
		cam->width = w, cam->height = h;
}

/* The noise model: --noise's (a model parsed with the options, or a file),
 * else the one a dataset's camera name implies; the unit of the image's
 * depth encoding when the model gives none. */
static void resolve_noise(struct options *o, const struct fct_image *img)
{
	struct fct_noise *nz = &o->depth.noise;
	struct fct_err err;
	if (o->noise && !fct_noise_names_model(o->noise) && fct_noise_read_file(o->noise, nz, &err))
		fct_die_err(&err);
	if (!o->noise && o->K)
		fct_noise_named(o->K, nz);
	if (nz->model != FCT_NOISE_UNKNOWN && nz->unit == 0)
		nz->unit = fct_depth_unit(img, &o->depth);
}

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"camera", required_argument, NULL, OPT_CAMERA},
		{"cylindrical", required_argument, NULL, OPT_CYL},
		{"depth-scale", required_argument, NULL, OPT_SCALE},
		{"baseline", required_argument, NULL, OPT_BASELINE},
		{"focal", required_argument, NULL, OPT_FOCAL},
		{"doffs", required_argument, NULL, OPT_DOFFS},
		{"range", required_argument, NULL, OPT_RANGE},
		{"step", required_argument, NULL, OPT_STEP},
		{"max-angle", required_argument, NULL, OPT_ANGLE},
		{"min-faces", required_argument, NULL, OPT_MINFACES},
		{"noise", required_argument, NULL, OPT_NOISE},
		{"points", no_argument, NULL, OPT_POINTS},
		{"max-edge", required_argument, NULL, OPT_MAXEDGE},
		{"pose", required_argument, NULL, OPT_POSE},
		{"image", required_argument, NULL, OPT_IMAGE},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ahj:K:o:qv";
	int c;
	double r[2];
	memset(o, 0, sizeof *o);
	fct_depth_params_default(&o->depth);
	o->max_edge = HUGE_VAL;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'j': o->depth.grid.max_jump = fct_opt_double("-j", optarg, 0, HUGE_VAL); break;
		case 'K': o->K = optarg; break;
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("dm2mesh (facet) " FCT_VERSION); exit(0);
		case OPT_CAMERA: o->camera_file = optarg; break;
		case OPT_CYL: o->cylindrical = optarg; break;
		case OPT_SCALE:
			o->depth.depth_scale = fct_opt_double("--depth-scale", optarg, 1e-300, 1e300);
			o->depth.scale_float = o->scale_given = 1;
			break;
		case OPT_BASELINE: o->depth.baseline = fct_opt_double("--baseline", optarg, 1e-300, 1e300); break;
		case OPT_FOCAL: o->focal = fct_opt_double("--focal", optarg, 1e-300, 1e300); break;
		case OPT_DOFFS:
			o->depth.doffs = fct_opt_double("--doffs", optarg, -1e9, 1e9);
			o->doffs_given = 1;
			break;
		case OPT_RANGE:
			fct_opt_doubles("--range", optarg, r, 2);
			if (!(r[0] >= 0 && r[1] > r[0]))
				fct_usage_error("--range: expected 0 <= min < max");
			o->depth.min_depth = r[0], o->depth.max_depth = r[1];
			break;
		case OPT_STEP: o->depth.step = (int)fct_opt_long("--step", optarg, 1, 1 << 20); break;
		case OPT_ANGLE:
			o->depth.grid.max_jump = tan(fct_opt_double("--max-angle", optarg, 0, 89.999) * M_PI / 180);
			break;
		case OPT_MINFACES: o->depth.grid.min_faces = (size_t)fct_opt_long("--min-faces", optarg, 0, 1L << 40); break;
		case OPT_NOISE: o->noise = optarg; break;
		case OPT_POINTS: o->points = 1; break;
		case OPT_MAXEDGE: o->max_edge = fct_opt_double("--max-edge", optarg, 0, HUGE_VAL); break;
		case OPT_POSE: o->pose_file = optarg; break;
		case OPT_IMAGE: o->image_file = optarg; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	o->input = fct_one_operand(argc, argv, optind, "-");
	if (o->focal > 0 && !(o->depth.baseline > 0))
		fct_usage_error("--focal is for disparities and needs --baseline");
	if (o->points && (o->depth.baseline > 0 || o->depth.step != 1))
		fct_usage_error("--points takes no --baseline or --step");
	if (!o->points && o->max_edge < HUGE_VAL)
		fct_usage_error("--max-edge is for --points");
	if (o->points && o->noise)
		fct_usage_error("--noise is for depth images");
	if (o->noise && fct_noise_names_model(o->noise)) {
		struct fct_err err;
		if (fct_noise_parse(&o->depth.noise, o->noise, &err))
			fct_usage_error("--%s", err.msg);
	}
}

static struct fct_mesh mesh_depth(struct options *o, struct fct_camera *cam)
{
	struct fct_err err;
	struct fct_image img;
	if (fct_image_read_file(&img, o->input, NULL, &err))
		fct_die_err(&err);
	resolve_camera(o, cam, img.width, img.height);
	if (o->doffs_given && !(o->depth.baseline > 0))
		fct_usage_error("--doffs is for disparities and needs --baseline");
	if (o->depth.baseline > 0)
		o->depth.focal = o->focal > 0 ? o->focal
		               : cam->kind == FCT_CAMERA_CYLINDRICAL ? cam->f : cam->fx;
	resolve_noise(o, &img);
	char why[300];
	if (fct_depth_implausible(why, sizeof why, &img, cam, &o->depth))
		fct_warn("%s: %s", fct_path_display(o->input), why);
	struct fct_mesh m;
	fct_report("pixels", "%zu", (size_t)img.width * (size_t)img.height);
	struct fct_grid_stats st;
	if (fct_depth_mesh(&m, &img, cam, &o->depth, &st, &err)) {
		fct_image_free(&img);
		fct_err_prefix(&err, "%s", fct_path_display(o->input));
		fct_die_err(&err);
	}
	fct_image_free(&img);
	fct_report("jump_faces", "%zu", st.jump_faces);
	fct_report("speck_faces", "%zu", st.speck_faces);
	return m;
}

static struct fct_mesh mesh_points(struct options *o, struct fct_camera *cam)
{
	struct fct_err err;
	struct fct_image_points pts;
	if (fct_image_points_read_file(&pts, o->input, &err))
		fct_die_err(&err);
	resolve_camera(o, cam, 0, 0);
	if (cam->kind != FCT_CAMERA_NONE && cam->width == 0 && o->image_file) {
		/* The image gives the size that texture coordinates need. */
		struct fct_image img;
		if (fct_image_read_file(&img, o->image_file, NULL, &err)) {
			fct_image_points_free(&pts);
			fct_die_err(&err);
		}
		cam->width = img.width, cam->height = img.height;
		fct_image_free(&img);
	}
	struct fct_sparse_params sp = { o->depth.grid.max_jump, o->max_edge };
	struct fct_mesh m;
	fct_report("points", "%zu", pts.n);
	struct fct_sparse_stats st;
	int rc = fct_sparse_mesh(&m, &pts, cam, &sp, &st, &err);
	fct_image_points_free(&pts);
	if (rc)
		fct_die_err(&err);
	fct_report("duplicates", "%zu", st.duplicates);
	fct_report("jump_faces", "%zu", st.jump_faces);
	fct_report("long_faces", "%zu", st.long_faces);
	return m;
}

int main(int argc, char **argv)
{
	fct_cli_init("dm2mesh");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	double pose[12];
	if (o.pose_file && fct_pose_read_file(o.pose_file, pose, &err))
		fct_die_err(&err);

	double t0 = fct_now(), c0 = fct_cpu_time();
	struct fct_camera cam;
	struct fct_mesh m = o.points ? mesh_points(&o, &cam) : mesh_depth(&o, &cam);
	double mesh_s = fct_now() - t0;

	if (o.pose_file) {
		/* float holds world coordinates to 1/100 of the nearest vertex's
		 * pixel footprint, or they are written as double */
		double near = HUGE_VAL;
		for (size_t v = 0; v < m.nv; v++) {
			near = fmin(near, hypot(hypot(m.xyz[3 * v], m.xyz[3 * v + 1]), m.xyz[3 * v + 2]));
			fct_pose_apply(pose, &m.xyz[3 * v], &m.xyz[3 * v]);
		}
		if (fct_mesh_keep_precision(&m, 0.01 * near * o.depth.step * fct_camera_pixel_angle(&cam)))
			fct_report("double_xyz", "1");
	}
	char noise[256];
	fct_noise_format(&o.depth.noise, noise, sizeof noise);
	fct_report("noise", "%s", *noise ? noise : "unknown");
	if (fct_header_set_camera(&m, &cam, &err) ||
	    fct_header_set_noise(&m, &o.depth.noise, &err) ||
	    (o.pose_file && fct_header_set_pose(&m, pose, &err)) ||
	    (o.image_file && fct_header_set_texture(&m, 0, o.image_file, &err)) ||
	    fct_header_add_provenance(&m, "dm2mesh", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, o.out, o.ascii, &err))
		fct_die_err(&err);
	double total_s = fct_now() - t0, cpu_s = fct_cpu_time() - c0;

	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("mesh_s", "%.4f", mesh_s);
	fct_report("total_s", "%.4f", total_s);
	fct_report("cpu_s", "%.4f", cpu_s);
	fct_report("faces_per_s", "%.0f", total_s > 0 ? m.nf / total_s : 0);
	fct_mesh_free(&m);
	return 0;
}
