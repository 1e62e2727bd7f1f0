/* qem.c - quadric edge-collapse decimation (see qem.h): Garland and
 * Heckbert, SIGGRAPH 1997, sec. 4-5 (quadrics, optimal placement, the heap
 * of pairs), with Garland's thesis (1999) for area weighting (sec. 3.3) and
 * border constraint planes (sec. 4.1), and the link condition of Dey,
 * Edelsbrunner, Guha and Nekhayev (1999) for topology. */
#include "geom/qem.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "geom/geom.h"

#define DEAD UINT32_MAX
#define MAX_PASSES 64
/* Regularisation of the heap order: see edge_key. */
#define SHAPE_WEIGHT 1e-6
/* Collapses whose ends hold more triangles than this are refused, so no
 * vertex grows a fan whose every change costs its whole size. */
#define MAX_FAN 512

enum { ALIVE = 1, BORDER = 2, LOCKED = 4, MOVED = 8 };
/* Held borders: a vertex inside, on a border, at a corner (qem.h). */
enum { INSIDE = 0, ON_BORDER = 1, CORNER = 2 };
/* Held borders: the thinnest triangle a collapse may make (twice the area
 * over the longest edge squared), unless it was as thin. */
#define HELD_QUALITY 1e-4

/* A quadric x^T A x + 2 b.x + c: a[0..5] = A00 A01 A02 A11 A12 A22,
 * a[6..8] = b, a[9] = c; w is the face area it carries. */
struct quad {
	double a[10];
	double w;
};

/* Per-vertex lists of item numbers (triangles or edges) in one pool:
 * pool[st[v] .. st[v] + cnt[v]), room for cap[v].  Entries may name dead
 * items (live[stride * i] == DEAD) until the list is next rewritten. */
struct lists {
	uint32_t *st, *cnt, *cap;
	uint32_t *pool;
	size_t n, pool_cap;
	const uint32_t *live;   /* the item array; item i is dead when live[stride * i] == DEAD */
	size_t stride;
	size_t base;            /* entries at the start: the pool is compacted past 4 times that */
};

/* A heap entry: an edge, its key and its lower vertex (ties go to the
 * lower vertex, then the higher, read from the edge). */
struct entry {
	double key;
	uint32_t e, a;
};

struct qem {
	size_t nv, nt, ne;
	double *p;              /* positions, relative to the centre */
	struct quad *q;         /* face planes */
	uint32_t *bq;           /* border planes of v: bquad[bq[v]], or NOBQ */
	struct quad *bquad;     /* w: the border weight they carry */
	size_t nbquad;
	unsigned char *flag;
	uint32_t *tri;          /* 3 per triangle; tri[3t] == DEAD once collapsed */
	size_t live;            /* triangles alive */
	uint32_t *ev;           /* 2 per edge, lower vertex first; ev[2e] == DEAD once gone */
	uint32_t *hpos;         /* heap position of each edge, or NOPOS */

	struct lists vt;        /* triangles of each vertex */
	struct lists ve;        /* edges of each vertex */

	uint32_t *mark;         /* per-vertex stamps for neighbour sets */
	uint32_t stamp;

	struct entry *heap;     /* indexed 4-ary heap of the edges waiting */
	size_t nheap;

	double *attr;           /* nattr interpolated properties per vertex */
	size_t nattr;
	long nrm[3];            /* columns of nx ny nz in attr, or -1 */

	unsigned char *cls;     /* held borders: INSIDE, ON_BORDER or CORNER; else NULL */
	double *wv;             /* with sigma: each vertex's 1 / sigma^2 */
	int has_vp;             /* with sigma: the viewpoint, relative to the centre */
	double vp[3];

	size_t target;
	int close_holes;
	double max_err2;        /* squared max_error, or INFINITY */
	struct fct_qem_stats *st;
};

/* Quadrics ---------------------------------------------------------------- */

/* Add w times the quadric of the plane n.x + d = 0 (n unit). */
static void quad_add_plane(struct quad *q, const double n[3], double d, double w)
{
	q->a[0] += w * n[0] * n[0];
	q->a[1] += w * n[0] * n[1];
	q->a[2] += w * n[0] * n[2];
	q->a[3] += w * n[1] * n[1];
	q->a[4] += w * n[1] * n[2];
	q->a[5] += w * n[2] * n[2];
	q->a[6] += w * d * n[0];
	q->a[7] += w * d * n[1];
	q->a[8] += w * d * n[2];
	q->a[9] += w * d * d;
}

static double quad_eval(const double a[10], const double x[3])
{
	double e = a[0] * x[0] * x[0] + 2 * a[1] * x[0] * x[1] + 2 * a[2] * x[0] * x[2] +
	           a[3] * x[1] * x[1] + 2 * a[4] * x[1] * x[2] + a[5] * x[2] * x[2] +
	           2 * (a[6] * x[0] + a[7] * x[1] + a[8] * x[2]) + a[9];
	return e > 0 ? e : 0;
}

/* The minimiser of the quadric a, when A is far enough from singular:
 * x = -A^-1 b by the adjugate.  Returns 0 when it is not. */
static int quad_solve(const double a[10], double x[3])
{
	double c00 = a[3] * a[5] - a[4] * a[4];
	double c01 = a[2] * a[4] - a[1] * a[5];
	double c02 = a[1] * a[4] - a[2] * a[3];
	double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
	double tr = a[0] + a[3] + a[5];
	if (!(tr > 0) || !(fabs(det) > 1e-9 * tr * tr * tr))
		return 0;
	double c11 = a[0] * a[5] - a[2] * a[2];
	double c12 = a[1] * a[2] - a[0] * a[4];
	double c22 = a[0] * a[3] - a[1] * a[1];
	double inv = -1 / det;
	x[0] = inv * (c00 * a[6] + c01 * a[7] + c02 * a[8]);
	x[1] = inv * (c01 * a[6] + c11 * a[7] + c12 * a[8]);
	x[2] = inv * (c02 * a[6] + c12 * a[7] + c22 * a[8]);
	return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]);
}

#define NOBQ UINT32_MAX
#define NOHOLE UINT32_MAX

enum { FACES = 1, BORDERS = 2 };

/* The quadric of the edge (a, b): its ends' face planes (parts & FACES)
 * and border planes (parts & BORDERS); *w (may be NULL) gets the weight
 * they carry. */
static void edge_quadric(const struct qem *s, uint32_t a, uint32_t b, int parts, double q[10],
                         double *w)
{
	double wsum = 0;
	if (parts & FACES) {
		const struct quad *qa = &s->q[a], *qb = &s->q[b];
		for (int k = 0; k < 10; k++)
			q[k] = qa->a[k] + qb->a[k];
		wsum = qa->w + qb->w;
	} else {
		memset(q, 0, sizeof(double[10]));
	}
	if (parts & BORDERS) {
		uint32_t ends[2] = {s->bq[a], s->bq[b]};
		for (int j = 0; j < 2; j++) {
			if (ends[j] == NOBQ)
				continue;
			const struct quad *qe = &s->bquad[ends[j]];
			for (int k = 0; k < 10; k++)
				q[k] += qe->a[k];
			wsum += qe->w;
		}
	}
	if (w)
		*w = wsum;
}

