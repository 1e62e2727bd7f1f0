/* delaunay.c - incremental Delaunay triangulation with exact predicates.
 *
 * Kang, Johnson, Szeliski (DEC CRL 95/7) section 2: sparse points are
 * connected by the Delaunay triangulation of their image coordinates.
 *
 * Algorithm: Bowyer-Watson insertion (Bowyer 1981, Watson 1981) in a biased
 * randomized insertion order (BRIO: Amenta, Choi, Rote, "Incremental
 * constructions con BRIO", SoCG 2003), each round sorted along a Hilbert
 * curve so that consecutive points are close, and point location by a
 * visibility walk from the last new triangle, which terminates on a
 * Delaunay triangulation (Edelsbrunner 1990).
 *
 * The triangulation is kept as a triangulation of the sphere: an extra
 * vertex INF ("infinity") joins every convex-hull edge, so each hull edge
 * (a, b) has a ghost triangle (b, a, INF) on its outer side and every
 * triangle has three neighbours.  A ghost is "in conflict" with a point q
 * (its circumcircle, a half-plane, contains q) when q lies strictly outside
 * its hull edge, or on the open hull edge itself.  Inserting q then is the
 * same step everywhere: remove the triangles in conflict with q (a region
 * star-shaped from q, found by a search from the triangle that contains q)
 * and join q to the edges around the hole.  Points outside the hull, on a
 * hull edge, and cocircular points need no special case; cocircular points
 * are not in conflict, so ties leave the triangulation as it is and the
 * result depends only on the insertion order, which depends only on the
 * input.
 *
 * Storage: flat arrays of 32-bit words, three vertices and three neighbour
 * "corners" per triangle.  Corner 3t+i is vertex i of triangle t; the edge
 * opposite it runs from vertex i+1 to vertex i+2 (mod 3), and nb[3t+i] is
 * the corner of the neighbour opposite that same edge.  A sphere with
 * n+1 vertices has 2n-2 triangles; each insertion removes k and adds k+2,
 * reusing the removed slots, so nothing is allocated per point. */
#include "geom/delaunay.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/predicates.h"

/* Ghosts use vertex index n (internal numbering); NONE marks "no corner". */
#define NONE UINT32_MAX

struct bedge {
	uint32_t u, v;      /* edge u -> v of the hole's boundary, hole on the left */
	uint32_t out;       /* corner of the triangle outside, opposite that edge */
};

struct dt {
	const double *p;    /* 2 per vertex, internal (insertion) order */
	uint32_t inf;       /* the vertex at infinity: the number of points */
	uint32_t *tv, *nb;  /* 3 per triangle */
	uint32_t *mark;     /* per triangle: stamp of the last insertion that looked */
	uint32_t ntri;
	uint32_t *first;    /* per vertex (inf included): new triangle from it */
	uint32_t last;      /* a live triangle to start the next walk from */
	uint32_t *stack;    /* triangles of the hole */
	size_t stack_cap;
	struct bedge *bnd;  /* edges around the hole */
	size_t bnd_cap;
};

static inline uint32_t next3(uint32_t c)
{
	return c % 3 == 2 ? c - 2 : c + 1;
}

static inline uint32_t prev3(uint32_t c)
{
	return c % 3 == 0 ? c + 2 : c - 1;
}

static inline const double *pt(const struct dt *d, uint32_t v)
{
	return d->p + 2 * (size_t)v;
}

static inline int is_ghost(const struct dt *d, uint32_t t)
{
	const uint32_t *v = d->tv + 3 * (size_t)t;
	return v[0] == d->inf || v[1] == d->inf || v[2] == d->inf;
}

static inline int same_point(const double *a, const double *b)
{
	return a[0] == b[0] && a[1] == b[1];
}

/* Is q strictly inside the circumcircle of t (for a ghost: strictly outside
 * its hull edge, or on the open edge)? */
