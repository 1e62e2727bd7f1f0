/* meshshot - a picture of a mesh, rendered headless by the software
 * rasteriser of raster.h into a PNG: the figures of Kang, Johnson and
 * Szeliski (DEC CRL 95/7, Figs. 1-9) and of Sun et al. - the dense mesh,
 * the planar patches, the simplified wireframe, the texture-mapped model -
 * from the sensor's own camera or from fitted front, side, top and oblique
 * views. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "geom/bvh.h"
#include "geom/geom.h"
#include "io/header.h"
#include "io/image.h"
#include "io/meshio.h"
#include "io/output.h"
#include "core/path.h"
#include "geom/planes.h"
#include "render/raster.h"
#include "io/texcoord.h"

static const char usage[] =
	"usage: meshshot [-ehqvw] [-m mode] [-o file] [-s WxH] [--bg r,g,b] [--cmap name]\n"
	"                [--eye x,y,z] [--fov degrees] [--line-width px] [--range lo,hi]\n"
	"                [--scalar name] [--smooth] [--target x,y,z] [--texture file]\n"
	"                [--title text] [--up x,y,z] [--view name] [mesh]\n"
	"Render a mesh (PLY or OBJ) to a PNG picture with a software rasteriser.\n"
	"  -e              draw the edge element (vertex1 vertex2, simpchain's\n"
	"                  wireframe) as red lines\n"
	"  -m mode         auto (default: texture when the mesh has texture\n"
	"                  coordinates, s t or face texcoord, and a TextureFile;\n"
	"                  shaded otherwise), shaded, patch (face\n"
	"                  patch coloured), texture, color (vertex red green blue),\n"
	"                  scalar (see --scalar)\n"
	"  -o file         the PNG (default standard output)\n"
	"  -q              quiet\n"
	"  -s WxH          picture size in pixels (default: the camera's, or 800x600)\n"
	"  -v              report sizes and times on stderr\n"
	"  -w              draw the faces' edges over the picture (wireframe)\n"
	"      --bg r,g,b  background colour, 0-255 each (default 255,255,255)\n"
	"      --cmap name colour map of --scalar: viridis (default), gray, coolwarm\n"
	"      --eye x,y,z look from this point (with --target, --up, --fov)\n"
	"      --fov deg   vertical field of view of fitted and --eye views (default 40)\n"
	"      --line-width px  width of wireframe lines (default 1; edges twice)\n"
	"      --range lo,hi    values mapped to the ends of the colour map\n"
	"                  (default: the smallest and largest value)\n"
	"      --scalar name    colour by the vertex (or face) property name, with a\n"
	"                  legend; implies -m scalar\n"
	"      --smooth    smooth shading from vertex normals (default flat)\n"
	"      --target x,y,z   the point looked at (default the bounding box centre)\n"
	"      --texture file   the texture image (default the TextureFile comment;\n"
	"                  PNG, JPEG, PFM or PPM; textures at most 2^26 pixels in all)\n"
	"      --title text     a caption in the top-left corner\n"
	"      --up x,y,z  the direction that points up in the picture (default the\n"
	"                  camera's up, -y of its frame)\n"
	"      --view name camera (default when there is a pinhole camera comment),\n"
	"                  front (default otherwise), side, top or oblique, fitted to\n"
	"                  the mesh\n"
	"  -h, --help      this help\n"
	"      --version   print the version\n";

/* The texture pixels drawn, all textures together: 2^26 (8192x8192, 200
 * MB as RGB); a texture past them is refused from its header before it is
 * decoded. */
#define TEXTURE_MAX_PIXELS ((size_t)1 << 26)

enum mode { M_AUTO, M_SHADED, M_PATCH, M_TEXTURE, M_COLOR, M_SCALAR };

struct opts {
	const char *out, *input, *scalar, *texture, *title, *view;
	enum mode mode;
	int width, height;      /* 0: default */
	int wire, edges, smooth;
	int has_eye, has_target, has_up, has_range;
	double eye[3], target[3], up[3], fov, range[2], line_width;
	unsigned char bg[3];
	enum fct_cmap cmap;
};

static void parse_size(const char *arg, int *w, int *h)
{
	char *end;
	long a = strtol(arg, &end, 10), b = 0;
	if (end != arg && (*end == 'x' || *end == 'X')) {
		const char *s = end + 1;
		b = strtol(s, &end, 10);
		if (end == s)
			b = 0;
	}
	if (*end || a < 1 || b < 1 || a > 16384 || b > 16384 || a * b > (1L << 26))
		fct_usage_error("-s: \"%s\" is not a size WxH (each 1 to 16384, at most 2^26 pixels)", arg);
	*w = (int)a, *h = (int)b;
}

