/* viewtex.c - texturing a mesh from registered photos; see viewtex.h for
 * the method (Waechter, Moehrle and Goesele, ECCV 2014). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "geom/bvh.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "render/graphcut.h"
#include "io/header.h"
#include "core/par.h"
#include "core/path.h"
#include "geom/planes.h"
#include "render/raster.h"
#include "render/texmap.h"
#include "render/viewcolor.h"
#include "render/viewtex.h"

#define TILE 1024            /* atlas texels rasterised at a time, per side */
#define GRAD_FLOOR 4.0       /* levels added to the gradient: flat faces still prefer area */
#define MIN_VISIBLE 0.3      /* visible fraction of a candidate's projected area */
#define PLANAR_COS 0.906     /* cos 25 degrees: faces that rectify with their plane */
#define SEAM_SAMPLES 16      /* most samples along one seam edge */

void fct_viewtex_params_default(struct fct_viewtex_params *p)
{
	memset(p, 0, sizeof *p);
	p->smooth = 10;
	p->min_cos = 0.1;
	p->depth_tol = 0.02;
	p->edge_px = 8;
	p->texel_scale = 1;
	p->padding = 4;
	p->atlas_max = 4096;
	p->max_pages = 16;
	p->level = 2;
	p->rectify = 1;
	p->candidates = 6;
	p->max_cycles = 8;
	p->fill[0] = p->fill[1] = p->fill[2] = 128;
}

struct cand {                /* a photo that can texture a face */
	float q;                 /* quality (see viewtex.h) */
	float area;              /* projected area, pixels */
	float col[3];            /* mean colour of its visible pixels */
	float npix;              /* those pixels (at least 1) */
	float vis;               /* the part of the face they are */
	float blend;             /* its weight in a blend (blend_weights) */
	int32_t view;
};

struct vt_view {
	struct fct_camera cam;
	double pose[12];
	struct fct_view v;
	int added;
	size_t faces;            /* labelled with it */
	size_t cands;            /* faces it is a candidate of */
};

struct chart {
	int32_t view, patch;
	int planar;
	uint32_t first, count;   /* its faces: chart_faces[first .. first + count) */
	int w, h;                /* rect with padding, texels */
	double i0, j0;           /* chart-local texel coordinates of the rect's corner */
	size_t page;
	int x, y;                /* the rect's place in its page */
};

struct seam {                /* an edge between two charts */
	uint32_t f[2];           /* the faces on its sides */
	uint32_t v[2];           /* its vertices */
	uint32_t first;          /* its samples: seam_col[6 (first + i) ...] */
	int n;
};

struct fct_viewtex {
	const struct fct_mesh *m;
	struct fct_viewtex_params p;
	size_t nviews;
	struct vt_view *views;
	uint32_t *tri, *tface;   /* the fan */
	size_t ntri;
	uint32_t *tri_first;     /* per face, its first triangle (nf + 1) */
	uint32_t *tcorner;       /* 3 corners (fvert indices) per triangle */
	double *fn, *fc, *farea; /* face unit normals, centroids, areas */
	double diag;
	struct fct_adj adj;
	int32_t *patch;
	struct fct_plane *planes;
	size_t nplanes;
	struct cand *cand;       /* p.candidates per face, best first */
	uint8_t *ncand;
	int32_t *label;
	struct chart *charts;
	size_t ncharts;
	uint32_t *chart_of, *chart_faces;
	float *ab;               /* page texel coordinates per corner */
	double scale;
	struct fct_image *pages;
	unsigned char **mask;
	size_t npages;
	int fill_page, fill_x, fill_y, fill_size;
	struct seam *seams;
	size_t nseams, nsamples;
	float *seam_col;         /* 6 per sample: side 0 RGB, side 1 RGB */
	uint8_t *seam_flat;      /* per sample: bit s when side s lies in a flat part of its photo */
	double *gain;            /* 3 per view */
	float *voff;             /* 3 per corner: levelling offsets */
	struct fct_raster tile;
	float **bsum;            /* blending, per page: 4 per texel, the weighted
	                          * colour sums and the sum of the weights */
	uint8_t **hole;          /* texels their chart's photo does not see */
	float *bdepth;           /* the depth seen by the photo being blended */
	size_t bview;
	struct fct_viewtex_stats st;
	size_t texels;           /* covered by faces */
	double bake;             /* a bake's texels per metre (0: from photos) */
};

/* ---- set-up --------------------------------------------------------------- */

static int check_params(const struct fct_viewtex_params *p, struct fct_err *err)
{
	if (!(p->smooth >= 0 && p->smooth <= 1e6) || !(p->min_cos >= 0 && p->min_cos < 1) ||
	    !(p->depth_tol > 0 && p->depth_tol < 1) || !(p->edge_px >= 0 && p->edge_px <= 1000) ||
	    !(p->texel_scale > 0 && p->texel_scale <= 4) || p->padding < 0 || p->padding > 64 ||
	    p->atlas_max < 64 || p->atlas_max > 16384 || (p->atlas_max & (p->atlas_max - 1)) ||
	    p->max_pages < 1 || p->max_pages > 1024 || p->level < 0 || p->level > 2 ||
	    p->candidates < 1 || p->candidates > 32 || p->max_cycles < 1 || p->max_cycles > 1000)
		return fct_fail(err, "texturing parameters out of range");
	/* The atlas's texels take 12 bytes each while sampling. */
	if ((double)p->max_pages * p->atlas_max * p->atlas_max > (double)((size_t)1 << 29))
		return fct_fail(err, "%d pages of %d x %d texels: more than 2^29 texels", p->max_pages,
		                p->atlas_max, p->atlas_max);
	return 0;
}

/* Face normals (Newell), areas and centroids (of the fan's triangles). */
static void face_geometry(struct fct_viewtex *T)
{
	const struct fct_mesh *m = T->m;
	for (size_t f = 0; f < m->nf; f++) {
		double n[3] = { 0, 0, 0 }, c[3] = { 0, 0, 0 }, a = 0;
		for (uint32_t k = T->tri_first[f]; k < T->tri_first[f + 1]; k++) {
			const double *p0 = m->xyz + 3 * (size_t)T->tri[3 * k];
			const double *p1 = m->xyz + 3 * (size_t)T->tri[3 * k + 1];
			const double *p2 = m->xyz + 3 * (size_t)T->tri[3 * k + 2];
			double e1[3], e2[3], x[3];
			fct_v3_sub(e1, p1, p0);
			fct_v3_sub(e2, p2, p0);
			fct_v3_cross(x, e1, e2);
			double ak = 0.5 * sqrt(fct_v3_dot(x, x));
			fct_v3_add(n, n, x);
			for (int j = 0; j < 3; j++)
				c[j] += ak * (p0[j] + p1[j] + p2[j]) / 3;
			a += ak;
		}
		double len = sqrt(fct_v3_dot(n, n));
		for (int j = 0; j < 3; j++) {
			T->fn[3 * f + (size_t)j] = len > 0 ? n[j] / len : 0;
			T->fc[3 * f + (size_t)j] = a > 0 ? c[j] / a : m->xyz[3 * (size_t)m->fvert[m->fstart[f]] + (size_t)j];
		}
		T->farea[f] = a;
	}
}

struct fct_viewtex *fct_viewtex_new(const struct fct_mesh *m, size_t nviews,
                                    const struct fct_viewtex_params *p, struct fct_err *err)
{
	if (check_params(p, err))
		return NULL;
	if (m->nf == 0) {
		fct_fail(err, "the mesh has no faces: nothing to texture");
		return NULL;
	}
	if (m->nf >= (size_t)INT32_MAX || nviews >= (size_t)INT32_MAX || m->fstart[m->nf] >= UINT32_MAX / 2) {
		fct_fail(err, "mesh or photo count too large");
		return NULL;
	}
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (size_t i = 0; i < m->nv; i++)
		for (int k = 0; k < 3; k++) {
			double x = m->xyz[3 * i + (size_t)k];
			if (!isfinite(x)) {
				fct_fail(err, "vertex %zu: coordinate is not finite", i);
				return NULL;
			}
			lo[k] = fmin(lo[k], x), hi[k] = fmax(hi[k], x);
		}
	struct fct_viewtex *T = calloc(1, sizeof *T);
	if (!T) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	T->m = m;
	T->p = *p;
	T->nviews = nviews;
	T->fill_page = -1;
	T->diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
	               (hi[2] - lo[2]) * (hi[2] - lo[2]));
	size_t nf = m->nf, K = (size_t)p->candidates;
	T->views = calloc(nviews ? nviews : 1, sizeof *T->views);
	T->fn = fct_alloc_array(nf, 3 * sizeof *T->fn, err);
	T->fc = fct_alloc_array(nf, 3 * sizeof *T->fc, err);
	T->farea = fct_alloc_array(nf, sizeof *T->farea, err);
	T->cand = fct_alloc_array(nf, K * sizeof *T->cand, err);
	T->ncand = calloc(nf, 1);
	T->label = fct_alloc_array(nf, sizeof *T->label, err);
	T->tri_first = fct_alloc_array(nf + 1, sizeof *T->tri_first, err);
	if (!T->views || !T->fn || !T->fc || !T->farea || !T->cand || !T->ncand || !T->label ||
	    !T->tri_first || fct_mesh_fan(m, &T->tri, &T->tface, &T->ntri, err) ||
	    fct_adj_build(&T->adj, m, err))
		goto fail;
	if (T->ntri >= UINT32_MAX - 1) {
		fct_fail(err, "too many triangles");
		goto fail;
	}
	/* Each fanned triangle's corners, and each face's first triangle. */
	if (!(T->tcorner = fct_alloc_array(T->ntri, 3 * sizeof *T->tcorner, err)))
		goto fail;
	for (size_t f = 0, k = 0; f <= nf; f++) {
		T->tri_first[f] = (uint32_t)k;
		if (f == nf)
			break;
		uint32_t s = m->fstart[f], n = fct_face_size(m, f);
		for (uint32_t j = 1; k < T->ntri && T->tface[k] == f; k++, j++) {
			T->tcorner[3 * k] = s;
			T->tcorner[3 * k + 1] = s + (j < n ? j : n - 1);
			T->tcorner[3 * k + 2] = s + (j + 1 < n ? j + 1 : n - 1);
		}
	}
	face_geometry(T);
	if (p->rectify) {
		int present;
		if (fct_planes_get(m, &T->planes, &T->nplanes, err) ||
		    (T->nplanes && fct_patches_get(m, &T->patch, &present, (long)T->nplanes, err)))
			goto fail;
	}
	return T;
fail:
	if (!T->views || !T->ncand)
		fct_fail(err, "out of memory");
	fct_viewtex_free(T);
	return NULL;
}

void fct_viewtex_free(struct fct_viewtex *T)
{
	if (!T)
		return;
	free(T->views);
	free(T->tri);
	free(T->tface);
	free(T->tri_first);
	free(T->tcorner);
	free(T->fn);
	free(T->fc);
	free(T->farea);
	fct_adj_free(&T->adj);
	free(T->patch);
	free(T->planes);
	free(T->cand);
	free(T->ncand);
	free(T->label);
	free(T->charts);
	free(T->chart_of);
	free(T->chart_faces);
	free(T->ab);
	for (size_t i = 0; i < T->npages; i++) {
		fct_image_free(&T->pages[i]);
		free(T->mask[i]);
	}
	free(T->pages);
	free(T->mask);
	free(T->seams);
	free(T->seam_col);
	free(T->seam_flat);
	free(T->gain);
	free(T->voff);
	fct_raster_free(&T->tile);
	for (size_t i = 0; T->bsum && i < T->npages; i++)
		free(T->bsum[i]);
	for (size_t i = 0; T->hole && i < T->npages; i++)
		free(T->hole[i]);
	free(T->hole);
	free(T->bsum);
	free(T->bdepth);
	free(T);
}

