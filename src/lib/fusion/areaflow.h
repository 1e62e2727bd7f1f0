/* areaflow.h - crease-preserving mesh smoothing by area decreasing flow
 * (Sun, Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor
 * Scenes Using a Mobile Range Scanner", sec. 2), and the two classic
 * baselines it is compared with, Laplacian and Taubin lambda/mu smoothing.
 *
 * Area decreasing flow moves each vertex v along its normal n by the step l
 * of eq. (3), the exact minimiser of eq. (2)
 *
 *     f(l) = sum_i 4 S_i(v + l n)^2 + lambda |v + l n - v0|^2
 *
 * (S_i the areas of the triangles of v's umbrella, v0 its input position),
 * scaled by exp(-5 s) where s in [0, 1] is the crease strength of eq. (4):
 * a tensor vote of the normals of the faces within a geodesic window of the
 * vertex.  Vertices are swept by colours (Gauss-Seidel within a fixed
 * colouring), so the result does not depend on the number of threads.
 *
 * Departures from the paper, for noise comparable to the sample spacing
 * (Kinect-class range meshes; the paper's scanner had noise well under its
 * spacing), all under the guide (guide below; off, the paper as written):
 * normals from the area vectors of a Laplacian-smoothed copy averaged over
 * rings; eq. (3)'s weights from that copy's umbrellas, lambda 0; eq. (4)
 * on the copy's face tensors n n^T averaged over rings (the arc transport
 * left out) with a noise ramp on s; moves along the sensor's rays.  With or
 * without the guide, a step of eq. (3) is held to the range of its
 * neighbours' heights (only binds when a weight is negative). */
#ifndef FCT_AREAFLOW_H
#define FCT_AREAFLOW_H

#include <stddef.h>

#include "core/mesh.h"

enum fct_smooth_method {
	FCT_SMOOTH_AREAFLOW,   /* eq. (3), adaptive by eq. (4) */
	FCT_SMOOTH_LAPLACIAN,  /* v += lap_lambda (mean of neighbours - v) */
	FCT_SMOOTH_TAUBIN      /* a lap_lambda step then a taubin_mu step */
};

struct fct_areaflow_params {
	enum fct_smooth_method method;
	/* The guide, for noise comparable to the sample spacing: 1 on, 0 off
	 * (the paper as written: passes, rings, vote_rings, the ramp and
	 * along_ray are not used), -1 (default) on when 5 Laplacian passes
	 * shorten the median edge below 0.8 of the input's. */
	int guide;
	/* eq. (2): the weight of the squared distance moved from the input, in
	 * squared median edge lengths of the input (so it does not depend on the
	 * units); default -1: 0 with the guide, 1 without. */
	double lambda;
	/* > 0: exactly this many iterations; 0: none (only the crease strength
	 * is computed); < 0: until the mean move of an iteration is below
	 * tol median edge lengths, at most max_iterations (default -1, 10, 0.02). */
	int iterations;
	int max_iterations;
	double tol;
	/* Tensor voting: faces whose centroid lies within window median edge
	 * lengths of the vertex, reached through faces that do (the geodesic
	 * window), vote with weight exp(-(d / sigma)^2), d the centroid's
	 * distance, sigma in median edge lengths (defaults 2.5 and 1.5); delta is
	 * the threshold of eq. (4) on the mean voted normal (default 0.3). */
	double window, sigma, delta;
	int crease;          /* 1 (default): scale the step by exp(-5 s); 0: s = 0 */
	double lap_lambda;   /* Laplacian and Taubin (default 0.5) */
	double taubin_mu;    /* Taubin's negative step (default -0.53) */
	int threads;         /* 0 (default): one per online processor, at most 64 */
	/* Guide: the face normals that vote and the vertex normals the steps
	 * follow are area vectors averaged over this many rings (default 8;
	 * without the guide 0: the faces' own normals and the umbrella's). */
	int rings;
	/* Guide: the normals are taken on a copy of the mesh smoothed by this
	 * many Laplacian passes (factor 0.5; default 5; without the guide 0:
	 * on the mesh itself); the
	 * flow moves the mesh itself.  With passes or rings the step follows
	 * the smoothed vertex normal, computed once per iteration.  With
	 * passes, eq. (3) also takes the tangential shape of each umbrella
	 * (which sets its weights; the heights along n stay the mesh's) from
	 * the copy: eq. (3) is the umbrella's cotangent-like Laplacian along n,
	 * and on a mesh whose noise is comparable to its edges the shape is
	 * noise, with negative weights where triangles are obtuse or folded. */
	int passes;
	/* > 0: the crease vote is the faces' tensors n n^T (and normals)
	 * averaged over this many rings of the guide instead of the geodesic
	 * window walk (transport ignored); 0: the window walk. */
	int vote_rings;
	/* The noise-aware ramp on s: s' = (s - crease_lo) / (crease_hi -
	 * crease_lo) held to [0, 1] (none when crease_hi <= crease_lo;
	 * defaults 0.05 and 0.15). */
	double crease_lo, crease_hi;
	/* 1: each vertex moves along the sensor's ray from origin through it,
	 * by as much as makes its move along n the step of eq. (3) (|n.r| held
	 * at 0.2 or more); 0 (default): along n. */
	int along_ray;
	double origin[3];
};

