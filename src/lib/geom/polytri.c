/* polytri.c - greedy and constrained Delaunay triangulation of a polygon
 * with holes (Kang, Johnson, Szeliski, DEC CRL 95/7, section 4); see
 * polytri.h for the method and its cost. */
#include "geom/polytri.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/delaunay.h"
#include "geom/predicates.h"

#define F_INSIDE 8u
#define F_OUTSIDE 16u
#define F_EDGES 7u

/* A half-edge record for matching triangle edges: the edge (a, b) with
 * a < b of triangle t, edge e; outside marks an edge of a triangle around a
 * cavity (t may then be -1 for the hull). */
struct rec {
	int32_t a, b, t;
	int8_t e, outside, cons;
};

/* A wedge seen from a vertex v: the rays v -> ra and v -> rb (counter-
 * clockwise), looking through the window edge ea-eb (ea on ra's side),
 * edge e of triangle t on v's side. */
struct funnel {
	int32_t ra, rb, ea, eb, t, e;
};

/* The greedy method follows a wedge through at most this many triangles
 * per vertex expansion before it falls back to the k-d tree. */
#define FUNNEL_STEPS 16

/* The triangulation: triangle t has corners tv[3t..3t+2] counter-clockwise,
 * edge e running from corner e to corner e+1, tn[3t+e] the triangle across
 * edge e (-1 on the hull), tf[t] the constrained bits of its edges and the
 * inside/outside marks.  vt[v] is some triangle with corner v. */
struct ct {
	const double *xy;
	size_t np, nt;
	int32_t *tv, *tn, *vt;
	uint32_t *deg;           /* greedy: triangles around v when last counted */
	uint8_t *tf;
	uint32_t *stamp, epoch;
	/* scratch, grown as needed */
	int32_t *ring, *cav, *left, *right, *poly, *newt, *stack, *cones, *direct;
	size_t ring_cap, cav_cap, left_cap, right_cap, poly_cap, newt_cap, stack_cap, cones_cap, direct_cap;
	struct funnel *fun;
	size_t fun_cap;
	size_t nring, ncav, nleft, nright, nnew;
	struct rec *recs;
	size_t rec_cap;
	struct fct_polytri_stats *st;
	struct fct_err *err;
};

static void ct_free(struct ct *c)
{
	free(c->tv), free(c->tn), free(c->vt), free(c->tf), free(c->stamp), free(c->deg);
	free(c->ring), free(c->cav), free(c->left), free(c->right), free(c->poly);
	free(c->newt), free(c->stack), free(c->recs), free(c->cones), free(c->direct), free(c->fun);
}

static int push32(int32_t **a, size_t *n, size_t *cap, int32_t v, struct fct_err *err)
{
	if (*n >= *cap && fct_grow((void **)a, cap, *n + 1, sizeof **a, err))
		return -1;
	(*a)[(*n)++] = v;
	return 0;
}

static double orient(const struct ct *c, int32_t a, int32_t b, int32_t d)
{
	return fct_orient2d(&c->xy[2 * a], &c->xy[2 * b], &c->xy[2 * d]);
}

/* The corner of t that is v, or -1. */
static int vidx(const struct ct *c, int32_t t, int32_t v)
{
	const int32_t *p = &c->tv[3 * (size_t)t];
	return p[0] == v ? 0 : p[1] == v ? 1 : p[2] == v ? 2 : -1;
}

/* The edge of t joining x and y (either way), or -1. */
static int eidx(const struct ct *c, int32_t t, int32_t x, int32_t y)
{
	const int32_t *p = &c->tv[3 * (size_t)t];
	for (int e = 0; e < 3; e++) {
		int32_t a = p[e], b = p[(e + 1) % 3];
		if ((a == x && b == y) || (a == y && b == x))
			return e;
	}
	return -1;
}

/* The triangles around v into c->ring (counter-clockwise from vt[v], then
 * clockwise from it when the hull stops the turn); returns 0 or -1. */
static int around(struct ct *c, int32_t v)
{
	c->nring = 0;
	int32_t t0 = c->vt[v], t = t0, nb;
	do {
		if (push32(&c->ring, &c->nring, &c->ring_cap, t, c->err))
			return -1;
		int i = vidx(c, t, v);
		nb = c->tn[3 * (size_t)t + (i + 2) % 3];
		if (nb < 0)
			break;
		t = nb;
	} while (t != t0);
	if (nb < 0) {
		t = t0;
		for (;;) {
			int i = vidx(c, t, v);
			nb = c->tn[3 * (size_t)t + i];
			if (nb < 0)
				break;
			t = nb;
			if (push32(&c->ring, &c->nring, &c->ring_cap, t, c->err))
				return -1;
		}
	}
	if (c->deg)
		c->deg[v] = (uint32_t)(c->nring < UINT32_MAX ? c->nring : UINT32_MAX);
	return 0;
}

static void mark_constrained(struct ct *c, int32_t t, int e)
{
	c->tf[t] |= (uint8_t)(1u << e);
	int32_t u = c->tn[3 * (size_t)t + e];
	if (u >= 0) {
		int k = eidx(c, u, c->tv[3 * (size_t)t + e], c->tv[3 * (size_t)t + (e + 1) % 3]);
		c->tf[u] |= (uint8_t)(1u << k);
	}
}

enum { FS_EDGE, FS_WEDGE, FS_BLOCKED, FS_ERROR };

/* Where the segment v -> w leaves v: along an existing edge (FS_EDGE, *t
 * and *e the edge), into the interior of triangle *t (FS_WEDGE), or not at
 * all (FS_BLOCKED: along an edge through another vertex, or out of the
 * triangulated hull). */
static int find_start(struct ct *c, int32_t v, int32_t w, int32_t *tout, int *eout)
{
	if (around(c, v))
		return FS_ERROR;
	for (size_t k = 0; k < c->nring; k++) {
		int32_t t = c->ring[k];
		int i = vidx(c, t, v);
		if (c->tv[3 * (size_t)t + (i + 1) % 3] == w) {
			*tout = t, *eout = i;
			return FS_EDGE;
		}
		if (c->tv[3 * (size_t)t + (i + 2) % 3] == w) {
			*tout = t, *eout = (i + 2) % 3;
			return FS_EDGE;
		}
	}
	const double *pv = &c->xy[2 * v], *pw = &c->xy[2 * w];
	for (size_t k = 0; k < c->nring; k++) {
		int32_t t = c->ring[k];
		int i = vidx(c, t, v);
		int32_t a = c->tv[3 * (size_t)t + (i + 1) % 3], b = c->tv[3 * (size_t)t + (i + 2) % 3];
		double o1 = orient(c, v, a, w), o2 = orient(c, v, b, w);
		const double *pa = &c->xy[2 * a], *pb = &c->xy[2 * b];
		if (o1 == 0 && (pa[0] - pv[0]) * (pw[0] - pv[0]) + (pa[1] - pv[1]) * (pw[1] - pv[1]) > 0)
			return FS_BLOCKED;
		if (o2 == 0 && (pb[0] - pv[0]) * (pw[0] - pv[0]) + (pb[1] - pv[1]) * (pw[1] - pv[1]) > 0)
			return FS_BLOCKED;
		if (o1 > 0 && o2 < 0) {
			*tout = t;
			return FS_WEDGE;
		}
	}
	return FS_BLOCKED;
}

enum { W_REACHED, W_BLOCKED, W_ERROR };