/* How much rounding an evaluation of q at x may hold: 1e-12 of the size of
 * its terms.  A point away from the ends must beat them by more than that,
 * so ends that are as good keep their coordinates bit for bit. */
static double quad_noise(const double q[10], const double x[3])
{
	double r2 = fct_v3_dot(x, x), b2 = q[6] * q[6] + q[7] * q[7] + q[8] * q[8];
	return 1e-12 * ((q[0] + q[3] + q[5]) * r2 + 2 * sqrt(b2 * r2) + fabs(q[9]));
}

/* The best point of the segment pa-pb for the quadric q: its ends, its
 * midpoint, the minimum along it.  The ends are tried first and kept on
 * ties (within rounding), so that vertices that need not move keep their
 * coordinates bit for bit. */
static double segment_cost(const double q[10], const double *pa, const double *pb, double x[3])
{
	double best = quad_eval(q, pa), e = quad_eval(q, pb);
	memcpy(x, pa, sizeof(double[3]));
	if (e < best)
		best = e, memcpy(x, pb, sizeof(double[3]));
	double bend = best, d[3], mid[3], y[3];
	fct_v3_sub(d, pb, pa);
	fct_v3_axpy(mid, pa, 0.5, d);
	e = quad_eval(q, mid);
	if (e < bend - quad_noise(q, mid))
		best = e, memcpy(x, mid, sizeof mid);
	/* The minimum on the segment: Q(pa + t d) is a parabola in t. */
	double ad[3] = {
		q[0] * d[0] + q[1] * d[1] + q[2] * d[2],
		q[1] * d[0] + q[3] * d[1] + q[4] * d[2],
		q[2] * d[0] + q[4] * d[1] + q[5] * d[2],
	};
	double dad = fct_v3_dot(d, ad);
	if (dad > 0) {
		double g = fct_v3_dot(pa, ad) + q[6] * d[0] + q[7] * d[1] + q[8] * d[2];
		double t = -g / dad;
		if (t > 0 && t < 1) {
			fct_v3_axpy(y, pa, t, d);
			e = quad_eval(q, y);
			if (e < best && e < bend - quad_noise(q, y))
				best = e, memcpy(x, y, sizeof y);
		}
	}
	return best;
}

/* The cost of collapsing (a, b) and where the vertex goes (see qem.h): the
 * quadric's optimum when it is well posed and near the edge, else
 * segment_cost. */
static double edge_cost(const struct qem *s, uint32_t a, uint32_t b, double x[3])
{
	double q[10], y[3], d[3], mid[3];
	const double *pa = s->p + 3 * (size_t)a, *pb = s->p + 3 * (size_t)b;
	edge_quadric(s, a, b, FACES | BORDERS, q, NULL);
	fct_v3_sub(d, pb, pa);
	fct_v3_axpy(mid, pa, 0.5, d);
	if (!quad_solve(q, y) || fct_v3_dist2(y, mid) > fct_v3_dot(d, d))
		return segment_cost(q, pa, pb, x);
	double best = quad_eval(q, pa), e = quad_eval(q, pb);
	memcpy(x, pa, sizeof(double[3]));
	if (e < best)
		best = e, memcpy(x, pb, sizeof(double[3]));
	e = quad_eval(q, y);
	if (e < best - quad_noise(q, y))
		best = e, memcpy(x, y, sizeof y);
	return best;
}

static int edge_faces(const struct qem *s, uint32_t v, uint32_t u);

/* Held borders: may v be removed into u?  Inside always; on a border along
 * it; a corner never. */
static int may_go(const struct qem *s, uint32_t v, uint32_t u)
{
	return s->cls[v] == INSIDE || (s->cls[v] == ON_BORDER && edge_faces(s, v, u) == 1);
}

/* The cost of collapsing (a, b) and where the vertex goes: edge_cost, or
 * with held borders the rules of qem.h (INFINITY when neither end may go). */
static double collapse_cost(const struct qem *s, uint32_t a, uint32_t b, double x[3])
{
	if (!s->cls)
		return edge_cost(s, a, b, x);
	int ga = may_go(s, a, b), gb = may_go(s, b, a);
	if (!ga && !gb)
		return INFINITY;
	if (ga && gb && s->cls[a] == INSIDE)
		return edge_cost(s, a, b, x);
	double q[10];
	edge_quadric(s, a, b, FACES | BORDERS, q, NULL);
	if (ga != gb) {
		const double *keep = s->p + 3 * (size_t)(ga ? b : a);
		memcpy(x, keep, sizeof(double[3]));
		return quad_eval(q, keep);
	}
	return segment_cost(q, s->p + 3 * (size_t)a, s->p + 3 * (size_t)b, x);
}

/* The heap key of an edge whose collapse costs cost: cost plus
 * SHAPE_WEIGHT (W_a + W_b) |b - a|^2.  On a plane, where every cost is zero
 * up to rounding, this collapses short edges between small vertices first,
 * so the plane is thinned evenly instead of one vertex swallowing its
 * neighbours one after another (which makes fans, slivers and refused
 * flips); elsewhere it changes the order only between collapses whose
 * distances to their planes are within 1e-3 edge lengths of each other. */
static double edge_key(const struct qem *s, uint32_t a, uint32_t b, double cost)
{
	double len2 = fct_v3_dist2(s->p + 3 * (size_t)a, s->p + 3 * (size_t)b);
	return cost + SHAPE_WEIGHT * (s->q[a].w + s->q[b].w) * len2;
}

/* Heap -------------------------------------------------------------------- */

#define NOPOS UINT32_MAX

static int entry_less(const struct qem *s, const struct entry *x, const struct entry *y)
{
	if (x->key != y->key)
		return x->key < y->key;
	if (x->a != y->a)
		return x->a < y->a;
	return s->ev[2 * (size_t)x->e + 1] < s->ev[2 * (size_t)y->e + 1];
}

static void heap_place(struct qem *s, size_t i, const struct entry *e)
{
	s->heap[i] = *e;
	s->hpos[e->e] = (uint32_t)i;
}

static void sift_up(struct qem *s, size_t i)
{
	struct entry e = s->heap[i];
	while (i > 0) {
		size_t p = (i - 1) / 4;
		if (!entry_less(s, &e, &s->heap[p]))
			break;
		heap_place(s, i, &s->heap[p]);
		i = p;
	}
	heap_place(s, i, &e);
}

static void sift_down(struct qem *s, size_t i)
{
	struct entry e = s->heap[i];
	size_t n = s->nheap;
	for (;;) {
		size_t c = 4 * i + 1, end = c + 4 < n ? c + 4 : n;
		if (c >= n)
			break;
		for (size_t j = c + 1; j < end; j++)
			if (entry_less(s, &s->heap[j], &s->heap[c]))
				c = j;
		if (!entry_less(s, &s->heap[c], &e))
			break;
		heap_place(s, i, &s->heap[c]);
		i = c;
	}
	heap_place(s, i, &e);
}

