/* areaflow.c - area decreasing flow with crease strength by tensor voting:
 * Sun, Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor
 * Scenes Using a Mobile Range Scanner", sec. 2, eqs. (2), (3) and (4); and
 * Laplacian and Taubin smoothing (Taubin, "A signal processing approach to
 * fair surface design", SIGGRAPH 1995) as baselines.
 *
 * Work is split into a fixed number of chunks of vertices (or faces) taken
 * by threads; every vertex writes only its own slots and per-chunk sums are
 * added in chunk order, so the result is the same for any thread count. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "fusion/areaflow.h"
#include "geom/geom.h"
#include "core/par.h"

void fct_areaflow_params_default(struct fct_areaflow_params *p)
{
	p->method = FCT_SMOOTH_AREAFLOW;
	p->lambda = -1;
	p->guide = -1;
	p->iterations = -1;
	p->max_iterations = 10;
	p->tol = 0.02;
	p->window = 2.5;
	p->sigma = 1.5;
	p->delta = 0.3;
	p->crease = 1;
	p->lap_lambda = 0.5;
	p->taubin_mu = -0.53;
	p->threads = 0;
	p->rings = 8;
	p->passes = 5;
	p->vote_rings = 8;
	p->crease_lo = 0.05;
	p->crease_hi = 0.15;
	p->along_ray = 0;
	p->origin[0] = p->origin[1] = p->origin[2] = 0;
}

/* Eq. (3) ---------------------------------------------------------------- */

/* The sums A and B of eq. (3) for one umbrella triangle (v, p1, p2). */
static inline void step_terms(const double v[3], const double p1[3], const double p2[3],
                              const double n[3], double *A, double *B)
{
	double a[3], b[3], d[3];
	fct_v3_sub(a, p1, v);
	fct_v3_sub(b, p2, v);
	fct_v3_sub(d, a, b);
	double an = fct_v3_dot(a, n), bn = fct_v3_dot(b, n), dn = fct_v3_dot(d, n);
	*A += bn * fct_v3_dot(a, d) - an * fct_v3_dot(b, d);
	*B += fct_v3_dot(d, d) - dn * dn;
}

/* The same with the tangential shape of the triangle taken from another
 * copy of it (v', p1', p2'): eq. (3) is linear in the heights along n,
 * A = sum (b.n) (a_t.d_t) - (a.n) (b_t.d_t) and B = sum |d_t|^2 with _t the
 * parts across n, i.e. a weighted umbrella Laplacian along n whose weights
 * come from the tangential shape alone.  On a range mesh whose noise is
 * comparable to its edges that shape is noise too (obtuse and folded
 * triangles give negative weights); taking it from a smoothed copy keeps
 * the minimiser of eq. (2) for the heights the mesh has. */
static inline void step_terms_shape(const double v[3], const double p1[3], const double p2[3],
                                    const double sv[3], const double s1[3], const double s2[3],
                                    const double n[3], double *A, double *B)
{
	double a[3], b[3], at[3], bt[3], d[3];
	fct_v3_sub(a, p1, v);
	fct_v3_sub(b, p2, v);
	fct_v3_sub(at, s1, sv);
	fct_v3_sub(bt, s2, sv);
	fct_v3_axpy(at, at, -fct_v3_dot(at, n), n);
	fct_v3_axpy(bt, bt, -fct_v3_dot(bt, n), n);
	fct_v3_sub(d, at, bt);
	*A += fct_v3_dot(b, n) * fct_v3_dot(at, d) - fct_v3_dot(a, n) * fct_v3_dot(bt, d);
	*B += fct_v3_dot(d, d);
}

static inline double step_solve(double A, double B, double lambda, double dvn)
{
	double den = B + lambda;
	if (!(den > 0) || !isfinite(den))
		return 0;
	double l = (A - lambda * dvn) / den;
	return isfinite(l) ? l : 0;
}

double fct_areaflow_step(const double v[3], const double v0[3], const double n[3],
                         const double *ring, size_t ntri, double lambda)
{
	double A = 0, B = 0, dv[3];
	for (size_t i = 0; i < ntri; i++)
		step_terms(v, ring + 6 * i, ring + 6 * i + 3, n, &A, &B);
	fct_v3_sub(dv, v, v0);
	return step_solve(A, B, lambda, fct_v3_dot(dv, n));
}

/* Eq. (4) ---------------------------------------------------------------- */

static void normalize_or(double v[3], const double *fallback)
{
	double len = sqrt(fct_v3_dot(v, v));
	if (len > 0 && isfinite(len)) {
		v[0] /= len, v[1] /= len, v[2] /= len;
		return;
	}
	if (fallback) {
		double f[3] = { fallback[0], fallback[1], fallback[2] };
		double fl = sqrt(fct_v3_dot(f, f));
		if (fl > 0 && isfinite(fl)) {
			v[0] = f[0] / fl, v[1] = f[1] / fl, v[2] = f[2] / fl;
			return;
		}
	}
	v[0] = 0, v[1] = 0, v[2] = 1;
}

/* A unit eigenvector of t's eigenvalue l1 (see fct_sym3_eigen); scale is
 * the sum of the eigenvalues' magnitudes. */
static void eigvec1(const double t[6], double l1, double scale, const double *hint, double e1[3])
{
	double a00 = t[0], a01 = t[1], a02 = t[2], a11 = t[3], a12 = t[4], a22 = t[5];
	/* e1 spans the null space of M = t - l1 I: the largest cross product of
	 * two of M's rows when its rank is 2. */
	double r0[3] = { a00 - l1, a01, a02 }, r1[3] = { a01, a11 - l1, a12 };
	double r2[3] = { a02, a12, a22 - l1 };
	double c[3][3];
	fct_v3_cross(c[0], r0, r1);
	fct_v3_cross(c[1], r0, r2);
	fct_v3_cross(c[2], r1, r2);
	double best = 0;
	int bi = -1;
	for (int i = 0; i < 3; i++) {
		double d = fct_v3_dot(c[i], c[i]);
		if (d > best) best = d, bi = i;
	}
	if (bi >= 0 && best > 1e-18 * scale * scale * scale * scale && isfinite(best)) {
		double len = sqrt(best);
		for (int k = 0; k < 3; k++)
			e1[k] = c[bi][k] / len;
		return;
	}
	/* l1 repeated: its eigenspace is orthogonal to M's largest row (or is
	 * everything when M vanishes); take hint's part in it. */
	double h[3] = { 0, 0, 1 };
	if (hint)
		h[0] = hint[0], h[1] = hint[1], h[2] = hint[2];
	const double *rows[3] = { r0, r1, r2 };
	double rb = 0;
	int ri = -1;
	for (int i = 0; i < 3; i++) {
		double d = fct_v3_dot(rows[i], rows[i]);
		if (d > rb) rb = d, ri = i;
	}
	if (ri >= 0 && rb > 1e-18 * scale * scale && isfinite(rb)) {
		double rl = sqrt(rb), u[3] = { rows[ri][0] / rl, rows[ri][1] / rl, rows[ri][2] / rl };
		double hu = fct_v3_dot(h, u);
		fct_v3_axpy(e1, h, -hu, u);
		/* hint along the row: any unit vector orthogonal to it */
		double other[3] = { fabs(u[0]) < 0.6 ? 1 : 0, fabs(u[0]) < 0.6 ? 0 : 1, 0 };
		double o[3];
		fct_v3_cross(o, u, other);
		normalize_or(e1, o);
		return;
	}
	normalize_or(h, NULL);
	e1[0] = h[0], e1[1] = h[1], e1[2] = h[2];
}