/* Walk along v -> w from triangle t (whose corner v's wedge holds w),
 * crossing only unconstrained edges: the triangles crossed go to c->cav,
 * the corners left and right of the segment, in order, to c->left and
 * c->right. */
static int walk(struct ct *c, int32_t v, int32_t w, int32_t t)
{
	int i = vidx(c, t, v);
	int32_t a = c->tv[3 * (size_t)t + (i + 1) % 3], b = c->tv[3 * (size_t)t + (i + 2) % 3];
	int e = (i + 1) % 3;
	c->ncav = c->nleft = c->nright = 0;
	c->st->walks++;
	if (push32(&c->cav, &c->ncav, &c->cav_cap, t, c->err) ||
	    push32(&c->right, &c->nright, &c->right_cap, a, c->err) ||
	    push32(&c->left, &c->nleft, &c->left_cap, b, c->err))
		return W_ERROR;
	for (;;) {
		c->st->walk_steps++;
		if (c->tf[t] & (1u << e))
			return W_BLOCKED;
		int32_t u = c->tn[3 * (size_t)t + e];
		if (u < 0)
			return W_BLOCKED;
		const int32_t *p = &c->tv[3 * (size_t)u];
		int32_t d = p[0] != a && p[0] != b ? p[0] : p[1] != a && p[1] != b ? p[1] : p[2];
		if (push32(&c->cav, &c->ncav, &c->cav_cap, u, c->err))
			return W_ERROR;
		if (d == w)
			return W_REACHED;
		double o = orient(c, v, w, d);
		if (o == 0)
			return W_BLOCKED;
		if (o > 0) {
			if (push32(&c->left, &c->nleft, &c->left_cap, d, c->err))
				return W_ERROR;
			b = d;
		} else {
			if (push32(&c->right, &c->nright, &c->right_cap, d, c->err))
				return W_ERROR;
			a = d;
		}
		t = u;
		e = eidx(c, u, a, b);
	}
}

/* Delaunay triangulation of the pseudo-polygon v, chain[0..m), w (the chain
 * on one side of v -> w): each sub-polygon (i, j) takes the vertex k whose
 * circle with i and j holds no other vertex between them.  Triangles are
 * appended to c->newt counter-clockwise.  0, 1 (a degenerate choice: not
 * inserted) or -1. */
static int tri_pseudo(struct ct *c, int32_t v, const int32_t *chain, size_t m, int32_t w)
{
	size_t n = m + 2, np = 0, ns = 0;
	for (size_t k = 0; k < n; k++)
		if (push32(&c->poly, &np, &c->poly_cap, k == 0 ? v : k == n - 1 ? w : chain[k - 1], c->err))
			return -1;
	const int32_t *P = c->poly;
	if (push32(&c->stack, &ns, &c->stack_cap, 0, c->err) ||
	    push32(&c->stack, &ns, &c->stack_cap, (int32_t)(n - 1), c->err))
		return -1;
	while (ns) {
		int32_t j = c->stack[--ns], i = c->stack[--ns];
		if (j - i < 2)
			continue;
		int32_t best = -1;
		double ob = 0;
		for (int32_t k = i + 1; k < j; k++) {
			double o = orient(c, P[i], P[k], P[j]);
			if (o == 0)
				continue;
			if (best < 0) {
				best = k, ob = o;
				continue;
			}
			double ic = ob > 0 ? fct_incircle(&c->xy[2 * P[i]], &c->xy[2 * P[best]], &c->xy[2 * P[j]], &c->xy[2 * P[k]])
			                   : fct_incircle(&c->xy[2 * P[i]], &c->xy[2 * P[j]], &c->xy[2 * P[best]], &c->xy[2 * P[k]]);
			if (ic > 0)
				best = k, ob = o;
		}
		if (best < 0)
			return 1;
		int32_t tri[3] = { P[i], ob > 0 ? P[best] : P[j], ob > 0 ? P[j] : P[best] };
		for (int q = 0; q < 3; q++)
			if (push32(&c->newt, &c->nnew, &c->newt_cap, tri[q], c->err))
				return -1;
		if (push32(&c->stack, &ns, &c->stack_cap, i, c->err) ||
		    push32(&c->stack, &ns, &c->stack_cap, best, c->err) ||
		    push32(&c->stack, &ns, &c->stack_cap, best, c->err) ||
		    push32(&c->stack, &ns, &c->stack_cap, j, c->err))
			return -1;
	}
	return 0;
}

static int rec_cmp(const void *pa, const void *pb)
{
	const struct rec *x = pa, *y = pb;
	if (x->a != y->a)
		return x->a < y->a ? -1 : 1;
	if (x->b != y->b)
		return x->b < y->b ? -1 : 1;
	if (x->outside != y->outside)
		return x->outside < y->outside ? -1 : 1;
	if (x->t != y->t)
		return x->t < y->t ? -1 : 1;
	return x->e - y->e;
}

static int add_rec(struct ct *c, size_t *n, int32_t x, int32_t y, int32_t t, int e, int outside, int cons)
{
	if (*n >= c->rec_cap && fct_grow((void **)&c->recs, &c->rec_cap, *n + 1, sizeof *c->recs, c->err))
		return -1;
	struct rec *r = &c->recs[(*n)++];
	r->a = x < y ? x : y, r->b = x < y ? y : x, r->t = t;
	r->e = (int8_t)e, r->outside = (int8_t)outside, r->cons = (int8_t)cons;
	return 0;
}

/* Replace the triangles the last walk crossed (v to w, reached) by the
 * triangulations of the two pseudo-polygons beside the segment, which
 * becomes a constrained edge.  0, 1 (degenerate: nothing changed) or -1. */
static int insert_cavity(struct ct *c, int32_t v, int32_t w)
{
	c->nnew = 0;
	int rc = tri_pseudo(c, v, c->left, c->nleft, w);
	if (!rc)
		rc = tri_pseudo(c, v, c->right, c->nright, w);
	if (rc)
		return rc;
	if (c->nnew != 3 * c->ncav)
		return 1;
	/* The edges around the cavity, with the triangle outside each. */
	if (++c->epoch == 0) {
		memset(c->stamp, 0, c->nt * sizeof *c->stamp);
		c->epoch = 1;
	}
	for (size_t k = 0; k < c->ncav; k++)
		c->stamp[c->cav[k]] = c->epoch;
	size_t nrec = 0;
	uint8_t marks = c->tf[c->cav[0]] & (F_INSIDE | F_OUTSIDE);
	for (size_t k = 0; k < c->ncav; k++) {
		int32_t t = c->cav[k];
		for (int e = 0; e < 3; e++) {
			int32_t u = c->tn[3 * (size_t)t + e];
			if (u >= 0 && c->stamp[u] == c->epoch)
				continue;
			int back = -1;
			if (u >= 0)
				for (int q = 0; q < 3; q++)
					if (c->tn[3 * (size_t)u + q] == t)
						back = q;
			if (add_rec(c, &nrec, c->tv[3 * (size_t)t + e], c->tv[3 * (size_t)t + (e + 1) % 3], u,
			            back, 1, (c->tf[t] >> e) & 1))
				return -1;
		}
	}
	for (size_t k = 0; k < c->ncav; k++) {
		int32_t t = c->cav[k];
		for (int q = 0; q < 3; q++) {
			c->tv[3 * (size_t)t + q] = c->newt[3 * k + q];
			c->tn[3 * (size_t)t + q] = -1;
		}
		c->tf[t] = marks;
		for (int e = 0; e < 3; e++)
			if (add_rec(c, &nrec, c->newt[3 * k + e], c->newt[3 * k + (e + 1) % 3], t, e, 0, 0))
				return -1;
	}
	qsort(c->recs, nrec, sizeof *c->recs, rec_cmp);
	int32_t sa = v < w ? v : w, sb = v < w ? w : v;
	for (size_t k = 0; k < nrec;) {
		struct rec *r = &c->recs[k], *s = k + 1 < nrec ? &c->recs[k + 1] : NULL;
		if (!s || s->a != r->a || s->b != r->b || r->outside || (k + 2 < nrec && c->recs[k + 2].a == r->a &&
		                                                          c->recs[k + 2].b == r->b))
			abort(); /* the cavity's edges must pair up */
		if (!s->outside) {
			c->tn[3 * (size_t)r->t + r->e] = s->t;
			c->tn[3 * (size_t)s->t + s->e] = r->t;
			if (r->a == sa && r->b == sb) {
				c->tf[r->t] |= (uint8_t)(1u << r->e);
				c->tf[s->t] |= (uint8_t)(1u << s->e);
			}
		} else {
			c->tn[3 * (size_t)r->t + r->e] = s->t;
			if (s->t >= 0)
				c->tn[3 * (size_t)s->t + s->e] = r->t;
			if (s->cons)
				c->tf[r->t] |= (uint8_t)(1u << r->e);
		}
		k += 2;
	}
	for (size_t k = 0; k < c->ncav; k++)
		for (int q = 0; q < 3; q++)
			c->vt[c->tv[3 * (size_t)c->cav[k] + q]] = c->cav[k];
	c->st->flips += c->ncav;
	return 0;
}