static void parse_opts(int argc, char **argv, struct opts *o)
{
	enum { BG = 256, CMAP, EYE, FOV, LW, RANGE, SCALAR, SMOOTH, TARGET, TEXTURE, TITLE, UP, VIEW, VERSION };
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, VERSION},
		{"bg", required_argument, NULL, BG}, {"cmap", required_argument, NULL, CMAP},
		{"eye", required_argument, NULL, EYE}, {"fov", required_argument, NULL, FOV},
		{"line-width", required_argument, NULL, LW}, {"range", required_argument, NULL, RANGE},
		{"scalar", required_argument, NULL, SCALAR}, {"smooth", no_argument, NULL, SMOOTH},
		{"target", required_argument, NULL, TARGET}, {"texture", required_argument, NULL, TEXTURE},
		{"title", required_argument, NULL, TITLE}, {"up", required_argument, NULL, UP},
		{"view", required_argument, NULL, VIEW}, {NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ehm:o:qs:vw";
	memset(o, 0, sizeof *o);
	o->fov = 40;
	o->line_width = 1;
	o->bg[0] = o->bg[1] = o->bg[2] = 255;
	int c, mode_set = 0;
	double v[3];
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'e': o->edges = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'm':
			mode_set = 1;
			if (!strcmp(optarg, "auto")) o->mode = M_AUTO;
			else if (!strcmp(optarg, "shaded")) o->mode = M_SHADED;
			else if (!strcmp(optarg, "patch")) o->mode = M_PATCH;
			else if (!strcmp(optarg, "texture")) o->mode = M_TEXTURE;
			else if (!strcmp(optarg, "color")) o->mode = M_COLOR;
			else if (!strcmp(optarg, "scalar")) o->mode = M_SCALAR;
			else fct_usage_error("-m: \"%s\" is not auto, shaded, patch, texture, color or scalar", optarg);
			break;
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 's': parse_size(optarg, &o->width, &o->height); break;
		case 'v': fct_verbose = 1; break;
		case 'w': o->wire = 1; break;
		case BG:
			fct_opt_doubles("--bg", optarg, v, 3);
			for (int k = 0; k < 3; k++) {
				if (!(v[k] >= 0 && v[k] <= 255))
					fct_usage_error("--bg: \"%s\": each value must be in [0, 255]", optarg);
				o->bg[k] = (unsigned char)lround(v[k]);
			}
			break;
		case CMAP:
			if (fct_cmap_parse(optarg, &o->cmap))
				fct_usage_error("--cmap: \"%s\" is not viridis, gray or coolwarm", optarg);
			break;
		case EYE: fct_opt_doubles("--eye", optarg, o->eye, 3); o->has_eye = 1; break;
		case FOV: o->fov = fct_opt_double("--fov", optarg, 1, 170); break;
		case LW: o->line_width = fct_opt_double("--line-width", optarg, 0.1, 100); break;
		case RANGE:
			fct_opt_doubles("--range", optarg, o->range, 2);
			if (!(o->range[0] < o->range[1]))
				fct_usage_error("--range: \"%s\": lo must be below hi", optarg);
			o->has_range = 1;
			break;
		case SCALAR: o->scalar = optarg; break;
		case SMOOTH: o->smooth = 1; break;
		case TARGET: fct_opt_doubles("--target", optarg, o->target, 3); o->has_target = 1; break;
		case TEXTURE: o->texture = optarg; break;
		case TITLE: o->title = optarg; break;
		case UP: fct_opt_doubles("--up", optarg, o->up, 3); o->has_up = 1; break;
		case VIEW:
			if (strcmp(optarg, "camera") && strcmp(optarg, "front") && strcmp(optarg, "side") &&
			    strcmp(optarg, "top") && strcmp(optarg, "oblique"))
				fct_usage_error("--view: \"%s\" is not camera, front, side, top or oblique", optarg);
			o->view = optarg;
			break;
		case VERSION: puts("meshshot (facet) " FCT_VERSION); exit(0);
		default: fct_bad_option(optstring, argv);
		}
	}
	if (o->scalar) {
		if (mode_set && o->mode != M_SCALAR)
			fct_usage_error("--scalar: only with -m scalar");
		o->mode = M_SCALAR;
	} else if (o->mode == M_SCALAR) {
		fct_usage_error("-m scalar: name the property with --scalar");
	}
	if (o->has_eye && o->view)
		fct_usage_error("--eye and --view cannot be used together");
	if ((o->has_target || o->has_up) && o->view && !strcmp(o->view, "camera"))
		fct_usage_error("--view camera takes its direction from the camera comment");
	o->input = fct_one_operand(argc, argv, optind, NULL);
}

/* The reference directions of the fitted views: forward (the sensor's line
 * of sight) and up, from the pose (or the camera frame: +z and -y), with
 * --up overriding up. */
