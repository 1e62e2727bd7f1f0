/* mcubes.h - marching cubes over a sparse voxel grid (voxgrid.h): the zero
 * level set of the signed distance as a closed, shared-vertex triangle mesh
 * (Lorensen and Cline 1987, with faces disambiguated by the asymptotic
 * decider of Nielson and Hamann 1991; the extraction step of Sun et al.
 * Sec. 3).
 *
 * Which cubes.  A cube is the 2x2x2 voxels with minimum corner (i, j, k);
 * it is extracted when all 8 corners are observed (weight > 0, weight >=
 * min_weight, sdf finite) and, with a clip box, when lo <= (i, j, k) < hi
 * componentwise.  Blocks need not be complete: corners are read across block
 * borders, and a missing block is unobserved space.
 *
 * The mesh.  One vertex per lattice edge whose two ends are observed and of
 * opposite sign (negative: sdf < 0; zero counts as positive), at the linear
 * zero crossing, kept at least 1/256 voxel from either end so that no two
 * vertices coincide; triangles are oriented counter-clockwise seen from the
 * positive side (normals point to free space).  On a face with two crossings
 * per sign (ambiguous), the bilinear interpolant decides which diagonal is
 * joined (the pair with the larger product of values; a tie joins the
 * positive diagonal); both cubes sharing the face compute this from the same
 * four values, so the surface is watertight, and each cube's contour loops
 * are triangulated as disks (a loop that crosses one face twice gets a
 * vertex at its centroid), so that every edge is in at most two triangles.
 * Where the observed region is closed around the surface the result is a
 * closed 2-manifold; it is open only where observation stops.  Vertices that
 * no triangle uses are not output.
 *
 * Properties.  Vertices get float nx ny nz: the normalised gradient of the
 * sdf (central differences at the two ends of the edge, one-sided beside
 * unobserved voxels, interpolated along it); with a colour grid, uchar red
 * green blue interpolated along the edge and rounded.  Output order is a
 * function of the grid's contents and block order only (byte-identical
 * across runs).
 *
 * Tiles.  Vertex positions are computed as ((double)i + t) * voxel from the
 * global index and the two corner values only, in a fixed order, so two grids
 * holding the same values on a lattice edge give bit-identical vertices.  To
 * fuse a large site as tiles: give tile T the clip box [lo_T, hi_T) (boxes
 * sharing faces), fuse each tile over at least [lo_T - 1, hi_T + 1] so that
 * the voxels the extraction reads (corners up to hi_T, gradients one voxel
 * beyond) hold the same values in both tiles, extract each with its box,
 * concatenate the meshes and merge vertices at identical positions with
 * fct_mesh_weld_exact (geom/adj.h).  The welded union has the untiled extraction's
 * triangles and vertices (in another order). */
#ifndef FCT_MCUBES_H
#define FCT_MCUBES_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "core/mesh.h"
#include "fusion/voxgrid.h"

#define FCT_MC_PHASES 6

/* Figures of one extraction (any pointer argument may be NULL). */
struct fct_mcubes_stats {
	size_t blocks;          /* blocks visited */
	size_t voxels;          /* blocks * 512 */
	size_t cubes;           /* cubes that produced triangles */
	size_t ambiguous;       /* cubes with an ambiguous face */
	size_t centres;         /* extra centroid vertices */
	size_t threads;         /* threads used */
	/* wall seconds of each phase: pass 0, pass 1, pass 2, the output's
	 * allocation, the vertex pass, the triangle pass (FCT_MC_PHASES) */
	double phase_s[FCT_MC_PHASES];
};

/* Extract the zero level set of g into out (overwritten with fct_mesh_init
 * first; the caller frees it).  clip_lo and clip_hi are both NULL (no clip)
 * or both 3 voxel indices, the box [lo, hi) of minimum corners.  Returns 0,
 * or -1 when out of memory or when the mesh would need more than 2^32 - 1
 * vertices (out is then empty). */
int fct_mcubes(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
               const int32_t *clip_lo, const int32_t *clip_hi, struct fct_err *err);
/* The same on `threads` threads (0: one per processor; the output is the
 * same bytes for any count), filling *stats (may be NULL) with the figures
 * of the run.  fct_mcubes is this with threads = 0. */
int fct_mcubes_stats(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                     const int32_t *clip_lo, const int32_t *clip_hi, int threads,
                     struct fct_mcubes_stats *stats, struct fct_err *err);

/* The same output as fct_mcubes, bit for bit, from the plain extraction in
 * mcubes.c (cube by cube, one thread, a lookup in the grid's hash per
 * voxel read, 6 KB per block): the reference the tests hold the fast path
 * to.  Returns 0 or -1 as fct_mcubes. */
int fct_mcubes_reference(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                         const int32_t *clip_lo, const int32_t *clip_hi, struct fct_err *err);


#endif