/* Make v -> w a constrained edge of the triangulation.  0, 1 (it crosses a
 * constrained edge or passes through a vertex) or -1. */
static int insert_constraint(struct ct *c, int32_t v, int32_t w)
{
	int32_t t;
	int e;
	switch (find_start(c, v, w, &t, &e)) {
	case FS_EDGE:
		mark_constrained(c, t, e);
		return 0;
	case FS_BLOCKED:
		return 1;
	case FS_ERROR:
		return -1;
	}
	int r = walk(c, v, w, t);
	if (r == W_ERROR)
		return -1;
	if (r == W_BLOCKED)
		return 1;
	return insert_cavity(c, v, w);
}

struct hrec {
	int32_t a, b, t, e;
};

static int hrec_cmp(const void *pa, const void *pb)
{
	const struct hrec *x = pa, *y = pb;
	if (x->a != y->a)
		return x->a < y->a ? -1 : 1;
	if (x->b != y->b)
		return x->b < y->b ? -1 : 1;
	if (x->t != y->t)
		return x->t < y->t ? -1 : 1;
	return x->e - y->e;
}

/* Adjacency of the Delaunay triangles tri[0..3nt). */
static int ct_init(struct ct *c, const uint32_t *tri, size_t nt)
{
	struct fct_err *err = c->err;
	c->nt = nt;
	c->tv = fct_alloc_array(3 * nt, sizeof *c->tv, err);
	c->tn = fct_alloc_array(3 * nt, sizeof *c->tn, err);
	c->tf = fct_alloc_array(nt, 1, err);
	c->stamp = fct_alloc_array(nt, sizeof *c->stamp, err);
	c->vt = fct_alloc_array(c->np, sizeof *c->vt, err);
	struct hrec *h = fct_alloc_array(3 * nt, sizeof *h, err);
	if (!c->tv || !c->tn || !c->tf || !c->stamp || !c->vt || !h) {
		free(h);
		return -1;
	}
	memset(c->tf, 0, nt);
	memset(c->stamp, 0, nt * sizeof *c->stamp);
	for (size_t v = 0; v < c->np; v++)
		c->vt[v] = -1;
	for (size_t t = 0; t < nt; t++)
		for (int e = 0; e < 3; e++) {
			int32_t a = (int32_t)tri[3 * t + e], b = (int32_t)tri[3 * t + (e + 1) % 3];
			c->tv[3 * t + e] = a;
			c->tn[3 * t + e] = -1;
			c->vt[a] = (int32_t)t;
			h[3 * t + e] = (struct hrec){ a < b ? a : b, a < b ? b : a, (int32_t)t, e };
		}
	qsort(h, 3 * nt, sizeof *h, hrec_cmp);
	for (size_t k = 0; k + 1 < 3 * nt; k++)
		if (h[k].a == h[k + 1].a && h[k].b == h[k + 1].b) {
			c->tn[3 * (size_t)h[k].t + h[k].e] = h[k + 1].t;
			c->tn[3 * (size_t)h[k + 1].t + h[k + 1].e] = h[k].t;
			k++;
		}
	free(h);
	return 0;
}

/* The triangle holding the directed edge a -> b, its edge index in *e. */
static int32_t find_directed(struct ct *c, int32_t a, int32_t b, int *e, int *rc)
{
	*rc = around(c, a);
	if (*rc)
		return -1;
	for (size_t k = 0; k < c->nring; k++) {
		int32_t t = c->ring[k];
		int i = vidx(c, t, a);
		if (c->tv[3 * (size_t)t + (i + 1) % 3] == b) {
			*e = i;
			return t;
		}
	}
	return -1;
}

/* Mark the triangles inside: left of some loop edge, or reached from one
 * without crossing a constrained edge.  0, 1 (a triangle both inside and
 * outside, or the inside reaching the hull) or -1. */
static int flood(struct ct *c, const uint32_t *lstart, size_t nloops, const int32_t *lv)
{
	int32_t *queue = fct_alloc_array(c->nt, sizeof *queue, c->err);
	if (!queue)
		return -1;
	size_t qn = 0, qh = 0;
	int rc = 0;
	for (size_t l = 0; l < nloops && !rc; l++) {
		size_t n = lstart[l + 1] - lstart[l];
		for (size_t k = 0; k < n && !rc; k++) {
			int32_t a = lv[lstart[l] + k], b = lv[lstart[l] + (k + 1) % n];
			int e;
			int32_t t = find_directed(c, a, b, &e, &rc);
			if (rc)
				break;
			if (t < 0 || (c->tf[t] & F_OUTSIDE)) {
				rc = 1;
				break;
			}
			if (!(c->tf[t] & F_INSIDE)) {
				c->tf[t] |= F_INSIDE;
				queue[qn++] = t;
			}
			int32_t u = c->tn[3 * (size_t)t + e];
			if (u >= 0) {
				if (c->tf[u] & F_INSIDE)
					rc = 1;
				c->tf[u] |= F_OUTSIDE;
			}
		}
	}
	while (!rc && qh < qn) {
		int32_t t = queue[qh++];
		for (int e = 0; e < 3; e++) {
			if (c->tf[t] & (1u << e))
				continue;
			int32_t u = c->tn[3 * (size_t)t + e];
			if (u < 0 || (c->tf[u] & F_OUTSIDE)) {
				rc = 1;
				break;
			}
			if (!(c->tf[u] & F_INSIDE)) {
				c->tf[u] |= F_INSIDE;
				queue[qn++] = u;
			}
		}
	}
	free(queue);
	return rc;
}

/* Greedy ------------------------------------------------------------------ */

struct pair {
	double d2;
	uint32_t a, b;
};

static int pair_less(const struct pair *x, const struct pair *y)
{
	if (x->d2 != y->d2)
		return x->d2 < y->d2;
	if (x->a != y->a)
		return x->a < y->a;
	return x->b < y->b;
}