static void reference_frame(const struct opts *o, const double pose[12], int has_pose,
                            double F[3], double U[3])
{
	if (has_pose) {
		for (int k = 0; k < 3; k++) {
			F[k] = pose[4 * k + 2];
			U[k] = -pose[4 * k + 1];
		}
	} else {
		F[0] = 0, F[1] = 0, F[2] = 1;
		U[0] = 0, U[1] = -1, U[2] = 0;
	}
	if (!o->has_up)
		return;
	double n = sqrt(fct_v3_dot(o->up, o->up));
	if (!(n > 0))
		fct_usage_error("--up: the direction has no length");
	for (int k = 0; k < 3; k++)
		U[k] = o->up[k] / n;
	double f[3];
	fct_v3_axpy(f, F, -fct_v3_dot(F, U), U);
	if (sqrt(fct_v3_dot(f, f)) < 0.2) {
		/* The sensor looked along up: look along the world axis most
		 * across it instead. */
		int best = 0;
		for (int k = 1; k < 3; k++)
			if (fabs(U[k]) < fabs(U[best]))
				best = k;
		double a[3] = {0, 0, 0};
		a[best] = 1;
		fct_v3_axpy(f, a, -fct_v3_dot(a, U), U);
	}
	double fn = sqrt(fct_v3_dot(f, f));
	for (int k = 0; k < 3; k++)
		F[k] = f[k] / fn;
}

/* The bounding box of the vertices that faces or edges use (all vertices
 * when there are none). */
static void bbox(const struct fct_mesh *m, double lo[3], double hi[3])
{
	for (int k = 0; k < 3; k++)
		lo[k] = INFINITY, hi[k] = -INFINITY;
	for (size_t i = 0; i < m->nv; i++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], m->xyz[3 * i + k]);
			hi[k] = fmax(hi[k], m->xyz[3 * i + k]);
		}
	if (m->nv == 0)
		for (int k = 0; k < 3; k++)
			lo[k] = hi[k] = 0;
}

static void choose_view(const struct opts *o, const struct fct_mesh *m, int reserve,
                        struct fct_view *v)
{
	struct fct_err err;
	struct fct_camera cam;
	double pose[12];
	int has_cam = fct_header_camera(m, &cam, &err);
	if (has_cam < 0)
		fct_die_err(&err);
	int has_pose = fct_header_pose(m, pose, &err);
	if (has_pose < 0)
		fct_die_err(&err);
	const char *view = o->view;
	if (!view && !o->has_eye)
		view = (has_cam && cam.kind == FCT_CAMERA_PINHOLE) ? "camera" : "front";
	double lo[3], hi[3], centre[3], diag[3];
	bbox(m, lo, hi);
	for (int k = 0; k < 3; k++) {
		centre[k] = 0.5 * (lo[k] + hi[k]);
		diag[k] = hi[k] - lo[k];
	}
	double size = sqrt(fct_v3_dot(diag, diag));
	if (view && !strcmp(view, "camera")) {
		if (!has_cam || cam.kind != FCT_CAMERA_PINHOLE)
			fct_die(1, "%s: no pinhole camera comment to take the view from; use --view or --eye",
			        fct_path_display(o->input));
		if (cam.width < 1 || cam.height < 1 || !(cam.fx > 0) || !(cam.fy > 0))
			fct_die(1, "%s: the camera comment has no usable size or focal length",
			        fct_path_display(o->input));
		int W = o->width ? o->width : cam.width, H = o->height ? o->height : cam.height;
		if ((size_t)W * (size_t)H > ((size_t)1 << 26))
			fct_die(1, "%s: the camera's picture (%dx%d) is too large; choose one with -s",
			        fct_path_display(o->input), W, H);
		if (fct_view_from_camera(v, &cam, has_pose ? pose : NULL, W, H,
		                         size > 0 ? 1e-4 * size : 1e-6, &err))
			fct_die_err_at(&err, "%s", fct_path_display(o->input));
		return;
	}
	int W = o->width ? o->width : 800, H = o->height ? o->height : 600;
	double F[3], U[3], up[3], dir[3], target[3];
	reference_frame(o, pose, has_pose > 0, F, U);
	if (o->has_eye) {
		memcpy(target, o->has_target ? o->target : centre, sizeof target);
		if (fct_view_look_at(v, o->eye, target, U, o->fov, W, H, &err))
			fct_usage_error("--eye: %s", err.msg);
		if (size > 0 && v->near > 1e-4 * size)
			v->near = 1e-4 * size;
		return;
	}
	double right[3];
	fct_v3_cross(right, F, U);
	memcpy(up, U, sizeof up);
	if (!strcmp(view, "front")) {
		memcpy(dir, F, sizeof dir);
	} else if (!strcmp(view, "side")) {
		for (int k = 0; k < 3; k++)
			dir[k] = -right[k];
	} else if (!strcmp(view, "top")) {
		for (int k = 0; k < 3; k++)
			dir[k] = -U[k];
		memcpy(up, F, sizeof up);
	} else {   /* oblique: from 35 degrees to the right and 25 degrees above */
		double yaw = 35 * M_PI / 180, pitch = 25 * M_PI / 180;
		for (int k = 0; k < 3; k++)
			dir[k] = cos(pitch) * cos(yaw) * F[k] - cos(pitch) * sin(yaw) * right[k] -
			         sin(pitch) * U[k];
	}
	memcpy(target, o->has_target ? o->target : centre, sizeof target);
	double eye[3];
	fct_v3_sub(eye, target, dir);
	if (fct_view_look_at(v, eye, target, up, o->fov, W, H, &err))
		fct_die_err_at(&err, "--view %s", view);
	/* Fit into the picture less the legend's strip on the right. */
	if (reserve > 0 && reserve < W / 2)
		v->width = W - reserve;
	fct_view_fit(v, target, m->xyz, m->nv, 0.05);
	v->width = W;
}

