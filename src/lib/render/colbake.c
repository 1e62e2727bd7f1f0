/* colbake.c - a model's texture baked from a dense mesh's vertex colours;
 * see colbake.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"
#include "io/header.h"
#include "render/colbake.h"

static const char *const colour_names[3] = { "red", "green", "blue" };

/* The vertex colour columns of m, or 0 when it has not all three. */
static int colour_props(const struct fct_mesh *m, const struct fct_prop *p[3])
{
	for (int j = 0; j < 3; j++) {
		p[j] = fct_elem_find(&m->vertex, colour_names[j]);
		if (!p[j] || p[j]->count_type != FCT_NONE)
			return 0;
	}
	return 1;
}

int fct_colbake_applies(const struct fct_mesh *m)
{
	const struct fct_prop *p[3];
	return m->nf > 0 && colour_props(m, p) && !fct_header_texture(m, 0);
}

void fct_colbake_free(struct fct_colbake *B)
{
	if (!B)
		return;
	fct_bvh_free(&B->tree);
	free(B->xyz);
	free(B->tri);
	free(B->rgb);
	memset(B, 0, sizeof *B);
}

int fct_colbake_init(struct fct_colbake *B, const struct fct_mesh *dense, struct fct_err *err)
{
	memset(B, 0, sizeof *B);
	const struct fct_prop *p[3];
	if (!colour_props(dense, p))
		return fct_fail(err, "the mesh has no vertex colours (red green blue) to bake");
	uint32_t *face = NULL;
	size_t nv = dense->nv;
	if (fct_mesh_fan(dense, &B->tri, &face, &B->ntri, err))
		return -1;
	free(face);
	B->nv = nv;
	B->xyz = fct_alloc_array(nv ? nv : 1, 3 * sizeof *B->xyz, err);
	B->rgb = fct_alloc_array(nv ? nv : 1, 3, err);
	if (!B->xyz || !B->rgb) {
		fct_colbake_free(B);
		return -1;
	}
	memcpy(B->xyz, dense->xyz, 3 * nv * sizeof *B->xyz);
	for (size_t i = 0; i < nv; i++)
		for (int j = 0; j < 3; j++) {
			double v = floor(fct_prop_get(p[j], i) + 0.5);
			B->rgb[3 * i + (size_t)j] = (uint8_t)(v > 0 ? v < 255 ? v : 255 : 0);
		}
	/* Triangles with a corner not finite have no nearest point to give. */
	size_t k = 0;
	double len = 0, n = 0;
	for (size_t t = 0; t < B->ntri; t++) {
		const uint32_t *c = B->tri + 3 * t;
		int ok = 1;
		for (int j = 0; j < 3 && ok; j++)
			for (int d = 0; d < 3; d++)
				ok &= isfinite(B->xyz[3 * (size_t)c[j] + (size_t)d]);
		if (!ok)
			continue;
		for (int j = 0; j < 3; j++) {
			double e = sqrt(fct_v3_dist2(B->xyz + 3 * (size_t)c[j], B->xyz + 3 * (size_t)c[(j + 1) % 3]));
			len += e, n += e > 0;
		}
		memmove(B->tri + 3 * k++, c, 3 * sizeof *c);
	}
	B->ntri = k;
	B->mean_edge = n > 0 ? len / n : 0;
	if (fct_bvh_build(&B->tree, B->xyz, B->tri, B->ntri, err)) {
		fct_colbake_free(B);
		return -1;
	}
	return 0;
}

/* Barycentric weights w of q (a point of triangle a b c) by the areas of
 * the sub-triangles, clamped into the triangle; a triangle without area
 * gives its nearest corner all the weight. */
