/* planemodel.h - what the planar model makes of a segmentation before its
 * decimation (planedecim; qem.h's "Planes"): patches too small to be planes
 * become free-form, specks of free-form faces inside a patch join it, and
 * small holes inside a patch are filled in its plane.  Kang, Johnson and
 * Szeliski (DEC CRL 95/7) model the planes of a room; noise leaves specks
 * and holes in them that a concise model should not keep. */
#ifndef FCT_PLANEMODEL_H
#define FCT_PLANEMODEL_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "core/mesh.h"
#include "planar/chain.h"
#include "geom/planes.h"
#include "geom/qem.h"
#include "planar/tripatch.h"

struct fct_tidy_stats {
	size_t small_faces;   /* faces of patches too small, made free-form */
	size_t speck_faces;   /* faces of specks, given to the one label around them */
	size_t off_plane_faces; /* ... kept apart: mostly farther than max_dev sigma from its plane */
	size_t closed_faces;  /* faces of patches with no outline (whole closed pieces), made free-form */
	size_t seam_faces;    /* faces along seams of patches facing apart (no viewpoint), free-form */
};

/* Tidy a segmentation for the planar model: patches of fewer than min_plane
 * faces become free-form (-1), too small to be worth a plane of their own;
 * then each piece of faces of one label (joined across edges; free-form
 * counts as a label) of fewer than min_free faces, or narrower than three
 * samples (fewer faces than three times its boundary edges), with one
 * other label all around it joins that label: specks of outliers inside a plane, which
 * the model puts on the plane, and the islands that a crease's noise leaves
 * on either side of it, each of which would cost the model a boundary.
 * With sigma (each vertex's, and planes: the np planes), a piece joins a
 * patch only when half its faces' corners or more lie within max_dev
 * times their sigma of that patch's plane; the rest stay as they are
 * (off_plane_faces).
 * With two_sided (no viewpoint: a fused scan; planes needed),
 * the faces along an edge between two patches whose normals are more than
 * 120 degrees apart (the two sides of a board thinner than the noise,
 * which would span one outline in the same triangles) become free-form: a
 * rim between them.
 * Last, a patch with no edge to another label or the mesh's border (a
 * whole closed piece: a blob whose top was a patch and whose rest joined
 * it as a speck) becomes free-form: no outline bounds its polygon.
 * patch: m->nf labels, changed in place; adj: m's adjacency (fct_adj_build). */
int fct_patches_tidy(int32_t *patch, const struct fct_mesh *m, const struct fct_adj *adj,
                     const struct fct_plane *planes,
                     size_t np, int two_sided, const double *sigma, double max_dev,
                     size_t min_plane, size_t min_free, struct fct_tidy_stats *st,
                     struct fct_err *err);

/* Facets of curved surfaces become free-form: each patch whose outline
 * (to other patches, the free-form surface and the outside) runs, for at
 * least min_share of its length, along
 * creases shallower than max_angle degrees (the angle between the planes'
 * normals; but 3 degrees at least: planes nearer parallel make no crease, a
 * sheet of paper on a table) with three or more patches.  Noise large enough lets planes fit
 * a sphere piecewise; such facets meet several others at shallow creases
 * all round, which walls, floors and boxes, meeting at right angles or at
 * the image's edge, do not, nor a plane that noise split in two.  A
 * patch of more than four times the faces of its largest shallow neighbour
 * stays a plane: facets are of about one size.  patch changes in place;
 * *facets gets the count.  adj: m's adjacency (fct_adj_build). */
int fct_patches_unfacet(int32_t *patch, const struct fct_mesh *m, const struct fct_adj *adj,
                        const struct fct_plane *planes,
                        size_t nplanes, double max_angle, double min_share, size_t *facets,
                        struct fct_err *err);

/* Fill the holes of the mesh inside one patch: each border loop of at most
 * max_edges edges whose faces are all in one patch p >= 0 and which bounds
 * a hole (the loop, projected on p's plane, turns clockwise about its
 * normal, against the faces' winding) is triangulated in that plane
 * (fct_polytri, greedy) and the triangles appended to m as faces of patch
 * p.  *patch (m->nf labels, malloc'd) is grown to match.  Where several
 * border loops pass one vertex (holes touching at a corner), each goes on
 * along the edge that turns first across its hole about p's normal.
 * Loops through a vertex twice, and loops the triangulation refuses
 * (self-crossing in the plane), are left open.  *filled gets the holes
 * filled; 0, or -1 out of memory. */
int fct_fill_plane_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                         size_t nplanes, size_t max_edges, size_t *filled, struct fct_err *err);

/* The other holes of at most max_edges edges: border loops through faces
 * of more than one label or free-form ones (-1) whose every vertex v lies
 * within max_dev sigma[v] of the plane through the loop's centroid normal
 * to its faces' mean normal (a surface no view saw, not a depth jump),
 * triangulated in that plane as free-form faces, on the same terms; where
 * holes touch, each goes on along the edge that turns first across it
 * about the normal of the face walked. */
