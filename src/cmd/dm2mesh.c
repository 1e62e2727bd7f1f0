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

#include "cli/cli.h"
#include "depth/depthmesh.h"
#include "cli/depthopts.h"
#include "io/header.h"
#include "io/image.h"
#include "io/meshio.h"
#include "core/path.h"
#include "depth/sparsemesh.h"

static const char usage[] =
	"usage: dm2mesh [-aqv] [-o file] [-K fx,fy,cx,cy | name] [--camera file]\n"
	"               [--cylindrical f,cy,theta0] [--depth-scale s] [--depth-code c]\n"
	"               [--baseline b] [--focal f] [--doffs d] [--range min,max]\n"
	"               [--step n] [-j jump] [--max-angle deg] [--min-faces n]\n"
	"               [--noise model | file] [--pose file] [--image file]\n"
	"               [depth-image]\n"
	"       dm2mesh --points [-aqv] [-o file] [camera options] [--max-edge l]\n"
	"               [-j jump] [--pose file] [--image file] [points]\n"
	"Mesh a depth image (16- or 8-bit PNG or PGM, PFM) by its pixel grid, or sparse\n"
	"points with image coordinates by the Delaunay triangulation of those\n"
	"coordinates, in the camera frame (the world frame with --pose).\n"
	"  -a                 write ascii PLY\n"
	"  -K fx,fy,cx,cy     pinhole camera (pixels); or a dataset's camera by name:\n"
	"                     tum tum1 tum2 tum3 redwood primesense kinect icl-nuim\n"
	"                     7scenes nyu (which also sets its depth scale and code)\n"
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
	"      --depth-code c the samples' encoding, comma-separated: swap (bytes),\n"
	"                     rotate (SUN RGB-D), kinect-raw (disparity codes), or\n"
	"                     the datasets nyu (swap,kinect-raw) and sun (rotate)\n"
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

enum { OPT_MINFACES = 256, OPT_POINTS, OPT_MAXEDGE, OPT_VERSION };

struct options {
	const char *out, *input;
	int ascii, points;
	double max_edge;
	struct fct_depth_opts d;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		FCT_DEPTH_LONGOPTS,
		{"min-faces", required_argument, NULL, OPT_MINFACES},
		{"points", no_argument, NULL, OPT_POINTS},
		{"max-edge", required_argument, NULL, OPT_MAXEDGE},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ahj:K:o:qv";
	int c;
	memset(o, 0, sizeof *o);
	fct_depth_opts_init(&o->d);
	o->max_edge = HUGE_VAL;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_depth_opt(&o->d, c, optarg))
			continue;
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("dm2mesh (facet) " FCT_VERSION); exit(0);
		case OPT_MINFACES: o->d.depth.grid.min_faces = (size_t)fct_opt_long("--min-faces", optarg, 0, 1L << 40); break;
		case OPT_POINTS: o->points = 1; break;
		case OPT_MAXEDGE: o->max_edge = fct_opt_double("--max-edge", optarg, 0, HUGE_VAL); break;
		default: fct_bad_option(optstring, argv);
		}
	}
	o->input = fct_one_operand(argc, argv, optind, "-");
	if (o->points && (o->d.depth.baseline > 0 || o->d.depth.step != 1))
		fct_usage_error("--points takes no --baseline or --step");
	if (!o->points && o->max_edge < HUGE_VAL)
		fct_usage_error("--max-edge is for --points");
	if (o->points && o->d.noise)
		fct_usage_error("--noise is for depth images");
	fct_depth_opts_check(&o->d);
}

static struct fct_mesh mesh_depth(struct options *o, struct fct_camera *cam)
{
	struct fct_err err;
	struct fct_image img;
	if (fct_image_read_file(&img, o->input, NULL, &err))
		fct_die_err(&err);
	fct_depth_opts_resolve(&o->d, cam, &img, fct_path_display(o->input));
	struct fct_mesh m;
	fct_report("pixels", "%zu", (size_t)img.width * (size_t)img.height);
	struct fct_grid_stats st;
	if (fct_depth_mesh(&m, &img, cam, &o->d.depth, &st, &err))
		fct_die_err_at(&err, "%s", fct_path_display(o->input));
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
	fct_depth_opts_camera(&o->d, cam, 0, 0, 0);
	if (cam->kind != FCT_CAMERA_NONE && cam->width == 0 && o->d.image_file) {
		/* The image gives the size that texture coordinates need. */
		struct fct_image img;
		if (fct_image_read_file(&img, o->d.image_file, NULL, &err)) {
			fct_image_points_free(&pts);
			fct_die_err(&err);
		}
		cam->width = img.width, cam->height = img.height;
		fct_image_free(&img);
	}
	struct fct_sparse_params sp = { o->d.depth.grid.max_jump, o->max_edge };
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
	fct_depth_opts_read_pose(&o.d);

	double t0 = fct_now(), c0 = fct_cpu_time();
	struct fct_camera cam;
	struct fct_mesh m = o.points ? mesh_points(&o, &cam) : mesh_depth(&o, &cam);
	double mesh_s = fct_now() - t0;

	if (fct_depth_opts_finish(&o.d, &m, &cam, &err))
		fct_die_err(&err);
	if (o.d.double_xyz)
		fct_report("double_xyz", "1");
	char noise[256];
	fct_noise_format(&o.d.depth.noise, noise, sizeof noise);
	fct_report("noise", "%s", *noise ? noise : "unknown");
	if (fct_header_add_provenance(&m, "dm2mesh", argc - 1, argv + 1, &err) ||
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