struct pheap {
	struct pair *h;
	size_t n, cap;
};

static int pheap_push(struct pheap *q, struct pair p, struct fct_err *err)
{
	if (q->n >= q->cap && fct_grow((void **)&q->h, &q->cap, q->n + 1, sizeof *q->h, err))
		return -1;
	size_t i = q->n++;
	while (i > 0) {
		size_t up = (i - 1) / 2;
		if (!pair_less(&p, &q->h[up]))
			break;
		q->h[i] = q->h[up];
		i = up;
	}
	q->h[i] = p;
	return 0;
}

static struct pair pheap_pop(struct pheap *q)
{
	struct pair top = q->h[0], last = q->h[--q->n];
	size_t i = 0;
	for (;;) {
		size_t l = 2 * i + 1;
		if (l >= q->n)
			break;
		if (l + 1 < q->n && pair_less(&q->h[l + 1], &q->h[l]))
			l++;
		if (!pair_less(&q->h[l], &last))
			break;
		q->h[i] = q->h[l];
		i = l;
	}
	if (q->n)
		q->h[i] = last;
	return top;
}

/* A k-d tree over the points: node k covers idx[begin..end) inside the box
 * lo..hi; its children are child and child + 1 (child < 0 for a leaf). */
struct kdnode {
	double lo[2], hi[2];
	uint32_t begin, end;
	int32_t child;
};

struct kd {
	uint32_t *idx;
	struct kdnode *node;
	size_t nnode;
};

static int kd_less(const double *xy, int axis, uint32_t a, uint32_t b)
{
	double x = xy[2 * a + axis], y = xy[2 * b + axis];
	return x < y || (x == y && a < b);
}

/* Put the k-th smallest (by axis, then index) of idx[0..n) at idx[k]. */
static void kd_select(const double *xy, int axis, uint32_t *idx, size_t n, size_t k)
{
	size_t lo = 0, hi = n - 1;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		/* median of three to idx[hi] as the pivot */
		if (kd_less(xy, axis, idx[mid], idx[lo])) { uint32_t s = idx[mid]; idx[mid] = idx[lo]; idx[lo] = s; }
		if (kd_less(xy, axis, idx[hi], idx[lo])) { uint32_t s = idx[hi]; idx[hi] = idx[lo]; idx[lo] = s; }
		if (kd_less(xy, axis, idx[mid], idx[hi])) { uint32_t s = idx[mid]; idx[mid] = idx[hi]; idx[hi] = s; }
		uint32_t pv = idx[hi];
		size_t st = lo;
		for (size_t i = lo; i < hi; i++)
			if (kd_less(xy, axis, idx[i], pv)) {
				uint32_t s = idx[i]; idx[i] = idx[st]; idx[st] = s;
				st++;
			}
		idx[hi] = idx[st], idx[st] = pv;
		if (st == k)
			return;
		if (k < st)
			hi = st - 1;
		else
			lo = st + 1;
	}
}

static int kd_build(struct kd *t, const double *xy, size_t n, struct fct_err *err)
{
	t->idx = fct_alloc_array(n, sizeof *t->idx, err);
	size_t cap = 2 * (n / 4 + 1) + 1;
	t->node = fct_alloc_array(cap, sizeof *t->node, err);
	if (!t->idx || !t->node)
		return -1;
	for (size_t i = 0; i < n; i++)
		t->idx[i] = (uint32_t)i;
	t->nnode = 1;
	t->node[0].begin = 0, t->node[0].end = (uint32_t)n;
	for (size_t k = 0; k < t->nnode; k++) {
		struct kdnode *nd = &t->node[k];
		nd->lo[0] = nd->lo[1] = HUGE_VAL, nd->hi[0] = nd->hi[1] = -HUGE_VAL;
		for (uint32_t i = nd->begin; i < nd->end; i++)
			for (int a = 0; a < 2; a++) {
				double x = xy[2 * t->idx[i] + a];
				nd->lo[a] = x < nd->lo[a] ? x : nd->lo[a];
				nd->hi[a] = x > nd->hi[a] ? x : nd->hi[a];
			}
		nd->child = -1;
		size_t m = nd->end - nd->begin;
		if (m <= 8 || t->nnode + 2 > cap)
			continue;
		int axis = nd->hi[1] - nd->lo[1] > nd->hi[0] - nd->lo[0];
		kd_select(xy, axis, t->idx + nd->begin, m, m / 2);
		nd->child = (int32_t)t->nnode;
		t->node[t->nnode].begin = nd->begin, t->node[t->nnode].end = nd->begin + (uint32_t)(m / 2);
		t->node[t->nnode + 1].begin = nd->begin + (uint32_t)(m / 2), t->node[t->nnode + 1].end = nd->end;
		t->nnode += 2;
	}
	return 0;
}

static double sq(double x)
{
	return x * x;
}

static double dist2(const double *xy, uint32_t a, uint32_t b)
{
	return sq(xy[2 * a] - xy[2 * b]) + sq(xy[2 * a + 1] - xy[2 * b + 1]);
}

/* Can the box of nd meet the inside of one of the wedges at v (the cones
 * v -> a, v -> b in c->cones)?  Exact: a box all of whose corners lie on
 * the closed outer side of a wedge's line lies there entirely. */
static int box_in_cones(const struct ct *c, int32_t v, const struct kdnode *nd, size_t ncone)
{
	const double corner[4][2] = {
		{ nd->lo[0], nd->lo[1] }, { nd->hi[0], nd->lo[1] }, { nd->lo[0], nd->hi[1] }, { nd->hi[0], nd->hi[1] },
	};
	const double *pv = &c->xy[2 * v];
	for (size_t k = 0; k < ncone; k += 2) {
		const double *pa = &c->xy[2 * c->cones[k]], *pb = &c->xy[2 * c->cones[k + 1]];
		int out_a = 1, out_b = 1;
		for (int q = 0; q < 4 && (out_a || out_b); q++) {
			if (fct_orient2d(pv, pa, corner[q]) > 0)
				out_a = 0;
			if (fct_orient2d(pv, pb, corner[q]) < 0)
				out_b = 0;
		}
		if (!out_a && !out_b)
			return 1;
	}
	return 0;
}

static int push_funnel(struct ct *c, size_t *n, int32_t ra, int32_t rb, int32_t ea, int32_t eb,
                       int32_t t, int e)
{
	if (*n >= c->fun_cap && fct_grow((void **)&c->fun, &c->fun_cap, *n + 1, sizeof *c->fun, c->err))
		return -1;
	c->fun[(*n)++] = (struct funnel){ ra, rb, ea, eb, t, e };
	return 0;
}

/* May a point beyond the segment a-b (seen from v) be within squared
 * distance R of v?  Decided with a margin, so it only says no when the
 * segment is surely farther. */
static int window_near(const struct ct *c, int32_t v, int32_t a, int32_t b, double R)
{
	if (R == HUGE_VAL)
		return 1;
	const double *p = &c->xy[2 * v], *pa = &c->xy[2 * a], *pb = &c->xy[2 * b];
	double dx = pb[0] - pa[0], dy = pb[1] - pa[1];
	double l2 = dx * dx + dy * dy;
	double s = l2 > 0 ? ((p[0] - pa[0]) * dx + (p[1] - pa[1]) * dy) / l2 : 0;
	s = s < 0 ? 0 : s > 1 ? 1 : s;
	double qx = pa[0] + s * dx - p[0], qy = pa[1] + s * dy - p[1];
	return qx * qx + qy * qy <= R * (1 + 1e-9) + 1e-300;
}

