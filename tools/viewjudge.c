/* viewjudge - the leave-views-out judge of a coloured model: render it from
 * the camera of each photo that was held out of its making, with
 * raster.h's rasteriser, and compare with the photo: PSNR over the pixels
 * the model covers, and the fraction of the photo it covers.  Textured
 * models (per-corner texcoord or vertex s t, texnumber, TextureFile) are
 * sampled bilinearly; vertex-coloured ones (tsdfuse --color) interpolate
 * their colours; so both kinds are judged the same way. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/image.h"
#include "io/meshio.h"
#include "core/path.h"
#include "render/photo.h"
#include "render/raster.h"
#include "render/texmap.h"

static const char usage[] =
	"usage: viewjudge [-qv] [-K fx,fy,cx,cy | name] [--camera file] [-m mode]\n"
	"                 [--poses file ...] [--image file ...]\n"
	"                 [--render dir] model [image ...]\n"
	"Render a textured or vertex-coloured model from each photo's camera and\n"
	"compare it with the photo: PSNR over the pixels the model covers and the\n"
	"fraction of the photo it covers, per photo and over all, on standard output.\n"
	"  -K fx,fy,cx,cy     the photos' camera (or a dataset name)\n"
	"  -m mode            auto (default: texture when the model has texture\n"
	"                     coordinates and a TextureFile, else color), texture, color\n"
	"  -q                 quiet\n"
	"  -v                 report sizes and times on stderr\n"
	"      --camera file  the photos' camera: an intrinsics file (see dm2mesh)\n"
	"      --image file   a photo (repeated; or as operands after the model)\n"
	"      --poses file   camera-to-world poses: one file per photo, or one\n"
	"                     trajectory (TUM, Redwood .log, KITTI, stacked 4x4)\n"
	"      --render dir   also write each rendering as dir/NN.png (background\n"
	"                     black)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum mode { M_AUTO, M_TEXTURE, M_COLOR };

struct options {
	const char *K, *camera, *model, *render;
	const char **poses, **images;
	size_t nposes, nimages;
	enum mode mode;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	enum { CAMERA = 256, POSES, IMAGE, RENDER, VERSION };
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, VERSION},
		{"camera", required_argument, NULL, CAMERA}, {"poses", required_argument, NULL, POSES},
		{"image", required_argument, NULL, IMAGE}, {"render", required_argument, NULL, RENDER},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "hK:m:qv";
	memset(o, 0, sizeof *o);
	o->poses = calloc((size_t)argc + 1, sizeof *o->poses);
	o->images = calloc((size_t)argc + 1, sizeof *o->images);
	if (!o->poses || !o->images)
		fct_die(1, "out of memory");
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'h': fputs(usage, stdout); exit(0);
		case 'K': o->K = optarg; break;
		case 'm':
			if (!strcmp(optarg, "auto")) o->mode = M_AUTO;
			else if (!strcmp(optarg, "texture")) o->mode = M_TEXTURE;
			else if (!strcmp(optarg, "color")) o->mode = M_COLOR;
			else fct_usage_error("-m: \"%s\" is not auto, texture or color", optarg);
			break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case CAMERA: o->camera = optarg; break;
		case POSES: o->poses[o->nposes++] = optarg; break;
		case IMAGE: o->images[o->nimages++] = optarg; break;
		case RENDER: o->render = optarg; break;
		case VERSION: puts("viewjudge (facet) " FCT_VERSION); exit(0);
		default: fct_bad_option(optstring, argv);
		}
	}
	if (optind >= argc)
		fct_usage_error("no model");
	o->model = argv[optind++];
	for (; optind < argc; optind++)
		o->images[o->nimages++] = argv[optind];
	if (!o->nimages)
		fct_usage_error("no photos: give them with --image or after the model");
	if (!o->K == !o->camera)
		fct_usage_error(o->K ? "-K and --camera exclude each other" : "no camera: give -K or --camera");
}

/* What the colour of a covered pixel is made from. */
struct model {
	const struct fct_mesh *m;
	uint32_t *tri, *tface;
	size_t ntri;
	uint32_t *corner;         /* 3 face-corner indices per triangle */
	float *st;                /* 2 per corner */
	int32_t *texnum;
	struct fct_image *tex;
	size_t ntex;
	double *rgb;              /* 3 per vertex, 0..255 */
};

