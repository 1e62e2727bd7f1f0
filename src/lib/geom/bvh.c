/* bvh.c - binned-SAH bounding volume hierarchy and nearest-first closest
 * point queries (see bvh.h).  The build follows Wald, "On fast Construction
 * of SAH-based Bounding Volume Hierarchies" (2007): centroids are binned
 * along the widest axis and the split with the least area-weighted count
 * wins. */
#include "geom/bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

enum {
	LEAF_MAX = 4,          /* triangles per leaf */
	NBINS = 16,
	SAH_DEPTH = 40,        /* below this depth, split at the object median */
	STACK_MAX = 128        /* > SAH_DEPTH + 32 + 1: the deepest possible tree */
};

/* Bounds of one triangle during the build: float, rounded outward. */
struct box {
	float lo[3], hi[3];
};

/* A triangle during the build, moved around with its index i. */
struct tbox {
	float lo[3], hi[3];
	float mid[3];
	uint32_t i;
};

static void box_empty(struct box *b)
{
	for (int k = 0; k < 3; k++) {
		b->lo[k] = FLT_MAX;
		b->hi[k] = -FLT_MAX;
	}
}

static void box_grow(struct box *b, const float lo[3], const float hi[3])
{
	for (int k = 0; k < 3; k++) {
		if (lo[k] < b->lo[k]) b->lo[k] = lo[k];
		if (hi[k] > b->hi[k]) b->hi[k] = hi[k];
	}
}

static double box_area(const struct box *b)
{
	double x = (double)b->hi[0] - b->lo[0], y = (double)b->hi[1] - b->lo[1];
	double z = (double)b->hi[2] - b->lo[2];
	if (x < 0 || y < 0 || z < 0)
		return 0;
	return x * y + y * z + z * x;
}

/* Floats that enclose v: the nearest float at or below / at or above it.
 * Beyond float range (|v| > 3.4e38) the bounds clamp to +-FLT_MAX and no
 * longer enclose: such coordinates are outside what the tree supports. */
static float float_down(double v)
{
	if (v <= -FLT_MAX) return -FLT_MAX;
	if (v >= FLT_MAX) return FLT_MAX;
	float f = (float)v;
	return (double)f > v ? nextafterf(f, -FLT_MAX) : f;
}

static float float_up(double v)
{
	if (v >= FLT_MAX) return FLT_MAX;
	if (v <= -FLT_MAX) return -FLT_MAX;
	float f = (float)v;
	return (double)f < v ? nextafterf(f, FLT_MAX) : f;
}

/* Work item of the build: make node `node` over tb[begin..end), whose
 * centroids span cb (the node's own box is already set). */
struct task {
	uint32_t node, begin, end;
	int depth;
	struct box cb;
};

/* For the object-median fallback: order by centroid on one axis, then index,
 * a total order so the tree does not depend on qsort's algorithm. */
#define MEDIAN_CMP(k) \
	static int median_cmp##k(const void *pa, const void *pb) \
	{ \
		const struct tbox *a = pa, *b = pb; \
		if (a->mid[k] != b->mid[k]) \
			return a->mid[k] < b->mid[k] ? -1 : 1; \
		return (a->i > b->i) - (a->i < b->i); \
	}
MEDIAN_CMP(0)
MEDIAN_CMP(1)
MEDIAN_CMP(2)
static int (*const median_cmp[3])(const void *, const void *) = {median_cmp0, median_cmp1, median_cmp2};

/* Box and centroid box of tb[0..n). */
static void range_box(const struct tbox *tb, uint32_t n, struct box *bb, struct box *cb)
{
	box_empty(bb);
	box_empty(cb);
	for (uint32_t i = 0; i < n; i++) {
		box_grow(bb, tb[i].lo, tb[i].hi);
		box_grow(cb, tb[i].mid, tb[i].mid);
	}
}

static inline int bin_of(float mid, float lo, double scale)
{
	int j = (int)(((double)mid - lo) * scale);
	return j < NBINS ? j : NBINS - 1;
}

/* Choose where to split tb[0..n), whose centroids span cb, and reorder it so
 * the first part comes first; returns the size of the first part, strictly
 * between 0 and n. */