/* ---- step 1: candidates ------------------------------------------------------ */

/* Pixel (u, v) and camera depth z of world point x in view v; 0 when x
 * is not in front of it. */
static int project(const struct fct_view *v, const double x[3], double *u, double *w, double *z)
{
	double q[3];
	fct_view_to_camera(v, x, q);
	if (!(q[2] > v->near))
		return 0;
	*u = v->fx * q[0] / q[2] + v->cx;
	*w = v->fy * q[1] / q[2] + v->cy;
	*z = q[2];
	return 1;
}

/* Gradient magnitude of the luminance (Sobel, divided by 8: levels per
 * pixel), W*H floats. */
static float *gradient(const struct fct_image *rgb, struct fct_err *err)
{
	int W = rgb->width, H = rgb->height;
	size_t n = (size_t)W * (size_t)H;
	float *L = fct_alloc_array(n, sizeof *L, err), *G = fct_alloc_array(n, sizeof *G, err);
	if (!L || !G) {
		free(L);
		free(G);
		return NULL;
	}
	const unsigned char *d = rgb->data;
	for (size_t i = 0; i < n; i++)
		L[i] = 0.299f * d[3 * i] + 0.587f * d[3 * i + 1] + 0.114f * d[3 * i + 2];
	for (int y = 0; y < H; y++)
		for (int x = 0; x < W; x++) {
			int xm = x > 0 ? x - 1 : x, xp = x + 1 < W ? x + 1 : x;
			int ym = y > 0 ? y - 1 : y, yp = y + 1 < H ? y + 1 : y;
#define PX(a, b) L[(size_t)(b) * (size_t)W + (size_t)(a)]
			float gx = PX(xp, ym) + 2 * PX(xp, y) + PX(xp, yp) - PX(xm, ym) - 2 * PX(xm, y) - PX(xm, yp);
			float gy = PX(xm, yp) + 2 * PX(x, yp) + PX(xp, yp) - PX(xm, ym) - 2 * PX(x, ym) - PX(xp, ym);
#undef PX
			G[(size_t)y * (size_t)W + (size_t)x] = sqrtf(gx * gx + gy * gy) / 8;
		}
	free(L);
	return G;
}

/* Keep (q, area, view) among face f's best candidates (by quality, ties
 * to the lower view). */
static void keep_candidate(struct fct_viewtex *T, size_t f, const struct cand *nc)
{
	size_t K = (size_t)T->p.candidates;
	struct cand *c = T->cand + K * f;
	size_t n = T->ncand[f], at = n;
	while (at > 0 && (c[at - 1].q < nc->q || (c[at - 1].q == nc->q && c[at - 1].view > nc->view)))
		at--;
	if (at >= K)
		return;
	if (n == K)
		n--;
	memmove(c + at + 1, c + at, (n - at) * sizeof *c);
	c[at] = *nc;
	T->ncand[f] = (uint8_t)(n + 1);
}

/* The mesh seen by view V: r (set up here) gets its visibility buffer,
 * *depth (malloc'd, W*H, 0 where nothing) the depth of what it sees.
 * 0 or -1. */
static int view_raster(const struct fct_viewtex *T, const struct vt_view *V, struct fct_raster *r,
                       float **depth, struct fct_err *err)
{
	*depth = NULL;
	if (fct_raster_init(r, V->cam.width, V->cam.height, err))
		return -1;
	for (size_t t = 0; t < T->ntri; t++) {
		double q[3][3];
		for (int j = 0; j < 3; j++)
			fct_view_to_camera(&V->v, T->m->xyz + 3 * (size_t)T->tri[3 * t + (size_t)j], q[j]);
		fct_raster_triangle(r, &V->v, q[0], q[1], q[2], (uint32_t)t);
	}
	size_t np = (size_t)V->cam.width * (size_t)V->cam.height;
	if (!(*depth = fct_alloc_array(np, sizeof **depth, err))) {
		fct_raster_free(r);
		return -1;
	}
	for (size_t i = 0; i < np; i++)
		(*depth)[i] = r->w[i] > 0 ? 1 / r->w[i] : 0;
	return 0;
}

/* What one photo saw, per pixel and per face, for judge_face. */
struct seen_maps {
	const struct vt_view *V;
	const unsigned char *pix;     /* the photo, RGB */
	const float *depth;           /* of the mesh, 0: nothing */
	const float *G, *E;           /* gradient magnitude; distance weight (NULL: 1) */
	const uint32_t *cnt;          /* visible pixels per face */
	const float *qsum, *csum;     /* their summed weighted gradients, colours */
};

/* The pixel of (u, v) clamped into the picture of V. */
static size_t pixel_at(const struct vt_view *V, double u, double v)
{
	int W = V->cam.width, H = V->cam.height;
	int px = (int)floor(u + 0.5), py = (int)floor(v + 0.5);
	px = px < 0 ? 0 : px >= W ? W - 1 : px;
	py = py < 0 ? 0 : py >= H ? H - 1 : py;
	return (size_t)py * (size_t)W + (size_t)px;
}

/* Is the photo a candidate for face f (see viewtex.h, step 1)?  1 with
 * *nc filled but for its view, or 0. */
static int judge_face(const struct fct_viewtex *T, const struct seen_maps *S, size_t f,
                      struct cand *nc)
{
	const struct fct_mesh *m = T->m;
	const struct vt_view *V = S->V;
	int W = V->cam.width, H = V->cam.height;
	/* In front; its projected area, in the picture or not. */
	uint32_t s = m->fstart[f], n = fct_face_size(m, f);
	double area2 = 0, u0 = 0, w0 = 0, up = 0, wp = 0, z = 0;
	int front = n >= 3, inside = 1;
	for (uint32_t i = 0; i < n && front; i++) {
		double u = 0, w = 0;
		front = project(&V->v, m->xyz + 3 * (size_t)m->fvert[s + i], &u, &w, &z);
		inside &= u >= 0 && w >= 0 && u <= W - 1 && w <= H - 1;
		if (i == 0)
			u0 = u, w0 = w;
		else
			area2 += (up - u0) * (w - w0) - (wp - w0) * (u - u0);
		up = u, wp = w;
	}
	if (!front || (!inside && !S->cnt[f]))
		return 0;
	double area = 0.5 * fabs(area2);
	/* The cosine of the viewing angle. */
	const double centre[3] = { V->pose[3], V->pose[7], V->pose[11] };
	double ray[3];
	fct_v3_sub(ray, centre, T->fc + 3 * f);
	double len = sqrt(fct_v3_dot(ray, ray));
	double cs = len > 0 ? fabs(fct_v3_dot(ray, T->fn + 3 * f)) / len : 0;
	if (!(cs > 0) || !(area > 0))
		return 0;
	/* The part of it the photo sees: its visible pixels, or for a face of
	 * a few pixels, nothing of the mesh in front of its centre. */
	double vis, u = 0, w = 0;
	project(&V->v, T->fc + 3 * f, &u, &w, &z);
	size_t at = pixel_at(V, u, w);
	if (area >= 8) {
		vis = fmin(1, S->cnt[f] / area);
	} else {
		float d = S->depth[at];
		vis = inside && !(d > 0 && d < z * (1 - T->p.depth_tol));
	}
	if (!(vis > 0))
		return 0;
	double q;
	if (S->cnt[f] > 0) {
		q = S->qsum[f];
		for (int j = 0; j < 3; j++)
			nc->col[j] = S->csum[3 * f + (size_t)j] / (float)S->cnt[f];
		nc->npix = (float)S->cnt[f];
	} else {       /* smaller than a pixel: its centre's pixel, times its area */
		q = area * (S->G[at] + GRAD_FLOOR) * (S->E ? S->E[at] : 1);
		for (int j = 0; j < 3; j++)
			nc->col[j] = S->pix[3 * at + (size_t)j];
		nc->npix = 1;
	}
	/* Seen too obliquely or too little: a last resort, for faces no photo
	 * sees well. */
	int poor = !(cs >= T->p.min_cos) || vis < MIN_VISIBLE;
	nc->q = (float)(q * cs * vis * vis * (poor ? 1e-3 : 1));
	nc->area = (float)area;
	nc->vis = (float)vis;
	return 1;
}

int fct_viewtex_add_view(struct fct_viewtex *T, size_t k, const struct fct_camera *cam,
                         const double pose[12], const struct fct_image *rgb, size_t *seen,
                         struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	if (seen)
		*seen = 0;
	if (k >= T->nviews || T->views[k].added)
		return fct_fail(err, "photo %zu: added twice or out of range", k);
	if (rgb->type != FCT_PIX_U8 || rgb->channels != 3 || cam->width != rgb->width ||
	    cam->height != rgb->height)
		return fct_fail(err, "photo %zu: the image must be RGB of the camera's size", k);
	struct vt_view *V = &T->views[k];
	if (fct_view_from_camera(&V->v, cam, pose, 0, 0, T->diag > 0 ? 1e-5 * T->diag : 1e-6, err))
		return -1;
	V->cam = *cam;
	memcpy(V->pose, pose, sizeof V->pose);
	V->added = 1;
	int W = cam->width, H = cam->height;
	size_t np = (size_t)W * (size_t)H, nf = m->nf;
	struct fct_raster r;
	float *depth;
	if (view_raster(T, V, &r, &depth, err))
		return -1;
	float *G = gradient(rgb, err);
	float *E = NULL, *qsum = NULL, *csum = NULL;
	uint32_t *cnt = NULL;
	const unsigned char *pix = rgb->data;
	int rc = -1;
	if (!G)
		goto out;
	/* Distance to depth edges and to the picture's border. */
	double slope = FCT_DEFAULT_MAX_JUMP * fct_camera_pixel_angle(cam);
	if (T->p.edge_px > 0) {
		if (!(E = fct_depth_edge_distance(depth, W, H, 1e-3 * T->diag, slope,
		                                  T->p.edge_px, err)))
			goto out;
		for (int y = 0; y < H; y++)
			for (int x = 0; x < W; x++) {
				float b = (float)fmin(fmin(x + 1, W - x), fmin(y + 1, H - y));
				float *e = &E[(size_t)y * (size_t)W + (size_t)x];
				*e = (1 + fminf(*e, b)) / (float)(1 + T->p.edge_px);
				if (*e > 1)
					*e = 1;
			}
	}
	cnt = calloc(nf, sizeof *cnt);
	qsum = calloc(nf, sizeof *qsum);
	csum = calloc(3 * nf, sizeof *csum);
	if (!cnt || !qsum || !csum) {
		fct_fail(err, "out of memory");
		goto out;
	}
	for (size_t i = 0; i < np; i++) {
		if (r.id[i] == FCT_RASTER_EMPTY)
			continue;
		uint32_t f = T->tface[r.id[i]];
		cnt[f]++;
		qsum[f] += (float)((G[i] + GRAD_FLOOR) * (E ? E[i] : 1));
		for (int j = 0; j < 3; j++)
			csum[3 * (size_t)f + (size_t)j] += pix[3 * i + (size_t)j];
	}
	struct seen_maps S = { V, pix, depth, G, E, cnt, qsum, csum };
	size_t nseen = 0;
	for (size_t f = 0; f < nf; f++) {
		struct cand nc;
		if (judge_face(T, &S, f, &nc)) {
			nc.view = (int32_t)k;
			keep_candidate(T, f, &nc);
			nseen++;
		}
	}
	if (seen)
		*seen = nseen;
	rc = 0;
out:
	fct_raster_free(&r);
	free(depth);
	free(G);
	free(E);
	free(cnt);
	free(qsum);
	free(csum);
	return rc;
}

/* ---- step 2: photometry, labels ------------------------------------------------- */