/* Take edge e out of the heap (if it is in). */
static void heap_remove(struct qem *s, uint32_t e)
{
	uint32_t i = s->hpos[e];
	if (i == NOPOS)
		return;
	s->hpos[e] = NOPOS;
	if (--s->nheap == i)
		return;
	struct entry last = s->heap[s->nheap];
	struct entry old = s->heap[i];
	heap_place(s, i, &last);
	if (entry_less(s, &last, &old))
		sift_up(s, i);
	else
		sift_down(s, i);
}

/* Cost edge e afresh and put it in the heap, or move it to its new place. */
static void heap_set(struct qem *s, uint32_t e)
{
	uint32_t a = s->ev[2 * (size_t)e], b = s->ev[2 * (size_t)e + 1];
	double x[3], cost = collapse_cost(s, a, b, x);
	if (cost == INFINITY) {
		heap_remove(s, e);   /* until an end changes */
		return;
	}
	struct entry n = {edge_key(s, a, b, cost), e, a};
	uint32_t i = s->hpos[e];
	if (i == NOPOS) {
		heap_place(s, s->nheap++, &n);
		sift_up(s, s->nheap - 1);
		return;
	}
	struct entry old = s->heap[i];
	heap_place(s, i, &n);
	if (entry_less(s, &n, &old))
		sift_up(s, i);
	else
		sift_down(s, i);
}

/* Put every live edge between unlocked vertices in the heap, costed afresh. */
static void heap_build(struct qem *s)
{
	s->nheap = 0;
	for (size_t e = 0; e < s->ne; e++) {
		s->hpos[e] = NOPOS;
		uint32_t a = s->ev[2 * e], b = s->ev[2 * e + 1];
		if (a == DEAD || ((s->flag[a] | s->flag[b]) & LOCKED))
			continue;
		double x[3], cost = collapse_cost(s, a, b, x);
		if (cost == INFINITY)
			continue;
		struct entry n = {edge_key(s, a, b, cost), (uint32_t)e, a};
		heap_place(s, s->nheap++, &n);
	}
	for (size_t i = (s->nheap + 2) / 4; i-- > 0;)
		sift_down(s, i);
}

/* Neighbour sets ---------------------------------------------------------- */

/* A fresh stamp st for marking vertices, with st + 1 fresh too. */
static uint32_t next_stamp(struct qem *s)
{
	if (s->stamp >= UINT32_MAX - 4) {
		memset(s->mark, 0, s->nv * sizeof *s->mark);
		s->stamp = 0;
	}
	s->stamp += 2;
	return s->stamp - 1;
}

/* Lists ------------------------------------------------------------------- */

static int item_live(const struct lists *l, uint32_t i)
{
	return l->live[l->stride * i] != DEAD;
}

/* Room for n entries at the end of the pool; rewrites the pool without dead
 * items and spare room once it has grown to four times its first size. */
static int lists_reserve(struct lists *l, size_t nv, size_t n, struct fct_err *err)
{
	if (l->n + n <= l->pool_cap)
		return 0;
	if (l->n > 4 * l->base) {
		size_t total = n;
		for (size_t v = 0; v < nv; v++)
			total += l->cnt[v];
		uint32_t *np = fct_alloc_array(total, sizeof *np, err);
		if (!np)
			return -1;
		size_t k = 0;
		for (size_t v = 0; v < nv; v++) {
			uint32_t c = 0;
			for (uint32_t i = 0; i < l->cnt[v]; i++) {
				uint32_t t = l->pool[l->st[v] + i];
				if (item_live(l, t))
					np[k + c++] = t;
			}
			l->st[v] = (uint32_t)k, l->cnt[v] = c, l->cap[v] = c;
			k += c;
		}
		free(l->pool);
		l->pool = np, l->n = k, l->pool_cap = total;
		if (l->n + n <= l->pool_cap)
			return 0;
	}
	if (l->n + n > UINT32_MAX)
		return fct_fail(err, "too many triangles for the vertex lists");
	return fct_grow((void **)&l->pool, &l->pool_cap, l->n + n, sizeof *l->pool, err);
}

/* keep's list becomes its live items followed by gone's; gone's is emptied. */
static int lists_merge(struct lists *l, size_t nv, uint32_t keep, uint32_t gone,
                       struct fct_err *err)
{
	uint32_t need = 0;
	for (int side = 0; side < 2; side++) {
		uint32_t v = side ? gone : keep;
		for (uint32_t i = 0; i < l->cnt[v]; i++)
			need += item_live(l, l->pool[l->st[v] + i]);
	}
	uint32_t dst, n = 0;
	if (need <= l->cap[keep]) {
		dst = l->st[keep];   /* in place: keep's live entries only move down */
	} else {
		if (lists_reserve(l, nv, 2 * (size_t)need, err))
			return -1;
		dst = (uint32_t)l->n;
		l->n += 2 * (size_t)need;
		l->cap[keep] = 2 * need;
	}
	for (int side = 0; side < 2; side++) {
		uint32_t v = side ? gone : keep;
		uint32_t src = l->st[v];
		for (uint32_t i = 0; i < l->cnt[v]; i++) {
			uint32_t t = l->pool[src + i];
			if (item_live(l, t))
				l->pool[dst + n++] = t;
		}
	}
	l->st[keep] = dst, l->cnt[keep] = n;
	l->cnt[gone] = 0;
	return 0;
}

/* Fill l from compressed rows: items of v are items[start[v] .. start[v+1]). */
static int lists_init(struct lists *l, size_t nv, const uint32_t *start, const uint32_t *items,
                      const uint32_t *live, size_t stride, struct fct_err *err)
{
	size_t nv1 = nv ? nv : 1, n = nv ? start[nv] : 0;
	l->live = live, l->stride = stride, l->base = n;
	l->n = n, l->pool_cap = n ? n : 1;
	if (!(l->st = fct_alloc_array(nv1, sizeof *l->st, err)) ||
	    !(l->cnt = fct_alloc_array(nv1, sizeof *l->cnt, err)) ||
	    !(l->cap = fct_alloc_array(nv1, sizeof *l->cap, err)) ||
	    !(l->pool = fct_alloc_array(l->pool_cap, sizeof *l->pool, err)))
		return -1;
	if (n)
		memcpy(l->pool, items, n * sizeof *items);
	for (size_t v = 0; v < nv; v++) {
		l->st[v] = start[v];
		l->cnt[v] = l->cap[v] = start[v + 1] - start[v];
	}
	return 0;
}

static void lists_free(struct lists *l)
{
	free(l->st);
	free(l->cnt);
	free(l->cap);
	free(l->pool);
}

/* Collapse ---------------------------------------------------------------- */

static int tri_has(const uint32_t *t, uint32_t v)
{
	return t[0] == v || t[1] == v || t[2] == v;
}