/* A vertex property as doubles (NULL when absent); fails on a list. */
static double *vertex_column(const struct fct_mesh *m, const char *name)
{
	const struct fct_prop *p = fct_elem_find(&m->vertex, name);
	if (!p)
		return NULL;
	if (p->count_type != FCT_NONE)
		fct_die(1, "vertex property %s is a list", name);
	struct fct_err err;
	double *v = fct_alloc_array(m->nv, sizeof *v, &err);
	if (!v)
		fct_die_err(&err);
	for (size_t i = 0; i < m->nv; i++)
		v[i] = fct_prop_get(p, i);
	return v;
}

/* What the shading pass needs. */
struct scene {
	const struct fct_mesh *m;
	const uint32_t *tri, *tface;
	const double *q;          /* camera-frame vertices */
	double *vn;               /* smooth: camera-frame vertex normals */
	float *uv;                /* texture coordinates at each triangle's 3 corners */
	int32_t *ttex;            /* each triangle's texture, -1 none */
	struct fct_image *tex;    /* RGB U8, one per TextureFile */
	size_t ntex;
	int32_t *patch;
	double *rgb[3];           /* vertex colours */
	double *val;              /* scalar per vertex, or per face when val_face */
	int val_face;
	double lo, hi;
};

/* The texture coordinates at the corners of each triangle (fct_mesh_fan's:
 * a face's triangles are consecutive, fanned from its first corner), from
 * the face corners (a texcoord list) or the vertices (s t or another name
 * of texcoord.h), NaN where a face has none; and each triangle's texture,
 * its face's texnumber (0 without one; -1 when out of range).  0, or -1
 * when the mesh has no texture coordinates. */
static int corner_texcoords(struct scene *sc, size_t ntri, size_t ntex, struct fct_err *err)
{
	const struct fct_mesh *m = sc->m;
	const struct fct_prop *ps, *pt, *corner = fct_texcoord_face(m);
	if (!corner && !fct_texcoord_vertex(m, &ps, &pt))
		return -1;
	const struct fct_prop *tn = fct_elem_find(&m->face, "texnumber");
	if (tn && tn->count_type != FCT_NONE)
		tn = NULL;
	if (!(sc->uv = fct_alloc_array(6 * ntri, sizeof *sc->uv, err)) ||
	    !(sc->ttex = fct_alloc_array(ntri, sizeof *sc->ttex, err)))
		fct_die_err(err);
	uint32_t j = 0;       /* the triangle's place in its face's fan */
	for (size_t k = 0; k < ntri; k++) {
		size_t f = sc->tface[k];
		j = k && sc->tface[k - 1] == f ? j + 1 : 1;
		double tex = tn ? fct_prop_get(tn, f) : 0;
		sc->ttex[k] = tex >= 0 && tex < (double)ntex ? (int32_t)tex : -1;
		uint32_t size = fct_face_size(m, f);
		uint32_t c[3] = { 0, size < 3 ? size - 1 : j, size < 3 ? size - 1 : j + 1 };
		for (int i = 0; i < 3; i++) {
			float *uv = sc->uv + 6 * k + 2 * (size_t)i;
			if (!corner) {
				uv[0] = (float)fct_prop_get(ps, sc->tri[3 * k + (size_t)i]);
				uv[1] = (float)fct_prop_get(pt, sc->tri[3 * k + (size_t)i]);
			} else if (corner->off[f + 1] > corner->off[f]) {
				uv[0] = (float)fct_prop_get(corner, corner->off[f] + 2 * (size_t)c[i]);
				uv[1] = (float)fct_prop_get(corner, corner->off[f] + 2 * (size_t)c[i] + 1);
			} else {
				uv[0] = uv[1] = NAN;
			}
		}
	}
	return 0;
}

/* Read the textures (tex[0] from --texture when given, else every
 * TextureFile) as RGB over bg, within TEXTURE_MAX_PIXELS in all. */
static void read_textures(struct scene *sc, const struct opts *o, struct fct_err *err)
{
	size_t n = fct_header_texture_count(sc->m), budget = TEXTURE_MAX_PIXELS;
	if (!n)
		n = 1;       /* --texture alone */
	if (!(sc->tex = fct_alloc_array(n, sizeof *sc->tex, err)))
		fct_die_err(err);
	memset(sc->tex, 0, n * sizeof *sc->tex);
	for (size_t i = 0; i < n; i++) {
		const char *path = i == 0 && o->texture ? o->texture : fct_header_texture(sc->m, i);
		struct fct_image raw;
		if (fct_image_read_file_max(&raw, path, budget, NULL, err) ||
		    fct_image_to_rgb8(&raw, o->bg, &sc->tex[i], err))
			fct_die_err(err);
		budget -= (size_t)raw.width * (size_t)raw.height;
		fct_image_free(&raw);
		sc->ntex = i + 1;
	}
}