/* The colour of candidate c after its photo's gain. */
static inline double corrected(const struct fct_viewtex *T, const struct cand *c, int ch)
{
	return T->gain[3 * (size_t)c->view + (size_t)ch] * c->col[ch];
}

/* Does candidate c see its face (nearly) whole, over 16 pixels or more?
 * Only then is its mean colour the face's, comparable with the other
 * photos' (a face of a pixel or two takes the colour of whatever its
 * pixels' centres hit). */
static inline int whole(const struct cand *c)
{
	return c->vis >= 0.9 && c->npix >= 16;
}

/* The weight of a candidate's colour: its visible pixels, at most 256, so
 * that large faces do not decide alone; 0 for a face seen in part. */
static inline double colour_weight(const struct cand *c)
{
	return whole(c) ? fmin(c->npix, 256) : 0;
}

/* Each face's consensus colour mu (3 per face): the weighted mean of its
 * candidates' corrected colours, each also weighted by rw. */
static void consensus(const struct fct_viewtex *T, const float *rw, double *mu)
{
	size_t K = (size_t)T->p.candidates;
	for (size_t f = 0; f < T->m->nf; f++) {
		const struct cand *c = T->cand + K * f;
		for (int ch = 0; ch < 3; ch++) {
			double sw = 0, sx = 0;
			for (size_t i = 0; i < T->ncand[f]; i++) {
				double w = colour_weight(&c[i]) * rw[K * f + i];
				sw += w, sx += w * corrected(T, &c[i], ch);
			}
			mu[3 * f + (size_t)ch] = sw > 0 ? sx / sw : 0;
		}
	}
}

/* Distance of candidate c of face f from the face's consensus, levels. */
static double deviation(const struct fct_viewtex *T, const struct cand *c, const double *mu)
{
	double r2 = 0;
	for (int ch = 0; ch < 3; ch++) {
		double r = corrected(T, c, ch) - mu[ch];
		r2 += r * r;
	}
	return sqrt(r2);
}

/* One gain per photo and channel against the consensus: least squares
 * over the faces seen by two or more photos, held towards 1 by a prior of
 * a hundredth of the photo's weight; then all scaled so that the corrected
 * colours' weighted sum is the raw colours' (the faces fix only ratios:
 * the texture keeps the photos' mean level). */
static void fit_gains(struct fct_viewtex *T, const float *rw, const double *mu, double *acc)
{
	size_t nf = T->m->nf, V = T->nviews, K = (size_t)T->p.candidates;
	for (int ch = 0; ch < 3; ch++) {
		memset(acc, 0, V * 3 * sizeof *acc);        /* sum w, w x x, w x y */
		double mean = 0, tot = 0, raw = 0, cor = 0;
		for (size_t f = 0; f < nf; f++) {
			if (T->ncand[f] < 2)
				continue;
			const struct cand *c = T->cand + K * f;
			for (size_t i = 0; i < T->ncand[f]; i++) {
				double w = colour_weight(&c[i]) * rw[K * f + i], x = c[i].col[ch];
				double *a = acc + 3 * (size_t)c[i].view;
				a[0] += w, a[1] += w * x * x, a[2] += w * x * mu[3 * f + (size_t)ch];
				mean += w * x, tot += w;
			}
		}
		mean = tot > 0 ? fmax(mean / tot, 1) : 128;
		for (size_t k = 0; k < V; k++) {
			const double *a = acc + 3 * k;
			double lam = 0.01 * a[0] * mean * mean + 1e-9;
			double g = (a[2] + lam) / (a[1] + lam);
			T->gain[3 * k + (size_t)ch] = g > 0.05 && g < 20 ? g : 1;
		}
		for (size_t f = 0; f < nf; f++)
			for (size_t i = 0; i < T->ncand[f]; i++) {
				const struct cand *c = T->cand + K * f + i;
				raw += colour_weight(c) * c->col[ch];
				cor += colour_weight(c) * corrected(T, c, ch);
			}
		double sc = cor > 0 ? raw / cor : 1;
		for (size_t k = 0; k < V; k++)
			T->gain[3 * k + (size_t)ch] *= sc;
	}
}

/* Photometric calibration (level >= 1): a gain per photo and channel (the
 * cameras' exposure and white balance) that makes the mean colours of each
 * face in its candidate photos agree, by alternating between each face's
 * consensus colour and each photo's gain, the consensus Huber-weighted
 * (HUBER levels) against the last residuals.  Then, choosing one photo per
 * face, the photo-consistency check of Waechter et al.: for faces with
 * three or more candidates, those whose corrected colour lies farther than
 * OUTLIER levels from the consensus are dropped (the photo saw something
 * in front of the face that the mesh does not hold, or misregistered it).
 * Blending keeps them all: the mean takes care of a stray photo. */
#define HUBER 8.0
#define OUTLIER 40.0
static int calibrate(struct fct_viewtex *T, struct fct_err *err)
{
	size_t nf = T->m->nf, K = (size_t)T->p.candidates;
	double *mu = fct_alloc_array(nf, 3 * sizeof *mu, err);
	double *acc = fct_alloc_array(T->nviews, 3 * sizeof *acc, err);
	float *rw = fct_alloc_array(nf * K, sizeof *rw, err);       /* robust weights */
	if (!mu || !acc || !rw) {
		free(mu);
		free(acc);
		free(rw);
		return -1;
	}
	for (size_t i = 0; i < nf * K; i++)
		rw[i] = 1;
	int iters = T->p.level >= 1 ? 12 : 1;
	for (int it = 0; it < iters; it++) {
		consensus(T, rw, mu);
		for (size_t f = 0; f < nf; f++)
			for (size_t i = 0; i < T->ncand[f]; i++) {
				double r = deviation(T, &T->cand[K * f + i], mu + 3 * f);
				rw[K * f + i] = (float)(r <= HUBER ? 1 : HUBER / r);
			}
		if (it + 1 < iters)
			fit_gains(T, rw, mu, acc);
	}
	for (size_t f = 0; f < nf && !T->p.blend; f++) {
		if (T->ncand[f] < 3)
			continue;
		struct cand *c = T->cand + K * f;
		size_t n = 0, nwhole = 0;
		for (size_t i = 0; i < T->ncand[f]; i++)
			nwhole += (size_t)whole(&c[i]);
		if (nwhole < 3)
			continue;
		for (size_t i = 0; i < T->ncand[f]; i++) {
			if (!whole(&c[i]) || deviation(T, &c[i], mu + 3 * f) <= OUTLIER)
				c[n++] = c[i];
			else
				T->st.outliers++;
		}
		if (n)
			T->ncand[f] = (uint8_t)n;
	}
	free(mu);
	free(acc);
	free(rw);
	return 0;
}

int fct_viewtex_label(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	size_t nf = m->nf, K = (size_t)T->p.candidates, V = T->nviews;
	T->gain = fct_alloc_array(V, 3 * sizeof *T->gain, err);
	if (!T->gain)
		return -1;
	for (size_t i = 0; i < 3 * V; i++)
		T->gain[i] = 1;
	if (calibrate(T, err))
		return -1;
	size_t *start = fct_alloc_array(nf + 1, sizeof *start, err);
	size_t *nb_start = fct_alloc_array(nf + 1, sizeof *nb_start, err);
	double *ppm = fct_alloc_array(nf, sizeof *ppm, err);       /* pixels per metre */
	int32_t *lab = NULL;
	double *cost = NULL, *nb_w = NULL;
	uint32_t *nb = NULL;
	int rc = -1;
	if (!start || !nb_start || !ppm)
		goto out;
	size_t nc = 0;
	for (size_t f = 0; f < nf; f++) {
		start[f] = nc;
		nc += T->ncand[f];
	}
	start[nf] = nc;
	T->st.candidates = nc;
	if (!(lab = fct_alloc_array(nc, sizeof *lab, err)) || !(cost = fct_alloc_array(nc, sizeof *cost, err)))
		goto out;
	for (size_t f = 0; f < nf; f++) {
		const struct cand *c = T->cand + K * f;
		double amax = 0;
		for (size_t i = 0; i < T->ncand[f]; i++)
			amax = fmax(amax, c[i].area);
		for (size_t i = 0; i < T->ncand[f]; i++) {
			lab[start[f] + i] = c[i].view;
			cost[start[f] + i] = c[0].q > 0 ? amax * (1 - c[i].q / c[0].q) : 0;
		}
		ppm[f] = T->farea[f] > 0 ? sqrt(amax / T->farea[f]) : 0;
		T->label[f] = T->ncand[f] ? c[0].view : -1;
	}
	/* Neighbours across edges walked by exactly two faces (a fold of
	 * more has no one pair to keep together). */
	const struct fct_adj *A = &T->adj;
	size_t nn = 0;
	for (size_t e = 0; e < A->ne; e++)
		nn += fct_adj_edge_nfaces(A, e) == 2 ? 2 : 0;
	if (!(nb = fct_alloc_array(nn, sizeof *nb, err)) || !(nb_w = fct_alloc_array(nn, sizeof *nb_w, err)))
		goto out;
	memset(nb_start, 0, (nf + 1) * sizeof *nb_start);
	for (size_t e = 0; e < A->ne; e++)
		if (fct_adj_edge_nfaces(A, e) == 2) {
			nb_start[A->edge_f[A->edge_fstart[e]] + 1]++;
			nb_start[A->edge_f[A->edge_fstart[e] + 1] + 1]++;
		}
	for (size_t f = 0; f < nf; f++)
		nb_start[f + 1] += nb_start[f];
	size_t *fill = fct_alloc_array(nf, sizeof *fill, err);
	if (!fill)
		goto out;
	memcpy(fill, nb_start, nf * sizeof *fill);
	for (size_t e = 0; e < A->ne; e++) {
		if (fct_adj_edge_nfaces(A, e) != 2)
			continue;
		uint32_t a = A->edge_f[A->edge_fstart[e]], b = A->edge_f[A->edge_fstart[e] + 1];
		if (a == b)
			continue;
		double len = sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)A->edge_v[2 * e],
		                               m->xyz + 3 * (size_t)A->edge_v[2 * e + 1]));
		double w = T->p.smooth * len * 0.5 * (ppm[a] + ppm[b]);
		nb[fill[a]] = b, nb_w[fill[a]++] = w;
		nb[fill[b]] = a, nb_w[fill[b]++] = w;
	}
	/* Pairs (a, a) were counted but not filled: close the gaps. */
	for (size_t f = 0; f < nf; f++)
		for (size_t i = fill[f]; i < nb_start[f + 1]; i++)
			nb[i] = (uint32_t)f, nb_w[i] = 0;
	free(fill);
	struct fct_labeling L = { nf, start, lab, cost, nb_start, nb, nb_w };
	T->st.energy_start = fct_labeling_energy(&L, T->label);
	if (fct_expansion(T->label, &L, (int32_t)T->nviews, T->p.max_cycles, &T->st.cycles, err))
		goto out;
	T->st.energy = fct_labeling_energy(&L, T->label);
	T->st.faces = nf;
	for (size_t f = 0; f < nf; f++) {
		if (T->label[f] < 0)
			T->st.unseen++;
		else
			T->views[T->label[f]].faces++;
	}
	for (size_t k = 0; k < T->nviews; k++)
		T->st.views_used += T->views[k].faces > 0;
	for (size_t f = 0; f < nf; f++)
		for (size_t i = 0; i < T->ncand[f]; i++)
			T->views[T->cand[K * f + i].view].cands++;
	rc = 0;
out:
	free(start);
	free(nb_start);
	free(ppm);
	free(lab);
	free(cost);
	free(nb);
	free(nb_w);
	return rc;
}

size_t fct_viewtex_view_faces(const struct fct_viewtex *T, size_t k)
{
	return k < T->nviews ? T->views[k].faces : 0;
}

