/* adj.c - edge and face adjacency, components, degenerate and duplicate
 * faces (see adj.h). */
#include "geom/adj.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

void fct_adj_free(struct fct_adj *a)
{
	if (!a)
		return;
	free(a->edge_v);
	free(a->edge_fstart);
	free(a->edge_f);
	free(a->face_e);
	free(a->vert_fstart);
	free(a->vert_f);
	memset(a, 0, sizeof *a);
}

/* The index arrays are 32-bit, like the mesh's own; a mesh too large for
 * them is refused rather than silently wrapped. */
static int check_size(const struct fct_mesh *m, struct fct_err *err)
{
	if (m->nv >= UINT32_MAX || m->nf >= UINT32_MAX)
		return fct_fail(err, "adjacency: more than %u vertices or faces", (unsigned)UINT32_MAX - 1);
	return 0;
}

/* A corner's step to the next corner, from the lower vertex to the higher:
 * sorted by (lo, hi, corner), runs of equal (lo, hi) are the edges.  The
 * sort moves the records themselves, so that the passes after it read
 * them in order. */
struct step {
	uint32_t lo, hi, face, corner;
};

/* (hi, corner) order; corners are unique, so any sort gives one result. */
static int step_cmp(const void *pa, const void *pb)
{
	const struct step *x = pa, *y = pb;
	if (x->hi != y->hi)
		return x->hi < y->hi ? -1 : 1;
	return (x->corner > y->corner) - (x->corner < y->corner);
}

/* Each run of equal lo in t[0..n) (corners increasing within a run) sorted
 * by (hi, corner).  A run is a vertex's edges to higher vertices, a
 * handful, sorted by insertion; a fan's centre may have any number, so a
 * long run goes to qsort. */
#define SHORT_RUN 32

static void sort_runs_by_hi(struct step *t, size_t n)
{
	for (size_t s = 0, e; s < n; s = e) {
		for (e = s + 1; e < n && t[e].lo == t[s].lo; e++)
			;
		if (e - s > SHORT_RUN) {
			qsort(t + s, e - s, sizeof *t, step_cmp);
			continue;
		}
		for (size_t i = s + 1; i < e; i++) {   /* stable: corners stay increasing */
			struct step x = t[i];
			size_t j = i;
			for (; j > s && t[j - 1].hi > x.hi; j--)
				t[j] = t[j - 1];
			t[j] = x;
		}
	}
}

/* The edges: sort the non-degenerate corners' steps by (lo, hi, corner)
 * and give each run of equal (lo, hi) one edge number. */
static int build_edges(struct fct_adj *a, const struct fct_mesh *m, struct fct_err *err)
{
	size_t nc = m->nf ? m->fstart[m->nf] : 0;
	struct step *t = fct_alloc_array(nc, sizeof *t, err);
	uint32_t *count = fct_alloc_array(m->nv + 1, sizeof *count, err);
	a->face_e = fct_alloc_array(nc, sizeof *a->face_e, err);
	int rc = -1;
	if (!t || !count || !a->face_e)
		goto out;

	/* Stably by lo, a counting sort (the steps counted, then put in
	 * place in corner order), then each lo's run by hi. */
	size_t nk = 0;  /* corners that give an edge */
	memset(count, 0, (m->nv + 1) * sizeof *count);
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], e = m->fstart[f + 1];
		for (uint32_t c = s; c < e; c++) {
			uint32_t u = m->fvert[c], v = m->fvert[c + 1 == e ? s : c + 1];
			a->face_e[c] = FCT_ADJ_NONE;
			if (u == v) {
				a->nskipped++;
				continue;
			}
			count[(u < v ? u : v) + 1]++;
			nk++;
		}
	}
	for (size_t v = 0; v < m->nv; v++)
		count[v + 1] += count[v];
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], e = m->fstart[f + 1];
		for (uint32_t c = s; c < e; c++) {
			uint32_t u = m->fvert[c], v = m->fvert[c + 1 == e ? s : c + 1];
			if (u == v)
				continue;
			uint32_t lo = u < v ? u : v;
			struct step *x = &t[count[lo]++];
			x->lo = lo, x->hi = u < v ? v : u, x->face = (uint32_t)f, x->corner = c;
		}
	}
	sort_runs_by_hi(t, nk);

	size_t ne = 0;
	for (size_t i = 0; i < nk; i++)
		if (i == 0 || t[i].lo != t[i - 1].lo || t[i].hi != t[i - 1].hi)
			ne++;
	a->ne = ne;
	a->edge_v = fct_alloc_array(2 * ne, sizeof *a->edge_v, err);
	a->edge_fstart = fct_alloc_array(ne + 1, sizeof *a->edge_fstart, err);
	a->edge_f = fct_alloc_array(nk, sizeof *a->edge_f, err);
	if (!a->edge_v || !a->edge_fstart || !a->edge_f)
		goto out;
	size_t e = (size_t)-1;
	for (size_t i = 0; i < nk; i++) {
		if (i == 0 || t[i].lo != t[i - 1].lo || t[i].hi != t[i - 1].hi) {
			e++;
			a->edge_v[2 * e] = t[i].lo;
			a->edge_v[2 * e + 1] = t[i].hi;
			a->edge_fstart[e] = (uint32_t)i;
		}
		a->edge_f[i] = t[i].face;
		a->face_e[t[i].corner] = (uint32_t)e;
	}
	a->edge_fstart[ne] = (uint32_t)nk;
	for (size_t k = 0; k < ne; k++) {
		uint32_t n = fct_adj_edge_nfaces(a, k);
		if (n == 1)
			a->nborder++;
		else if (n == 2)
			a->nmanifold++;
		else
			a->nnonmanifold++;
	}
	rc = 0;