/* Every inside triangle around v has three constrained edges. */
static int finished(struct ct *c, int32_t v, int *rc)
{
	*rc = around(c, v);
	if (*rc)
		return 0;
	for (size_t k = 0; k < c->nring; k++) {
		uint8_t f = c->tf[c->ring[k]];
		if ((f & F_INSIDE) && (f & F_EDGES) != F_EDGES)
			return 0;
	}
	return 1;
}

/* Take the candidate v - w if it is a valid diagonal: 1 taken, 0 not, -1.
 * The search starts at the end with fewer triangles around it when last
 * seen (fans from one vertex of a long boundary have thousands). */
static int try_pair(struct ct *c, int32_t v, int32_t w)
{
	int32_t t;
	int e;
	if (c->deg[w] < c->deg[v]) {
		int32_t s = v;
		v = w, w = s;
	}
	switch (find_start(c, v, w, &t, &e)) {
	case FS_EDGE:
		if ((c->tf[t] & (1u << e)) || !(c->tf[t] & F_INSIDE))
			return 0;
		mark_constrained(c, t, e);
		return 1;
	case FS_BLOCKED:
		return 0;
	case FS_ERROR:
		return -1;
	}
	if (!(c->tf[t] & F_INSIDE))
		return 0;
	int r = walk(c, v, w, t);
	if (r == W_ERROR)
		return -1;
	if (r == W_BLOCKED)
		return 0;
	r = insert_cavity(c, v, w);
	return r < 0 ? -1 : r == 0;
}

/* The greedy run (see polytri.h for the scheme): the k-d tree over the
 * points, the heap of candidate pairs, the heap of vertices by the squared
 * radius of their next expansion (pairs (r_v^2, v) with b unused), and
 * r2[v], the squared radius up to which v's pairs have been produced. */
struct greedy {
	struct ct *c;
	struct kd kd;
	struct pheap pairs, verts;
	double *r2;
};

static void greedy_free(struct greedy *g)
{
	free(g->r2), free(g->kd.idx), free(g->kd.node), free(g->pairs.h), free(g->verts.h);
}

static int greedy_init(struct greedy *g, struct ct *c)
{
	size_t np = c->np;
	memset(g, 0, sizeof *g);
	g->c = c;
	g->r2 = fct_alloc_array(np, sizeof *g->r2, c->err);
	c->deg = fct_alloc_array(np, sizeof *c->deg, c->err);
	if (!g->r2 || !c->deg || kd_build(&g->kd, c->xy, np, c->err))
		return -1;
	for (size_t v = 0; v < np; v++)
		c->deg[v] = 6;
	for (size_t v = 0; v < np; v++) {
		g->r2[v] = 0;
		if (pheap_push(&g->verts, (struct pair){ 0, (uint32_t)v, 0 }, c->err))
			return -1;
	}
	return 0;
}

/* The unconstrained edges between inside triangles, each counted once:
 * the diagonals the greedy run still has to choose. */
static size_t open_edges(const struct ct *c)
{
	size_t u = 0;
	for (size_t t = 0; t < c->nt; t++)
		if (c->tf[t] & F_INSIDE)
			for (int e = 0; e < 3; e++)
				if (!(c->tf[t] & (1u << e)) && c->tn[3 * t + e] >= 0 && (size_t)c->tn[3 * t + e] > t)
					u++;
	return u;
}

/* The squared radius of v's next expansion: at the first, its nearest
 * neighbour in the triangulation (c->ring holds the triangles around v),
 * then four times (twice the radius) the last; HUGE_VAL when that would
 * not grow. */
static double expansion_radius(const struct ct *c, const double *r2, uint32_t v)
{
	double R = HUGE_VAL;
	if (r2[v] == 0) {
		for (size_t k = 0; k < c->nring; k++) {
			int32_t t = c->ring[k];
			int i = vidx(c, t, (int32_t)v);
			double d = dist2(c->xy, v, (uint32_t)c->tv[3 * (size_t)t + (i + 1) % 3]);
			R = d < R ? d : R;
		}
	} else {
		R = 4 * r2[v];
	}
	return R > r2[v] ? R : HUGE_VAL;
}

/* What can still start at v: the unconstrained edges at v (direct
 * candidates, to c->direct) and the wedges of inside triangles (v, a, b)
 * whose far edge a-b is unconstrained (a segment into such a wedge must
 * cross a-b), as funnels to c->fun.  0 or -1. */
static int open_wedges(struct ct *c, uint32_t v, double R, size_t *nfun, size_t *ndirect)
{
	for (size_t k = 0; k < c->nring; k++) {
		int32_t t = c->ring[k];
		int i = vidx(c, t, (int32_t)v);
		int32_t a = c->tv[3 * (size_t)t + (i + 1) % 3], b = c->tv[3 * (size_t)t + (i + 2) % 3];
		if (!(c->tf[t] & F_INSIDE))
			continue;
		if (!(c->tf[t] & (1u << ((i + 1) % 3))) && window_near(c, (int32_t)v, a, b, R) &&
		    push_funnel(c, nfun, a, b, a, b, t, (i + 1) % 3))
			return -1;
		if (!(c->tf[t] & (1u << i)) && push32(&c->direct, ndirect, &c->direct_cap, a, c->err))
			return -1;
	}
	return 0;
}

/* Follow each wedge at v through the triangulation as a funnel: across its
 * window edge lies a triangle whose third vertex is either inside the
 * wedge (a visible vertex, a direct candidate, splitting the wedge in two)
 * or beside it (narrowing the window); a window that is constrained, or
 * farther than R, closes.  Wedges still open after FUNNEL_STEPS steps go to
 * c->cones (ray pairs) for the k-d tree.  Constraints only accumulate, so
 * a segment outside every wedge now never becomes valid: nothing is
 * missed.  0 or -1. */
static int follow_funnels(struct ct *c, uint32_t v, double R, size_t nfun, size_t *ndirect,
                          size_t *ncone)
{
	size_t steps = 0;
	while (nfun) {
		struct funnel f = c->fun[--nfun];
		if (steps >= FUNNEL_STEPS) {
			if (push32(&c->cones, ncone, &c->cones_cap, f.ra, c->err) ||
			    push32(&c->cones, ncone, &c->cones_cap, f.rb, c->err))
				return -1;
			continue;
		}
		steps++;
		int32_t u = c->tn[3 * (size_t)f.t + f.e];
		if (u < 0)
			continue;
		const int32_t *pu = &c->tv[3 * (size_t)u];
		int32_t w = pu[0] != f.ea && pu[0] != f.eb ? pu[0] : pu[1] != f.ea && pu[1] != f.eb ? pu[1] : pu[2];
		double oa = orient(c, (int32_t)v, f.ra, w), ob = orient(c, (int32_t)v, f.rb, w);
		int e1 = eidx(c, u, f.ea, w), e2 = eidx(c, u, w, f.eb);
		int open1 = !(c->tf[u] & (1u << e1)) && window_near(c, (int32_t)v, f.ea, w, R);
		int open2 = !(c->tf[u] & (1u << e2)) && window_near(c, (int32_t)v, w, f.eb, R);
		if (oa > 0 && ob < 0) {
			if (push32(&c->direct, ndirect, &c->direct_cap, w, c->err) ||
			    (open1 && push_funnel(c, &nfun, f.ra, w, f.ea, w, u, e1)) ||
			    (open2 && push_funnel(c, &nfun, w, f.rb, w, f.eb, u, e2)))
				return -1;
		} else if (oa <= 0) {
			if (open2 && push_funnel(c, &nfun, f.ra, f.rb, w, f.eb, u, e2))
				return -1;
		} else if (open1 && push_funnel(c, &nfun, f.ra, f.rb, f.ea, w, u, e1)) {
			return -1;
		}
	}
	return 0;
}

