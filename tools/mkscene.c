/* mkscene - synthetic test scenes with exact ground truth: a room (or a
 * small scene) as a mesh with its true planes, rendered by ray casting into
 * depth and colour images from pinhole cameras and a cylindrical panorama,
 * with the sensor noise of depth cameras.  The library does the work
 * (scene.h); this is options, files and figures. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/image.h"
#include "io/meshio.h"
#include "io/output.h"
#include "core/path.h"
#include "scene/scene.h"

static const char usage[] =
	"usage: mkscene [-qv] [-K fx,fy,cx,cy] [--albedo checker | grain] [--depth png16 | pfm]\n"
	"               [--depth-scale s] [--fx f] [--grazing degrees] [--jitter px]\n"
	"               [--missing fraction] [--noise model] [--outliers fraction]\n"
	"               [--panorama WxH] [--points] [--range near,far] [--scene name]\n"
	"               [--seed n] [--size WxH] [--views n] -o dir\n"
	"Synthesise a scene with exact ground truth into the folder dir: scene.ply\n"
	"(the mesh, with face property patch and its plane element), scene.txt (its\n"
	"surfaces), and for each view NN: viewNN.depth.pfm (or .png), viewNN.truth.pfm\n"
	"(without noise), viewNN.color.png, viewNN.patch.png (patch + 1, 0 none),\n"
	"viewNN.camera, viewNN.pose, viewNN.noise (the noise model, for dm2mesh\n"
	"--noise); pano.* likewise for the panorama.\n"
	"  -K fx,fy,cx,cy      pinhole intrinsics in pixels (default from --fx)\n"
	"  -o dir              the output folder, made if missing\n"
	"  -q                  quiet\n"
	"  -v                  report sizes, times and noise figures on stderr\n"
	"      --albedo a      the surfaces' colour: checker (default), or grain: the\n"
	"                      checker times a fine value noise (4 and 2 cm), detail\n"
	"                      that texture keeps and 1 cm vertex colours blur\n"
	"      --depth fmt     depth images as pfm (float metres, default) or png16\n"
	"      --depth-scale s png16 units per metre (default 1000)\n"
	"      --fx f          focal length in pixels, fx = fy = f, centre in the\n"
	"                      middle of the image (default 525)\n"
	"      --grazing deg   drop pixels seen more than deg from their surface's\n"
	"                      normal (default 90: none)\n"
	"      --jitter px     sample each pixel's depth this far off its centre (a\n"
	"                      normal deviate per axis; default 0.5 with --noise\n"
	"                      kinect, else 0)\n"
	"      --missing f     drop this fraction of the pixels at random (default 0)\n"
	"      --noise model   depth noise: a sensor model (as dm2mesh --noise: none,\n"
	"                      kinect[:F,B[,SD[,STEP]]], tof[:A,B], poly:A,B,C,\n"
	"                      stereo:FB,SD[,DOFFS]; kinect = disparity noise in\n"
	"                      1/8-pixel steps, as ICL-NUIM), or Gaussian along the\n"
	"                      rays: gaussian:sigma (metres) and kinect-gauss:a\n"
	"                      (sigma = a z^2), which may be given together\n"
	"                      (default none)\n"
	"      --outliers f    replace this fraction of the pixels by depths uniform\n"
	"                      in [0.5, 1.5] times the truth (default 0)\n"
	"      --panorama WxH  also render a cylindrical panorama of that size\n"
	"      --points        also write viewNN.points.ply: each depth pixel's point\n"
	"                      in the world frame, with its colour\n"
	"      --range n,f     drop pixels whose true depth is outside [n, f] metres\n"
	"      --scene name    room (default), plane, steps, cube or sphere\n"
	"      --seed n        seed of the noise (default 1)\n"
	"      --size WxH      pinhole image size (default 640x480)\n"
	"      --views n       number of pinhole views (default 1; 0: none)\n"
	"  -h, --help          this help\n"
	"      --version       print the version\n";

enum { MAX_PIXELS = 1 << 26, MAX_VIEWS = 1000 };

struct options {
	const char *dir, *scene;
	int views, width, height, pano_w, pano_h, png16, points, grain;
	int have_k, have_fx;
	double k[4], fx, depth_scale, jitter;
	struct fct_scene_noise noise;
	struct fct_noise model;   /* what viewNN.noise says; unknown: no file */
	uint64_t seed;
};

