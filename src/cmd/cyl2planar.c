/* cyl2planar - planar (pinhole) views of a cylindrical panorama, and a
 * model textured through them: Kang, Johnson and Szeliski, "Extraction of
 * Concise and Realistic 3-D Models from Real Data" (DEC CRL 95/7),
 * section 7.  The library does the work (cylview.h). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "render/cylview.h"
#include "io/header.h"
#include "io/image.h"
#include "io/meshio.h"
#include "io/output.h"
#include "core/path.h"

static const char usage[] =
	"usage: cyl2planar [-qv] [--camera file | --cylindrical f,cy,theta0] [--pose file]\n"
	"                  [--count n] [--step deg] [--fov deg] [--yaw deg] [--size WxH]\n"
	"                  [--no-seam-check] -o dir panorama\n"
	"       cyl2planar --mesh file [-aqv] [camera and view options] [--no-split]\n"
	"                  -o model [panorama]\n"
	"Split a 360-degree cylindrical panorama into overlapping planar views at\n"
	"regular yaw angles (dir/viewNN.png with viewNN.camera and viewNN.pose), or\n"
	"texture a mesh in the panorama's frame from them: each face from the view in\n"
	"which it lies whole and is seen most frontally.\n"
	"  -a                  write ascii PLY\n"
	"  -o dir | model      the folder of the views; with --mesh, the model:\n"
	"                      name.obj (with .mtl) or name.ply (per-face texcoord and\n"
	"                      texnumber), its views beside it as name.viewNN.png\n"
	"  -q                  quiet\n"
	"  -v                  report sizes, counts and times on stderr\n"
	"      --camera file   the panorama's camera: a line \"camera cylindrical W H f\n"
	"                      cy theta0\" (default: the mesh's camera comment)\n"
	"      --cylindrical f,cy,theta0\n"
	"                      the panorama's camera; f and cy may be empty for\n"
	"                      W/(2 pi) and (H-1)/2 (the default without a mesh)\n"
	"      --count n       number of views (default 8, or 360/step)\n"
	"      --fov deg       horizontal field of view of each view, below 180\n"
	"                      (default 90)\n"
	"      --mesh file     the mesh to texture (PLY or OBJ); the panorama defaults\n"
	"                      to its TextureFile\n"
	"      --no-seam-check accept a panorama whose last and first columns do not\n"
	"                      meet\n"
	"      --no-split      do not bisect faces that fit in no view: name them\n"
	"      --pose file     the panorama's camera-to-world pose (default: the mesh's)\n"
	"      --size WxH      view size in pixels (default: the panorama's resolution\n"
	"                      at the view's centre, and its whole height)\n"
	"      --step deg      degrees between views (default 360/count)\n"
	"      --yaw deg       azimuth of view 0 (default 0: the camera's forward axis)\n"
	"  -h, --help          this help\n"
	"      --version       print the version\n";

enum { OPT_CAMERA = 256, OPT_CYL, OPT_POSE, OPT_COUNT, OPT_STEP, OPT_FOV, OPT_YAW, OPT_SIZE,
       OPT_MESH, OPT_NOSEAM, OPT_NOSPLIT, OPT_VERSION };

struct options {
	const char *out, *camera, *cylindrical, *pose, *mesh, *pano, *step_arg;
	int ascii, seam_check, split, count_given;
	struct fct_cylview_params view;
};

static void parse_size(const char *arg, int *w, int *h)
{
	char *x = strchr(arg, 'x');
	if (!x || x == arg)
		fct_usage_error("--size: expected WxH, got \"%s\"", arg);
	char buf[32];
	size_t n = (size_t)(x - arg);
	if (n >= sizeof buf)
		fct_usage_error("--size: expected WxH, got \"%s\"", arg);
	memcpy(buf, arg, n);
	buf[n] = 0;
	*w = (int)fct_opt_long("--size", buf, 1, 1 << 16);
	*h = (int)fct_opt_long("--size", x + 1, 1, 1 << 16);
}

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"camera", required_argument, NULL, OPT_CAMERA},
		{"cylindrical", required_argument, NULL, OPT_CYL},
		{"pose", required_argument, NULL, OPT_POSE},
		{"count", required_argument, NULL, OPT_COUNT},
		{"step", required_argument, NULL, OPT_STEP},
		{"fov", required_argument, NULL, OPT_FOV},
		{"yaw", required_argument, NULL, OPT_YAW},
		{"size", required_argument, NULL, OPT_SIZE},
		{"mesh", required_argument, NULL, OPT_MESH},
		{"no-seam-check", no_argument, NULL, OPT_NOSEAM},
		{"no-split", no_argument, NULL, OPT_NOSPLIT},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "aho:qv";
	memset(o, 0, sizeof *o);
	fct_cylview_params_default(&o->view);
	o->seam_check = o->split = 1;
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("cyl2planar (facet) " FCT_VERSION); exit(0);
		case OPT_CAMERA: o->camera = optarg; break;
		case OPT_CYL: o->cylindrical = optarg; break;
		case OPT_POSE: o->pose = optarg; break;
		case OPT_COUNT:
			o->view.count = (int)fct_opt_long("--count", optarg, 0, FCT_CYLVIEW_MAX_COUNT);
			if (o->view.count == 0)
				fct_usage_error("--count: zero views");
			o->count_given = 1;
			break;
		case OPT_STEP:
			o->view.step = fct_opt_double("--step", optarg, 0, 360);
			if (!(o->view.step > 0))
				fct_usage_error("--step: must be above 0 degrees");
			o->step_arg = optarg;
			break;
		case OPT_FOV:
			o->view.fov = fct_opt_double("--fov", optarg, -HUGE_VAL, HUGE_VAL);
			if (!(o->view.fov > 0 && o->view.fov < 180))
				fct_usage_error("--fov: %s degrees: a planar view sees less than 180", optarg);
			break;
		case OPT_YAW: o->view.yaw0 = fct_opt_double("--yaw", optarg, -36000, 36000); break;
		case OPT_SIZE: parse_size(optarg, &o->view.width, &o->view.height); break;
		case OPT_MESH: o->mesh = optarg; break;
		case OPT_NOSEAM: o->seam_check = 0; break;
		case OPT_NOSPLIT: o->split = 0; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	o->pano = fct_one_operand(argc, argv, optind, NULL);
	if (!o->out)
		fct_usage_error("-o %s is needed", o->mesh ? "model" : "dir");
	if (!o->mesh && !o->pano)
		fct_usage_error("a panorama is needed");
	if (o->camera && o->cylindrical)
		fct_usage_error("--camera and --cylindrical exclude each other");
	if (o->step_arg && !o->count_given) {
		double n = ceil(360 / o->view.step - 1e-9);
		if (n > FCT_CYLVIEW_MAX_COUNT)
			fct_usage_error("--step: %s degrees makes more than %d views", o->step_arg,
			                FCT_CYLVIEW_MAX_COUNT);
		o->view.count = (int)n;
	}
}

static char *xprintf(const char *fmt, const char *a, int k, const char *ext)
{
	size_t n = strlen(a) + strlen(ext) + 32;
	char *p = malloc(n);
	if (!p)
		fct_die(1, "out of memory");
	snprintf(p, n, fmt, a, k, ext);
	return p;
}

int main(int argc, char **argv)
{
	fct_cli_init("cyl2planar");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	double t0 = fct_now();

	/* The mesh, its camera and pose. */
	struct fct_mesh m;
	fct_mesh_init(&m);
	struct fct_camera cam;
	memset(&cam, 0, sizeof cam);
	double pose[12];
	int have_pose = 0, have_cam = 0;
	const char *mname = o.mesh ? fct_path_display(o.mesh) : NULL;
	if (o.mesh) {
		if (fct_mesh_read_file(&m, o.mesh, NULL, &err))
			fct_die_err(&err);
		int r = fct_header_camera(&m, &cam, &err);
		if (r < 0)
			fct_die_err_at(&err, "%s", mname);
		have_cam = r;
		if ((r = fct_header_pose(&m, pose, &err)) < 0)
			fct_die_err_at(&err, "%s", mname);
		have_pose = r;
		if (!o.pano && !(o.pano = fct_header_texture(&m, 0)))
			fct_usage_error("%s: no TextureFile: name the panorama", mname);
	}
	if (o.pose) {
		if (fct_pose_read_file(o.pose, pose, &err))
			fct_die_err(&err);
		have_pose = 1;
	}

	struct fct_image img;
	double t1 = fct_now();
	if (fct_image_read_file(&img, o.pano, NULL, &err))
		fct_die_err(&err);
	double read_s = fct_now() - t1;
	const char *pname = fct_path_display(o.pano);
	if (o.camera) {
		if (fct_camera_read_file(o.camera, &cam, &err))
			fct_die_err(&err);
		have_cam = 1;
	} else if (o.cylindrical || !have_cam) {
		fct_opt_cylindrical(o.cylindrical ? o.cylindrical : ",,0", img.width, img.height, &cam);
		cam.width = img.width, cam.height = img.height;
		have_cam = 1;
	}
	if (cam.kind != FCT_CAMERA_CYLINDRICAL)
		fct_die(1, "%s: the camera is not cylindrical", o.camera ? o.camera : mname);
	if (cam.width == 0)
		cam.width = img.width, cam.height = img.height;
	double seam_ratio;
	if (fct_cylview_check_panorama(&img, &cam, o.seam_check, &seam_ratio, &err))
		fct_die_err_at(&err, "%s", pname);
	if (o.mesh && img.type == FCT_PIX_F32)
		fct_die(1, "%s: a PFM image cannot texture a model: give a PNG", pname);

	size_t nviews = (size_t)o.view.count;
	struct fct_cylview *views = calloc(nviews, sizeof *views);
	if (!views)
		fct_die(1, "out of memory");
	if (fct_cylview_plan(&cam, &o.view, views, &err)) {
		free(views);
		fct_die_err(&err);
	}
	if (!o.mesh)
		fct_make_folder(NULL, o.out);

	if (o.mesh) {
		/* The model textured from the views, written beside it. */
		struct fct_cylview_model_stats mst;
		double t2 = fct_now();
		if (fct_cylview_texture_model(&m, &img, &cam, have_pose ? pose : NULL, &o.view, o.split,
		                              mname, o.out, &mst, &err) ||
		    fct_header_add_provenance(&m, "cyl2planar", argc - 1, argv + 1, &err) ||
		    fct_mesh_write_file(&m, o.out, o.ascii, &err))
			fct_die_err(&err);
		fct_report("panorama", "%dx%d", img.width, img.height);
		fct_report("channels", "%d", img.channels);
		fct_report("views", "%zu", nviews);
		fct_report("view_size", "%dx%d", views[0].cam.width, views[0].cam.height);
		fct_report("focal", "%.9g", views[0].cam.fx);
		fct_report("written", "%zu", mst.written);
		fct_report("seam_ratio", "%.4g", seam_ratio);
		fct_report("faces", "%zu", mst.assign.faces);
		fct_report("splits", "%zu", mst.assign.splits);
		fct_report("views_used", "%zu", mst.assign.views_used);
		fct_report("max_depth_ratio", "%.9g", mst.assign.max_ratio);
		fct_report("read_s", "%.4f", read_s);
		fct_report("texture_s", "%.4f", fct_now() - t2);
		fct_report("total_s", "%.4f", fct_now() - t0);
		free(views);
		fct_image_free(&img);
		fct_mesh_free(&m);
		return 0;
	}

	/* The views, their cameras and poses, in the folder made above. */
	const char *ext = img.type == FCT_PIX_F32 ? ".pfm" : ".png";
	double split_s = 0, write_s = 0;
	size_t pixels = 0;
	for (size_t k = 0; k < nviews; k++) {
		char *name = xprintf("%s/view%02d%s", o.out, (int)k, ext);
		struct fct_image vi;
		double t3 = fct_now();
		if (fct_cylview_render(&img, &cam, &views[k], &vi, &err))
			fct_die_err_at(&err, "%s", pname);
		double t4 = fct_now();
		split_s += t4 - t3;
		fct_write_image_or_die(&vi, name);
		free(name);
		pixels += (size_t)vi.width * vi.height;
		fct_image_free(&vi);
		char text[600], line[300];
		fct_camera_format(&views[k].cam, line, sizeof line);
		snprintf(text, sizeof text, "camera %s\n", line);
		char *p = xprintf("%s/view%02d%s", o.out, (int)k, ".camera");
		fct_write_text_or_die(text, p);
		free(p);
		double vp[12];
		fct_cylview_pose(&views[k], have_pose ? pose : NULL, vp);
		size_t len = 0;
		for (int i = 0; i < 12; i++)
			len += (size_t)snprintf(text + len, sizeof text - len, "%.17g%c",
			                        vp[i] + 0.0, i % 4 == 3 ? '\n' : ' ');
		snprintf(text + len, sizeof text - len, "0 0 0 1\n");
		p = xprintf("%s/view%02d%s", o.out, (int)k, ".pose");
		fct_write_text_or_die(text, p);
		free(p);
		write_s += fct_now() - t4;
	}

	fct_report("panorama", "%dx%d", img.width, img.height);
	fct_report("channels", "%d", img.channels);
	fct_report("views", "%zu", nviews);
	fct_report("view_size", "%dx%d", views[0].cam.width, views[0].cam.height);
	fct_report("focal", "%.9g", views[0].cam.fx);
	fct_report("written", "%zu", nviews);
	fct_report("seam_ratio", "%.4g", seam_ratio);
	fct_report("read_s", "%.4f", read_s);
	fct_report("split_s", "%.4f", split_s);
	fct_report("pixels_per_s", "%.0f", split_s > 0 ? pixels / split_s : 0);
	fct_report("write_s", "%.4f", write_s);
	fct_report("total_s", "%.4f", fct_now() - t0);
	free(views);
	fct_image_free(&img);
	fct_mesh_free(&m);
	return 0;
}