/* Number of live triangles around v that hold the edge (v, u). */
static int edge_faces(const struct qem *s, uint32_t v, uint32_t u)
{
	int n = 0;
	const uint32_t *l = s->vt.pool + s->vt.st[v];
	for (uint32_t i = 0; i < s->vt.cnt[v]; i++) {
		const uint32_t *t = s->tri + 3 * (size_t)l[i];
		if (t[0] != DEAD && tri_has(t, u))
			n++;
	}
	return n;
}

/* Does an edge of v have one live triangle? */
static int on_border(const struct qem *s, uint32_t v)
{
	const uint32_t *l = s->vt.pool + s->vt.st[v];
	for (uint32_t i = 0; i < s->vt.cnt[v]; i++) {
		const uint32_t *t = s->tri + 3 * (size_t)l[i];
		if (t[0] == DEAD)
			continue;
		for (int k = 0; k < 3; k++)
			if (t[k] != v && edge_faces(s, v, t[k]) == 1)
				return 1;
	}
	return 0;
}

/* Does a live triangle around v hold both u and w? */
static int has_triangle(const struct qem *s, uint32_t v, uint32_t u, uint32_t w)
{
	const uint32_t *l = s->vt.pool + s->vt.st[v];
	for (uint32_t i = 0; i < s->vt.cnt[v]; i++) {
		const uint32_t *t = s->tri + 3 * (size_t)l[i];
		if (t[0] != DEAD && tri_has(t, u) && tri_has(t, w))
			return 1;
	}
	return 0;
}

/* The link condition and border rules for collapsing (a, b) (see qem.h);
 * *dying gets the number of triangles the collapse removes and *hole the
 * third corner of a triangular hole the collapse closes (NOHOLE if none).
 * 1 when it may be collapsed. */
static int link_ok(struct qem *s, uint32_t a, uint32_t b, int *dying, uint32_t *hole)
{
	uint32_t opp[2];
	int nopp = 0;
	*hole = NOHOLE;
	uint32_t st = next_stamp(s);   /* st + 1 marks a common neighbour counted */
	const uint32_t *l = s->vt.pool + s->vt.st[a];
	for (uint32_t i = 0; i < s->vt.cnt[a]; i++) {
		const uint32_t *t = s->tri + 3 * (size_t)l[i];
		if (t[0] == DEAD)
			continue;
		if (tri_has(t, b)) {
			if (nopp == 2)
				return 0;   /* a non-manifold edge (cannot be: its ends are locked) */
			opp[nopp++] = t[0] != a && t[0] != b ? t[0] : t[1] != a && t[1] != b ? t[1] : t[2];
		}
		for (int k = 0; k < 3; k++)
			if (t[k] != a)
				s->mark[t[k]] = st;
	}
	*dying = nopp;
	if (nopp == 0)
		return 0;
	int common = 0;
	uint32_t other = NOHOLE;   /* a common neighbour that is not opposite */
	l = s->vt.pool + s->vt.st[b];
	for (uint32_t i = 0; i < s->vt.cnt[b]; i++) {
		const uint32_t *t = s->tri + 3 * (size_t)l[i];
		if (t[0] == DEAD)
			continue;
		for (int k = 0; k < 3; k++)
			if (t[k] != b && t[k] != a && s->mark[t[k]] == st) {
				s->mark[t[k]] = st + 1;
				common++;
				if (t[k] != opp[0] && (nopp == 1 || t[k] != opp[1]))
					other = t[k];
			}
	}
	if (nopp == 2 && opp[0] == opp[1])
		return 0;   /* the same triangle twice over the edge */
	int ba = s->flag[a] & BORDER, bb = s->flag[b] & BORDER;
	if (nopp == 2) {
		if (common != 2 || (ba && bb))
			return 0;   /* a common neighbour off the edge, or a pinch between two borders */
		/* a tetrahedron's fold: triangles (a, c, d) and (b, c, d) both present */
		if (has_triangle(s, a, opp[0], opp[1]) && has_triangle(s, b, opp[0], opp[1]))
			return 0;
		return 1;
	}
	/* A border edge: its triangle must not have its other two edges on the border too. */
	if (edge_faces(s, a, opp[0]) == 1 && edge_faces(s, b, opp[0]) == 1)
		return 0;
	if (common == 1)
		return 1;
	/* The one other common neighbour h may close a triangular hole (a, b, h):
	 * (a, h) and (b, h) border edges, and no fold (triangles (a, c, h) and
	 * (b, c, h) both present). */
	if (common != 2 || !s->close_holes || edge_faces(s, a, other) != 1 ||
	    edge_faces(s, b, other) != 1 ||
	    (has_triangle(s, a, opp[0], other) && has_triangle(s, b, opp[0], other)))
		return 0;
	*hole = other;
	return 1;
}

/* The longest edge of triangle c, to the fourth power. */
static double before_l4(const double *const c[3])
{
	double l2 = fct_v3_dist2(c[0], c[1]), m2 = fct_v3_dist2(c[1], c[2]), k2 = fct_v3_dist2(c[2], c[0]);
	l2 = m2 > l2 ? m2 : l2;
	l2 = k2 > l2 ? k2 : l2;
	return l2 * l2;
}

/* Held borders with a viewpoint (one view's mesh): would the triangle with
 * corners c before (normal n0) and n after (normal n1) turn to face the
 * other way as seen from the viewpoint?  A depth map's surface is a height
 * field over its image; so it must stay, or its triangles fold over its
 * borders in the image, where the planes beside them are triangulated. */
static int turns_from_view(const struct qem *s, const double *const c[3], const double *const n[3],
                           const double n0[3], const double n1[3])
{
	double g0[3], g1[3];
	for (int i = 0; i < 3; i++) {
		g0[i] = (c[0][i] + c[1][i] + c[2][i]) / 3 - s->vp[i];
		g1[i] = (n[0][i] + n[1][i] + n[2][i]) / 3 - s->vp[i];
	}
	double r0 = fct_v3_dot(n0, g0), r1 = fct_v3_dot(n1, g1);
	return r0 != 0 && !(r0 * r1 > 0);
}

