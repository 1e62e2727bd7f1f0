/* chain.c - patch boundaries as chains and their simplification: Kang,
 * Johnson and Szeliski, "Extraction of Concise and Realistic 3-D Models from
 * Real Data" (DEC CRL 95/7), section 3 (see chain.h for the rules). */
#include "planar/chain.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "core/arena.h"
#include "geom/geom.h"
#include "io/header.h"
#include "geom/predicates.h"

#define OUTSIDE FCT_CHAIN_OUTSIDE

void fct_chain_params_default(struct fct_chain_params *p)
{
	p->threshold = 3;
	p->keep_topology = 1;
	p->keep_small_loops = 0;
	p->scale = NULL;
	p->scale_factor = 3;
	p->tolerance = NULL;
	p->keep_vertex = NULL;
	p->count_left = 1;
	p->cache = NULL;
}

void fct_chains_free(struct fct_chains *c)
{
	if (!c)
		return;
	free(c->start);
	free(c->vert);
	free(c->keep);
	free(c->left);
	free(c->right);
	free(c->closed);
	free(c->frozen);
	memset(c, 0, sizeof *c);
}

/* Extraction -------------------------------------------------------------- */

/* The order in which sides are preferred as the left side of a record:
 * patches by label, then unlabelled (-1), then the outside. */
static long side_rank(int32_t s)
{
	return s >= 0 ? (long)s : s == -1 ? (long)INT32_MAX + 1 : (long)INT32_MAX + 2;
}

struct side {
	int32_t label;
	int dir;          /* +1: walks lower -> higher vertex, -1: the other way */
};

static int side_cmp(const void *pa, const void *pb)
{
	const struct side *a = pa, *b = pb;
	long ra = side_rank(a->label), rb = side_rank(b->label);
	if (ra != rb)
		return ra < rb ? -1 : 1;
	return (a->dir > b->dir) - (a->dir < b->dir);
}

static void sides_sort(struct side *s, size_t n)
{
	if (n > 16) {
		qsort(s, n, sizeof *s, side_cmp);
		return;
	}
	for (size_t i = 1; i < n; i++) {
		struct side t = s[i];
		size_t j = i;
		while (j > 0 && side_cmp(&s[j - 1], &t) > 0) {
			s[j] = s[j - 1];
			j--;
		}
		s[j] = t;
	}
}

/* A directed boundary record: left walks a -> b. */
struct rec {
	uint32_t a, b;
	int32_t l, r;
};

struct recs {
	struct rec *r;
	size_t n, cap;
};

static int rec_add(struct recs *rs, uint32_t lo, uint32_t hi, int32_t p, int pdir, int32_t q,
                   struct fct_err *err)
{
	/* p walks in direction pdir; q (another side or the outside) the other way. */
	if (fct_grow((void **)&rs->r, &rs->cap, rs->n + 1, sizeof *rs->r, err))
		return -1;
	struct rec *x = &rs->r[rs->n++];
	int32_t l = p, r = q;
	int dir = pdir;
	if (side_rank(q) < side_rank(p))
		l = q, r = p, dir = -pdir;
	x->a = dir > 0 ? lo : hi;
	x->b = dir > 0 ? hi : lo;
	x->l = l, x->r = r;
	return 0;
}

/* The boundary records of edge e from its walking sides s[0..n): bounded
 * sides (odd count) paired a -> b with b -> a in rank order, the rest against
 * the outside.  s is sorted here. */
static int edge_records(struct recs *rs, uint32_t lo, uint32_t hi, struct side *s, size_t n,
                        struct side *plus, struct side *minus, unsigned char *touch_out,
                        struct fct_err *err)
{
	sides_sort(s, n);
	size_t np = 0, nm = 0;
	for (size_t i = 0; i < n;) {
		size_t j = i;
		int net = 0;
		while (j < n && s[j].label == s[i].label)
			net += s[j++].dir;
		if ((j - i) % 2) {
			struct side x = { s[i].label, net > 0 ? 1 : -1 };
			if (x.dir > 0)
				plus[np++] = x;
			else
				minus[nm++] = x;
		}
		i = j;
	}
	size_t k = 0;
	for (; k < np && k < nm; k++)
		if (rec_add(rs, lo, hi, plus[k].label, 1, minus[k].label, err))
			return -1;
	for (size_t i = k; i < np; i++)
		if (rec_add(rs, lo, hi, plus[i].label, 1, OUTSIDE, err))
			return -1;
	for (size_t i = k; i < nm; i++)
		if (rec_add(rs, lo, hi, minus[i].label, -1, OUTSIDE, err))
			return -1;
	if (np != nm)
		touch_out[lo] = touch_out[hi] = 1;
	return 0;
}

/* Distinct sides around v, counted up to 3. */
static int vertex_sides(const struct fct_adj *a, const int32_t *patch, int outside, uint32_t v)
{
	int32_t seen[3];
	int n = 0;
	if (outside)
		seen[n++] = OUTSIDE;
	for (uint32_t k = a->vert_fstart[v]; k < a->vert_fstart[v + 1]; k++) {
		int32_t p = patch[a->vert_f[k]];
		int found = 0;
		for (int i = 0; i < n; i++)
			found |= seen[i] == p;
		if (found)
			continue;
		if (n == 2)
			return 3;
		seen[n++] = p;
	}
	return n;
}

/* Growing the chain arrays: one capacity per array. */
struct chain_build {
	struct fct_chains *c;
	size_t np;                          /* points so far */
	size_t cap_start, cap_l, cap_r, cap_closed, cap_vert;
};

static int chain_begin(struct chain_build *b, int32_t l, int32_t r, struct fct_err *err)
{
	struct fct_chains *c = b->c;
	if (fct_grow((void **)&c->start, &b->cap_start, c->n + 2, sizeof *c->start, err) ||
	    fct_grow((void **)&c->left, &b->cap_l, c->n + 1, sizeof *c->left, err) ||
	    fct_grow((void **)&c->right, &b->cap_r, c->n + 1, sizeof *c->right, err) ||
	    fct_grow((void **)&c->closed, &b->cap_closed, c->n + 1, sizeof *c->closed, err))
		return -1;
	c->start[c->n] = b->np;
	c->left[c->n] = l, c->right[c->n] = r, c->closed[c->n] = 0;
	return 0;
}

static int chain_point(struct chain_build *b, uint32_t v, struct fct_err *err)
{
	if (fct_grow((void **)&b->c->vert, &b->cap_vert, b->np + 1, sizeof *b->c->vert, err))
		return -1;
	b->c->vert[b->np++] = v;
	return 0;
}

static void chain_end(struct chain_build *b, int loop)
{
	struct fct_chains *c = b->c;
	c->closed[c->n] = c->vert[c->start[c->n]] != c->vert[b->np - 1] ? 0 : loop ? 2 : 1;
	c->start[++c->n] = b->np;
}

/* The mean edge length (the unit of the simplification's threshold); the
 * most faces on one edge in *maxk. */
static double mean_edge(const struct fct_adj *a, const struct fct_mesh *m, size_t *maxk)
{
	double sum = 0;
	*maxk = 0;
	for (size_t e = 0; e < a->ne; e++) {
		sum += sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)a->edge_v[2 * e],
		                         m->xyz + 3 * (size_t)a->edge_v[2 * e + 1]));
		if (fct_adj_edge_nfaces(a, e) > *maxk)
			*maxk = fct_adj_edge_nfaces(a, e);
	}
	return a->ne ? sum / (double)a->ne : 0;
}

/* The boundary graph: the directed records with a patch on a side, their
 * out-lists (CSR by tail), each vertex's in-record, and the junctions. */
struct boundary {
	struct recs rs;
	uint32_t *outstart, *outrec, *inrec;
	unsigned char *touch_out;   /* per vertex: on an edge with the outside */
	unsigned char *junction;
};

/* g->rs: the records of every edge with different sides, less those that
 * only touched the outside; marks g->touch_out.  Counts the non-manifold
 * edges into c. */
static int boundary_records(struct boundary *g, struct fct_chains *c, const struct fct_adj *a,
                            const struct fct_mesh *m, const int32_t *patch, size_t maxk,
                            struct fct_err *err)
{
	int rc = -1;
	struct fct_arena ar = { 0 };
	signed char *dir = fct_arena_array(&ar, a->edge_fstart[a->ne], sizeof *dir, err);
	uint32_t *cursor = fct_arena_zeroed(&ar, a->ne ? a->ne : 1, sizeof *cursor, err);
	struct side *sbuf = fct_arena_array(&ar, 3 * (maxk ? maxk : 1), sizeof *sbuf, err);
	if (!dir || !cursor || !sbuf)
		goto done;
	/* The direction of every face's walk along every edge, in the order of
	 * edge_f (faces in increasing index, corners in order). */
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++) {
			uint32_t e = a->face_e[k];
			if (e == FCT_ADJ_NONE)
				continue;
			dir[a->edge_fstart[e] + cursor[e]++] = m->fvert[k] == a->edge_v[2 * e] ? 1 : -1;
		}
	for (size_t e = 0; e < a->ne; e++) {
		uint32_t k0 = a->edge_fstart[e], k1 = a->edge_fstart[e + 1];
		if (k1 - k0 == 2 && patch[a->edge_f[k0]] == patch[a->edge_f[k0 + 1]])
			continue;       /* interior, however wound (even count) */
		size_t n = 0;
		for (uint32_t k = k0; k < k1; k++)
			sbuf[n].label = patch[a->edge_f[k]], sbuf[n++].dir = dir[k];
		if (n >= 3)
			c->nonmanifold_edges++;
		if (edge_records(&g->rs, a->edge_v[2 * e], a->edge_v[2 * e + 1], sbuf, n, sbuf + maxk,
		                 sbuf + 2 * maxk, g->touch_out, err))
			goto done;
	}
	size_t nr = 0;
	for (size_t i = 0; i < g->rs.n; i++)
		if (g->rs.r[i].l >= 0)
			g->rs.r[nr++] = g->rs.r[i];
	g->rs.n = nr;
	rc = 0;
