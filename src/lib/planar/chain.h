/* chain.h - the boundaries of planar patches as chains, and their
 * simplification: Kang, Johnson and Szeliski, "Extraction of Concise and
 * Realistic 3-D Models from Real Data" (DEC CRL 95/7), section 3.
 *
 * Boundary.  Every face has a side label: its patch (>= 0) or -1
 * (unlabelled); the outside of the mesh is a side of its own
 * (FCT_CHAIN_OUTSIDE).  A boundary edge is a mesh edge whose two sides
 * differ: faces of two patches, or one face and the outside.  It becomes a
 * directed record a -> b with a left side L (the side whose faces walk the
 * edge a -> b, so L lies to the left seen from where its normal points) and
 * a right side R (whose faces walk b -> a, or the outside).  L is the
 * preferred of the two sides: the smaller patch label when both are patches,
 * a patch before -1, anything before the outside.  Records with no patch on
 * either side (-1 against the outside) are not boundaries of any patch and
 * are dropped, though they still make their vertices touch the outside.
 *
 * Non-manifold and badly wound edges.  For each side label on an edge, the
 * parity of the number of its faces walking the edge decides whether the
 * edge bounds it (odd) or is interior to it (even: two consistently or even
 * inconsistently wound faces of one patch), and the sign of the net walking
 * direction gives the direction.  The bounded sides walking a -> b are
 * paired with those walking b -> a in label order, one record per pair; the
 * rest face the outside.  So each patch sees every edge of its own boundary
 * exactly once, and when its faces are consistently wound its boundary
 * records form closed paths (equal in- and out-degree at every vertex).
 * Two patches whose faces both walk an edge the same way (a winding flip
 * between them) give two records on that edge, each against the outside.
 *
 * Chains.  A junction is a boundary vertex where three or more sides meet
 * (patch labels of its faces, plus the outside when it lies on a record
 * against the outside), or whose boundary records do not continue as one
 * path with the same two sides (not exactly one record in and one out: a
 * branching or pinched boundary).  The records are cut into chains from
 * junction to junction, each walked in its left side's direction; records
 * that meet no junction form closed loops.  A chain that starts and ends at
 * the same junction (a lasso) is closed too.
 *
 * Simplification.  Each chain is simplified once, so both patches keep the
 * identical boundary, by iterative end-point fit in 3-D (Duda and Hart): the
 * farthest point from the segment between the kept ends (distance to the
 * segment, not the line) is kept while that distance exceeds threshold times
 * the mean edge length of the mesh.  One pass then drops kept points the
 * bound does not need (the fit's first split of a U-shaped chain lands
 * anywhere on its far side, which then needs both corners as well).
 * Junctions are never removed.  A closed chain starts at its junction, or
 * for a loop at its point farthest from the loop's centroid (a corner, for a
 * polygon), is split at its point farthest from there, and keeps at least
 * three points.
 *
 * Crossings.  Then the simplified chains are checked with exact predicates
 * (predicates.h) in two kinds of 2-D map: each patch's plane (its plane
 * element's, or without one the area-weighted normal of its faces), with
 * the chains of that patch; and, when the vertices carry image coordinates
 * s t, the image (in pixels, s W and t H of the camera comment, snapped to
 * pixel centres within 1e-3 pixel as tripatch does, so both judge the same
 * points), with all the chains at once (a view's image is a planar
 * map of everything it saw, so there a narrow hole or unlabelled region may
 * not collapse either; a cylindrical panorama's wrapping s is checked patch
 * by patch, unwrapped).  In a map, two simplified segments may not cross,
 * touch or overlap except at a shared kept vertex, and no kept vertex may lie
 * strictly inside the sliver between a simplified segment and the original
 * points it replaces (it would change sides of that boundary: a hole leaving
 * its patch, say).  A segment in conflict is split at its farthest point (its
 * halves refitted to its chain's tolerance), and the check repeats until nothing is
 * in conflict.  Conflicts the input already has are not chased: when the
 * original edges of the two spans already conflict in that map (noise folds
 * a boundary over itself in a plane seen obliquely, or an occlusion boundary
 * has points on both surfaces), the pair is counted in conflicts_left and
 * left alone, and so is a sliver whose own original edges conflict.  A
 * median-split tree of the segments' and points' boxes finds the candidate
 * pairs in O(n log n) however unevenly the points lie, and after the first
 * round only pairs with a newly split chain are tested again.
 */