void fct_sym3_eigen(const double t[6], double nu[3], double e1[3], const double *hint)
{
	double a00 = t[0], a01 = t[1], a02 = t[2], a11 = t[3], a12 = t[4], a22 = t[5];
	double p1 = a01 * a01 + a02 * a02 + a12 * a12;
	double q = (a00 + a11 + a22) / 3;
	double b00 = a00 - q, b11 = a11 - q, b22 = a22 - q;
	double p2 = b00 * b00 + b11 * b11 + b22 * b22 + 2 * p1;
	double l1, l2, l3;
	int closed = p2 > 0 && isfinite(p2);
	if (!closed) {
		l1 = l2 = l3 = isfinite(q) ? q : 0;
	} else {
		double p = sqrt(p2 / 6);
		double c00 = b00 / p, c11 = b11 / p, c22 = b22 / p;
		double c01 = a01 / p, c02 = a02 / p, c12 = a12 / p;
		double det = c00 * (c11 * c22 - c12 * c12) - c01 * (c01 * c22 - c12 * c02) +
		             c02 * (c01 * c12 - c11 * c02);
		double r = det / 2;
		r = r < -1 ? -1 : r > 1 ? 1 : r;
		double phi = acos(r) / 3;
		l1 = q + 2 * p * cos(phi);
		l3 = q + 2 * p * cos(phi + 2.0943951023931954923);
		l2 = 3 * q - l1 - l3;
		if (l2 > l1) { double s = l1; l1 = l2; l2 = s; }
		if (l3 > l2) { double s = l2; l2 = l3; l3 = s; }
		if (l2 > l1) { double s = l1; l1 = l2; l2 = s; }
	}
	eigvec1(t, l1, fabs(l1) + fabs(l2) + fabs(l3), hint, e1);
	/* The closed form keeps only half the digits of an eigenvalue that is
	 * (nearly) repeated, which the two smaller ones are on a plane (T of
	 * rank one): take them from t restricted to the plane across e1, a 2x2
	 * problem that keeps them to rounding. */
	if (closed) {
		double ax[3] = { 0, 0, 0 }, u[3], w[3], tu[3], tw[3];
		int k = fabs(e1[0]) <= fabs(e1[1]) ? (fabs(e1[0]) <= fabs(e1[2]) ? 0 : 2)
		                                   : (fabs(e1[1]) <= fabs(e1[2]) ? 1 : 2);
		ax[k] = 1;
		fct_v3_cross(u, e1, ax);
		double ul = sqrt(fct_v3_dot(u, u));
		if (ul > 0) {
			u[0] /= ul, u[1] /= ul, u[2] /= ul;
			fct_v3_cross(w, e1, u);
			tu[0] = t[0] * u[0] + t[1] * u[1] + t[2] * u[2];
			tu[1] = t[1] * u[0] + t[3] * u[1] + t[4] * u[2];
			tu[2] = t[2] * u[0] + t[4] * u[1] + t[5] * u[2];
			tw[0] = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
			tw[1] = t[1] * w[0] + t[3] * w[1] + t[4] * w[2];
			tw[2] = t[2] * w[0] + t[4] * w[1] + t[5] * w[2];
			double a = fct_v3_dot(u, tu), b = fct_v3_dot(u, tw), c = fct_v3_dot(w, tw);
			double m = (a + c) / 2, h = (a - c) / 2, r = sqrt(h * h + b * b);
			l2 = m + r, l3 = m - r;
			if (l2 > l1)
				l1 = l2;
		}
	}
	nu[0] = l1, nu[1] = l2, nu[2] = l3;
}

/* Accumulates the votes of eq. (4) at one vertex. */
struct vote {
	double t[6];    /* xx xy xz yy yz zz */
	double nbar[3];
	double wsum;
};

/* The vote of the face with centroid p and unit normal n, weight mu, at q:
 * n transported along the arc from p to q, in the plane of n and pq, whose
 * tangent at p is perpendicular to n: n' = 2 (n.w) w / |w|^2 - n, the
 * reflection of n about the chord's perpendicular w in that plane.  With
 * w = (pq x n) x pq = |pq|^2 n - (pq.n) pq that is n' = n - 2 (pq.n) pq /
 * |pq|^2 for any length of n (the reflection in the plane across the
 * chord), without a square root. */
static inline void vote_add(struct vote *vt, const double q[3], const double p[3],
                            const double n[3], double mu)
{
	double pq[3], c[3], nn[3];
	fct_v3_sub(pq, q, p);
	fct_v3_cross(c, pq, n);
	if (fct_v3_dot(c, c) > 0) {
		double a = 2 * fct_v3_dot(pq, n) / fct_v3_dot(pq, pq);
		nn[0] = n[0] - a * pq[0], nn[1] = n[1] - a * pq[1], nn[2] = n[2] - a * pq[2];
	} else {
		/* p at q, or pq along n: no arc to follow */
		nn[0] = n[0], nn[1] = n[1], nn[2] = n[2];
	}
	vt->t[0] += mu * nn[0] * nn[0];
	vt->t[1] += mu * nn[0] * nn[1];
	vt->t[2] += mu * nn[0] * nn[2];
	vt->t[3] += mu * nn[1] * nn[1];
	vt->t[4] += mu * nn[1] * nn[2];
	vt->t[5] += mu * nn[2] * nn[2];
	vt->nbar[0] += mu * nn[0];
	vt->nbar[1] += mu * nn[1];
	vt->nbar[2] += mu * nn[2];
	vt->wsum += mu;
}

static double vote_strength(const struct vote *vt, double delta)
{
	if (!(vt->wsum > 0) || !isfinite(vt->wsum))
		return 0;
	double nu[3], e1[3], nb[3];
	for (int k = 0; k < 3; k++)
		nb[k] = vt->nbar[k] / vt->wsum;
	fct_sym3_eigen(vt->t, nu, e1, nb);
	if (!(nu[0] > 0) || !isfinite(nu[0]))
		return 0;
	if (fabs(fct_v3_dot(nb, e1)) < delta)
		return 1;
	double s = (nu[1] - nu[2]) / nu[0];
	return s > 0 ? (s < 1 ? s : 1) : 0;
}

/* The noise-aware ramp: (s - crease_lo) / (crease_hi - crease_lo) held to
 * [0, 1]; s itself when crease_hi <= crease_lo. */
static double ramp(const struct fct_areaflow_params *p, double s)
{
	if (!(p->crease_hi > p->crease_lo))
		return s;
	s = (s - p->crease_lo) / (p->crease_hi - p->crease_lo);
	return s > 0 ? (s < 1 ? s : 1) : 0;
}

double fct_crease_strength(const double q[3], const double *p, const double *n,
                           const double *mu, size_t m, double delta)
{
	struct vote vt;
	memset(&vt, 0, sizeof vt);
	for (size_t i = 0; i < m; i++)
		if (mu[i] > 0)
			vote_add(&vt, q, p + 3 * i, n + 3 * i, mu[i]);
	return vote_strength(&vt, delta);
}

/* Threads ---------------------------------------------------------------- */

enum { GUIDE_PASSES = 5 };
#define GUIDE_RATIO 0.93

enum { NCHUNK = 256, MAX_EXPAND = 64, NCOLOR = 64, WIN_NONE = 255, WIN_MAX = 254,
       MAX_VOTES = 64 /* bound of M: the first faces of the walk, nearest rings first */ };

struct flow;
typedef void chunk_fn(struct flow *F, int tid, size_t lo, size_t hi, int chunk);

/* Per-thread scratch of the window gathering. */
struct scratch {
	uint32_t *vstamp, *fstamp, *queue;
	uint32_t stamp;
};