/* The corners (indices into m->fvert) of each fanned triangle. */
static uint32_t *fan_corners(const struct fct_mesh *m, const uint32_t *tface, size_t ntri)
{
	struct fct_err err;
	uint32_t *c = fct_alloc_array(ntri, 3 * sizeof *c, &err);
	if (!c)
		fct_die_err(&err);
	size_t prev = SIZE_MAX;
	uint32_t j = 0;
	for (size_t k = 0; k < ntri; k++) {
		size_t f = tface[k];
		j = f == prev ? j + 1 : 1;
		prev = f;
		uint32_t s = m->fstart[f], n = fct_face_size(m, f);
		c[3 * k] = s;
		c[3 * k + 1] = s + (j < n ? j : n - 1);
		c[3 * k + 2] = s + (j + 1 < n ? j + 1 : n - 1);
	}
	return c;
}

static void load_model(struct model *M, const struct fct_mesh *m, enum mode mode, const char *name)
{
	struct fct_err err;
	memset(M, 0, sizeof *M);
	M->m = m;
	if (fct_mesh_fan(m, &M->tri, &M->tface, &M->ntri, &err))
		fct_die_err(&err);
	if (M->ntri >= FCT_RASTER_EMPTY)
		fct_die(1, "%s: too many triangles (%zu)", name, M->ntri);
	M->corner = fan_corners(m, M->tface, M->ntri);
	int has_tc = fct_texmap_corners(m, &M->st, &M->texnum, &err);
	if (has_tc < 0)
		fct_die_err_at(&err, "%s", name);
	M->ntex = fct_header_texture_count(m);
	if (mode == M_AUTO)
		mode = has_tc && M->ntex ? M_TEXTURE : M_COLOR;
	if (mode == M_TEXTURE) {
		if (!has_tc || !M->ntex)
			fct_die(1, "%s: -m texture: no texture coordinates and TextureFile", name);
		M->tex = calloc(M->ntex, sizeof *M->tex);
		if (!M->tex)
			fct_die(1, "out of memory");
		static const unsigned char grey[3] = { 128, 128, 128 };
		for (size_t i = 0; i < M->ntex; i++) {
			struct fct_image raw;
			if (fct_image_read_file(&raw, fct_header_texture(m, i), NULL, &err) ||
			    fct_image_to_rgb8(&raw, grey, &M->tex[i], &err))
				fct_die_err(&err);
			fct_image_free(&raw);
		}
		return;
	}
	static const char *const cn[3] = { "red", "green", "blue" };
	const struct fct_prop *p[3];
	for (int j = 0; j < 3; j++)
		if (!(p[j] = fct_elem_find(&m->vertex, cn[j])) || p[j]->count_type != FCT_NONE)
			fct_die(1, "%s: neither texture nor vertex colour (red green blue)", name);
	double scale = p[0]->type >= FCT_FLOAT32 ? 255 : 1;   /* float colours are 0..1 */
	if (!(M->rgb = fct_alloc_array(m->nv, 3 * sizeof *M->rgb, &err)))
		fct_die_err(&err);
	for (size_t i = 0; i < m->nv; i++)
		for (int j = 0; j < 3; j++)
			M->rgb[3 * i + (size_t)j] = scale * fct_prop_get(p[j], i);
}

static void free_model(struct model *M)
{
	for (size_t i = 0; M->tex && i < M->ntex; i++)
		fct_image_free(&M->tex[i]);
	free(M->tex);
	free(M->tri);
	free(M->tface);
	free(M->corner);
	free(M->st);
	free(M->texnum);
	free(M->rgb);
}

/* The model's colour at a pixel of triangle k with barycentrics b1 b2. */
static void shade(const struct model *M, uint32_t k, double b1, double b2, double c[3])
{
	double b0 = 1 - b1 - b2;
	if (M->rgb) {
		const uint32_t *t = M->tri + 3 * (size_t)k;
		for (int j = 0; j < 3; j++)
			c[j] = b0 * M->rgb[3 * (size_t)t[0] + (size_t)j] + b1 * M->rgb[3 * (size_t)t[1] + (size_t)j] +
			       b2 * M->rgb[3 * (size_t)t[2] + (size_t)j];
		return;
	}
	int32_t tn = M->texnum[M->tface[k]];
	if (tn < 0 || (size_t)tn >= M->ntex) {
		c[0] = c[1] = c[2] = 128;   /* untextured */
		return;
	}
	const uint32_t *cr = M->corner + 3 * (size_t)k;
	double s = b0 * M->st[2 * (size_t)cr[0]] + b1 * M->st[2 * (size_t)cr[1]] + b2 * M->st[2 * (size_t)cr[2]];
	double t = b0 * M->st[2 * (size_t)cr[0] + 1] + b1 * M->st[2 * (size_t)cr[1] + 1] +
	           b2 * M->st[2 * (size_t)cr[2] + 1];
	if (isfinite(s) && isfinite(t))
		fct_texture_sample(&M->tex[tn], s, t, c);
	else
		c[0] = c[1] = c[2] = 128;
}