out:
	free(t);
	free(count);
	return rc;
}

/* A breadth-first walk through the faces from s, kept to the ball of
 * radius r (adj.h). */
size_t fct_vertices_within(const struct fct_mesh *m, const uint32_t *vert_fstart, const uint32_t *vert_f,
                           size_t s, double r, uint32_t *stamp, uint32_t mark, uint32_t *list)
{
	const double *ps = m->xyz + 3 * s;
	double r2 = r * r;
	size_t head = 0, tail = 0;
	list[tail++] = (uint32_t)s;
	stamp[s] = mark;
	while (head < tail) {
		uint32_t u = list[head++];
		for (uint32_t k = vert_fstart[u]; k < vert_fstart[u + 1]; k++) {
			uint32_t f = vert_f[k];
			for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
				uint32_t v = m->fvert[c];
				if (stamp[v] == mark)
					continue;
				stamp[v] = mark;
				if (fct_v3_dist2(ps, m->xyz + 3 * (size_t)v) <= r2)
					list[tail++] = v;
			}
		}
	}
	return tail;
}

/* The faces of each vertex, each face once: a face's stamp in last[v]
 * tells that it was already counted for v. */
int fct_vertex_faces(const struct fct_mesh *m, uint32_t **vert_fstart, uint32_t **vert_f,
                     struct fct_err *err)
{
	*vert_fstart = NULL, *vert_f = NULL;
	uint32_t *last = fct_alloc_array(m->nv, sizeof *last, err);
	uint32_t *start = fct_alloc_array(m->nv + 1, sizeof *start, err);
	if (!last || !start) {
		free(last);
		free(start);
		return -1;
	}
	memset(start, 0, (m->nv + 1) * sizeof *start);
	memset(last, 0xff, m->nv * sizeof *last);
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
			uint32_t v = m->fvert[c];
			if (last[v] != f) {
				last[v] = (uint32_t)f;
				start[v + 1]++;
			}
		}
	for (size_t v = 0; v < m->nv; v++)
		start[v + 1] += start[v];
	uint32_t *list = fct_alloc_array(start[m->nv], sizeof *list, err);
	if (!list) {
		free(last);
		free(start);
		return -1;
	}
	/* Fill with start[v] as the cursor, then shift the starts back. */
	memset(last, 0xff, m->nv * sizeof *last);
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
			uint32_t v = m->fvert[c];
			if (last[v] != f) {
				last[v] = (uint32_t)f;
				list[start[v]++] = (uint32_t)f;
			}
		}
	for (size_t v = m->nv; v > 0; v--)
		start[v] = start[v - 1];
	start[0] = 0;
	free(last);
	*vert_fstart = start, *vert_f = list;
	return 0;
}