int32_t fct_viewtex_face_photo(const struct fct_viewtex *T, size_t f)
{
	return T->label && f < T->m->nf ? T->label[f] : -1;
}

void fct_viewtex_photo_gain(const struct fct_viewtex *T, size_t k, double gain[3])
{
	for (int j = 0; j < 3; j++)
		gain[j] = T->gain && k < T->nviews ? T->gain[3 * k + (size_t)j] : 1;
}

int fct_viewtex_needs_view(const struct fct_viewtex *T, size_t k)
{
	return k < T->nviews && (T->views[k].faces || T->views[k].cands);
}

/* ---- step 3: charts, parametrisation, packing ------------------------------------ */

/* The chart key of face f: faces join a chart when they share it. */
static int same_chart(const struct fct_viewtex *T, size_t f, size_t g)
{
	if (T->label[f] != T->label[g] || T->label[f] < 0)
		return 0;
	return !T->patch || T->patch[f] == T->patch[g];
}

/* Connected faces with the same photo (and patch): chart_of, charts[] with
 * their faces in chart_faces. */
static int make_charts(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	const struct fct_adj *A = &T->adj;
	size_t nf = m->nf;
	T->chart_of = fct_alloc_array(nf, sizeof *T->chart_of, err);
	T->chart_faces = fct_alloc_array(nf, sizeof *T->chart_faces, err);
	if (!T->chart_of || !T->chart_faces)
		return -1;
	for (size_t f = 0; f < nf; f++)
		T->chart_of[f] = UINT32_MAX;
	size_t cap = 0, head = 0, tail = 0;
	for (size_t f0 = 0; f0 < nf; f0++) {
		if (T->chart_of[f0] != UINT32_MAX || T->label[f0] < 0)
			continue;
		if (fct_grow((void **)&T->charts, &cap, T->ncharts + 1, sizeof *T->charts, err))
			return -1;
		uint32_t id = (uint32_t)T->ncharts++;
		struct chart *c = &T->charts[id];
		memset(c, 0, sizeof *c);
		c->view = T->label[f0];
		c->patch = T->patch ? T->patch[f0] : -1;
		c->first = (uint32_t)tail;
		/* Breadth first; chart_faces doubles as the queue. */
		T->chart_of[f0] = id;
		T->chart_faces[tail++] = (uint32_t)f0;
		for (; head < tail; head++) {
			uint32_t f = T->chart_faces[head];
			for (uint32_t i = m->fstart[f]; i < m->fstart[f + 1]; i++) {
				uint32_t e = A->face_e[i];
				if (e == FCT_ADJ_NONE || fct_adj_edge_nfaces(A, e) != 2)
					continue;
				for (uint32_t j = A->edge_fstart[e]; j < A->edge_fstart[e + 1]; j++) {
					uint32_t g = A->edge_f[j];
					if (T->chart_of[g] == UINT32_MAX && same_chart(T, f, g)) {
						T->chart_of[g] = id;
						T->chart_faces[tail++] = g;
					}
				}
			}
		}
		c->count = (uint32_t)(tail - c->first);
	}
	return 0;
}

/* The plane frame of a planar chart: e1 along the photo's x axis, e2
 * along its y axis (both in the plane), and the texels per metre. */
static int planar_frame(const struct fct_viewtex *T, const struct chart *c, double e1[3],
                        double e2[3], double *density)
{
	const struct fct_plane *pl = &T->planes[c->patch];
	const struct vt_view *V = &T->views[c->view];
	for (uint32_t i = 0; i < c->count; i++) {
		uint32_t f = T->chart_faces[c->first + i];
		if (!(fabs(fct_v3_dot(T->fn + 3 * (size_t)f, pl->n)) >= PLANAR_COS))
			return 0;
	}
	double x[3] = { V->pose[0], V->pose[4], V->pose[8] }, y[3] = { V->pose[1], V->pose[5], V->pose[9] };
	fct_v3_axpy(e1, x, -fct_v3_dot(x, pl->n), pl->n);
	double l = sqrt(fct_v3_dot(e1, e1));
	if (l < 0.1) {                  /* looking along the plane's x: use y */
		fct_v3_axpy(e1, y, -fct_v3_dot(y, pl->n), pl->n);
		l = sqrt(fct_v3_dot(e1, e1));
	}
	if (!(l > 0))
		return 0;
	for (int j = 0; j < 3; j++)
		e1[j] /= l;
	fct_v3_cross(e2, pl->n, e1);
	if (fct_v3_dot(e2, y) < 0)
		for (int j = 0; j < 3; j++)
			e2[j] = -e2[j];
	double best = 0;
	for (uint32_t i = 0; i < c->count; i++) {
		uint32_t f = T->chart_faces[c->first + i];
		double q[3];
		fct_view_to_camera(&V->v, T->fc + 3 * (size_t)f, q);
		if (q[2] > 0)
			best = fmax(best, sqrt(V->v.fx * V->v.fy) / q[2]);
	}
	*density = best;
	return best > 0;
}

/* The frame of a baked chart (no photo): its plane's, with e1 along the
 * world axis that lies most in the plane, when every face is within 25
 * degrees of the plane (returns 1); else the plane across its key's axis
 * (orthographic along the axis, which every face's normal is within 55
 * degrees of). */
static int bake_frame(const struct fct_viewtex *T, const struct chart *c, double e1[3], double e2[3])
{
	memset(e1, 0, 3 * sizeof *e1);
	memset(e2, 0, 3 * sizeof *e2);
	int planar = T->p.rectify && c->patch >= 0 && (size_t)c->patch < T->nplanes;
	const double *n = planar ? T->planes[c->patch].n : NULL;
	for (uint32_t i = 0; planar && i < c->count; i++) {
		uint32_t f = T->chart_faces[c->first + i];
		planar = fabs(fct_v3_dot(T->fn + 3 * (size_t)f, n)) >= PLANAR_COS;
	}
	if (planar) {
		int a = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
		double x[3] = { 0, 0, 0 };
		x[a] = 1;
		fct_v3_axpy(e1, x, -n[a], n);
		double l = sqrt(fct_v3_dot(e1, e1));
		if (l > 0.5) {             /* at least sqrt(2/3) for a unit normal */
			for (int j = 0; j < 3; j++)
				e1[j] /= l;
			fct_v3_cross(e2, n, e1);
			return 1;
		}
	}
	int axis = c->view / 2;
	e1[(axis + 1) % 3] = 1;
	e2[(axis + 2) % 3] = c->view % 2 ? -1 : 1;
	return 0;
}

/* Chart-local texel coordinates of every corner of chart c at scale s,
 * into ab; the rect (with padding) into c->w, h, i0, j0. */
static void parametrise(struct fct_viewtex *T, struct chart *c, double s)
{
	const struct fct_mesh *m = T->m;
	const struct vt_view *V = &T->views[T->bake ? 0 : c->view];
	double e1[3] = { 0, 0, 0 }, e2[3] = { 0, 0, 0 }, density = T->bake;
	if (T->bake)
		c->planar = bake_frame(T, c, e1, e2);
	else
		c->planar = T->p.rectify && c->patch >= 0 && (size_t)c->patch < T->nplanes &&
		            planar_frame(T, c, e1, e2, &density);
	int metric = c->planar || T->bake;
	double amin = INFINITY, amax = -INFINITY, bmin = INFINITY, bmax = -INFINITY;
	double limit = T->p.atlas_max - 2 * T->p.padding - 2;
	for (int pass = 0; pass < 2; pass++) {
		double k = metric ? s * density : s, n = 0, sa = 0, sb = 0;
		for (uint32_t i = 0; i < c->count; i++) {
			uint32_t f = T->chart_faces[c->first + i];
			for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
				const double *x = m->xyz + 3 * (size_t)m->fvert[j];
				double a, b;
				if (metric) {
					a = k * fct_v3_dot(x, e1);
					b = k * fct_v3_dot(x, e2);
				} else {
					double u, w, z;
					if (!project(&V->v, x, &u, &w, &z))
						u = w = 0;     /* not for a candidate face: all in front */
					a = k * (u + 0.5);
					b = k * (w + 0.5);
				}
				T->ab[2 * (size_t)j] = (float)a, T->ab[2 * (size_t)j + 1] = (float)b;
				n++, sa += a, sb += b;
			}
		}
		/* Turned so that its principal axis runs along the rows: a long
		 * thin chart slanted in its photo would waste its box. */
		double ma = sa / n, mb = sb / n, caa = 0, cbb = 0, cab = 0;
		for (uint32_t i = 0; i < c->count; i++) {
			uint32_t f = T->chart_faces[c->first + i];
			for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
				double a = T->ab[2 * (size_t)j] - ma, b = T->ab[2 * (size_t)j + 1] - mb;
				caa += a * a, cbb += b * b, cab += a * b;
			}
		}
		double th = 0.5 * atan2(2 * cab, caa - cbb), cs = cos(th), sn = sin(th);
		for (uint32_t i = 0; i < c->count; i++) {
			uint32_t f = T->chart_faces[c->first + i];
			for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
				double a = T->ab[2 * (size_t)j], b = T->ab[2 * (size_t)j + 1];
				double ra = cs * a + sn * b, rb = -sn * a + cs * b;
				T->ab[2 * (size_t)j] = (float)ra, T->ab[2 * (size_t)j + 1] = (float)rb;
				amin = fmin(amin, ra), amax = fmax(amax, ra);
				bmin = fmin(bmin, rb), bmax = fmax(bmax, rb);
			}
		}
		/* A chart larger than a page is drawn smaller. */
		double big = fmax(amax - amin, bmax - bmin);
		if (pass == 1 || !(big > limit))
			break;
		s *= limit / big * 0.999;
		amin = bmin = INFINITY, amax = bmax = -INFINITY;
	}
	int pad = T->p.padding;
	c->i0 = floor(amin) - pad;
	c->j0 = floor(bmin) - pad;
	c->w = (int)(ceil(amax) - c->i0) + pad;
	c->h = (int)(ceil(bmax) - c->j0) + pad;
}

/* Shelf packing of rects (w, h; sorted tallest first) into pages of side
 * S: returns the number of pages and fills page, x, y. */
struct rect {
	int w, h;
	size_t id;
	size_t page;
	int x, y;
};

static int cmp_rect(const void *a, const void *b)
{
	const struct rect *p = a, *q = b;
	if (p->h != q->h)
		return p->h > q->h ? -1 : 1;
	if (p->w != q->w)
		return p->w > q->w ? -1 : 1;
	return (p->id > q->id) - (p->id < q->id);
}

static size_t shelf_pack(struct rect *r, size_t n, int S, int *last_height)
{
	size_t page = 0;
	int x = 0, y = 0, shelf = 0;
	for (size_t i = 0; i < n; i++) {
		if (x + r[i].w > S) {
			y += shelf, x = 0, shelf = 0;
		}
		if (y + r[i].h > S) {
			page++, x = 0, y = 0, shelf = 0;
		}
		r[i].page = page, r[i].x = x, r[i].y = y;
		x += r[i].w;
		shelf = r[i].h > shelf ? r[i].h : shelf;
	}
	*last_height = y + shelf;
	return n ? page + 1 : 0;
}

/* The edges between charts of different photos, and room for their
 * samples: one per four pixels of the edge's length in the finer photo,
 * 1 to SEAM_SAMPLES. */
