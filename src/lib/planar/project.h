/* project.h - vertex projection onto the planes of a segmentation, texture
 * coordinates from the camera, and two corrections from world knowledge:
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D
 * Models from Real Data" (DEC CRL 95/7), sections 5, 6 and 8.
 *
 * Section 5: a vertex whose incident faces carry k distinct patch labels is
 * moved to the point of those k planes nearest to it: onto the plane (k = 1),
 * onto the line of the two planes (k = 2), to the least-squares point of the
 * planes (k >= 3, eq. 2 solved with the pseudoinverse).  All three are one
 * formula: with N the k x 3 matrix of unit normals and r_i = -(n_i.p0 + d_i)
 * the signed offsets of the vertex p0, the move is the minimum-norm
 * least-squares solution delta = N^+ r, found from the singular value
 * decomposition N = U S V^T (LAPACK dgesvd) as
 *     delta = sum over j < rank of v_j (u_j . r) / s_j,
 * singular values below rank_tol times the largest counting as zero (planes
 * that are nearly parallel act as one).  A move longer than the bound is
 * refused and the vertex kept, as the paper does for planes "close to
 * parallel"; with fallback, the longest truncation of that sum (a lower
 * rank) within the bound is used instead.
 *
 * Section 6: after the move, s = (u + 0.5) / W and t = 1 - (v + 0.5) / H
 * of the pixel (u, v) the camera comment sees the vertex at (through the
 * inverse of the pose comment), so the image stays registered.
 *
 * Section 8: fct_planes_orthogonalize snaps nearly orthogonal or parallel
 * planes to an exact frame with a common up axis; fct_depth_scale_solve
 * finds the scaling of camera-frame depth that makes adjacent planes
 * orthogonal (the paper's Figure 8).  projverts(1) gives the mathematics
 * in full. */
#ifndef FCT_PROJECT_H
#define FCT_PROJECT_H

#include <stddef.h>
#include <stdint.h>

#include "io/camera.h"
#include "core/mesh.h"
#include "geom/planes.h"

/* The defaults of fct_project_params_default. */
#define FCT_PROJECT_RANK_TOL 1e-2       /* singular value ratio: planes ~1.15 degrees apart act as one */
#define FCT_PROJECT_MAX_MOVE_EDGES 1.0  /* default bound: the mean edge length */
#define FCT_PROJECT_SCALE_ANGLE 5.0     /* degrees from orthogonal for a depth-scale inlier */
#define FCT_PROJECT_SCALE_PARALLEL 20.0 /* pairs closer to parallel propose no scale */
#define FCT_PROJECT_SCALE_RANGE 10.0    /* scales proposed lie in [1/10, 10] */
#define FCT_PROJECT_TEAR_COS 0.1       /* a torn copy's ray meets its plane at most
                                           ~84 degrees from the normal */
#define FCT_PROJECT_TEAR_EDGES 10.0    /* and moves at most this many bounds */
#define FCT_PROJECT_RAY_EDGES 3.0      /* a vertex of one plane refused for its distance
                                           moves along its ray at most this many bounds */
#define FCT_PROJECT_TEAR_APART 0.1     /* a rank-deficient point this many bounds off one
                                           of its planes is torn too */
#define FCT_PROJECT_SCALE_MIN_AREA 0.01 /* fct_project_mesh: patches under this fraction
                                           of the labelled area pair with none */

struct fct_project_params {
	double max_move;        /* largest move kept, in coordinate units; < 0: max_move_edges
	                           times the mean edge length of the mesh (HUGE_VAL: no bound) */
	double max_move_edges;  /* see above (default 1) */
	double rank_tol;        /* relative singular value threshold (default 1e-2) */
	int fallback;           /* a refused move falls back to the best lower rank */
	double ortho_angle;     /* degrees in (0, 40]; 0: no snapping */
	int depth_scale_fix;    /* solve and apply the depth scale first */
	double scale_angle;     /* degrees from 90 that make a pair an inlier of the scale
	                           (default FCT_PROJECT_SCALE_ANGLE, or ortho_angle when set) */
	int texcoords;          /* recompute s t when there is a camera (default 1) */
	int along_rays;         /* with a camera, k = 1, 2 move along the vertex's ray
	                           instead of perpendicularly (the paper's rule) */
	int tear;               /* wireframes seen by a camera: a vertex of k >= 2 planes
	                           whose move is refused is torn, one copy per plane,
	                           each moved along the vertex's ray onto its plane
	                           (default 1; see fct_project_mesh) */
	int straighten;         /* wireframes: drop crease vertices projection put on
	                           the line of their two planes (default 1) */
};

void fct_project_params_default(struct fct_project_params *p);