/* Is v - w a pair for v's expansion to R: farther than v's last radius,
 * within R, and not already produced by w?  Sets *d to its squared length. */
static int new_pair(const struct greedy *g, uint32_t v, uint32_t w, double R, double *d)
{
	*d = dist2(g->c->xy, v, w);
	return *d > g->r2[v] && *d <= R && *d > g->r2[w];
}

static int push_pair(struct greedy *g, uint32_t v, uint32_t w, double d)
{
	struct pair p = { d, v < w ? v : w, v < w ? w : v };
	if (pheap_push(&g->pairs, p, g->c->err))
		return -1;
	g->c->st->candidates++;
	return 0;
}

/* Is w strictly inside one of the ncone / 2 wedges at v in c->cones? */
static int in_cones(const struct ct *c, uint32_t v, uint32_t w, size_t ncone)
{
	for (size_t k = 0; k < ncone; k += 2)
		if (orient(c, (int32_t)v, c->cones[k], (int32_t)w) > 0 &&
		    orient(c, (int32_t)v, c->cones[k + 1], (int32_t)w) < 0)
			return 1;
	return 0;
}

/* Pairs of v with the points of the k-d tree strictly inside an open wedge
 * (c->cones) and new for an expansion to R.  0 or -1. */
static int search_cones(struct greedy *g, uint32_t v, size_t ncone, double R)
{
	const struct ct *c = g->c;
	int32_t stack[256];
	size_t ns = 0;
	if (ncone)
		stack[ns++] = 0;
	const double *pv = &c->xy[2 * v];
	while (ns) {
		const struct kdnode *nd = &g->kd.node[stack[--ns]];
		double dx = pv[0] < nd->lo[0] ? nd->lo[0] - pv[0] : pv[0] > nd->hi[0] ? pv[0] - nd->hi[0] : 0;
		double dy = pv[1] < nd->lo[1] ? nd->lo[1] - pv[1] : pv[1] > nd->hi[1] ? pv[1] - nd->hi[1] : 0;
		if (dx * dx + dy * dy > R || !box_in_cones(c, (int32_t)v, nd, ncone))
			continue;
		if (nd->child >= 0) {
			stack[ns++] = nd->child;
			stack[ns++] = nd->child + 1;
			continue;
		}
		for (uint32_t i = nd->begin; i < nd->end; i++) {
			uint32_t w = g->kd.idx[i];
			double d;
			if (w == v || !new_pair(g, v, w, R, &d) || !in_cones(c, v, w, ncone))
				continue;
			if (push_pair(g, v, w, d))
				return -1;
		}
	}
	return 0;
}

/* Expand v to its next radius: produce the pairs it can still take there,
 * and queue its next expansion; a vertex that is finished (every inside
 * triangle around it fully constrained) expands no more.  0 or -1. */
static int expand(struct greedy *g, uint32_t v)
{
	struct ct *c = g->c;
	int frc;
	if (finished(c, (int32_t)v, &frc) || frc) {
		g->r2[v] = HUGE_VAL;
		return frc ? -1 : 0;
	}
	size_t ncone = 0, ndirect = 0, nfun = 0;
	double R = expansion_radius(c, g->r2, v);
	if (open_wedges(c, v, R, &nfun, &ndirect) || follow_funnels(c, v, R, nfun, &ndirect, &ncone))
		return -1;
	for (size_t k = 0; k < ndirect; k++) {
		uint32_t w = (uint32_t)c->direct[k];
		double d;
		if (new_pair(g, v, w, R, &d) && push_pair(g, v, w, d))
			return -1;
	}
	if (search_cones(g, v, ncone, R))
		return -1;
	g->r2[v] = R;
	if (R < HUGE_VAL && pheap_push(&g->verts, (struct pair){ R, v, 0 }, c->err))
		return -1;
	return 0;
}

/* Out of budget: the edges the triangulation still holds cross nothing;
 * take them all, which completes a valid triangulation. */
static void take_remaining(struct ct *c)
{
	c->st->budget_hits++;
	for (size_t t = 0; t < c->nt; t++)
		if (c->tf[t] & F_INSIDE)
			for (int e = 0; e < 3; e++)
				if (!(c->tf[t] & (1u << e)))
					mark_constrained(c, (int32_t)t, e);
}

/* The paper's greedy triangulation of the inside triangles' region: take
 * the shortest candidate pair while no vertex can still produce a shorter
 * one, else expand the vertex of least radius, until every diagonal is
 * chosen or the budget is spent. */
static int greedy(struct ct *c)
{
	size_t u = open_edges(c), np = c->np;
	if (u == 0)
		return 0;
	struct greedy g;
	int rc = -1;
	if (greedy_init(&g, c))
		goto out;
	size_t cand0 = c->st->candidates, steps0 = c->st->walk_steps;
	size_t budget_c = 64 * np + 65536, budget_s = 256 * np + ((size_t)1 << 20);
	while (u > 0) {
		if (c->st->candidates - cand0 > budget_c || c->st->walk_steps - steps0 > budget_s)
			break;
		if (g.pairs.n && (!g.verts.n || g.pairs.h[0].d2 <= g.verts.h[0].d2)) {
			struct pair p = pheap_pop(&g.pairs);
			int r = try_pair(c, (int32_t)p.a, (int32_t)p.b);
			if (r < 0)
				goto out;
			u -= (size_t)r;
		} else if (!g.verts.n) {
			break;   /* out of candidates: cannot happen */
		} else if (expand(&g, pheap_pop(&g.verts).a)) {
			goto out;
		}
	}
	if (u > 0)
		take_remaining(c);
	rc = 0;
out:
	greedy_free(&g);
	return rc;
}

/* The driver --------------------------------------------------------------- */

double fct_polytri_loop_area2(const double *xy, const uint32_t *lv, size_t n)
{
	double s = 0;
	if (n < 3)
		return 0;
	const double *o = &xy[2 * (size_t)lv[0]];
	for (size_t k = 1; k + 1 < n; k++) {
		const double *a = &xy[2 * (size_t)lv[k]], *b = &xy[2 * (size_t)lv[k + 1]];
		s += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
	}
	return s;
}

/* Check the loops and give the used points local numbers: *lv the loops in
 * local numbers, *pts the local points, *glob their indices.  0, 1 or -1. */