done:
	fct_arena_free(&ar);
	return rc;
}

/* g's out-lists and in-records, and its junctions: the vertices where a
 * chain must end, with other than one record in and one out, or a change
 * of the sides, or three sides around (the outside counted). */
static int find_junctions(struct boundary *g, struct fct_chains *c, const struct fct_adj *a,
                          const int32_t *patch, size_t nv, struct fct_arena *ar,
                          struct fct_err *err)
{
	const struct rec *r = g->rs.r;
	size_t nr = g->rs.n;
	g->outstart = fct_arena_zeroed(ar, nv + 1, sizeof *g->outstart, err);
	g->inrec = fct_arena_array(ar, nv, sizeof *g->inrec, err);
	g->outrec = fct_arena_array(ar, nr, sizeof *g->outrec, err);
	g->junction = fct_arena_zeroed(ar, nv ? nv : 1, 1, err);
	uint32_t *fill = fct_arena_zeroed(ar, nv ? nv : 1, sizeof *fill, err);
	if (!g->outstart || !g->inrec || !g->outrec || !g->junction || !fill)
		return -1;
	uint32_t *outstart = g->outstart;
	unsigned char *junction = g->junction;
	/* indeg in junction[] temporarily: 0, 1, 2 = two or more. */
	for (size_t i = 0; i < nr; i++) {
		outstart[r[i].a + 1]++;
		uint32_t b = r[i].b;
		if (junction[b] < 2)
			junction[b]++;
		g->inrec[b] = (uint32_t)i;
	}
	for (size_t v = 0; v < nv; v++)
		outstart[v + 1] += outstart[v];
	for (size_t i = 0; i < nr; i++)
		g->outrec[outstart[r[i].a] + fill[r[i].a]++] = (uint32_t)i;
	for (uint32_t v = 0; v < nv; v++) {
		uint32_t outdeg = outstart[v + 1] - outstart[v], indeg = junction[v];
		if (!outdeg && !indeg) {
			junction[v] = 0;
			continue;
		}
		c->boundary_vertices++;
		int j = outdeg != 1 || indeg != 1;
		if (!j) {
			const struct rec *ri = &r[g->inrec[v]], *ro = &r[g->outrec[outstart[v]]];
			j = ri->l != ro->l || ri->r != ro->r ||
			    vertex_sides(a, patch, g->touch_out[v], v) >= 3;
		}
		junction[v] = (unsigned char)j;
		c->junctions += (size_t)j;
	}
	return 0;
}

/* The chains of g into c: walked from the junctions, then the loops left. */
static int walk_chains(struct fct_chains *c, const struct boundary *g, unsigned char *visited,
                       struct fct_err *err)
{
	const struct rec *rs = g->rs.r;
	struct chain_build b = { c, 0, 0, 0, 0, 0, 0 };
	if (fct_grow((void **)&c->start, &b.cap_start, 1, sizeof *c->start, err))
		return -1;
	c->start[0] = 0;
	for (int pass = 0; pass < 2; pass++)
		for (size_t i = 0; i < g->rs.n; i++) {
			if (visited[i] || (pass == 0 && !g->junction[rs[i].a]))
				continue;
			uint32_t first = rs[i].a;
			if (chain_begin(&b, rs[i].l, rs[i].r, err) || chain_point(&b, first, err))
				return -1;
			for (size_t r = i;;) {
				if (visited[r])
					abort();    /* a non-junction has one record in and one out */
				visited[r] = 1;
				uint32_t v = rs[r].b;
				if (chain_point(&b, v, err))
					return -1;
				if (g->junction[v] || v == first)
					break;
				r = g->outrec[g->outstart[v]];
			}
			chain_end(&b, pass == 1);
			c->loops += pass == 1;
		}
	return 0;
}

int fct_chains_extract(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                       struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	struct fct_adj a;
	if (fct_adj_build(&a, m, err))
		return -1;
	int rc = fct_chains_extract_adj(c, m, &a, patch, err);
	fct_adj_free(&a);
	return rc;
}

int fct_chains_copy(struct fct_chains *dst, const struct fct_chains *src, struct fct_err *err)
{
	*dst = *src;
	dst->start = NULL, dst->vert = NULL, dst->keep = NULL, dst->left = NULL, dst->right = NULL;
	dst->closed = NULL, dst->frozen = NULL;
	size_t n = src->n, np = src->start ? src->start[n] : 0;
	if (!(dst->start = fct_alloc_array(n + 1, sizeof *dst->start, err)) ||
	    !(dst->vert = fct_alloc_array(np ? np : 1, sizeof *dst->vert, err)) ||
	    !(dst->keep = fct_alloc_array(np ? np : 1, 1, err)) ||
	    !(dst->left = fct_alloc_array(n ? n : 1, sizeof *dst->left, err)) ||
	    !(dst->right = fct_alloc_array(n ? n : 1, sizeof *dst->right, err)) ||
	    !(dst->closed = fct_alloc_array(n ? n : 1, 1, err)) ||
	    (src->frozen && !(dst->frozen = fct_alloc_array(n ? n : 1, 1, err)))) {
		fct_chains_free(dst);
		return -1;
	}
	dst->start[0] = 0;
	if (src->start)
		memcpy(dst->start, src->start, (n + 1) * sizeof *dst->start);
	if (np) {
		memcpy(dst->vert, src->vert, np * sizeof *dst->vert);
		memcpy(dst->keep, src->keep, np);
	}
	if (n) {
		memcpy(dst->left, src->left, n * sizeof *dst->left);
		memcpy(dst->right, src->right, n * sizeof *dst->right);
		memcpy(dst->closed, src->closed, n);
		if (src->frozen)
			memcpy(dst->frozen, src->frozen, n);
	}
	return 0;
}

int fct_chains_extract_adj(struct fct_chains *c, const struct fct_mesh *m, const struct fct_adj *adj,
                           const int32_t *patch, struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	struct fct_adj a = *adj;   /* read only */
	int rc = -1;
	struct fct_arena ar = { 0 };
	struct boundary g;
	memset(&g, 0, sizeof g);
	size_t maxk;
	c->mean_edge = mean_edge(&a, m, &maxk);
	if (!(g.touch_out = fct_arena_zeroed(&ar, m->nv ? m->nv : 1, 1, err)) ||
	    boundary_records(&g, c, &a, m, patch, maxk, err))
		goto done;
	c->boundary_edges = g.rs.n;
	unsigned char *visited = fct_arena_zeroed(&ar, g.rs.n ? g.rs.n : 1, 1, err);
	if (!visited || find_junctions(&g, c, &a, patch, m->nv, &ar, err) ||
	    walk_chains(c, &g, visited, err))
		goto done;
	size_t np = c->start[c->n];
	if (!(c->keep = fct_alloc_array(np, 1, err)))
		goto done;
	memset(c->keep, 1, np);
	rc = 0;
done:
	free(g.rs.r);
	fct_arena_free(&ar);
	if (rc)
		fct_chains_free(c);
	return rc;
}

/* Simplification ---------------------------------------------------------- */

static const double *pt(const struct fct_mesh *m, const struct fct_chains *c, size_t i)
{
	return m->xyz + 3 * (size_t)c->vert[i];
}

/* The point of (i, j) farthest from segment i-j (3-D, ties to the lowest
 * position) and its squared distance in *d2; i + 1 < j. */
static size_t farthest(const struct fct_mesh *m, const struct fct_chains *c, size_t i, size_t j,
                       double *d2)
{
	const double *a = pt(m, c, i), *b = pt(m, c, j);
	double best = -1, q[3];
	size_t k = i + 1;
	for (size_t x = i + 1; x < j; x++) {
		double d = fct_closest_on_segment(pt(m, c, x), a, b, q);
		if (d > best)
			best = d, k = x;
	}
	*d2 = best;
	return k;
}

/* Iterative end-point fit of positions i..j (both kept): keep the farthest
 * point while its squared distance exceeds tol2.  stack holds 2 (j - i)
 * entries. */
static void endpoint_fit(const struct fct_mesh *m, struct fct_chains *c, size_t i, size_t j,
                         double tol2, size_t *stack)
{
	size_t n = 0;
	stack[n++] = i, stack[n++] = j;
	while (n) {
		size_t hi = stack[--n], lo = stack[--n];
		if (hi - lo < 2)
			continue;
		double d2;
		size_t k = farthest(m, c, lo, hi, &d2);
		if (!(d2 > tol2))
			continue;
		c->keep[k] = 1;
		stack[n++] = lo, stack[n++] = k;
		stack[n++] = k, stack[n++] = hi;
	}
}

/* The end-point fit between each two consecutive kept positions of s..e,
 * after the points on forced vertices (NULL: none) are kept too. */
static void fit_between_kept(const struct fct_mesh *m, struct fct_chains *c, size_t s, size_t e,
                             double tol2, const unsigned char *forced, size_t *stack)
{
	if (forced)
		for (size_t x = s + 1; x < e; x++)
			c->keep[x] |= forced[c->vert[x]];
	for (size_t a = s, b; a < e; a = b) {
		for (b = a + 1; !c->keep[b]; b++)
			;
		endpoint_fit(m, c, a, b, tol2, stack);
	}
}