static int conflict(const struct dt *d, uint32_t t, const double *q)
{
	const uint32_t *v = d->tv + 3 * (size_t)t;
	for (int k = 0; k < 3; k++) {
		if (v[k] != d->inf)
			continue;
		const double *a = pt(d, v[(k + 1) % 3]), *b = pt(d, v[(k + 2) % 3]);
		double o = fct_orient2d(a, b, q);
		if (o != 0)
			return o > 0;
		/* Collinear: between a and b, exclusive?  Compare along an axis
		 * on which they differ; exact, as only comparisons are made. */
		int ax = a[0] != b[0] ? 0 : 1;
		double lo = a[ax] < b[ax] ? a[ax] : b[ax], hi = a[ax] < b[ax] ? b[ax] : a[ax];
		return q[ax] > lo && q[ax] < hi;
	}
	return fct_incircle(pt(d, v[0]), pt(d, v[1]), pt(d, v[2]), q) > 0;
}

/* The triangle containing q (closed), or a ghost in conflict with q when q
 * is outside the hull: a visibility walk from d->last. */
static uint32_t locate(const struct dt *d, const double *q)
{
	uint32_t t = d->last;
	if (is_ghost(d, t)) {
		const uint32_t *v = d->tv + 3 * (size_t)t;
		int k = v[0] == d->inf ? 0 : v[1] == d->inf ? 1 : 2;
		t = d->nb[3 * t + (uint32_t)k] / 3;
	}
	uint32_t from = NONE;
	/* Each step moves to a triangle in front of the last; on a Delaunay
	 * triangulation that order is acyclic, so 2 ntri steps cannot be
	 * exceeded unless the structure is broken. */
	for (size_t steps = 0; steps <= 2 * (size_t)d->ntri; steps++) {
		const uint32_t *v = d->tv + 3 * (size_t)t;
		uint32_t e;
		for (e = 0; e < 3; e++) {
			uint32_t c = 3 * t + e;
			if (c == from)
				continue;
			if (fct_orient2d(pt(d, v[(e + 1) % 3]), pt(d, v[(e + 2) % 3]), q) < 0)
				break;
		}
		if (e == 3)
			return t;
		from = d->nb[3 * t + e];
		t = from / 3;
		if (is_ghost(d, t))
			return t;
	}
	abort();
}

/* Join apex to each edge u -> v of bnd[0..nb): triangle (u, v, apex) with
 * its corner 2 facing bnd's outside corner.  The triangles go into slots
 * slot[0..nb); the boundary must be one closed cycle. */
static void fan(struct dt *d, uint32_t apex, const struct bedge *bnd, size_t nbnd, const uint32_t *slot)
{
	for (size_t j = 0; j < nbnd; j++) {
		uint32_t t = slot[j], *v = d->tv + 3 * (size_t)t;
		v[0] = bnd[j].u;
		v[1] = bnd[j].v;
		v[2] = apex;
		d->nb[3 * t + 2] = bnd[j].out;
		d->nb[bnd[j].out] = 3 * t + 2;
		d->first[bnd[j].u] = t;
	}
	for (size_t j = 0; j < nbnd; j++) {
		uint32_t t = slot[j], t2 = d->first[bnd[j].v];
		/* edge v -> apex of t (opposite corner 0) is apex -> v of t2
		 * (opposite its corner 1) */
		d->nb[3 * t] = 3 * t2 + 1;
		d->nb[3 * t2 + 1] = 3 * t;
	}
}

static int grow_stack(struct dt *d, size_t need, struct fct_err *err)
{
	if (need > d->stack_cap) {
		void *p = d->stack;
		if (fct_grow(&p, &d->stack_cap, need, sizeof *d->stack, err))
			return -1;
		d->stack = p;
	}
	return 0;
}

static int grow_bnd(struct dt *d, size_t need, struct fct_err *err)
{
	if (need > d->bnd_cap) {
		void *p = d->bnd;
		if (fct_grow(&p, &d->bnd_cap, need, sizeof *d->bnd, err))
			return -1;
		d->bnd = p;
	}
	return 0;
}

/* Insert vertex q (internal index) with stamp s (distinct per insertion).
 * Returns 0, 1 when q duplicates vertex *dup, or -1 on out of memory. */
