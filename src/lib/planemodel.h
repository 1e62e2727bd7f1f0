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

#include "err.h"
#include "mesh.h"
#include "chain.h"
#include "planes.h"
#include "qem.h"
#include "tripatch.h"

struct fct_tidy_stats {
	size_t small_faces;   /* faces of patches too small, made free-form */
	size_t speck_faces;   /* faces of specks, given to the one label around them */
};

/* Tidy a segmentation for the planar model: patches of fewer than min_plane
 * faces become free-form (-1), too small to be worth a plane of their own;
 * then each piece of faces of one label (joined across edges; free-form
 * counts as a label) of fewer than min_free faces with one other label
 * all around it joins that label: specks of outliers inside a plane, which
 * the model puts on the plane, and the islands that a crease's noise leaves
 * on either side of it, each of which would cost the model a boundary.
 * patch: m->nf labels, changed in place. */
int fct_patches_tidy(int32_t *patch, const struct fct_mesh *m, size_t min_plane, size_t min_free,
                     struct fct_tidy_stats *st, struct fct_err *err);

/* Fill the holes of the mesh inside one patch: each border loop of at most
 * max_edges edges whose faces are all in one patch p >= 0 and which bounds
 * a hole (the loop, projected on p's plane, turns clockwise about its
 * normal, against the faces' winding) is triangulated in that plane
 * (fct_polytri, greedy) and the triangles appended to m as faces of patch
 * p.  *patch (m->nf labels, malloc'd) is grown to match.  Loops through a
 * vertex on more than one border loop, and loops the triangulation refuses
 * (self-crossing in the plane), are left open.  *filled gets the holes
 * filled; 0, or -1 out of memory. */
int fct_fill_plane_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                         size_t nplanes, size_t max_edges, size_t *filled, struct fct_err *err);

struct fct_retri_stats {
	struct fct_chain_stats chains;       /* the outlines' simplification */
	struct fct_tripatch_stats tri;       /* their triangulation */
	size_t planar_triangles, free_faces;
	size_t kept_patches;                 /* patches whose outline tripatch could not
	                                        triangulate cleanly: faces kept */
};

/* Rebuild the faces of the planar patches of m from their outlines: the
 * boundary between patches (and the free-form faces, -1, and the outside)
 * as chains, each simplified once by end-point fit to tolerance times its
 * points' mean sample spacing (with spacing, m->nv lengths; else chain.h's
 * default of three mean edges), without crossings (chain.h): an outline is
 * known to a sample across it, not to the depth's noise; then each patch's
 * polygon triangulated
 * (tripatch.h): Kang, Johnson and Szeliski's sections 3 and 4.  The chains
 * against free-form faces keep every point and the free-form faces stay as
 * they are, so the surface stays one piece.  A patch whose outline does not
 * triangulate cleanly (its loops cross in its plane: slits, repairs) keeps
 * its faces too, the chains around it every point, in rounds until the
 * rebuilt patches are all clean.  Vertices no face uses any more
 * are dropped.  *patch (m->nf labels) is replaced to match m's new faces.
 * 0, or -1 (message set). */
int fct_planes_retriangulate(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                             size_t nplanes, const double *spacing, double tolerance,
                             struct fct_retri_stats *st, struct fct_err *err);

/* Every vertex of a face of a patch onto the nearest of its patches' planes:
 * along its ray from viewpoint (when not NULL, and no more than four times
 * as far as straight across), which keeps its pixel and so every face's
 * orientation in the image; else straight across.  *moved gets the count.
 * 0, or -1 out of memory. */
int fct_planes_project(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                       const double *viewpoint, size_t *moved, struct fct_err *err);

struct fct_meet_stats {
	size_t lines;     /* vertices put on the line of two planes */
	size_t corners;   /* ... on the point of three or more */
	size_t stayed;    /* where patches meet, but no line or point near enough */
	size_t undone;    /* moves taken back: a face turned over or thinned */
};

/* Every vertex where patches meet onto their point (three or more planes
 * whose normals spread: least eigenvalue of their scatter at least 0.1) or
 * else the nearest line of two of them (not within 10 degrees of parallel;
 * its point nearest the vertex's ray with a viewpoint), when that is within
 * max_move times the vertex's sigma (no bound without sigma); a move that
 * turns a face over (against its plane's normal) or leaves it a sliver is
 * taken back, in rounds: Kang et al.'s section 5.  0, or -1 out of memory. */
int fct_planes_meet(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                    const double *sigma, double max_move, const double *viewpoint,
                    struct fct_meet_stats *st, struct fct_err *err);

/* The planar model of a segmented mesh (planedecim, planarize): */
struct fct_planar_params {
	double max_error;     /* quadric distance of a collapse, in sigma (default 1) */
	size_t target_faces;  /* stop the decimation at this many triangles (0: the bound) */
	double border_tol;    /* border distances in edge lengths (default 1; qem.h) */
	double outline_tol;   /* outlines simplified to this many sample spacings
	                         (default 3; 0: not rebuilt) */
	double max_move;      /* moves onto lines and points, in sigma (default 4) */
	size_t min_free;      /* specks of fewer faces join the label around them (64) */
	size_t min_plane;     /* patches of fewer faces are free-form (64) */
	size_t max_hole;      /* holes of at most this many edges inside a patch are
	                         filled (64; 0: none) */
};

struct fct_planar_stats {
	size_t vertices_in, faces_in, vertices_out, faces_out, planes;
	int sigma_estimated;             /* no sigma property: estimated (noise.h) */
	struct fct_tidy_stats tidy;
	size_t holes_filled, projected;
	struct fct_qem_stats qem;
	struct fct_retri_stats outline;
	struct fct_meet_stats meet;
	size_t no_pixel;                 /* vertices whose s t no camera pixel gives */
};

void fct_planar_params_default(struct fct_planar_params *p);

/* Make the planar model of m in place: m needs the face property patch and
 * the plane element (segplanes); its vertex property sigma, or else the
 * noise its data show (fct_noise_estimate_vertices), measures every bound;
 * its camera and pose comments, when present, give the viewpoint (moves
 * along rays) and the sample spacing, and s t are computed again from the
 * camera when m has them.  The steps: fct_patches_tidy, fct_fill_plane_holes,
 * fct_planes_project, fct_qem_decimate with the planes, fct_planes_retriangulate,
 * fct_planes_meet.  0, or -1 (message set; m may be half done). */
int fct_planar_model(struct fct_mesh *m, const struct fct_planar_params *p,
                     struct fct_planar_stats *st, struct fct_err *err);

#endif