int fct_adj_build(struct fct_adj *a, const struct fct_mesh *m, struct fct_err *err)
{
	memset(a, 0, sizeof *a);
	if (check_size(m, err))
		return -1;
	a->nv = m->nv;
	a->nf = m->nf;
	if (build_edges(a, m, err) || fct_vertex_faces(m, &a->vert_fstart, &a->vert_f, err)) {
		fct_adj_free(a);
		return -1;
	}
	return 0;
}

/* Union-find root with path halving. */
static uint32_t find_root(uint32_t *parent, uint32_t x)
{
	while (parent[x] != x) {
		parent[x] = parent[parent[x]];
		x = parent[x];
	}
	return x;
}

long fct_adj_components(const struct fct_adj *a, uint32_t *label, struct fct_err *err)
{
	uint32_t *parent = fct_alloc_array(a->nf, sizeof *parent, err);
	if (!parent)
		return -1;
	for (size_t f = 0; f < a->nf; f++)
		parent[f] = (uint32_t)f;
	/* The smaller root always wins, so a root is its component's smallest face. */
	for (size_t e = 0; e < a->ne; e++) {
		uint32_t r0 = find_root(parent, a->edge_f[a->edge_fstart[e]]);
		for (uint32_t i = a->edge_fstart[e] + 1; i < a->edge_fstart[e + 1]; i++) {
			uint32_t r = find_root(parent, a->edge_f[i]);
			if (r < r0)
				parent[r0] = r, r0 = r;
			else if (r > r0)
				parent[r] = r0;
		}
	}
	long n = 0;
	for (size_t f = 0; f < a->nf; f++) {
		uint32_t r = find_root(parent, (uint32_t)f);
		label[f] = r == f ? (uint32_t)n++ : label[r];  /* r < f is labelled already */
	}
	free(parent);
	return n;
}

long fct_mesh_drop_small_pieces(struct fct_mesh *m, size_t min_faces, size_t *dropped,
                                struct fct_err *err)
{
	if (dropped)
		*dropped = 0;
	if (min_faces <= 1 || !m->nf)
		return 0;
	struct fct_adj a;
	if (fct_adj_build(&a, m, err))
		return -1;
	uint32_t *label = fct_alloc_array(m->nf, sizeof *label, err);
	long n = label ? fct_adj_components(&a, label, err) : -1;
	size_t *size = n >= 0 ? fct_alloc_array((size_t)n + 1, sizeof *size, err) : NULL;
	size_t *keep = size ? fct_alloc_array(m->nf + m->nv, sizeof *keep, err) : NULL;
	long rc = -1;
	if (keep) {
		memset(size, 0, ((size_t)n + 1) * sizeof *size);
		for (size_t f = 0; f < m->nf; f++)
			size[label[f]]++;
		/* The largest piece (the first of them) always stays: a mesh of
		 * one small piece is an object, not debris. */
		long largest = 0;
		for (long c = 1; c < n; c++)
			if (size[c] > size[largest])
				largest = c;
		size[largest] = min_faces > size[largest] ? min_faces : size[largest];
		size_t nkeep = 0, small = 0;
		for (long c = 0; c < n; c++)
			small += size[c] < min_faces;
		for (size_t f = 0; f < m->nf; f++)
			if (size[label[f]] >= min_faces)
				keep[nkeep++] = f;
		/* Debris is what lies beside the surface: where the small pieces
		 * hold half the faces or more, they are the surface (a mesh of
		 * scattered patches, a triangle soup), and all stay. */
		if (2 * nkeep <= m->nf)
			nkeep = m->nf, small = 0;
		rc = (long)(m->nf - nkeep);
		if (rc > 0) {
			/* The vertices kept: those a kept face uses, and those no face
			 * used (a vertex only the dropped pieces used goes with them). */
			unsigned char *gone = fct_alloc_array(m->nv ? m->nv : 1, 1, err);
			if (!gone || fct_mesh_gather_faces(m, keep, nkeep, err)) {
				rc = -1;
			} else {
				for (size_t v = 0; v < m->nv; v++)
					gone[v] = a.vert_fstart[v] < a.vert_fstart[v + 1];
				for (size_t k = 0; k < m->fstart[m->nf]; k++)
					gone[m->fvert[k]] = 0;
				size_t nvkeep = 0;
				for (size_t v = 0; v < m->nv; v++)
					if (!gone[v])
						keep[nvkeep++] = v;
				if (fct_mesh_gather_vertices(m, keep, nvkeep, err))
					rc = -1;
			}
			free(gone);
		}
		if (rc >= 0 && dropped)
			*dropped = small;
	}
	free(keep);
	free(size);
	free(label);
	fct_adj_free(&a);
	return rc;
}