static int make_seams(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	const struct fct_adj *A = &T->adj;
	size_t cap = 0;
	for (size_t e = 0; e < A->ne; e++) {
		if (fct_adj_edge_nfaces(A, e) != 2)
			continue;
		uint32_t f = A->edge_f[A->edge_fstart[e]], g = A->edge_f[A->edge_fstart[e] + 1];
		if (T->label[f] < 0 || T->label[g] < 0 || T->chart_of[f] == T->chart_of[g] ||
		    T->label[f] == T->label[g])
			continue;
		if (fct_grow((void **)&T->seams, &cap, T->nseams + 1, sizeof *T->seams, err))
			return -1;
		struct seam *sm = &T->seams[T->nseams++];
		sm->f[0] = f, sm->f[1] = g;
		sm->v[0] = A->edge_v[2 * e], sm->v[1] = A->edge_v[2 * e + 1];
		/* One sample per four pixels of its length in the finer photo. */
		double px = 0;
		for (int side = 0; side < 2; side++) {
			const struct fct_view *v = &T->views[T->label[sm->f[side]]].v;
			double u0, w0, u1, w1, z;
			if (project(v, m->xyz + 3 * (size_t)sm->v[0], &u0, &w0, &z) &&
			    project(v, m->xyz + 3 * (size_t)sm->v[1], &u1, &w1, &z))
				px = fmax(px, hypot(u1 - u0, w1 - w0));
		}
		sm->n = (int)fmin(SEAM_SAMPLES, fmax(1, ceil(px / 4)));
		sm->first = (uint32_t)T->nsamples;
		T->nsamples += (size_t)sm->n;
	}
	T->st.seam_edges = T->nseams;
	T->seam_flat = calloc(T->nsamples ? T->nsamples : 1, 1);
	if (!T->seam_flat ||
	    !(T->seam_col = calloc(T->nsamples ? T->nsamples : 1, 6 * sizeof *T->seam_col)))
		return fct_fail(err, "out of memory");
	return 0;
}

/* Steps 3-4 after the labels, with photos or baked. */
static int layout(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	if (make_charts(T, err))
		return -1;
	if (!(T->ab = fct_alloc_array(m->fstart[m->nf], 2 * sizeof *T->ab, err)))
		return -1;
	size_t nr = T->ncharts + (T->st.unseen > 0);
	struct rect *r = fct_alloc_array(nr, sizeof *r, err);
	if (!r)
		return -1;
	int pad = T->p.padding, S = T->p.atlas_max, last_h = 0;
	T->fill_size = 1 + 2 * pad;
	double s = T->p.texel_scale;
	size_t npages = 0;
	for (int attempt = 0;; attempt++) {
		double area = 0;
		int side = 1;
		for (size_t i = 0; i < T->ncharts; i++) {
			struct chart *c = &T->charts[i];
			parametrise(T, c, s);
			r[i].w = c->w, r[i].h = c->h, r[i].id = i;
		}
		if (nr > T->ncharts)
			r[nr - 1].w = r[nr - 1].h = T->fill_size, r[nr - 1].id = nr - 1;
		for (size_t i = 0; i < nr; i++) {
			area += (double)r[i].w * r[i].h;
			while (side < r[i].w || side < r[i].h)
				side *= 2;
		}
		qsort(r, nr, sizeof *r, cmp_rect);
		/* The smallest power of two that holds it all on one page, at
		 * most atlas_max. */
		S = 64;
		while (S < T->p.atlas_max && ((double)S * S < area / 0.85 || S < side))
			S *= 2;
		for (;;) {
			npages = shelf_pack(r, nr, S, &last_h);
			if (npages <= 1 || S >= T->p.atlas_max)
				break;
			S *= 2;
		}
		if (npages <= (size_t)T->p.max_pages || attempt >= 60)
			break;
		s *= 0.8 * sqrt((double)T->p.max_pages / (double)npages);
	}
	if (npages > (size_t)T->p.max_pages) {
		free(r);
		return fct_fail(err, "the texture does not fit %d pages of %d x %d", T->p.max_pages, S, S);
	}
	T->scale = s;
	for (size_t i = 0; i < nr; i++) {
		if (r[i].id == T->ncharts) {
			T->fill_page = (int)r[i].page, T->fill_x = r[i].x, T->fill_y = r[i].y;
			continue;
		}
		struct chart *c = &T->charts[r[i].id];
		c->page = r[i].page, c->x = r[i].x, c->y = r[i].y;
	}
	free(r);
	/* Page texel coordinates: chart-local minus the rect's corner plus
	 * its place. */
	for (size_t i = 0; i < T->ncharts; i++) {
		const struct chart *c = &T->charts[i];
		for (uint32_t k = 0; k < c->count; k++) {
			uint32_t f = T->chart_faces[c->first + k];
			for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
				T->ab[2 * (size_t)j] = (float)(T->ab[2 * (size_t)j] - c->i0 + c->x);
				T->ab[2 * (size_t)j + 1] = (float)(T->ab[2 * (size_t)j + 1] - c->j0 + c->y);
			}
		}
		T->st.rectified += (size_t)c->planar;
	}
	for (size_t f = 0; f < m->nf; f++)
		if (T->label[f] < 0)
			for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
				T->ab[2 * (size_t)j] = (float)(T->fill_x + 0.5 * T->fill_size);
				T->ab[2 * (size_t)j + 1] = (float)(T->fill_y + 0.5 * T->fill_size);
			}
	/* The pages. */
	T->npages = npages;
	T->pages = calloc(npages ? npages : 1, sizeof *T->pages);
	T->mask = calloc(npages ? npages : 1, sizeof *T->mask);
	if (!T->pages || !T->mask)
		return fct_fail(err, "out of memory");
	for (size_t i = 0; i < npages; i++) {
		int h = S;
		if (i + 1 == npages)
			for (h = 64; h < last_h; h *= 2)
				;
		if (fct_image_alloc(&T->pages[i], S, h > S ? S : h, 3, FCT_PIX_U8, err))
			return -1;
		if (!(T->mask[i] = calloc((size_t)S * (size_t)T->pages[i].height, 1)))
			return fct_fail(err, "out of memory");
	}
	T->st.charts = T->ncharts;
	T->st.pages = npages;
	T->st.page_width = npages ? T->pages[0].width : 0;
	T->st.page_height = npages ? T->pages[0].height : 0;
	T->st.scale = s;
	/* A bake has no photos to level between: its charts' edges are not seams. */
	if (!T->bake && make_seams(T, err))
		return -1;
	return fct_raster_init(&T->tile, TILE, TILE, err);
}

int fct_viewtex_layout(struct fct_viewtex *T, struct fct_err *err)
{
	if (T->bake || T->pages)
		return fct_fail(err, "layout: done already");
	return layout(T, err);
}

/* The key of a baked face of unit normal n: 2 a + (n_a < 0) for the axis a
 * nearest n (the lower axis on a tie). */
static int32_t axis_key(const double n[3])
{
	int a = 0;
	for (int j = 1; j < 3; j++)
		if (fabs(n[j]) > fabs(n[a]))
			a = j;
	return 2 * a + (n[a] < 0);
}

int fct_viewtex_layout_bake(struct fct_viewtex *T, double texels_per_metre, struct fct_err *err)
{
	if (T->bake || T->pages)
		return fct_fail(err, "layout: done already");
	if (!(texels_per_metre > 0 && texels_per_metre < 1e300))
		return fct_fail(err, "bake: %g texels per metre", texels_per_metre);
	const struct fct_mesh *m = T->m;
	T->bake = texels_per_metre;
	for (size_t f = 0; f < m->nf; f++) {
		const double *n = T->fn + 3 * f;
		/* A face of a planar patch that lies in its plane takes the
		 * plane's key, so the patch is one chart in the plane's frame. */
		if (T->patch && T->patch[f] >= 0 && (size_t)T->patch[f] < T->nplanes) {
			const double *pn = T->planes[T->patch[f]].n;
			if (fabs(fct_v3_dot(n, pn)) >= PLANAR_COS)
				n = pn;
		}
		T->label[f] = axis_key(n);
	}
	T->st.faces = m->nf;
	return layout(T, err);
}

/* ---- step 4: texels ------------------------------------------------------------ */

typedef void texel_fn(struct fct_viewtex *T, const struct chart *c, uint32_t tri, double b1,
                      double b2, size_t at, void *ctx);

/* Call fn for every texel of chart c that one of its faces covers: the
 * faces' triangles rasterised at their page coordinates, a tile at a
 * time, at flat depth (so the barycentrics are the affine ones). */
static int chart_texels(struct fct_viewtex *T, const struct chart *c, texel_fn *fn, void *ctx,
                        struct fct_err *err)
{
	const struct fct_image *pg = &T->pages[c->page];
	for (int ty = 0; ty < c->h; ty += TILE)
		for (int tx = 0; tx < c->w; tx += TILE) {
			int tw = c->w - tx < TILE ? c->w - tx : TILE, th = c->h - ty < TILE ? c->h - ty : TILE;
			int x0 = c->x + tx, y0 = c->y + ty;
			if (fct_raster_reset(&T->tile, tw, th, err))
				return -1;
			struct fct_view v;
			memset(&v, 0, sizeof v);
			v.R[0] = v.R[4] = v.R[8] = 1;
			v.fx = v.fy = 1;
			v.cx = -x0 - 0.5, v.cy = -y0 - 0.5;
			v.near = 0.5;
			v.width = tw, v.height = th;
			for (uint32_t i = 0; i < c->count; i++) {
				uint32_t f = T->chart_faces[c->first + i];
				for (uint32_t k = T->tri_first[f]; k < T->tri_first[f + 1]; k++) {
					double q[3][3];
					for (int j = 0; j < 3; j++) {
						const float *ab = T->ab + 2 * (size_t)T->tcorner[3 * k + (size_t)j];
						q[j][0] = ab[0], q[j][1] = ab[1], q[j][2] = 1;
					}
					fct_raster_triangle(&T->tile, &v, q[0], q[1], q[2], k);
				}
			}
			for (int y = 0; y < th; y++)
				for (int x = 0; x < tw; x++) {
					size_t i = (size_t)y * (size_t)tw + (size_t)x;
					if (T->tile.id[i] == FCT_RASTER_EMPTY)
						continue;
					size_t at = (size_t)(y0 + y) * (size_t)pg->width + (size_t)(x0 + x);
					fn(T, c, T->tile.id[i], T->tile.b[2 * i], T->tile.b[2 * i + 1], at, ctx);
				}
		}
	return 0;
}

/* The 3-D point at barycentrics b1 b2 of triangle k. */
static void tri_point(const struct fct_viewtex *T, uint32_t k, double b1, double b2, double x[3])
{
	const double *p0 = T->m->xyz + 3 * (size_t)T->tri[3 * (size_t)k];
	const double *p1 = T->m->xyz + 3 * (size_t)T->tri[3 * (size_t)k + 1];
	const double *p2 = T->m->xyz + 3 * (size_t)T->tri[3 * (size_t)k + 2];
	for (int j = 0; j < 3; j++)
		x[j] = (1 - b1 - b2) * p0[j] + b1 * p1[j] + b2 * p2[j];
}

/* Bilinear colour of photo rgb at world point x seen by view v. */
static void photo_colour(const struct fct_view *v, const struct fct_image *rgb, const double x[3],
                         double col[3])
{
	double u, w, z;
	if (!project(v, x, &u, &w, &z))
		u = w = 0;
	fct_texture_sample(rgb, (u + 0.5) / rgb->width, 1 - (w + 0.5) / rgb->height, col);
}

/* Does the photo being sampled (T->bview, its depth in T->bdepth) see
 * world point x: inside the picture, nothing of the mesh in front of it?
 * (u, v) gets its pixel. */
static int sees_point(const struct fct_viewtex *T, const double x[3], double *u, double *v)
{
	const struct vt_view *V = &T->views[T->bview];
	double z;
	if (!project(&V->v, x, u, v, &z) || *u < 0 || *v < 0 || *u > V->cam.width - 1 ||
	    *v > V->cam.height - 1)
		return 0;
	int px = (int)floor(*u + 0.5), py = (int)floor(*v + 0.5);
	float d = T->bdepth[(size_t)py * (size_t)V->cam.width + (size_t)px];
	return !(d > 0 && d < z * (1 - T->p.depth_tol));
}