/* "WxH" with sides >= 1 and at most MAX_PIXELS pixels. */
static void parse_size(const char *opt, const char *arg, int *w, int *h)
{
	char *end;
	errno = 0;
	long a = strtol(arg, &end, 10), b = 0;
	int ok = end != arg && *end == 'x' && arg[0] >= '0' && arg[0] <= '9';
	if (ok) {
		const char *s = end + 1;
		ok = *s >= '0' && *s <= '9';
		b = strtol(s, &end, 10);
		ok = ok && !*end && errno == 0;
	}
	if (!ok || a < 1 || b < 1 || a > MAX_PIXELS || b > MAX_PIXELS || a * b > MAX_PIXELS)
		fct_usage_error("%s: \"%s\" is not WxH with at most %d pixels", opt, arg, MAX_PIXELS);
	*w = (int)a;
	*h = (int)b;
}

/* One --noise: a Gaussian along the rays (gaussian:S, kinect-gauss:A, which
 * add up) or a sensor model of noise.h, not both. */
static void parse_noise(const char *arg, struct fct_scene_noise *nz)
{
	int sensor = nz->sensor.model != FCT_NOISE_UNKNOWN, gauss = nz->sigma > 0 || nz->kinect_gauss > 0;
	size_t name = strcspn(arg, ":, \t");
	if (!strncmp(arg, "gaussian:", 9) || !strncmp(arg, "kinect-gauss:", 13)) {
		if (sensor)
			fct_usage_error("--noise: %s and a sensor model exclude each other", arg);
		if (arg[0] == 'k')
			nz->kinect_gauss = fct_opt_double("--noise kinect-gauss", arg + 13, 0, 1);
		else
			nz->sigma = fct_opt_double("--noise gaussian", arg + 9, 0, 10);
		return;
	}
	struct fct_err err;
	if (fct_noise_parse(&nz->sensor, arg, &err)) {
		if (!strncmp(err.msg, "noise: \"", 8))
			fct_usage_error("--noise: \"%s\" is not gaussian:sigma, kinect-gauss:a or a sensor model (%s)",
			                arg, fct_noise_models());
		fct_usage_error("--%s", err.msg);
	}
	/* kinect:a was sigma = a z^2 before the structured model took the name. */
	const char *p = arg + name;
	if (!strncmp(arg, "kinect", name) && *p == ':' && !strpbrk(p + 1, ":, \t"))
		fct_usage_error("--noise: %s: sigma = a z^2 is kinect-gauss:a; kinect takes F,B[,SD[,STEP]]", arg);
	if (sensor || gauss)
		fct_usage_error("--noise: %s: one sensor model, without gaussian: or kinect-gauss:", arg);
}

/* The model viewNN.noise gives: the sensor's, or the Gaussian one as poly
 * (gaussian:S is poly S 0 0, kinect-gauss:A poly 0 0 A; both together are
 * no poly, and no file is written), or none; with png16 depth, its unit. */
static void describe_noise(struct options *op)
{
	const struct fct_scene_noise *nz = &op->noise;
	struct fct_noise *m = &op->model;
	memset(m, 0, sizeof *m);
	if (nz->sensor.model != FCT_NOISE_UNKNOWN) {
		*m = nz->sensor;
	} else if (nz->sigma > 0 && nz->kinect_gauss > 0) {
		return;
	} else if (nz->sigma > 0 || nz->kinect_gauss > 0) {
		m->model = FCT_NOISE_POLY;
		m->coef[0] = nz->sigma, m->coef[2] = nz->kinect_gauss;
	} else {
		m->model = FCT_NOISE_NONE;
	}
	if (op->png16)
		m->unit = 1 / op->depth_scale;
}