int main(int argc, char **argv)
{
	fct_cli_init("viewjudge");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	double t0 = fct_now();
	struct fct_camera cam;
	fct_opt_camera(&cam, NULL, NULL, o.K, o.camera);
	struct fct_photo *ph;
	if (fct_photos_make(&ph, &cam, o.images, o.nimages, o.poses, o.nposes, &err))
		fct_die_err(&err);
	struct fct_mesh m;
	if (fct_mesh_read_file(&m, o.model, NULL, &err))
		fct_die_err(&err);
	const char *name = fct_path_display(o.model);
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (size_t i = 0; i < m.nv; i++)
		for (int k = 0; k < 3; k++) {
			double x = m.xyz[3 * i + (size_t)k];
			if (!isfinite(x))
				fct_die(1, "%s: vertex %zu: coordinate is not finite", name, i);
			lo[k] = fmin(lo[k], x), hi[k] = fmax(hi[k], x);
		}
	double diag = m.nv ? sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
	                          (hi[2] - lo[2]) * (hi[2] - lo[2])) : 1;
	struct model M;
	load_model(&M, &m, o.mode, name);

	printf("# photo covered psnr_db\n");
	double sse_all = 0, cov_all = 0, pix_all = 0;
	for (size_t i = 0; i < o.nimages; i++) {
		struct fct_image photo;
		struct fct_camera pc;
		struct fct_view view;
		if (fct_photo_read(&ph[i], 1 << 14, &photo, &pc, &err))
			fct_die_err(&err);
		if (fct_view_from_camera(&view, &pc, ph[i].pose, 0, 0, diag > 0 ? 1e-4 * diag : 1e-6, &err))
			fct_die_err_at(&err, "%s", ph[i].path);
		struct fct_raster r;
		if (fct_raster_init(&r, view.width, view.height, &err))
			fct_die_err(&err);
		for (size_t k = 0; k < M.ntri; k++) {
			const uint32_t *t = M.tri + 3 * k;
			double q[3][3];
			for (int j = 0; j < 3; j++)
				fct_view_to_camera(&view, m.xyz + 3 * (size_t)t[j], q[j]);
			fct_raster_triangle(&r, &view, q[0], q[1], q[2], (uint32_t)k);
		}
		struct fct_image out = { 0 };
		if (o.render && fct_image_alloc(&out, view.width, view.height, 3, FCT_PIX_U8, &err))
			fct_die_err(&err);
		size_t n = (size_t)view.width * (size_t)view.height, covered = 0;
		double sse = 0;
		const unsigned char *P = photo.data;
		for (size_t p = 0; p < n; p++) {
			if (r.id[p] == FCT_RASTER_EMPTY)
				continue;
			double c[3];
			shade(&M, r.id[p], r.b[2 * p], r.b[2 * p + 1], c);
			for (int j = 0; j < 3; j++) {
				double v = floor(c[j] + 0.5);
				v = v < 0 ? 0 : v > 255 ? 255 : v;
				double d = v - P[3 * p + (size_t)j];
				sse += d * d;
				if (o.render)
					((unsigned char *)out.data)[3 * p + (size_t)j] = (unsigned char)v;
			}
			covered++;
		}
		double mse = covered ? sse / (3.0 * (double)covered) : 0;
		double psnr = covered ? (mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : INFINITY) : 0;
		printf("%s %.6f %.4f\n", ph[i].path, (double)covered / (double)n, psnr);
		sse_all += sse, cov_all += (double)covered, pix_all += (double)n;
		if (o.render) {
			char path[4096];
			snprintf(path, sizeof path, "%s/%02zu.png", o.render, i);
			fct_write_image_or_die(&out, path);
			fct_image_free(&out);
		}
		fct_raster_free(&r);
		fct_image_free(&photo);
	}
	double mse = cov_all > 0 ? sse_all / (3 * cov_all) : 0;
	printf("all %.6f %.4f\n", pix_all > 0 ? cov_all / pix_all : 0,
	       cov_all > 0 ? (mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : INFINITY) : 0);
	fct_report("photos", "%zu", o.nimages);
	fct_report("faces", "%zu", m.nf);
	fct_report("mode", "%s", M.rgb ? "color" : "texture");
	fct_report("total_s", "%.3f", fct_now() - t0);
	free_model(&M);
	fct_mesh_free(&m);
	free(ph);
	free(o.poses);
	free(o.images);
	if (fflush(stdout) || ferror(stdout))
		fct_die(1, "<stdout>: write error");
	return 0;
}
