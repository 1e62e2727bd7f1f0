/* planes.h - the planar patches of DESIGN.md as they travel on the pipes:
 * the face property `int patch` (the plane a face belongs to, -1 none) and
 * the element `plane` (nx ny nz d: unit normal, n.p + d = 0; int count: the
 * points fitted; rms: the fit residual), the i-th plane being patch i.
 *
 * Every stage of the planar pipeline reads and writes them through these
 * functions, so the on-disk types (double planes, int patch) are fixed in
 * one place; a file whose plane element uses float or another integer type
 * is read all the same.  And the fits behind them: a plane to a scatter of
 * points, the eigenvalues of a symmetric 3x3. */
#ifndef FCT_PLANES_H
#define FCT_PLANES_H

#include <stdint.h>

#include "core/mesh.h"

struct fct_plane {
	double n[3], d;          /* unit normal and offset: n.p + d = 0 */
	long count;              /* points (or faces) the fit used */
	double rms;              /* residual of the fit */
};

/* The plane element of m as a malloc'd array (*planes NULL and *n 0 when m
 * has none).  Fails on a plane element without nx ny nz d, or whose normal
 * is not finite and of unit length (to 1e-6). */
int fct_planes_get(const struct fct_mesh *m, struct fct_plane **planes, size_t *n,
                   struct fct_err *err);
/* Replace m's plane element by planes[0..n). */
int fct_planes_set(struct fct_mesh *m, const struct fct_plane *planes, size_t n,
                   struct fct_err *err);

/* The face property patch as a malloc'd array of m->nf labels (NULL when m
 * has none: *present = 0).  Labels must be -1 or in [0, nplanes) when
 * nplanes >= 0 (pass -1 to skip that check). */
int fct_patches_get(const struct fct_mesh *m, int32_t **patch, int *present, long nplanes,
                    struct fct_err *err);
/* Set the face property patch (int) from patch[0..m->nf). */
int fct_patches_set(struct fct_mesh *m, const int32_t *patch, struct fct_err *err);

/* One edge of the wireframe element `edge` (simpchain's output, DESIGN.md):
 * v1 -> v2 runs with patch p1 on its left, seen from the side its plane
 * normal points to; p2 is on the other side; -1 is no patch. */
struct fct_wire {
	uint32_t v1, v2;
	int32_t p1, p2;
};

/* The edge element of m as a malloc'd array (*present = 0, *wires NULL when
 * m has none).  Fails on an edge element without scalar vertex1 vertex2
 * patch1 patch2, a vertex out of range, equal ends, a patch that is neither
 * -1 nor in [0, nplanes) (nplanes < 0: any non-negative int), or an edge
 * with no patch on either side. */
int fct_wires_get(const struct fct_mesh *m, long nplanes, struct fct_wire **wires, size_t *n,
                  int *present, struct fct_err *err);

/* Replace m's edge element by wires[0..n) (int vertex1 vertex2 patch1
 * patch2). */
int fct_wires_set(struct fct_mesh *m, const struct fct_wire *wires, size_t n, struct fct_err *err);

/* An orthonormal frame (e1, e2) of the plane with unit normal n, with
 * e1 x e2 = n; the same frame for the same n everywhere. */
void fct_plane_frame(const double n[3], double e1[3], double e2[3]);

/* Signed distance of p from the plane. */
static inline double fct_plane_distance(const struct fct_plane *pl, const double p[3])
{
	return pl->n[0] * p[0] + pl->n[1] * p[1] + pl->n[2] * p[2] + pl->d;
}

/* Fits ---------------------------------------------------------------- */

/* The plane fitted to the scatter of weighted points: centroid c, central
 * scatter s = {sxx, syy, szz, sxy, syz, sxz}.  Writes the
 * unit normal (eigenvector of the smallest eigenvalue, by Jacobi rotations)
 * and d = -n.c into pl, and returns the smallest eigenvalue.  pl->count and
 * pl->rms are left alone.  A scatter of rank < 2 gives a normal all the
 * same (some unit vector orthogonal to its spread). */
double fct_plane_fit(struct fct_plane *pl, const double c[3], const double s[6]);

/* The smallest eigenvalue of the symmetric positive semi-definite 3x3
 * matrix s = {sxx, syy, szz, sxy, syz, sxz}, 0 for a singular one: a root of
 * the characteristic polynomial, so its absolute error is of the order of
 * 1e-16 l1^2 / l2 (l1 >= l2 the other two eigenvalues); Jacobi rotations
 * when the eigenvalues are nearly equal. */
double fct_sym3_min_eigenvalue(const double s[6]);

/* Cyclic Jacobi rotations on the symmetric a, which they destroy: v gets
 * the eigenvectors as columns, ev the eigenvalues: every eigenvector, where
 * areaflow.h's fct_sym3_eigen (closed form, trigonometric) gives the
 * largest eigenvalue's only; a plane wants the smallest's. */
void fct_sym3_jacobi(double v[3][3], double ev[3], double a[3][3]);

#endif
