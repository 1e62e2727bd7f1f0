/* fuse.c - one view fused into the volume (fct_fuse_view): its triangles,
 * its raster (fuseraster.c), its candidate voxels (fusecand.c), then their
 * true signed distance (fusetrue.c; by a noisy depth image's planes,
 * fuseplane.c) or projective depth difference (fuseproj.c) on the
 * threads.  Sun, Paik, Koschan and Abidi, sec. 3 (see
 * fuse.h); carving is carve.c, the curvature flow levelset.c. */
#include "fusion/fusepriv.h"

#include <stdlib.h>

#include "geom/adj.h"
#include "geom/geom.h"
#include "core/clock.h"
#include "core/par.h"

void fuse_geo_free(struct geo *G)
{
	free(G->tvown);
	free(G->tn);
	free(G->vfs);
	free(G->vf);
	if (G->own)
		fct_mesh_free(&G->tris);
	memset(G, 0, sizeof *G);
}

/* Unit normal and offset of each triangle (NaN: degenerate), and the count
 * of the proper ones. */
static void normals_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	struct geo *G = ctx;
	const double *xyz = G->xyz;
	const uint32_t *tv = G->tv;
	size_t proper = 0;
	for (size_t f = lo; f < hi; f++) {
		const uint32_t *v = &tv[3 * f];
		const double *a = &xyz[3 * v[0]], *b = &xyz[3 * v[1]], *c = &xyz[3 * v[2]];
		double n[3];
		fct_triangle_cross(n, a, b, c);
		double nn = fct_v3_dot(n, n), len = sqrt(nn);
		/* Most are far above the view's bound (degenerate_bound); the
		 * others take the exact test itself. */
		float u[3] = { NAN, NAN, NAN };
		if (len > 0 && isfinite(len) && (nn > G->nondegen || !fct_triangle_degenerate(a, b, c))) {
			for (int k = 0; k < 3; k++)
				u[k] = (float)(n[k] / len);
			proper++;
		}
		float *o = &G->tn[4 * f];
		o[0] = u[0], o[1] = u[1], o[2] = u[2];
		o[3] = (float)(u[0] * a[0] + u[1] * a[1] + u[2] * a[2]);   /* NaN with the normal */
	}
	atomic_fetch_add(&G->nproper, proper);
}

/* A bound for G's triangles: one whose corners are finite (as they are when
 * its cross product is) and whose cross product squared exceeds it is not
 * degenerate.  An edge's difference along an axis is at most the extent of
 * G's box there, so fct_degenerate_limit of the box's diagonal squared
 * bounds the triangle's limit (each rounding in the same expression is
 * monotone).  Not finite when the box is not: no triangle passes then. */
static double degenerate_bound(const struct geo *G)
{
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (size_t i = 0; i < G->nv; i++)
		box_add(lo, hi, &G->xyz[3 * i], &G->xyz[3 * i]);   /* NaN compares false: left out */
	double e[3];
	fct_v3_sub(e, hi, lo);
	return fct_degenerate_limit(fct_v3_dot(e, e));
}

int fuse_geo_normals(struct geo *G, int nthreads, struct fct_err *err)
{
	size_t nt = G->nt;
	if (nt > (size_t)UINT32_MAX / 3)
		return fct_fail(err, "%zu triangles: too many", nt);
	G->tn = fct_alloc_array(nt, 4 * sizeof *G->tn, err);
	if (!G->tn)
		return -1;
	G->nondegen = degenerate_bound(G);
	fct_par_run(nthreads, nt, 0, normals_chunk, G);
	return 0;
}

/* Triangles of m (polygons fan-triangulated); with topo, their unit
 * normals too (the faces around each vertex come from geo_rings). */
int fuse_geo_build(struct geo *G, const struct fct_mesh *m, int topo, int nthreads,
                     struct fct_err *err)
{
	memset(G, 0, sizeof *G);
	const struct fct_mesh *t = m;
	int alltri = 1;
	for (size_t f = 0; f < m->nf && alltri; f++)
		alltri = fct_face_size(m, f) == 3 && m->fstart[f] == 3 * f;
	if (!alltri) {
		/* Fan-triangulate polygons into a copy of the positions. */
		G->own = 1;
		fct_mesh_init(&G->tris);
		if (fct_mesh_set_vertex_count(&G->tris, m->nv, err))
			goto fail;
		if (m->nv)
			memcpy(G->tris.xyz, m->xyz, 3 * m->nv * sizeof *m->xyz);
		for (size_t f = 0; f < m->nf; f++) {
			const uint32_t *v = &m->fvert[m->fstart[f]];
			for (uint32_t k = 2; k < fct_face_size(m, f); k++) {
				uint32_t tri[3] = { v[0], v[k - 1], v[k] };
				if (fct_mesh_add_face(&G->tris, tri, 3, err) < 0)
					goto fail;
			}
		}
		t = &G->tris;
	}
	G->m = t;
	G->nt = t->nf, G->nv = t->nv;
	G->xyz = t->xyz;
	G->tv = t->fvert;
	if (!topo || !fuse_geo_normals(G, nthreads, err))
		return 0;
fail:
	fuse_geo_free(G);
	return -1;
}

