/* polytri.h - triangulation of a plane polygon with holes: the greedy
 * shortest-diagonal triangulation of Kang, Johnson and Szeliski, "Extraction
 * of Concise and Realistic 3-D Models from Real Data" (DEC CRL 95/7),
 * section 4, and the constrained Delaunay triangulation.
 *
 * The region is given as closed loops over points in the plane, each with the
 * region on its left: outer boundaries counter-clockwise and holes clockwise
 * (x right, y up).  Loops may share vertices (a hole touching the outer
 * boundary at one vertex, two lobes meeting at one vertex) but must not
 * cross, overlap along an edge, or pass through another vertex.
 *
 * Both methods start from the same structure: the Delaunay triangulation of
 * the points (delaunay.h), the loop edges inserted as constraints by
 * walking along each edge and retriangulating the triangles it crosses as
 * two Delaunay pseudo-polygons (Anglada 1997; Shewchuk's lecture notes), so
 * the result is the constrained Delaunay triangulation (CDT); triangles are
 * then marked inside by a flood from the left side of each loop edge that
 * crosses no constrained edge.  Every decision uses the exact predicates of
 * predicates.h.
 *
 * The greedy method (the paper's pseudo-code) adds, among all valid
 * diagonals (inside the region, crossing no loop edge and no diagonal
 * already taken, through no vertex), always the shortest, until the region
 * is triangulated.  It is computed exactly without listing the O(n^2)
 * candidate segments:
 *  - the segments taken so far are held as constraints in the triangulation
 *    above, so a candidate is valid exactly when a walk along it from one
 *    end reaches the other end through inside triangles crossing only
 *    unconstrained edges; an accepted segment is inserted like a loop edge;
 *  - candidates are produced lazily in increasing length: each vertex v has
 *    a radius r_v up to which its pairs have been produced, doubled at each
 *    expansion; a pair is produced by whichever end reaches it first.  A
 *    pair of length L is taken from the candidate heap only when
 *    L <= min r_v, so no shorter pair can still be missing, and the order
 *    is the global (length, lower index, higher index) order of the
 *    paper's sorted list;
 *  - an expansion of v produces only segments that can still be valid: the
 *    unconstrained edges at v, and vertices seen through the wedges of the
 *    inside triangles at v whose far edge is unconstrained, each wedge
 *    followed as a funnel through at most 16 triangles (a vertex inside the
 *    funnel is a candidate and splits it; a constrained or distant window
 *    closes it), the wedges still open then searched by angle in a k-d
 *    tree.  Constraints only accumulate, so nothing skipped could have
 *    become valid later: the result equals the brute-force greedy (tested
 *    edge for edge);
 *  - a vertex stops expanding once every inside triangle around it has three
 *    constrained edges; the run stops when no unconstrained inside edge is
 *    left.
 * Memory is O(n) plus the pending candidates.  On long boundaries (100000
 * vertices: zig-zag strips, a two-vertex side facing a zig-zag, random
 * star-shaped polygons, a circle) it produces 1 to 3 candidates per vertex
 * and runs in about 0.5 to 3 s, against 0.1 to 0.4 s for the CDT alone.
 * Shapes where many vertices are near one another yet hidden far behind
 * constraints can need more candidates; a budget of 64 n + 65536
 * candidates and 256 n + 2^20 walk steps bounds the work, after which the
 * edges the constrained triangulation still holds are taken (they cross
 * nothing, so this completes a valid triangulation) and budget_hits counts
 * the event.  The result is then not exactly the greedy one, but the
 * work stays O(n) candidates and walk steps (times a heap's log n).
 *
 * Each triangle comes out counter-clockwise (fct_orient2d > 0).  For n loop
 * vertices (counted once per loop they are on) and h holes, a simple
 * polygon with holes gets n + 2h - 2 triangles. */
#ifndef FCT_POLYTRI_H
#define FCT_POLYTRI_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"

enum fct_polytri_method {
	FCT_POLYTRI_GREEDY = 0,   /* the paper's shortest-diagonal greedy method */
	FCT_POLYTRI_CDT = 1       /* constrained Delaunay */
};

/* What a call did; every field is added to, so one struct can sum calls. */
struct fct_polytri_stats {
	size_t candidates;    /* greedy: candidate pairs produced */
	size_t walks;         /* segments walked (constraints and candidates) */
	size_t walk_steps;    /* triangles crossed by those walks */
	size_t flips;         /* triangles replaced by segment insertion */
	size_t budget_hits;   /* greedy runs completed from the CDT on budget */
	size_t forced_ears;   /* earclip: ears cut without a valid ear */
};

/* Triangulate the region bounded by nloops loops over the points xy (point
 * i at xy[2i], xy[2i+1], i < np): loop k is lvert[lstart[k] .. lstart[k+1]),
 * lstart having nloops + 1 entries, each loop at least three vertices.
 *
 * Returns 0 with *tri a malloc'd array of 3 * *ntri point indices (free()),
 * each triangle counter-clockwise; 1 when the loops do not bound a region as
 * described in the header comment (no loops, a loop of fewer than three
 * vertices, two loop edges crossing or overlapping, a loop edge through a
 * vertex, two used points at the same place, all points on a line, a loop
 * of the wrong orientation or nesting, a loop vertex repeated in a row, a
 * coordinate that is not finite), with the reason in err and *tri NULL; -1
 * on an index out of range, lstart not starting at 0 or decreasing, or out
 * of memory.  st may be NULL. */
int fct_polytri(uint32_t **tri, size_t *ntri, const double *xy, size_t np,
                const uint32_t *lstart, size_t nloops, const uint32_t *lvert,
                enum fct_polytri_method method, struct fct_polytri_stats *st, struct fct_err *err);

/* The repair of last resort for loops fct_polytri refuses: loops of positive
 * signed area are outer boundaries, the others holes, each given to the
 * smallest outer loop that contains its first vertex (the largest outer
 * loop when none does); each hole is joined to its outer loop by a bridge
 * from its rightmost vertex to the nearest vertex of the outer sequence, and
 * the resulting sequence is cut into ears, a convex corner whose triangle
 * holds no other vertex when there is one (checked for sequences up to 4096
 * corners), otherwise the most convex corner (counted in st->forced_ears).
 * The triangles keep the loops' winding and topology (n + 2h - 2 per outer
 * loop) but may overlap in the plane when the loops cross.  Time O(n^2) per
 * outer loop up to 4096 corners and about O(n) per pass beyond.  Returns 0,
 * or -1 (bad index, out of memory; err set); 1 when there is no loop of
 * positive area. */
int fct_polytri_earclip(uint32_t **tri, size_t *ntri, const double *xy, size_t np,
                        const uint32_t *lstart, size_t nloops, const uint32_t *lvert,
                        struct fct_polytri_stats *st, struct fct_err *err);

/* Which outer loop each loop belongs to: owner[l] = l for a loop of
 * positive signed area (an outer boundary); for the others (holes), the
 * outer loop of smallest area that contains the hole's first vertex (even-odd
 * rule), or the outer loop of largest area when none does, or -1 when there
 * is no outer loop at all (then the call returns 1). */
int fct_polytri_nest(long *owner, const double *xy, const uint32_t *lstart, size_t nloops,
                     const uint32_t *lvert);

/* Twice the signed area of loop lvert[0..n) (positive counter-clockwise),
 * summed relative to its first point. */
double fct_polytri_loop_area2(const double *xy, const uint32_t *lvert, size_t n);

#endif