/* dir/name, malloc'd; exits on failure. */
static char *out_path(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 2;
	char *p = malloc(n);
	if (!p)
		fct_die(1, "out of memory");
	snprintf(p, n, "%s/%s", dir, name);
	return p;
}

static void write_text(const char *dir, const char *name, const char *text)
{
	char *path = out_path(dir, name);
	fct_write_text_or_die(text, path);
	free(path);
}

static void write_image(const char *dir, const char *name, const struct fct_image *img)
{
	char *path = out_path(dir, name);
	fct_write_image_or_die(img, path);
	free(path);
}

static void alloc_image(struct fct_image *img, int w, int h, int c, enum fct_pix t)
{
	struct fct_err err;
	if (fct_image_alloc(img, w, h, c, t, &err))
		fct_die_err(&err);
}

/* A %.17g number without a negative zero. */
static void put_num(char *buf, size_t size, double v)
{
	snprintf(buf, size, "%.17g", v + 0.0);
}

/* The figures summed over all views for -v. */
struct totals {
	size_t images, pixels, hits, overflow;
	double render_s, jitter_s;
	struct fct_scene_noise_stats noise;
};

/* The world-frame point cloud of a depth image, with colours, as a mesh
 * without faces carrying the camera and pose. */
static void write_points(const char *dir, const char *name, const struct fct_camera *cam,
                         const double pose[12], const double *depth, const uint8_t *rgb,
                         int argc, char **argv)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	size_t w = (size_t)cam->width, n = w * (size_t)cam->height, nv = 0;
	for (size_t i = 0; i < n; i++)
		nv += depth[i] > 0;
	for (size_t i = 0; i < n; i++) {
		if (!(depth[i] > 0))
			continue;
		double ray[3], p[3];
		fct_camera_ray(cam, (double)(i % w), (double)(i / w), ray);
		for (int k = 0; k < 3; k++)
			p[k] = depth[i] * ray[k];
		fct_pose_apply(pose, p, p);
		if (fct_mesh_add_vertex(&m, p[0], p[1], p[2], &err) < 0)
			fct_die_err(&err);
	}
	static const char *const names[3] = {"red", "green", "blue"};
	for (int c = 0; c < 3; c++) {
		if (!fct_elem_add_scalar(&m.vertex, names[c], FCT_UINT8, &err))
			fct_die_err(&err);
	}
	struct fct_prop *col[3];
	for (int c = 0; c < 3; c++)
		col[c] = fct_elem_find(&m.vertex, names[c]);
	size_t v = 0;
	for (size_t i = 0; i < n; i++) {
		if (!(depth[i] > 0))
			continue;
		for (int c = 0; c < 3; c++)
			fct_prop_set(col[c], v, rgb[3 * i + c]);
		v++;
	}
	char *path = out_path(dir, name);
	if (fct_header_set_camera(&m, cam, &err) || fct_header_set_pose(&m, pose, &err) ||
	    fct_header_add_provenance(&m, "mkscene", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, path, 0, &err))
		fct_die_err(&err);
	free(path);
	fct_mesh_free(&m);
}