static uint32_t split(struct tbox *tb, uint32_t n, int depth, const struct box *cb)
{
	int axis = 0;
	double ext[3], scale[3];
	for (int k = 0; k < 3; k++) {
		ext[k] = (double)cb->hi[k] - cb->lo[k];
		scale[k] = ext[k] > 0 ? NBINS / ext[k] : 0;
	}
	/* Widest axis of the centroids; ties keep the lower axis. */
	if (ext[1] > ext[axis]) axis = 1;
	if (ext[2] > ext[axis]) axis = 2;
	if (!(ext[axis] > 0))
		return n / 2;   /* every centroid equal: any halving will do */

	if (depth < SAH_DEPTH) {
		/* Bin along the widest axis only: a third of the work of trying
		 * all three, and no slower to query on scanned surfaces. */
		int k = axis;
		struct box bins[NBINS];
		uint32_t cnt[NBINS] = {0};
		for (int j = 0; j < NBINS; j++)
			box_empty(&bins[j]);
		for (uint32_t i = 0; i < n; i++) {
			int j = bin_of(tb[i].mid[k], cb->lo[k], scale[k]);
			cnt[j]++;
			box_grow(&bins[j], tb[i].lo, tb[i].hi);
		}
		/* Sweep from the right for the right-hand areas, then from the left. */
		double right_area[NBINS];
		uint32_t right_cnt[NBINS];
		struct box acc;
		box_empty(&acc);
		uint32_t c = 0;
		for (int j = NBINS - 1; j > 0; j--) {
			box_grow(&acc, bins[j].lo, bins[j].hi);
			c += cnt[j];
			right_area[j] = box_area(&acc);
			right_cnt[j] = c;
		}
		int best_bin = -1;
		double best_cost = INFINITY;
		box_empty(&acc);
		c = 0;
		for (int j = 0; j < NBINS - 1; j++) {
			box_grow(&acc, bins[j].lo, bins[j].hi);
			c += cnt[j];
			if (c == 0 || right_cnt[j + 1] == 0)
				continue;
			double cost = box_area(&acc) * c + right_area[j + 1] * right_cnt[j + 1];
			if (cost < best_cost) {
				best_cost = cost;
				best_bin = j;
			}
		}
		if (best_bin >= 0) {
			uint32_t i = 0, j = n;
			/* In-place partition: bins <= best_bin to the front. */
			while (i < j) {
				if (bin_of(tb[i].mid[k], cb->lo[k], scale[k]) <= best_bin) {
					i++;
				} else {
					struct tbox tmp = tb[i];
					tb[i] = tb[--j];
					tb[j] = tmp;
				}
			}
			if (i > 0 && i < n)
				return i;
		}
	}
	/* Object median along the widest axis: halves the range, bounding depth. */
	qsort(tb, n, sizeof *tb, median_cmp[axis]);
	return n / 2;
}

static void set_box(struct fct_bvh_node *nd, const struct box *b)
{
	memcpy(nd->lo, b->lo, sizeof nd->lo);
	memcpy(nd->hi, b->hi, sizeof nd->hi);
}

/* Build the tree over tb[0..n) into b->nodes, reordering tb into leaf order;
 * b->tris is filled by the caller from tb[k].i. */
