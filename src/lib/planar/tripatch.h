/* tripatch.h - each planar patch of a simplified wireframe triangulated:
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D
 * Models from Real Data" (DEC CRL 95/7), section 4.
 *
 * Input (simpchain's output, DESIGN.md): vertices, the element `edge`
 * (int vertex1 vertex2 patch1 patch2; vertex1 -> vertex2 runs with patch1
 * on its left, seen from the side its plane normal points to; patch2 is on
 * the other side, -1 on the mesh border), optionally the `plane` element.
 *
 * Per patch p: its boundary is the edges with patch1 = p as given and those
 * with patch2 = p reversed, so the patch lies on the left of each.  A pair
 * of opposite edges of one patch (a slit) cancels, a repeated edge counts
 * once.  The edges are chained into closed loops (at a vertex where the
 * patch touches itself the next edge is the first one clockwise from the
 * way back, so loops that touch at a vertex come out as separate loops),
 * mapped to 2-D and triangulated by polytri.h:
 *   1. in image coordinates (s*W, t*H with W, H from the camera comment,
 *      snapped to pixel centres within 1e-3 pixel so that vertices on one
 *      image line are exactly collinear; or s, t without a camera) when
 *      the vertices have s and t -- the paper's choice;
 *   2. else, or when the loops are not simple there (crossing, touching
 *      along an edge, two vertices on one pixel, wrong nesting), in the
 *      patch plane's own frame (the plane element's normal, or the Newell
 *      normal of the patch's edges when there is none) -- a fallback;
 *   3. when that fails too, each outer loop with its holes alone, in either
 *      frame, and when a piece fails in both, cut into ears in the plane
 *      frame (polytri.h fct_polytri_earclip) -- a repair: the triangles
 *      keep the topology, but may overlap in the plane.
 * A frame seen from behind (the loops' total signed area negative) is
 * mirrored first, so outer loops run counter-clockwise.  Triangles are
 * wound like the patch's edges, and the whole patch is reversed if its
 * triangles' area vector points against its plane normal.  Edges that
 * close no loop are dropped (counted); a patch with no closed loop gives no
 * triangle and is counted as a failure.
 *
 * Output: the same vertices, the same order, every property kept; a face
 * element of triangles with int patch (sorted by patch, each triangle
 * starting at its lowest vertex, then by vertices); the edge element is
 * removed; the plane element and comments stay. */
#ifndef FCT_TRIPATCH_H
#define FCT_TRIPATCH_H

#include <stddef.h>

#include "core/mesh.h"
#include "geom/polytri.h"

struct fct_tripatch_params {
	enum fct_polytri_method method;   /* greedy (default) or CDT */
	int plane_only;                   /* ignore s t: triangulate in the plane */
	unsigned char *unclean;           /* NULL, or one flag per plane (nplanes of
	                                     the plane element), set to 1 for a patch
	                                     whose edges had slits or repeats, did not
	                                     all close, or whose loops needed repair
	                                     (step 3) or gave no triangle */
	unsigned char *trouble;           /* NULL, or one byte per vertex of m: where
	                                     polytri refused a patch's loops in both
	                                     frames, bit 0 set at both ends of each
	                                     loop edge that crosses, overlaps or runs
	                                     through a vertex of another edge of its
	                                     patch's loops in the frame with fewer
	                                     such pairs (the s t frame on a tie),
	                                     bit 1 likewise in the other frame:
	                                     where the outline needs mending */
};

struct fct_tripatch_stats {
	size_t edges;          /* edges read */
	size_t patches;        /* patches with at least one edge */
	size_t polygons;       /* outer loops triangulated */
	size_t holes;          /* hole loops */
	size_t triangles;      /* triangles written */
	size_t in_st;          /* patches triangulated in s t */
	size_t in_plane;       /* patches triangulated in the plane frame */
	size_t fallbacks;      /* of those, patches whose s t loops were not simple */
	size_t repairs;        /* patches triangulated piece by piece (step 3) */
	size_t earclipped;     /* pieces cut into ears */
	size_t failures;       /* patches with edges but no triangle */
	long first_failure;    /* the lowest such patch, -1 none */
	size_t open_edges;     /* patch edges on no closed loop */
	size_t slits;          /* opposite edge pairs of one patch cancelled */
	size_t duplicates;     /* repeated edges ignored */
	size_t degenerate;     /* loops of fewer than 3 vertices or no area, dropped */
	size_t reversed;       /* patches reversed to agree with their plane normal */
	size_t slivers_flipped; /* triangles of no area in space (three corners on
	                          one line) whose longest edge was flipped */
	struct fct_polytri_stats tri;
};

void fct_tripatch_params_default(struct fct_tripatch_params *p);

/* Replace m's faces by the triangulated patches of its edge element (see
 * above) and remove the edge element.  Fails (-1, err set, m unchanged)
 * without an edge element or its four properties, on an edge whose vertex
 * is out of range, whose ends are equal, whose patch is neither -1 nor a
 * plane (when m has a plane element), or that has no patch on either side;
 * on a plane element that planes.h refuses; and out of memory.  st may be
 * NULL. */
int fct_tripatch(struct fct_mesh *m, const struct fct_tripatch_params *p,
                 struct fct_tripatch_stats *st, struct fct_err *err);

#endif