/* Towards the light, in the camera frame: from above left of the eye. */
static const double light[3] = { -0.22965760608731267, -0.32152064852223772, -0.91863042434925068 };

static void shade(const struct opts *o, const struct scene *sc, const struct fct_raster *r,
                  enum mode mode, struct fct_image *img)
{
	unsigned char *out = img->data;
	size_t n = (size_t)r->width * (size_t)r->height;
	for (size_t i = 0; i < n; i++) {
		unsigned char *px = out + 3 * i;
		uint32_t k = r->id[i];
		if (k == FCT_RASTER_EMPTY) {
			memcpy(px, o->bg, 3);
			continue;
		}
		const uint32_t *t = sc->tri + 3 * (size_t)k;
		double b1 = r->b[2 * i], b2 = r->b[2 * i + 1], b0 = 1 - b1 - b2;
		const double *q0 = sc->q + 3 * (size_t)t[0], *q1 = sc->q + 3 * (size_t)t[1];
		const double *q2 = sc->q + 3 * (size_t)t[2];
		double c[3] = {0, 0, 0};
		double lam = 0;
		if (mode == M_SHADED || mode == M_PATCH) {
			double nrm[3], e1[3], e2[3], p[3];
			if (o->smooth) {
				for (int j = 0; j < 3; j++)
					nrm[j] = b0 * sc->vn[3 * (size_t)t[0] + j] + b1 * sc->vn[3 * (size_t)t[1] + j] +
					         b2 * sc->vn[3 * (size_t)t[2] + j];
			} else {
				fct_v3_sub(e1, q1, q0);
				fct_v3_sub(e2, q2, q0);
				fct_v3_cross(nrm, e1, e2);
			}
			for (int j = 0; j < 3; j++)
				p[j] = b0 * q0[j] + b1 * q1[j] + b2 * q2[j];
			double len = sqrt(fct_v3_dot(nrm, nrm));
			if (len > 0) {
				if (fct_v3_dot(nrm, p) > 0)    /* seen from behind: light the side we see */
					len = -len;
				lam = fct_v3_dot(nrm, light) / len;
				lam = lam > 0 ? lam : 0;
			}
		}
		switch (mode) {
		case M_PATCH: {
			unsigned char pc[3];
			fct_patch_color(sc->patch ? sc->patch[sc->tface[k]] : -1, pc);
			for (int j = 0; j < 3; j++)
				c[j] = pc[j] * (0.55 + 0.45 * lam);
			break;
		}
		case M_TEXTURE: {
			const float *uv = sc->uv + 6 * (size_t)k;
			double s = b0 * uv[0] + b1 * uv[2] + b2 * uv[4];
			double tt = b0 * uv[1] + b1 * uv[3] + b2 * uv[5];
			if (isfinite(s) && isfinite(tt) && sc->ttex[k] >= 0)
				fct_texture_sample(&sc->tex[sc->ttex[k]], s, tt, c);
			else
				c[0] = c[1] = c[2] = 128;
			break;
		}
		case M_COLOR:
			for (int j = 0; j < 3; j++)
				c[j] = b0 * sc->rgb[j][t[0]] + b1 * sc->rgb[j][t[1]] + b2 * sc->rgb[j][t[2]];
			break;
		case M_SCALAR: {
			double val = sc->val_face ? sc->val[sc->tface[k]]
			                          : b0 * sc->val[t[0]] + b1 * sc->val[t[1]] + b2 * sc->val[t[2]];
			unsigned char vc[3];
			fct_cmap_color(o->cmap, sc->hi > sc->lo ? (val - sc->lo) / (sc->hi - sc->lo)
			                                          : (isfinite(val) ? 0.5 : NAN), vc);
			c[0] = vc[0], c[1] = vc[1], c[2] = vc[2];
			break;
		}
		default:
			for (int j = 0; j < 3; j++)
				c[j] = 220 * (0.25 + 0.75 * lam);
			break;
		}
		for (int j = 0; j < 3; j++)
			px[j] = (unsigned char)lround(c[j] < 0 ? 0 : c[j] > 255 ? 255 : c[j]);
	}
}

/* Area-weighted vertex normals in the camera frame, oriented towards the
 * viewer where a vertex's faces disagree only by winding... they are summed
 * as wound, so consistently wound meshes get smooth normals. */