/* Would moving a and b to x turn or flatten a surviving triangle? */
static int flips(const struct qem *s, uint32_t a, uint32_t b, const double x[3])
{
	for (int side = 0; side < 2; side++) {
		uint32_t v = side ? b : a, o = side ? a : b;
		const uint32_t *l = s->vt.pool + s->vt.st[v];
		for (uint32_t i = 0; i < s->vt.cnt[v]; i++) {
			const uint32_t *t = s->tri + 3 * (size_t)l[i];
			if (t[0] == DEAD || tri_has(t, o))
				continue;
			const double *c[3], *n[3];
			for (int k = 0; k < 3; k++) {
				c[k] = s->p + 3 * (size_t)t[k];
				n[k] = t[k] == v ? x : c[k];
			}
			double e1[3], e2[3], e3[3], n0[3], n1[3];
			fct_v3_sub(e1, c[1], c[0]);
			fct_v3_sub(e2, c[2], c[0]);
			fct_v3_cross(n0, e1, e2);
			fct_v3_sub(e1, n[1], n[0]);
			fct_v3_sub(e2, n[2], n[0]);
			fct_v3_sub(e3, n[2], n[1]);
			fct_v3_cross(n1, e1, e2);
			double l2 = fct_v3_dot(e1, e1), m2 = fct_v3_dot(e2, e2), k2 = fct_v3_dot(e3, e3);
			if (m2 > l2)
				l2 = m2;
			if (k2 > l2)
				l2 = k2;
			if (!(fct_v3_dot(n1, n1) > 1e-24 * l2 * l2))
				return 1;
			if (fct_v3_dot(n0, n1) <= 0 && (n0[0] != 0 || n0[1] != 0 || n0[2] != 0))
				return 1;
			if (s->cls && s->has_vp && turns_from_view(s, c, n, n0, n1))
				return 1;
			/* Held borders: no sliver thinner than HELD_QUALITY (twice the
			 * area over the longest edge squared) unless it was. */
			if (s->cls && sqrt(fct_v3_dot(n1, n1)) < HELD_QUALITY * l2 &&
			    fct_v3_dot(n1, n1) * before_l4(c) < fct_v3_dot(n0, n0) * l2 * l2)
				return 1;
		}
	}
	return 0;
}

/* Collapse edge e = (a, b) into x. */
static int collapse(struct qem *s, uint32_t e, const double x[3], uint32_t hole,
                    struct fct_err *err)
{
	uint32_t a = s->ev[2 * (size_t)e], b = s->ev[2 * (size_t)e + 1];
	double *pa = s->p + 3 * (size_t)a, *pb = s->p + 3 * (size_t)b;
	double da = fct_v3_dist2(x, pa), db = fct_v3_dist2(x, pb);
	uint32_t keep = db < da ? b : a, gone = keep == a ? b : a;

	/* Interpolation parameter of x along a -> b. */
	double d[3], r[3];
	fct_v3_sub(d, pb, pa);
	fct_v3_sub(r, x, pa);
	double len2 = fct_v3_dot(d, d), t = keep == a ? 0 : 1;
	if (len2 > 0 && !(x[0] == pa[0] && x[1] == pa[1] && x[2] == pa[2]) &&
	    !(x[0] == pb[0] && x[1] == pb[1] && x[2] == pb[2])) {
		t = fct_v3_dot(r, d) / len2;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
	}
	if (s->nattr) {
		double *xa = s->attr + s->nattr * a, *xb = s->attr + s->nattr * b;
		double *xk = s->attr + s->nattr * keep;
		for (size_t k = 0; k < s->nattr; k++)
			xk[k] = t == 0 ? xa[k] : t == 1 ? xb[k] : (1 - t) * xa[k] + t * xb[k];
		if (s->nrm[0] >= 0 && t != 0 && t != 1) {
			double *n0 = xk + s->nrm[0], *n1 = xk + s->nrm[1], *n2 = xk + s->nrm[2];
			double len = sqrt(*n0 * *n0 + *n1 * *n1 + *n2 * *n2);
			if (len > 0)
				*n0 /= len, *n1 /= len, *n2 /= len;
		}
	}

	double *pk = s->p + 3 * (size_t)keep;
	if (pk[0] != x[0] || pk[1] != x[1] || pk[2] != x[2]) {
		memcpy(pk, x, sizeof(double[3]));
		s->flag[keep] |= MOVED;
	}
	for (int k = 0; k < 10; k++)
		s->q[keep].a[k] += s->q[gone].a[k];
	s->q[keep].w += s->q[gone].w;
	if (s->bq[gone] != NOBQ) {
		if (s->bq[keep] == NOBQ) {
			s->bq[keep] = s->bq[gone];
		} else {
			struct quad *qk = &s->bquad[s->bq[keep]];
			const struct quad *qg = &s->bquad[s->bq[gone]];
			for (int k = 0; k < 10; k++)
				qk->a[k] += qg->a[k];
			qk->w += qg->w;
		}
	}
	s->flag[keep] |= s->flag[gone] & BORDER;
	s->flag[gone] &= (unsigned char)~ALIVE;

	/* Triangles: kill the edge's, rename gone to keep in the others. */
	const uint32_t *l = s->vt.pool + s->vt.st[gone];
	for (uint32_t i = 0; i < s->vt.cnt[gone]; i++) {
		uint32_t *tv = s->tri + 3 * (size_t)l[i];
		if (tv[0] == DEAD)
			continue;
		if (tri_has(tv, keep)) {
			tv[0] = DEAD;
			s->live--;
			continue;
		}
		for (int k = 0; k < 3; k++)
			if (tv[k] == gone)
				tv[k] = keep;
	}
	if (lists_merge(&s->vt, s->nv, keep, gone, err))
		return -1;
	if (hole != NOHOLE) {
		/* keep and hole are still on the border if they are on another
		 * loop; if not, the planes that held them to the hole go too. */
		uint32_t ends[2] = {keep, hole};
		for (int k = 0; k < 2; k++)
			if (!on_border(s, ends[k])) {
				s->flag[ends[k]] &= (unsigned char)~BORDER;
				s->bq[ends[k]] = NOBQ;
			}
		s->st->holes_closed++;
	}

	/* Edges: e goes; gone's edges to keep's neighbours (the opposite
	 * corners) go too, the others are renamed. */
	heap_remove(s, e);
	s->ev[2 * (size_t)e] = DEAD;
	uint32_t st = next_stamp(s);
	l = s->ve.pool + s->ve.st[keep];
	for (uint32_t i = 0; i < s->ve.cnt[keep]; i++) {
		const uint32_t *ev = s->ev + 2 * (size_t)l[i];
		if (ev[0] != DEAD)
			s->mark[ev[0] == keep ? ev[1] : ev[0]] = st;
	}
	l = s->ve.pool + s->ve.st[gone];
	for (uint32_t i = 0; i < s->ve.cnt[gone]; i++) {
		uint32_t g = l[i], *ev = s->ev + 2 * (size_t)g;
		if (ev[0] == DEAD)
			continue;
		uint32_t n = ev[0] == gone ? ev[1] : ev[0];
		if (s->mark[n] == st) {
			heap_remove(s, g);
			ev[0] = DEAD;
			continue;
		}
		ev[0] = keep < n ? keep : n;
		ev[1] = keep < n ? n : keep;
	}
	if (lists_merge(&s->ve, s->nv, keep, gone, err))
		return -1;
	l = s->ve.pool + s->ve.st[keep];
	for (uint32_t i = 0; i < s->ve.cnt[keep]; i++) {
		uint32_t g = l[i];
		const uint32_t *ev = s->ev + 2 * (size_t)g;
		if (!((s->flag[ev[0]] | s->flag[ev[1]]) & LOCKED))
			heap_set(s, g);
	}
	s->st->collapses++;
	return 0;
}

/* One pass: collapse from the top of the heap until it is empty or the
 * target is reached.  A refused edge leaves the heap until one of its ends
 * changes (or the next pass). */