/* Largest squared distance of the points strictly between positions i and
 * j from segment i-j (0 when there are none). */
static double span_dev2(const struct fct_mesh *m, const struct fct_chains *c, size_t i, size_t j)
{
	double d2 = 0;
	if (j - i >= 2)
		farthest(m, c, i, j, &d2);
	return d2;
}

/* One pass over the kept points of positions s..e (ends kept): drop a point
 * when the segment between its kept neighbours still holds every original
 * point within the tolerance.  The end-point fit's first split of a U-shaped
 * chain lands anywhere on the far side, which then needs both corners too;
 * this takes such points out again.  A closed chain keeps min_kept points. */
static void drop_redundant(const struct fct_mesh *m, struct fct_chains *c, size_t s, size_t e,
                           double tol2, size_t min_kept, const unsigned char *forced)
{
	size_t kept = 0;
	for (size_t x = s; x < e; x++)
		kept += c->keep[x];
	size_t a = s;
	for (size_t k = s + 1; k < e; k++) {
		if (!c->keep[k])
			continue;
		size_t b = k + 1;
		while (!c->keep[b])
			b++;
		if (kept > min_kept && !(forced && forced[c->vert[k]]) && span_dev2(m, c, a, b) <= tol2) {
			c->keep[k] = 0;
			kept--;
		} else {
			a = k;
		}
	}
}

/* Rotate the loop at positions s..e (e repeats s) to start at position k. */
static int rotate_loop(struct fct_chains *c, size_t s, size_t e, size_t k, struct fct_err *err)
{
	size_t len = e - s;       /* distinct points */
	if (k == s)
		return 0;
	uint32_t *tmp = fct_alloc_array(len, sizeof *tmp, err);
	if (!tmp)
		return -1;
	for (size_t i = 0; i < len; i++)
		tmp[i] = c->vert[s + (k - s + i) % len];
	memcpy(c->vert + s, tmp, len * sizeof *tmp);
	c->vert[e] = c->vert[s];
	free(tmp);
	return 0;
}

/* Simplify chain ci alone by the end-point fit. */
static int simplify_chain(const struct fct_mesh *m, struct fct_chains *c, size_t ci, double tol2,
                          const unsigned char *forced, size_t *stack, struct fct_chain_stats *st,
                          struct fct_err *err)
{
	size_t s = c->start[ci], e = c->start[ci + 1] - 1;
	memset(c->keep + s, 0, e - s + 1);
	c->keep[s] = c->keep[e] = 1;
	if (!c->closed[ci]) {
		fit_between_kept(m, c, s, e, tol2, forced, stack);
		drop_redundant(m, c, s, e, tol2, 0, forced);
		return 0;
	}
	size_t len = e - s;
	if (len <= 3) {
		memset(c->keep + s, 1, len + 1);
		return 0;
	}
	if (c->closed[ci] == 2) {
		/* A loop: start at the point farthest from its centroid. */
		double g[3] = { 0, 0, 0 };
		for (size_t x = s; x < e; x++)
			fct_v3_add(g, g, pt(m, c, x));
		for (int k = 0; k < 3; k++)
			g[k] /= (double)len;
		size_t best = s;
		double bd = -1;
		for (size_t x = s; x < e; x++) {
			double d = fct_v3_dist2(pt(m, c, x), g);
			if (d > bd)
				bd = d, best = x;
		}
		if (rotate_loop(c, s, e, best, err))
			return -1;
	}
	/* Split at the point farthest from the start. */
	size_t mid = s + 1;
	double md = -1;
	for (size_t x = s + 1; x < e; x++) {
		double d = fct_v3_dist2(pt(m, c, x), pt(m, c, s));
		if (d > md)
			md = d, mid = x;
	}
	c->keep[mid] = 1;
	fit_between_kept(m, c, s, e, tol2, forced, stack);
	size_t kept = 0;
	for (size_t x = s; x < e; x++)
		kept += c->keep[x];
	if (kept < 3) {
		/* Only the two anchors: keep the point farthest from the segment
		 * between them as well. */
		double d1, d2;
		size_t k1 = mid - s >= 2 ? farthest(m, c, s, mid, &d1) : 0;
		size_t k2 = e - mid >= 2 ? farthest(m, c, mid, e, &d2) : 0;
		if (mid - s < 2)
			d1 = -1;
		if (e - mid < 2)
			d2 = -1;
		/* Distances to the same segment s-mid: farthest() on mid..e measures
		 * from segment mid-e, which is the same segment reversed. */
		/* The new point shortens a segment: refit its two halves so every
		 * point stays within the tolerance. */
		size_t k = d1 >= d2 ? k1 : k2, lo = d1 >= d2 ? s : mid, hi = d1 >= d2 ? mid : e;
		c->keep[k] = 1;
		st->loop_points++;
		endpoint_fit(m, c, lo, k, tol2, stack);
		endpoint_fit(m, c, k, hi, tol2, stack);
	}
	drop_redundant(m, c, s, e, tol2, 3, forced);
	return 0;
}

/* Crossing checks ---------------------------------------------------------- */

/* A static tree of 2-D boxes (median splits along the wider side), to find
 * the items whose boxes meet a query box in O(log n + answers) however
 * unevenly the items lie.  Boxes are exact minima and maxima of the
 * coordinates, so two closed segments that meet always have meeting boxes:
 * no padding is needed. */
struct box_node {
	double b[4];              /* xmin ymin xmax ymax */
	uint32_t lo, hi;          /* items idx[lo .. hi) */
	uint32_t left;            /* children left, left + 1; 0 for a leaf */
};

struct box_tree {
	double *box;              /* 4 per item, filled by the caller */
	uint32_t *idx;
	struct box_node *node;
	size_t n, nnode;
	size_t cap_box, cap_idx, cap_node;
};

#define BOX_LEAF 8

static int box_tree_reserve(struct box_tree *t, struct fct_arena *a, size_t n, struct fct_err *err)
{
	t->n = n;
	return fct_arena_grow(a, (void **)&t->box, &t->cap_box, 4 * (n ? n : 1), sizeof *t->box, err) ||
	       fct_arena_grow(a, (void **)&t->idx, &t->cap_idx, n ? n : 1, sizeof *t->idx, err) ||
	       fct_arena_grow(a, (void **)&t->node, &t->cap_node, 2 * (n / (BOX_LEAF / 2) + 1),
	                      sizeof *t->node, err)
	       ? -1 : 0;
}

/* Centre of item i along axis a, twice (no rounding), ties by index. */
static int box_before(const struct box_tree *t, uint32_t i, uint32_t j, int a)
{
	double ci = t->box[4 * (size_t)i + (size_t)a] + t->box[4 * (size_t)i + 2 + (size_t)a];
	double cj = t->box[4 * (size_t)j + (size_t)a] + t->box[4 * (size_t)j + 2 + (size_t)a];
	return ci < cj || (ci == cj && i < j);
}

/* Put the items of idx[lo .. hi) that come before the median first
 * (quickselect, median-of-three pivots). */
static void box_select(struct box_tree *t, uint32_t lo, uint32_t hi, uint32_t mid, int a)
{
	uint32_t *x = t->idx;
	while (hi - lo > 2) {
		uint32_t m = lo + (hi - lo) / 2, l = hi - 1;
		if (box_before(t, x[m], x[lo], a)) { uint32_t q = x[m]; x[m] = x[lo]; x[lo] = q; }
		if (box_before(t, x[l], x[lo], a)) { uint32_t q = x[l]; x[l] = x[lo]; x[lo] = q; }
		if (box_before(t, x[l], x[m], a)) { uint32_t q = x[l]; x[l] = x[m]; x[m] = q; }
		uint32_t pivot = x[m];
		uint32_t i = lo, j = hi - 1;
		for (;;) {
			while (box_before(t, x[i], pivot, a))
				i++;
			while (box_before(t, pivot, x[j], a))
				j--;
			if (i >= j)
				break;
			uint32_t q = x[i]; x[i] = x[j]; x[j] = q;
			i++, j--;
		}
		/* x[lo .. j] <= pivot <= x[j + 1 .. hi) */
		if (mid <= j)
			hi = j + 1;
		else
			lo = j + 1;
	}
	if (hi - lo == 2 && box_before(t, x[lo + 1], x[lo], a)) {
		uint32_t q = x[lo]; x[lo] = x[lo + 1]; x[lo + 1] = q;
	}
}