static double *vertex_normals(const struct fct_mesh *m, const double *q, const uint32_t *tri,
                              size_t ntri)
{
	struct fct_err err;
	double *vn = fct_alloc_array(m->nv, 3 * sizeof *vn, &err);
	if (!vn)
		fct_die_err(&err);
	memset(vn, 0, m->nv * 3 * sizeof *vn);
	for (size_t k = 0; k < ntri; k++) {
		const uint32_t *t = tri + 3 * k;
		double e1[3], e2[3], n[3];
		fct_v3_sub(e1, q + 3 * (size_t)t[1], q + 3 * (size_t)t[0]);
		fct_v3_sub(e2, q + 3 * (size_t)t[2], q + 3 * (size_t)t[0]);
		fct_v3_cross(n, e1, e2);
		for (int c = 0; c < 3; c++)
			for (int j = 0; j < 3; j++)
				vn[3 * (size_t)t[c] + j] += n[j];
	}
	return vn;
}

/* The width the legend of a picture h pixels high takes at the right edge. */
static int legend_width(const struct scene *sc, const char *name, int h)
{
	int scale = h >= 300 ? 2 : 1, tw = 0, w, hh;
	char lab[40];
	double v[3] = { sc->hi, 0.5 * (sc->lo + sc->hi), sc->lo };
	for (int i = 0; i < 3; i++) {
		snprintf(lab, sizeof lab, "%.4g", v[i]);
		fct_text_size(lab, scale, &w, &hh);
		tw = w > tw ? w : tw;
	}
	fct_text_size(name, scale, &w, &hh);
	int bar = 8 * scale + 9 * scale + tw;      /* bar, tick and gap, labels */
	return (w > bar ? w : bar) + 12 * scale;
}

static void draw_legend(const struct opts *o, struct fct_image *img, const struct scene *sc)
{
	unsigned char ink[3], hi_c[3];
	int lum = (299 * o->bg[0] + 587 * o->bg[1] + 114 * o->bg[2]) / 1000;
	ink[0] = ink[1] = ink[2] = lum > 128 ? 0 : 255;
	int scale = img->height >= 300 ? 2 : 1;
	int barw = 8 * scale, barh = img->height * 6 / 10, margin = 6 * scale;
	char lab[3][40];
	snprintf(lab[0], sizeof lab[0], "%.4g", sc->hi);
	snprintf(lab[1], sizeof lab[1], "%.4g", 0.5 * (sc->lo + sc->hi));
	snprintf(lab[2], sizeof lab[2], "%.4g", sc->lo);
	int tw = 0, w, h;
	for (int i = 0; i < 3; i++) {
		fct_text_size(lab[i], scale, &w, &h);
		tw = w > tw ? w : tw;
	}
	int x0 = img->width - margin - tw - margin / 2 - barw;
	int y0 = (img->height - barh) / 2;
	if (x0 < 0 || barh < 4)
		return;
	fct_text_size(o->scalar, scale, &w, &h);
	fct_draw_text(img, img->width - margin - w > 0 ? img->width - margin - w : 0,
	              y0 - h - 3 * scale, scale, ink, o->scalar);
	for (int y = 0; y < barh; y++) {
		fct_cmap_color(o->cmap, 1 - (double)y / (barh - 1), hi_c);
		fct_draw_rect(img, x0, y0 + y, x0 + barw, y0 + y + 1, hi_c);
	}
	for (int i = 0; i < 3; i++) {
		int y = y0 + i * (barh - 1) / 2;
		fct_text_size(lab[i], scale, &w, &h);
		fct_draw_rect(img, x0 + barw, y, x0 + barw + margin / 3, y + scale, ink);
		fct_draw_text(img, x0 + barw + margin / 2, y - h / 2, scale, ink, lab[i]);
	}
}

static int cmp_edge(const void *a, const void *b)
{
	const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return (x > y) - (x < y);
}

/* Each edge of the faces once, as (lo << 32 | hi) sorted. */
static uint64_t *face_edges(const struct fct_mesh *m, size_t *n)
{
	struct fct_err err;
	size_t cap = m->fstart[m->nf];
	uint64_t *e = fct_alloc_array(cap, sizeof *e, &err);
	if (!e)
		fct_die_err(&err);
	size_t k = 0;
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], c = fct_face_size(m, f);
		if (c < 2)
			continue;
		for (uint32_t i = 0; i < c && !(c == 2 && i == 1); i++) {
			uint64_t a = m->fvert[s + i], b = m->fvert[s + (i + 1) % c];
			if (a != b)
				e[k++] = a < b ? a << 32 | b : b << 32 | a;
		}
	}
	qsort(e, k, sizeof *e, cmp_edge);
	size_t u = 0;
	for (size_t i = 0; i < k; i++)
		if (u == 0 || e[i] != e[u - 1])
			e[u++] = e[i];
	*n = u;
	return e;
}