struct flow {
	struct fct_mesh *m;
	const struct fct_adj *adj;
	const struct fct_areaflow_params *p;
	double *cur, *next;       /* positions */
	const double *x0;         /* input positions */
	double *fn, *fc;          /* unit face normals (0 for no area), centroids */
	double *fa;               /* face area vectors (twice the area) */
	double *g;                /* smoothed face area vectors (rings passes) */
	double *vn;               /* smoothed unit vertex normals */
	double *sm, *sm2;         /* Laplacian-smoothed copies (passes) */
	const double *shape;      /* the smoothed copy of this iteration (passes) */
	double *s;                /* crease strength */
	double *ft, *vt9;         /* diffused tensors and normals (vote_rings) */
	unsigned char *held;      /* 1: does not move */
	uint32_t *order;          /* moving vertices by colour */
	size_t color_start[NCOLOR + 1], color_lo;
	uint32_t *corner;         /* parallel to adj->vert_f: v's corner in that face */
	uint32_t *nbr, *nbr_start;  /* vertex neighbours (Laplacian) */
	double lambda_abs, radius2, sigma2, factor;
	double part[NCHUNK];
	double partmax[NCHUNK];
	/* The window cache (crease_chunk): per vertex, the faces its walk
	 * accepted beyond the umbrella (wacc of them, in walk order) and those
	 * it examined and turned away (wrej), at woff in its chunk's buffer
	 * wbuf; wacc == WIN_NONE: not cached (the walk is done every time). */
	int win_want;             /* the crease is computed more than once: cache */
	int wacc_built;           /* the cache holds the first pass's walks */
	struct fct_areaflow_stats *st;
	int win_build;            /* this pass records the walks (later ones
	                           * record a changed walk where it fits) */
	uint32_t *wbuf[NCHUNK];
	size_t wlen[NCHUNK], wcap[NCHUNK];
	int wfail[NCHUNK];        /* out of memory: that chunk is not cached */
	uint32_t *woff;
	unsigned char *wacc, *wrej;
	size_t wwalk[NCHUNK];     /* cached vertices walked again in the last pass */
	int nthreads;
	struct scratch sc[FCT_PAR_MAX];
};

struct job {
	struct flow *F;
	chunk_fn *fn;
	size_t n;
};

static void job_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	struct job *j = ctx;
	j->fn(j->F, worker, lo, hi, (int)fct_par_chunk_of(j->n, NCHUNK, lo));
}

/* Run fn over [0, n) in NCHUNK chunks (par.h) on F->nthreads threads; fn
 * gets its chunk's index for per-chunk sums, added in chunk order. */
static void run(struct flow *F, chunk_fn *fn, size_t n)
{
	struct job j = { F, fn, n };
	memset(F->part, 0, sizeof F->part);
	memset(F->partmax, 0, sizeof F->partmax);
	fct_par_run(F->nthreads, n, NCHUNK, job_chunk, &j);
}

static double sum_parts(const double *part)
{
	double s = 0;
	for (int c = 0; c < NCHUNK; c++)
		s += part[c];
	return s;
}

/* Per-iteration geometry -------------------------------------------------- */

static void faces_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	const struct fct_mesh *m = F->m;
	const double *x = F->cur;
	for (size_t f = lo; f < hi; f++) {
		uint32_t b = m->fstart[f], k = m->fstart[f + 1] - b;
		double a[3] = { 0, 0, 0 }, c[3] = { 0, 0, 0 };
		for (uint32_t i = 0; i < k; i++) {
			const double *p = x + 3 * (size_t)m->fvert[b + i];
			const double *q = x + 3 * (size_t)m->fvert[b + (i + 1 == k ? 0 : i + 1)];
			/* Newell: the vector area, exact for triangles */
			a[0] += (p[1] - q[1]) * (p[2] + q[2]);
			a[1] += (p[2] - q[2]) * (p[0] + q[0]);
			a[2] += (p[0] - q[0]) * (p[1] + q[1]);
			fct_v3_add(c, c, p);
		}
		double *fa = F->fa + 3 * f, *fn = F->fn + 3 * f, *fc = F->fc + 3 * f;
		double len = sqrt(fct_v3_dot(a, a));
		for (int j = 0; j < 3; j++) {
			fa[j] = isfinite(len) ? a[j] : 0;
			fn[j] = len > 0 && isfinite(len) ? a[j] / len : 0;
			fc[j] = k ? c[j] / k : 0;
		}
	}
}

/* Ring averaging of w <= 9 numbers per face or vertex, by which the normal
 * smoothing and the diffused vote widen their reach a ring per pair of
 * passes.  To vertices: the mean over the vertex's faces; to faces: the
 * mean over the face's corners. */
/* Always inlined, and the sum unrolled: with w a constant the 3-wide pass
 * is as fast as one written for 3 (rolled, it cost 8% of the flow on the
 * 640x480 room). */
static inline __attribute__((always_inline)) void
mean_to_vertices(const struct flow *F, const double *face_val, double *vert_val, int w, size_t lo, size_t hi)
{
	const struct fct_adj *A = F->adj;
	for (size_t v = lo; v < hi; v++) {
		double a[9];
		for (int j = 0; j < w; j++)
			a[j] = 0;
		uint32_t b = A->vert_fstart[v], e = A->vert_fstart[v + 1];
		for (uint32_t i = b; i < e; i++) {
			const double *t = face_val + (size_t)w * A->vert_f[i];
#pragma GCC unroll 9
			for (int j = 0; j < w; j++)
				a[j] += t[j];
		}
		double k = e > b ? 1.0 / (double)(e - b) : 0;
		for (int j = 0; j < w; j++)
			vert_val[(size_t)w * v + (size_t)j] = a[j] * k;
	}
}

static inline __attribute__((always_inline)) void
mean_to_faces(const struct flow *F, const double *vert_val, double *face_val, int w, size_t lo, size_t hi)
{
	const struct fct_mesh *m = F->m;
	for (size_t f = lo; f < hi; f++) {
		uint32_t b = m->fstart[f], k = m->fstart[f + 1] - b;
		double a[9];
		for (int j = 0; j < w; j++)
			a[j] = 0;
		for (uint32_t i = 0; i < k; i++) {
			const double *t = vert_val + (size_t)w * m->fvert[b + i];
#pragma GCC unroll 9
			for (int j = 0; j < w; j++)
				a[j] += t[j];
		}
		for (int j = 0; j < w; j++)
			face_val[(size_t)w * f + (size_t)j] = k ? a[j] / k : 0;
	}
}

/* The normal smoothing: vn = the mean of g over the faces of the vertex
 * (unnormalised: area vectors add up to the vector area of the region,
 * whose direction is the region's normal however noisy its triangles
 * are), then g = the mean of vn over the corners of the face. */
static void vsmooth_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	mean_to_vertices(F, F->g, F->vn, 3, lo, hi);
}

static void fsmooth_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	mean_to_faces(F, F->vn, F->g, 3, lo, hi);
}

/* Unit smoothed normals: face normals (for the vote) from g, vertex normals
 * (the direction of the step) from vn. */
static void fnormal_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	for (size_t f = lo; f < hi; f++) {
		double *g = F->g + 3 * f, *n = F->fn + 3 * f, len = sqrt(fct_v3_dot(g, g));
		for (int j = 0; j < 3; j++)
			n[j] = len > 0 && isfinite(len) ? g[j] / len : 0;
	}
}

static void vnormal_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	for (size_t v = lo; v < hi; v++) {
		double *n = F->vn + 3 * v, len = sqrt(fct_v3_dot(n, n));
		for (int j = 0; j < 3; j++)
			n[j] = len > 0 && isfinite(len) ? n[j] / len : 0;
	}
}