/* Render one view named base ("view00", "pano") and write its files. */
static void do_view(const struct options *op, const struct fct_scene *s, const char *base,
                    const struct fct_camera *cam, const double pose[12], uint64_t stream,
                    struct totals *tot, int argc, char **argv)
{
	struct fct_err err;
	struct fct_render r;
	double t0 = fct_now();
	if (fct_scene_render(s, cam, pose, &r, &err))
		fct_die_err(&err);
	tot->render_s += fct_now() - t0;
	size_t n = (size_t)cam->width * (size_t)cam->height;
	tot->images++;
	tot->pixels += n;
	double *noisy = malloc(sizeof *noisy * n);
	if (!noisy)
		fct_die(1, "out of memory for %zu pixels", n);
	double *sampled = NULL;
	if (op->jitter > 0) {
		t0 = fct_now();
		if (!(sampled = malloc(sizeof *sampled * n)))
			fct_die(1, "out of memory for %zu pixels", n);
		if (fct_scene_render_jitter(s, cam, pose, op->jitter, op->seed, stream, sampled, &err))
			fct_die_err(&err);
		tot->jitter_s += fct_now() - t0;
	}
	struct fct_scene_noise_stats st;
	fct_depth_noise(&op->noise, op->seed, stream, r.depth, sampled, r.cosine, noisy, n, &st);
	free(sampled);
	tot->hits += st.valid;
	struct fct_scene_noise_stats *t = &tot->noise;
	t->valid += st.valid, t->range += st.range, t->grazing += st.grazing;
	t->missing += st.missing, t->outliers += st.outliers, t->noisy += st.noisy, t->lost += st.lost;
	t->sum += st.sum, t->sum2 += st.sum2, t->model2 += st.model2;

	char name[64], text[1024], num[40];
	struct fct_image img;
	/* Depth as measured, the truth, the colours, the patch labels. */
	if (op->png16) {
		alloc_image(&img, cam->width, cam->height, 1, FCT_PIX_U16);
		uint16_t *d = img.data;
		for (size_t i = 0; i < n; i++) {
			double v = floor(noisy[i] * op->depth_scale + 0.5);
			if (v > 65535) {
				tot->overflow++;
				v = 0;
			}
			d[i] = (uint16_t)v;
			noisy[i] = v / op->depth_scale;   /* what the file says, for --points */
		}
		snprintf(name, sizeof name, "%s.depth.png", base);
	} else {
		alloc_image(&img, cam->width, cam->height, 1, FCT_PIX_F32);
		float *d = img.data;
		for (size_t i = 0; i < n; i++) {
			d[i] = (float)noisy[i];
			noisy[i] = d[i];
		}
		snprintf(name, sizeof name, "%s.depth.pfm", base);
	}
	write_image(op->dir, name, &img);
	fct_image_free(&img);

	alloc_image(&img, cam->width, cam->height, 1, FCT_PIX_F32);
	for (size_t i = 0; i < n; i++)
		((float *)img.data)[i] = (float)r.depth[i];
	snprintf(name, sizeof name, "%s.truth.pfm", base);
	write_image(op->dir, name, &img);
	fct_image_free(&img);

	alloc_image(&img, cam->width, cam->height, 3, FCT_PIX_U8);
	memcpy(img.data, r.rgb, 3 * n);
	snprintf(name, sizeof name, "%s.color.png", base);
	write_image(op->dir, name, &img);
	fct_image_free(&img);

	alloc_image(&img, cam->width, cam->height, 1, FCT_PIX_U16);
	for (size_t i = 0; i < n; i++) {
		int p = r.face[i] >= 0 ? s->surf[s->face_surface[r.face[i]]].patch : -1;
		((uint16_t *)img.data)[i] = (uint16_t)(p + 1);
	}
	snprintf(name, sizeof name, "%s.patch.png", base);
	write_image(op->dir, name, &img);
	fct_image_free(&img);

	/* Camera and pose. */
	fct_camera_format(cam, text, sizeof text - 8);
	char line[300];
	snprintf(line, sizeof line, "camera %s\n", text);
	snprintf(name, sizeof name, "%s.camera", base);
	write_text(op->dir, name, line);
	text[0] = 0;
	for (int row = 0; row < 4; row++) {
		for (int col = 0; col < 4; col++) {
			double v = row < 3 ? pose[4 * row + col] : col == 3;
			put_num(num, sizeof num, v);
			strcat(text, num);
			strcat(text, col < 3 ? " " : "\n");
		}
	}
	snprintf(name, sizeof name, "%s.pose", base);
	write_text(op->dir, name, text);
	if (op->model.model != FCT_NOISE_UNKNOWN) {
		char model[256];
		fct_noise_format(&op->model, model, sizeof model);
		snprintf(line, sizeof line, "noise %s\n", model);
		snprintf(name, sizeof name, "%s.noise", base);
		write_text(op->dir, name, line);
	}

