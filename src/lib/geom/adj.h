/* adj.h - edge and face adjacency of a polygon mesh, built on demand.
 *
 * An edge is an unordered pair of distinct vertices {a, b} that some face
 * walks between two consecutive corners (the last corner to the first
 * included).  Edges are numbered in the order of (min vertex, max vertex),
 * so the numbering depends only on the mesh, never on memory or hashing.
 *
 * Nothing here assumes a manifold: an edge may have one face (border), two
 * (manifold) or more (non-manifold); vertices may be used by no face
 * (isolated); faces may be repeated.  A face that repeats a vertex at two
 * consecutive corners, as (1 2 2), walks a zero-length "edge" (2, 2): that
 * corner is skipped and gives no edge (face_e holds FCT_ADJ_NONE there).  A
 * face that uses the same edge twice, as (1 2 1 3), is listed twice among
 * that edge's faces: the count of an edge is the number of times faces walk
 * it, which is what tells a border from a manifold edge.
 *
 * The build is linear in the number of corners plus vertices: two stable
 * counting sorts of the corners (by max vertex, then by min vertex). */
#ifndef FCT_ADJ_H
#define FCT_ADJ_H

#include <stddef.h>
#include <stdint.h>

#include "core/mesh.h"

/* No edge at this corner (a zero-length step between repeated vertices). */
#define FCT_ADJ_NONE UINT32_MAX

struct fct_adj {
	size_t nv, nf;      /* of the mesh it was built from */
	size_t ne;          /* unique undirected edges */

	/* Edge e joins vertices edge_v[2e] < edge_v[2e+1]; edges are sorted by
	 * that pair. */
	uint32_t *edge_v;

	/* Faces walking edge e: edge_f[edge_fstart[e] .. edge_fstart[e+1]), in
	 * increasing face index (a face walking it twice appears twice). */
	uint32_t *edge_fstart;   /* ne + 1 entries */
	uint32_t *edge_f;

	/* Edges of each face, parallel to the mesh's fvert: face_e[fstart[f] + k]
	 * is the edge from corner k to corner k+1 (mod the face size), or
	 * FCT_ADJ_NONE for a zero-length step. */
	uint32_t *face_e;

	/* Faces using vertex v: vert_f[vert_fstart[v] .. vert_fstart[v+1]), in
	 * increasing face index, each face once even when it repeats v. */
	uint32_t *vert_fstart;   /* nv + 1 entries */
	uint32_t *vert_f;

	size_t nborder;          /* edges walked once */
	size_t nmanifold;        /* edges walked twice */
	size_t nnonmanifold;     /* edges walked three or more times */
	size_t nskipped;         /* corners skipped as zero-length steps */
};

/* Build the adjacency of m into a (which is overwritten; free it with
 * fct_adj_free).  m's face indices must be below m->nv, as every reader
 * guarantees.  Returns 0, or -1 when out of memory (a is then empty). */
int fct_adj_build(struct fct_adj *a, const struct fct_mesh *m, struct fct_err *err);

/* Only the faces of each vertex, as fct_adj_build gives them in vert_fstart
 * and vert_f (each face once, in increasing index), for users that need no
 * edges; both arrays are the caller's to free.  0, or -1 when out of
 * memory (both NULL). */
int fct_vertex_faces(const struct fct_mesh *m, uint32_t **vert_fstart, uint32_t **vert_f,
                     struct fct_err *err);

/* The vertices within r of m's vertex s reached through faces (from s,
 * through vertices within r), s first, into list (room for m->nv); every
 * vertex looked at gets mark in stamp (m->nv entries), which none may hold
 * before.  vert_fstart, vert_f: as fct_vertex_faces gives them.  Returns
 * how many. */
size_t fct_vertices_within(const struct fct_mesh *m, const uint32_t *vert_fstart, const uint32_t *vert_f,
                           size_t s, double r, uint32_t *stamp, uint32_t mark, uint32_t *list);