size_t fct_adj_isolated_vertices(const struct fct_adj *a)
{
	size_t n = 0;
	for (size_t v = 0; v < a->nv; v++)
		n += a->vert_fstart[v] == a->vert_fstart[v + 1];
	return n;
}

/* Face checks ------------------------------------------------------------- */

/* Half the norm of the vector area of face f (a fan from corner 0). */
static double face_area(const struct fct_mesh *m, size_t f)
{
	const uint32_t *v = m->fvert + m->fstart[f];
	uint32_t n = fct_face_size(m, f);
	const double *p0 = m->xyz + 3 * (size_t)v[0];
	double s[3] = {0, 0, 0};
	for (uint32_t i = 1; i + 1 < n; i++) {
		const double *p = m->xyz + 3 * (size_t)v[i], *q = m->xyz + 3 * (size_t)v[i + 1];
		double u[3] = {p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]};
		double w[3] = {q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]};
		s[0] += u[1] * w[2] - u[2] * w[1];
		s[1] += u[2] * w[0] - u[0] * w[2];
		s[2] += u[0] * w[1] - u[1] * w[0];
	}
	return 0.5 * sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
}

long fct_mesh_degenerate_faces(const struct fct_mesh *m, double min_area, unsigned char *flag,
                               struct fct_err *err)
{
	if (check_size(m, err))
		return -1;
	uint32_t *last = fct_alloc_array(m->nv, sizeof *last, err);
	if (!last)
		return -1;
	memset(last, 0xff, m->nv * sizeof *last);
	long n = 0;
	for (size_t f = 0; f < m->nf; f++) {
		int bad = fct_face_size(m, f) < 3;
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
			uint32_t v = m->fvert[c];
			bad |= last[v] == f;
			last[v] = (uint32_t)f;
		}
		if (!bad)
			bad = face_area(m, f) <= min_area;
		if (flag)
			flag[f] = (unsigned char)bad;
		n += bad;
	}
	free(last);
	return n;
}

static int cmp_u32(const void *a, const void *b)
{
	uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
	return (x > y) - (x < y);
}

/* Sort v[0..n) and drop repeats; returns the new length. */
static uint32_t sort_unique(uint32_t *v, uint32_t n)
{
	if (n <= 32) {
		for (uint32_t i = 1; i < n; i++) {
			uint32_t x = v[i], j = i;
			for (; j > 0 && v[j - 1] > x; j--)
				v[j] = v[j - 1];
			v[j] = x;
		}
	} else {
		qsort(v, n, sizeof *v, cmp_u32);
	}
	uint32_t k = 0;
	for (uint32_t i = 0; i < n; i++)
		if (k == 0 || v[i] != v[k - 1])
			v[k++] = v[i];
	return k;
}

static uint64_t mix64(uint64_t x)
{
	x ^= x >> 33;
	x *= 0xff51afd7ed558ccdULL;
	x ^= x >> 33;
	x *= 0xc4ceb9fe1a85ec53ULL;
	x ^= x >> 33;
	return x;
}

/* The sorted vertex sets of the faces: set f is set[start[f] .. + len[f]). */
struct face_sets {
	const uint32_t *start;
	uint32_t *set;
	uint32_t *len;
};

/* Order of two faces' sets (length, then lexicographic), then of the faces. */
static int cmp_sets(const struct face_sets *s, uint32_t f, uint32_t g)
{
	if (s->len[f] != s->len[g])
		return s->len[f] < s->len[g] ? -1 : 1;
	int c = 0;
	for (uint32_t i = 0; i < s->len[f] && !c; i++) {
		uint32_t x = s->set[s->start[f] + i], y = s->set[s->start[g] + i];
		c = (x > y) - (x < y);
	}
	return c ? c : (f > g) - (f < g);
}