#ifndef FCT_CHAIN_H
#define FCT_CHAIN_H

#include <stddef.h>
#include <stdint.h>

#include "core/mesh.h"
#include "geom/adj.h"
#include "geom/planes.h"

/* The side label of the outside of the mesh. */
#define FCT_CHAIN_OUTSIDE (-2)

struct fct_chains {
	size_t n;               /* chains, open and closed */
	size_t *start;          /* n + 1: chain c is points start[c] .. start[c+1] */
	uint32_t *vert;         /* mesh vertex of each point; a closed chain repeats
	                           its first point at its end */
	unsigned char *keep;    /* 1 where the simplification keeps the point (all 1
	                           after extraction) */
	int32_t *left, *right;  /* the sides: left >= 0; right a patch, -1 or
	                           FCT_CHAIN_OUTSIDE */
	unsigned char *closed;  /* 0 open; 1 closed at a junction (a lasso); 2 a
	                           loop without junction */
	unsigned char *frozen;  /* NULL, or 1 for the chains whose keep the caller
	                           has set (malloc'd; fct_chains_free frees it):
	                           simplification leaves them as they are */

	double mean_edge;       /* mean length of the mesh's edges */
	size_t boundary_edges;  /* records in the chains */
	size_t boundary_vertices;
	size_t junctions;
	size_t loops;           /* closed chains without a junction */
	size_t nonmanifold_edges;  /* boundary edges walked by three or more faces */
};

/* Find the boundary of the labelled faces of m (patch: m->nf labels, >= 0 or
 * -1) and cut it into chains, as described above, in c (initialised here;
 * free with fct_chains_free).  Chains come in a fixed order: those from a
 * junction in the order of their first record (records are ordered by their
 * edge's (lower vertex, higher vertex)), then the loops likewise.  -1 when out
 * of memory. */
int fct_chains_extract(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                       struct fct_err *err);
/* The same with m's adjacency (fct_adj_build of m) from the caller, who
 * may extract the chains of several labellings of one mesh with it. */
int fct_chains_extract_adj(struct fct_chains *c, const struct fct_mesh *m, const struct fct_adj *a,
                           const int32_t *patch, struct fct_err *err);
/* dst (initialised here) a copy of src, frozen included; -1 when out of
 * memory (dst then empty). */
int fct_chains_copy(struct fct_chains *dst, const struct fct_chains *src, struct fct_err *err);

/* Free what c owns and make it empty; c may be NULL. */
void fct_chains_free(struct fct_chains *c);

struct fct_chain_params {
	double threshold;      /* in mean edge lengths (default 3) */
	int keep_topology;     /* 1 (default): prevent crossings; 0: plain end-point fit */
	int keep_small_loops;  /* 0 (default): a loop without junction that lies within
	                          the tolerance of its centroid is dropped, filling the
	                          hole or absorbing the island it bounds */
	const double *scale;   /* NULL (default), or a length for each vertex (its
	                          sample spacing, say): a chain's tolerance is then
	                          scale_factor times its points' mean scale, instead
	                          of threshold mean edges of the whole mesh */
	double scale_factor;
	const double *tolerance;  /* NULL (default), or a tolerance for each chain of
	                             c (a length; 0 keeps the one above): a crease
	                             chain that will be moved onto its planes' line
	                             anyway, say */
	const unsigned char *keep_vertex;  /* NULL (default), or a flag for each vertex
	                                      of m: the points of a chain on a flagged
	                                      vertex are always kept, anchors of the
	                                      end-point fit (a stretch of outline that
	                                      must stay as sampled) */
	int count_left;        /* 1 (default): count conflicts_left and
	                          conflicts_left_image (one more pass of the
	                          checks); 0: leave them 0 */
	struct fct_chain_cache *cache;  /* NULL (default), or the crossings of the
	                                   last simplification with this cache,
	                                   replaced by this one's (see below) */
};