static int run_pass(struct qem *s, struct fct_err *err)
{
	while (s->nheap > 0 && s->live > s->target) {
		uint32_t e = s->heap[0].e;
		heap_remove(s, e);
		uint32_t a = s->ev[2 * (size_t)e], b = s->ev[2 * (size_t)e + 1];
		double x[3], fq[10], bqd[10], w, wb;
		if (collapse_cost(s, a, b, x) == INFINITY)
			continue;
		edge_quadric(s, a, b, FACES, fq, &w);
		edge_quadric(s, a, b, BORDERS, bqd, &wb);
		double fcost = quad_eval(fq, x), bcost = quad_eval(bqd, x);
		double d2 = w > 0 ? fcost / w : fcost > 0 ? INFINITY : 0;
		if (wb > 0 && bcost / wb > d2)
			d2 = bcost / wb;
		if (d2 > s->max_err2) {
			s->st->refused_error++;
			continue;
		}
		if (s->vt.cnt[a] + s->vt.cnt[b] > MAX_FAN) {
			s->st->refused_topology++;
			continue;
		}
		int dying = 0;
		uint32_t hole;
		if (!link_ok(s, a, b, &dying, &hole)) {
			s->st->refused_topology++;
			continue;
		}
		if (s->live - (size_t)dying < s->target)
			continue;
		if (flips(s, a, b, x)) {
			s->st->refused_flip++;
			continue;
		}
		if (d2 > s->st->max_error)
			s->st->max_error = d2;   /* squared until the end */
		if (fcost > s->st->max_cost)
			s->st->max_cost = fcost;
		if (collapse(s, e, x, hole, err))
			return -1;
	}
	return 0;
}

/* Set-up ------------------------------------------------------------------ */

/* Add a border plane carrying weight w, its quadric weighted wq, to v's
 * border quadric (made on first use; there is room for one per border
 * vertex). */
static void border_plane(struct qem *s, uint32_t v, const double n[3], double d, double wq,
                         double w)
{
	if (s->bq[v] == NOBQ) {
		s->bq[v] = (uint32_t)s->nbquad++;
		memset(&s->bquad[s->bq[v]], 0, sizeof s->bquad[0]);
	}
	quad_add_plane(&s->bquad[s->bq[v]], n, d, wq);
	s->bquad[s->bq[v]].w += w;
}

/* From the adjacency of the triangles: the edges and the vertex lists; lock
 * the vertices on non-manifold edges; flag the border vertices; add the
 * border planes. */
static int find_topology(struct qem *s, double border_weight, double border_tol,
                         const unsigned char *corner, struct fct_err *err)
{
	struct fct_mesh tm;
	struct fct_adj adj;
	fct_mesh_init(&tm);
	memset(&adj, 0, sizeof adj);
	uint32_t *fs = fct_alloc_array(s->nt + 1, sizeof *fs, err);
	uint32_t *vstart = fct_alloc_array(s->nv + 1, sizeof *vstart, err);
	uint32_t *vedge = NULL;
	int rc = -1;
	if (!fs || !vstart)
		goto out;
	for (size_t t = 0; t <= s->nt; t++)
		fs[t] = (uint32_t)(3 * t);
	tm.nv = s->nv, tm.nf = s->nt, tm.fstart = fs, tm.fvert = s->tri;
	if (fct_adj_build(&adj, &tm, err))
		goto out;
	s->ne = adj.ne;
	if (!(s->ev = fct_alloc_array(2 * s->ne, sizeof *s->ev, err)) ||
	    !(s->hpos = fct_alloc_array(s->ne, sizeof *s->hpos, err)) ||
	    !(s->heap = fct_alloc_array(s->ne, sizeof *s->heap, err)) ||
	    !(vedge = fct_alloc_array(2 * s->ne, sizeof *vedge, err)))
		goto out;
	memcpy(s->ev, adj.edge_v, 2 * s->ne * sizeof *s->ev);
	memset(vstart, 0, (s->nv + 1) * sizeof *vstart);
	size_t nborder = 0;
	for (size_t e = 0; e < adj.ne; e++) {
		uint32_t n = fct_adj_edge_nfaces(&adj, e);
		uint32_t u = adj.edge_v[2 * e], v = adj.edge_v[2 * e + 1];
		vstart[u + 1]++, vstart[v + 1]++;
		if (n > 2) {
			s->flag[u] |= LOCKED, s->flag[v] |= LOCKED;
		} else if (n == 1) {
			nborder += !(s->flag[u] & BORDER) + !(s->flag[v] & BORDER);
			s->flag[u] |= BORDER, s->flag[v] |= BORDER;
		}
	}
	if (!(s->bq = fct_alloc_array(s->nv, sizeof *s->bq, err)) ||
	    !(s->bquad = fct_alloc_array(nborder, sizeof *s->bquad, err)))
		goto out;
	for (size_t v = 0; v < s->nv; v++)
		s->bq[v] = NOBQ;
	for (size_t e = 0; e < adj.ne && border_weight > 0; e++) {
		if (fct_adj_edge_nfaces(&adj, e) != 1)
			continue;
		uint32_t u = adj.edge_v[2 * e], v = adj.edge_v[2 * e + 1];
		const uint32_t *t = s->tri + 3 * (size_t)adj.edge_f[adj.edge_fstart[e]];
		const double *pu = s->p + 3 * (size_t)u, *pv = s->p + 3 * (size_t)v;
		double fn[3], dir[3], m[3], e2[3];
		fct_v3_sub(dir, s->p + 3 * (size_t)t[1], s->p + 3 * (size_t)t[0]);
		fct_v3_sub(e2, s->p + 3 * (size_t)t[2], s->p + 3 * (size_t)t[0]);
		fct_v3_cross(fn, dir, e2);
		fct_v3_sub(dir, pv, pu);
		fct_v3_cross(m, dir, fn);
		double len = sqrt(fct_v3_dot(m, m));
		if (len > 0) {
			m[0] /= len, m[1] /= len, m[2] /= len;
			double l2 = fct_v3_dot(dir, dir), w = border_weight * l2, dd = -fct_v3_dot(m, pu);
			if (s->cls) {
				/* Held borders: in units of border_tol times the edge. */
				double wq = border_weight / (border_tol * border_tol * l2);
				border_plane(s, u, m, dd, wq, border_weight);
				border_plane(s, v, m, dd, wq, border_weight);
			} else {
				border_plane(s, u, m, dd, w, w);
				border_plane(s, v, m, dd, w, w);
			}
		}
	}
	/* Edges of each vertex, in edge order. */
	for (size_t v = 0; v < s->nv; v++)
		vstart[v + 1] += vstart[v];
	for (size_t e = 0; e < adj.ne; e++)
		for (int k = 0; k < 2; k++)
			vedge[vstart[adj.edge_v[2 * e + (size_t)k]]++] = (uint32_t)e;
	for (size_t v = s->nv; v > 0; v--)
		vstart[v] = vstart[v - 1];
	vstart[0] = 0;
	if (lists_init(&s->ve, s->nv, vstart, vedge, s->ev, 2, err) ||
	    lists_init(&s->vt, s->nv, adj.vert_fstart, adj.vert_f, s->tri, 3, err))
		goto out;

	for (size_t v = 0; v < s->nv; v++)
		s->st->locked += (s->flag[v] & LOCKED) != 0;
	if (s->cls) {
		/* Border edges at each vertex: none inside, two on a border. */
		memset(s->cls, 0, s->nv);
		for (size_t e = 0; e < adj.ne; e++)
			if (fct_adj_edge_nfaces(&adj, e) == 1)
				for (int k = 0; k < 2; k++) {
					unsigned char *c = &s->cls[adj.edge_v[2 * e + (size_t)k]];
					*c += *c < 3;
				}
		for (size_t v = 0; v < s->nv; v++) {
			s->cls[v] = s->cls[v] == 0 ? INSIDE : s->cls[v] == 2 ? ON_BORDER : CORNER;
			if (corner && corner[v])
				s->cls[v] = CORNER;
			s->st->corners += s->cls[v] == CORNER;
		}
	}
	rc = 0;
out:
	fct_adj_free(&adj);
	free(fs);
	free(vstart);
	free(vedge);
	return rc;
}