static int build_tree(struct fct_bvh *b, struct tbox *tb, uint32_t n, struct fct_err *err)
{
	/* Node 0 is the root, node 1 padding, then child pairs from node 2, so
	 * with 32-byte nodes every pair shares one 64-byte line.  A tree with
	 * leaves of >= 1 triangle has at most 2n - 1 nodes. */
	size_t cap = 2 * (size_t)n + 2, bytes;
	if (fct_mul_size(cap, sizeof *b->nodes, &bytes))
		return fct_fail(err, "bvh: %u triangles: too many", n);
	bytes = (bytes + 63) / 64 * 64;
	b->nodes = aligned_alloc(64, bytes);
	struct task *stack = malloc(sizeof *stack * STACK_MAX);
	if (!b->nodes || !stack) {
		free(stack);
		return fct_fail(err, "bvh: out of memory for %u triangles", n);
	}
	memset(&b->nodes[1], 0, sizeof b->nodes[1]);
	struct box bb, cb;
	range_box(tb, n, &bb, &cb);
	set_box(&b->nodes[0], &bb);
	uint32_t used = 2;
	int sp = 0, depth = 0;
	stack[sp++] = (struct task){0, 0, n, 0, cb};
	while (sp > 0) {
		struct task t = stack[--sp];
		struct fct_bvh_node *nd = &b->nodes[t.node];
		if (t.depth > depth)
			depth = t.depth;
		if (t.end - t.begin <= LEAF_MAX) {
			nd->first = t.begin;
			nd->count = t.end - t.begin;
			continue;
		}
		uint32_t mid = t.begin + split(tb + t.begin, t.end - t.begin, t.depth, &t.cb);
		uint32_t l = used;
		if (l + 2 > cap || sp + 2 > STACK_MAX)
			abort();    /* cannot happen: see the bounds above */
		used += 2;
		nd->first = l;
		nd->count = 0;
		struct box lcb, rcb;
		range_box(tb + t.begin, mid - t.begin, &bb, &lcb);
		set_box(&b->nodes[l], &bb);
		range_box(tb + mid, t.end - mid, &bb, &rcb);
		set_box(&b->nodes[l + 1], &bb);
		/* Right pushed first so the left subtree is laid out next. */
		stack[sp++] = (struct task){l + 1, mid, t.end, t.depth + 1, rcb};
		stack[sp++] = (struct task){l, t.begin, mid, t.depth + 1, lcb};
	}
	b->nnodes = used;
	b->depth = depth;
	free(stack);
	return 0;
}

/* Common build over triangles given as corner index triples and ids. */
static int build(struct fct_bvh *b, const double *xyz, const uint32_t *tri, const uint32_t *ids,
                 size_t ntri, struct fct_err *err)
{
	memset(b, 0, sizeof *b);
	if (ntri == 0)
		return 0;
	if (ntri > (size_t)1 << 31)
		return fct_fail(err, "bvh: %zu triangles: more than 2^31", ntri);
	uint32_t n = (uint32_t)ntri;
	struct tbox *tb = malloc(sizeof *tb * ntri);
	b->tris = malloc(sizeof *b->tris * ntri);
	if (!tb || !b->tris) {
		free(tb);
		fct_bvh_free(b);
		return fct_fail(err, "bvh: out of memory for %zu triangles", ntri);
	}
	for (uint32_t i = 0; i < n; i++) {
		const double *p[3];
		for (int j = 0; j < 3; j++) {
			uint32_t v = tri[3 * (size_t)i + j];
			p[j] = xyz + 3 * (size_t)v;
			/* A NaN would make boxes and bins meaningless: refuse it here. */
			if (!isfinite(p[j][0]) || !isfinite(p[j][1]) || !isfinite(p[j][2])) {
				free(tb);
				fct_bvh_free(b);
				return fct_fail(err, "vertex %u: coordinate is not finite", v);
			}
		}
		for (int k = 0; k < 3; k++) {
			double lo = fmin(p[0][k], fmin(p[1][k], p[2][k]));
			double hi = fmax(p[0][k], fmax(p[1][k], p[2][k]));
			tb[i].lo[k] = float_down(lo);
			tb[i].hi[k] = float_up(hi);
			/* From the clamped bounds, so centroids stay finite floats. */
			tb[i].mid[k] = (float)(0.5 * tb[i].lo[k] + 0.5 * tb[i].hi[k]);
		}
		tb[i].i = i;
	}
	int rc = build_tree(b, tb, n, err);
	if (rc == 0) {
		for (uint32_t i = 0; i < n; i++) {
			size_t t = tb[i].i;
			struct fct_bvh_tri *o = &b->tris[i];
			memcpy(o->a, xyz + 3 * (size_t)tri[3 * t], sizeof o->a);
			memcpy(o->b, xyz + 3 * (size_t)tri[3 * t + 1], sizeof o->b);
			memcpy(o->c, xyz + 3 * (size_t)tri[3 * t + 2], sizeof o->c);
			o->id = ids ? ids[t] : (uint32_t)t;
			o->degenerate = (uint32_t)fct_triangle_degenerate(o->a, o->b, o->c);
		}
		b->ntri = ntri;
	} else {
		fct_bvh_free(b);
	}
	free(tb);
	return rc;
}

int fct_bvh_build(struct fct_bvh *b, const double *xyz, const uint32_t *tri, size_t ntri,
                  struct fct_err *err)
{
	return build(b, xyz, tri, NULL, ntri, err);
}