/* Eq. (4) at every vertex: the faces of the geodesic window are gathered by
 * a breadth-first walk from the vertex through the vertices of faces whose
 * centroid is within the radius; the distance is the straight one to the
 * centroid, which is the geodesic one up to the curvature over the window,
 * while the walk keeps to the surface connected to the vertex.  The walk
 * stops after MAX_VOTES votes (M is bounded; the walk visits the rings
 * nearest the vertex first), which bounds the cost on noisy meshes whose
 * edge lengths are mostly noise.
 *
 * The topology never changes and the vertices move little, so the first
 * pass records each walk (the faces it accepted and those it examined and
 * turned away) and later passes replay it: a replay that finds every
 * accepted face still within the radius with a normal and every turned-away
 * face still outside is the walk the positions of this pass would take,
 * face for face, so its votes are the same in the same order; otherwise
 * the vertex is walked again.  The result is exactly the walk's, only
 * cheaper.  A walk with a face of no normal in it, or more than WIN_MAX
 * faces of either kind, is not recorded. */

/* The walk from v at q, voting into vt.  When acc and rej are not NULL
 * the accepted faces beyond the umbrella and the turned-away ones are
 * recorded there (WIN_MAX at most); returns 0 when the walk was recorded
 * (or not asked to be), -1 when it cannot be. */
static int walk(struct flow *F, struct scratch *sc, size_t v, const double q[3],
                struct vote *vt, uint32_t *acc, size_t *nacc, uint32_t *rej, size_t *nrej)
{
	const struct fct_mesh *m = F->m;
	const struct fct_adj *A = F->adj;
	int rec = acc != NULL, ok = 1;
	size_t na = 0, nr = 0;
	if (++sc->stamp == 0) {
		memset(sc->vstamp, 0, sizeof *sc->vstamp * m->nv);
		memset(sc->fstamp, 0, sizeof *sc->fstamp * (m->nf ? m->nf : 1));
		sc->stamp = 1;
	}
	uint32_t st = sc->stamp;
	size_t head = 0, tail = 0, votes = 0;
	sc->queue[tail++] = (uint32_t)v;
	sc->vstamp[v] = st;
	while (head < tail && votes < MAX_VOTES) {
		uint32_t u = sc->queue[head++];
		for (uint32_t i = A->vert_fstart[u]; i < A->vert_fstart[u + 1]; i++) {
			uint32_t f = A->vert_f[i];
			if (sc->fstamp[f] == st)
				continue;
			sc->fstamp[f] = st;
			const double *c = F->fc + 3 * (size_t)f;
			double d2 = fct_v3_dist2(c, q);
			if (!(d2 <= F->radius2) && u != v) {
				if (rec && ok) {
					if (nr < WIN_MAX)
						rej[nr++] = f;
					else
						ok = 0;
				}
				continue;   /* the umbrella always votes (M > I) */
			}
			const double *n = F->fn + 3 * (size_t)f;
			if (n[0] != 0 || n[1] != 0 || n[2] != 0) {
				vote_add(vt, q, c, n, exp(-d2 / F->sigma2));
				votes++;
			} else {
				ok = 0;
			}
			if (rec && ok && u != v) {
				if (na < WIN_MAX)
					acc[na++] = f;
				else
					ok = 0;
			}
			if (m->fstart[f + 1] - m->fstart[f] > MAX_EXPAND)
				continue;   /* no walk through huge polygons (quadratic) */
			for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++) {
				uint32_t x = m->fvert[k];
				if (sc->vstamp[x] != st) {
					sc->vstamp[x] = st;
					sc->queue[tail++] = x;
				}
			}
		}
	}
	if (rec) {
		*nacc = na;
		*nrej = nr;
	}
	return ok ? 0 : -1;
}

/* The recorded walk of v replayed at q (rec: nacc faces accepted, then
 * nrej turned away): 0 with its votes in vt, or -1 when this pass's walk
 * would differ (vt is then to be discarded). */
static int replay(const struct flow *F, size_t v, const double q[3], struct vote *vt,
                  const uint32_t *rec, size_t nacc, size_t nrej)
{
	const struct fct_adj *A = F->adj;
	for (uint32_t i = A->vert_fstart[v]; i < A->vert_fstart[v + 1]; i++) {
		uint32_t f = A->vert_f[i];
		const double *c = F->fc + 3 * (size_t)f, *n = F->fn + 3 * (size_t)f;
		if (n[0] == 0 && n[1] == 0 && n[2] == 0)
			return -1;
		vote_add(vt, q, c, n, exp(-fct_v3_dist2(c, q) / F->sigma2));
	}
	for (size_t i = 0; i < nrej; i++)
		if (fct_v3_dist2(F->fc + 3 * (size_t)rec[nacc + i], q) <= F->radius2)
			return -1;
	for (size_t i = 0; i < nacc; i++) {
		uint32_t f = rec[i];
		const double *c = F->fc + 3 * (size_t)f, *n = F->fn + 3 * (size_t)f;
		double d2 = fct_v3_dist2(c, q);
		if (!(d2 <= F->radius2) || (n[0] == 0 && n[1] == 0 && n[2] == 0))
			return -1;
		vote_add(vt, q, c, n, exp(-d2 / F->sigma2));
	}
	return 0;
}

static void crease_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	const struct fct_adj *A = F->adj;
	struct scratch *sc = &F->sc[tid];
	double sum = 0;
	size_t walked = 0;
	uint32_t acc[WIN_MAX], rej[WIN_MAX];
	for (size_t v = lo; v < hi; v++) {
		if (A->vert_fstart[v] == A->vert_fstart[v + 1]) {
			F->s[v] = 0;
			continue;
		}
		const double *q = F->cur + 3 * v;
		struct vote vt;
		memset(&vt, 0, sizeof vt);
		if (F->win_build) {
			size_t na = 0, nr = 0;
			F->wacc[v] = WIN_NONE;
			struct fct_err e;
			int ok = walk(F, sc, v, q, &vt, acc, &na, rej, &nr) == 0;
			if (ok && na + nr == 0) {
				F->woff[v] = 0;   /* the umbrella alone */
				F->wacc[v] = F->wrej[v] = 0;
			} else if (ok && !F->wfail[chunk]) {
				if (F->wlen[chunk] + na + nr > UINT32_MAX ||   /* offsets are 32 bits */
				    fct_grow((void **)&F->wbuf[chunk], &F->wcap[chunk], F->wlen[chunk] + na + nr,
				             sizeof *acc, &e)) {
					F->wfail[chunk] = 1;   /* the rest of the chunk walks every time */
				} else {
					uint32_t *w = F->wbuf[chunk] + F->wlen[chunk];
					memcpy(w, acc, sizeof *acc * na);
					memcpy(w + na, rej, sizeof *rej * nr);
					F->woff[v] = (uint32_t)F->wlen[chunk];
					F->wacc[v] = (unsigned char)na;
					F->wrej[v] = (unsigned char)nr;
					F->wlen[chunk] += na + nr;
				}
			}
		} else if (F->wacc && F->wacc[v] != WIN_NONE) {
			uint32_t *w = F->wbuf[chunk] ? F->wbuf[chunk] + F->woff[v] : NULL;
			size_t room = (size_t)F->wacc[v] + F->wrej[v], na = 0, nr = 0;
			if (replay(F, v, q, &vt, w, F->wacc[v], F->wrej[v])) {
				/* walked again, and recorded in place when the new walk
				 * fits the old one's room: a record is good for any
				 * positions its faces agree with */
				memset(&vt, 0, sizeof vt);
				if (walk(F, sc, v, q, &vt, acc, &na, rej, &nr) == 0 && na + nr <= room) {
					if (na + nr > 0) {
						memcpy(w, acc, sizeof *acc * na);
						memcpy(w + na, rej, sizeof *rej * nr);
					}
					F->wacc[v] = (unsigned char)na;
					F->wrej[v] = (unsigned char)nr;
				}
				walked++;
			}
		} else {
			walk(F, sc, v, q, &vt, NULL, NULL, NULL, NULL);
		}
		double s = ramp(F->p, vote_strength(&vt, F->p->delta));
		F->s[v] = s;
		sum += s;
	}
	F->part[chunk] = sum;
	F->wwalk[chunk] = walked;
}