int main(int argc, char **argv)
{
	fct_cli_init("meshshot");
	struct opts o;
	parse_opts(argc, argv, &o);
	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now();
	if (fct_mesh_read_file(&m, o.input, NULL, &err))
		fct_die_err(&err);
	const char *name = fct_path_display(o.input);
	for (size_t i = 0; i < 3 * m.nv; i++)
		if (!isfinite(m.xyz[i]))
			fct_die(1, "%s: vertex %zu: coordinate is not finite", name, i / 3);
	double read_s = fct_now() - t0;

	t0 = fct_now();
	struct scene sc;
	memset(&sc, 0, sizeof sc);
	sc.m = &m;
	uint32_t *tri, *tface;
	size_t ntri;
	if (fct_mesh_fan(&m, &tri, &tface, &ntri, &err))
		fct_die_err(&err);
	if (ntri >= FCT_RASTER_EMPTY)
		fct_die(1, "%s: too many triangles (%zu)", name, ntri);
	sc.tri = tri, sc.tface = tface;

	/* What the mode needs, before any drawing, so bad data fails early. */
	enum mode mode = o.mode;
	size_t ntex = fct_header_texture_count(&m);
	int has_uv = mode == M_AUTO || mode == M_TEXTURE ?
	             !corner_texcoords(&sc, ntri, ntex ? ntex : 1, &err) : 0;
	if (mode == M_AUTO) {
		mode = (has_uv && (ntex || o.texture) && ntri) ? M_TEXTURE : M_SHADED;
		for (size_t i = o.texture ? 1 : 0; mode == M_TEXTURE && i < ntex; i++) {
			const char *path = fct_header_texture(&m, i);
			FILE *f = fopen(path, "rb");
			if (!f) {
				fct_warn("%s: TextureFile %s cannot be opened; drawing shaded", name, path);
				mode = M_SHADED;
			} else {
				fclose(f);
			}
		}
	}
	if (mode == M_TEXTURE) {
		if (!has_uv)
			fct_die(1, "%s: -m texture: no texture coordinates (vertex s t, texture_u "
			        "texture_v, u v, or face texcoord)", name);
		if (!ntex && !o.texture)
			fct_die(1, "%s: -m texture: no TextureFile comment; name the image with --texture", name);
		read_textures(&sc, &o, &err);
	}
	if (mode == M_PATCH) {
		int present;
		if (fct_patches_get(&m, &sc.patch, &present, -1, &err))
			fct_die_err_at(&err, "%s", name);
		if (!present)
			fct_die(1, "%s: -m patch: the faces have no patch property", name);
	}
	if (mode == M_COLOR) {
		static const char *const cn[3] = { "red", "green", "blue" };
		for (int j = 0; j < 3; j++)
			if (!(sc.rgb[j] = vertex_column(&m, cn[j])))
				fct_die(1, "%s: -m color: the vertices have no %s", name, cn[j]);
		int is_float = fct_elem_find(&m.vertex, "red")->type >= FCT_FLOAT32;
		for (int j = 0; j < 3 && is_float; j++)     /* float colours are 0..1 */
			for (size_t i = 0; i < m.nv; i++)
				sc.rgb[j][i] *= 255;
	}
	if (mode == M_SCALAR) {
		sc.val = vertex_column(&m, o.scalar);
		if (!sc.val) {
			const struct fct_prop *p = fct_elem_find(&m.face, o.scalar);
			if (!p)
				fct_die(1, "%s: --scalar: no vertex or face property %s", name, o.scalar);
			if (p->count_type != FCT_NONE)
				fct_die(1, "%s: --scalar: face property %s is a list", name, o.scalar);
			if (!(sc.val = fct_alloc_array(m.nf, sizeof *sc.val, &err)))
				fct_die_err(&err);
			for (size_t f = 0; f < m.nf; f++)
				sc.val[f] = fct_prop_get(p, f);
			sc.val_face = 1;
		}
		size_t nval = sc.val_face ? m.nf : m.nv;
		sc.lo = INFINITY, sc.hi = -INFINITY;
		for (size_t i = 0; i < nval; i++)
			if (isfinite(sc.val[i])) {
				sc.lo = fmin(sc.lo, sc.val[i]);
				sc.hi = fmax(sc.hi, sc.val[i]);
			}
		if (o.has_range)
			sc.lo = o.range[0], sc.hi = o.range[1];
		else if (!(sc.lo <= sc.hi))
			sc.lo = sc.hi = 0;
	}
	const struct fct_elem *edge_el = NULL;
	const struct fct_prop *ev1 = NULL, *ev2 = NULL;
	if (o.edges) {
		edge_el = fct_mesh_find_elem(&m, "edge");
		if (!edge_el)
			fct_die(1, "%s: -e: there is no edge element", name);
		ev1 = fct_elem_find(edge_el, "vertex1");
		ev2 = fct_elem_find(edge_el, "vertex2");
		if (!ev1 || !ev2 || ev1->count_type != FCT_NONE || ev2->count_type != FCT_NONE)
			fct_die(1, "%s: -e: the edge element has no scalar vertex1 vertex2", name);
		for (size_t i = 0; i < edge_el->count; i++) {
			double a = fct_prop_get(ev1, i), b = fct_prop_get(ev2, i);
			if (!(a >= 0 && a < (double)m.nv && a == floor(a)) ||
			    !(b >= 0 && b < (double)m.nv && b == floor(b)))
				fct_die(1, "%s: edge %zu: vertex out of range (%zu vertices)", name, i, m.nv);
		}
	}

	struct fct_view view;
	memset(&view, 0, sizeof view);
	int H0 = o.height ? o.height : 600;
	choose_view(&o, &m, mode == M_SCALAR ? legend_width(&sc, o.scalar, H0) : 0, &view);
	double *q = fct_alloc_array(m.nv, 3 * sizeof *q, &err);
	if (!q)
		fct_die_err(&err);
	for (size_t i = 0; i < m.nv; i++)
		fct_view_to_camera(&view, m.xyz + 3 * i, q + 3 * i);
	sc.q = q;
	if (o.smooth && (mode == M_SHADED || mode == M_PATCH))
		sc.vn = vertex_normals(&m, q, tri, ntri);
	double setup_s = fct_now() - t0;

	t0 = fct_now();
	struct fct_raster r;
	if (fct_raster_init(&r, view.width, view.height, &err))
		fct_die_err(&err);
	long written = 0;
	for (size_t k = 0; k < ntri; k++) {
		const uint32_t *t = tri + 3 * k;
		written += fct_raster_triangle(&r, &view, q + 3 * (size_t)t[0], q + 3 * (size_t)t[1],
		                               q + 3 * (size_t)t[2], (uint32_t)k);
	}
	double raster_s = fct_now() - t0;

	t0 = fct_now();
	struct fct_image img;
	if (fct_image_alloc(&img, view.width, view.height, 3, FCT_PIX_U8, &err))
		fct_die_err(&err);
	shade(&o, &sc, &r, mode, &img);
	size_t covered = 0;
	for (size_t i = 0; i < (size_t)r.width * (size_t)r.height; i++)
		covered += r.id[i] != FCT_RASTER_EMPTY;
	double shade_s = fct_now() - t0;

	t0 = fct_now();
	size_t nwire = 0;
	if (o.wire) {
		static const unsigned char wc[3] = { 40, 40, 40 };
		uint64_t *e = face_edges(&m, &nwire);
		for (size_t i = 0; i < nwire; i++)
			fct_draw_line3d(&img, &r, &view, q + 3 * (e[i] >> 32), q + 3 * (e[i] & 0xffffffffu),
			                o.line_width, wc, 0.8);
		free(e);
	}
	if (edge_el) {
		static const unsigned char ec[3] = { 220, 20, 20 };
		for (size_t i = 0; i < edge_el->count; i++) {
			size_t a = (size_t)fct_prop_get(ev1, i), b = (size_t)fct_prop_get(ev2, i);
			fct_draw_line3d(&img, &r, &view, q + 3 * a, q + 3 * b, 2 * o.line_width, ec, 1);
		}
	}
	if (mode == M_SCALAR)
		draw_legend(&o, &img, &sc);
	if (o.title) {
		unsigned char ink[3];
		int lum = (299 * o.bg[0] + 587 * o.bg[1] + 114 * o.bg[2]) / 1000;
		ink[0] = ink[1] = ink[2] = lum > 128 ? 0 : 255;
		int scale = img.height >= 300 ? 2 : 1;
		fct_draw_text(&img, 4 * scale, 4 * scale, scale, ink, o.title);
	}
	double lines_s = fct_now() - t0;

	t0 = fct_now();
	fct_write_image_or_die(&img, o.out);
	double write_s = fct_now() - t0;

	static const char *const mode_name[] = { "auto", "shaded", "patch", "texture", "color", "scalar" };
	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("triangles", "%zu", ntri);
	fct_report("mode", "%s", mode_name[mode]);
	fct_report("size", "%dx%d", view.width, view.height);
	fct_report("pixels_written", "%ld", written);
	fct_report("pixels_covered", "%zu", covered);
	fct_report("wire_edges", "%zu", nwire);
	if (mode == M_SCALAR) {
		fct_report("range_lo", "%.9g", sc.lo);
		fct_report("range_hi", "%.9g", sc.hi);
	}
	fct_report("read_s", "%.3f", read_s);
	fct_report("setup_s", "%.3f", setup_s);
	fct_report("raster_s", "%.3f", raster_s);
	fct_report("shade_s", "%.3f", shade_s);
	fct_report("lines_s", "%.3f", lines_s);
	fct_report("write_s", "%.3f", write_s);

	fct_image_free(&img);
	for (size_t i = 0; i < sc.ntex; i++)
		fct_image_free(&sc.tex[i]);
	free(sc.tex);
	fct_raster_free(&r);
	free(q);
	free(sc.vn);
	free(sc.uv);
	free(sc.ttex);
	free(sc.patch);
	free(sc.val);
	for (int j = 0; j < 3; j++)
		free(sc.rgb[j]);
	free(tri);
	free(tface);
	fct_mesh_free(&m);
	return 0;
}