/* What fct_project_point did for one vertex. */
struct fct_point_fit {
	int rank;      /* numerical rank of the k normals (at most 3) */
	int used;      /* rank of the applied solution: rank, less with fallback, 0 if kept */
	double want;   /* length of the full-rank move */
	double move;   /* length of the move applied (0 when kept) */
};

/* The point of the k planes (normals[3i..3i+2] unit, offsets[i]: n.x + d = 0)
 * nearest p0, as described above, into out (out may be p0).  bound: the
 * longest move accepted; rank_tol as in the params.  k = 0 keeps p0.
 * 0, or -1 when out of memory or LAPACK fails. */
int fct_project_point(const double *normals, const double *offsets, size_t k, const double p0[3],
                      double bound, double rank_tol, int fallback, double out[3],
                      struct fct_point_fit *fit, struct fct_err *err);

/* Texture coordinates of mesh point p seen by cam (width and height set)
 * after the world-to-camera transform inv_pose (NULL: p is in the camera
 * frame): s = (u + 0.5) / W, t = 1 - (v + 0.5) / H.  1, or 0 when the point
 * has no pixel (behind a pinhole camera, on a cylinder's axis). */
int fct_project_texcoord(const struct fct_camera *cam, const double *inv_pose, const double p[3],
                         double *s, double *t);

/* Section 6: each vertex's s t from the camera (fct_project_texcoord), the
 * columns made (float) when missing; a vertex with no pixel keeps its
 * values and counts in *no_pixel. */
int fct_camera_texcoords(struct fct_mesh *m, const struct fct_camera *cam, const double *inv_pose,
                         size_t *no_pixel, struct fct_err *err);

/* Snapping to a frame (section 8), in degrees A = angle:
 *  1. up: among the plane normals (as lines; with up_prior, only those
 *     within 45 degrees of it, when there are any), the one with the largest
 *     weight of normals within A of it, refined twice to the principal
 *     eigenvector of sum w n n^T over the normals within A of it;
 *  2. vertical planes (normal within A of perpendicular to up) are grouped
 *     greedily by azimuth modulo 90 degrees (the heaviest group first, its
 *     azimuth the weighted circular mean of 4 x azimuth, divided by 4);
 *     each group is a frame: up and two horizontal axes (at most 256
 *     frames; vertical planes left over are only made vertical);
 *  3. a normal within A of +-up becomes +-up; a vertical one becomes the
 *     nearest signed horizontal axis of its frame; any other normal within A
 *     of perpendicular to a horizontal axis of the main (heaviest) frame
 *     loses its component along the nearer such axis;
 *  4. a changed plane turns about the point of the old plane nearest to
 *     pivot[3i..3i+2] (NULL, or a non-finite pivot: the point of the old
 *     plane nearest the origin).
 * weight (n entries, NULL: all 1) weighs each plane in steps 1 and 2.
 * up_prior: a unit vector or NULL. */
struct fct_ortho_result {
	double up[3];
	size_t frames;          /* groups of vertical planes */
	size_t horizontal;      /* planes snapped to +-up */
	size_t vertical;        /* planes snapped to a horizontal axis */
	size_t oblique;         /* planes made perpendicular to one horizontal axis */
	double max_change;      /* largest change of a normal, degrees */
};
int fct_planes_orthogonalize(struct fct_plane *pl, size_t n, const double *weight,
                             const double *pivot, const double *up_prior, double angle,
                             struct fct_ortho_result *res, struct fct_err *err);

/* Depth scale (section 8, Figure 8).  In the frame where depth is measured
 * (the camera frame: world = R cam + t), the mesh is taken to be the true
 * scene with depth scaled by 1/lambda: camera-frame z for pinhole cameras
 * (and for meshes without a camera), the distance from the vertical axis
 * (x and z) for cylindrical ones.  Scaling it back by lambda maps a
 * camera-frame normal n to S^-1 n (S = diag(1, 1, lambda) or diag(lambda,
 * 1, lambda)), so planes i, j become orthogonal when
 *     a_ij + b_ij / lambda^2 = 0,
 * a_ij summing n_i n_j over the unscaled axes and b_ij over the scaled ones.
 * Each pair with a_ij b_ij < 0, not within 20 degrees of parallel as it
 * is, proposes lambda_ij = sqrt(-b_ij / a_ij) when in [0.1, 10]; the
 * proposal (of the 1000 heaviest pairs) that makes the largest weight of
 * pairs orthogonal to within angle degrees wins, and lambda then minimises
 * the weighted sum of squared cosines of those inliers (golden section on
 * log lambda, inliers chosen again twice).  */