/* The other two corners of the i-th face of vertex v (vert_f[i]; a polygon:
 * v's neighbours there). */
static inline void corner_ring(const struct flow *F, uint32_t i, uint32_t *p1, uint32_t *p2)
{
	const struct fct_mesh *m = F->m;
	uint32_t f = F->adj->vert_f[i], b = m->fstart[f], k = m->fstart[f + 1] - b;
	uint32_t j = F->corner[i];
	*p1 = m->fvert[b + (j + 1 == k ? 0 : j + 1)];
	*p2 = m->fvert[b + (j == 0 ? k - 1 : j - 1)];
}

/* One step of eq. (3), scaled by exp(-5 s), at the vertices order[lo..hi)
 * of the colour being swept, in place: no two vertices of one colour share
 * a face, so each sees its neighbours as the earlier colours left them
 * (Gauss-Seidel), whatever the thread count.  The normal is the
 * area-weighted normal of the umbrella as it is at that moment; with
 * passes, the smoothed copy's normal, and eq. (3)'s weights come from the
 * copy's umbrella shape (step_terms_shape). */
static void flow_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid;
	const struct fct_adj *A = F->adj;
	double *x = F->cur;
	double sum = 0;
	for (size_t k = lo; k < hi; k++) {
		size_t v = F->order[F->color_lo + k];
		double *p = x + 3 * v;
		double n[3] = { 0, 0, 0 };
		for (uint32_t i = A->vert_fstart[v]; i < A->vert_fstart[v + 1]; i++) {
			uint32_t p1, p2;
			double a[3], b[3], c[3];
			corner_ring(F, i, &p1, &p2);
			fct_v3_sub(a, x + 3 * (size_t)p1, p);
			fct_v3_sub(b, x + 3 * (size_t)p2, p);
			fct_v3_cross(c, a, b);
			fct_v3_add(n, n, c);
		}
		/* an umbrella of no area stays, whatever normal the guide gives */
		if (!(fct_v3_dot(n, n) > 0))
			continue;
		if (F->p->rings > 0 || F->p->passes > 0)
			n[0] = F->vn[3 * v], n[1] = F->vn[3 * v + 1], n[2] = F->vn[3 * v + 2];
		double len = sqrt(fct_v3_dot(n, n));
		if (!(len > 0) || !isfinite(len))
			continue;   /* no normal: the vertex stays */
		n[0] /= len, n[1] /= len, n[2] /= len;
		double a = 0, b = 0, dv[3], hlo = 0, hhi = 0;
		int first = 1;
		for (uint32_t i = A->vert_fstart[v]; i < A->vert_fstart[v + 1]; i++) {
			uint32_t p1, p2;
			corner_ring(F, i, &p1, &p2);
			double h1 = fct_v3_dot(x + 3 * (size_t)p1, n) - fct_v3_dot(p, n);
			double h2 = fct_v3_dot(x + 3 * (size_t)p2, n) - fct_v3_dot(p, n);
			if (first)
				hlo = hhi = h1, first = 0;
			hlo = fmin(hlo, fmin(h1, h2));
			hhi = fmax(hhi, fmax(h1, h2));
			if (F->p->passes > 0)
				step_terms_shape(p, x + 3 * (size_t)p1, x + 3 * (size_t)p2, F->shape + 3 * v,
				                 F->shape + 3 * (size_t)p1, F->shape + 3 * (size_t)p2, n, &a, &b);
			else
				step_terms(p, x + 3 * (size_t)p1, x + 3 * (size_t)p2, n, &a, &b);
		}
		fct_v3_sub(dv, p, F->x0 + 3 * v);
		double l = step_solve(a, b, F->lambda_abs, fct_v3_dot(dv, n));
		/* eq. (3) is a weighted mean of the neighbours' heights along n
		 * (and of -dv.n, by lambda); with negative weights (obtuse or
		 * folded triangles) it can leave their range and, swept again,
		 * run away: held to the range, a no-op when no weight is negative */
		double back = -fct_v3_dot(dv, n);
		if (F->lambda_abs > 0)
			hlo = fmin(hlo, back), hhi = fmax(hhi, back);
		l = l < hlo ? hlo : l > hhi ? hhi : l;
		if (F->p->crease)
			l *= exp(-5 * F->s[v]);
		double q[3];
		if (F->p->along_ray) {
			/* along the sensor's ray through the vertex, as far as makes
			 * the move along n equal to l (|n.r| at least 0.2) */
			double r[3];
			fct_v3_sub(r, p, F->p->origin);
			double rl = sqrt(fct_v3_dot(r, r)), c = rl > 0 ? fct_v3_dot(r, n) / rl : 0;
			if (!(rl > 0) || !isfinite(c)) {
				fct_v3_axpy(q, p, l, n);
			} else {
				c = fabs(c) < 0.2 ? (c < 0 ? -0.2 : 0.2) : c;
				fct_v3_axpy(q, p, l / (c * rl), r);
			}
		} else {
			fct_v3_axpy(q, p, l, n);
		}
		if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]))
			continue;
		p[0] = q[0], p[1] = q[1], p[2] = q[2];
		sum += fabs(l);
	}
	F->part[chunk] += sum;
}

/* Colours for the Gauss-Seidel sweep: greedy in vertex order, the smallest
 * colour no earlier vertex sharing a face has; vertices that find all
 * NCOLOR - 1 colours taken get the last, swept on one thread in order.
 * order lists the moving vertices by colour, then index. */
static int build_colours(struct flow *F, struct fct_err *err)
{
	const struct fct_mesh *m = F->m;
	const struct fct_adj *A = F->adj;
	unsigned char *col = fct_alloc_array(m->nv, 1, err);
	F->order = fct_alloc_array(m->nv, sizeof *F->order, err);
	if (!col || !F->order) {
		free(col);
		return -1;
	}
	size_t count[NCOLOR];
	memset(count, 0, sizeof count);
	for (size_t v = 0; v < m->nv; v++) {
		uint64_t used = 0;
		for (uint32_t i = A->vert_fstart[v]; i < A->vert_fstart[v + 1]; i++) {
			uint32_t f = A->vert_f[i];
			for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++) {
				uint32_t u = m->fvert[k];
				if (u < v)
					used |= (uint64_t)1 << col[u];
			}
		}
		int c = 0;
		while (c < NCOLOR - 1 && (used >> c & 1))
			c++;
		col[v] = (unsigned char)c;
		if (!F->held[v])
			count[c]++;
	}
	size_t at = 0;
	for (int c = 0; c < NCOLOR; c++) {
		F->color_start[c] = at;
		at += count[c];
	}
	F->color_start[NCOLOR] = at;
	size_t fill[NCOLOR];
	memcpy(fill, F->color_start, sizeof fill);
	for (size_t v = 0; v < m->nv; v++)
		if (!F->held[v])
			F->order[fill[col[v]]++] = (uint32_t)v;
	free(col);
	return 0;
}