/* A texel of a chart of the photo being sampled: its colour there; where
 * the photo does not see the point (a face partly outside it, or partly
 * hidden), the texel is a hole that the other photos fill (blend_texel),
 * the clamped colour only the last resort. */
static void fill_texel(struct fct_viewtex *T, const struct chart *c, uint32_t tri, double b1,
                       double b2, size_t at, void *ctx)
{
	const struct fct_image *rgb = ctx;
	double x[3], col[3], u, v;
	tri_point(T, tri, b1, b2, x);
	if (!sees_point(T, x, &u, &v))
		T->hole[c->page][at] = 1;
	photo_colour(&T->views[c->view].v, rgb, x, col);
	unsigned char *px = (unsigned char *)T->pages[c->page].data + 3 * at;
	for (int j = 0; j < 3; j++)
		px[j] = (unsigned char)floor(col[j] + 0.5);
	T->texels += !T->mask[c->page][at];
	T->mask[c->page][at] = 1;
}

/* Is the photo flat around world point x (colour col there): within
 * FLAT levels, in every channel, at 2 pixels up, down, left and right?
 * Seam samples elsewhere differ between two photos because the edges of
 * the texture fall apart on imperfect geometry, not because of exposure,
 * and levelling must not follow them. */
#define FLAT 12.0
static int flat_at(const struct fct_view *v, const struct fct_image *rgb, const double x[3],
                   const double col[3])
{
	double u, w, z;
	if (!project(v, x, &u, &w, &z))
		return 0;
	static const int d[4][2] = { { 2, 0 }, { -2, 0 }, { 0, 2 }, { 0, -2 } };
	for (int k = 0; k < 4; k++) {
		double c[3];
		fct_texture_sample(rgb, (u + d[k][0] + 0.5) / rgb->width, 1 - (w + d[k][1] + 0.5) / rgb->height, c);
		for (int j = 0; j < 3; j++)
			if (!(fabs(c[j] - col[j]) <= FLAT))
				return 0;
	}
	return 1;
}

/* Each candidate's weight in a blend: its resolution on its face, the
 * square root of its projected area over the largest of the face's
 * candidates'.  A photo that sees the face at half the resolution of the
 * best has samples twice as wide, which blur the texel; the plain mean
 * lost 0.2-0.3 dB at held-out views of mkscene's rooms (Kinect noise,
 * grained albedo), the area itself as the weight 0.03 dB of the 7-Scenes
 * frames'. */
static void blend_weights(struct fct_viewtex *T)
{
	for (size_t f = 0; f < T->m->nf; f++) {
		struct cand *cd = T->cand + (size_t)T->p.candidates * f;
		double most = 0;
		for (size_t k = 0; k < T->ncand[f]; k++)
			most = cd[k].area > most ? cd[k].area : most;
		for (size_t k = 0; k < T->ncand[f]; k++)
			cd[k].blend = most > 0 ? (float)sqrt(cd[k].area / most) : 1;
	}
}

/* Blending: add photo T->bview's colour (after its gain) of the texel's
 * point to the texel's sums, weighed by the photo's resolution there
 * (blend_weights), when the photo is a candidate of the face and sees the
 * point (inside, nothing of the mesh in front of it). */
static void blend_texel(struct fct_viewtex *T, const struct chart *c, uint32_t tri, double b1,
                        double b2, size_t at, void *ctx)
{
	const struct fct_image *rgb = ctx;
	uint32_t f = T->tface[tri];
	const struct cand *cd = T->cand + (size_t)T->p.candidates * f;
	size_t i = 0;
	while (i < T->ncand[f] && cd[i].view != (int32_t)T->bview)
		i++;
	double x[3], u, v, col[3];
	tri_point(T, tri, b1, b2, x);
	if (i == T->ncand[f] || !sees_point(T, x, &u, &v))
		return;
	fct_texture_sample(rgb, (u + 0.5) / rgb->width, 1 - (v + 0.5) / rgb->height, col);
	float *sum = T->bsum[c->page] + 4 * at;
	double w = cd[i].blend;
	for (int j = 0; j < 3; j++) {
		double g = T->gain[3 * T->bview + (size_t)j] * col[j];
		sum[j] += (float)(w * (g < 0 ? 0 : g > 255 ? 255 : g));
	}
	sum[3] += (float)w;
}

/* Does chart c hold a face that photo k is a candidate of? */
static int chart_sees(const struct fct_viewtex *T, const struct chart *c, size_t k)
{
	for (uint32_t i = 0; i < c->count; i++) {
		uint32_t f = T->chart_faces[c->first + i];
		const struct cand *cd = T->cand + (size_t)T->p.candidates * f;
		for (size_t j = 0; j < T->ncand[f]; j++)
			if (cd[j].view == (int32_t)k)
				return 1;
	}
	return 0;
}

/* The per-texel sums over photos (blending, and the holes' fill), and
 * the candidates' weights in them, the candidates being final. */
static int blend_alloc(struct fct_viewtex *T, struct fct_err *err)
{
	blend_weights(T);
	T->bsum = calloc(T->npages, sizeof *T->bsum);
	T->hole = calloc(T->npages, sizeof *T->hole);
	if (!T->bsum || !T->hole)
		return fct_fail(err, "out of memory");
	for (size_t i = 0; i < T->npages; i++) {
		size_t n = (size_t)T->pages[i].width * (size_t)T->pages[i].height;
		T->bsum[i] = calloc(n, 4 * sizeof **T->bsum);
		T->hole[i] = calloc(n, 1);
		if (!T->bsum[i] || !T->hole[i])
			return fct_fail(err, "out of memory");
	}
	return 0;
}

int fct_viewtex_sample_view(struct fct_viewtex *T, size_t k, const struct fct_image *rgb,
                            struct fct_err *err)
{
	if (k >= T->nviews || !T->views[k].added || !T->pages)
		return fct_fail(err, "photo %zu: not added, or sampled before the layout", k);
	const struct vt_view *V = &T->views[k];
	if (rgb->type != FCT_PIX_U8 || rgb->channels != 3 || rgb->width != V->cam.width ||
	    rgb->height != V->cam.height)
		return fct_fail(err, "photo %zu: not the image that was added", k);
	if (!T->bsum && blend_alloc(T, err))
		return -1;
	struct fct_raster r;
	if (view_raster(T, V, &r, &T->bdepth, err))
		return -1;
	fct_raster_free(&r);
	T->bview = k;
	int rc = 0;
	for (size_t i = 0; i < T->ncharts && !rc; i++) {
		const struct chart *c = &T->charts[i];
		if (c->view == (int32_t)k)
			rc = chart_texels(T, c, fill_texel, (void *)rgb, err);
		if (!rc && chart_sees(T, c, k))
			rc = chart_texels(T, c, blend_texel, (void *)rgb, err);
	}
	free(T->bdepth);
	T->bdepth = NULL;
	if (rc)
		return -1;
	for (size_t i = 0; i < T->nseams; i++) {
		const struct seam *sm = &T->seams[i];
		for (int side = 0; side < 2; side++) {
			if (T->label[sm->f[side]] != (int32_t)k)
				continue;
			const double *a = T->m->xyz + 3 * (size_t)sm->v[0], *b = T->m->xyz + 3 * (size_t)sm->v[1];
			for (int j = 0; j < sm->n; j++) {
				double t = (j + 0.5) / sm->n, x[3], col[3];
				for (int d = 0; d < 3; d++)
					x[d] = a[d] + t * (b[d] - a[d]);
				size_t at = (size_t)sm->first + (size_t)j;
				photo_colour(&V->v, rgb, x, col);
				float *out = T->seam_col + 6 * at + 3 * (size_t)side;
				for (int d = 0; d < 3; d++)
					out[d] = (float)col[d];
				if (flat_at(&V->v, rgb, x, col))
					T->seam_flat[at] |= (uint8_t)(1 << side);
			}
		}
	}
	return 0;
}

/* ---- a bake's texels ------------------------------------------------------------ */

#define BAKE_BATCH (1u << 18)    /* texels collected before a parallel pass */

struct bake_texel {
	uint32_t tri;
	float b1, b2;
	uint32_t page;
	size_t at;
};

struct bake_run {
	struct fct_viewtex *T;
	fct_viewtex_colour_fn *fn;
	const void *ctx;
	int nthreads;
	struct bake_texel *t;
	unsigned char *rgb;      /* 3 per collected texel */
	size_t n;
};

static void bake_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	struct bake_run *B = ctx;
	for (size_t i = lo; i < hi; i++) {
		const struct bake_texel *t = &B->t[i];
		double x[3], col[3];
		tri_point(B->T, t->tri, t->b1, t->b2, x);
		B->fn(B->ctx, B->T->tface[t->tri], x, col);
		for (int j = 0; j < 3; j++) {
			double v = floor(col[j] + 0.5);
			B->rgb[3 * i + (size_t)j] = (unsigned char)(v > 0 ? v < 255 ? v : 255 : 0);
		}
	}
}

/* The collected texels' colours, in parallel (each texel's own), then
 * written in the pages. */
static void bake_flush(struct bake_run *B)
{
	struct fct_viewtex *T = B->T;
	fct_par_run(B->nthreads, B->n, 0, bake_chunk, B);
	for (size_t i = 0; i < B->n; i++) {
		const struct bake_texel *t = &B->t[i];
		memcpy((unsigned char *)T->pages[t->page].data + 3 * t->at, B->rgb + 3 * i, 3);
		T->texels += !T->mask[t->page][t->at];
		T->mask[t->page][t->at] = 1;
	}
	B->n = 0;
}

static void bake_collect(struct fct_viewtex *T, const struct chart *c, uint32_t tri, double b1,
                         double b2, size_t at, void *ctx)
{
	(void)T;
	struct bake_run *B = ctx;
	B->t[B->n++] = (struct bake_texel){ tri, (float)b1, (float)b2, (uint32_t)c->page, at };
	if (B->n == BAKE_BATCH)
		bake_flush(B);
}

/* Collect the texel under barycentrics (b1, b2) of triangle k of chart c
 * (its corners' page coordinates a) when it is empty. */
static void bake_point(struct bake_run *B, const struct chart *c, uint32_t k, double b1, double b2,
                       const float *const a[3])
{
	struct fct_viewtex *T = B->T;
	double ab[2];
	for (int d = 0; d < 2; d++)
		ab[d] = (1 - b1 - b2) * a[0][d] + b1 * a[1][d] + b2 * a[2][d];
	int x = (int)floor(ab[0]), y = (int)floor(ab[1]);
	x = x < c->x ? c->x : x >= c->x + c->w ? c->x + c->w - 1 : x;
	y = y < c->y ? c->y : y >= c->y + c->h ? c->y + c->h - 1 : y;
	size_t at = (size_t)y * (size_t)T->pages[c->page].width + (size_t)x;
	if (!T->mask[c->page][at])
		bake_collect(T, c, k, b1, b2, at, B);
}