int fct_mesh_fan(const struct fct_mesh *m, uint32_t **tri, uint32_t **face, size_t *ntri,
                 struct fct_err *err)
{
	size_t n = 0;
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t k = fct_face_size(m, f);
		n += k >= 3 ? k - 2 : k > 0;
	}
	*tri = NULL;
	*face = NULL;
	*ntri = 0;
	if (n > (size_t)1 << 31 || m->nf > UINT32_MAX)
		return fct_fail(err, "%zu triangles: more than 2^31", n);
	uint32_t *t3 = malloc(sizeof *t3 * 3 * (n ? n : 1));
	uint32_t *ids = malloc(sizeof *ids * (n ? n : 1));
	if (!t3 || !ids) {
		free(t3);
		free(ids);
		return fct_fail(err, "out of memory for %zu triangles", n);
	}
	size_t t = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *v = m->fvert + m->fstart[f];
		uint32_t k = fct_face_size(m, f);
		if (k == 0)
			continue;
		if (k < 3) {
			t3[3 * t] = v[0];
			t3[3 * t + 1] = t3[3 * t + 2] = v[k - 1];
			ids[t++] = (uint32_t)f;
			continue;
		}
		for (uint32_t i = 1; i + 1 < k; i++) {
			t3[3 * t] = v[0];
			t3[3 * t + 1] = v[i];
			t3[3 * t + 2] = v[i + 1];
			ids[t++] = (uint32_t)f;
		}
	}
	*tri = t3;
	*face = ids;
	*ntri = n;
	return 0;
}

int fct_bvh_build_mesh(struct fct_bvh *b, const struct fct_mesh *m, struct fct_err *err)
{
	uint32_t *tri, *ids;
	size_t ntri;
	memset(b, 0, sizeof *b);
	if (fct_mesh_fan(m, &tri, &ids, &ntri, err))
		return -1;
	int rc = build(b, m->xyz, tri, ids, ntri, err);
	free(tri);
	free(ids);
	return rc;
}

void fct_bvh_free(struct fct_bvh *b)
{
	if (!b)
		return;
	free(b->nodes);
	free(b->tris);
	memset(b, 0, sizeof *b);
}

/* Squared distance from p to the box of n (0 inside).  Computed in double
 * from the float bounds, which already enclose the triangles. */
static inline double box_dist2(const struct fct_bvh_node *n, const double p[3])
{
	double d2 = 0;
	for (int k = 0; k < 3; k++) {
		double lo = (double)n->lo[k] - p[k], hi = p[k] - (double)n->hi[k];
		double d = lo > hi ? lo : hi;
		if (d > 0)
			d2 += d * d;
	}
	return d2;
}

/* Test one triangle; update hit and return the new best squared distance.
 * With no limit, the first triangle is taken even when its squared distance
 * overflows to infinity, so an unlimited query always has an answer. */
static inline double test_tri(const struct fct_bvh_tri *t, const double p[3], double best,
                              struct fct_bvh_hit *hit, int *found)
{
	double q[3], d2;
	if (t->degenerate) {
		d2 = fct_closest_on_triangle(p, t->a, t->b, t->c, q, NULL);
	} else {
		d2 = fct_closest_on_triangle_nd(p, t->a, t->b, t->c, q, NULL);
	}
	if (d2 < best || (!*found && best == INFINITY)) {
		memcpy(hit->q, q, sizeof q);
		hit->d2 = d2;
		hit->id = t->id;
		*found = 1;
		return d2;
	}
	return best;
}