/* One umbrella-Laplacian step with factor F->factor into F->next. */
static void laplace_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid;
	const double *x = F->cur;
	double sum = 0;
	for (size_t v = lo; v < hi; v++) {
		const double *p = x + 3 * v;
		double *o = F->next + 3 * v;
		o[0] = p[0], o[1] = p[1], o[2] = p[2];
		uint32_t b = F->nbr_start[v], e = F->nbr_start[v + 1];
		if (b == e)
			continue;
		double c[3] = { 0, 0, 0 };
		for (uint32_t i = b; i < e; i++)
			fct_v3_add(c, c, x + 3 * (size_t)F->nbr[i]);
		double d[3], q[3];
		for (int k = 0; k < 3; k++)
			d[k] = c[k] / (double)(e - b) - p[k];
		fct_v3_axpy(q, p, F->factor, d);
		if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]))
			continue;
		o[0] = q[0], o[1] = q[1], o[2] = q[2];
		sum += sqrt(fct_v3_dist2(q, p));
	}
	F->part[chunk] = sum;
}

/* Distances from the input: sum, sum over moving vertices, max. */
static void offset_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid;
	double sum = 0, mx = 0;
	for (size_t v = lo; v < hi; v++) {
		double d = sqrt(fct_v3_dist2(F->cur + 3 * v, F->x0 + 3 * v));
		sum += d;
		if (d > mx)
			mx = d;
	}
	F->part[chunk] = sum;
	F->partmax[chunk] = mx;
}

/* The driver -------------------------------------------------------------- */

static int alloc_doubles(double **p, size_t n, size_t k, struct fct_err *err)
{
	size_t c;
	if (fct_mul_size(n ? n : 1, k, &c))
		return fct_fail(err, "too many elements (%zu)", n);
	*p = fct_alloc_array(c, sizeof **p, err);
	return *p ? 0 : -1;
}

static int build_neighbours(struct flow *F, struct fct_err *err)
{
	const struct fct_adj *A = F->adj;
	size_t nv = F->m->nv;
	F->nbr_start = fct_alloc_array(nv + 1, sizeof *F->nbr_start, err);
	F->nbr = fct_alloc_array(2 * A->ne, sizeof *F->nbr, err);
	if (!F->nbr_start || !F->nbr)
		return -1;
	memset(F->nbr_start, 0, sizeof *F->nbr_start * (nv + 1));
	for (size_t e = 0; e < A->ne; e++) {
		F->nbr_start[A->edge_v[2 * e] + 1]++;
		F->nbr_start[A->edge_v[2 * e + 1] + 1]++;
	}
	for (size_t v = 0; v < nv; v++)
		F->nbr_start[v + 1] += F->nbr_start[v];
	uint32_t *fill = fct_alloc_array(nv, sizeof *fill, err);
	if (!fill)
		return -1;
	memcpy(fill, F->nbr_start, sizeof *fill * nv);
	for (size_t e = 0; e < A->ne; e++) {
		uint32_t a = A->edge_v[2 * e], b = A->edge_v[2 * e + 1];
		F->nbr[fill[a]++] = b;
		F->nbr[fill[b]++] = a;
	}
	free(fill);
	return 0;
}

/* F->corner: faces are listed at each vertex in increasing order, once
 * each, so walking the faces in order fills each vertex's list in order. */
static int build_corners(struct flow *F, struct fct_err *err)
{
	const struct fct_mesh *m = F->m;
	const struct fct_adj *A = F->adj;
	size_t n = A->vert_fstart[m->nv];
	uint32_t *fill = fct_alloc_array(m->nv, sizeof *fill, err);
	F->corner = fct_alloc_array(n, sizeof *F->corner, err);
	if (!fill || !F->corner) {
		free(fill);
		return -1;
	}
	memcpy(fill, A->vert_fstart, sizeof *fill * m->nv);
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t j = 0; j < m->fstart[f + 1] - m->fstart[f]; j++) {
			uint32_t v = m->fvert[m->fstart[f] + j];
			if (fill[v] > A->vert_fstart[v] && A->vert_f[fill[v] - 1] == f)
				continue;   /* v repeated in f: its first corner */
			if (fill[v] >= A->vert_fstart[v + 1] || A->vert_f[fill[v]] != f)
				abort();
			F->corner[fill[v]++] = j;
		}
	free(fill);
	return 0;
}

static int scratch_alloc(struct flow *F, struct fct_err *err)
{
	size_t nv = F->m->nv, nf = F->m->nf;
	for (int t = 0; t < F->nthreads; t++) {
		struct scratch *sc = &F->sc[t];
		sc->vstamp = calloc(nv ? nv : 1, sizeof *sc->vstamp);
		sc->fstamp = calloc(nf ? nf : 1, sizeof *sc->fstamp);
		sc->queue = fct_alloc_array(nv, sizeof *sc->queue, err);
		sc->stamp = 0;
		if (!sc->vstamp || !sc->fstamp || !sc->queue)
			return fct_fail(err, "out of memory for the voting windows of %zu vertices", nv);
	}
	return 0;
}

static void flow_free(struct flow *F)
{
	free(F->next);
	free(F->fn);
	free(F->fc);
	free(F->fa);
	free(F->g);
	free(F->vn);
	free(F->sm);
	free(F->sm2);
	free(F->s);
	free(F->ft);
	free(F->vt9);
	free(F->held);
	free(F->nbr);
	free(F->nbr_start);
	free(F->corner);
	free(F->order);
	for (int c = 0; c < NCHUNK; c++)
		free(F->wbuf[c]);
	free(F->woff);
	free(F->wacc);
	free(F->wrej);
	for (int t = 0; t < FCT_PAR_MAX; t++) {
		free(F->sc[t].vstamp);
		free(F->sc[t].fstamp);
		free(F->sc[t].queue);
	}
}

/* The crease vote by diffusion (vote_rings): every face's tensor n n^T and
 * normal n (9 numbers), averaged to the vertices, back to the faces, ... */
static void tinit_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	for (size_t f = lo; f < hi; f++) {
		const double *n = F->fn + 3 * f;
		double *t = F->ft + 9 * f;
		t[0] = n[0] * n[0], t[1] = n[0] * n[1], t[2] = n[0] * n[2];
		t[3] = n[1] * n[1], t[4] = n[1] * n[2], t[5] = n[2] * n[2];
		t[6] = n[0], t[7] = n[1], t[8] = n[2];
	}
}

static void tvert_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	mean_to_vertices(F, F->ft, F->vt9, 9, lo, hi);
}

static void tface_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid, (void)chunk;
	mean_to_faces(F, F->vt9, F->ft, 9, lo, hi);
}

static double vote_strength(const struct vote *vt, double delta);

static void tcrease_chunk(struct flow *F, int tid, size_t lo, size_t hi, int chunk)
{
	(void)tid;
	double sum = 0;
	for (size_t v = lo; v < hi; v++) {
		const double *t = F->vt9 + 9 * v;
		struct vote vt;
		memcpy(vt.t, t, sizeof vt.t);
		memcpy(vt.nbar, t + 6, sizeof vt.nbar);
		vt.wsum = t[0] + t[3] + t[5];
		double s = ramp(F->p, vote_strength(&vt, F->p->delta));
		F->s[v] = s;
		sum += s;
	}
	F->part[chunk] = sum;
}

/* Face geometry, vertex normals and (when needed) crease strength of the
 * current positions; returns the mean s over vertices with faces. */