static int prepare(const double *xy, size_t np, const uint32_t *lstart, size_t nloops,
                   const uint32_t *lvert, int32_t **lv, double **pts, uint32_t **glob, size_t *n,
                   struct fct_err *err)
{
	size_t total = lstart[nloops];
	if (lstart[0] != 0)
		return fct_fail(err, "loop 0 does not start at 0");
	for (size_t l = 0; l < nloops; l++) {
		if (lstart[l + 1] < lstart[l])
			return fct_fail(err, "loop %zu: negative length", l);
		size_t m = lstart[l + 1] - lstart[l];
		if (m < 3) {
			fct_fail(err, "loop %zu has %zu vertices", l, m);
			return 1;
		}
	}
	if (total > FCT_DELAUNAY_MAX_POINTS)
		return fct_fail(err, "%zu loop vertices: too many", total);
	for (size_t k = 0; k < total; k++)
		if (lvert[k] >= np)
			return fct_fail(err, "loop vertex %u out of range (%zu points)", lvert[k], np);
	int32_t *map = fct_alloc_array(np, sizeof *map, err);
	*lv = fct_alloc_array(total, sizeof **lv, err);
	if (!map || !*lv) {
		free(map);
		return -1;
	}
	for (size_t i = 0; i < np; i++)
		map[i] = -1;
	size_t m = 0;
	for (size_t k = 0; k < total; k++)
		if (map[lvert[k]] < 0)
			map[lvert[k]] = (int32_t)m++;
	*pts = fct_alloc_array(2 * m, sizeof **pts, err);
	*glob = fct_alloc_array(m, sizeof **glob, err);
	if (!*pts || !*glob) {
		free(map);
		return -1;
	}
	int rc = 0;
	for (size_t k = 0; k < total; k++) {
		int32_t i = map[lvert[k]];
		(*lv)[k] = i;
		(*glob)[i] = lvert[k];
		(*pts)[2 * i] = xy[2 * (size_t)lvert[k]];
		(*pts)[2 * i + 1] = xy[2 * (size_t)lvert[k] + 1];
		if (!isfinite((*pts)[2 * i]) || !isfinite((*pts)[2 * i + 1])) {
			fct_fail(err, "point %u: coordinate is not finite", lvert[k]);
			rc = 1;
		}
	}
	for (size_t l = 0; l < nloops && !rc; l++)
		for (size_t k = lstart[l]; k < lstart[l + 1]; k++) {
			size_t next = k + 1 < lstart[l + 1] ? k + 1 : lstart[l];
			if (lvert[k] == lvert[next]) {
				fct_fail(err, "loop %zu: vertex %u twice in a row", l, lvert[k]);
				rc = 1;
				break;
			}
		}
	free(map);
	*n = m;
	return rc;
}

int fct_polytri(uint32_t **tri, size_t *ntri, const double *xy, size_t np,
                const uint32_t *lstart, size_t nloops, const uint32_t *lvert,
                enum fct_polytri_method method, struct fct_polytri_stats *st, struct fct_err *err)
{
	struct fct_polytri_stats dummy;
	if (!st) {
		memset(&dummy, 0, sizeof dummy);
		st = &dummy;
	}
	*tri = NULL, *ntri = 0;
	if (nloops == 0) {
		fct_fail(err, "no loops");
		return 1;
	}
	int32_t *lv = NULL;
	double *pts = NULL;
	uint32_t *glob = NULL, *dt = NULL, *out = NULL;
	size_t n = 0, ndt = 0, ndup = 0;
	struct ct c;
	memset(&c, 0, sizeof c);
	int rc = prepare(xy, np, lstart, nloops, lvert, &lv, &pts, &glob, &n, err);
	if (rc)
		goto done;
	if (fct_delaunay(&dt, &ndt, &ndup, pts, n, err)) {
		rc = -1;
		goto done;
	}
	if (ndup || ndt == 0) {
		rc = 1;
		if (ndup)
			fct_fail(err, "%zu loop vertices at the same point as another", ndup);
		else
			fct_fail(err, "all loop vertices on one line");
		goto done;
	}
	c.xy = pts, c.np = n, c.st = st, c.err = err;
	if (ct_init(&c, dt, ndt)) {
		rc = -1;
		goto done;
	}
	for (size_t l = 0; l < nloops; l++) {
		size_t m = lstart[l + 1] - lstart[l];
		for (size_t k = 0; k < m; k++) {
			int32_t a = lv[lstart[l] + k], b = lv[lstart[l] + (k + 1) % m];
			rc = insert_constraint(&c, a, b);
			if (rc) {
				if (rc > 0)
					fct_fail(err, "loop %zu: edge %u-%u crosses another edge or passes through a vertex",
					         l, glob[a], glob[b]);
				goto done;
			}
		}
	}
	rc = flood(&c, lstart, nloops, lv);
	if (rc) {
		if (rc > 0)
			fct_fail(err, "the loops do not bound a region (wrong orientation or nesting)");
		goto done;
	}
	if (method == FCT_POLYTRI_GREEDY && (rc = greedy(&c)))
		goto done;
	size_t nin = 0;
	for (size_t t = 0; t < c.nt; t++)
		nin += (c.tf[t] & F_INSIDE) != 0;
	out = fct_alloc_array(3 * nin, sizeof *out, err);
	if (!out) {
		rc = -1;
		goto done;
	}
	double area_t = 0, area_abs = 0, area_l = 0;
	size_t k = 0;
	for (size_t t = 0; t < c.nt; t++) {
		if (!(c.tf[t] & F_INSIDE))
			continue;
		const int32_t *p = &c.tv[3 * t];
		double o = orient(&c, p[0], p[1], p[2]);
		const double *a = &pts[2 * p[0]], *b = &pts[2 * p[1]], *d = &pts[2 * p[2]];
		double a2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
		if (!(o > 0)) {
			rc = 1;
			fct_fail(err, "a triangle came out inverted or flat");
			goto done;
		}
		area_t += a2, area_abs += fabs(a2);
		for (int q = 0; q < 3; q++)
			out[k++] = glob[p[q]];
	}
	for (size_t l = 0; l < nloops; l++) {
		/* lv in local numbers: the area from the local points */
		double s = 0;
		size_t m = lstart[l + 1] - lstart[l];
		const double *o = &pts[2 * lv[lstart[l]]];
		for (size_t q = 1; q + 1 < m; q++) {
			const double *a = &pts[2 * lv[lstart[l] + q]], *b = &pts[2 * lv[lstart[l] + q + 1]];
			s += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
		}
		area_l += s;
	}
	if (!(fabs(area_t - area_l) <= 1e-9 * area_abs)) {
		rc = 1;
		fct_fail(err, "the triangles' area %.17g differs from the loops' %.17g", area_t / 2, area_l / 2);
		goto done;
	}
	*tri = out, *ntri = nin;
	out = NULL;
done:
	ct_free(&c);
	free(lv), free(pts), free(glob), free(dt), free(out);
	return rc;
}

/* Ear clipping repair ------------------------------------------------------ */

/* p strictly inside or on the boundary of the counter-clockwise triangle abc. */
static int in_triangle(const double *a, const double *b, const double *c, const double *p)
{
	return fct_orient2d(a, b, p) >= 0 && fct_orient2d(b, c, p) >= 0 && fct_orient2d(c, a, p) >= 0;
}