int fct_bvh_closest(const struct fct_bvh *b, const double p[3], double max_d2,
                    struct fct_bvh_hit *hit)
{
	if (b->ntri == 0)
		return 0;
	const struct fct_bvh_node *nodes = b->nodes;
	struct {
		uint32_t node;
		double d2;
	} stack[STACK_MAX];
	int sp = 0, found = 0;
	double best = max_d2;
	const struct fct_bvh_node *n = &nodes[0];
	/* Far beyond the scale of doubles, box distances overflow to infinity;
	 * an unlimited query still descends (to the first child) to answer. */
	if (!(box_dist2(n, p) < best) && best != INFINITY)
		return 0;
	for (;;) {
		if (n->count) {
			const struct fct_bvh_tri *t = b->tris + n->first;
			for (uint32_t i = 0; i < n->count; i++)
				best = test_tri(&t[i], p, best, hit, &found);
		} else {
			const struct fct_bvh_node *l = &nodes[n->first], *r = l + 1;
			double dl = box_dist2(l, p), dr = box_dist2(r, p);
			uint32_t near = n->first, far = near + 1;
			if (dr < dl) {
				double tmp = dl;
				dl = dr;
				dr = tmp;
				near = far;
				far = n->first;
			}
			if (dl < best || (!found && best == INFINITY)) {
				/* Descend into the nearer child now, keep the farther one. */
				if (dr < best) {
					stack[sp].node = far;
					stack[sp++].d2 = dr;
				}
				n = &nodes[near];
				continue;
			}
		}
		/* Pop the next subtree that may still hold something closer. */
		for (;;) {
			if (sp == 0)
				return found;
			sp--;
			if (stack[sp].d2 < best) {
				n = &nodes[stack[sp].node];
				break;
			}
		}
	}
}

int fct_bvh_closest_brute(const struct fct_bvh *b, const double p[3], double max_d2,
                          struct fct_bvh_hit *hit)
{
	int found = 0;
	double best = max_d2;
	for (size_t i = 0; i < b->ntri; i++)
		best = test_tri(&b->tris[i], p, best, hit, &found);
	return found;
}

/* Ray casting ----------------------------------------------------------------- */

/* A ray prepared once for the watertight test and the slab test. */
struct ray {
	double org[3], dir[3];
	double inv[3];        /* 1 / dir (infinite for a zero component) */
	int kx, ky, kz;       /* kz: the largest component of dir */
	double sx, sy, sz;    /* the shear that maps dir to the z axis */
};

static int ray_setup(struct ray *r, const double org[3], const double dir[3])
{
	for (int k = 0; k < 3; k++) {
		if (!isfinite(org[k]) || !isfinite(dir[k]))
			return -1;
		r->org[k] = org[k];
		r->dir[k] = dir[k];
		r->inv[k] = 1.0 / dir[k];   /* +-inf for a zero: handled in box_enter */
	}
	int kz = 0;
	if (fabs(dir[1]) > fabs(dir[kz])) kz = 1;
	if (fabs(dir[2]) > fabs(dir[kz])) kz = 2;
	if (dir[kz] == 0)
		return -1;
	int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
	if (dir[kz] < 0) {   /* keep the winding: a mirror flips it */
		int tmp = kx;
		kx = ky;
		ky = tmp;
	}
	r->kx = kx, r->ky = ky, r->kz = kz;
	r->sx = dir[kx] / dir[kz];
	r->sy = dir[ky] / dir[kz];
	r->sz = 1.0 / dir[kz];
	return 0;
}

/* Where the ray enters the box of n within [tmin, tfar], or -INFINITY
 * when it misses it.  The far bound is widened by 1 + 4 DBL_EPSILON, more than
 * Ize's 1 + 2 gamma(3), so rounding never loses a box the ray touches; an
 * axis the ray runs parallel to is a plain inside test (no 0 * inf). */
static inline double box_enter(const struct ray *r, const struct fct_bvh_node *n, double tmin,
                               double tfar)
{
	double tnear = tmin;
	for (int k = 0; k < 3; k++) {
		double lo = n->lo[k], hi = n->hi[k];
		if (r->dir[k] == 0) {
			if (r->org[k] < lo || r->org[k] > hi)
				return -1;
			continue;
		}
		double t0 = (lo - r->org[k]) * r->inv[k], t1 = (hi - r->org[k]) * r->inv[k];
		if (t0 > t1) {
			double tmp = t0;
			t0 = t1;
			t1 = tmp;
		}
		if (t0 > tnear) tnear = t0;
		if (t1 < tfar) tfar = t1;
	}
	return tnear <= tfar + fabs(tfar) * (4 * DBL_EPSILON) ? tnear : -INFINITY;
}

/* Is (t, id, idx) before the hit found so far? */
static inline int ray_better(double t, uint32_t id, uint32_t idx, const struct fct_bvh_ray_hit *h,
                             int found)
{
	if (!found || t < h->t)
		return 1;
	return t == h->t && (id < h->id || (id == h->id && idx < h->tri));
}