static int insert(struct dt *d, uint32_t qi, uint32_t s, uint32_t *dup, struct fct_err *err)
{
	const double *q = pt(d, qi);
	uint32_t t0 = locate(d, q);
	if (!is_ghost(d, t0)) {
		const uint32_t *v = d->tv + 3 * (size_t)t0;
		for (int k = 0; k < 3; k++)
			if (same_point(pt(d, v[k]), q)) {
				*dup = v[k];
				return 1;
			}
	}
	uint32_t in = 2 * s, out = 2 * s + 1;
	size_t nstack = 0, nbnd = 0;
	d->stack[nstack++] = t0;
	d->mark[t0] = in;
	for (size_t i = 0; i < nstack; i++) {
		uint32_t t = d->stack[i];
		for (uint32_t e = 0; e < 3; e++) {
			uint32_t c = 3 * t + e, oc = d->nb[c], u = oc / 3;
			if (d->mark[u] == in)
				continue;
			if (d->mark[u] != out) {
				if (conflict(d, u, q)) {
					if (grow_stack(d, nstack + 1, err))
						return -1;
					d->mark[u] = in;
					d->stack[nstack++] = u;
					continue;
				}
				d->mark[u] = out;
			}
			if (grow_bnd(d, nbnd + 1, err))
				return -1;
			d->bnd[nbnd].u = d->tv[next3(c)];
			d->bnd[nbnd].v = d->tv[prev3(c)];
			d->bnd[nbnd].out = oc;
			nbnd++;
		}
	}
	/* A disk of k triangles with all vertices on its boundary has k + 2
	 * boundary edges; anything else means the structure is broken. */
	if (nbnd != nstack + 2)
		abort();
	if (grow_stack(d, nstack + 2, err))
		return -1;
	d->stack[nstack] = d->ntri;
	d->stack[nstack + 1] = d->ntri + 1;
	d->mark[d->ntri] = d->mark[d->ntri + 1] = 0;
	d->ntri += 2;
	fan(d, qi, d->bnd, nbnd, d->stack);
	d->last = d->stack[0];
	return 0;
}

/* ---- insertion order ---- */

/* The Hilbert curve as a 4-state machine, 4 levels per step.  At each
 * level the curve's frame is the square's frame possibly with x and y
 * complemented (c) and/or swapped (s); the quadrant (rx, ry) in that frame
 * is visited as digit (3 rx) ^ ry, and a quadrant with ry = 0 flips s and
 * complements when rx = 1 (the classic xy2d loop, as a state change).
 * hilbert_table[state][x nibble][y nibble] = 8 digit bits | next state << 8. */
static void hilbert_table(uint16_t tab[4][16][16])
{
	for (unsigned st = 0; st < 4; st++)
		for (unsigned x = 0; x < 16; x++)
			for (unsigned y = 0; y < 16; y++) {
				unsigned sw = st & 1, cp = st >> 1, key = 0;
				for (int lv = 3; lv >= 0; lv--) {
					unsigned bx = (x >> lv & 1) ^ cp, by = (y >> lv & 1) ^ cp;
					unsigned rx = sw ? by : bx, ry = sw ? bx : by;
					key = key << 2 | ((3 * rx) ^ ry);
					if (!ry) {
						sw ^= 1;
						cp ^= rx;
					}
				}
				tab[st][x][y] = (uint16_t)(key | (sw | cp << 1) << 8);
			}
}

/* Position of (x, y) (28-bit each) on the Hilbert curve: 56 bits. */
static uint64_t hilbert(const uint16_t tab[4][16][16], uint32_t x, uint32_t y)
{
	uint64_t key = 0;
	unsigned st = 0;
	for (int sh = 24; sh >= 0; sh -= 4) {
		unsigned e = tab[st][(x >> sh) & 15][(y >> sh) & 15];
		key = key << 8 | (e & 255);
		st = e >> 8;
	}
	return key;
}