struct fct_plane_pair {
	uint32_t a, b;         /* plane indices */
	double w;              /* weight (fct_project_mesh: the smaller patch's area) */
};
struct fct_scale_result {
	double scale;          /* lambda; 1 when nothing constrains it */
	size_t pairs;          /* pairs that proposed a scale */
	size_t inliers;        /* pairs orthogonal within angle at the scale */
	double rms_cos;        /* weighted rms cosine of the inliers at the scale */
};
/* to_cam: the world-to-camera pose (NULL: identity). */
int fct_depth_scale_solve(const struct fct_plane *pl, size_t n, const struct fct_plane_pair *pairs,
                          size_t npairs, const double *to_cam, int cylindrical, double angle,
                          struct fct_scale_result *res, struct fct_err *err);
/* Apply lambda: points (n of them, in place), planes (in place, exactly),
 * and the camera's focal length (pinhole fx fy, cylindrical f; cam may be
 * NULL), so pixels of scaled points are those of the unscaled ones.  pose:
 * camera-to-world (NULL: identity). */
void fct_depth_scale_apply(double lambda, const double *pose, int cylindrical, double *xyz,
                           size_t nv, struct fct_plane *pl, size_t npl, struct fct_camera *cam);

/* Figures of a run of fct_project_mesh. */
struct fct_project_stats {
	size_t nvert, nplanes;
	size_t by_k[4];          /* vertices on 0, 1, 2, >= 3 planes */
	size_t moved[4];         /* of those, moved */
	size_t rejected;         /* moves over the bound: vertex kept */
	size_t flip_refused;     /* moves that would turn a face against its plane: kept */
	size_t torn;             /* vertices torn apart (counted here, not as rejected) */
	size_t tear_copies;      /* vertices added by tearing */
	size_t straightened;     /* crease vertices dropped (on their line) */
	size_t straight_refused; /* crease vertices kept: dropping one would cross */
	size_t cross_refused;    /* moves that would make a patch boundary cross itself
	                            in the image (then torn or moved along the ray, or kept) */
	size_t ray_fallback;     /* vertices of one plane moved along their ray instead */
	size_t along_ray;        /* moves made along the camera's ray */
	size_t fallback;         /* moved at a lower rank than the full solution */
	size_t rank_deficient;   /* numerical rank below min(k, 3) */
	double mean_edge, bound;
	double mean_move, max_move;       /* over moved vertices */
	double rms_before, rms_after;     /* distance to own planes, over (vertex, plane) pairs */
	double max_after;
	int texcoords;           /* 1 when s t were recomputed */
	size_t no_pixel;         /* vertices without a pixel: s t kept */
	int ortho;               /* snapping done */
	struct fct_ortho_result ortho_res;
	int scaled;              /* depth scale done */
	struct fct_scale_result scale_res;
};

/* The whole stage on m, in place: reads the face property patch, or for a
 * mesh without faces the wireframe element edge (planes.h fct_wires_get:
 * a vertex's planes are then the patches on either side of its edges), and
 * the plane element (planes.h; a mesh without them fails); optionally fixes
 * the depth scale (vertices, planes, camera comment), optionally snaps the
 * planes, projects every vertex, recomputes s t from the camera and pose
 * comments (adding float s t when missing) and writes the planes back when
 * they changed.  Topology and every other property are kept, except that
 * with tear a wireframe seen by a camera tears its occlusion boundaries: a
 * vertex of two or more planes whose move to their common point is refused
 * (parallel planes, or planes meeting far away: a box before a wall, which
 * the depth map joined by a veil) gets one copy per plane (the first plane
 * keeps the vertex, the others get new vertices appended with all its
 * properties), each moved along the vertex's ray onto its plane -- where
 * that surface is seen at the vertex's pixel -- provided every ray meets its
 * plane within FCT_PROJECT_TEAR_COS of the normal and moves at most
 * FCT_PROJECT_TEAR_EDGES bounds.  Each edge then joins the copies of its own
 * side's plane: an edge whose two sides got different vertices becomes two
 * edges, one per side, each with -1 on the other.  The copies share their
 * pixel, so the model has no gap in the image and a true depth
 * discontinuity in space.  The same along-ray move rescues a vertex of one
 * plane (no copy), and tears or moves a vertex whose move would make a
 * patch boundary cross itself in the image (tripatch triangulates there),
 * which is refused; a vertex of one plane refused for its distance moves at
 * most FCT_PROJECT_RAY_EDGES bounds.  Crease vertices left on the line of
 * their two planes are dropped with straighten (projverts(1) has the
 * rules).  st may be NULL.  0 or -1. */
int fct_project_mesh(struct fct_mesh *m, const struct fct_project_params *p,
                     struct fct_project_stats *st, struct fct_err *err);

#endif