int fct_fill_free_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                        size_t nplanes, size_t max_edges, const double *sigma, double max_dev,
                        size_t *filled, struct fct_err *err);


/* Every vertex of a face of a patch onto the nearest of its patches' planes:
 * along its ray from viewpoint (when not NULL, and no more than four times
 * as far as straight across), which keeps its pixel and so every face's
 * orientation in the image; else straight across.  A move along its ray of
 * more than max_move times its uncertainty (below) is not made: the vertex
 * stays at its sample (issue 23: no vertex moved farther than its noise
 * allows; a floor vertex slid along a grazing ray ends off the data).
 * With a viewpoint, a vertex of exactly two patches that the nearer plane
 * would take farther
 * from their planes' line than it is goes onto that line instead, where it
 * passes nearest the vertex's ray (unless that is more than four times as
 * far as onto the nearer plane, or more than max_move times its
 * uncertainty, the root of sigma^2 (sigma NULL: 0) plus the span of
 * pixel_angle at its distance squared): along its ray onto the nearer plane
 * alone, a vertex of the floor at a far wall, its ray grazing the floor,
 * slides on past the wall.  With occluded (NULL, or m->nv entries), not
 * where the two planes would hide the vertex's own sample (its ray meets
 * one of them more than that bound before it, on that patch's side of the
 * line): the patches do not meet there, one occludes the other;
 * occluded[v] is 1 for such a vertex (fct_planar_model splits it), 0 for
 * the others.  So does a vertex of the floor alone slide past the wall
 * (the wall's faces beside it free-form, or none): a vertex of one patch,
 * on its border (not inside a closed fan of that patch's faces), whose ray
 * meets its plane at a grazing angle (more than twice as far as straight
 * across) and meets the plane of another patch more than its uncertainty
 * before that, within max_move times its uncertainty of the vertex and on
 * the side of the two planes' line where the corners of that patch's
 * faces within that distance lie (reached through the mesh), would lie
 * hidden behind that patch: it goes onto the two planes' line where that
 * passes nearest its ray, when that is within max_move times its
 * uncertainty.  off_crease (NULL, or 3 * m->nv) gets for each
 * vertex so put on a line where the nearer (or only) plane alone would have put it,
 * NaN for the others.  *moved gets the vertices moved, *creased those put
 * on a line.  adj: m's adjacency (fct_adj_build; the faces of each vertex
 * are what it takes).  0, or -1 out of memory. */
int fct_planes_project(struct fct_mesh *m, const struct fct_adj *adj, const int32_t *patch,
                       const struct fct_plane *planes, const double *viewpoint, const double *sigma,
                       double pixel_angle, double max_move, double *off_crease,
                       unsigned char *occluded, size_t *moved, size_t *creased, struct fct_err *err);

struct fct_meet_stats {
	size_t lines;     /* vertices put on the line of two planes */
	size_t corners;   /* ... on the point of three or more */
	size_t stayed;    /* where patches meet, but no line or point near enough */
	size_t undone;    /* moves taken back: a face turned over or thinned */
	size_t torn;      /* copies of vertices off a plane of theirs, on it */
};

/* Every vertex where patches meet onto their point (three or more planes
 * whose normals spread: least eigenvalue of their scatter at least 0.1) or
 * else the nearest line of two of them (not within 10 degrees of parallel;
 * its point nearest the vertex's ray with a viewpoint), when that is within
 * max_move times the vertex's uncertainty, sqrt(sigma^2 + spacing^2): its
 * noise along its ray and its sample spacing across it (no bound when both
 * are NULL; where creases meet is known to a sample), and not where the
 * two planes would hide the vertex's own sample (fct_planes_project); a
 * move that
 * turns a face over (against its plane's normal) or leaves it a sliver is
 * taken back, in rounds: Kang et al.'s section 5.  A vertex then still off
 * one of its planes by more than its uncertainty (where patches meet, or
 * where a patch meets the free-form surface) is torn: that patch's
 * faces get a copy of it on their plane, so that no plane is tilted by
 * another's vertex; the surface has a crack there, as the sensor saw it
 * (an occlusion).  The copy goes along the vertex's ray when that is
 * within the bound, or when the plane lies before the sample (the ray
 * passes the edge of a surface in front), the ray meets it at a sine of
 * 0.3 or more and another plane of the vertex holds the sample (without
 * one, the copy goes the bound along the ray, no farther: the sample is
 * the plane's own, seen along a grazing ray); else straight across.  Without a viewpoint (a fused scan:
 * no occlusion, and a crack would open a closed surface) nothing is
 * torn; the vertex stays shared.  0, or -1 out of memory. */
int fct_planes_meet(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                    const double *sigma, const double *spacing, double max_move,
                    const double *viewpoint, struct fct_meet_stats *st, struct fct_err *err);