/* Stable LSD radix sort of idx[0..n) by key, 11 bits at a time. */
static int radix_sort(uint64_t *key, uint32_t *idx, size_t n, struct fct_err *err)
{
	uint64_t *k2 = fct_alloc_array(n, sizeof *k2, err);
	uint32_t *i2 = k2 ? fct_alloc_array(n, sizeof *i2, err) : NULL;
	if (!i2) {
		free(k2);
		return -1;
	}
	size_t count[2048];
	for (int shift = 0; shift < 64; shift += 11) {
		memset(count, 0, sizeof count);
		for (size_t i = 0; i < n; i++)
			count[(key[i] >> shift) & 2047]++;
		if (count[(key[0] >> shift) & 2047] == n)
			continue;   /* every key has this digit */
		size_t sum = 0;
		for (int b = 0; b < 2048; b++) {
			size_t c = count[b];
			count[b] = sum;
			sum += c;
		}
		for (size_t i = 0; i < n; i++) {
			size_t j = count[(key[i] >> shift) & 2047]++;
			k2[j] = key[i];
			i2[j] = idx[i];
		}
		memcpy(key, k2, n * sizeof *key);
		memcpy(idx, i2, n * sizeof *idx);
	}
	free(k2);
	free(i2);
	return 0;
}

/* The insertion order: BRIO rounds (point i goes to round "number of
 * trailing zero bits of a hash of i", the highest rounds first, so the last
 * round holds about half the points), Hilbert order within a round, ties by
 * index.  order[k] is the input index of the k-th point. */
static int insertion_order(const double *uv, size_t n, uint32_t *order, struct fct_err *err)
{
	double xmin = uv[0], xmax = uv[0], ymin = uv[1], ymax = uv[1];
	for (size_t i = 1; i < n; i++) {
		double x = uv[2 * i], y = uv[2 * i + 1];
		xmin = x < xmin ? x : xmin;
		xmax = x > xmax ? x : xmax;
		ymin = y < ymin ? y : ymin;
		ymax = y > ymax ? y : ymax;
	}
	/* Halves, so that spans of huge coordinates do not overflow. */
	double hw = 0.5 * xmax - 0.5 * xmin, hh = 0.5 * ymax - 0.5 * ymin;
	double span = hw > hh ? hw : hh;
	const double top = (double)((1u << 28) - 1);
	double scale = span > 0 ? top / span : 0;
	uint16_t tab[4][16][16];
	hilbert_table(tab);
	uint64_t *key = fct_alloc_array(n, sizeof *key, err);
	if (!key)
		return -1;
	for (size_t i = 0; i < n; i++) {
		double fx = (0.5 * uv[2 * i] - 0.5 * xmin) * scale;
		double fy = (0.5 * uv[2 * i + 1] - 0.5 * ymin) * scale;
		uint32_t x = fx > 0 ? (uint32_t)(fx < top ? fx : top) : 0;
		uint32_t y = fy > 0 ? (uint32_t)(fy < top ? fy : top) : 0;
		/* splitmix64's finaliser as the hash of i */
		uint64_t h = (uint64_t)i + 0x9e3779b97f4a7c15u;
		h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9u;
		h = (h ^ (h >> 27)) * 0x94d049bb133111ebu;
		h ^= h >> 31;
		uint64_t rnd = 0;
		while (rnd < 63 && !(h & 1)) {
			h >>= 1;
			rnd++;
		}
		key[i] = (63 - rnd) << 56 | hilbert((const uint16_t (*)[16][16])tab, x, y);
		order[i] = (uint32_t)i;
	}
	int r = radix_sort(key, order, n, err);
	free(key);
	return r;
}

/* ---- duplicates among collinear points ---- */

static int cmp_lex(const void *a, const void *b)
{
	const double *p = a, *q = b;
	if (p[0] != q[0])
		return p[0] < q[0] ? -1 : 1;
	if (p[1] != q[1])
		return p[1] < q[1] ? -1 : 1;
	return 0;
}

/* Number of points in p[0..n) equal to an earlier one.  Only reached when
 * there is no triangle to find them with (collinear input). */