static void barycentric(const double *a, const double *b, const double *c, const double q[3],
                        double w[3])
{
	double e1[3], e2[3], d[3];
	fct_v3_sub(e1, b, a);
	fct_v3_sub(e2, c, a);
	fct_v3_sub(d, q, a);
	double d11 = fct_v3_dot(e1, e1), d12 = fct_v3_dot(e1, e2), d22 = fct_v3_dot(e2, e2);
	double den = d11 * d22 - d12 * d12;
	if (den > 1e-12 * d11 * d22 && den > 0) {
		double p1 = fct_v3_dot(d, e1), p2 = fct_v3_dot(d, e2);
		double v = (d22 * p1 - d12 * p2) / den, u = (d11 * p2 - d12 * p1) / den;
		v = v < 0 ? 0 : v > 1 ? 1 : v;
		u = u < 0 ? 0 : u > 1 - v ? 1 - v : u;
		w[0] = 1 - v - u, w[1] = v, w[2] = u;
		return;
	}
	double da = fct_v3_dist2(q, a), db = fct_v3_dist2(q, b), dc = fct_v3_dist2(q, c);
	w[0] = da <= db && da <= dc;
	w[1] = !w[0] && db <= dc;
	w[2] = !w[0] && !w[1];
}

int fct_colbake_colour(const struct fct_colbake *B, const double x[3], double rgb[3])
{
	struct fct_bvh_hit hit;
	rgb[0] = rgb[1] = rgb[2] = 0;
	if (!fct_bvh_closest(&B->tree, x, INFINITY, &hit))
		return -1;
	const uint32_t *c = B->tri + 3 * (size_t)hit.id;
	double w[3];
	barycentric(B->xyz + 3 * (size_t)c[0], B->xyz + 3 * (size_t)c[1], B->xyz + 3 * (size_t)c[2], hit.q, w);
	for (int j = 0; j < 3; j++)
		for (int k = 0; k < 3; k++)
			rgb[j] += w[k] * B->rgb[3 * (size_t)c[k] + (size_t)j];
	return 0;
}

void fct_colbake_params_default(struct fct_colbake_params *p)
{
	memset(p, 0, sizeof *p);
	p->atlas_max = 4096;
}

double fct_colbake_texel(const struct fct_colbake *B, const struct fct_mesh *model,
                         const struct fct_colbake_params *p)
{
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (size_t i = 0; i < model->nv; i++)
		for (int k = 0; k < 3; k++) {
			double v = model->xyz[3 * i + (size_t)k];
			lo[k] = v < lo[k] ? v : lo[k];
			hi[k] = v > hi[k] ? v : hi[k];
		}
	double diag = model->nv ? sqrt(fct_v3_dist2(lo, hi)) : 0;
	double t = p->texel > 0 ? p->texel : 0.5 * B->mean_edge;
	/* Finer than a page's side across the model would only be shrunk
	 * again by the packing, after texelling all of it. */
	if (!(t >= diag / 16384))
		t = diag / 16384;
	return t;
}

static void colour_at(const void *ctx, size_t face, const double x[3], double rgb[3])
{
	(void)face;
	fct_colbake_colour(ctx, x, rgb);
}

struct fct_viewtex *fct_colbake_texture(const struct fct_colbake *B, const struct fct_mesh *model,
                                        const struct fct_colbake_params *p, struct fct_err *err)
{
	struct fct_viewtex_params vp;
	fct_viewtex_params_default(&vp);
	vp.atlas_max = p->atlas_max;
	vp.max_pages = 1;
	vp.level = 0;
	double texel = fct_colbake_texel(B, model, p);
	if (!(texel > 0) || !isfinite(texel)) {
		fct_fail(err, "bake: the model has no extent to texture");
		return NULL;
	}
	struct fct_viewtex *T = fct_viewtex_new(model, 0, &vp, err);
	if (!T)
		return NULL;
	if (fct_viewtex_layout_bake(T, 1 / texel, err) ||
	    fct_viewtex_bake(T, colour_at, B, p->nthreads, err) || fct_viewtex_finish(T, err)) {
		fct_viewtex_free(T);
		return NULL;
	}
	return T;
}