/* The faces around each vertex, unless the grid has them. */
static int geo_rings(struct geo *G, const struct pixgrid *grid, struct fct_err *err)
{
	if (grid) {
		G->grid = grid;
		return 0;
	}
	return fct_vertex_faces(G->m, &G->vfs, &G->vf, err);
}

/* The statistics, and the fresh blocks that got nothing out of g again
 * (from index `from` on, where the view's blocks begin): g keeps the blocks
 * written, in the order of s. */
static int commit(struct fct_voxgrid *g, size_t from, const struct scratch *s,
                  struct fct_fuse_stats *st, struct fct_err *err)
{
	unsigned char *keep = fct_alloc_array(s->n ? s->n : 1, 1, err);
	if (!keep)
		return -1;
	size_t n = 0;
	for (size_t bi = 0; bi < s->n; bi++) {
		const struct sblock *b = s->blk[bi];
		st->border += b->nborder;
		st->voxels += b->nvox;
		if (b->fresh)
			keep[n++] = b->nvox > 0;
	}
	fct_voxgrid_drop(g, from, keep);
	free(keep);
	return 0;
}

int fct_fuse_view(struct fct_voxgrid *g, const struct fct_fuse_view *v,
                  const struct fct_fuse_params *p, struct fct_fuse_stats *stats,
                  struct fct_err *err)
{
	struct fct_fuse_stats dummy = { 0 };
	struct fct_fuse_stats *st = stats ? stats : &dummy;
	int nthreads = fct_par_threads(p->threads);
	double vox = fct_voxgrid_voxel(g), band = p->band;
	int proj = p->projective;
	/* A depth image to be fused by its planes needs its triangles'
	 * normals only where its grid is not found (the raster makes them
	 * then, for the search). */
	int by_planes = !proj && v->planes && v->cam.kind == FCT_CAMERA_PINHOLE;
	struct geo G;
	double t0 = fct_now();
	if (fuse_geo_build(&G, v->mesh, !proj && !by_planes, nthreads, err))
		return -1;
	double t1 = fct_now();
	st->triangles_s += t1 - t0;
	struct raster R;
	struct scratch s = { 0 };
	struct planes T = { 0 };
	size_t from = fct_voxgrid_count(g);
	int rc = -1;
	size_t max_samples = (size_t)1 << 26;
	int failed;
	if (!proj)
		failed = fuse_raster_true(&R, v, &G, max_samples, nthreads, err) ||
		         geo_rings(&G, R.grid.cell ? &R.grid : NULL, err);
	else if (v->depth)
		failed = fuse_raster_image(&R, v, err);
	else
		failed = fuse_raster_build(&R, v, &G, 1, 0, max_samples, nthreads, err);
	double t2 = fct_now();
	st->raster_s += t2 - t1;
	if (failed)
		goto done;
	if (R.w > 0) {
		const struct fct_fuse_view *img = proj && fuse_image_grid(v, &G) ? v : NULL;
		if (fuse_candidates(&s, g, &G, img, vox, band, proj, err))
			goto done;
		double t3 = fct_now();
		st->candidates_s += t3 - t2;
		struct fctx F = { &G, &R, v, p, &s, vox, band_kept(band, vox), NULL };
		void (*blocks)(void *, size_t, size_t, int) = proj ? fuse_projective_blocks : fuse_true_blocks;
		if (by_planes && R.grid.cell) {
			if (fuse_planes_build(&T, &R, v, p, vox, err))
				goto done;
			F.T = &T, blocks = fuse_plane_blocks;
			st->plane_views++;
		}
		fct_par_run(nthreads, s.n, 0, blocks, &F);
		if (commit(g, from, &s, st, err))
			goto done;
		st->distances_s += fct_now() - t3;
	}
	/* By planes every triangle of the grid counts, as projective
	 * fusion counts them; the search leaves degenerate ones out. */
	st->faces += proj ? v->mesh->nf : G.tn ? G.nproper : G.nt;
	rc = 0;
done:
	if (rc)   /* no half-made blocks left behind */
		fct_voxgrid_drop(g, from, NULL);
	fuse_planes_free(&T);
	fuse_scratch_free(&s);
	fuse_raster_free(&R);
	fuse_geo_free(&G);
	return rc;
}