static int count_duplicates(const double *p, size_t n, size_t *ndup, struct fct_err *err)
{
	double *s = fct_alloc_array(n, 2 * sizeof *s, err);
	if (!s)
		return -1;
	memcpy(s, p, n * 2 * sizeof *s);
	qsort(s, n, 2 * sizeof *s, cmp_lex);
	size_t k = 0;
	for (size_t i = 1; i < n; i++)
		k += same_point(s + 2 * i, s + 2 * (i - 1));
	free(s);
	*ndup = k;
	return 0;
}

/* ---- the whole ---- */

static void dt_free(struct dt *d)
{
	free(d->tv);
	free(d->nb);
	free(d->mark);
	free(d->first);
	free(d->stack);
	free(d->bnd);
}

/* The points in insertion order: *order[k] the input index of the k-th,
 * *p its coordinates (both malloc'd, NULL for none).  0 or -1. */
static int ordered_points(const double *uv, size_t n, uint32_t **order, double **p,
                          struct fct_err *err)
{
	*order = fct_alloc_array(n, sizeof **order, err);
	*p = *order ? fct_alloc_array(n, 2 * sizeof **p, err) : NULL;
	if (!*p)
		return -1;
	if (n > 0 && insertion_order(uv, n, *order, err))
		return -1;
	for (size_t k = 0; k < n; k++) {
		(*p)[2 * k] = uv[2 * (size_t)(*order)[k]];
		(*p)[2 * k + 1] = uv[2 * (size_t)(*order)[k] + 1];
	}
	return 0;
}

/* Seeds: the first point, the first one different from it (*j1), and the
 * first one not on the line through those two (*j2).  The points passed
 * over are duplicates or collinear; they are inserted later like any
 * other.  0, or 1 when there are fewer than three distinct points or all
 * are on one line. */
static int find_seeds(const double *p, size_t n, size_t *j1, size_t *j2)
{
	size_t a = 1, b;
	while (a < n && same_point(p, p + 2 * a))
		a++;
	b = a + 1;
	while (b < n && fct_orient2d(p, p + 2 * a, p + 2 * b) == 0)
		b++;
	*j1 = a, *j2 = b;
	return b >= n;
}

/* Move the seeds j1, j2 to places 1 and 2 (point and input index), so that
 * points 0, 1, 2 make a counter-clockwise triangle. */
static void seeds_first(double *p, uint32_t *order, size_t j1, size_t j2)
{
	for (int s = 0; s < 2; s++) {
		size_t a = (size_t)s + 1, b = s ? j2 : j1;
		double tx = p[2 * a], ty = p[2 * a + 1];
		uint32_t to = order[a];
		p[2 * a] = p[2 * b];
		p[2 * a + 1] = p[2 * b + 1];
		order[a] = order[b];
		p[2 * b] = tx;
		p[2 * b + 1] = ty;
		order[b] = to;
	}
	if (fct_orient2d(p, p + 2, p + 4) < 0) {
		for (int c = 0; c < 2; c++) {
			double t = p[2 + c];
			p[2 + c] = p[4 + c];
			p[4 + c] = t;
		}
		uint32_t t = order[1];
		order[1] = order[2];
		order[2] = t;
	}
}

/* Start the triangulation of the n points p (at least three, the first
 * three a counter-clockwise triangle), with room for all of them: triangle
 * 0 = (0, 1, 2) and its three ghosts as a fan around INF over its reversed
 * edges.  0 or -1. */
static int dt_start(struct dt *d, const double *p, size_t n, struct fct_err *err)
{
	size_t maxtri = 2 * n;
	d->p = p;
	d->inf = (uint32_t)n;
	d->tv = fct_alloc_array(maxtri, 3 * sizeof *d->tv, err);
	d->nb = d->tv ? fct_alloc_array(maxtri, 3 * sizeof *d->nb, err) : NULL;
	d->mark = d->nb ? fct_alloc_array(maxtri, sizeof *d->mark, err) : NULL;
	d->first = d->mark ? fct_alloc_array(n + 1, sizeof *d->first, err) : NULL;
	if (!d->first || grow_stack(d, 64, err) || grow_bnd(d, 64, err))
		return -1;
	uint32_t *v = d->tv;
	v[0] = 0;
	v[1] = 1;
	v[2] = 2;
	struct bedge hull[3];
	uint32_t slot[3] = {1, 2, 3};
	for (uint32_t e = 0; e < 3; e++) {
		hull[e].u = v[prev3(e)];
		hull[e].v = v[next3(e)];
		hull[e].out = e;
	}
	d->ntri = 4;
	memset(d->mark, 0, 4 * sizeof *d->mark);
	fan(d, d->inf, hull, 3, slot);
	d->last = 0;
	return 0;
}