static double geometry(struct flow *F, int want_crease, size_t nwith)
{
	double *save = F->cur, *save_next = F->next;
	if (F->p->passes > 0) {
		/* normals (and vote positions) of a Laplacian-smoothed copy */
		memcpy(F->sm, save, sizeof *F->sm * 3 * F->m->nv);
		F->cur = F->sm;
		F->next = F->sm2;
		F->factor = 0.5;
		for (int i = 0; i < F->p->passes; i++) {
			run(F, laplace_chunk, F->m->nv);
			double *t = F->cur; F->cur = F->next; F->next = t;
		}
		F->shape = F->cur;
	}
	run(F, faces_chunk, F->m->nf);
	memcpy(F->g, F->fa, sizeof *F->g * 3 * F->m->nf);
	for (int r = 0; r < F->p->rings; r++) {
		run(F, vsmooth_chunk, F->m->nv);
		run(F, fsmooth_chunk, F->m->nf);
	}
	run(F, vsmooth_chunk, F->m->nv);
	run(F, vnormal_chunk, F->m->nv);
	run(F, fnormal_chunk, F->m->nf);
	double ms = 0;
	if (want_crease) {
		if (F->p->vote_rings > 0) {
			run(F, tinit_chunk, F->m->nf);
			for (int r = 0; r < F->p->vote_rings; r++) {
				run(F, tvert_chunk, F->m->nv);
				run(F, tface_chunk, F->m->nf);
			}
			run(F, tvert_chunk, F->m->nv);
			run(F, tcrease_chunk, F->m->nv);
			F->cur = save;
			F->next = save_next;
			return nwith ? sum_parts(F->part) / (double)nwith : 0;
		}
		F->win_build = F->win_want && !F->wacc_built;
		run(F, crease_chunk, F->m->nv);
		ms = nwith ? sum_parts(F->part) / (double)nwith : 0;
		if (F->win_build) {
			F->wacc_built = 1;
			F->win_build = 0;
			for (int c = 0; c < NCHUNK; c++) {
				/* to size: the cache stays for the whole run */
				uint32_t *t = F->wlen[c] ? realloc(F->wbuf[c], sizeof *t * F->wlen[c]) : NULL;
				if (t)
					F->wbuf[c] = t, F->wcap[c] = F->wlen[c];
				F->st->window_ids += F->wlen[c];
			}
		} else {
			for (int c = 0; c < NCHUNK; c++)
				F->st->window_walks += F->wwalk[c];
		}
	}
	F->cur = save;
	F->next = save_next;
	return ms;
}

/* The median length of the edges at positions x (0 with none). */
static int median_edge(const struct fct_adj *adj, const double *x, double *out, struct fct_err *err)
{
	double *el = NULL;
	if (alloc_doubles(&el, adj->ne, 1, err))
		return -1;
	size_t nel = 0;
	for (size_t e = 0; e < adj->ne; e++) {
		double d = sqrt(fct_v3_dist2(x + 3 * (size_t)adj->edge_v[2 * e],
		                             x + 3 * (size_t)adj->edge_v[2 * e + 1]));
		if (isfinite(d))
			el[nel++] = d;
	}
	*out = nel ? fct_select_kth(el, nel, nel / 2) : 0;
	free(el);
	return 0;
}

/* The arrays every method needs; x0, the input positions, is the
 * caller's to free.  F->cur starts on the mesh's own positions. */
static int flow_alloc(struct flow *F, double **x0, struct fct_err *err)
{
	const struct fct_mesh *m = F->m;
	if (alloc_doubles(x0, m->nv, 3, err) || alloc_doubles(&F->next, m->nv, 3, err) ||
	    alloc_doubles(&F->fn, m->nf, 3, err) || alloc_doubles(&F->fc, m->nf, 3, err) ||
	    alloc_doubles(&F->fa, m->nf, 3, err) || alloc_doubles(&F->g, m->nf, 3, err) ||
	    alloc_doubles(&F->vn, m->nv, 3, err) ||
	    alloc_doubles(&F->sm, m->nv, 3, err) || alloc_doubles(&F->sm2, m->nv, 3, err) ||
	    alloc_doubles(&F->s, m->nv, 1, err) ||
	    !(F->held = fct_alloc_array(m->nv, 1, err)))
		return -1;
	F->x0 = *x0;
	if (m->nv)
		memcpy(*x0, m->xyz, sizeof **x0 * 3 * m->nv);
	memset(F->s, 0, sizeof *F->s * (m->nv ? m->nv : 1));
	F->cur = m->xyz;
	return 0;
}

/* The guide left to us (guide < 0; areaflow.h): on when GUIDE_PASSES
 * Laplacian passes shorten the median edge below GUIDE_RATIO of the
 * input's (edge), i.e. when the noise is more than about half the sample
 * spacing. */
static int choose_guide(struct flow *F, struct fct_areaflow_params *pv, double edge,
                        struct fct_err *err)
{
	const struct fct_mesh *m = F->m;
	if (build_neighbours(F, err))
		return -1;
	memcpy(F->sm, m->xyz, sizeof *F->sm * 3 * m->nv);
	double *save = F->cur, *save_next = F->next;
	F->cur = F->sm, F->next = F->sm2, F->factor = 0.5;
	for (int i = 0; i < GUIDE_PASSES; i++) {
		run(F, laplace_chunk, m->nv);
		double *t = F->cur; F->cur = F->next; F->next = t;
	}
	double se;
	int fail = median_edge(F->adj, F->cur, &se, err);
	F->cur = save, F->next = save_next;
	if (fail)
		return -1;
	F->st->edge_ratio = se / edge;
	pv->guide = F->st->edge_ratio < GUIDE_RATIO;
	return 0;
}

/* What the method and the guide imply for the other options. */
static void settle_params(struct fct_areaflow_params *pv, struct fct_areaflow_stats *st)
{
	if (pv->method == FCT_SMOOTH_AREAFLOW && pv->guide == 0) {
		/* the paper's own: no guide, eq. (4) over the window walk */
		pv->passes = pv->rings = pv->vote_rings = 0;
		pv->crease_lo = pv->crease_hi = 0;
		pv->along_ray = 0;
		if (pv->lambda < 0)
			pv->lambda = 1;
	}
	if (pv->lambda < 0)
		pv->lambda = 0;
	st->guide = pv->method == FCT_SMOOTH_AREAFLOW && pv->guide != 0;
}

/* F->held: the vertices that do not move, those without faces and, in
 * the area flow, those on a non-manifold edge; their counts into the
 * stats.  Returns the vertices with faces. */
static size_t hold_vertices(struct flow *F)
{
	const struct fct_adj *adj = F->adj;
	struct fct_areaflow_stats *st = F->st;
	size_t nv = F->m->nv, nwith = 0;
	for (size_t v = 0; v < nv; v++) {
		int has = adj->vert_fstart[v] < adj->vert_fstart[v + 1];
		nwith += has;
		st->isolated += !has;
		F->held[v] = !has;
	}
	if (F->p->method == FCT_SMOOTH_AREAFLOW)
		for (size_t e = 0; e < adj->ne; e++)
			if (fct_adj_edge_nfaces(adj, e) > 2)
				F->held[adj->edge_v[2 * e]] = F->held[adj->edge_v[2 * e + 1]] = 1;
	for (size_t v = 0; v < nv; v++)
		st->moving += !F->held[v];
	st->held = nv - st->moving - st->isolated;
	return nwith;
}

/* The tables the method and options use, each only when used: corners
 * and colours (the area flow), the voting windows (the crease by the
 * window walk), the window cache (that crease computed twice or more in
 * maxit iterations and the crease asked for, crease_out), and the
 * neighbours (Laplacian, Taubin, smoothed copies). */