/* Point p inside loop lv[0..n) by the even-odd rule. */
static int point_in_loop(const double *xy, const uint32_t *lv, size_t n, const double *p)
{
	int in = 0;
	for (size_t i = 0, j = n - 1; i < n; j = i++) {
		const double *a = &xy[2 * (size_t)lv[i]], *b = &xy[2 * (size_t)lv[j]];
		if ((a[1] > p[1]) != (b[1] > p[1]) &&
		    p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
			in = !in;
	}
	return in;
}

/* Cut the sequence seq[0..n) (point indices, possibly repeating) into n - 2
 * ears appended to *out (count *nout, capacity *cap). */
static int clip_sequence(const double *xy, const uint32_t *seq, size_t n, uint32_t **out,
                         size_t *nout, size_t *cap, struct fct_polytri_stats *st, struct fct_err *err)
{
	size_t *prev = fct_alloc_array(n, sizeof *prev, err), *next = fct_alloc_array(n, sizeof *next, err);
	int rc = -1;
	if (!prev || !next)
		goto out;
	for (size_t i = 0; i < n; i++)
		prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
	size_t left = n, cur = 0, misses = 0;
	int check = n <= 4096;
	while (left > 3) {
		size_t a = prev[cur], b = next[cur];
		const double *pa = &xy[2 * (size_t)seq[a]], *pc = &xy[2 * (size_t)seq[cur]], *pb = &xy[2 * (size_t)seq[b]];
		int ear = fct_orient2d(pa, pc, pb) > 0;
		if (ear && check)
			for (size_t k = next[b]; k != a; k = next[k]) {
				uint32_t s = seq[k];
				if (s == seq[a] || s == seq[b] || s == seq[cur])
					continue;
				if (in_triangle(pa, pc, pb, &xy[2 * (size_t)s])) {
					ear = 0;
					break;
				}
			}
		if (!ear && ++misses <= left) {
			cur = next[cur];
			continue;
		}
		if (!ear) {
			/* No valid ear in a whole turn: the most convex corner. */
			size_t best = cur;
			double bo = -HUGE_VAL;
			size_t k = cur;
			do {
				double o = fct_orient2d(&xy[2 * (size_t)seq[prev[k]]], &xy[2 * (size_t)seq[k]],
				                        &xy[2 * (size_t)seq[next[k]]]);
				if (o > bo)
					bo = o, best = k;
				k = next[k];
			} while (k != cur);
			cur = best, a = prev[cur], b = next[cur];
			st->forced_ears++;
		}
		if (*nout + 1 > *cap / 3 && fct_grow((void **)out, cap, 3 * (*nout + 1), sizeof **out, err))
			goto out;
		(*out)[3 * *nout] = seq[a], (*out)[3 * *nout + 1] = seq[cur], (*out)[3 * *nout + 2] = seq[b];
		(*nout)++;
		next[a] = b, prev[b] = a;
		left--;
		misses = 0;
		cur = a;
	}
	if (left == 3) {
		size_t a = prev[cur], b = next[cur];
		if (*nout + 1 > *cap / 3 && fct_grow((void **)out, cap, 3 * (*nout + 1), sizeof **out, err))
			goto out;
		(*out)[3 * *nout] = seq[a], (*out)[3 * *nout + 1] = seq[cur], (*out)[3 * *nout + 2] = seq[b];
		(*nout)++;
	}
	rc = 0;
out:
	free(prev), free(next);
	return rc;
}

int fct_polytri_nest(long *owner, const double *xy, const uint32_t *lstart, size_t nloops,
                     const uint32_t *lvert)
{
	long biggest = -1;
	double ba = 0;
	for (size_t l = 0; l < nloops; l++) {
		size_t n = lstart[l + 1] - lstart[l];
		double a = n >= 3 ? fct_polytri_loop_area2(xy, lvert + lstart[l], n) : 0;
		owner[l] = a > 0 ? (long)l : -1;
		if (a > 0 && (biggest < 0 || a > ba))
			biggest = (long)l, ba = a;
	}
	if (biggest < 0)
		return 1;
	for (size_t l = 0; l < nloops; l++) {
		if (owner[l] == (long)l || lstart[l + 1] - lstart[l] < 3)
			continue;
		const double *p = &xy[2 * (size_t)lvert[lstart[l]]];
		double best = HUGE_VAL;
		for (size_t o = 0; o < nloops; o++) {
			if (owner[o] != (long)o)
				continue;
			size_t n = lstart[o + 1] - lstart[o];
			double a = fct_polytri_loop_area2(xy, lvert + lstart[o], n);
			if (a < best && point_in_loop(xy, lvert + lstart[o], n, p))
				owner[l] = (long)o, best = a;
		}
		if (owner[l] < 0)
			owner[l] = biggest;
	}
	return 0;
}

int fct_polytri_earclip(uint32_t **tri, size_t *ntri, const double *xy, size_t np,
                        const uint32_t *lstart, size_t nloops, const uint32_t *lvert,
                        struct fct_polytri_stats *st, struct fct_err *err)
{
	struct fct_polytri_stats dummy;
	if (!st) {
		memset(&dummy, 0, sizeof dummy);
		st = &dummy;
	}
	*tri = NULL, *ntri = 0;
	for (size_t k = 0; k < (nloops ? lstart[nloops] : 0); k++)
		if (lvert[k] >= np)
			return fct_fail(err, "loop vertex %u out of range (%zu points)", lvert[k], np);
	double *area = fct_alloc_array(nloops, sizeof *area, err);
	long *owner = fct_alloc_array(nloops, sizeof *owner, err);
	uint32_t *seq = NULL, *out = NULL;
	size_t cap = 0, nout = 0, seqcap = 0;
	int rc = -1;
	if (!area || !owner)
		goto done;
	for (size_t l = 0; l < nloops; l++)
		area[l] = lstart[l + 1] - lstart[l] >= 3 ? fct_polytri_loop_area2(xy, lvert + lstart[l], lstart[l + 1] - lstart[l]) : 0;
	if (fct_polytri_nest(owner, xy, lstart, nloops, lvert)) {
		rc = 1;
		fct_fail(err, "no loop of positive area");
		goto done;
	}
	for (size_t l = 0; l < nloops; l++)
		if (owner[l] == (long)l)
			owner[l] = -1;
	for (size_t o = 0; o < nloops; o++) {
		if (!(area[o] > 0))
			continue;
		size_t n = lstart[o + 1] - lstart[o];
		if (n > seqcap && fct_grow((void **)&seq, &seqcap, n, sizeof *seq, err))
			goto done;
		memcpy(seq, lvert + lstart[o], n * sizeof *seq);
		/* Holes by decreasing rightmost x, each bridged from its rightmost
		 * vertex to the nearest vertex of the sequence so far. */
		for (;;) {
			long hbest = -1;
			size_t hv = 0;
			for (size_t l = 0; l < nloops; l++) {
				if (owner[l] != (long)o)
					continue;
				for (size_t k = lstart[l]; k < lstart[l + 1]; k++) {
					const double *p = &xy[2 * (size_t)lvert[k]];
					const double *q = hbest >= 0 ? &xy[2 * (size_t)lvert[hv]] : NULL;
					if (!q || p[0] > q[0] || (p[0] == q[0] && p[1] < q[1]))
						hbest = (long)l, hv = k;
				}
			}
			if (hbest < 0)
				break;
			owner[hbest] = -1;
			size_t hn = lstart[hbest + 1] - lstart[hbest];
			size_t at = 0;
			double bd = HUGE_VAL;
			for (size_t k = 0; k < n; k++) {
				double d = dist2(xy, seq[k], lvert[hv]);
				if (d < bd)
					bd = d, at = k;
			}
			if (n + hn + 2 > seqcap && fct_grow((void **)&seq, &seqcap, n + hn + 2, sizeof *seq, err))
				goto done;
			memmove(seq + at + 1 + hn + 2, seq + at + 1, (n - at - 1) * sizeof *seq);
			for (size_t k = 0; k <= hn; k++)
				seq[at + 1 + k] = lvert[lstart[hbest] + (hv - lstart[hbest] + k) % hn];
			seq[at + 1 + hn + 1] = seq[at];
			n += hn + 2;
		}
		if (clip_sequence(xy, seq, n, &out, &nout, &cap, st, err))
			goto done;
	}
	*tri = out, *ntri = nout;
	out = NULL;
	rc = 0;
done:
	free(area), free(owner), free(seq), free(out);
	return rc;
}
