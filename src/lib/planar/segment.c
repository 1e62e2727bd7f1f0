/* segment.c - planar segmentation by global region growing (see segment.h):
 * Kang, Johnson and Szeliski (DEC CRL 95/7), section 2 and eq. 1; the
 * area-weighted fit answers section 7's uneven vertex density.
 *
 * Memory, for a mesh of F faces and E ~ 1.5 F adjacent face pairs:
 *   region[F]   central moments of each patch, kept at its union-find root
 *   parent[F]   union-find (a negative entry is a root: minus its face count)
 *   pair[E]     the adjacent face pairs (after phase 1: the distinct pairs
 *               of adjacent patches)
 *   queue       at most one entry per pair
 * No adjacency list is kept or merged: a queued pair names two faces, and
 * their current patches are found through the union-find when it is popped,
 * so a merge costs O(1) whatever the size of the patches. */
#include "planar/segment.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "core/arena.h"
#include "core/clock.h"
#include "core/unionfind.h"
#include "io/noise.h"

/* Around a non-manifold edge of more faces, only consecutive ones are paired. */
#define MAX_ALL_PAIRS 8
/* Phase 1 clusters: at most this many faces, and a mean squared residual
 * at most CLUSTER_FIT^2 in units of the points' noise (see cost1). */
#define CLUSTER_FACES 64
#define CLUSTER_FIT 2.0
/* Faces narrower than this many times their noise are no plane's evidence
 * (see narrow). */
#define PEEL_ROUNDS 2
/* Fits and peels to make the guarantee hold (see finish). */
#define FINAL_ROUNDS 4
/* Rounding in the moments is of the order of 1e-16 times the scatter's
 * trace: an increase of the residual below 64 times that is no increase. */
#define ROUNDING 1.4e-14
/* Upper bound on the fresh passes of the automatic criterion. */
#define MAX_SWEEPS 64

struct region {
	double w;        /* total weight: each point's 1 / sigma^2 */
	double n;        /* points (corners, or area in mean face areas) */
	double c[3];     /* weighted centroid */
	double s[6];     /* central scatter: xx yy zz xy yz xz */
	double sse;      /* smallest eigenvalue of s: chi^2, the squared residuals in units of noise */
	double va[3];    /* vector area: the sum of its faces' (which way the patch faces) */
};

/* A queued pair is a 64-bit key: its cost as the bits of a non-negative
 * float in the high half (they order as the floats do), the pair's index in
 * the low half, so keys are unique and ties go to the lower index. */
typedef uint64_t qkey;

/* A monotone priority queue: a radix heap (Ahuja, Mehlhorn, Orlin and
 * Tarjan, 1990).  Every key pushed is above the last one popped (a pair is
 * pushed back only when its cost grew), which is all a radix heap needs:
 * bucket i > 0 holds the keys whose cost's highest bit differing from the
 * last popped cost is bit i - 1, bucket 0 those of equal cost (in order),
 * and a key only ever moves to a lower bucket, so it costs O(1) amortised
 * per bit of the cost and the buckets are scanned sequentially (a binary
 * heap of a million pairs spends its time in cache misses).  In front of
 * it, the next FRONT least keys wait in a small sorted array while the
 * data of their pairs is prefetched a few pops ahead: the pops jump all
 * over the mesh, and the time goes in waiting for memory, which is better
 * spent in parallel.  Keys pushed below the last one the buckets gave up go
 * into the front array, in order. */
#define FRONT 32

struct rheap {
	qkey *b[33];
	size_t n[33], cap[33];
	int sorted0;                 /* b[0] is in decreasing order */
	uint64_t last;
	size_t size;                 /* in the buckets */
	qkey front[2 * FRONT];
	int head, nfront;            /* front[head .. nfront) */
};

struct seg {
	const struct fct_mesh *m;
	const struct fct_segment_params *p;
	struct region *region;
	int32_t *parent;
	uint32_t (*pair)[2];
	size_t npairs;
	uint32_t (*fpair)[2];    /* the adjacent face pairs, for finish */
	size_t nfpairs;
	struct rheap q;
	double *wv;              /* each vertex's weight, 1 / sigma^2 */
	double *isigma;          /* and 1 / sigma */
	double area_unit;        /* area weighting: a third of the mean face area */
	double floor2;           /* no noise below (1e-7 bounding-box diagonal)^2 */
	double round2;           /* squared distance rounding the coordinates can move a point */
	double max_ms, stop;     /* max_rms^2, factor^2 */
	double fit2;             /* fit^2: the largest mean chi^2 of a patch */
	int two_sided;           /* no viewpoint: a plane may be seen from both sides */
	size_t patches;
	unsigned char *dirty;    /* phase 2: the roots merged since the last refill */
	const struct region *face;   /* finish: each face's moments (face_moments) */
	double (*ray)[4];        /* finish with a viewpoint: each vertex's ray_terms */
	struct fct_segment_stats st;
	struct fct_err *err;
	struct fct_arena arena;  /* the run's scratch, freed at fct_segment's exit */
};

void fct_segment_params_default(struct fct_segment_params *p)
{
	p->target = 0;
	p->factor = FCT_SEGMENT_FACTOR;
	p->fit = FCT_SEGMENT_FIT;
	p->max_dev = FCT_SEGMENT_MAX_DEV;
	p->min_extent = FCT_SEGMENT_MIN_EXTENT;
	p->sigma = NULL;
	p->max_rms = HUGE_VAL;
	p->area_weighted = 0;
	p->min_faces = FCT_SEGMENT_MIN_FACES;
	p->use_viewpoint = 0;
	p->viewpoint[0] = p->viewpoint[1] = p->viewpoint[2] = 0;
}

/* Moments ----------------------------------------------------------------- */

/* r = a + b (parallel-axis rule); r may be a or b. */
static void region_add(struct region *r, const struct region *a, const struct region *b)
{
	double w = a->w + b->w;
	double d[3] = { b->c[0] - a->c[0], b->c[1] - a->c[1], b->c[2] - a->c[2] };
	double k = w > 0 ? a->w * b->w / w : 0;
	double t = w > 0 ? b->w / w : 0.5;
	double s[6] = {
		a->s[0] + b->s[0] + k * d[0] * d[0],
		a->s[1] + b->s[1] + k * d[1] * d[1],
		a->s[2] + b->s[2] + k * d[2] * d[2],
		a->s[3] + b->s[3] + k * d[0] * d[1],
		a->s[4] + b->s[4] + k * d[1] * d[2],
		a->s[5] + b->s[5] + k * d[0] * d[2],
	};
	for (int i = 0; i < 3; i++) {
		r->c[i] = a->c[i] + t * d[i];
		r->va[i] = a->va[i] + b->va[i];
	}
	memcpy(r->s, s, sizeof s);
	r->n = a->n + b->n;
	r->w = w;
}

/* The summed squared residual of the plane fitted to the union of a and b
 * (the smallest eigenvalue of its scatter); *trace gets the scatter's trace.
 * A residual that rounding the coordinates could make is 0: a
 * depth plateau of a quantising sensor is exactly flat in the camera's
 * frame and flat to the last bit in any other, and its unions must tie
 * (then the lower pair goes first) in every frame alike. */
static double union_sse(const struct seg *S, const struct region *a, const struct region *b,
                        double *trace)
{
	struct region u;
	region_add(&u, a, b);
	*trace = u.s[0] + u.s[1] + u.s[2];
	double l = fct_sym3_min_eigenvalue(u.s);
	return l > S->round2 * u.w ? l : 0;
}

/* The vector area of face f (its fan of triangles from corner 0): its
 * normal times its area, pointing the way its winding faces. */