/* Free what a owns and make it empty; a may be NULL. */
void fct_adj_free(struct fct_adj *a);

/* Number of faces walking edge e. */
static inline uint32_t fct_adj_edge_nfaces(const struct fct_adj *a, size_t e)
{
	return a->edge_fstart[e + 1] - a->edge_fstart[e];
}

/* Connected components of faces, two faces being connected when they share
 * an edge (sharing only a vertex does not connect them; a face with no edge,
 * as (3 3 3), is a component of its own).  label (a->nf entries, caller's)
 * gets each face's component; components are numbered 0, 1, ... in the
 * order of their smallest face index.  Returns the number of components,
 * or -1 when out of memory. */
long fct_adj_components(const struct fct_adj *a, uint32_t *label, struct fct_err *err);

/* Drop the pieces (connected components, as fct_adj_components) of m with
 * fewer than min_faces faces, and the vertices only they used: a fusion's
 * floating debris.  The faces and vertices kept stay in their order, with
 * all their properties; a vertex no face used stays, and so does the
 * largest piece (the first of them), however small: a mesh of one small
 * piece is an object, not debris.  Nothing is dropped when the small
 * pieces hold half the faces or more: they are the surface, not what lies
 * beside it (a mesh of scattered patches).  dropped (may be NULL)
 * gets the number of pieces dropped.  min_faces 0 or 1 drops nothing.
 * Returns the number of faces dropped, or -1 when out of memory. */
long fct_mesh_drop_small_pieces(struct fct_mesh *m, size_t min_faces, size_t *dropped,
                                struct fct_err *err);

/* Count the vertices at the position of an earlier vertex (bit-identical
 * x, y, z as doubles).  first (m->nv entries, may be NULL) gets, for each
 * vertex, the smallest index of a vertex at its position (itself when it
 * is the first).  Returns the count, or -1 when out of memory. */
long fct_mesh_duplicate_vertices(const struct fct_mesh *m, uint32_t *first, struct fct_err *err);

/* Merge vertices with bit-identical positions (x, y, z as doubles): the
 * first vertex of each position in index order is kept with its properties,
 * the others are dropped, faces renumbered (faces are kept as they are, even
 * if they become degenerate).  Used to join tiles.  Returns the number of
 * vertices removed, or -1 when out of memory. */
long fct_mesh_weld_exact(struct fct_mesh *m, struct fct_err *err);

/* fct_mesh_weld_exact, then the faces that repeat a vertex (or have fewer
 * than 3 corners) dropped, their count in *dropped: a triangle soup (every face its own corners, as an
 * STL file or an exporter that splits vertices writes) made one surface.
 * Returns the vertices removed, or -1 when out of memory. */
long fct_mesh_weld(struct fct_mesh *m, size_t *dropped, struct fct_err *err);

/* Number of vertices used by no face. */
size_t fct_adj_isolated_vertices(const struct fct_adj *a);

/* Face checks ------------------------------------------------------------- */

/* Count the degenerate faces of m: fewer than 3 corners, a vertex used
 * twice in the face (anywhere, not only at consecutive corners), or a vector
 * area (half the norm of the sum of the cross products of a fan from corner
 * 0, in doubles) of at most min_area.  flag (m->nf entries, may be NULL)
 * gets 1 for a degenerate face and 0 otherwise.  Returns the count, or -1
 * when out of memory. */
long fct_mesh_degenerate_faces(const struct fct_mesh *m, double min_area, unsigned char *flag,
                               struct fct_err *err);

/* Find faces with the same vertex set as an earlier face (order, orientation
 * and repetitions ignored: (1 2 3), (3 2 1) and (1 2 3 3) are the same).
 * first (m->nf entries, may be NULL) gets, for each face, the smallest index
 * of a face with its vertex set (itself when it is the first).  Returns the
 * number of faces that repeat an earlier one, or -1 when out of memory. */
long fct_mesh_duplicate_faces(const struct fct_mesh *m, uint32_t *first, struct fct_err *err);

#endif