static void qem_free(struct qem *s)
{
	free(s->p);
	free(s->q);
	free(s->bq);
	free(s->bquad);
	free(s->flag);
	free(s->tri);
	free(s->ev);
	free(s->hpos);
	lists_free(&s->vt);
	lists_free(&s->ve);
	free(s->mark);
	free(s->heap);
	free(s->attr);
	free(s->cls);
	free(s->wv);
}

void fct_qem_params_default(struct fct_qem_params *p)
{
	p->target_faces = 0;
	p->max_error = 0;
	p->border_weight = 1;
	p->close_holes = 0;
	p->hold_borders = 0;
	p->border_tol = 1;
	p->corner = NULL;
	p->sigma = NULL;
	p->use_viewpoint = 0;
	p->viewpoint[0] = p->viewpoint[1] = p->viewpoint[2] = 0;
	p->use_centre = 0;
	p->centre[0] = p->centre[1] = p->centre[2] = 0;
}

/* The squared noise across triangle tv's plane (unit normal n): see qem.h. */
static double triangle_noise2(const struct qem *s, const uint32_t *tv, const double n[3])
{
	double s2 = (1 / s->wv[tv[0]] + 1 / s->wv[tv[1]] + 1 / s->wv[tv[2]]) / 3;
	if (!s->has_vp)
		return s2;
	const double *a = s->p + 3 * (size_t)tv[0], *b = s->p + 3 * (size_t)tv[1];
	const double *c = s->p + 3 * (size_t)tv[2];
	double g[3], r[3];
	for (int i = 0; i < 3; i++)
		g[i] = (a[i] + b[i] + c[i]) / 3;
	fct_v3_sub(r, g, s->vp);
	double r2 = fct_v3_dot(r, r), cos2 = 1;
	if (r2 > 0) {
		double nr = fct_v3_dot(n, r);
		cos2 = nr * nr / r2;
	}
	double l = (sqrt(fct_v3_dist2(a, b)) + sqrt(fct_v3_dist2(b, c)) + sqrt(fct_v3_dist2(c, a))) / 3;
	double e = s2 * cos2 + l * l * (1 - cos2);
	return e > 0 ? e : s2 > 0 ? s2 : 1;
}

/* The interpolated vertex properties: scalar float and double columns. */
static int is_interpolated(const struct fct_prop *p)
{
	return p->count_type == FCT_NONE && (p->type == FCT_FLOAT32 || p->type == FCT_FLOAT64);
}

/* Triangles of m: faces fanned, those with a repeated corner dropped;
 * src[t] gets each triangle's face. */
static int make_triangles(struct qem *s, const struct fct_mesh *m, size_t **src,
                          struct fct_err *err)
{
	size_t nt = 0;
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t k = fct_face_size(m, f);
		if (k >= 3)
			nt += k - 2;
	}
	if (nt > UINT32_MAX / 3)
		return fct_fail(err, "%zu triangles: too many", nt);
	s->tri = fct_alloc_array(3 * nt, sizeof *s->tri, err);
	*src = fct_alloc_array(nt, sizeof **src, err);
	if (!s->tri || !*src)
		return -1;
	size_t n = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *fv = m->fvert + m->fstart[f];
		uint32_t k = fct_face_size(m, f);
		for (uint32_t i = 1; i + 1 < k; i++) {
			uint32_t a = fv[0], b = fv[i], c = fv[i + 1];
			if (a == b || b == c || a == c) {
				s->st->dropped++;
				continue;
			}
			s->tri[3 * n] = a, s->tri[3 * n + 1] = b, s->tri[3 * n + 2] = c;
			(*src)[n++] = f;
		}
	}
	s->nt = n;
	return 0;
}

/* Write the result into m. */
static int write_back(struct qem *s, struct fct_mesh *m, const size_t *src, const double ctr[3],
                      struct fct_err *err)
{
	size_t nkf = 0, nkv = 0;
	for (size_t t = 0; t < s->nt; t++)
		nkf += s->tri[3 * t] != DEAD;
	for (size_t v = 0; v < s->nv; v++)
		nkv += (s->flag[v] & ALIVE) != 0;
	size_t *keep = fct_alloc_array(nkf > nkv ? nkf : nkv, sizeof *keep, err);
	if (!keep)
		return -1;
	size_t k = 0;
	for (size_t t = 0; t < s->nt; t++)
		if (s->tri[3 * t] != DEAD)
			keep[k++] = src[t];
	int rc = -1;
	if (fct_elem_gather(&m->face, keep, nkf, err) || fct_mesh_set_triangle_count(m, nkf, err))
		goto out;
	k = 0;
	for (size_t t = 0; t < s->nt; t++)
		if (s->tri[3 * t] != DEAD) {
			memcpy(m->fvert + 3 * k, s->tri + 3 * t, 3 * sizeof *m->fvert);
			k++;
		}
	k = 0;
	for (size_t v = 0; v < s->nv; v++)
		if (s->flag[v] & ALIVE)
			keep[k++] = v;
	if (fct_mesh_gather_vertices(m, keep, nkv, err))
		goto out;
	if (m->nf != nkf)
		abort();   /* every kept triangle names kept vertices */
	for (size_t i = 0; i < nkv; i++) {
		size_t v = keep[i];
		if (s->flag[v] & MOVED)
			for (int c = 0; c < 3; c++)
				m->xyz[3 * i + (size_t)c] = s->p[3 * v + (size_t)c] + ctr[c];
	}
	size_t col = 0;
	for (size_t j = 0; j < m->vertex.nprops; j++) {
		struct fct_prop *p = &m->vertex.props[j];
		if (!is_interpolated(p))
			continue;
		for (size_t i = 0; i < nkv; i++)
			fct_prop_set(p, i, s->attr[s->nattr * keep[i] + col]);
		col++;
	}
	fct_mesh_remove_elem(m, "edge");
	rc = 0;
out:
	free(keep);
	return rc;
}