	if (op->points) {
		snprintf(name, sizeof name, "%s.points.ply", base);
		write_points(op->dir, name, cam, pose, noisy, r.rgb, argc, argv);
	}
	free(noisy);
	fct_render_free(&r);
}

/* scene.txt: every surface with its parameters. */
static void write_description(const char *dir, const struct fct_scene *s)
{
	size_t cap = 4096 + 512 * s->nsurf, len = 0;
	char *text = malloc(cap);
	if (!text)
		fct_die(1, "out of memory");
#define PUT(...) (len += (size_t)snprintf(text + len, cap - len, __VA_ARGS__))
	PUT("# mkscene %s: the surfaces of scene.ply, metres, world frame with z up\n", s->name);
	PUT("# plane PATCH NAME nx ny nz d  ox oy oz  e1x e1y e1z  e2x e2y e2z  CELL  R G B\n");
	PUT("# sphere NAME cx cy cz r  R G B\n");
	PUT("# cylinder NAME cx cy cz r h CELL  R G B\n");
	PUT("light %.17g %.17g %.17g\n", s->light[0], s->light[1], s->light[2]);
	for (size_t i = 0; i < s->nsurf; i++) {
		const struct fct_scene_surface *su = &s->surf[i];
		char name[sizeof su->name];
		snprintf(name, sizeof name, "%s", su->name);
		for (char *c = name; *c; c++)
			if (*c == ' ')
				*c = '_';
		if (su->kind == FCT_SURF_PLANE) {
			PUT("plane %d %s", su->patch, name);
			const double *v[5] = {su->n, &su->d, su->o, su->e1, su->e2};
			const int cnt[5] = {3, 1, 3, 3, 3};
			for (int j = 0; j < 5; j++)
				for (int k = 0; k < cnt[j]; k++)
					PUT(" %.17g", v[j][k] + 0.0);
			PUT(" %.17g", su->cell);
		} else if (su->kind == FCT_SURF_SPHERE) {
			PUT("sphere %s %.17g %.17g %.17g %.17g", name, su->c[0], su->c[1], su->c[2], su->r);
		} else {
			PUT("cylinder %s %.17g %.17g %.17g %.17g %.17g %.17g", name, su->c[0], su->c[1],
			    su->c[2], su->r, su->h, su->cell);
		}
		PUT(" %d %d %d\n", su->rgb[0], su->rgb[1], su->rgb[2]);
	}
#undef PUT
	if (len >= cap)
		abort();   /* cannot happen: cap allows 512 bytes a surface */
	write_text(dir, "scene.txt", text);
	free(text);
}