/* The planar model of a segmented mesh (planedecim, planarize). */
struct fct_planar_params {
	double max_error;     /* the free-form decimation's quadric distance, in sigma
	                         (default 1.5) */
	double border_tol;    /* its border distances in edge lengths (default 1) */
	double outline_tol;   /* outlines simplified to this many sample spacings
	                         (default 3) */
	double max_move;      /* moves onto lines and points, in sigma (default 4) */
	size_t min_free;      /* specks of fewer faces join the label around them (64) */
	size_t min_plane;     /* patches of fewer faces are free-form (64) */
	size_t min_piece;     /* without a camera, pieces of fewer faces are
	                         dropped: a fusion's floating debris (64; 0: none) */
	size_t max_hole;      /* holes of at most this many edges inside a patch are
	                         filled (64; 0: none) */
	double facet_angle;   /* a patch whose boundary with other patches runs
	                         mostly (half its length) along creases shallower
	                         than this is a facet of a curved surface: free-form
	                         (20 degrees; 0: none) */
};

struct fct_planar_stats {
	size_t vertices_in, faces_in, vertices_out, faces_out, planes;
	size_t debris_pieces, debris_faces;  /* pieces dropped (no camera), their faces */
	int sigma_estimated;             /* no sigma property: estimated (noise.h) */
	size_t facets;                   /* patches found facets of curved surfaces */
	struct fct_tidy_stats tidy;
	size_t holes_filled, free_holes_filled, projected;
	size_t creased;                  /* of those, put on two planes' line */
	size_t split;                    /* of the others, split: a crease there would hide their sample */
	size_t uncreased;                /* ... and taken off it again: corners of
	                                    triangles of no area */
	struct fct_qem_stats qem;        /* the free-form faces' decimation */
	struct fct_chain_stats chains;   /* the outlines' simplification */
	struct fct_tripatch_stats tri;   /* their triangulation */
	size_t planar_triangles, free_faces;
	size_t border_free_faces;        /* free-form faces of the model with a corner on
	                                    one of its open borders */
	size_t duplicates_dropped;       /* a patch's triangles over a free-form one */
	size_t rounds, dense_patches;    /* patches whose outline was kept as sampled */
	size_t pinned;                   /* diagonals found elsewhere (edges of three faces) */
	size_t mended;                   /* stretches of outline kept as sampled where
	                                    they crossed */
	size_t tightened;                /* whole outlines simplified more tightly */
	size_t unclean_patches;          /* ... and made free-form, still not clean */
	size_t reprojected;              /* vertices of theirs moved onto the planes of
	                                    the patches they still have */
	struct fct_meet_stats meet;
	size_t no_pixel;                 /* vertices whose s t no camera pixel gives */
};

void fct_planar_params_default(struct fct_planar_params *p);

/* Make the planar model of m in place (Kang, Johnson and Szeliski, DEC CRL
 * 95/7, sections 3 to 5, with free-form surfaces, their section 9's open
 * case): m needs the face property patch and the plane element
 * (segplanes).  Its vertex property sigma, or else the noise its data show
 * (fct_noise_estimate_vertices), measures every bound; its camera and pose
 * comments, when present, give the viewpoint (moves along rays) and the
 * sample spacing (one pixel's span; else the mean edge), and s t are
 * computed again from the camera when m has them.  The steps:
 *  0. without a camera (a fused scan, another tool's mesh), the pieces
 *     (connected components) of fewer than min_piece faces are dropped
 *     (fct_mesh_drop_small_pieces): the floating debris a fusion's noise
 *     leaves, which no user wants in a model of the room;
 *  1. fct_patches_tidy, fct_fill_plane_holes, fct_planes_project;
 *  2. the free-form faces (-1) alone decimated by quadric edge collapse
 *     (qem.h, in units of sigma), the junctions of the patch boundaries kept;
 *  3. the patch boundaries as chains (chain.h): those against the free-form
 *     surface keep the vertices its decimation kept, the others simplified
 *     by end-point fit to outline_tol sample spacings without crossings;
 *  4. each patch the polygon of its outline, triangulated (tripatch.h), and
 *     the free-form faces beside them: one surface, edge for edge;
 *  5. a patch whose outline does not triangulate cleanly (its loops cross,
 *     or a diagonal would be an edge of three faces) is mended there: the
 *     simplified segments between the ends of the crossing loop edges (in
 *     the frame with fewer crossings, then the other) are kept as
 *     sampled, those beside the diagonal's ends keep their middle point
 *     (then, if it comes back, all their points) (the rest of its outline
 *     stays as simplified, so that where the trouble is, not whether there
 *     is any, decides the outline); a patch that cannot be mended so
 *     becomes free-form, or when it holds a fiftieth of the faces or more
 *     (and no small patch went free-form in that round), has its whole
 *     outline tightened step by step to as sampled (and free-form only if
 *     even that fails); the vertices of a patch made free-form that still
 *     have a patch go from their samples onto the nearest plane of those
 *     again (step 1 may have put them on the one gone); the model is made
 *     again, until none is left;
 *  6. fct_planes_meet: vertices onto the planes' lines and corners.
 * 0, or -1 (message set; m may be half done). */
int fct_planar_model(struct fct_mesh *m, const struct fct_planar_params *p,
                     struct fct_planar_stats *st, struct fct_err *err);

#endif
