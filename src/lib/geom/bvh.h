/* bvh.h - a bounding volume hierarchy over triangles for exact closest-point
 * queries: the spatial search under meshdist and anyone else who needs the
 * distance from points to a surface.
 *
 * The tree is built once with binned SAH splits (surface area heuristic,
 * 16 bins on the widest axis of the centroids; object-median splits below
 * depth 40 so the depth stays bounded on any input) into a flat node array,
 * with the triangles copied in tree order in double precision.  The same
 * input gives the same tree.  Node boxes are float, rounded outward, so they
 * never exclude a point they should hold.  A query walks the tree nearest
 * child first and skips every box farther than the best distance found so
 * far; the triangle distance itself is exact in double (geom.h).
 *
 * The same tree answers ray casts (fct_bvh_raycast): nearest hit first,
 * with a watertight ray-triangle test, so renderers and scene synthesis
 * share the tree with the distance queries. */
#ifndef FCT_BVH_H
#define FCT_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "core/mesh.h"

/* A node: a box and either two children (count == 0: children first and
 * first + 1, stored side by side so one cache line holds both boxes) or a
 * leaf (count > 0: triangles first .. first + count). */
struct fct_bvh_node {
	float lo[3], hi[3];
	uint32_t first;
	uint32_t count;
};

/* A triangle in tree order: its corners, whether it has no usable area
 * (then it is searched as its three edges) and the caller's id for it. */
struct fct_bvh_tri {
	double a[3], b[3], c[3];
	uint32_t id;
	uint32_t degenerate;
};

struct fct_bvh {
	struct fct_bvh_node *nodes;   /* node 0 is the root (none when ntri == 0) */
	size_t nnodes;
	struct fct_bvh_tri *tris;
	size_t ntri;
	int depth;                    /* levels below the root, for reports */
};

/* The answer to a query: the closest point, its squared distance and the id
 * of the triangle it lies on (ties go to the triangle met first). */
struct fct_bvh_hit {
	double q[3];
	double d2;
	uint32_t id;
};

/* Build over ntri triangles tri[3k..3k+2] indexing the points xyz (3 doubles
 * each; the indices must be < the number of points).  Triangle k gets id k.
 * b is initialised here; free it with fct_bvh_free.  Fails (out of memory,
 * more than 2^31 triangles, a corner with a NaN or infinite coordinate:
 * "vertex N: coordinate is not finite") with -1 and a message. */
int fct_bvh_build(struct fct_bvh *b, const double *xyz, const uint32_t *tri, size_t ntri,
                  struct fct_err *err);

/* Fan the faces of m into triangles: face f of k >= 3 vertices gives
 * (v0, vi, vi+1) for i = 1 .. k-2; a face of one or two vertices gives the
 * degenerate triangle (v0, vk-1, vk-1), a point or a segment; empty faces
 * give nothing.  *tri gets 3 indices per triangle and *face the face of each
 * (both malloc'd, free them; non-NULL even when *ntri is 0). */
int fct_mesh_fan(const struct fct_mesh *m, uint32_t **tri, uint32_t **face, size_t *ntri,
                 struct fct_err *err);

/* Build over the faces of m, each fanned from its first vertex into
 * triangles (v0, vi, vi+1) that carry the face's index as id.  A face of one
 * or two vertices counts as a point or a segment; faces with no vertices are
 * skipped.  Fanning is exact for convex faces; a concave face is covered by
 * its fan, which may reach outside it. */
int fct_bvh_build_mesh(struct fct_bvh *b, const struct fct_mesh *m, struct fct_err *err);

/* Free what b owns and make it empty; b may be NULL. */
void fct_bvh_free(struct fct_bvh *b);

/* Find the closest point of the triangles to p among those closer than
 * sqrt(max_d2).  Returns 1 and fills hit, or 0 when there is none (no
 * triangles, or all too far).  With max_d2 = INFINITY, a tree with
 * triangles always answers (hit->d2 is infinite when it overflows). */
int fct_bvh_closest(const struct fct_bvh *b, const double p[3], double max_d2,
                    struct fct_bvh_hit *hit);

/* The same by testing every triangle: the reference the tests compare with. */
int fct_bvh_closest_brute(const struct fct_bvh *b, const double p[3], double max_d2,
                          struct fct_bvh_hit *hit);

/* The answer to a ray cast: the ray parameter t of the hit (the point is
 * org + t dir), its barycentric coordinates on the tree triangle (the point
 * is (1 - u - v) a + u b + v c), the triangle's id and its index in
 * b->tris (for its corners). */
struct fct_bvh_ray_hit {
	double t, u, v;
	uint32_t id;
	uint32_t tri;
};

/* The first hit of the ray org + t dir, tmin <= t <= tmax, with any
 * triangle, from either side (0 and INFINITY: in front of org; a negative
 * range looks behind it).  Returns 1 and fills hit, or 0 when there is none
 * (no triangles, an org or dir not finite, a dir of zero, nothing in
 * range).
 *
 * The triangle test is the watertight one of Woop, Benthin and Wald
 * ("Watertight Ray/Triangle Intersection", JCGT 2(1), 2013) in double: the
 * corners are moved into a frame where the ray is the z axis and the three
 * edge functions are evaluated so that an edge shared by two triangles
 * (the same corner coordinates) gives exactly opposite values in both, so a
 * ray through a shared edge or vertex never slips between them.  A triangle
 * seen edge-on (zero area along the ray) or degenerate is never hit.  Box
 * tests use Ize's conservative slab bound ("Robust BVH Ray Traversal",
 * JCGT 2(2), 2013), so no box is skipped that holds a hit.
 *
 * Equal t goes to the lower id, then the lower tree index: the answer is
 * the brute-force one exactly, whatever the traversal order. */
int fct_bvh_raycast(const struct fct_bvh *b, const double org[3], const double dir[3],
                    double tmin, double tmax, struct fct_bvh_ray_hit *hit);

/* The same by testing every triangle: the reference the tests compare with. */
int fct_bvh_raycast_brute(const struct fct_bvh *b, const double org[3], const double dir[3],
                          double tmin, double tmax, struct fct_bvh_ray_hit *hit);

#endif
