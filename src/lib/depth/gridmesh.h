/* gridmesh.h - triangle meshes from organised range data.
 *
 * Kang et al. sec. 2: the pixels of a dense depth map are connected by a
 * planar triangulation of their image coordinates; Sun et al. mesh each range
 * image the same way.  Here the pixels (or range-grid cells) form a regular
 * grid and each grid square becomes at most two triangles:
 *
 * - a cell without data leaves a hole (a square with three valid corners
 *   still gets the one triangle on them);
 * - no triangle is made across a depth discontinuity: an edge between cells
 *   a and b, L grid steps apart, is cut when
 *       |depth_a - depth_b| > max_jump * L * footprint * min(depth_a, depth_b)
 *                             + noise_jump * sqrt(2) * max(sigma_a, sigma_b),
 *   footprint * depth being the lateral size of one grid step at that depth,
 *   so max_jump is the largest depth change per lateral step that still
 *   counts as one surface (tan of the grazing angle), and the last term the
 *   change the sensor's noise alone makes of one surface: noise_jump
 *   deviations of the difference of two samples of deviation sigma (none
 *   without per-cell sigma);
 * - of the two diagonals of a square, the one along which the surface bends
 *   less is chosen: for each diagonal, the distance of its end cells from the
 *   3-D lines through their neighbours along it (zero on any plane and along
 *   a crease that follows the diagonal); where those neighbours lack data,
 *   the shorter 3-D diagonal;
 * - connected pieces with fewer than min_faces triangles (specks of flying
 *   pixels) are dropped.
 *
 * Triangles are ordered so that their normals face the sensor for the
 * camera models of camera.h (u right, v down). */
#ifndef FCT_GRIDMESH_H
#define FCT_GRIDMESH_H

#include <math.h>
#include <stdint.h>

#include "core/mesh.h"

/* Cell positions are given either explicitly (xyz) or, for a camera whose
 * rays factor into a column part and a row part as both camera models of
 * camera.h do, as depth * (col[3i], row[j], col[3i+2]) -- which saves
 * storing a position per pixel of a large depth map. */
/* The depth-jump test that both the grid mesher and the sparse mesher apply:
 * depths da and db, `steps` pixels (or grid steps) apart laterally, are one
 * surface when |da - db| <= limit * steps * min(da, db) + allow, limit being
 * max_jump times the footprint of one step per unit depth and allow what
 * noise may add. */
static inline int fct_depth_joined(double da, double db, double limit, double steps, double allow)
{
	return fabs(da - db) <= limit * steps * (da < db ? da : db) + allow;
}

struct fct_range_grid {
	int width, height;       /* cells per row, rows */
	const double *xyz;       /* 3 per cell, row by row; or NULL: */
	const double *col;       /* 3 per column: ray x, unused, ray z */
	const double *row;       /* 1 per row: ray y */
	const double *depth;     /* per cell, along the sensor's ray; not > 0: no data */
	double footprint;        /* lateral size of one grid step per unit depth */
	int wrap;                /* the last column borders the first (360-degree cylinder) */
	const float *sigma;      /* per cell, the deviation of its depth; or NULL */
	double noise_jump;       /* deviations of noise allowed in a jump */
};

struct fct_grid_params {
	double max_jump;         /* see above; infinity disables the test */
	size_t min_faces;        /* smaller connected pieces are dropped (0, 1: keep all) */
};

/* What fct_grid_mesh left out, for reports. */
struct fct_grid_stats {
	size_t jump_faces;       /* triangles not made across a discontinuity */
	size_t speck_faces;      /* triangles dropped with their small pieces */
};

/* Triangulate g into m (which should be empty): the vertices are the cells
 * used by a triangle, in row-major order, and when cell_of is not NULL it gets
 * a malloc'd array mapping each vertex to its cell index.  stats may be NULL.
 * 0 or -1. */
int fct_grid_mesh(struct fct_mesh *m, const struct fct_range_grid *g,
                  const struct fct_grid_params *p, uint32_t **cell_of,
                  struct fct_grid_stats *stats, struct fct_err *err);

#endif