void fct_chain_params_default(struct fct_chain_params *p);

/* The crossing checks first find the crossings the input already has: the
 * original edges of each patch's chains that cross, in its plane and in
 * the image.  Those are a function of the chains' points alone, and the
 * rounds of the planar model simplify the same outlines again and again
 * with a few stretches changed (planedecim on the 7-Scenes frame 000250:
 * a third of each round's crossing checks went to finding them anew).  A cache (zeroed before its first use) keeps them
 * from one simplification to the next, for the checks whose chains,
 * vertices and points are bit for bit the same. */
struct fct_cached_check;
struct fct_chain_cache {
	struct fct_cached_check *check;
	size_t n;
};

/* Free what cache holds and make it empty; cache may be NULL. */
void fct_chain_cache_free(struct fct_chain_cache *cache);

struct fct_chain_stats {
	double tolerance;          /* threshold * mean edge length */
	double max_dev;            /* largest distance of a chain point from the
	                              simplified segment that replaces it */
	size_t kept_vertices;      /* distinct vertices kept */
	size_t segments;           /* simplified segments (edges written) */
	size_t loop_points;        /* points kept only so a closed chain has three */
	size_t conflicts_plain;    /* conflicts in the plain end-point fit: crossing or
	                              overlapping segment pairs and kept vertices
	                              inside slivers, summed over the patches */
	size_t topology_points;    /* points kept beyond the threshold to remove them */
	size_t conflicts_left;     /* conflicts no split can remove (between original
	                              mesh edges), in the patch planes */
	size_t conflicts_left_image;  /* the same in image coordinates (s t) */
	size_t rounds;             /* check-and-split rounds */
	size_t cached_checks;      /* checks whose input crossings came from the cache */
	size_t loops_dropped;      /* loops below the tolerance, dropped */
};

/* Simplify the chains of c (extracted from m and patch) in place, setting
 * c->keep, with p's threshold; planes[0..nplanes) give the patch planes used
 * for the crossing checks (a patch without one uses the area-weighted normal
 * of its faces).  st (may be NULL) gets the figures.  -1 when out of memory. */
int fct_chains_simplify(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                        const struct fct_plane *planes, size_t nplanes,
                        const struct fct_chain_params *p, struct fct_chain_stats *st,
                        struct fct_err *err);

/* The whole stage on a labelled mesh, in place: m keeps only the kept
 * boundary vertices (in their original order, with all their properties),
 * loses its faces, and gets an element edge (int vertex1 vertex2 patch1
 * patch2, one row per simplified segment, vertex1 -> vertex2 in patch1's
 * direction, patch2 -1 for unlabelled faces or the outside) in chain order;
 * the plane element, other elements and comments are kept.  Fails (message
 * set) on faces without a patch property or labels outside the plane
 * element.  A mesh with the patch property but no faces gives an empty
 * wireframe.  ch (may be NULL) receives the simplified chains (the caller
 * frees them with fct_chains_free; their vertices are the input's). */
int fct_simpchain(struct fct_mesh *m, const struct fct_chain_params *p,
                  struct fct_chains *ch, struct fct_chain_stats *st, struct fct_err *err);

/* Do closed segments ab and cd (2-D, exact predicates) meet anywhere other
 * than at a vertex they share?  va, vb, vc, vd are the vertices' identities:
 * a shared vertex (same identity) is a legal meeting point unless the two
 * segments overlap along a stretch there; segments sharing both vertices
 * always conflict.  Equal coordinates under different identities do not
 * count as shared. */
int fct_segments_conflict(const double a[2], const double b[2], const double c[2],
                          const double d[2], uint32_t va, uint32_t vb, uint32_t vc, uint32_t vd);

#endif