/* The watertight test of one triangle (Woop, Benthin and Wald, 2013); on a
 * hit with tmin <= t <= tmax that beats *hit, *hit is updated. */
static inline void ray_tri(const struct ray *r, const struct fct_bvh_tri *tri, uint32_t idx,
                           double tmin, double tmax, struct fct_bvh_ray_hit *hit, int *found)
{
	const int kx = r->kx, ky = r->ky, kz = r->kz;
	double a[3], b[3], c[3];
	fct_v3_sub(a, tri->a, r->org);
	fct_v3_sub(b, tri->b, r->org);
	fct_v3_sub(c, tri->c, r->org);
	double ax = a[kx] - r->sx * a[kz], ay = a[ky] - r->sy * a[kz];
	double bx = b[kx] - r->sx * b[kz], by = b[ky] - r->sy * b[kz];
	double cx = c[kx] - r->sx * c[kz], cy = c[ky] - r->sy * c[kz];
	/* Each edge function is a difference of two products that the other
	 * triangle of the edge forms with its operands swapped: exactly the
	 * negated value, so the two sign tests agree. */
	double eu = cx * by - cy * bx;
	double ev = ax * cy - ay * cx;
	double ew = bx * ay - by * ax;
	if ((eu < 0 || ev < 0 || ew < 0) && (eu > 0 || ev > 0 || ew > 0))
		return;
	double det = eu + ev + ew;
	if (det == 0)
		return;
	double az = r->sz * a[kz], bz = r->sz * b[kz], cz = r->sz * c[kz];
	double t = (eu * az + ev * bz + ew * cz) / det;
	if (!(t >= tmin && t <= tmax))
		return;
	if (!ray_better(t, tri->id, idx, hit, *found))
		return;
	hit->t = t;
	hit->u = ev / det;
	hit->v = ew / det;
	hit->id = tri->id;
	hit->tri = idx;
	*found = 1;
}

int fct_bvh_raycast(const struct fct_bvh *b, const double org[3], const double dir[3],
                    double tmin, double tmax, struct fct_bvh_ray_hit *hit)
{
	struct ray r;
	if (b->ntri == 0 || ray_setup(&r, org, dir) || !(tmin <= tmax))
		return 0;
	const struct fct_bvh_node *nodes = b->nodes;
	struct {
		uint32_t node;
		double t;
	} stack[STACK_MAX];
	int sp = 0, found = 0;
	double best = tmax;   /* hits beyond are not wanted; ties at best are */
	if (box_enter(&r, &nodes[0], tmin, best) == -INFINITY)
		return 0;
	const struct fct_bvh_node *n = &nodes[0];
	for (;;) {
		if (n->count) {
			for (uint32_t i = 0; i < n->count; i++)
				ray_tri(&r, &b->tris[n->first + i], n->first + i, tmin, best, hit, &found);
			if (found)
				best = hit->t;
		} else {
			uint32_t near = n->first, far = near + 1;
			double tl = box_enter(&r, &nodes[near], tmin, best);
			double tr = box_enter(&r, &nodes[far], tmin, best);
			const double miss = -INFINITY;
			if (tl != miss || tr != miss) {
				if (tl == miss || (tr != miss && tr < tl)) {
					double tmp = tl;
					tl = tr;
					tr = tmp;
					near = far;
					far = n->first;
				}
				if (tr != miss) {
					stack[sp].node = far;
					stack[sp++].t = tr;
				}
				n = &nodes[near];
				continue;
			}
		}
		/* Pop the next subtree the ray may still meet at or before best. */
		for (;;) {
			if (sp == 0)
				return found;
			sp--;
			if (stack[sp].t <= best + fabs(best) * (4 * DBL_EPSILON)) {
				n = &nodes[stack[sp].node];
				break;
			}
		}
	}
}

int fct_bvh_raycast_brute(const struct fct_bvh *b, const double org[3], const double dir[3],
                          double tmin, double tmax, struct fct_bvh_ray_hit *hit)
{
	struct ray r;
	if (b->ntri == 0 || ray_setup(&r, org, dir) || !(tmin <= tmax))
		return 0;
	int found = 0;
	for (size_t i = 0; i < b->ntri; i++)
		ray_tri(&r, &b->tris[i], (uint32_t)i, tmin, found ? hit->t : tmax, hit, &found);
	return found;
}