static int flow_tables(struct flow *F, int maxit, int crease_out, struct fct_err *err)
{
	const struct fct_areaflow_params *p = F->p;
	size_t nv = F->m->nv;
	int flow = p->method == FCT_SMOOTH_AREAFLOW;
	if (flow && (build_corners(F, err) || build_colours(F, err)))
		return -1;
	if (((flow && p->crease) || crease_out) && p->vote_rings <= 0 && scratch_alloc(F, err))
		return -1;
	F->win_want = flow && p->crease && p->vote_rings <= 0 && maxit + crease_out >= 2;
	if (F->win_want &&
	    (!(F->woff = fct_alloc_array(nv, sizeof *F->woff, err)) ||
	     !(F->wacc = fct_alloc_array(nv, 1, err)) || !(F->wrej = fct_alloc_array(nv, 1, err))))
		return -1;
	if ((p->method == FCT_SMOOTH_LAPLACIAN || p->method == FCT_SMOOTH_TAUBIN || p->passes > 0) &&
	    !F->nbr && build_neighbours(F, err))
		return -1;
	return 0;
}

/* One iteration of the area flow (eq. (4)): the geometry and crease of the
 * current positions, then the vertices moved colour by colour (the last,
 * crowded colour in order on one thread); returns the summed move. */
static double flow_sweep(struct flow *F, size_t nwith)
{
	double ms = geometry(F, F->p->crease, nwith);
	if (F->p->crease)
		F->st->mean_crease = ms;
	double moved = 0;
	for (int c = 0; c < NCOLOR; c++) {
		F->color_lo = F->color_start[c];
		int nt = F->nthreads;
		if (c == NCOLOR - 1)
			F->nthreads = 1;
		if (F->color_start[c + 1] > F->color_start[c]) {
			run(F, flow_chunk, F->color_start[c + 1] - F->color_start[c]);
			moved += sum_parts(F->part);
		}
		F->nthreads = nt;
	}
	return moved;
}

/* One Laplacian pass, or Taubin's two (lambda, then mu); returns the
 * summed move of the last. */
static double laplace_sweep(struct flow *F)
{
	const struct fct_areaflow_params *p = F->p;
	F->factor = p->lap_lambda;
	run(F, laplace_chunk, F->m->nv);
	double moved = sum_parts(F->part);
	if (p->method == FCT_SMOOTH_TAUBIN) {
		double *t = F->cur; F->cur = F->next; F->next = t;
		F->factor = p->taubin_mu;
		run(F, laplace_chunk, F->m->nv);
		moved = sum_parts(F->part);
	}
	double *t = F->cur; F->cur = F->next; F->next = t;
	return moved;
}

/* maxit iterations, or (iterations < 0) until the mean move falls below
 * tol median edges. */
static void iterate(struct flow *F, int maxit, double edge, size_t nwith)
{
	const struct fct_areaflow_params *p = F->p;
	struct fct_areaflow_stats *st = F->st;
	for (int it = 0; it < maxit; it++) {
		double moved = p->method == FCT_SMOOTH_AREAFLOW ? flow_sweep(F, nwith) : laplace_sweep(F);
		st->iterations = it + 1;
		st->last_move = st->moving ? moved / (double)st->moving : 0;
		if (p->iterations < 0 && st->last_move < p->tol * edge)
			break;
	}
}

/* The result into the mesh, the crease strength of the result into crease
 * (when not NULL), and the offsets from the input into the stats. */
static void write_result(struct flow *F, double *crease, size_t nwith)
{
	struct fct_mesh *m = F->m;
	struct fct_areaflow_stats *st = F->st;
	if (F->cur != m->xyz) {
		memcpy(m->xyz, F->cur, sizeof *m->xyz * 3 * m->nv);
		F->next = F->cur;     /* the buffer we own */
		F->cur = m->xyz;
	}
	if (crease) {
		st->mean_crease = geometry(F, 1, nwith);
		memcpy(crease, F->s, sizeof *crease * m->nv);
	}
	run(F, offset_chunk, m->nv);
	st->mean_offset = st->moving ? sum_parts(F->part) / (double)st->moving : 0;
	for (int c = 0; c < NCHUNK; c++)
		if (F->partmax[c] > st->max_offset)
			st->max_offset = F->partmax[c];
}

int fct_areaflow(struct fct_mesh *m, const struct fct_areaflow_params *pin, double *crease,
                 struct fct_areaflow_stats *st, struct fct_err *err)
{
	struct fct_areaflow_params pv = *pin;
	const struct fct_areaflow_params *p = &pv;
	struct fct_areaflow_stats dummy;
	if (!st)
		st = &dummy;
	memset(st, 0, sizeof *st);
	for (size_t i = 0; i < 3 * m->nv; i++)
		if (!isfinite(m->xyz[i]))
			return fct_fail(err, "vertex %zu: coordinate is not finite", i / 3);
	if (m->nv > UINT32_MAX - 1)
		return fct_fail(err, "too many vertices (%zu)", m->nv);

	struct flow F;
	memset(&F, 0, sizeof F);
	struct fct_adj adj;
	memset(&adj, 0, sizeof adj);
	F.m = m;
	F.p = p;
	F.st = st;
	F.adj = &adj;
	F.nthreads = fct_par_threads(p->threads);
	st->threads = (size_t)F.nthreads;
	int rc = -1;
	double *x0 = NULL;
	if (fct_adj_build(&adj, m, err) || flow_alloc(&F, &x0, err))
		goto out;
	/* Median edge length of the input: the unit of lambda, window and
	 * sigma (the median, as the long edges across depth jumps and grazing
	 * surfaces of range meshes would inflate a mean). */
	double edge;
	if (median_edge(&adj, m->xyz, &edge, err))
		goto out;
	if (p->method == FCT_SMOOTH_AREAFLOW && p->guide < 0 && edge > 0 &&
	    choose_guide(&F, &pv, edge, err))
		goto out;
	settle_params(&pv, st);
	if (p->vote_rings > 0 && (alloc_doubles(&F.ft, m->nf, 9, err) ||
	                          alloc_doubles(&F.vt9, m->nv, 9, err)))
		goto out;
	st->edge = edge;
	F.lambda_abs = p->lambda * edge * edge;
	F.radius2 = p->window * edge * p->window * edge;
	F.sigma2 = p->sigma * edge * p->sigma * edge;
	if (!(F.sigma2 > 0))
		F.sigma2 = 1;
	size_t nwith = hold_vertices(&F);
	int maxit = p->iterations >= 0 ? p->iterations : p->max_iterations;
	if (!(edge > 0))
		maxit = 0;   /* no edge of any length: nothing can move */
	if (flow_tables(&F, maxit, crease != NULL, err))
		goto out;
	iterate(&F, maxit, edge, nwith);
	write_result(&F, crease, nwith);
	rc = 0;
out:
	/* every failure comes before the first move, so m is unchanged */
	free(x0);
	flow_free(&F);
	fct_adj_free(&adj);
	return rc;
}

void fct_vertex_normals(const struct fct_mesh *m, double *vn)
{
	memset(vn, 0, sizeof *vn * 3 * m->nv);
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t b = m->fstart[f], k = m->fstart[f + 1] - b;
		double a[3] = { 0, 0, 0 };
		for (uint32_t i = 0; i < k; i++) {
			const double *p = m->xyz + 3 * (size_t)m->fvert[b + i];
			const double *q = m->xyz + 3 * (size_t)m->fvert[b + (i + 1 == k ? 0 : i + 1)];
			a[0] += (p[1] - q[1]) * (p[2] + q[2]);
			a[1] += (p[2] - q[2]) * (p[0] + q[0]);
			a[2] += (p[0] - q[0]) * (p[1] + q[1]);
		}
		for (uint32_t i = 0; i < k; i++) {
			double *n = vn + 3 * (size_t)m->fvert[b + i];
			fct_v3_add(n, n, a);
		}
	}
	for (size_t v = 0; v < m->nv; v++) {
		double *n = vn + 3 * v, len = sqrt(fct_v3_dot(n, n));
		for (int j = 0; j < 3; j++)
			n[j] = len > 0 && isfinite(len) ? n[j] / len : 0;
	}
}