static int same_set(const struct face_sets *s, uint32_t f, uint32_t g)
{
	return s->len[f] == s->len[g] &&
	       !memcmp(s->set + s->start[f], s->set + s->start[g], s->len[f] * sizeof *s->set);
}

/* Merge sort of faces v[0..n) by cmp_sets (tmp holds n entries); used only
 * on runs of equal hash keys, so it rarely sees more than two faces unless
 * they are true duplicates. */
static void sort_by_set(const struct face_sets *s, uint32_t *v, uint32_t *tmp, size_t n)
{
	if (n < 2)
		return;
	size_t h = n / 2;
	sort_by_set(s, v, tmp, h);
	sort_by_set(s, v + h, tmp, n - h);
	size_t i = 0, j = h, k = 0;
	while (i < h && j < n)
		tmp[k++] = cmp_sets(s, v[i], v[j]) <= 0 ? v[i++] : v[j++];
	while (i < h)
		tmp[k++] = v[i++];
	while (j < n)
		tmp[k++] = v[j++];
	memcpy(v, tmp, n * sizeof *v);
}

struct hashed {
	uint64_t h;
	uint32_t f;
};

/* The hash bits faces are sorted by: the top 33, in three 11-bit digits
 * whose counts fit in L1.  Faces that agree on them (about n^2 / 2^34 pairs
 * by chance) are then ordered by their sets. */
#define KEY_SHIFT 31
#define DIGIT_BITS 11
#define DIGITS (1u << DIGIT_BITS)

static uint64_t sort_key(const struct hashed *x)
{
	return x->h >> KEY_SHIFT;
}

/* Stable LSD radix sort of x[0..n) by sort_key (tmp: n entries). */
static void radix_sort_hashes(struct hashed *x, struct hashed *tmp, size_t n)
{
	size_t count[DIGITS + 1];
	for (int shift = 0; shift < 64 - KEY_SHIFT; shift += DIGIT_BITS) {
		memset(count, 0, sizeof count);
		for (size_t i = 0; i < n; i++)
			count[((sort_key(&x[i]) >> shift) & (DIGITS - 1)) + 1]++;
		for (size_t k = 0; k < DIGITS; k++)
			count[k + 1] += count[k];
		for (size_t i = 0; i < n; i++)
			tmp[count[(sort_key(&x[i]) >> shift) & (DIGITS - 1)]++] = x[i];
		memcpy(x, tmp, n * sizeof *x);
	}
}

/* Faces are hashed on their sorted vertex sets and radix-sorted by hash, so
 * the work is linear; faces of equal hash are then ordered by their sets, so
 * a hash collision can cost time but never a wrong answer. */
long fct_mesh_duplicate_faces(const struct fct_mesh *m, uint32_t *first, struct fct_err *err)
{
	if (check_size(m, err))
		return -1;
	size_t nc = m->nf ? m->fstart[m->nf] : 0;
	struct face_sets s = {m->fstart, NULL, NULL};
	s.set = fct_alloc_array(nc, sizeof *s.set, err);
	s.len = fct_alloc_array(m->nf, sizeof *s.len, err);
	struct hashed *x = fct_alloc_array(m->nf, sizeof *x, err);
	struct hashed *tmp = fct_alloc_array(m->nf, sizeof *tmp, err);
	uint32_t *run = fct_alloc_array(m->nf, sizeof *run, err);
	uint32_t *rtmp = fct_alloc_array(m->nf, sizeof *rtmp, err);
	long n = -1;
	if (!s.set || !s.len || !x || !tmp || !run || !rtmp)
		goto out;
	if (nc)
		memcpy(s.set, m->fvert, nc * sizeof *s.set);
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t *v = s.set + m->fstart[f];
		uint32_t k = s.len[f] = sort_unique(v, fct_face_size(m, f));
		uint64_t h = mix64(k + 0x9e3779b97f4a7c15ULL);
		for (uint32_t i = 0; i < k; i++)
			h = mix64(h ^ (v[i] + 0x9e3779b97f4a7c15ULL));
		x[f].h = h;
		x[f].f = (uint32_t)f;
	}
	radix_sort_hashes(x, tmp, m->nf);
	n = 0;
	for (size_t i = 0, j; i < m->nf; i = j) {
		for (j = i; j < m->nf && sort_key(&x[j]) == sort_key(&x[i]); j++)
			run[j - i] = x[j].f;
		sort_by_set(&s, run, rtmp, j - i);
		/* In each group of equal sets the smallest face comes first. */
		uint32_t lead = run[0];
		for (size_t k = 0; k < j - i; k++) {
			uint32_t f = run[k];
			if (k > 0 && same_set(&s, lead, f))
				n++;
			else
				lead = f;
			if (first)
				first[f] = lead;
		}
	}