int fct_qem_centre(double centre[3], const struct fct_mesh *m, struct fct_err *err)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (size_t v = 0; v < m->nv; v++)
		for (int c = 0; c < 3; c++) {
			double x = m->xyz[3 * v + (size_t)c];
			if (!isfinite(x))
				return fct_fail(err, "vertex %zu: coordinate is not finite", v);
			lo[c] = x < lo[c] ? x : lo[c];
			hi[c] = x > hi[c] ? x : hi[c];
		}
	for (int c = 0; c < 3; c++)
		centre[c] = m->nv ? 0.5 * lo[c] + 0.5 * hi[c] : 0;
	return 0;
}

int fct_qem_decimate(struct fct_mesh *m, const struct fct_qem_params *p,
                     struct fct_qem_stats *st, struct fct_err *err)
{
	struct fct_qem_stats local;
	struct qem s;
	size_t *src = NULL;
	int rc = -1;
	if (!st)
		st = &local;
	memset(st, 0, sizeof *st);
	memset(&s, 0, sizeof s);
	s.st = st;
	s.nv = m->nv;
	s.target = p->target_faces;
	s.close_holes = p->close_holes;
	s.max_err2 = p->max_error > 0 ? p->max_error * p->max_error : INFINITY;
	st->vertices_in = m->nv;

	double ctr[3];
	if (fct_qem_centre(ctr, m, err))
		return -1;
	if (p->use_centre)
		memcpy(ctr, p->centre, sizeof ctr);

	if (make_triangles(&s, m, &src, err))
		goto out;
	st->faces_in = s.live = s.nt;
	if (s.nt == 0) {
		/* Nothing to collapse (a point cloud, or only degenerate faces):
		 * the faces go and the vertices stay as they are, without the
		 * quadrics and lists of a few hundred bytes a vertex that
		 * decimation needs (3.3 GB for a 300 MB point cloud). */
		if (fct_elem_gather(&m->face, src, 0, err) || fct_mesh_set_triangle_count(m, 0, err))
			goto out;
		fct_mesh_remove_elem(m, "edge");
		st->vertices_out = m->nv;
		rc = 0;
		goto out;
	}
	size_t nv1 = s.nv ? s.nv : 1;
	if (!(s.p = fct_alloc_array(3 * nv1, sizeof *s.p, err)) ||
	    !(s.q = fct_alloc_array(nv1, sizeof *s.q, err)) ||
	    !(s.flag = fct_alloc_array(nv1, 1, err)) ||
	    !(s.mark = fct_alloc_array(nv1, sizeof *s.mark, err)))
		goto out;
	memset(s.q, 0, nv1 * sizeof *s.q);
	memset(s.mark, 0, nv1 * sizeof *s.mark);
	for (size_t v = 0; v < s.nv; v++) {
		for (int c = 0; c < 3; c++)
			s.p[3 * v + (size_t)c] = m->xyz[3 * v + (size_t)c] - ctr[c];
		s.flag[v] = ALIVE;
	}

	/* Interpolated properties. */
	s.nrm[0] = s.nrm[1] = s.nrm[2] = -1;
	for (size_t j = 0; j < m->vertex.nprops; j++) {
		const struct fct_prop *pr = &m->vertex.props[j];
		if (!is_interpolated(pr))
			continue;
		static const char *const nn[3] = {"nx", "ny", "nz"};
		for (int c = 0; c < 3; c++)
			if (!strcmp(pr->name, nn[c]))
				s.nrm[c] = (long)s.nattr;
		s.nattr++;
	}
	if (s.nrm[0] < 0 || s.nrm[1] < 0 || s.nrm[2] < 0)
		s.nrm[0] = s.nrm[1] = s.nrm[2] = -1;
	if (s.nattr) {
		size_t n;
		if (fct_mul_size(s.nattr, nv1, &n)) {
			fct_fail(err, "too many vertex properties");
			goto out;
		}
		if (!(s.attr = fct_alloc_array(n, sizeof *s.attr, err)))
			goto out;
		size_t col = 0;
		for (size_t j = 0; j < m->vertex.nprops; j++) {
			const struct fct_prop *pr = &m->vertex.props[j];
			if (!is_interpolated(pr))
				continue;
			for (size_t v = 0; v < s.nv; v++)
				s.attr[s.nattr * v + col] = fct_prop_get(pr, v);
			col++;
		}
	}

	/* Face quadrics, weighted by area (over the noise across them). */
	if (p->sigma) {
		if (!(s.wv = fct_alloc_array(nv1, sizeof *s.wv, err)))
			goto out;
		for (size_t v = 0; v < s.nv; v++) {
			double sg = p->sigma[v];
			s.wv[v] = sg > 0 && isfinite(sg) ? 1 / (sg * sg) : 1;
		}
		s.has_vp = p->use_viewpoint;
		fct_v3_sub(s.vp, p->viewpoint, ctr);
	}
	for (size_t t = 0; t < s.nt; t++) {
		const uint32_t *tv = s.tri + 3 * t;
		const double *a = s.p + 3 * (size_t)tv[0], *b = s.p + 3 * (size_t)tv[1];
		const double *c = s.p + 3 * (size_t)tv[2];
		double e1[3], e2[3], n[3];
		fct_v3_sub(e1, b, a);
		fct_v3_sub(e2, c, a);
		fct_v3_cross(n, e1, e2);
		double len = sqrt(fct_v3_dot(n, n));
		if (!(len > 0) || !isfinite(len))
			continue;
		n[0] /= len, n[1] /= len, n[2] /= len;
		double d = -fct_v3_dot(n, a), area = 0.5 * len;
		double wq = s.wv ? area / triangle_noise2(&s, tv, n) : area;
		for (int k = 0; k < 3; k++) {
			quad_add_plane(&s.q[tv[k]], n, d, wq);
			s.q[tv[k]].w += area;
		}
	}
	if (p->hold_borders && !(s.cls = fct_alloc_array(nv1, 1, err)))
		goto out;
	if (find_topology(&s, p->border_weight, p->border_tol, p->corner, err))
		goto out;

	for (;;) {
		size_t before = st->collapses;
		size_t refused[3] = {st->refused_topology, st->refused_flip, st->refused_error};
		heap_build(&s);
		st->passes++;
		if (run_pass(&s, err))
			goto out;
		st->last_refused[0] = st->refused_topology - refused[0];
		st->last_refused[1] = st->refused_flip - refused[1];
		st->last_refused[2] = st->refused_error - refused[2];
		if (s.live <= s.target || st->collapses == before || st->passes >= MAX_PASSES)
			break;
	}
	st->max_error = sqrt(st->max_error);
	if (write_back(&s, m, src, ctr, err))
		goto out;
	st->faces_out = m->nf;
	st->vertices_out = m->nv;
	rc = 0;
out:
	free(src);
	qem_free(&s);
	return rc;
}