static void face_vector_area(const struct fct_mesh *m, size_t f, double va[3])
{
	uint32_t s = m->fstart[f], n = m->fstart[f + 1] - s;
	va[0] = va[1] = va[2] = 0;
	if (n < 3)
		return;
	const double *o = &m->xyz[3 * (size_t)m->fvert[s]];
	for (uint32_t k = 1; k + 1 < n; k++) {
		const double *p1 = &m->xyz[3 * (size_t)m->fvert[s + k]];
		const double *p2 = &m->xyz[3 * (size_t)m->fvert[s + k + 1]];
		double u[3] = { p1[0] - o[0], p1[1] - o[1], p1[2] - o[2] };
		double v[3] = { p2[0] - o[0], p2[1] - o[1], p2[2] - o[2] };
		va[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
		va[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
		va[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
	}
}

/* Do vector areas a and b point more than TURNED_AWAY apart?  Both sides
 * of a board point 180 degrees apart; noise flips a face seen edge-on a
 * little past 90. */
#define TURNED_AWAY (2 * M_PI / 3)
static int turned_away(const double a[3], const double b[3])
{
	double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
	return dot < cos(TURNED_AWAY) * sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) *
	                                     (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
}

/* Do a and b face opposite ways?  Only asked of a mesh without a
 * viewpoint (S->two_sided): a fused scan holds both sides of a board or a
 * wall, parallel and closer than the noise allows a plane to tell apart,
 * and one patch of both would fold over itself in its plane.  A mesh seen
 * from one viewpoint faces it everywhere but where noise flips a face. */
static int opposed(const struct seg *S, const struct region *a, const struct region *b)
{
	return S->two_sided && turned_away(a->va, b->va);
}

/* The moments of face f: its corners, each weighted by its vertex's
 * 1 / sigma^2 (wv), or the area of its fan of triangles from corner 0 in
 * units of area_unit, weighted by the mean of its corners' weights. */
static void face_moments(struct region *r, const struct fct_mesh *m, size_t f, int area,
                         const double *wv, double area_unit)
{
	memset(r, 0, sizeof *r);
	uint32_t s = m->fstart[f], n = m->fstart[f + 1] - s;
	if (n == 0)
		return;
	double va[3];
	face_vector_area(m, f, va);
	const double *o = &m->xyz[3 * (size_t)m->fvert[s]];
	if (!area || n < 3) {
		/* Corners relative to the first, for precision. */
		double c[3] = { 0, 0, 0 }, w = 0;
		for (uint32_t k = 0; k < n; k++) {
			uint32_t v = m->fvert[s + k];
			const double *p = &m->xyz[3 * (size_t)v];
			for (int i = 0; i < 3; i++)
				c[i] += wv[v] * (p[i] - o[i]);
			w += wv[v];
		}
		for (int i = 0; i < 3; i++)
			c[i] /= w;
		for (uint32_t k = 0; k < n; k++) {
			uint32_t v = m->fvert[s + k];
			const double *p = &m->xyz[3 * (size_t)v];
			double d[3] = { p[0] - o[0] - c[0], p[1] - o[1] - c[1], p[2] - o[2] - c[2] };
			double x = wv[v];
			r->s[0] += x * d[0] * d[0], r->s[1] += x * d[1] * d[1], r->s[2] += x * d[2] * d[2];
			r->s[3] += x * d[0] * d[1], r->s[4] += x * d[1] * d[2], r->s[5] += x * d[0] * d[2];
		}
		for (int i = 0; i < 3; i++)
			r->c[i] = o[i] + c[i];
		r->w = area ? 0 : w;
		r->n = area ? 0 : n;
		r->sse = n > 3 ? fmax(0, fct_sym3_min_eigenvalue(r->s)) : 0;
		memcpy(r->va, va, sizeof va);
		return;
	}
	double wmean = 0;
	for (uint32_t k = 0; k < n; k++)
		wmean += wv[m->fvert[s + k]];
	wmean /= n;
	/* Area: a triangle of area A, centroid g and corners v_k has
	 * integral (x - g)(x - g)^T dA = A/12 sum_k (v_k - g)(v_k - g)^T. */
	int first = 1;
	for (uint32_t k = 1; k + 1 < n; k++) {
		const double *p1 = &m->xyz[3 * (size_t)m->fvert[s + k]];
		const double *p2 = &m->xyz[3 * (size_t)m->fvert[s + k + 1]];
		double u[3] = { p1[0] - o[0], p1[1] - o[1], p1[2] - o[2] };
		double v[3] = { p2[0] - o[0], p2[1] - o[1], p2[2] - o[2] };
		double x[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
		struct region t;
		t.n = 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / area_unit;
		t.w = t.n * wmean;
		t.sse = 0;
		double g[3] = { (u[0] + v[0]) / 3, (u[1] + v[1]) / 3, (u[2] + v[2]) / 3 };
		double q[3][3] = {
			{ -g[0], -g[1], -g[2] },
			{ u[0] - g[0], u[1] - g[1], u[2] - g[2] },
			{ v[0] - g[0], v[1] - g[1], v[2] - g[2] },
		};
		memset(t.s, 0, sizeof t.s);
		for (int j = 0; j < 3; j++) {
			const double *d = q[j];
			t.s[0] += d[0] * d[0], t.s[1] += d[1] * d[1], t.s[2] += d[2] * d[2];
			t.s[3] += d[0] * d[1], t.s[4] += d[1] * d[2], t.s[5] += d[0] * d[2];
		}
		for (int i = 0; i < 6; i++)
			t.s[i] *= t.w / 12;
		for (int i = 0; i < 3; i++)
			t.c[i] = g[i];
		if (first)
			*r = t, first = 0;
		else
			region_add(r, r, &t);
	}
	for (int i = 0; i < 3; i++)
		r->c[i] += o[i];
	r->sse = n > 3 ? fmax(0, fct_sym3_min_eigenvalue(r->s)) : 0;
	memcpy(r->va, va, sizeof va);
}

/* Union-find -------------------------------------------------------------- */

/* Merge the patches of roots a and b, whose union has the summed squared
 * residual sse; returns the new root (the larger patch's, the lower index
 * on a tie). */
static uint32_t merge(struct seg *S, uint32_t a, uint32_t b, double sse)
{
	int32_t *parent = S->parent;
	if (parent[a] > parent[b] || (parent[a] == parent[b] && a > b)) {
		uint32_t t = a;
		a = b, b = t;
	}
	parent[a] += parent[b];
	parent[b] = (int32_t)a;
	region_add(&S->region[a], &S->region[a], &S->region[b]);
	S->region[a].sse = sse;
	S->patches--;
	if (S->dirty)
		S->dirty[a] = 1;
	return a;
}

/* Costs ------------------------------------------------------------------- */

/* Phase 1, clusters: the key of patches a and b is the chi^2 of their
 * union, which can only grow as a part grows, so a queued key is a lower
 * bound and the order is exactly greedy.  Returns the key, or -1 when the
 * pair is refused for good: a union of more than CLUSTER_FACES faces, of
 * rms above max_rms, or of mean chi^2 above CLUSTER_FIT^2 (its points lie
 * farther from one plane than their noise allows). */
static double cost1(struct seg *S, uint32_t a, uint32_t b, double *sse)
{
	const struct region *ra = &S->region[a], *rb = &S->region[b];
	if (-((int64_t)S->parent[a] + S->parent[b]) > CLUSTER_FACES)
		return -1;
	double tr, u = union_sse(S, ra, rb, &tr), w = ra->w + rb->w, n = ra->n + rb->n;
	S->st.evaluations++;
	*sse = u;
	if (u > S->max_ms * w || u > CLUSTER_FIT * CLUSTER_FIT * n || opposed(S, ra, rb))
		return -1;
	return u;
}

/* Does the union of a and b, of chi^2 u, stay a plane: mean chi^2 within
 * fit^2 and rms within max_rms? */
static int union_fits(const struct seg *S, const struct region *ra, const struct region *rb,
                      double u)
{
	if (u > S->max_ms * (ra->w + rb->w) || opposed(S, ra, rb))
		return 0;
	return S->p->target > 0 || u <= S->fit2 * (ra->n + rb->n);
}

/* Phase 2, patches: the key of patches a and b is how far, in mean square
 * and in units of the noise, the points of the smaller one move from its
 * own plane to the plane of the union:
 *     t = (chi^2(a u b) - chi^2(a) - chi^2(b)) / n_small.
 * *sse gets chi^2(a u b). */
static double cost2(struct seg *S, uint32_t a, uint32_t b, double *sse)
{
	const struct region *ra = &S->region[a], *rb = &S->region[b];
	double tr, u = union_sse(S, ra, rb, &tr);
	S->st.evaluations++;
	*sse = u;
	double inc = u - ra->sse - rb->sse - ROUNDING * tr - S->round2 * (ra->w + rb->w);
	double small = ra->n < rb->n ? ra->n : rb->n;
	if (!(inc > 0) || !(small > 0))
		return 0;
	return inc / small;
}

/* The queue --------------------------------------------------------------- */

/* The buckets go by the cost (the high half of a key) only: keys of equal
 * cost wait together in bucket 0, kept in decreasing order, and leave it
 * from the end. */
static int bucket_of(qkey x, qkey last)
{
	uint32_t a = (uint32_t)(x >> 32), b = (uint32_t)(last >> 32);
	return a == b ? 0 : 32 - __builtin_clz(a ^ b);
}

static int rh_add(struct seg *S, int i, qkey x)
{
	struct rheap *q = &S->q;
	if (q->n[i] == q->cap[i] &&
	    fct_grow((void **)&q->b[i], &q->cap[i], q->n[i] + 1, sizeof *q->b[i], S->err))
		return -1;
	q->b[i][q->n[i]++] = x;
	if (i == 0)
		q->sorted0 = 0;
	return 0;
}

static int key_desc(const void *x, const void *y)
{
	qkey a = *(const qkey *)x, b = *(const qkey *)y;
	return a < b ? 1 : a > b ? -1 : 0;
}

/* Pop the least key of the buckets into *x: 1 done, 0 empty, -1 out of
 * memory.  A bucket emptied by redistribution gives its memory back, so the
 * buckets hold no more than their entries and growth slack. */
static int rh_pop_bucket(struct seg *S, qkey *x)
{
	struct rheap *q = &S->q;
	if (q->size == 0)
		return 0;
	if (q->n[0] == 0) {
		int i = 1;
		while (q->n[i] == 0)
			i++;
		qkey min = q->b[i][0];
		for (size_t k = 1; k < q->n[i]; k++)
			if (q->b[i][k] < min)
				min = q->b[i][k];
		q->last = min;
		size_t n = q->n[i];
		q->n[i] = 0;
		for (size_t k = 0; k < n; k++)
			if (rh_add(S, bucket_of(q->b[i][k], min), q->b[i][k]))
				return -1;
		if (q->cap[i] > 4096) {
			free(q->b[i]);
			q->b[i] = NULL;
			q->cap[i] = 0;
		}
	}
	if (!q->sorted0) {
		qsort(q->b[0], q->n[0], sizeof *q->b[0], key_desc);
		q->sorted0 = 1;
	}
	*x = q->b[0][--q->n[0]];
	q->size--;
	return 1;
}

/* Queue pair i at cost key, which is above the last popped. */
static int rh_push(struct seg *S, float key, size_t i)
{
	struct rheap *q = &S->q;
	uint32_t bits;
	memcpy(&bits, &key, sizeof bits);
	qkey x = (qkey)bits << 32 | i;
	if (x < q->last) {
		/* Below what the buckets may hold: into the front, in order
		 * (it holds at most FRONT: one is pushed back per pop). */
		if (q->nfront == 2 * FRONT) {
			memmove(q->front, q->front + q->head, (size_t)(q->nfront - q->head) * sizeof *q->front);
			q->nfront -= q->head;
			q->head = 0;
		}
		int k = q->nfront++;
		while (k > q->head && q->front[k - 1] > x) {
			q->front[k] = q->front[k - 1];
			k--;
		}
		q->front[k] = x;
		return 0;
	}
	q->size++;
	int b = bucket_of(x, q->last);
	if (b == 0 && q->sorted0) {
		/* Bucket 0 stays in order: insert. */
		if (rh_add(S, 0, x))
			return -1;
		size_t k = q->n[0] - 1;
		while (k > 0 && q->b[0][k - 1] < x) {
			q->b[0][k] = q->b[0][k - 1];
			k--;
		}
		q->b[0][k] = x;
		q->sorted0 = 1;
		return 0;
	}
	return rh_add(S, b, x);
}

/* Prefetch stages for front entry k: its pair; its faces' parents; their
 * patches' moments (two cache lines each). */
static void fetch_parents(const struct seg *S, int k)
{
	const struct rheap *q = &S->q;
	if (k >= q->nfront)
		return;
	const uint32_t *pr = S->pair[(uint32_t)q->front[k]];
	__builtin_prefetch(&S->parent[pr[0]]);
	__builtin_prefetch(&S->parent[pr[1]]);
}

static void fetch_regions(const struct seg *S, int k)
{
	const struct rheap *q = &S->q;
	if (k >= q->nfront)
		return;
	const uint32_t *pr = S->pair[(uint32_t)q->front[k]];
	const char *a = (const char *)&S->region[fct_uf_root(S->parent, pr[0])];
	const char *b = (const char *)&S->region[fct_uf_root(S->parent, pr[1])];
	__builtin_prefetch(a);
	__builtin_prefetch(a + 64);
	__builtin_prefetch(b);
	__builtin_prefetch(b + 64);
}

/* Prefetch distances, in pops ahead. */
#define AHEAD_PARENTS 8
#define AHEAD_REGIONS 4

/* Pop the least key into *x: 1 done, 0 empty, -1 out of memory.  The front
 * is topped up from the buckets before it runs short, its new pairs
 * prefetched; each pop then fetches ahead the parents and the moments that
 * later pops will need, so that the memory of several pops is in flight at
 * once. */
static int rh_pop(struct seg *S, qkey *x)
{
	struct rheap *q = &S->q;
	if (q->nfront - q->head <= AHEAD_PARENTS && q->size > 0) {
		int live = q->nfront - q->head;
		memmove(q->front, q->front + q->head, (size_t)live * sizeof *q->front);
		q->head = 0, q->nfront = live;
		int r = 0;
		while (q->nfront < FRONT && (r = rh_pop_bucket(S, &q->front[q->nfront])) == 1)
			__builtin_prefetch(&S->pair[(uint32_t)q->front[q->nfront++]]);
		if (r < 0)
			return -1;
		if (live == 0) {
			for (int k = 0; k < AHEAD_PARENTS; k++)
				fetch_parents(S, k);
			for (int k = 0; k < AHEAD_REGIONS; k++)
				fetch_regions(S, k);
		}
	}
	if (q->head == q->nfront)
		return 0;
	fetch_parents(S, q->head + AHEAD_PARENTS);
	fetch_regions(S, q->head + AHEAD_REGIONS);
	*x = q->front[q->head++];
	return 1;
}

static void rh_clear(struct rheap *q)
{
	for (int i = 0; i < 33; i++)
		q->n[i] = 0;
	q->sorted0 = 1;
	q->last = 0;
	q->size = 0;
	q->head = q->nfront = 0;
}

static void rh_free(struct rheap *q)
{
	for (int i = 0; i < 33; i++)
		free(q->b[i]);
	memset(q, 0, sizeof *q);
}

static float key_of(qkey x)
{
	uint32_t bits = (uint32_t)(x >> 32);
	float f;
	memcpy(&f, &bits, sizeof f);
	return f;
}

/* Region growing ---------------------------------------------------------- */

/* Pop, cost again, push back when the cost grew, else merge, until the
 * queue is empty or a criterion stops it: phase 1 (clusters) or 2
 * (patches).  Returns the number of merges, or -1 when out of memory. */
static long grow(struct seg *S, int phase)
{
	long merges = 0, target = S->p->target;
	qkey x;
	int r;
	while ((r = rh_pop(S, &x)) == 1) {
		if (target > 0 && S->patches <= (size_t)target)
			break;
		size_t i = (uint32_t)x;
		uint32_t a = fct_uf_root(S->parent, S->pair[i][0]), b = fct_uf_root(S->parent, S->pair[i][1]);
		if (a == b)
			continue;
		double sse, cost;
		if (phase == 1) {
			if ((cost = cost1(S, a, b, &sse)) < 0)
				continue;   /* refused for good */
		} else {
			cost = cost2(S, a, b, &sse);
			if (!union_fits(S, &S->region[a], &S->region[b], sse))
				continue;   /* until a or b changes (the sweeps) */
		}
		if ((float)cost > key_of(x)) {
			S->st.repushes++;
			if (rh_push(S, (float)cost, i))
				return -1;
			continue;
		}
		if (phase == 2) {
			if (target <= 0 && cost > S->stop)
				break;   /* the cheapest merge is past the criterion */
			S->st.last_ratio = sqrt(cost);
		}
		merge(S, a, b, sse);
		merges++;
	}
	return r < 0 ? -1 : merges;
}

static int pair_cmp(const void *x, const void *y)
{
	const uint32_t *p = x, *q = y;
	if (p[0] != q[0])
		return p[0] < q[0] ? -1 : 1;
	return p[1] < q[1] ? -1 : p[1] > q[1];
}

/* Replace the pairs by the pairs of adjacent patches (their roots, lower
 * first); sorted and distinct when sort is set, so that a long boundary
 * between two patches becomes one pair. */
static void compact(struct seg *S, int sort)
{
	size_t n = 0;
	for (size_t i = 0; i < S->npairs; i++) {
		uint32_t a = fct_uf_root(S->parent, S->pair[i][0]), b = fct_uf_root(S->parent, S->pair[i][1]);
		if (a == b)
			continue;
		S->pair[n][0] = a < b ? a : b;
		S->pair[n][1] = a < b ? b : a;
		n++;
	}
	S->npairs = n;
	if (!sort)
		return;
	qsort(S->pair, n, sizeof *S->pair, pair_cmp);
	size_t k = 0;
	for (size_t i = 0; i < n; i++)
		if (k == 0 || pair_cmp(S->pair[i], S->pair[k - 1]))
			memcpy(S->pair[k++], S->pair[i], sizeof *S->pair);
	S->npairs = k;
}

/* Fill the queue afresh with the pairs of adjacent patches whose union
 * passes the criteria now (all of them when aiming at a target).  After
 * the first time, only pairs with a patch that has grown since the last
 * time are costed: the others were costed with these same patches, found
 * past the criterion, and still are. */
static int refill(struct seg *S, int first)
{
	compact(S, first);
	rh_clear(&S->q);
	for (size_t i = 0; i < S->npairs; i++) {
		uint32_t a = S->pair[i][0], b = S->pair[i][1];
		if (!first && !S->dirty[a] && !S->dirty[b])
			continue;
		double sse, t = cost2(S, a, b, &sse);
		if (!union_fits(S, &S->region[a], &S->region[b], sse) ||
		    (S->p->target <= 0 && t > S->stop))
			continue;
		if (rh_push(S, (float)t, i))
			return -1;
	}
	memset(S->dirty, 0, S->m->nf);
	return 0;
}

/* Absorb each patch of fewer than min_faces faces into the adjacent patch
 * of at least min_faces faces whose plane fits it best: the least mean
 * move t (as in phase 2), as long as the union still passes the tests of
 * phase 2 (t within factor^2, mean chi^2 within fit^2, rms within
 * max_rms); the host's plane is fitted again to the union.  Rounds until
 * none is absorbed: a small patch that no neighbour's plane fits stays
 * apart (finish may then call it free-form).  best and gain: scratch, F
 * each. */
static void absorb(struct seg *S, uint32_t *best, double *gain)
{
	size_t nf = S->m->nf;
	int32_t small = -(int32_t)(S->p->min_faces > INT32_MAX ? INT32_MAX : S->p->min_faces);
	for (;;) {
		compact(S, 1);
		for (size_t f = 0; f < nf; f++)
			best[f] = UINT32_MAX;
		int any = 0;
		for (size_t i = 0; i < S->npairs; i++) {
			uint32_t a = S->pair[i][0], b = S->pair[i][1];
			for (int side = 0; side < 2; side++) {
				uint32_t x = side ? b : a, y = side ? a : b;
				if (S->parent[x] <= small || S->parent[y] > small)
					continue;   /* x not small, or y not a host */
				const struct region *rx = &S->region[x], *ry = &S->region[y];
				double tr, u = union_sse(S, rx, ry, &tr);
				S->st.evaluations++;
				if (!union_fits(S, rx, ry, u) || !(rx->n > 0))
					continue;
				double t = (u - rx->sse - ry->sse) / rx->n;
				if (t > S->p->max_dev * S->p->max_dev)
					continue;
				if (best[x] == UINT32_MAX || t < gain[x] || (t == gain[x] && y < best[x])) {
					best[x] = y;
					gain[x] = t;
					any = 1;
				}
			}
		}
		if (!any)
			break;
		size_t done = 0;
		for (size_t x = 0; x < nf; x++) {
			if (best[x] == UINT32_MAX)
				continue;
			uint32_t a = fct_uf_root(S->parent, (uint32_t)x), b = fct_uf_root(S->parent, best[x]);
			if (a == b || S->parent[a] <= small)
				continue;   /* already absorbed, or grown past small */
			double tr, u = union_sse(S, &S->region[a], &S->region[b], &tr);
			if (!union_fits(S, &S->region[a], &S->region[b], u))
				continue;   /* the host took others this round */
			merge(S, a, b, u);
			S->st.absorbed++;
			done++;
		}
		if (!done)
			break;
	}
}

/* The pairs of adjacent faces, from the mesh's edges. */
static int build_pairs(struct seg *S, struct fct_err *err)
{
	struct fct_adj adj;
	if (fct_adj_build(&adj, S->m, err))
		return -1;
	size_t n = 0;
	for (size_t e = 0; e < adj.ne; e++) {
		size_t k = fct_adj_edge_nfaces(&adj, e);
		const uint32_t *fs = &adj.edge_f[adj.edge_fstart[e]];
		if (k <= MAX_ALL_PAIRS) {
			for (size_t i = 0; i < k; i++)
				for (size_t j = i + 1; j < k; j++)
					n += fs[i] != fs[j];
		} else {
			for (size_t i = 0; i + 1 < k; i++)
				n += fs[i] != fs[i + 1];
		}
	}
	if (n > UINT32_MAX) {
		fct_adj_free(&adj);
		return fct_fail(err, "segment: %zu adjacent face pairs, more than %u", n, (unsigned)UINT32_MAX);
	}
	S->pair = fct_alloc_array(n, sizeof *S->pair, err);
	if (!S->pair) {
		fct_adj_free(&adj);
		return -1;
	}
	size_t i = 0;
	for (size_t e = 0; e < adj.ne; e++) {
		size_t k = fct_adj_edge_nfaces(&adj, e);
		const uint32_t *fs = &adj.edge_f[adj.edge_fstart[e]];
		for (size_t x = 0; x < k; x++) {
			size_t end = k <= MAX_ALL_PAIRS ? k : x + 2 < k ? x + 2 : k;
			for (size_t y = x + 1; y < end; y++)
				if (fs[x] != fs[y]) {
					S->pair[i][0] = fs[x];
					S->pair[i][1] = fs[y];
					i++;
				}
		}
	}
	S->npairs = n;
	fct_adj_free(&adj);
	return 0;
}

/* The element of rank `rank` (from 0) of the n non-negative floats in v,
 * by radix selection on their bits (which order as unsigned integers);
 * count is scratch of 65536 entries. */
static float select_float(const float *v, size_t n, size_t rank, uint32_t *count)
{
	if (n == 0)
		return 0;
	uint32_t prefix = 0;
	for (int pass = 0; pass < 2; pass++) {
		memset(count, 0, 65536 * sizeof *count);
		for (size_t i = 0; i < n; i++) {
			uint32_t u;
			memcpy(&u, &v[i], sizeof u);
			if (pass == 1 && (u >> 16) != prefix)
				continue;
			count[pass ? u & 0xffff : u >> 16]++;
		}
		uint32_t b = 0;
		while (rank >= count[b])
			rank -= count[b++];
		prefix = pass ? (prefix << 16 | b) : b;
	}
	float x;
	memcpy(&x, &prefix, sizeof x);
	return x;
}

/* The plane of points p = o + s u (u unit rays from the viewpoint o, s the
 * distance along them) whose noise lies along the rays: such a plane is
 * a.(p - o) = 1, i.e. 1/s = a.u, linear in a, so least squares in 1/s has no
 * error in the variables (the orthogonal fit of eq. 1 is biased when the
 * noise is not isotropic: by a degree and more on small planes seen from
 * afar by a Kinect).  Constant weights suit noise that grows as s^2 (depth
 * sensors measure disparity).  q = {sum u u^T (6), sum u / s (3)}.  Replaces
 * pl's n and d and returns 1, or returns 0 (pl untouched) when the system is
 * too ill-conditioned to trust. */
static int ray_fit(struct fct_plane *pl, const double q[9], const double o[3])
{
	double a[3][3] = {
		{ q[0], q[3], q[5] },
		{ q[3], q[1], q[4] },
		{ q[5], q[4], q[2] },
	}, v[3][3], ev[3];
	fct_sym3_jacobi(v, ev, a);
	double hi = fmax(ev[0], fmax(ev[1], ev[2])), lo = fmin(ev[0], fmin(ev[1], ev[2]));
	if (!(hi > 0) || !(lo > 1e-12 * hi))
		return 0;
	/* x = V diag(1/ev) V^T b */
	double x[3] = { 0, 0, 0 };
	for (int k = 0; k < 3; k++) {
		double t = (v[0][k] * q[6] + v[1][k] * q[7] + v[2][k] * q[8]) / ev[k];
		for (int i = 0; i < 3; i++)
			x[i] += t * v[i][k];
	}
	double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
	if (!(len > 0) || !isfinite(len))
		return 0;
	/* a.(p - o) = 1: n = a/|a|, d = -(a.o + 1)/|a|. */
	for (int i = 0; i < 3; i++)
		pl->n[i] = x[i] / len;
	pl->d = -(pl->n[0] * o[0] + pl->n[1] * o[1] + pl->n[2] * o[2]) - 1 / len;
	return 1;
}

/* Each vertex's unit ray from the viewpoint and its length, {u, len}, as
 * the fits along the rays take them for each corner of each face (the fits
 * are made again and again, and the square root and divisions were much
 * of their time); len 0 for a vertex at the viewpoint, which they skip. */
static void ray_terms(double (*t)[4], const struct fct_mesh *m, const double *vp)
{
	for (size_t v = 0; v < m->nv; v++) {
		const double *p = &m->xyz[3 * v];
		double u[3] = { p[0] - vp[0], p[1] - vp[1], p[2] - vp[2] };
		double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
		memset(t[v], 0, sizeof t[v]);
		if (!(len > 0))
			continue;
		u[0] /= len, u[1] /= len, u[2] /= len;
		t[v][0] = u[0], t[v][1] = u[1], t[v][2] = u[2], t[v][3] = len;
	}
}

/* The moments of each patch of label (np patches; -1 faces skipped) from
 * its faces: R[np], and ray[9 np] for the fit along the rays when ray is
 * not NULL; only the patches flagged in redo (NULL: all), the others' left
 * as they are. */
static void patch_moments(const struct seg *S, const int32_t *label, size_t np, struct region *R,
                          double *ray, const unsigned char *redo)
{
	const struct fct_mesh *m = S->m;
	for (size_t l = 0; l < np; l++)
		if (!redo || redo[l]) {
			memset(&R[l], 0, sizeof *R);
			if (ray)
				memset(&ray[9 * l], 0, 9 * sizeof *ray);
		}
	for (size_t f = 0; f < m->nf; f++) {
		if (label[f] < 0 || (redo && !redo[label[f]]))
			continue;
		struct region t = S->face[f];
		struct region *r = &R[label[f]];
		if (r->n == 0 && r->w == 0)
			*r = t;
		else
			region_add(r, r, &t);
		if (!ray)
			continue;
		double *q = &ray[9 * (size_t)label[f]];
		uint32_t s0 = m->fstart[f], n = m->fstart[f + 1] - s0;
		double w = S->p->area_weighted && n ? t.n / n : 1;
		for (uint32_t k = 0; k < n; k++) {
			const double *u = S->ray[m->fvert[s0 + k]], len = u[3];
			if (!(len > 0))
				continue;
			/* 1/s has deviation sigma / s^2: weight s^4 / sigma^2. */
			double x = w * len * len * len * len * S->wv[m->fvert[s0 + k]];
			q[0] += x * u[0] * u[0], q[1] += x * u[1] * u[1], q[2] += x * u[2] * u[2];
			q[3] += x * u[0] * u[1], q[4] += x * u[1] * u[2], q[5] += x * u[0] * u[2];
			q[6] += x * u[0] / len, q[7] += x * u[1] / len, q[8] += x * u[2] / len;
		}
	}
	for (size_t l = 0; l < np; l++)
		if (!redo || redo[l])
			R[l].sse = fmax(0, fct_sym3_min_eigenvalue(R[l].s));
}

/* The plane of a patch's moments r: the weighted orthogonal fit, or the
 * fit along the rays (ray not NULL) where it is well posed.  Without rays
 * its normal points the way the patch faces (its vector area), as finish
 * writes it, so that face_deviation can tell a face turned away. */
static void patch_plane(struct fct_plane *pl, const struct region *r, const double *ray,
                        const double *viewpoint)
{
	fct_plane_fit(pl, r->c, r->s);
	if (ray)
		ray_fit(pl, ray, viewpoint);
	else if (pl->n[0] * r->va[0] + pl->n[1] * r->va[1] + pl->n[2] * r->va[2] < 0) {
		for (int i = 0; i < 3; i++)
			pl->n[i] = -pl->n[i];
		pl->d = -pl->d;
	}
}

/* The distance of face f from plane pl in units of its noise: the mean
 * over its corners of their signed distances over their sigma (the
 * distance of its centroid, where the corners' noise is alike).  A face
 * turned away from a two-sided mesh's plane (patch_plane) is on the
 * other side of a board, not on this plane: infinitely far (its vector
 * area from S->face, made once for finish). */
static double face_deviation(const struct seg *S, size_t f, const struct fct_plane *pl)
{
	const struct fct_mesh *m = S->m;
	uint32_t c0 = m->fstart[f], n = m->fstart[f + 1] - c0;
	if (n == 0)
		return 0;
	if (S->two_sided && turned_away(S->face[f].va, pl->n))
		return HUGE_VAL;
	double dev = 0;
	for (uint32_t c = c0; c < c0 + n; c++) {
		uint32_t v = m->fvert[c];
		const double *p = &m->xyz[3 * (size_t)v];
		double d = pl->n[0] * p[0] + pl->n[1] * p[1] + pl->n[2] * p[2] + pl->d;
		dev += d * S->isigma[v];
	}
	return fabs(dev) / n;
}

/* Is a patch too narrow to be a plane: its lesser width across the plane,
 * sqrt(12 l2 / w) for the middle eigenvalue l2 of its scatter (the width
 * of a uniform strip), below min_extent times its noise sqrt(n / w)?  A
 * strip a few samples wide fits any plane through it, and its fit says
 * nothing of the surface's shape. */
static int narrow(const struct region *r, double min_extent)
{
	if (!(min_extent > 0) || !(r->w > 0))
		return 0;
	double a[3][3] = {
		{ r->s[0], r->s[3], r->s[5] },
		{ r->s[3], r->s[1], r->s[4] },
		{ r->s[5], r->s[4], r->s[2] },
	}, v[3][3], ev[3];
	fct_sym3_jacobi(v, ev, a);
	double lo = fmin(ev[0], fmin(ev[1], ev[2])), hi = fmax(ev[0], fmax(ev[1], ev[2]));
	double mid = ev[0] + ev[1] + ev[2] - lo - hi;
	double width2 = 12 * fmax(mid, 0) / r->w, noise2 = r->n / r->w;
	return width2 < min_extent * min_extent * noise2;
}

/* The face pairs of each face, for the rounds below to visit only the
 * faces next to a change: the pairs of face f are
 * pairs[start[f] .. start[f + 1]), in increasing order. */
struct face_pairs {
	uint32_t *start, *pairs;
};

static void face_pairs_free(struct face_pairs *fp)
{
	free(fp->start), free(fp->pairs);
	fp->start = fp->pairs = NULL;
}

static int face_pairs(struct face_pairs *fp, struct seg *S, struct fct_err *err)
{
	size_t nf = S->m->nf;
	fp->start = fct_alloc_array(nf + 1, sizeof *fp->start, err);
	fp->pairs = fct_alloc_array(2 * S->nfpairs + 1, sizeof *fp->pairs, err);
	if (!fp->start || !fp->pairs) {
		face_pairs_free(fp);
		return -1;
	}
	memset(fp->start, 0, (nf + 1) * sizeof *fp->start);
	for (size_t i = 0; i < S->nfpairs; i++)
		fp->start[S->fpair[i][0] + 1]++, fp->start[S->fpair[i][1] + 1]++;
	for (size_t f = 0; f < nf; f++)
		fp->start[f + 1] += fp->start[f];
	for (size_t i = 0; i < S->nfpairs; i++)
		for (int side = 0; side < 2; side++)
			fp->pairs[fp->start[S->fpair[i][side]]++] = (uint32_t)i;
	for (size_t f = nf; f > 0; f--)
		fp->start[f] = fp->start[f - 1];
	fp->start[0] = 0;
	return 0;
}

/* The other face of pair i than f. */
static uint32_t other_face(const struct seg *S, uint32_t i, uint32_t f)
{
	return S->fpair[i][0] == f ? S->fpair[i][1] : S->fpair[i][0];
}

/* The next round's faces: those of list[0 .. n) and their neighbours, each
 * once, into next; returns how many.  seen: all 0, left so. */
static size_t next_faces(const struct seg *S, const struct face_pairs *fp, const uint32_t *list,
                         size_t n, unsigned char *seen, uint32_t *next)
{
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		uint32_t f = list[i];
		if (!seen[f])
			seen[f] = 1, next[m++] = f;
		for (uint32_t k = fp->start[f]; k < fp->start[f + 1]; k++) {
			uint32_t g = other_face(S, fp->pairs[k], f);
			if (!seen[g])
				seen[g] = 1, next[m++] = g;
		}
	}
	for (size_t i = 0; i < m; i++)
		seen[next[i]] = 0;
	return m;
}

/* Scratch of the rounds below: the faces of a round (list), of the next
 * (next), each listed face's choice (best), and a flag per face (seen). */
struct rounds_scratch {
	struct fct_arena ar;
	uint32_t *list, *next;
	int32_t *best;
	unsigned char *seen;
};

static int rounds_scratch(struct rounds_scratch *r, size_t nf, struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	size_t n = nf ? nf : 1;
	r->list = fct_arena_array(&r->ar, n, sizeof *r->list, err);
	r->next = fct_arena_array(&r->ar, n, sizeof *r->next, err);
	r->best = fct_arena_array(&r->ar, n, sizeof *r->best, err);
	r->seen = fct_arena_zeroed(&r->ar, n, 1, err);
	if (r->list && r->next && r->best && r->seen) {
		for (size_t f = 0; f < nf; f++)
			r->list[f] = (uint32_t)f;
		return 0;
	}
	fct_arena_free(&r->ar);
	return -1;
}

/* Grow the patches into the free-form faces their planes fit: in rounds,
 * each free-form face next to a patch joins the neighbouring patch whose
 * plane it is nearest (face_deviation, ties to the lower label) when that
 * is within max_dev sigma.  Region growing leaves the faces along a
 * boundary to whichever side got there first, and peeling frees some that
 * the plane beside them fits; without this, labels along boundaries
 * alternate and every alternation is a corner of the model.  Stops when a
 * round takes none.  A face stays free until a neighbour is taken, so after
 * the first round only the faces next to those taken in the last are
 * looked at (the choice is the least deviation, whatever the order). */
static int grow_into_free(struct seg *S, int32_t *patch, const struct fct_plane *pl,
                          const struct face_pairs *fp, struct fct_err *err)
{
	struct rounds_scratch r;
	if (rounds_scratch(&r, S->m->nf, err))
		return -1;
	size_t n = S->m->nf;
	for (;;) {
		for (size_t i = 0; i < n; i++) {
			uint32_t f = r.list[i];
			int32_t best = -1;
			double dev = S->p->max_dev;
			for (uint32_t k = fp->start[f]; patch[f] < 0 && k < fp->start[f + 1]; k++) {
				uint32_t g = other_face(S, fp->pairs[k], f);
				if (patch[g] < 0)
					continue;
				double d = face_deviation(S, f, &pl[patch[g]]);
				if (d < dev || (d == dev && best >= 0 && patch[g] < best) || (d <= dev && best < 0))
					best = patch[g], dev = d;
			}
			r.best[i] = best;
		}
		/* The faces taken, to the front of the list. */
		size_t nt = 0;
		for (size_t i = 0; i < n; i++)
			if (r.best[i] >= 0) {
				patch[r.list[i]] = r.best[i];
				r.list[nt++] = r.list[i];
			}
		S->st.grown += nt;
		if (!nt)
			break;
		n = next_faces(S, fp, r.list, nt, r.seen, r.next);
		uint32_t *t = r.list;
		r.list = r.next, r.next = t;
	}
	fct_arena_free(&r.ar);
	return 0;
}

/* Move each face on a boundary between patches to the neighbouring patch
 * whose plane it is nearer (face_deviation, ties to the lower label), in
 * rounds until none moves (at most 64): region growing gives the faces
 * along a crease to whichever side reached them first, so that the
 * boundary runs in teeth on either side of the planes' line, which no
 * model of straight edges can follow; nearer-plane labels put it on the
 * line, to the noise.  A face only moves nearer a plane, so none ends
 * farther from its plane than max_dev.  Only where a label changed last
 * round can one change now: a round looks at the faces that moved and
 * their neighbours, and weighs a face's neighbours across the pairs with
 * a face that moved. */
static int settle_boundaries(struct seg *S, int32_t *patch, const struct fct_plane *pl,
                             const struct face_pairs *fp, struct fct_err *err)
{
	size_t nf = S->m->nf, n = nf;
	struct rounds_scratch r;
	if (rounds_scratch(&r, nf, err))
		return -1;
	unsigned char *changed = fct_arena_array(&r.ar, nf ? nf : 1, 1, err);
	if (!changed) {
		fct_arena_free(&r.ar);
		return -1;
	}
	memset(changed, 1, nf);
	for (int round = 0; round < 64; round++) {
		for (size_t i = 0; i < n; i++) {
			uint32_t f = r.list[i];
			int32_t a = patch[f], best = -1;
			double dev = 0;
			for (uint32_t k = fp->start[f]; a >= 0 && k < fp->start[f + 1]; k++) {
				uint32_t g = other_face(S, fp->pairs[k], f);
				int32_t b = patch[g];
				if (b < 0 || a == b || (!changed[f] && !changed[g]))
					continue;
				if (best < 0) {
					best = a;
					dev = face_deviation(S, f, &pl[a]);
				}
				double d = face_deviation(S, f, &pl[b]);
				if (d < dev || (d == dev && b < best))
					best = b, dev = d;
			}
			r.best[i] = best;
		}
		/* Every face that moved last round is in the list: all are
		 * decided afresh; those that move now go to its front. */
		size_t nc = 0;
		for (size_t i = 0; i < n; i++) {
			uint32_t f = r.list[i];
			changed[f] = r.best[i] >= 0 && r.best[i] != patch[f];
			if (changed[f]) {
				patch[f] = r.best[i];
				r.list[nc++] = f;
			}
		}
		S->st.settled += nc;
		if (!nc)
			break;
		n = next_faces(S, fp, r.list, nc, r.seen, r.next);
		uint32_t *t = r.list;
		r.list = r.next, r.next = t;
	}
	fct_arena_free(&r.ar);
	return 0;
}

/* Number the labels 0, 1, ... in the order of their smallest face,
 * dropping the unused; returns the count. */
static size_t renumber(int32_t *label, size_t nf, int32_t *map)
{
	size_t np = 0;
	for (size_t f = 0; f < nf; f++)
		map[f] = -1;
	for (size_t f = 0; f < nf; f++) {
		if (label[f] < 0)
			continue;
		if (map[label[f]] < 0)
			map[label[f]] = (int32_t)np++;
		label[f] = map[label[f]];
	}
	return np;
}

/* Fits the plane of each patch flagged in redo (NULL: every one) to the
 * faces it holds now; the others keep theirs (their faces are the same,
 * so a fit would give the same bits). */
static void fit_planes(struct seg *S, const int32_t *patch, size_t np, struct region *R,
                       struct fct_plane *pl, double *ray, const unsigned char *redo)
{
	patch_moments(S, patch, np, R, ray, redo);
	for (size_t l = 0; l < np; l++)
		if (!redo || redo[l])
			patch_plane(&pl[l], &R[l], ray ? &ray[9 * l] : NULL, S->p->viewpoint);
}

/* Frees (-1) every face farther than max_dev sigma from its patch's plane
 * (none when max_dev is not positive), looking only at the patches flagged
 * in redo (their planes new since the last look); redo then flags the
 * patches that lost a face.  Returns how many. */
static size_t peel(struct seg *S, int32_t *patch, const struct fct_plane *pl, unsigned char *redo,
                   size_t np)
{
	double max_dev = S->p->max_dev;
	size_t peeled = 0;
	for (size_t f = 0; f < S->m->nf; f++) {
		int32_t l = patch[f];
		if (max_dev > 0 && l >= 0 && (redo[l] & 1) && face_deviation(S, f, &pl[l]) > max_dev) {
			patch[f] = -1;
			redo[l] |= 2;
			peeled++;
		}
	}
	for (size_t l = 0; l < np; l++)
		redo[l] >>= 1;
	S->st.peeled += peeled;
	return peeled;
}

/* Patches too narrow to be a plane (narrow), or still smaller than
 * min_faces, are free-form too (a curved surface cut into facets), unless
 * no patch reaches min_faces (a cube of twelve triangles).  drop: scratch,
 * np entries. */
static int drop_small(struct seg *S, int32_t *patch, size_t np, const struct region *R,
                      int32_t *drop, struct fct_err *err)
{
	size_t nf = S->m->nf;
	int32_t *nfaces = fct_arena_zeroed(&S->arena, np ? np : 1, sizeof *nfaces, err);
	if (!nfaces)
		return -1;
	for (size_t f = 0; f < nf; f++)
		if (patch[f] >= 0)
			nfaces[patch[f]]++;
	int any_big = 0;
	for (size_t l = 0; l < np; l++)
		any_big |= nfaces[l] >= S->p->min_faces;
	for (size_t l = 0; l < np; l++)
		drop[l] = narrow(&R[l], S->p->min_extent) ||
		          (any_big && S->p->target <= 0 && nfaces[l] < S->p->min_faces);
	for (size_t f = 0; f < nf; f++)
		if (patch[f] >= 0 && drop[patch[f]]) {
			patch[f] = -1;
			S->st.narrow_faces++;
		}
	return 0;
}

/* The region growing's np patches checked against their planes (pl, fitted
 * here): a face farther than max_dev sigma from its patch's plane leaves it
 * (free-form, -1) and the plane is fitted again without it, for
 * PEEL_ROUNDS rounds; patches grow into the free faces their planes fit
 * and settle their boundaries; small and narrow patches go.  map: scratch,
 * np entries. */
static int check_patches(struct seg *S, int32_t *patch, size_t np, struct region *R,
                         struct fct_plane *pl, double *ray, int32_t *map, struct fct_err *err)
{
	/* (map holds the patches to fit again: every one at first, then those
	 * that lost faces to peeling) */
	unsigned char *redo = (unsigned char *)map;
	memset(redo, 1, np);
	for (int round = 0; round <= PEEL_ROUNDS; round++) {
		fit_planes(S, patch, np, R, pl, ray, redo);
		if (round == PEEL_ROUNDS || !peel(S, patch, pl, redo, np))
			break;
	}
	struct face_pairs fp;
	if (face_pairs(&fp, S, err))
		return -1;
	if ((S->p->max_dev > 0 && grow_into_free(S, patch, pl, &fp, err)) ||
	    settle_boundaries(S, patch, pl, &fp, err)) {
		face_pairs_free(&fp);
		return -1;
	}
	face_pairs_free(&fp);
	if (drop_small(S, patch, np, R, map, err))
		return -1;
	/* The guarantee: the planes fitted again to what the patches now hold
	 * (growing and settling judged faces by the planes before), and every
	 * face beyond max_dev of them peeled, until a fit peels none (at most
	 * FINAL_ROUNDS); the planes are those of the last fit, which every
	 * face left lies within max_dev of, since peeling only takes faces. */
	memset(redo, 1, np);
	for (int round = 0; round < FINAL_ROUNDS; round++) {
		fit_planes(S, patch, np, R, pl, ray, redo);
		if (!peel(S, patch, pl, redo, np))
			break;
	}
	for (size_t f = 0; f < S->m->nf; f++)
		S->st.free_faces += patch[f] < 0;
	return 0;
}

/* The planes moved to their patches' new numbers map (np0 old numbers;
 * peeling may have reordered the patches' first faces). */
static int renumber_planes(struct seg *S, struct fct_plane *pl, const int32_t *map, size_t np0,
                           struct fct_err *err)
{
	struct fct_plane *tmp = fct_arena_array(&S->arena, np0 ? np0 : 1, sizeof *tmp, err);
	if (!tmp)
		return -1;
	memcpy(tmp, pl, np0 * sizeof *pl);
	for (size_t l = 0; l < np0; l++)
		if (map[l] >= 0)
			pl[map[l]] = tmp[l];
	return 0;
}

/* Each patch's squared distances of its corners from its plane and their
 * count (res, 2 per patch), and its faces' vector area (wind, 3 per patch:
 * which way it faces); returns the faces in patches. */
static size_t patch_residuals(const struct fct_mesh *m, const int32_t *patch,
                              const struct fct_plane *pl, double *res, double *wind)
{
	size_t nfaces_in = 0;
	for (size_t f = 0; f < m->nf; f++) {
		if (patch[f] < 0)
			continue;
		size_t l = (size_t)patch[f];
		nfaces_in++;
		uint32_t s = m->fstart[f], n = m->fstart[f + 1] - s;
		for (uint32_t k = 0; k < n; k++) {
			uint32_t v = m->fvert[s + k];
			const double *p = &m->xyz[3 * (size_t)v];
			double d = pl[l].n[0] * p[0] + pl[l].n[1] * p[1] + pl[l].n[2] * p[2] + pl[l].d;
			res[2 * l] += d * d;
			res[2 * l + 1] += 1;
		}
		double va[3];
		face_vector_area(m, f, va);
		for (int i = 0; i < 3; i++)
			wind[3 * l + (size_t)i] += va[i];
	}
	return nfaces_in;
}

/* pl[l].count: the distinct vertices of each patch, its faces (nfaces_in
 * in all) taken patch by patch so that one stamp per vertex tells. */
static int count_vertices(struct seg *S, struct fct_plane *pl, size_t np, const int32_t *patch,
                          size_t nfaces_in, struct fct_err *err)
{
	const struct fct_mesh *m = S->m;
	struct fct_arena *a = &S->arena;
	uint32_t *stamp = fct_arena_array(a, m->nv, sizeof *stamp, err);
	uint32_t *start = fct_arena_zeroed(a, np + 1, sizeof *start, err);
	uint32_t *order = fct_arena_array(a, nfaces_in, sizeof *order, err);
	if (!stamp || !start || !order)
		return -1;
	memset(stamp, 0xff, m->nv * sizeof *stamp);
	for (size_t l = 0; l < np; l++)
		pl[l].count = 0;
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0)
			start[patch[f] + 1]++;
	for (size_t l = 0; l < np; l++)
		start[l + 1] += start[l];
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0)
			order[start[patch[f]]++] = (uint32_t)f;
	for (size_t l = np; l > 0; l--)
		start[l] = start[l - 1];
	start[0] = 0;
	for (size_t l = 0; l < np; l++)
		for (uint32_t i = start[l]; i < start[l + 1]; i++)
			for (uint32_t c = m->fstart[order[i]]; c < m->fstart[order[i] + 1]; c++)
				if (stamp[m->fvert[c]] != (uint32_t)l) {
					stamp[m->fvert[c]] = (uint32_t)l;
					pl[l].count++;
				}
	return 0;
}

/* Each plane turned the way its faces wind (without winding to go by,
 * its first non-zero component positive), its rms from res; the stats'
 * max and mean rms. */
static void orient_planes(struct seg *S, struct fct_plane *pl, size_t np, const double *wind,
                          const double *res)
{
	double sum_rms = 0, max_rms = 0;
	for (size_t l = 0; l < np; l++) {
		const double *wv = &wind[3 * l];
		double dot = pl[l].n[0] * wv[0] + pl[l].n[1] * wv[1] + pl[l].n[2] * wv[2];
		int flip = dot < 0;
		if (dot == 0) {
			for (int i = 0; i < 3; i++)
				if (pl[l].n[i] != 0) {
					flip = pl[l].n[i] < 0;
					break;
				}
		}
		if (flip) {
			for (int i = 0; i < 3; i++)
				pl[l].n[i] = -pl[l].n[i];
			pl[l].d = -pl[l].d;
		}
		for (int i = 0; i < 3; i++)
			pl[l].n[i] += 0.0;   /* no -0 in the output */
		pl[l].d += 0.0;
		pl[l].rms = res[2 * l + 1] > 0 ? sqrt(res[2 * l] / res[2 * l + 1]) : 0;
		if (pl[l].rms > max_rms)
			max_rms = pl[l].rms;
		sum_rms += pl[l].rms * res[2 * l + 1];
	}
	double ncorners = 0;
	for (size_t l = 0; l < np; l++)
		ncorners += res[2 * l + 1];
	S->st.max_rms = max_rms;
	S->st.mean_rms = ncorners > 0 ? sum_rms / ncorners : 0;
}

/* Each plane's orientation, count and rms. */
static int describe_planes(struct seg *S, struct fct_plane *pl, size_t np, const int32_t *patch,
                           struct fct_err *err)
{
	double *wind = fct_arena_zeroed(&S->arena, 3 * (np ? np : 1), sizeof *wind, err);
	double *res = fct_arena_zeroed(&S->arena, 2 * (np ? np : 1), sizeof *res, err);
	if (!wind || !res)
		return -1;
	size_t nfaces_in = patch_residuals(S->m, patch, pl, res, wind);
	if (count_vertices(S, pl, np, patch, nfaces_in, err))
		return -1;
	orient_planes(S, pl, np, wind, res);
	return 0;
}

/* Labels, free-form faces, planes, stats: the patches checked against
 * their planes (check_patches), then the labels in the order of the
 * smallest face index, and each plane with its orientation, count and
 * rms.  *planes is the caller's (NULL with no patch). */
static int finish(struct seg *S, int32_t *patch, struct fct_plane **planes, size_t *nplanes,
                  struct fct_err *err)
{
	size_t nf = S->m->nf;
	int32_t *map = fct_arena_array(&S->arena, nf, sizeof *map, err);
	if (!map)
		return -1;
	for (size_t f = 0; f < nf; f++)
		patch[f] = (int32_t)fct_uf_root(S->parent, (uint32_t)f);
	/* The patches' moments are done with: their memory holds each face's
	 * from now on, for the fits to sum. */
	for (size_t f = 0; f < nf; f++)
		face_moments(&S->region[f], S->m, f, S->p->area_weighted, S->wv, S->area_unit);
	S->face = S->region;
	size_t np = renumber(patch, nf, map);
	struct region *R = fct_arena_array(&S->arena, np ? np : 1, sizeof *R, err);
	double *ray = S->p->use_viewpoint
	              ? fct_arena_array(&S->arena, 9 * (np ? np : 1), sizeof *ray, err) : NULL;
	if (ray && (S->ray = fct_arena_array(&S->arena, S->m->nv ? S->m->nv : 1, sizeof *S->ray, err)))
		ray_terms(S->ray, S->m, S->p->viewpoint);
	struct fct_plane *pl = fct_alloc_array(np ? np : 1, sizeof *pl, err);
	if (!R || (S->p->use_viewpoint && (!ray || !S->ray)) || !pl ||
	    check_patches(S, patch, np, R, pl, ray, map, err))
		goto fail;
	/* The patches that remain, numbered afresh, with those planes. */
	size_t np0 = np;
	np = renumber(patch, nf, map);
	if (renumber_planes(S, pl, map, np0, err) || describe_planes(S, pl, np, patch, err))
		goto fail;
	S->st.patches = np;
	if (np == 0) {
		free(pl);
		pl = NULL;
	}
	*planes = pl;
	*nplanes = np;
	return 0;
fail:
	free(pl);
	return -1;
}

/* The squared diagonal of m's bounding box; fails on a coordinate that is
 * not finite. */
static int box_diagonal2(const struct fct_mesh *m, double *diag2, struct fct_err *err)
{
	double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
	for (size_t v = 0; v < m->nv; v++)
		for (int i = 0; i < 3; i++) {
			double x = m->xyz[3 * v + i];
			if (!isfinite(x))
				return fct_fail(err, "segment: vertex %zu: coordinate not finite", v);
			lo[i] = x < lo[i] ? x : lo[i];
			hi[i] = x > hi[i] ? x : hi[i];
		}
	*diag2 = 0;
	if (m->nv)
		for (int i = 0; i < 3; i++)
			*diag2 += (hi[i] - lo[i]) * (hi[i] - lo[i]);
	return 0;
}

/* The squared distance by which rounding m's coordinates can move a point:
 * half an ulp of the largest coordinate on each of three axes, a float's
 * when every coordinate is one (a mesh read from floats), else a double's. */
static double coordinate_rounding2(const struct fct_mesh *m)
{
	double far = 0;
	int floats = 1;
	for (size_t k = 0; k < 3 * m->nv; k++) {
		far = fmax(far, fabs(m->xyz[k]));
		floats = floats && (double)(float)m->xyz[k] == m->xyz[k];
	}
	return 3 * ldexp(far * far, floats ? -48 : -106);
}

/* A third of the mean face area, so that a regular mesh's face counts as
 * its three corners would.  Sets S->wv to 1 (its first use). */
static double area_unit(struct seg *S)
{
	const struct fct_mesh *m = S->m;
	double area = 0;
	for (size_t v = 0; v < m->nv; v++)
		S->wv[v] = 1;
	for (size_t f = 0; f < m->nf; f++) {
		struct region t;
		face_moments(&t, m, f, 1, S->wv, 1);
		area += t.n;
	}
	return area > 0 ? area / (3.0 * m->nf) : 1;
}

/* Each vertex's weight S->wv, 1 / sigma^2, and S->isigma, 1 / sigma: from
 * the noise model, or else from the noise the data show (noise.h), or
 * else (too few vertices to tell) the floor of exact data.  The median
 * sigma into the stats. */
static int vertex_weights(struct seg *S, struct fct_err *err)
{
	const struct fct_mesh *m = S->m;
	int rc = -1;
	struct fct_arena ar = { 0 };
	float *sv = fct_arena_array(&ar, m->nv, sizeof *sv, err);
	uint32_t *count = fct_arena_array(&ar, 65536, sizeof *count, err);
	S->isigma = fct_arena_array(&S->arena, m->nv, sizeof *S->isigma, err);
	if (!sv || !count || !S->isigma)
		goto done;
	struct fct_err ignored;
	int have = 1;
	if (S->p->sigma) {
		for (size_t v = 0; v < m->nv; v++)
			sv[v] = (float)S->p->sigma[v];
	} else if (fct_noise_estimate_vertices(sv, m, &ignored)) {
		have = 0;
	} else {
		S->st.noise_estimated = 1;
	}
	double floor = sqrt(S->floor2);
	for (size_t v = 0; v < m->nv; v++) {
		double sg = have ? sv[v] : floor;
		if (!(sg >= floor) || !isfinite(sg))
			sg = isfinite(sg) && sg >= 0 ? floor : HUGE_VAL;
		S->wv[v] = sg < HUGE_VAL && sg > 0 ? 1 / (sg * sg) : 0;
		sv[v] = (float)(sg < HUGE_VAL ? sg : 0);
	}
	S->st.noise = m->nv ? select_float(sv, m->nv, (m->nv - 1) / 2, count) : 0;
	for (size_t v = 0; v < m->nv; v++)
		S->isigma[v] = sqrt(S->wv[v]);
	rc = 0;
done:
	fct_arena_free(&ar);
	return rc;
}

/* Phase 1: clusters.  Every pair's union costed and queued, then grown
 * into clusters; the merges into the stats. */
static int cluster(struct seg *S, struct fct_err *err)
{
	size_t nf = S->m->nf;
	qkey *least = fct_alloc_array(nf, sizeof *least, err);
	if (!least)
		return -1;
	for (size_t f = 0; f < nf; f++)
		least[f] = UINT64_MAX;
	/* Every pair's union: the first phase-1 key, and each face's least. */
	for (size_t i = 0; i < S->npairs; i++) {
		uint32_t f = S->pair[i][0], g = S->pair[i][1];
		double tr, u = union_sse(S, &S->region[f], &S->region[g], &tr);
		S->st.evaluations++;
		if (rh_push(S, (float)u, i)) {
			free(least);
			return -1;
		}
		float fu = (float)u;
		uint32_t bits;
		memcpy(&bits, &fu, sizeof bits);
		qkey key = (qkey)bits << 32 | i;
		if (key < least[f])
			least[f] = key;
		if (key < least[g])
			least[g] = key;
	}
	/* A pair that is the least of both its faces' is popped before
	 * anything touches either face, its cost unchanged: such pairs are
	 * settled now, in one pass over the pairs (the queue then finds them
	 * inside one patch and drops them), which spares the queue a third of
	 * its random accesses and changes no result. */
	size_t pre = 0;
	for (size_t i = 0; i < S->npairs; i++) {
		uint32_t f = S->pair[i][0], g = S->pair[i][1];
		if ((uint32_t)least[f] != i || (uint32_t)least[g] != i || least[f] == UINT64_MAX ||
		    least[f] != least[g])
			continue;
		double sse;
		if (cost1(S, f, g, &sse) >= 0) {
			merge(S, f, g, sse);
			pre++;
		}
	}
	free(least);
	long k = grow(S, 1);
	if (k < 0)
		return -1;
	S->st.merges = (size_t)k + pre;
	S->st.clusters = S->patches;
	return 0;
}

/* Phase 2: patches, then fresh sweeps until one merges nothing.  Keeps
 * the face pairs for finish (refill turns S->pair into patch pairs). */
static int grow_patches(struct seg *S, struct fct_err *err)
{
	S->dirty = fct_arena_zeroed(&S->arena, S->m->nf, 1, err);
	S->nfpairs = S->npairs;
	S->fpair = fct_arena_array(&S->arena, S->npairs, sizeof *S->fpair, err);
	if (!S->dirty || !S->fpair)
		return -1;
	memcpy(S->fpair, S->pair, S->npairs * sizeof *S->pair);
	for (int first = 1;; first = 0) {
		long k;
		if (refill(S, first) || (k = grow(S, 2)) < 0)
			return -1;
		S->st.merges += (size_t)k;
		if (S->p->target > 0 || k == 0 || S->st.sweeps == MAX_SWEEPS)
			break;
		S->st.sweeps++;
	}
	return 0;
}

/* The patches of fewer than min_faces faces absorbed (absorb); its
 * scratch, two arrays of F, given back at once. */
static int absorb_small(struct seg *S, struct fct_err *err)
{
	struct fct_arena ar = { 0 };
	uint32_t *best = fct_arena_array(&ar, S->m->nf, sizeof *best, err);
	double *gain = fct_arena_array(&ar, S->m->nf, sizeof *gain, err);
	if (best && gain)
		absorb(S, best, gain);
	fct_arena_free(&ar);
	return best && gain ? 0 : -1;
}

/* The run's scratch lives in S.arena, freed at the one exit; the pairs
 * and the queue, the largest arrays of the growing phases, are given back
 * before finish. */
int fct_segment(int32_t *patch, struct fct_plane **planes, size_t *nplanes,
                const struct fct_mesh *m, const struct fct_segment_params *p,
                struct fct_segment_stats *stats, struct fct_err *err)
{
	double t0 = fct_now();
	struct seg S;
	memset(&S, 0, sizeof S);
	S.m = m, S.p = p, S.err = err;
	*planes = NULL, *nplanes = 0;
	if (stats)
		memset(stats, 0, sizeof *stats);
	size_t nf = m->nf;
	if (nf > INT32_MAX)
		return fct_fail(err, "segment: %zu faces, more than %d", nf, INT32_MAX);
	double diag2 = 0;
	if (box_diagonal2(m, &diag2, err))
		return -1;
	if (nf == 0) {
		if (stats)
			stats->seconds = fct_now() - t0;
		return 0;
	}
	S.floor2 = 1e-14 * diag2;
	S.round2 = coordinate_rounding2(m);
	S.max_ms = p->max_rms < HUGE_VAL ? p->max_rms * p->max_rms : HUGE_VAL;
	S.stop = p->factor * p->factor;
	S.fit2 = p->fit * p->fit;
	S.two_sided = !p->use_viewpoint;

	int rc = -1;
	if (build_pairs(&S, err))
		goto out;
	S.st.adjacencies = S.npairs;
	S.region = fct_arena_array(&S.arena, nf, sizeof *S.region, err);
	S.parent = fct_arena_array(&S.arena, nf, sizeof *S.parent, err);
	S.wv = fct_arena_array(&S.arena, m->nv, sizeof *S.wv, err);
	if (!S.region || !S.parent || !S.wv)
		goto out;
	if (p->area_weighted)
		S.area_unit = area_unit(&S);
	if (vertex_weights(&S, err))
		goto out;
	for (size_t f = 0; f < nf; f++) {
		face_moments(&S.region[f], m, f, p->area_weighted, S.wv, S.area_unit);
		S.parent[f] = -1;
	}
	S.patches = nf;
	if (cluster(&S, err) || grow_patches(&S, err))
		goto out;
	rh_free(&S.q);
	if (p->min_faces > 1 && p->target <= 0 && absorb_small(&S, err))
		goto out;
	free(S.pair);
	S.pair = NULL;
	if (finish(&S, patch, planes, nplanes, err))
		goto out;
	rc = 0;
out:
	free(S.pair);
	rh_free(&S.q);
	fct_arena_free(&S.arena);
	S.st.seconds = fct_now() - t0;
	if (stats && rc == 0)
		*stats = S.st;
	return rc;
}