int main(int argc, char **argv)
{
	enum { O_ALBEDO = 256, O_DEPTH, O_SCALE, O_FX, O_GRAZING, O_JITTER, O_MISSING, O_NOISE, O_OUTLIERS, O_PANO,
	       O_POINTS, O_RANGE, O_SCENE, O_SEED, O_SIZE, O_VIEWS, O_VERSION };
	static const struct option longopts[] = {
		{"albedo", required_argument, NULL, O_ALBEDO},
		{"depth", required_argument, NULL, O_DEPTH},
		{"depth-scale", required_argument, NULL, O_SCALE},
		{"fx", required_argument, NULL, O_FX},
		{"grazing", required_argument, NULL, O_GRAZING},
		{"help", no_argument, NULL, 'h'},
		{"jitter", required_argument, NULL, O_JITTER},
		{"missing", required_argument, NULL, O_MISSING},
		{"noise", required_argument, NULL, O_NOISE},
		{"outliers", required_argument, NULL, O_OUTLIERS},
		{"panorama", required_argument, NULL, O_PANO},
		{"points", no_argument, NULL, O_POINTS},
		{"range", required_argument, NULL, O_RANGE},
		{"scene", required_argument, NULL, O_SCENE},
		{"seed", required_argument, NULL, O_SEED},
		{"size", required_argument, NULL, O_SIZE},
		{"version", no_argument, NULL, O_VERSION},
		{"views", required_argument, NULL, O_VIEWS},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("mkscene");
	struct options op;
	memset(&op, 0, sizeof op);
	op.scene = "room";
	op.views = 1;
	op.width = 640, op.height = 480;
	op.fx = 525;
	op.depth_scale = 1000;
	op.noise.grazing = 90;
	op.seed = 1;
	op.jitter = -1;
	static const char optstring[] = "hK:o:qv";
	int c;
	double range[2];
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'h': fputs(usage, stdout); return 0;
		case 'K':
			fct_opt_doubles("-K", optarg, op.k, 4);
			if (!(op.k[0] > 0 && op.k[1] > 0))
				fct_usage_error("-K: the focal lengths must be positive");
			op.have_k = 1;
			break;
		case 'o': op.dir = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case O_ALBEDO:
			if (!strcmp(optarg, "grain"))
				op.grain = 1;
			else if (strcmp(optarg, "checker"))
				fct_usage_error("--albedo: \"%s\" is not checker or grain", optarg);
			break;
		case O_DEPTH:
			if (!strcmp(optarg, "png16"))
				op.png16 = 1;
			else if (!strcmp(optarg, "pfm"))
				op.png16 = 0;
			else
				fct_usage_error("--depth: \"%s\" is not png16 or pfm", optarg);
			break;
		case O_SCALE: op.depth_scale = fct_opt_double("--depth-scale", optarg, 1e-3, 1e6); break;
		case O_FX:
			op.fx = fct_opt_double("--fx", optarg, 1e-3, 1e9);
			op.have_fx = 1;
			break;
		case O_GRAZING: op.noise.grazing = fct_opt_double("--grazing", optarg, 0, 90); break;
		case O_JITTER: op.jitter = fct_opt_double("--jitter", optarg, 0, 10); break;
		case O_MISSING: op.noise.missing = fct_opt_double("--missing", optarg, 0, 1); break;
		case O_NOISE: parse_noise(optarg, &op.noise); break;
		case O_OUTLIERS: op.noise.outliers = fct_opt_double("--outliers", optarg, 0, 1); break;
		case O_PANO: parse_size("--panorama", optarg, &op.pano_w, &op.pano_h); break;
		case O_POINTS: op.points = 1; break;
		case O_RANGE:
			fct_opt_doubles("--range", optarg, range, 2);
			if (!(range[0] >= 0 && range[0] < range[1]))
				fct_usage_error("--range: \"%s\" is not near,far with 0 <= near < far", optarg);
			op.noise.near = range[0];
			op.noise.far = range[1];
			break;
		case O_SCENE: op.scene = optarg; break;
		case O_SEED: op.seed = (uint64_t)fct_opt_long("--seed", optarg, 0, 0x7fffffffffffffffL); break;
		case O_SIZE: parse_size("--size", optarg, &op.width, &op.height); break;
		case O_VIEWS: op.views = (int)fct_opt_long("--views", optarg, 0, MAX_VIEWS); break;
		case O_VERSION: puts("mkscene (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (optind < argc)
		fct_usage_error("%s: unexpected operand (the output folder is -o dir)", argv[optind]);
	if (!op.dir)
		fct_usage_error("-o dir is needed");
	if (op.have_k && op.have_fx)
		fct_usage_error("-K and --fx exclude each other");
	if (op.jitter < 0)
		op.jitter = op.noise.sensor.model == FCT_NOISE_KINECT ? 0.5 : 0;
	describe_noise(&op);

	struct fct_err err;
	struct fct_scene s;
	double t0 = fct_now();
	if (fct_scene_build(&s, op.scene, &err)) {
		if (!strncmp(err.msg, "scene: unknown", 14))
			fct_usage_error("--scene: \"%s\" is not one of %s", op.scene, fct_scene_names());
		fct_die_err(&err);
	}
	s.grain = op.grain;
	double build_s = fct_now() - t0;

	fct_make_folder(NULL, op.dir);

	/* The mesh and its description. */
	struct fct_mesh *m = &s.mesh;
	char *path = out_path(op.dir, "scene.ply");
	if (fct_header_add_provenance(m, "mkscene", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(m, path, 0, &err))
		fct_die_err(&err);
	free(path);
	write_description(op.dir, &s);

	struct totals tot;
	memset(&tot, 0, sizeof tot);
	struct fct_camera cam;
	memset(&cam, 0, sizeof cam);
	cam.kind = FCT_CAMERA_PINHOLE;
	cam.width = op.width, cam.height = op.height;
	if (op.have_k) {
		cam.fx = op.k[0], cam.fy = op.k[1], cam.cx = op.k[2], cam.cy = op.k[3];
	} else {
		cam.fx = cam.fy = op.fx;
		cam.cx = 0.5 * (op.width - 1);
		cam.cy = 0.5 * (op.height - 1);
	}
	struct fct_progress pr;
	fct_progress_start(&pr, "rendering");
	int nimg = op.views + (op.pano_w > 0);
	for (int i = 0; i < op.views; i++) {
		double pose[12];
		char base[32];
		fct_scene_view_pose(&s, i, op.views, pose);
		snprintf(base, sizeof base, "view%02d", i);
		do_view(&op, &s, base, &cam, pose, (uint64_t)i, &tot, argc, argv);
		fct_progress_update(&pr, i + 1, nimg);
	}
	if (op.pano_w > 0) {
		struct fct_camera pc;
		memset(&pc, 0, sizeof pc);
		pc.kind = FCT_CAMERA_CYLINDRICAL;
		pc.width = op.pano_w, pc.height = op.pano_h;
		pc.f = op.pano_w / (2 * M_PI);
		pc.cy = 0.5 * (op.pano_h - 1);
		pc.theta0 = 0;
		double pose[12];
		fct_scene_panorama_pose(&s, pose);
		do_view(&op, &s, "pano", &pc, pose, UINT64_C(1) << 32, &tot, argc, argv);
		fct_progress_update(&pr, nimg, nimg);
	}
	fct_progress_end(&pr);

	const struct fct_scene_noise_stats *ns = &tot.noise;
	fct_report("scene", "%s", s.name);
	fct_report("vertices", "%zu", m->nv);
	fct_report("faces", "%zu", m->nf);
	fct_report("triangles", "%zu", s.bvh.ntri);
	fct_report("planes", "%zu", s.nplanes);
	fct_report("surfaces", "%zu", s.nsurf);
	fct_report("images", "%zu", tot.images);
	fct_report("pixels", "%zu", tot.pixels);
	fct_report("hits", "%zu", tot.hits);
	fct_report("build_s", "%.3f", build_s);
	fct_report("render_s", "%.3f", tot.render_s);
	fct_report("rays_per_s", "%.0f", tot.render_s > 0 ? (double)tot.pixels / tot.render_s : 0);
	fct_report("dropped_range", "%zu", ns->range);
	fct_report("dropped_grazing", "%zu", ns->grazing);
	fct_report("missing", "%zu", ns->missing);
	fct_report("outliers", "%zu", ns->outliers);
	fct_report("noisy", "%zu", ns->noisy);
	fct_report("lost", "%zu", ns->lost);
	double mean = ns->noisy ? ns->sum / (double)ns->noisy : 0;
	double var = ns->noisy ? ns->sum2 / (double)ns->noisy - mean * mean : 0;
	fct_report("noise_mean", "%.9g", mean);
	fct_report("noise_stdev", "%.9g", sqrt(var > 0 ? var : 0));
	fct_report("noise_model_rms", "%.9g", ns->noisy ? sqrt(ns->model2 / (double)ns->noisy) : 0);
	fct_report("jitter_s", "%.3f", tot.jitter_s);
	if (op.png16)
		fct_report("png16_overflow", "%zu", tot.overflow);
	fct_scene_free(&s);
	return 0;
}