void fct_areaflow_params_default(struct fct_areaflow_params *p);

/* What a run did. */
struct fct_areaflow_stats {
	int iterations;        /* done */
	double edge;           /* median edge length of the input */
	double last_move;      /* mean distance moved in the last iteration */
	double mean_offset;    /* mean distance of the moving vertices from the input */
	double max_offset;     /* largest distance of a vertex from the input */
	double mean_crease;    /* mean s over the vertices with faces (last computed) */
	size_t moving;         /* vertices that may move */
	size_t held;           /* on a non-manifold edge: held (areaflow only) */
	size_t isolated;       /* in no face */
	size_t threads;        /* used */
	/* The crease vote's window cache (areaflow with the crease, computed
	 * twice or more): face ids held (4 bytes each, beside 6 bytes per
	 * vertex), and windows walked again because a face had crossed the
	 * radius since the cache was made (over all passes). */
	size_t window_ids;
	size_t window_walks;
	int guide;             /* 1: the guide was used (areaflow) */
	double edge_ratio;     /* guide auto: median edge after 5 Laplacian
	                        * passes over the input's (0: not measured) */
};

/* Smooth m's positions in place by p->method.  Vertices in no face stay.
 * Area decreasing flow holds vertices on non-manifold edges (walked by three
 * or more faces) and moves every other vertex, border vertices included,
 * along its normal only (the area-weighted mean of its faces' normals), so
 * no vertex slides within the surface and borders do not recede; a vertex
 * whose normal vanishes stays.  A polygon contributes to the umbrella of
 * each corner the triangle of the corner and its two neighbours.  When
 * crease is not NULL it gets (m->nv entries) the crease strength s of every
 * vertex of the output mesh (0 for vertices in no face).  Fails (-1) on a
 * non-finite coordinate or out of memory; m is then unchanged.  Never
 * produces a non-finite coordinate. */
int fct_areaflow(struct fct_mesh *m, const struct fct_areaflow_params *p, double *crease,
                 struct fct_areaflow_stats *st, struct fct_err *err);

/* Eq. (3): the step l along the unit normal n that minimises eq. (2) for a
 * vertex at v with input position v0 and umbrella of ntri triangles
 * (v, ring[6i..6i+2], ring[6i+3..6i+5]); lambda in absolute units (length
 * squared).  0 when the minimum is not unique or not finite. */
double fct_areaflow_step(const double v[3], const double v0[3], const double n[3],
                         const double *ring, size_t ntri, double lambda);

/* Eq. (4): the crease strength at q from m votes: face centroids
 * p[3i..3i+2], unit face normals n[3i..3i+2] and weights mu[i] >= 0.  Each
 * normal is transported along the arc from its centroid to q
 * (n' = 2 (n.w) w - n) and T = sum mu n' n'^T; s = 1 when the mean voted
 * normal is within delta of perpendicular to T's first eigenvector, else
 * (nu2 - nu3) / nu1.  0 with no (or only zero-weight) votes; always in
 * [0, 1]. */
double fct_crease_strength(const double q[3], const double *p, const double *n,
                           const double *mu, size_t m, double delta);

/* Eigenvalues (nu[0] >= nu[1] >= nu[2]) of the symmetric 3x3 matrix
 * t = (xx, xy, xz, yy, yz, zz), and a unit eigenvector e1 of nu[0] (when
 * nu[0] is repeated, any unit vector of its eigenspace closest to hint,
 * which may be NULL).  Closed form (trigonometric). */
void fct_sym3_eigen(const double t[6], double nu[3], double e1[3], const double *hint);

/* Unit area-weighted vertex normals of m (3 per vertex into vn, 0 0 0 for a
 * vertex whose faces have no area or which has none); polygons by Newell's
 * vector area.  No allocation, cannot fail. */
void fct_vertex_normals(const struct fct_mesh *m, double *vn);

#endif