/* Insert points 3 .. n-1; a duplicate is counted in *ndup and the vertex
 * it duplicates takes the lower of their input indices.  0 or -1. */
static int insert_rest(struct dt *d, uint32_t *order, size_t n, size_t *ndup, struct fct_err *err)
{
	for (size_t k = 3; k < n; k++) {
		uint32_t dup;
		int r = insert(d, (uint32_t)k, (uint32_t)k, &dup, err);
		if (r < 0)
			return -1;
		if (r == 1) {
			(*ndup)++;
			if (order[k] < order[dup])
				order[dup] = order[k];
		}
	}
	return 0;
}

/* The triangles that are not ghosts, in input indices, each rotated to
 * put its smallest index first (the orientation stays): *out (malloc'd)
 * holds *nout of them.  0 or -1. */
static int real_triangles(const struct dt *d, const uint32_t *order, uint32_t **out, size_t *nout,
                          struct fct_err *err)
{
	size_t nreal = 0;
	for (uint32_t t = 0; t < d->ntri; t++)
		nreal += !is_ghost(d, t);
	*out = fct_alloc_array(nreal, 3 * sizeof **out, err);
	if (!*out)
		return -1;
	size_t m = 0;
	for (uint32_t t = 0; t < d->ntri; t++) {
		if (is_ghost(d, t))
			continue;
		uint32_t a = order[d->tv[3 * t]], b = order[d->tv[3 * t + 1]], c = order[d->tv[3 * t + 2]];
		if (b < a && b < c) {
			uint32_t x = a;
			a = b;
			b = c;
			c = x;
		} else if (c < a && c < b) {
			uint32_t x = c;
			c = b;
			b = a;
			a = x;
		}
		(*out)[3 * m] = a;
		(*out)[3 * m + 1] = b;
		(*out)[3 * m + 2] = c;
		m++;
	}
	*nout = nreal;
	return 0;
}

int fct_delaunay(uint32_t **tri, size_t *ntri, size_t *nduplicates, const double *uv, size_t n,
                 struct fct_err *err)
{
	*tri = NULL;
	*ntri = 0;
	if (nduplicates)
		*nduplicates = 0;
	if (n > FCT_DELAUNAY_MAX_POINTS)
		return fct_fail(err, "%zu points: at most %zu can be triangulated", n, FCT_DELAUNAY_MAX_POINTS);
	for (size_t i = 0; i < 2 * n; i++)
		if (!isfinite(uv[i]))
			return fct_fail(err, "point %zu: coordinate is not finite", i / 2);

	struct dt d;
	memset(&d, 0, sizeof d);
	double *p = NULL;
	uint32_t *order = NULL, *out = NULL;
	size_t ndup = 0, nout = 0, j1, j2;
	int rc = -1;
	if (ordered_points(uv, n, &order, &p, err))
		goto done;
	if (find_seeds(p, n, &j1, &j2)) {
		/* no triangle: success, with the duplicates counted apart */
		if (count_duplicates(p, n, &ndup, err))
			goto done;
		out = fct_alloc_array(0, sizeof *out, err);
		rc = out ? 0 : -1;
		goto done;
	}
	seeds_first(p, order, j1, j2);
	if (dt_start(&d, p, n, err) || insert_rest(&d, order, n, &ndup, err) ||
	    real_triangles(&d, order, &out, &nout, err))
		goto done;
	*ntri = nout;
	rc = 0;
done:
	if (rc == 0) {
		*tri = out;
		if (nduplicates)
			*nduplicates = ndup;
	} else {
		free(out);
	}
	dt_free(&d);
	free(p);
	free(order);
	return rc;
}