int fct_viewtex_bake(struct fct_viewtex *T, fct_viewtex_colour_fn *fn, const void *ctx, int nthreads,
                     struct fct_err *err)
{
	if (!T->bake || !T->pages)
		return fct_fail(err, "bake: before fct_viewtex_layout_bake");
	struct bake_run B = { T, fn, ctx, fct_par_threads(nthreads), NULL, NULL, 0 };
	B.t = fct_alloc_array(BAKE_BATCH, sizeof *B.t, err);
	B.rgb = fct_alloc_array(BAKE_BATCH, 3, err);
	int rc = B.t && B.rgb ? 0 : -1;
	for (size_t i = 0; i < T->ncharts && !rc; i++)
		rc = chart_texels(T, &T->charts[i], bake_collect, &B, err);
	/* A sliver narrower than a texel covers no texel's centre: the texels
	 * along its edges, a texel apart, and under its centroid, when still
	 * empty, take its colour there, so that a viewer's bilinear lookup
	 * anywhere on it reads the face (and the padding around it), not the
	 * black between charts. */
	if (!rc && B.n)
		bake_flush(&B);
	static const double corner_b[4][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 0, 0 } };
	for (size_t i = 0; i < T->ncharts && !rc; i++) {
		const struct chart *c = &T->charts[i];
		for (uint32_t j = 0; j < c->count; j++) {
			uint32_t f = T->chart_faces[c->first + j];
			for (uint32_t k = T->tri_first[f]; k < T->tri_first[f + 1]; k++) {
				const float *a[3];
				for (int q = 0; q < 3; q++)
					a[q] = T->ab + 2 * (size_t)T->tcorner[3 * (size_t)k + (size_t)q];
				bake_point(&B, c, k, 1.0 / 3, 1.0 / 3, a);
				for (int e = 0; e < 3; e++) {
					double len = hypot(a[(e + 1) % 3][0] - a[e][0], a[(e + 1) % 3][1] - a[e][1]);
					int n = len < 1 ? 1 : len < 16384 ? (int)ceil(len) : 16384;
					for (int q = 0; q < n; q++) {
						double t = (double)q / n;
						bake_point(&B, c, k, (1 - t) * corner_b[e][0] + t * corner_b[e + 1][0],
						           (1 - t) * corner_b[e][1] + t * corner_b[e + 1][1], a);
					}
				}
			}
		}
	}
	if (!rc && B.n)
		bake_flush(&B);
	free(B.t);
	free(B.rgb);
	return rc;
}

/* ---- step 5: levelling, padding ---------------------------------------------- */

/* A sparse least-squares problem: rows of (column, value) pairs, the
 * right-hand side, solved by CGLS (conjugate gradients on the normal
 * equations) from 0, which converges to the least-norm solution. */
struct lsq {
	size_t nrows, ncols;
	size_t *start;           /* nrows + 1 */
	uint32_t *col;
	double *val, *rhs;
	size_t cap_rows, cap_col, cap_val, cap_start;
};

static int lsq_row(struct lsq *L, const uint32_t *cols, const double *vals, int n, double rhs,
                   struct fct_err *err)
{
	size_t e = L->nrows ? L->start[L->nrows] : 0;
	if (fct_grow((void **)&L->start, &L->cap_start, L->nrows + 2, sizeof *L->start, err) ||
	    fct_grow((void **)&L->rhs, &L->cap_rows, L->nrows + 1, sizeof *L->rhs, err) ||
	    fct_grow((void **)&L->col, &L->cap_col, e + (size_t)n, sizeof *L->col, err) ||
	    fct_grow((void **)&L->val, &L->cap_val, e + (size_t)n, sizeof *L->val, err))
		return -1;
	L->start[0] = 0;
	for (int i = 0; i < n; i++)
		L->col[e + (size_t)i] = cols[i], L->val[e + (size_t)i] = vals[i];
	L->rhs[L->nrows++] = rhs;
	L->start[L->nrows] = e + (size_t)n;
	return 0;
}

static void lsq_free(struct lsq *L)
{
	free(L->start);
	free(L->col);
	free(L->val);
	free(L->rhs);
	memset(L, 0, sizeof *L);
}

/* x (ncols) = the least-squares solution, iters at most. */
static int lsq_solve(const struct lsq *L, double *x, int iters, struct fct_err *err)
{
	size_t n = L->ncols, mr = L->nrows;
	double *r = fct_alloc_array(mr, sizeof *r, err), *q = fct_alloc_array(mr, sizeof *q, err);
	double *s = fct_alloc_array(n, sizeof *s, err), *p = fct_alloc_array(n, sizeof *p, err);
	int rc = r && q && s && p ? 0 : -1;
	if (rc)
		goto out;
	memset(x, 0, n * sizeof *x);
	memcpy(r, L->rhs, mr * sizeof *r);
	memset(s, 0, n * sizeof *s);
	for (size_t i = 0; i < mr; i++)
		for (size_t e = L->start[i]; e < L->start[i + 1]; e++)
			s[L->col[e]] += L->val[e] * r[i];
	memcpy(p, s, n * sizeof *p);
	double gamma = 0, g0;
	for (size_t j = 0; j < n; j++)
		gamma += s[j] * s[j];
	g0 = gamma;
	for (int it = 0; it < iters && gamma > 1e-20 * g0 && gamma > 0; it++) {
		double qq = 0;
		for (size_t i = 0; i < mr; i++) {
			double v = 0;
			for (size_t e = L->start[i]; e < L->start[i + 1]; e++)
				v += L->val[e] * p[L->col[e]];
			q[i] = v;
			qq += v * v;
		}
		if (!(qq > 0))
			break;
		double alpha = gamma / qq;
		for (size_t j = 0; j < n; j++)
			x[j] += alpha * p[j];
		for (size_t i = 0; i < mr; i++)
			r[i] -= alpha * q[i];
		memset(s, 0, n * sizeof *s);
		for (size_t i = 0; i < mr; i++)
			for (size_t e = L->start[i]; e < L->start[i + 1]; e++)
				s[L->col[e]] += L->val[e] * r[i];
		double g1 = 0;
		for (size_t j = 0; j < n; j++)
			g1 += s[j] * s[j];
		double beta = g1 / gamma;
		gamma = g1;
		for (size_t j = 0; j < n; j++)
			p[j] = s[j] + beta * p[j];
	}
out:
	free(r);
	free(q);
	free(s);
	free(p);
	return rc;
}

/* Waechter et al.'s seam levelling: an offset per (vertex, chart), one
 * unknown per distinct chart around each vertex, making the two sides of
 * each seam sample agree and adjacent vertices of a chart alike. */
static int level_seams(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	const struct fct_adj *A = &T->adj;
	size_t nc = m->fstart[m->nf];
	uint32_t *unk = fct_alloc_array(nc, sizeof *unk, err);   /* unknown of each corner */
	if (!unk)
		return -1;
	size_t nu = 0;
	for (size_t v = 0; v < m->nv; v++) {
		/* The charts around v, numbered in the order of its faces. */
		for (uint32_t i = A->vert_fstart[v]; i < A->vert_fstart[v + 1]; i++) {
			uint32_t f = A->vert_f[i];
			if (T->label[f] < 0)
				continue;
			uint32_t c = T->chart_of[f], id = UINT32_MAX;
			for (uint32_t j = A->vert_fstart[v]; j < i && id == UINT32_MAX; j++) {
				uint32_t g = A->vert_f[j];
				if (T->label[g] >= 0 && T->chart_of[g] == c)
					for (uint32_t k = m->fstart[g]; k < m->fstart[g + 1]; k++)
						if (m->fvert[k] == v)
							id = unk[k];
			}
			if (id == UINT32_MAX)
				id = (uint32_t)nu++;
			for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++)
				if (m->fvert[k] == v)
					unk[k] = id;
		}
	}
	for (size_t f = 0; f < m->nf; f++)
		if (T->label[f] < 0)
			for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++)
				unk[k] = UINT32_MAX;
	double *x = fct_alloc_array(nu, sizeof *x, err);
	int rc = x ? 0 : -1;
	for (int ch = 0; ch < 3 && !rc; ch++) {
		struct lsq L;
		memset(&L, 0, sizeof L);
		L.ncols = nu;
		for (size_t i = 0; i < T->nseams && !rc; i++) {
			const struct seam *sm = &T->seams[i];
			uint32_t u[2][2];
			for (int side = 0; side < 2; side++)
				for (int e = 0; e < 2; e++) {
					u[side][e] = UINT32_MAX;
					for (uint32_t k = m->fstart[sm->f[side]]; k < m->fstart[sm->f[side] + 1]; k++)
						if (m->fvert[k] == sm->v[e])
							u[side][e] = unk[k];
				}
			const double *g0 = T->gain + 3 * (size_t)T->label[sm->f[0]];
			const double *g1 = T->gain + 3 * (size_t)T->label[sm->f[1]];
			for (int j = 0; j < sm->n && !rc; j++) {
				if (T->seam_flat[(size_t)sm->first + (size_t)j] != 3) {
					rc = lsq_row(&L, NULL, NULL, 0, 0, err);    /* keeps rows and samples aligned */
					continue;
				}
				const float *c = T->seam_col + 6 * ((size_t)sm->first + (size_t)j);
				double t = (j + 0.5) / sm->n;
				double c0 = g0[ch] * c[ch], c1 = g1[ch] * c[3 + ch];
				uint32_t cols[4] = { u[0][0], u[0][1], u[1][0], u[1][1] };
				double vals[4] = { 1 - t, t, -(1 - t), -t };
				rc = lsq_row(&L, cols, vals, 4, c1 - c0, err);
			}
		}
		/* Smoothness inside charts: each face edge once per face. */
		for (size_t f = 0; f < m->nf && !rc; f++) {
			if (T->label[f] < 0)
				continue;
			uint32_t s = m->fstart[f], n = fct_face_size(m, f);
			for (uint32_t k = 0; k < n && !rc; k++) {
				uint32_t cols[2] = { unk[s + k], unk[s + (k + 1) % n] };
				if (cols[0] == cols[1])
					continue;
				double vals[2] = { 0.3, -0.3 };
				rc = lsq_row(&L, cols, vals, 2, 0, err);
			}
		}
		/* Each offset held towards 0, so that a small chart cannot take
		 * a seam's whole difference alone. */
		for (size_t k = 0; k < nu && !rc; k++) {
			uint32_t col = (uint32_t)k;
			double val = 0.5;
			rc = lsq_row(&L, &col, &val, 1, 0, err);
		}
		/* Iteratively reweighted: seam samples that still disagree by
		 * more than HUBER after a solve (an edge of the texture that the
		 * two photos place apart, or two surfaces, not a change of
		 * exposure) weigh HUBER / |residual|, and nothing beyond three
		 * times that. */
		size_t nseam_rows = 0;
		for (size_t i = 0; i < T->nseams; i++)
			nseam_rows += (size_t)T->seams[i].n;
		size_t nent = nseam_rows ? L.start[nseam_rows] : 0;
		double *w = rc ? NULL : fct_alloc_array(nseam_rows + nent, sizeof *w, err);
		rc = rc || !w ? -1 : 0;
		double *base = w ? w + nseam_rows : NULL;      /* the rows' unweighted values */
		for (size_t e = 0; e < nent && !rc; e++)
			base[e] = L.val[e];
		for (size_t r = 0; r < nseam_rows && !rc; r++)
			w[r] = L.rhs[r];                          /* unweighted right-hand sides */
		for (int it = 0; it < 4 && !rc; it++) {
			rc = lsq_solve(&L, x, 500, err);
			for (size_t r = 0; r < nseam_rows && !rc && it < 3; r++) {
				double v = -w[r];
				for (size_t e = L.start[r]; e < L.start[r + 1]; e++)
					v += base[e] * x[L.col[e]];
				double res = fabs(v), nw = res <= HUBER ? 1 : res <= 3 * HUBER ? HUBER / res : 0;
				for (size_t e = L.start[r]; e < L.start[r + 1]; e++)
					L.val[e] = nw * base[e];
				L.rhs[r] = nw * w[r];
			}
		}
		free(w);
		for (size_t k = 0; k < nc && !rc; k++)
			T->voff[3 * k + (size_t)ch] = unk[k] == UINT32_MAX ? 0 : (float)x[unk[k]];
		lsq_free(&L);
	}
	free(x);
	free(unk);
	return rc;
}

