/* colbake.h - a texture atlas baked from a dense mesh's vertex colours, for
 * a model made from that mesh (planarize's planar model of a coloured
 * scan): each texel of the model takes the colour of the point of the dense
 * mesh nearest to it, interpolated between that triangle's vertex colours
 * (barycentric), so the model, a few thousand faces, shows what the dense
 * mesh's hundred thousand coloured vertices drew, where its own decimated
 * vertex colours blur it.  The atlas is viewtex's (viewtex.h, baking):
 * charts on the planar patches in their planes' frames, the rest projected
 * along the nearest axis, packed on shelves into power-of-two pages,
 * padded; the nearest points come from the BVH (bvh.h).
 *
 * The texel is half the dense mesh's mean edge (by default): two texels a
 * vertex spacing resolve what the vertices drew without adding texels
 * that only interpolate.  The pages are at most one of atlas_max squared
 * texels (the texel grows until the model fits).  The same inputs give the
 * same pages, bit for bit, on any number of threads. */
#ifndef FCT_COLBAKE_H
#define FCT_COLBAKE_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "core/mesh.h"
#include "geom/bvh.h"
#include "render/viewtex.h"

/* The dense coloured surface: its triangles in a BVH, their corners'
 * colours. */
struct fct_colbake {
	struct fct_bvh tree;
	double *xyz;             /* the vertices, 3 each */
	uint32_t *tri;           /* 3 vertex indices per triangle (the tree's ids) */
	uint8_t *rgb;            /* 3 per vertex */
	size_t nv, ntri;
	double mean_edge;        /* of the triangles' edges, metres */
};

/* Does m carry vertex colours (red green blue) and faces, and no texture
 * (TextureFile) already? */
int fct_colbake_applies(const struct fct_mesh *m);

/* The colour source of dense (copied: dense may change afterwards): 0, or
 * -1 (out of memory; a mesh without vertex colours).  Faces with a
 * non-finite vertex are left out.  Free with fct_colbake_free (B may be
 * zeroed, or NULL). */
int fct_colbake_init(struct fct_colbake *B, const struct fct_mesh *dense, struct fct_err *err);
void fct_colbake_free(struct fct_colbake *B);

/* The colour of the dense surface's point nearest to x (barycentric between
 * its triangle's vertex colours) into rgb (0-255); 0, or -1 when the source
 * has no triangle (rgb then 0). */
int fct_colbake_colour(const struct fct_colbake *B, const double x[3], double rgb[3]);

struct fct_colbake_params {
	double texel;            /* metres; 0: half the dense mesh's mean edge (default) */
	int atlas_max;           /* page side at most, a power of two in [64, 16384] (default 4096) */
	int nthreads;            /* 0: one per processor (default) */
};

void fct_colbake_params_default(struct fct_colbake_params *p);

/* The texel a bake of the model uses with p (before the atlas shrinks it to
 * fit a page): p->texel, or half the source's mean edge; never finer than
 * a 16384th of the model's bounding box diagonal. */
double fct_colbake_texel(const struct fct_colbake *B, const struct fct_mesh *model,
                         const struct fct_colbake_params *p);

/* Bake model's texture from B: a texturer of model (viewtex.h) with its
 * pages filled and padded, ready for fct_viewtex_page and
 * fct_viewtex_apply (model must outlive it unchanged until then); NULL on
 * error (a model without faces, a non-finite vertex, bad parameters, out
 * of memory). */
struct fct_viewtex *fct_colbake_texture(const struct fct_colbake *B, const struct fct_mesh *model,
                                        const struct fct_colbake_params *p, struct fct_err *err);

#endif