static void box_tree_build(struct box_tree *t)
{
	for (size_t i = 0; i < t->n; i++)
		t->idx[i] = (uint32_t)i;
	t->nnode = 1;
	t->node[0].lo = 0, t->node[0].hi = (uint32_t)t->n;
	/* Nodes are made in breadth-first order: node k's children come after it. */
	for (size_t k = 0; k < t->nnode; k++) {
		struct box_node *nd = &t->node[k];
		double b[4] = { HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
		for (uint32_t i = nd->lo; i < nd->hi; i++) {
			const double *q = t->box + 4 * (size_t)t->idx[i];
			b[0] = q[0] < b[0] ? q[0] : b[0], b[1] = q[1] < b[1] ? q[1] : b[1];
			b[2] = q[2] > b[2] ? q[2] : b[2], b[3] = q[3] > b[3] ? q[3] : b[3];
		}
		memcpy(nd->b, b, sizeof b);
		nd->left = 0;
		if (nd->hi - nd->lo <= BOX_LEAF)
			continue;
		uint32_t lo = nd->lo, hi = nd->hi, mid = lo + (hi - lo) / 2;
		box_select(t, lo, hi, mid, b[2] - b[0] >= b[3] - b[1] ? 0 : 1);
		nd->left = (uint32_t)t->nnode;
		t->node[t->nnode].lo = lo, t->node[t->nnode++].hi = mid;
		t->node[t->nnode].lo = mid, t->node[t->nnode++].hi = hi;
	}
}

static int box_meet(const double *a, const double *b)
{
	return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

/* Call fn(ctx, item) for every item whose box meets q; stops early when fn
 * returns non-zero. */
static void box_tree_query(const struct box_tree *t, const double q[4],
                           int (*fn)(void *ctx, uint32_t item), void *ctx)
{
	uint32_t stack[128];
	int n = 0;
	if (!t->n)
		return;
	stack[n++] = 0;
	while (n) {
		const struct box_node *nd = &t->node[stack[--n]];
		if (!box_meet(nd->b, q))
			continue;
		if (nd->left) {
			if (n + 2 > 128)
				abort();    /* median splits: depth is at most log2(n) */
			stack[n++] = nd->left + 1;
			stack[n++] = nd->left;
			continue;
		}
		for (uint32_t i = nd->lo; i < nd->hi; i++)
			if (box_meet(t->box + 4 * (size_t)t->idx[i], q) && fn(ctx, t->idx[i]))
				return;
	}
}

static int sgn(double x)
{
	return (x > 0) - (x < 0);
}

/* c on closed segment ab, given collinear. */
static int on_segment(const double *a, const double *b, const double *c)
{
	return (a[0] <= c[0]) == (c[0] <= b[0]) && (a[1] <= c[1]) == (c[1] <= b[1]) &&
	       ((a[0] <= c[0] && c[0] <= b[0]) || (b[0] <= c[0] && c[0] <= a[0])) &&
	       ((a[1] <= c[1] && c[1] <= b[1]) || (b[1] <= c[1] && c[1] <= a[1]));
}

int fct_segments_conflict(const double a[2], const double b[2], const double c[2],
                          const double d[2], uint32_t va, uint32_t vb, uint32_t vc, uint32_t vd)
{
	int ac = va == vc, ad = va == vd, bc = vb == vc, bd = vb == vd;
	if ((ac && bd) || (ad && bc))
		return 1;
	if (ac || ad || bc || bd) {
		/* Shared vertex o; the others p (of ab) and q (of cd) must not lie
		 * on one ray from o. */
		const double *o = ac || ad ? a : b, *p = ac || ad ? b : a, *q = ac || bc ? d : c;
		if (fct_orient2d(o, p, q) != 0)
			return 0;
		return sgn(p[0] - o[0]) == sgn(q[0] - o[0]) && sgn(p[1] - o[1]) == sgn(q[1] - o[1]);
	}
	int o1 = sgn(fct_orient2d(a, b, c)), o2 = sgn(fct_orient2d(a, b, d));
	int o3 = sgn(fct_orient2d(c, d, a)), o4 = sgn(fct_orient2d(c, d, b));
	if (o1 * o2 < 0 && o3 * o4 < 0)
		return 1;
	return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
	       (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

/* Squared distance from p to segment ab in 2-D (floating point). */
static double seg_dist2(const double *p, const double *a, const double *b)
{
	double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
	double t = len2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0;
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
	return ex * ex + ey * ey;
}

/* Is q strictly inside the closed polygon p[0..n) by the even-odd rule (exact
 * predicates; points on its edges may go either way)? */
static int inside_polygon(const double *p, size_t n, const double *q)
{
	int in = 0;
	for (size_t k = 0; k < n; k++) {
		const double *u = p + 2 * k, *w = p + 2 * ((k + 1) % n);
		if ((u[1] > q[1]) != (w[1] > q[1])) {
			double o = fct_orient2d(u, w, q);
			if (w[1] > u[1] ? o > 0 : o < 0)
				in ^= 1;
		}
	}
	return in;
}

/* A segment of a patch's boundary: chain positions i -> j (j = i + 1 for an
 * original mesh edge). */
struct seg {
	uint32_t chain;   /* index into the patch's chain list */
	size_t i, j;
};

/* Working memory of the checks, reused from patch to patch; every array
 * is the arena's. */
struct checker {
	struct fct_arena arena;
	const struct fct_mesh *m;
	struct fct_chains *c;
	const int32_t *lab;       /* the patches' labels, increasing; patch p is lab[p] */
	size_t np;
	size_t *pchain_start;     /* patch -> chains CSR */
	uint32_t *pchain;
	const uint32_t *list;     /* the chains of the patch being checked */
	size_t nlist;
	double (*normal)[3];
	double *xy;               /* 2-D points of the patch's chains, local index */
	size_t *base;             /* local index of each listed chain's first point */
	struct seg *seg;
	size_t nseg;
	uint32_t *pts;            /* kept points: local index */
	unsigned char *mark;      /* per segment: split it */
	uint32_t *fpre;           /* prefix counts of crossing original edges by the
	                             local index of their first point */
	uint32_t *flist;          /* the local indices of those edges, increasing */
	size_t nflist;
	uint32_t **fpre_of, **flist_of;   /* fpre and flist of each check, kept from
	                                     round to round (the input does not change) */
	size_t *nflist_of;
	double **xy_of;           /* xy of each check, likewise */
	struct fct_chain_cache *cache;   /* the last simplification's, or NULL */
	size_t cached_checks;     /* checks that took their input crossings from it */
	size_t cap_base, cap_seg, cap_pts, cap_mark;
	struct box_tree sg, pg;      /* segments, kept points */
	unsigned char *split;     /* per chain position: split the segment starting here */
	unsigned char *chain_dirty;
	unsigned char *chain_new; /* chains split in the last round */
	unsigned char *checked;   /* per check: done once (later rounds test only
	                             the pairs with a new segment) */
	unsigned char *dirty;     /* per check: due this round */
	size_t *unresolved;       /* per check: its conflicts inherited from the input */
	size_t nchecks;           /* 2 np + 2 (see plan_checks) */
	const struct fct_prop *ps, *pt;   /* image coordinates, or NULL */
	double W, H;              /* the camera's image size (1 without a camera) */
	int wrap;                 /* s wraps round (a cylindrical panorama) */
};

static size_t local_of(const struct checker *k, uint32_t chain, size_t pos)
{
	return k->base[chain] + (pos - k->c->start[k->list[chain]]);
}

static const double *lxy(const struct checker *k, const struct seg *s, size_t pos)
{
	return k->xy + 2 * local_of(k, s->chain, pos);
}

static int seg_pair_conflict(const struct checker *k, const struct seg *a, const struct seg *b)
{
	const uint32_t *v = k->c->vert;
	if (v[a->i] == v[a->j] || v[b->i] == v[b->j])
		return 0;
	return fct_segments_conflict(lxy(k, a, a->i), lxy(k, a, a->j), lxy(k, b, b->i), lxy(k, b, b->j),
	                             v[a->i], v[a->j], v[b->i], v[b->j]);
}

/* The crossing original edges within segment s's span: flist[*lo .. *hi). */
static void flagged_range(const struct checker *k, const struct seg *s, size_t *lo, size_t *hi)
{
	size_t a = local_of(k, s->chain, s->i), b = local_of(k, s->chain, s->j);
	*lo = k->fpre[a], *hi = k->fpre[b];
}

/* Does the input already conflict between the spans of a and b: some
 * crossing original edge of one against one of the other?  Past a
 * budget of tests, assume so. */
static int inherited(const struct checker *k, const struct seg *a, const struct seg *b)
{
	size_t a0, a1, b0, b1;
	flagged_range(k, a, &a0, &a1);
	flagged_range(k, b, &b0, &b1);
	if (a0 == a1 || b0 == b1)
		return 0;
	if ((a1 - a0) * (b1 - b0) > 4096)
		return 1;
	for (size_t x = a0; x < a1; x++)
		for (size_t y = b0; y < b1; y++) {
			/* Local index to chain position: find the listed chain. */
			struct seg e[2];
			size_t l[2] = { k->flist[x], k->flist[y] };
			for (int z = 0; z < 2; z++) {
				size_t lo = 0, hi = k->nlist;
				while (hi - lo > 1) {
					size_t mid = (lo + hi) / 2;
					if (k->base[mid] <= l[z])
						lo = mid;
					else
						hi = mid;
				}
				e[z].chain = (uint32_t)lo;
				e[z].i = k->c->start[k->list[lo]] + (l[z] - k->base[lo]);
				e[z].j = e[z].i + 1;
			}
			if (seg_pair_conflict(k, &e[0], &e[1]))
				return 1;
		}
	return 0;
}

struct pair_ctx {
	struct checker *k;
	size_t s;                 /* the segment being tested */
	int original;             /* the segments are original edges: flag them */
	int all;                  /* test every pair, not only those with a new segment */
	size_t conflicts, unresolved;
};

static int test_pair(void *ctx, uint32_t t)
{
	struct pair_ctx *pc = ctx;
	struct checker *k = pc->k;
	size_t s = pc->s;
	if (t == s)
		return 0;
	/* A pair of two new segments (or any pair when testing all) is tested
	 * from its lower one; a new against an old one from the new. */
	int tnew = pc->all || k->chain_new[k->list[k->seg[t].chain]];
	if (tnew && t < s)
		return 0;
	const struct seg *a = &k->seg[s], *b = &k->seg[t];
	if (!seg_pair_conflict(k, a, b))
		return 0;
	if (pc->original) {
		/* Flag both edges (fpre holds flags until made prefix counts). */
		k->fpre[local_of(k, a->chain, a->i) + 1] = 1;
		k->fpre[local_of(k, b->chain, b->i) + 1] = 1;
		return 0;
	}
	pc->conflicts++;
	if (inherited(k, a, b)) {
		pc->unresolved++;
		return 0;
	}
	k->mark[s] = 1;
	k->mark[t] = 1;
	return 0;
}

/* Put k->seg[0..nseg) into the box tree and test the pairs whose boxes
 * meet. */
static int find_pairs(struct checker *k, struct pair_ctx *pc, struct fct_err *err)
{
	size_t n = k->nseg;
	struct box_tree *t = &k->sg;
	if (box_tree_reserve(t, &k->arena, n, err))
		return -1;
	for (size_t s = 0; s < n; s++) {
		const double *a = lxy(k, &k->seg[s], k->seg[s].i), *b = lxy(k, &k->seg[s], k->seg[s].j);
		double *q = t->box + 4 * s;
		q[0] = a[0] < b[0] ? a[0] : b[0], q[2] = a[0] < b[0] ? b[0] : a[0];
		q[1] = a[1] < b[1] ? a[1] : b[1], q[3] = a[1] < b[1] ? b[1] : a[1];
	}
	box_tree_build(t);
	for (size_t s = 0; s < n; s++) {
		if (!pc->all && !k->chain_new[k->list[k->seg[s].chain]])
			continue;
		pc->s = s;
		double q[4];
		memcpy(q, t->box + 4 * s, sizeof q);
		box_tree_query(t, q, test_pair, pc);
	}
	return 0;
}

struct sliver_ctx {
	struct checker *k;
	const double *P, *A, *B;  /* the span's points, the segment's ends */
	size_t n;
	double dev2;
	uint32_t va, vb;          /* the segment's vertices */
	int inside;
};

/* Is kept point q strictly inside the sliver (and not an end of it)? */
static int sliver_point(void *ctx, uint32_t q)
{
	struct sliver_ctx *sc = ctx;
	struct checker *k = sc->k;
	const struct fct_chains *c = k->c;
	uint32_t lq = k->pts[q];
	const double *o = k->xy + 2 * (size_t)lq;
	if (seg_dist2(o, sc->A, sc->B) > sc->dev2)
		return 0;
	size_t lo = 0, hi = k->nlist;
	while (hi - lo > 1) {
		size_t mid = (lo + hi) / 2;
		if (k->base[mid] <= lq)
			lo = mid;
		else
			hi = mid;
	}
	uint32_t vq = c->vert[c->start[k->list[lo]] + (lq - k->base[lo])];
	if (vq == sc->va || vq == sc->vb || !inside_polygon(sc->P, sc->n, o))
		return 0;
	sc->inside = 1;
	return 1;
}

/* A kept point strictly inside the sliver between a simplified segment and
 * the points it replaces would change sides of that boundary: mark the
 * segment.  Segments whose span holds crossing original edges are left
 * alone (the input is already tangled there). */
static int sliver_checks(struct checker *k, struct pair_ctx *pc, size_t nkept,
                         struct fct_err *err)
{
	const struct fct_chains *c = k->c;
	struct box_tree *t = &k->pg;
	if (box_tree_reserve(t, &k->arena, nkept, err))
		return -1;
	for (size_t q = 0; q < nkept; q++) {
		const double *o = k->xy + 2 * (size_t)k->pts[q];
		double *b = t->box + 4 * q;
		b[0] = b[2] = o[0], b[1] = b[3] = o[1];
	}
	box_tree_build(t);
	struct sliver_ctx sc = { k, NULL, NULL, NULL, 0, 0, 0, 0, 0 };
	for (size_t s = 0; s < k->nseg; s++) {
		const struct seg *sg = &k->seg[s];
		size_t f0, f1;
		flagged_range(k, sg, &f0, &f1);
		if (sg->j - sg->i < 2 || k->mark[s] || f0 != f1)
			continue;
		const double *P = lxy(k, sg, sg->i);
		size_t n = sg->j - sg->i + 1;
		const double *A = P, *B = P + 2 * (n - 1);
		double q[4] = { HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL }, dev2 = 0;
		for (size_t x = 0; x < n; x++) {
			const double *o = P + 2 * x;
			q[0] = o[0] < q[0] ? o[0] : q[0], q[2] = o[0] > q[2] ? o[0] : q[2];
			q[1] = o[1] < q[1] ? o[1] : q[1], q[3] = o[1] > q[3] ? o[1] : q[3];
			double d = seg_dist2(o, A, B);
			dev2 = d > dev2 ? d : dev2;
		}
		/* The sliver lies in the hull of its points, so within sqrt(dev2) of
		 * the segment: a cheap, generously rounded filter before the exact
		 * parity test. */
		sc.P = P, sc.A = A, sc.B = B, sc.n = n;
		sc.dev2 = dev2 * (1 + 1e-6) + 1e-300;
		sc.va = c->vert[sg->i], sc.vb = c->vert[sg->j];
		sc.inside = 0;
		box_tree_query(t, q, sliver_point, &sc);
		if (sc.inside) {
			k->mark[s] = 1;
			pc->conflicts++;
		}
	}
	return 0;
}

/* The listed chains' points into k->xy: in patch p's plane (image 0) or
 * in image coordinates (image 1). */
static void project_chains(struct checker *k, size_t p, int image)
{
	const struct fct_chains *c = k->c;
	double u[3] = { 1, 0, 0 }, w[3] = { 0, 1, 0 }, ref = HUGE_VAL;
	if (!image)
		fct_plane_frame(k->normal[p], u, w);
	for (size_t x = 0; x < k->nlist; x++) {
		size_t ci = k->list[x];
		size_t s = c->start[ci], e = c->start[ci + 1];
		for (size_t q = s; q < e; q++) {
			double *o = k->xy + 2 * (k->base[x] + (q - s));
			if (image) {
				o[0] = k->W == 1 ? fct_prop_get(k->ps, c->vert[q]) : fct_snap_pixel_centre(fct_prop_get(k->ps, c->vert[q]) * k->W);
				o[1] = k->H == 1 ? fct_prop_get(k->pt, c->vert[q]) : fct_snap_pixel_centre(fct_prop_get(k->pt, c->vert[q]) * k->H);
				if (k->wrap) {
					/* Unwrap s to within half a turn of the patch's
					 * first point. */
					if (ref == HUGE_VAL)
						ref = o[0];
					o[0] -= k->W * floor((o[0] - ref) / k->W + 0.5);
				}
			} else {
				const double *P = pt(k->m, c, q);
				o[0] = fct_v3_dot(P, u), o[1] = fct_v3_dot(P, w);
			}
		}
	}
}

/* A check of the last simplification (fct_chain_cache): the crossing
 * original edges of its chains, which are a function of the chains' points
 * and vertices alone. */
struct fct_cached_check {
	int32_t label;     /* the patch's, or GLOBAL_CHECK */
	int image;
	size_t nlist, npt, nflist;
	uint32_t *len;     /* each listed chain's points */
	uint32_t *vert;    /* their vertices (npt) */
	double *xy;        /* and 2-D points (2 npt) */
	uint32_t *fpre;    /* the check's fpre (npt + 1) and flist */
	uint32_t *flist;
};

#define GLOBAL_CHECK INT32_MIN

static int32_t check_label(const struct checker *k, size_t v)
{
	return v / 2 < k->np ? k->lab[v / 2] : GLOBAL_CHECK;
}

/* Is cached check e one of the same chains, vertices and points as check
 * v now (k->list, k->base, k->xy)? */
static int same_check(const struct checker *k, const struct fct_cached_check *e, size_t v,
                      size_t npt)
{
	const struct fct_chains *c = k->c;
	if (e->label != check_label(k, v) || e->image != (int)(v % 2) || e->nlist != k->nlist ||
	    e->npt != npt)
		return 0;
	for (size_t x = 0, at = 0; x < k->nlist; x++) {
		size_t ci = k->list[x], n = c->start[ci + 1] - c->start[ci];
		if (e->len[x] != n || memcmp(e->vert + at, c->vert + c->start[ci], n * sizeof *e->vert))
			return 0;
		at += n;
	}
	return !memcmp(e->xy, k->xy, 2 * npt * sizeof *e->xy);
}

/* Check v's crossing original edges (fpre_of, flist_of) from the cache
 * when it holds the same check: 1, else 0; -1 out of memory. */
static int cached_crossings(struct checker *k, size_t v, size_t npt, struct fct_err *err)
{
	const struct fct_chain_cache *cache = k->cache;
	for (size_t i = 0; cache && i < cache->n; i++) {
		const struct fct_cached_check *e = &cache->check[i];
		if (!same_check(k, e, v, npt))
			continue;
		if (!(k->flist_of[v] = fct_arena_array(&k->arena, e->nflist ? e->nflist : 1,
		                                       sizeof *k->flist, err)))
			return -1;
		memcpy(k->fpre_of[v], e->fpre, (npt + 1) * sizeof *e->fpre);
		memcpy(k->flist_of[v], e->flist, e->nflist * sizeof *e->flist);
		k->nflist_of[v] = e->nflist;
		k->cached_checks++;
		return 1;
	}
	return 0;
}

static void cached_check_free(struct fct_cached_check *e)
{
	free(e->len), free(e->vert), free(e->xy), free(e->fpre), free(e->flist);
}

void fct_chain_cache_free(struct fct_chain_cache *cache)
{
	if (!cache)
		return;
	for (size_t i = 0; i < cache->n; i++)
		cached_check_free(&cache->check[i]);
	free(cache->check);
	memset(cache, 0, sizeof *cache);
}

/* The cache replaced by this simplification's checks (those made). */
static int save_checks(struct checker *k, struct fct_err *err)
{
	const struct fct_chains *c = k->c;
	size_t n = 0;
	for (size_t v = 0; v < k->nchecks; v++)
		n += k->fpre_of[v] != NULL;
	struct fct_cached_check *check = calloc(n ? n : 1, sizeof *check);
	if (!check)
		return fct_fail(err, "out of memory");
	size_t i = 0;
	for (size_t v = 0; v < k->nchecks; v++) {
		if (!k->fpre_of[v])
			continue;
		struct fct_cached_check *e = &check[i++];
		size_t p = v / 2, c0 = k->pchain_start[p], nc = k->pchain_start[p + 1] - c0, npt = 0;
		for (size_t x = 0; x < nc; x++)
			npt += c->start[k->pchain[c0 + x] + 1] - c->start[k->pchain[c0 + x]];
		e->label = check_label(k, v), e->image = (int)(v % 2);
		e->nlist = nc, e->npt = npt, e->nflist = k->nflist_of[v];
		e->len = malloc((nc ? nc : 1) * sizeof *e->len);
		e->vert = malloc((npt ? npt : 1) * sizeof *e->vert);
		e->xy = malloc(2 * (npt ? npt : 1) * sizeof *e->xy);
		e->fpre = malloc((npt + 1) * sizeof *e->fpre);
		e->flist = malloc((e->nflist ? e->nflist : 1) * sizeof *e->flist);
		if (!e->len || !e->vert || !e->xy || !e->fpre || !e->flist) {
			for (size_t j = 0; j < i; j++)
				cached_check_free(&check[j]);
			free(check);
			return fct_fail(err, "out of memory");
		}
		for (size_t x = 0, at = 0; x < nc; x++) {
			size_t ci = k->pchain[c0 + x], len = c->start[ci + 1] - c->start[ci];
			e->len[x] = (uint32_t)len;
			memcpy(e->vert + at, c->vert + c->start[ci], len * sizeof *e->vert);
			at += len;
		}
		memcpy(e->xy, k->xy_of[v], 2 * npt * sizeof *e->xy);
		memcpy(e->fpre, k->fpre_of[v], (npt + 1) * sizeof *e->fpre);
		memcpy(e->flist, k->flist_of[v], e->nflist * sizeof *e->flist);
	}
	fct_chain_cache_free(k->cache);
	k->cache->check = check, k->cache->n = n;
	return 0;
}

/* Check patch p's simplified chains in its plane (image 0) or in image
 * coordinates (image 1); mark the segments to split in k->split and their
 * chains in k->chain_dirty.  Adds the conflicts found, and those inherited
 * from the input (not pursued), to *conflicts and *unresolved.  -1 when out
 * of memory. */
static int check_patch(struct checker *k, size_t v, int count_only, size_t *conflicts,
                       size_t *unresolved, struct fct_err *err)
{
	size_t p = v / 2;
	int image = (int)(v % 2);
	const struct fct_chains *c = k->c;
	size_t c0 = k->pchain_start[p], nc = k->pchain_start[p + 1] - c0;
	k->list = k->pchain + c0, k->nlist = nc;
	if (fct_arena_grow(&k->arena, (void **)&k->base, &k->cap_base, nc + 1, sizeof *k->base, err))
		return -1;
	size_t npt = 0, nkept = 0;
	for (size_t x = 0; x < nc; x++) {
		size_t ci = k->list[x];
		k->base[x] = npt;
		npt += c->start[ci + 1] - c->start[ci];
	}
	k->base[nc] = npt;
	struct fct_arena *a = &k->arena;
	if (fct_arena_grow(a, (void **)&k->seg, &k->cap_seg, npt ? npt : 1, sizeof *k->seg, err) ||
	    fct_arena_grow(a, (void **)&k->pts, &k->cap_pts, npt ? npt : 1, sizeof *k->pts, err) ||
	    fct_arena_grow(a, (void **)&k->mark, &k->cap_mark, npt ? npt : 1, sizeof *k->mark, err))
		return -1;
	/* The first check of v projects its chains and finds the crossing
	 * original edges (or takes them from the cache); later ones reuse
	 * both. */
	int first = !k->fpre_of[v];
	if (first && (!(k->fpre_of[v] = fct_arena_zeroed(a, npt + 1, sizeof *k->fpre, err)) ||
	              !(k->xy_of[v] = fct_arena_array(a, 2 * (npt ? npt : 1), sizeof *k->xy, err))))
		return -1;
	k->fpre = k->fpre_of[v];
	k->xy = k->xy_of[v];
	if (first)
		project_chains(k, p, image);
	int cached = first ? cached_crossings(k, v, npt, err) : 0;
	if (cached < 0)
		return -1;

	/* The original edges that already conflict in this map, found on the
	 * first check. */
	struct pair_ctx pc = { k, 0, 1, 1, 0, 0 };
	if (first && !cached) {
		k->nseg = 0;
		for (size_t x = 0; x < nc; x++) {
			size_t ci = k->list[x];
			for (size_t q = c->start[ci] + 1; q < c->start[ci + 1]; q++) {
				struct seg *g = &k->seg[k->nseg++];
				g->chain = (uint32_t)x, g->i = q - 1, g->j = q;
			}
		}
		if (find_pairs(k, &pc, err))
			return -1;
		size_t nf = 0;
		for (size_t l = 0; l < npt; l++)
			nf += k->fpre[l + 1];
		if (!(k->flist_of[v] = fct_arena_array(a, nf, sizeof *k->flist, err)))
			return -1;
		nf = 0;
		for (size_t l = 0; l < npt; l++) {
			if (k->fpre[l + 1])
				k->flist_of[v][nf++] = (uint32_t)l;
			k->fpre[l + 1] = (uint32_t)nf;
		}
		k->nflist_of[v] = nf;
	}
	k->flist = k->flist_of[v], k->nflist = k->nflist_of[v];

	/* The simplified segments and kept points. */
	k->nseg = 0;
	for (size_t x = 0; x < nc; x++) {
		size_t ci = k->list[x];
		size_t s = c->start[ci], e = c->start[ci + 1], last = s;
		for (size_t q = s; q < e; q++) {
			if (!c->keep[q])
				continue;
			if (!(c->closed[ci] && q == e - 1))
				k->pts[nkept++] = (uint32_t)(k->base[x] + (q - s));
			if (q > s) {
				struct seg *g = &k->seg[k->nseg++];
				g->chain = (uint32_t)x, g->i = last, g->j = q;
			}
			last = q;
		}
	}
	memset(k->mark, 0, k->nseg);
	pc.original = 0;
	pc.all = count_only || !k->checked[v];
	k->checked[v] = 1;
	if (find_pairs(k, &pc, err))
		return -1;
	if (count_only) {
		*unresolved += pc.unresolved;
		return 0;
	}
	if (sliver_checks(k, &pc, nkept, err))
		return -1;
	for (size_t s = 0; s < k->nseg; s++)
		if (k->mark[s]) {
			k->split[k->seg[s].i] = 1;
			k->chain_dirty[k->list[k->seg[s].chain]] = 1;
		}
	*conflicts += pc.conflicts;
	*unresolved += pc.unresolved;
	return 0;
}

static int label_cmp(const void *pa, const void *pb)
{
	int32_t a = *(const int32_t *)pa, b = *(const int32_t *)pb;
	return (a > b) - (a < b);
}

static long label_id(const int32_t *lab, size_t n, int32_t x)
{
	const int32_t *f = bsearch(&x, lab, n, sizeof *lab, label_cmp);
	return f ? (long)(f - lab) : -1;
}

/* The distinct labels on the chains' sides into lab (2 n entries),
 * increasing; returns their count. */
static size_t side_labels(int32_t *lab, const struct fct_chains *c)
{
	size_t n = 0;
	for (size_t i = 0; i < c->n; i++) {
		lab[n++] = c->left[i];
		if (c->right[i] >= 0)
			lab[n++] = c->right[i];
	}
	qsort(lab, n, sizeof *lab, label_cmp);
	size_t u = 0;
	for (size_t i = 0; i < n; i++)
		if (!u || lab[i] != lab[u - 1])
			lab[u++] = lab[i];
	return u;
}

/* The chains of each patch, CSR (k->pchain_start, k->pchain); the extra
 * list np holds every chain (the global image check). */
static int chains_by_patch(struct checker *k, struct fct_err *err)
{
	const struct fct_chains *c = k->c;
	size_t np = k->np;
	size_t *start = fct_arena_zeroed(&k->arena, np + 2, sizeof *start, err);
	uint32_t *list = fct_arena_array(&k->arena, 3 * c->n, sizeof *list, err);
	size_t *fill = fct_arena_zeroed(&k->arena, np ? np : 1, sizeof *fill, err);
	if (!start || !list || !fill)
		return -1;
	for (size_t i = 0; i < c->n; i++) {
		start[label_id(k->lab, np, c->left[i]) + 1]++;
		if (c->right[i] >= 0)
			start[label_id(k->lab, np, c->right[i]) + 1]++;
	}
	start[np + 1] = c->n;
	for (size_t i = 0; i < np + 1; i++)
		start[i + 1] += start[i];
	for (size_t i = 0; i < c->n; i++)
		list[start[np] + i] = (uint32_t)i;
	for (size_t i = 0; i < c->n; i++) {
		long a = label_id(k->lab, np, c->left[i]);
		list[start[a] + fill[a]++] = (uint32_t)i;
		if (c->right[i] >= 0) {
			long b = label_id(k->lab, np, c->right[i]);
			list[start[b] + fill[b]++] = (uint32_t)i;
		}
	}
	k->pchain_start = start, k->pchain = list;
	return 0;
}

/* Each patch's unit normal, the plane its boundary is checked in: the
 * plane's, or the faces' area-weighted (Newell) normal for a patch without
 * one; +z when that vanishes. */
static int patch_normals(struct checker *k, const int32_t *patch, const struct fct_plane *planes,
                         size_t nplanes, struct fct_err *err)
{
	const struct fct_mesh *m = k->m;
	const int32_t *lab = k->lab;
	size_t np = k->np;
	double (*normal)[3] = fct_arena_zeroed(&k->arena, np + 1, sizeof *normal, err);
	if (!normal)
		return -1;
	int need = 0;
	for (size_t i = 0; i < np; i++) {
		if ((size_t)lab[i] < nplanes)
			memcpy(normal[i], planes[lab[i]].n, sizeof normal[i]);
		else
			need = 1;
	}
	if (need)
		for (size_t f = 0; f < m->nf; f++) {
			if (patch[f] < 0 || (size_t)patch[f] < nplanes)
				continue;
			long id = label_id(lab, np, patch[f]);
			if (id < 0)
				continue;
			for (uint32_t x = m->fstart[f]; x < m->fstart[f + 1]; x++) {
				uint32_t y = x + 1 < m->fstart[f + 1] ? x + 1 : m->fstart[f];
				const double *a = m->xyz + 3 * (size_t)m->fvert[x], *b = m->xyz + 3 * (size_t)m->fvert[y];
				normal[id][0] += (a[1] - b[1]) * (a[2] + b[2]);
				normal[id][1] += (a[2] - b[2]) * (a[0] + b[0]);
				normal[id][2] += (a[0] - b[0]) * (a[1] + b[1]);
			}
		}
	for (size_t i = 0; i < np; i++) {
		double l = sqrt(fct_v3_dot(normal[i], normal[i]));
		if (!(l > 0) || !isfinite(l)) {
			normal[i][0] = normal[i][1] = 0, normal[i][2] = 1;
			continue;
		}
		for (int x = 0; x < 3; x++)
			normal[i][x] /= l;
	}
	k->normal = normal;
	return 0;
}

/* The checks and what each needs.  Each patch is checked in its plane
 * (check 2 p), and when the vertices carry image coordinates, the whole
 * boundary in the image (check 2 np + 1): one view's image is a planar map
 * of all its surfaces, so there no chains may cross whatever patches they
 * bound, and a hole or an unlabelled region may not collapse either.  A
 * cylindrical panorama's s wraps round; it is unwrapped patch by patch
 * (checks 2 p + 1) instead.  All of them are due in the first round. */
static int plan_checks(struct checker *k, struct fct_err *err)
{
	const struct fct_mesh *m = k->m;
	size_t np = k->np, nv2 = 2 * np + 2;
	struct fct_arena *a = &k->arena;
	size_t total = k->c->start[k->c->n], nc = k->c->n ? k->c->n : 1;
	k->ps = fct_elem_find(&m->vertex, "s"), k->pt = fct_elem_find(&m->vertex, "t");
	if (!k->ps || !k->pt || k->ps->count_type || k->pt->count_type)
		k->ps = k->pt = NULL;
	struct fct_camera cam;
	int have_cam = fct_header_camera(m, &cam, NULL) == 1 && cam.width > 0 && cam.height > 0;
	k->wrap = have_cam && cam.kind == FCT_CAMERA_CYLINDRICAL;
	k->W = have_cam ? cam.width : 1, k->H = have_cam ? cam.height : 1;
	k->nchecks = nv2;
	k->split = fct_arena_zeroed(a, total ? total : 1, 1, err);
	k->chain_dirty = fct_arena_zeroed(a, nc, 1, err);
	k->chain_new = fct_arena_zeroed(a, nc, 1, err);
	k->dirty = fct_arena_zeroed(a, nv2, 1, err);
	k->unresolved = fct_arena_zeroed(a, nv2, sizeof *k->unresolved, err);
	k->checked = fct_arena_zeroed(a, nv2, 1, err);
	k->fpre_of = fct_arena_zeroed(a, nv2, sizeof *k->fpre_of, err);
	k->flist_of = fct_arena_zeroed(a, nv2, sizeof *k->flist_of, err);
	k->nflist_of = fct_arena_zeroed(a, nv2, sizeof *k->nflist_of, err);
	k->xy_of = fct_arena_zeroed(a, nv2, sizeof *k->xy_of, err);
	if (!k->split || !k->chain_dirty || !k->chain_new || !k->dirty || !k->unresolved ||
	    !k->checked || !k->fpre_of || !k->flist_of || !k->nflist_of || !k->xy_of)
		return -1;
	for (size_t p = 0; p < np; p++)
		k->dirty[2 * p] = 1, k->dirty[2 * p + 1] = k->ps && k->wrap;
	k->dirty[2 * np + 1] = k->ps && !k->wrap;
	return 0;
}

/* Runs the checks that are due; the first round's conflicts are the plain
 * simplification's. */
static int run_checks(struct checker *k, struct fct_chain_stats *st, struct fct_err *err)
{
	for (size_t v = 0; v < k->nchecks; v++) {
		if (!k->dirty[v])
			continue;
		k->dirty[v] = 0;
		size_t conf = 0;
		k->unresolved[v] = 0;
		if (check_patch(k, v, 0, &conf, &k->unresolved[v], err))
			return -1;
		if (st->rounds == 0)
			st->conflicts_plain += conf;
	}
	return 0;
}

/* Splits chain ci's segments that the checks marked; 1 when any was. */
static int split_chain(struct checker *k, size_t ci, double tol2, size_t *stack,
                       struct fct_chain_stats *st)
{
	struct fct_chains *c = k->c;
	int any = 0;
	size_t last = c->start[ci];
	for (size_t q = c->start[ci] + 1; q < c->start[ci + 1]; q++) {
		if (!c->keep[q])
			continue;
		if (k->split[last]) {
			k->split[last] = 0;
			if (q - last >= 2 && !(c->frozen && c->frozen[ci])) {
				/* Split at the farthest point, then refit both
				 * halves: a shorter segment may leave points
				 * beyond the tolerance that the longer one did not. */
				double d2;
				size_t kk = farthest(k->m, c, last, q, &d2);
				c->keep[kk] = 1;
				endpoint_fit(k->m, c, last, kk, tol2, stack);
				endpoint_fit(k->m, c, kk, q, tol2, stack);
				st->topology_points++;
				any = 1;
			}
		}
		last = q;
	}
	return any;
}

/* Chain ci changed: the checks of the patches on its sides, and of the
 * image that holds it, are due again. */
static void recheck_chain(struct checker *k, size_t ci)
{
	const struct fct_chains *c = k->c;
	size_t np = k->np;
	int32_t side[2] = { c->left[ci], c->right[ci] };
	for (int x = 0; x < 2 && side[x] >= 0; x++) {
		size_t p = (size_t)label_id(k->lab, np, side[x]);
		k->dirty[2 * p] = 1;
		k->dirty[2 * p + 1] |= k->ps && k->wrap;
	}
	k->dirty[2 * np + 1] |= k->ps && !k->wrap;
}

/* Splits the marked segments of every marked chain; 1 when any was split
 * (another round is due). */
static int split_marked(struct checker *k, const double *tol2, size_t *stack, struct fct_chain_stats *st)
{
	const struct fct_chains *c = k->c;
	int any = 0;
	memset(k->chain_new, 0, c->n);
	for (size_t ci = 0; ci < c->n; ci++) {
		if (!k->chain_dirty[ci])
			continue;
		k->chain_dirty[ci] = 0;
		if (split_chain(k, ci, tol2[ci], stack, st)) {
			k->chain_new[ci] = 1;
			recheck_chain(k, ci);
			any = 1;
		}
	}
	return any;
}

/* The conflicts left, inherited from the input: one pass over all pairs
 * (the rounds after the first test only pairs with a new segment). */
static int count_left(struct checker *k, struct fct_chain_stats *st, struct fct_err *err)
{
	for (size_t v = 0; v < k->nchecks; v++) {
		size_t conf = 0;
		k->unresolved[v] = 0;
		if (k->checked[v] && check_patch(k, v, 1, &conf, &k->unresolved[v], err))
			return -1;
	}
	for (size_t v = 0; v < k->nchecks; v++) {
		if (v % 2)
			st->conflicts_left_image += k->unresolved[v];
		else
			st->conflicts_left += k->unresolved[v];
	}
	return 0;
}

/* Per-patch crossing checks and splits until nothing more can be split;
 * then, with count, the conflicts left counted; with a cache, the crossings
 * of the input taken from it where they can be and left in it. */
static int keep_topology(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                         const struct fct_plane *planes, size_t nplanes, const double *tol2,
                         int count, struct fct_chain_cache *cache, size_t *stack,
                         struct fct_chain_stats *st, struct fct_err *err)
{
	int rc = -1;
	struct checker k;
	memset(&k, 0, sizeof k);
	k.m = m, k.c = c, k.cache = cache;
	int32_t *lab = fct_arena_array(&k.arena, 2 * c->n, sizeof *lab, err);
	if (!lab)
		goto done;
	k.lab = lab;
	k.np = side_labels(lab, c);
	if (chains_by_patch(&k, err) || patch_normals(&k, patch, planes, nplanes, err) ||
	    plan_checks(&k, err))
		goto done;
	do {
		if (run_checks(&k, st, err))
			goto done;
		st->rounds++;
	} while (split_marked(&k, tol2, stack, st));
	if ((count && count_left(&k, st, err)) || (k.cache && save_checks(&k, err)))
		goto done;
	st->cached_checks = k.cached_checks;
	rc = 0;
done:
	fct_arena_free(&k.arena);
	return rc;
}

int fct_chains_simplify(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                        const struct fct_plane *planes, size_t nplanes,
                        const struct fct_chain_params *p, struct fct_chain_stats *st,
                        struct fct_err *err)
{
	struct fct_chain_stats local;
	if (!st)
		st = &local;
	memset(st, 0, sizeof *st);
	st->tolerance = p->threshold * c->mean_edge;
	if (p->scale && c->start[c->n] > 0) {
		/* The checks' tolerance: the chains' median point's. */
		size_t np = c->start[c->n];
		double *sv = fct_alloc_array(np, sizeof *sv, err);
		if (!sv)
			return -1;
		for (size_t q = 0; q < np; q++)
			sv[q] = p->scale[c->vert[q]];
		qsort(sv, np, sizeof *sv, fct_cmp_double);
		st->tolerance = p->scale_factor * sv[np / 2];
		free(sv);
	}
	double tol2 = st->tolerance * st->tolerance;
	size_t maxlen = 0;
	for (size_t i = 0; i < c->n; i++)
		if (c->start[i + 1] - c->start[i] > maxlen)
			maxlen = c->start[i + 1] - c->start[i];
	size_t *stack = fct_alloc_array(2 * maxlen + 2, sizeof *stack, err);
	double *chain_tol2 = fct_alloc_array(c->n ? c->n : 1, sizeof *chain_tol2, err);
	if (!stack || !chain_tol2) {
		free(stack);
		return -1;
	}
	/* Each chain's own tolerance, which the splits against crossings keep
	 * too: refitting a border seen obliquely to the median point's
	 * tolerance brought back the teeth its own had dropped. */
	for (size_t i = 0; i < c->n; i++) {
		chain_tol2[i] = tol2;
		if (p->scale) {
			double sum = 0;
			for (size_t q = c->start[i]; q < c->start[i + 1]; q++)
				sum += p->scale[c->vert[q]];
			double t = p->scale_factor * sum / (double)(c->start[i + 1] - c->start[i]);
			chain_tol2[i] = t * t;
		}
		if (p->tolerance && p->tolerance[i] > 0)
			chain_tol2[i] = p->tolerance[i] * p->tolerance[i];
	}
	int rc = 0;
	for (size_t i = 0; i < c->n && !rc; i++)
		if (!(c->frozen && c->frozen[i]))   /* else the caller's keep */
			rc = simplify_chain(m, c, i, chain_tol2[i], p->keep_vertex, stack, st, err);
	if (!rc && p->keep_topology)
		rc = keep_topology(c, m, patch, planes, nplanes, chain_tol2, p->count_left, p->cache, stack,
		                   st, err);
	free(stack), free(chain_tol2);
	if (rc)
		return -1;

	/* The figures of the result. */
	unsigned char *seen = calloc(m->nv ? m->nv : 1, 1);
	if (!seen)
		return fct_fail(err, "out of memory");
	for (size_t i = 0; i < c->n; i++) {
		size_t last = c->start[i];
		for (size_t q = c->start[i]; q < c->start[i + 1]; q++) {
			if (!c->keep[q])
				continue;
			if (!seen[c->vert[q]])
				seen[c->vert[q]] = 1, st->kept_vertices++;
			if (q == last)
				continue;
			st->segments++;
			if (q - last >= 2) {
				double d2;
				farthest(m, c, last, q, &d2);
				if (sqrt(d2) > st->max_dev)
					st->max_dev = sqrt(d2);
			}
			last = q;
		}
	}
	free(seen);
	return 0;
}

/* Drop the loops without junction that lie within tol of their centroid:
 * the hole or island they bound is below the model's resolution, and keeping
 * three points of each would fill a noisy view's model with specks.  The
 * patch around a dropped hole covers it; a dropped island's patch vanishes
 * into the patch around it. */
static void drop_small_loops(struct fct_chains *c, const struct fct_mesh *m,
                             const struct fct_plane *planes, size_t nplanes, double tol,
                             size_t *dropped)
{
	for (size_t i = 0; i < c->n; i++) {
		if (c->closed[i] != 2)
			continue;
		size_t s = c->start[i], e = c->start[i + 1] - 1;   /* the last point repeats the first */
		if (c->right[i] < 0) {
			/* Against the outside, a loop is a hole (drop it) only when its
			 * patch, on its left, lies outside it: the loop turns clockwise
			 * about the patch's normal.  Otherwise it is the patch's own
			 * outline, which must stay. */
			if ((size_t)c->left[i] >= nplanes)
				continue;
			double area[3] = { 0, 0, 0 };
			for (size_t q = s; q < e; q++) {
				double x[3];
				fct_v3_cross(x, m->xyz + 3 * (size_t)c->vert[q], m->xyz + 3 * (size_t)c->vert[q + 1]);
				fct_v3_add(area, area, x);
			}
			if (fct_v3_dot(area, planes[c->left[i]].n) >= 0)
				continue;
		}
		double g[3] = { 0, 0, 0 }, far = 0;
		for (size_t q = s; q < e; q++)
			fct_v3_add(g, g, m->xyz + 3 * (size_t)c->vert[q]);
		for (int k = 0; k < 3; k++)
			g[k] /= (double)(e - s);
		for (size_t q = s; q < e; q++) {
			double d = fct_v3_dist2(m->xyz + 3 * (size_t)c->vert[q], g);
			if (d > far)
				far = d;
		}
		if (far <= tol * tol) {
			memset(c->keep + s, 0, e - s + 1);
			(*dropped)++;
		}
	}
}

int fct_simpchain(struct fct_mesh *m, const struct fct_chain_params *p,
                  struct fct_chains *ch, struct fct_chain_stats *st, struct fct_err *err)
{
	struct fct_plane *planes = NULL;
	size_t nplanes = 0;
	int32_t *patch = NULL;
	int present = 0, rc = -1;
	struct fct_chains c;
	memset(&c, 0, sizeof c);
	size_t *keepv = NULL;
	struct fct_wire *wires = NULL;
	uint32_t *map = NULL;
	if (fct_planes_get(m, &planes, &nplanes, err))
		return -1;
	if (fct_patches_get(m, &patch, &present, fct_mesh_find_elem(m, "plane") ? (long)nplanes : -1, err))
		goto done;
	if (!present) {
		fct_fail(err, m->nf ? "faces have no patch property (label them with segplanes)"
		                    : "no faces with a patch property (label them with segplanes)");
		goto done;
	}
	if (fct_chains_extract(&c, m, patch, err) ||
	    fct_chains_simplify(&c, m, patch, planes, nplanes, p, st, err))
		goto done;
	st->loops_dropped = 0;
	if (!p->keep_small_loops)
		drop_small_loops(&c, m, planes, nplanes, st->tolerance, &st->loops_dropped);

	/* Kept vertices in their original order, and the edges between them. */
	map = fct_alloc_array(m->nv, sizeof *map, err);
	if (!map)
		goto done;
	for (size_t v = 0; v < m->nv; v++)
		map[v] = UINT32_MAX;
	for (size_t q = 0; q < c.start[c.n]; q++)
		if (c.keep[q])
			map[c.vert[q]] = 0;
	size_t nk = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (map[v] == 0)
			nk++;
	keepv = fct_alloc_array(nk, sizeof *keepv, err);
	if (!keepv)
		goto done;
	nk = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (map[v] == 0)
			map[v] = (uint32_t)nk, keepv[nk++] = v;
	size_t ne = 0;
	for (size_t i = 0; i < c.n; i++)
		for (size_t q = c.start[i] + 1; q < c.start[i + 1]; q++)
			ne += c.keep[q];
	if (fct_mesh_gather_faces(m, NULL, 0, err) || fct_mesh_gather_vertices(m, keepv, nk, err))
		goto done;
	m->has_faces = 0;
	while (m->face.nprops)
		fct_elem_remove(&m->face, m->face.props[0].name);
	wires = fct_alloc_array(ne, sizeof *wires, err);
	if (!wires && ne)
		goto done;
	size_t row = 0;
	for (size_t i = 0; i < c.n; i++) {
		size_t last = c.start[i];
		for (size_t q = c.start[i] + 1; q < c.start[i + 1]; q++) {
			if (!c.keep[q])
				continue;
			wires[row++] = (struct fct_wire){ map[c.vert[last]], map[c.vert[q]], c.left[i],
			                                  c.right[i] >= 0 ? c.right[i] : -1 };
			last = q;
		}
	}
	if (fct_wires_set(m, wires, ne, err))
		goto done;
	rc = 0;
done:
	free(planes);
	free(patch);
	free(map);
	free(keepv);
	free(wires);
	if (!rc && ch)
		*ch = c;
	else
		fct_chains_free(&c);
	return rc;
}