/* RMS difference of the seam samples where both photos are flat (those
 * levelling works on), raw or levelled (after the gains and the seam
 * offsets). */
static double seam_rms(const struct fct_viewtex *T, int levelled)
{
	const struct fct_mesh *m = T->m;
	double sum = 0, n = 0;
	for (size_t i = 0; i < T->nseams; i++) {
		const struct seam *sm = &T->seams[i];
		double g[2][3], vo[2][2][3];
		for (int side = 0; side < 2; side++) {
			size_t k = (size_t)T->label[sm->f[side]];
			for (int ch = 0; ch < 3; ch++) {
				g[side][ch] = levelled ? T->gain[3 * k + (size_t)ch] : 1;
			}
			for (int e = 0; e < 2; e++)
				for (uint32_t c = m->fstart[sm->f[side]]; c < m->fstart[sm->f[side] + 1]; c++)
					if (m->fvert[c] == sm->v[e])
						for (int ch = 0; ch < 3; ch++)
							vo[side][e][ch] = levelled ? T->voff[3 * (size_t)c + (size_t)ch] : 0;
		}
		for (int j = 0; j < sm->n; j++) {
			if (T->seam_flat[(size_t)sm->first + (size_t)j] != 3)
				continue;
			const float *c = T->seam_col + 6 * ((size_t)sm->first + (size_t)j);
			double t = (j + 0.5) / sm->n;
			for (int ch = 0; ch < 3; ch++) {
				double a = g[0][ch] * c[ch] + (1 - t) * vo[0][0][ch] + t * vo[0][1][ch];
				double b = g[1][ch] * c[3 + ch] + (1 - t) * vo[1][0][ch] + t * vo[1][1][ch];
				sum += (a - b) * (a - b);
				n++;
			}
		}
	}
	return n > 0 ? sqrt(sum / n) : 0;
}

static void correct_texel(struct fct_viewtex *T, const struct chart *c, uint32_t tri, double b1,
                          double b2, size_t at, void *ctx)
{
	(void)ctx;
	unsigned char *out = (unsigned char *)T->pages[c->page].data + 3 * at;
	const float *sum = T->bsum ? T->bsum[c->page] + 4 * at : NULL;
	if (sum && sum[3] > 0 && (T->p.blend || T->hole[c->page][at])) {
		for (int j = 0; j < 3; j++) {
			double v = floor(sum[j] / sum[3] + 0.5);
			out[j] = (unsigned char)(v > 255 ? 255 : v);
		}
		return;
	}
	const double *g = T->gain + 3 * (size_t)c->view;
	const float *v0 = T->voff + 3 * (size_t)T->tcorner[3 * (size_t)tri];
	const float *v1 = T->voff + 3 * (size_t)T->tcorner[3 * (size_t)tri + 1];
	const float *v2 = T->voff + 3 * (size_t)T->tcorner[3 * (size_t)tri + 2];
	unsigned char *px = (unsigned char *)T->pages[c->page].data + 3 * at;
	for (int j = 0; j < 3; j++) {
		double v = g[j] * px[j] + (1 - b1 - b2) * v0[j] + b1 * v1[j] + b2 * v2[j];
		v = floor(v + 0.5);
		px[j] = (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : v);
	}
}

/* One ring of padding inside the rect [x0, x0 + w) x [y0, y0 + h) of
 * page pg: unfilled texels with filled 8-neighbours (mask 1 .. it: the
 * charts and the rings before) take their mean; their places go to ring. */
static size_t pad_ring(struct fct_viewtex *T, size_t pg, int x0, int y0, int w, int h, int it,
                       uint32_t *ring, size_t nr)
{
	struct fct_image *img = &T->pages[pg];
	const unsigned char *mask = T->mask[pg];
	unsigned char *d = img->data;
	int W = img->width, H = img->height;
	for (int y = y0; y < y0 + h; y++)
		for (int x = x0; x < x0 + w; x++) {
			size_t i = (size_t)y * (size_t)W + (size_t)x;
			if (mask[i])
				continue;
			int sum[3] = { 0, 0, 0 }, k = 0;
			for (int dy = -1; dy <= 1; dy++)
				for (int dx = -1; dx <= 1; dx++) {
					int xx = x + dx, yy = y + dy;
					if (xx < 0 || yy < 0 || xx >= W || yy >= H)
						continue;
					size_t j = (size_t)yy * (size_t)W + (size_t)xx;
					if (!mask[j] || mask[j] > it)
						continue;
					for (int c = 0; c < 3; c++)
						sum[c] += d[3 * j + (size_t)c];
					k++;
				}
			if (!k)
				continue;
			for (int c = 0; c < 3; c++)
				d[3 * i + (size_t)c] = (unsigned char)((sum[c] + k / 2) / k);
			ring[nr++] = (uint32_t)i;
		}
	return nr;
}

/* Pad every chart of every page, ring by ring (each ring reads only the
 * rings before it, so two charts' paddings never mix). */
static int pad_charts(struct fct_viewtex *T, struct fct_err *err)
{
	size_t most = 0;
	for (size_t i = 0; i < T->npages; i++) {
		size_t n = (size_t)T->pages[i].width * (size_t)T->pages[i].height;
		most = n > most ? n : most;
	}
	uint32_t *ring = fct_alloc_array(most, sizeof *ring, err);
	if (!ring)
		return -1;
	for (int it = 1; it <= T->p.padding; it++)
		for (size_t pg = 0; pg < T->npages; pg++) {
			size_t nr = 0;
			for (size_t i = 0; i < T->ncharts; i++) {
				const struct chart *c = &T->charts[i];
				if (c->page == pg)
					nr = pad_ring(T, pg, c->x, c->y, c->w, c->h, it, ring, nr);
			}
			for (size_t r = 0; r < nr; r++)
				T->mask[pg][ring[r]] = (unsigned char)(it + 1);
		}
	free(ring);
	return 0;
}

int fct_viewtex_finish(struct fct_viewtex *T, struct fct_err *err)
{
	const struct fct_mesh *m = T->m;
	if (!T->pages)
		return fct_fail(err, "finish before the layout");
	size_t nc = m->fstart[m->nf];
	T->voff = calloc(nc ? 3 * nc : 1, sizeof *T->voff);
	if (!T->voff)
		return fct_fail(err, "out of memory");
	T->st.seam_rms_before = seam_rms(T, 0);
	if (T->p.level >= 2 && !T->p.blend && T->nseams && level_seams(T, err))
		return -1;
	T->st.seam_rms_after = seam_rms(T, 1);
	/* Texels from one photo take its gain and the seam offsets; blended
	 * ones are the weighted mean of their photos' corrected colours. */
	if (T->bsum)
		for (size_t i = 0; i < T->ncharts; i++)
			if (chart_texels(T, &T->charts[i], correct_texel, NULL, err))
				return -1;
	if (T->fill_page >= 0) {
		struct fct_image *pg = &T->pages[T->fill_page];
		for (int y = 0; y < T->fill_size; y++)
			for (int x = 0; x < T->fill_size; x++) {
				size_t at = (size_t)(T->fill_y + y) * (size_t)pg->width + (size_t)(T->fill_x + x);
				memcpy((unsigned char *)pg->data + 3 * at, T->p.fill, 3);
				T->mask[T->fill_page][at] = 1;
			}
	}
	if (pad_charts(T, err))
		return -1;
	size_t total = 0;
	for (size_t i = 0; i < T->npages; i++)
		total += (size_t)T->pages[i].width * (size_t)T->pages[i].height;
	T->st.fill_ratio = total ? (double)T->texels / (double)total : 0;
	return 0;
}

size_t fct_viewtex_npages(const struct fct_viewtex *T)
{
	return T->npages;
}

const struct fct_image *fct_viewtex_page(const struct fct_viewtex *T, size_t i)
{
	return i < T->npages ? &T->pages[i] : NULL;
}

int fct_viewtex_apply(struct fct_viewtex *T, struct fct_mesh *m, char *const *names, int per_face,
                      struct fct_err *err)
{
	if (m != T->m || !T->ab)
		return fct_fail(err, "apply: not the mesh that was textured, or before the layout");
	size_t nc = m->fstart[m->nf];
	float *st = fct_alloc_array(nc, 2 * sizeof *st, err);
	int32_t *tn = fct_alloc_array(m->nf, sizeof *tn, err);
	int rc = -1;
	if (!st || !tn)
		goto out;
	for (size_t f = 0; f < m->nf; f++) {
		size_t pg = T->label[f] >= 0 ? T->charts[T->chart_of[f]].page : (size_t)T->fill_page;
		tn[f] = (int32_t)pg;
		double W = T->pages[pg].width, H = T->pages[pg].height;
		for (uint32_t j = m->fstart[f]; j < m->fstart[f + 1]; j++) {
			st[2 * (size_t)j] = (float)(T->ab[2 * (size_t)j] / W);
			st[2 * (size_t)j + 1] = (float)(1 - T->ab[2 * (size_t)j + 1] / H);
		}
	}
	/* TextureFile comments: the pages, replacing any there. */
	fct_header_remove_textures(m);
	for (size_t i = 0; i < T->npages; i++)
		if (fct_header_set_texture(m, i, names[i], err))
			goto out;
	/* After this the mesh may have more vertices: T is done with it. */
	rc = fct_texmap_set_corners(m, st, tn, per_face, err);
	T->m = NULL;
out:
	free(st);
	free(tn);
	return rc;
}

void fct_viewtex_get_stats(const struct fct_viewtex *T, struct fct_viewtex_stats *st)
{
	*st = T->st;
}

/* ---- photos read from their files, one at a time -------------------------------- */

/* The largest side of a photo read (viewtex's limit). */
#define PHOTO_MAX_SIDE (1 << 14)

int fct_viewtex_add_photos(struct fct_viewtex *T, const struct fct_photo *ph, size_t n, size_t *seen,
                           struct fct_err *err)
{
	for (size_t i = 0; i < n; i++) {
		struct fct_image rgb;
		struct fct_camera cam;
		if (fct_photo_read(&ph[i], PHOTO_MAX_SIDE, &rgb, &cam, err))
			return -1;
		int rc = fct_viewtex_add_view(T, i, &cam, ph[i].pose, &rgb, seen ? &seen[i] : NULL, err);
		fct_image_free(&rgb);
		if (rc) {
			fct_err_prefix(err, "%s", ph[i].path);
			return -1;
		}
	}
	return 0;
}

int fct_viewtex_sample_photos(struct fct_viewtex *T, const struct fct_photo *ph, size_t n,
                              struct fct_err *err)
{
	for (size_t i = 0; i < n; i++) {
		if (!fct_viewtex_needs_view(T, i))
			continue;
		struct fct_image rgb;
		struct fct_camera cam;
		if (fct_photo_read(&ph[i], PHOTO_MAX_SIDE, &rgb, &cam, err))
			return -1;
		int rc = fct_viewtex_sample_view(T, i, &rgb, err);
		fct_image_free(&rgb);
		if (rc) {
			fct_err_prefix(err, "%s", ph[i].path);
			return -1;
		}
	}
	return 0;
}

char **fct_viewtex_page_names(const char *model, size_t n, struct fct_err *err)
{
	size_t stem = fct_path_stem_length(model);
	char **names = calloc(n ? n : 1, sizeof *names);
	if (!names) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	for (size_t i = 0; i < n; i++) {
		size_t len = stem + 40;
		if (!(names[i] = malloc(len))) {
			fct_viewtex_page_names_free(names, i);
			fct_fail(err, "out of memory");
			return NULL;
		}
		snprintf(names[i], len, "%.*s_atlas%zu.png", (int)stem, model, i);
	}
	return names;
}

void fct_viewtex_page_names_free(char **names, size_t n)
{
	for (size_t i = 0; names && i < n; i++)
		free(names[i]);
	free(names);
}