out:
	free(s.set);
	free(s.len);
	free(x);
	free(tmp);
	free(run);
	free(rtmp);
	return n;
}

struct weld_key {
	double p[3];
	uint32_t v;
};

static int cmp_key(const void *pa, const void *pb)
{
	const struct weld_key *a = pa, *b = pb;
	int r = memcmp(a->p, b->p, sizeof a->p);
	return r ? r : (a->v > b->v) - (a->v < b->v);
}

long fct_mesh_duplicate_vertices(const struct fct_mesh *m, uint32_t *first, struct fct_err *err)
{
	if (m->nv > UINT32_MAX)
		return fct_fail(err, "duplicate vertices: too many vertices");
	struct weld_key *key = fct_alloc_array(m->nv ? m->nv : 1, sizeof *key, err);
	if (!key)
		return -1;
	for (size_t v = 0; v < m->nv; v++) {
		memcpy(key[v].p, m->xyz + 3 * v, sizeof key[v].p);
		key[v].v = (uint32_t)v;
	}
	/* byte order of the positions: equal positions are adjacent, the
	 * smallest index first */
	qsort(key, m->nv, sizeof *key, cmp_key);
	long n = 0;
	for (size_t i = 0, lead = 0; i < m->nv; i++) {
		if (i > 0 && memcmp(key[i].p, key[i - 1].p, sizeof key[i].p))
			lead = i;
		n += lead != i;
		if (first)
			first[key[i].v] = key[lead].v;
	}
	free(key);
	return n;
}

long fct_mesh_weld_exact(struct fct_mesh *m, struct fct_err *err)
{
	uint32_t *rep = fct_alloc_array(m->nv ? m->nv : 1, sizeof *rep, err);
	size_t *keep = rep ? fct_alloc_array(m->nv ? m->nv : 1, sizeof *keep, err) : NULL;
	long rc = -1, removed = keep ? fct_mesh_duplicate_vertices(m, rep, err) : -1;
	if (removed <= 0) {
		/* nothing to merge: the mesh stays as it is, not copied over */
		rc = removed;
		goto done;
	}
	size_t n = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (rep[v] == v)
			keep[n++] = v;
	for (size_t i = 0; m->nf && i < m->fstart[m->nf]; i++)
		m->fvert[i] = rep[m->fvert[i]];
	/* renumbers the faces, whose vertices are all kept now */
	if (fct_mesh_gather_vertices(m, keep, n, err))
		goto done;
	rc = removed;
done:
	free(rep);
	free(keep);
	return rc;
}

long fct_mesh_weld(struct fct_mesh *m, size_t *dropped, struct fct_err *err)
{
	*dropped = 0;
	long merged = fct_mesh_weld_exact(m, err);
	if (merged < 0)
		return -1;
	unsigned char *bad = fct_alloc_array(m->nf ? m->nf : 1, 1, err);
	size_t *keep = bad ? fct_alloc_array(m->nf ? m->nf : 1, sizeof *keep, err) : NULL;
	/* min_area -1: only faces with a repeated vertex (or < 3 corners) */
	long ndeg = keep ? fct_mesh_degenerate_faces(m, -1, bad, err) : -1;
	size_t n = 0;
	for (size_t f = 0; ndeg > 0 && f < m->nf; f++)
		if (!bad[f])
			keep[n++] = f;
	if (ndeg < 0 || (ndeg > 0 && fct_mesh_gather_faces(m, keep, n, err)))
		merged = -1;
	else
		*dropped = (size_t)ndeg;
	free(bad);
	free(keep);
	return merged;
}
