/* graphcut.c - Boykov-Kolmogorov max-flow and alpha-expansion; see
 * graphcut.h.  The max-flow follows the paper's sec. 3: nodes of the
 * source tree S and the sink tree T, the free ones; growth from the active
 * nodes, augmentation on the path found, adoption of orphans (a new parent
 * in the same tree whose path reaches the terminal, the nearest by the
 * distance marks, else freed).  Distances and timestamps are the paper's
 * heuristics; they change the work, never the cut. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/graphcut.h"

#define NONE UINT32_MAX          /* no arc, no node */
#define TERMINAL (UINT32_MAX - 1) /* parent: the node hangs on its terminal */
#define ORPHAN (UINT32_MAX - 2)   /* parent: lost during augmentation */

struct fct_mf_node {
	uint32_t first;       /* first outgoing arc, NONE */
	uint32_t parent;      /* arc to the parent, TERMINAL, ORPHAN, or NONE: free */
	uint32_t next;        /* active queue; NONE: not in it */
	uint32_t onext;       /* orphan list */
	int32_t ts, dist;     /* the time its distance was known, and that distance */
	double tr;            /* residual terminal capacity: > 0 from the source, < 0 to the sink */
	unsigned char sink;   /* in T (meaningful when parent != NONE) */
};

struct fct_mf_arc {
	uint32_t head;        /* the node it points to */
	uint32_t next;        /* next arc out of the same tail */
	double r;             /* residual capacity */
};

int fct_maxflow_init(struct fct_maxflow *g, size_t n, size_t edges_hint, struct fct_err *err)
{
	memset(g, 0, sizeof *g);
	if (n >= (size_t)INT32_MAX - 2)
		return fct_fail(err, "graph of %zu nodes: too many", n);
	g->nodes = fct_alloc_array(n, sizeof *g->nodes, err);
	if (!g->nodes)
		return -1;
	for (size_t i = 0; i < n; i++) {
		g->nodes[i].first = NONE;
		g->nodes[i].tr = 0;
	}
	g->nnodes = n;
	if (edges_hint && fct_grow((void **)&g->arcs, &g->arc_cap, 2 * edges_hint, sizeof *g->arcs, err)) {
		fct_maxflow_free(g);
		return -1;
	}
	return 0;
}

void fct_maxflow_free(struct fct_maxflow *g)
{
	if (!g)
		return;
	free(g->nodes);
	free(g->arcs);
	memset(g, 0, sizeof *g);
}

void fct_maxflow_add_terminal(struct fct_maxflow *g, size_t i, double source, double sink)
{
	/* Only the difference flows through the node; the shared part is
	 * flow already. */
	double tr = g->nodes[i].tr;
	if (tr > 0)
		source += tr;
	else
		sink -= tr;
	g->flow += source < sink ? source : sink;
	g->nodes[i].tr = source - sink;
}

int fct_maxflow_add_edge(struct fct_maxflow *g, size_t i, size_t j, double cap, double rev,
                         struct fct_err *err)
{
	if (g->narcs + 2 > (size_t)INT32_MAX)
		return fct_fail(err, "graph of more than 2^31 arcs");
	if (fct_grow((void **)&g->arcs, &g->arc_cap, g->narcs + 2, sizeof *g->arcs, err))
		return -1;
	uint32_t a = (uint32_t)g->narcs;
	struct fct_mf_arc *A = g->arcs;
	A[a].head = (uint32_t)j, A[a].r = cap, A[a].next = g->nodes[i].first;
	A[a + 1].head = (uint32_t)i, A[a + 1].r = rev, A[a + 1].next = g->nodes[j].first;
	g->nodes[i].first = a;
	g->nodes[j].first = a + 1;
	g->narcs += 2;
	return 0;
}

/* The active queue: FIFO through next; the last node points to itself so
 * that next != NONE means "queued". */
static void set_active(struct fct_maxflow *g, uint32_t i)
{
	struct fct_mf_node *N = g->nodes;
	if (N[i].next != NONE)
		return;
	N[i].next = i;
	if (g->active_last != NONE)
		N[g->active_last].next = i;
	else
		g->active_first = i;
	g->active_last = i;
}

/* The next queued node that is still in a tree, NONE when none is. */
static uint32_t next_active(struct fct_maxflow *g)
{
	struct fct_mf_node *N = g->nodes;
	while (g->active_first != NONE) {
		uint32_t i = g->active_first;
		g->active_first = N[i].next == i ? NONE : N[i].next;
		if (g->active_first == NONE)
			g->active_last = NONE;
		N[i].next = NONE;
		if (N[i].parent != NONE)
			return i;
	}
	return NONE;
}

/* Orphans: a LIFO at the front (as augmentation finds them) and a FIFO
 * at the rear (as adoption makes them), linked through onext. */
static void orphan_front(struct fct_maxflow *g, uint32_t i)
{
	g->nodes[i].parent = ORPHAN;
	g->nodes[i].onext = g->orphan_first;
	g->orphan_first = i;
	if (g->orphan_last == NONE)
		g->orphan_last = i;
}

static void orphan_rear(struct fct_maxflow *g, uint32_t i)
{
	g->nodes[i].parent = ORPHAN;
	g->nodes[i].onext = NONE;
	if (g->orphan_last != NONE)
		g->nodes[g->orphan_last].onext = i;
	else
		g->orphan_first = i;
	g->orphan_last = i;
}

/* Push the bottleneck along the path source -> ... -> tail(mid) -> mid ->
 * head(mid) -> ... -> sink; nodes whose link to their tree saturates
 * become orphans. */
static void augment(struct fct_maxflow *g, uint32_t mid)
{
	struct fct_mf_node *N = g->nodes;
	struct fct_mf_arc *A = g->arcs;
	double b = A[mid].r;
	uint32_t i, a;
	for (i = A[mid ^ 1].head; (a = N[i].parent) != TERMINAL; i = A[a].head)
		if (b > A[a ^ 1].r)
			b = A[a ^ 1].r;
	if (b > N[i].tr)
		b = N[i].tr;
	for (i = A[mid].head; (a = N[i].parent) != TERMINAL; i = A[a].head)
		if (b > A[a].r)
			b = A[a].r;
	if (b > -N[i].tr)
		b = -N[i].tr;
	A[mid ^ 1].r += b;
	A[mid].r -= b;
	for (i = A[mid ^ 1].head; (a = N[i].parent) != TERMINAL; i = A[a].head) {
		A[a].r += b;
		A[a ^ 1].r -= b;
		if (!(A[a ^ 1].r > 0))
			orphan_front(g, i);
	}
	N[i].tr -= b;
	if (!(N[i].tr > 0))
		orphan_front(g, i);
	for (i = A[mid].head; (a = N[i].parent) != TERMINAL; i = A[a].head) {
		A[a ^ 1].r += b;
		A[a].r -= b;
		if (!(A[a].r > 0))
			orphan_front(g, i);
	}
	N[i].tr += b;
	if (!(N[i].tr < 0))
		orphan_front(g, i);
	g->flow += b;
}

/* Find orphan i a new parent in its tree: the neighbour with residual
 * capacity towards i (source tree) or from i (sink tree) whose own path
 * reaches the terminal, nearest by distance; or free it, making its
 * children orphans and its tree neighbours active. */
static void adopt(struct fct_maxflow *g, uint32_t i)
{
	struct fct_mf_node *N = g->nodes;
	struct fct_mf_arc *A = g->arcs;
	int sink = N[i].sink;
	uint32_t best = NONE;
	int32_t dmin = INT32_MAX;
	for (uint32_t a0 = N[i].first; a0 != NONE; a0 = A[a0].next) {
		if (!((sink ? A[a0].r : A[a0 ^ 1].r) > 0))
			continue;
		uint32_t j = A[a0].head;
		if (N[j].sink != sink || N[j].parent == NONE)
			continue;
		/* Walk towards the root until a node marked in this round. */
		int32_t d = 0;
		for (;;) {
			if (N[j].ts == g->time) {
				d += N[j].dist;
				break;
			}
			uint32_t a = N[j].parent;
			d++;
			if (a == TERMINAL) {
				N[j].ts = g->time;
				N[j].dist = 1;
				break;
			}
			if (a == ORPHAN) {
				d = INT32_MAX;
				break;
			}
			j = A[a].head;
		}
		if (d == INT32_MAX)
			continue;
		if (d < dmin)
			best = a0, dmin = d;
		for (j = A[a0].head; N[j].ts != g->time; j = A[N[j].parent].head) {
			N[j].ts = g->time;
			N[j].dist = d--;
		}
	}
	if (best != NONE) {
		N[i].parent = best;
		N[i].ts = g->time;
		N[i].dist = dmin + 1;
		return;
	}
	N[i].parent = NONE;
	for (uint32_t a0 = N[i].first; a0 != NONE; a0 = A[a0].next) {
		uint32_t j = A[a0].head, a = N[j].parent;
		if (N[j].sink != sink || a == NONE)
			continue;
		if ((sink ? A[a0].r : A[a0 ^ 1].r) > 0)
			set_active(g, j);
		if (a != TERMINAL && a != ORPHAN && A[a].head == i)
			orphan_rear(g, j);
	}
}

double fct_maxflow_solve(struct fct_maxflow *g)
{
	struct fct_mf_node *N = g->nodes;
	struct fct_mf_arc *A = g->arcs;
	g->active_first = g->active_last = NONE;
	g->orphan_first = g->orphan_last = NONE;
	g->time = 0;
	for (uint32_t i = 0; i < g->nnodes; i++) {
		N[i].next = NONE;
		N[i].ts = 0;
		if (N[i].tr > 0 || N[i].tr < 0) {
			N[i].sink = N[i].tr < 0;
			N[i].parent = TERMINAL;
			N[i].dist = 1;
			set_active(g, i);
		} else {
			N[i].parent = NONE;
			N[i].sink = 0;
			N[i].dist = 0;
		}
	}
	uint32_t cur = NONE;
	for (;;) {
		uint32_t i = cur;
		if (i != NONE) {
			N[i].next = NONE;
			if (N[i].parent == NONE)
				i = NONE;
		}
		if (i == NONE && (i = next_active(g)) == NONE)
			break;
		/* Grow i's tree by one layer, or find where the trees meet. */
		uint32_t mid = NONE;
		int sink = N[i].sink;
		for (uint32_t a = N[i].first; a != NONE; a = A[a].next) {
			if (!((sink ? A[a ^ 1].r : A[a].r) > 0))
				continue;
			uint32_t j = A[a].head;
			if (N[j].parent == NONE) {
				N[j].sink = (unsigned char)sink;
				N[j].parent = a ^ 1;
				N[j].ts = N[i].ts;
				N[j].dist = N[i].dist + 1;
				set_active(g, j);
			} else if (N[j].sink != sink) {
				mid = sink ? a ^ 1 : a;
				break;
			} else if (N[j].ts <= N[i].ts && N[j].dist > N[i].dist) {
				N[j].parent = a ^ 1;
				N[j].ts = N[i].ts;
				N[j].dist = N[i].dist + 1;
			}
		}
		g->time++;
		if (mid == NONE) {
			cur = NONE;
			continue;
		}
		N[i].next = i;     /* keep i: it may meet the other tree again */
		cur = i;
		augment(g, mid);
		while (g->orphan_first != NONE) {
			uint32_t o = g->orphan_first;
			g->orphan_first = N[o].onext;
			if (g->orphan_first == NONE)
				g->orphan_last = NONE;
			adopt(g, o);
		}
	}
	return g->flow;
}

int fct_maxflow_in_sink(const struct fct_maxflow *g, size_t i)
{
	const struct fct_mf_node *n = &g->nodes[i];
	return n->parent != NONE && n->sink;
}

/* ---- alpha-expansion ------------------------------------------------------ */

/* The data cost of label l at site p, or NAN when l is not a candidate. */
static double data_cost(const struct fct_labeling *L, size_t p, int32_t l)
{
	for (size_t k = L->start[p]; k < L->start[p + 1]; k++)
		if (L->label[k] == l)
			return L->cost[k];
	return NAN;
}

double fct_labeling_energy(const struct fct_labeling *L, const int32_t *lab)
{
	double e = 0;
	for (size_t p = 0; p < L->n; p++) {
		if (lab[p] >= 0)
			e += data_cost(L, p, lab[p]);
		for (size_t k = L->nb_start[p]; k < L->nb_start[p + 1]; k++) {
			size_t q = L->nb[k];
			if (q > p && lab[p] >= 0 && lab[q] >= 0 && lab[p] != lab[q])
				e += L->nb_w[k];
		}
	}
	return e;
}

/* The part of the energy that sites in the move (node[p] != NONE) can
 * change: their data costs and the pairs they are in. */
static double local_energy(const struct fct_labeling *L, const int32_t *lab, const uint32_t *node)
{
	double e = 0;
	for (size_t p = 0; p < L->n; p++) {
		if (node[p] == NONE)
			continue;
		e += data_cost(L, p, lab[p]);
		for (size_t k = L->nb_start[p]; k < L->nb_start[p + 1]; k++) {
			size_t q = L->nb[k];
			if ((node[q] == NONE || q > p) && lab[q] >= 0 && lab[p] != lab[q])
				e += L->nb_w[k];
		}
	}
	return e;
}

/* One expansion move of label alpha; *changed gets whether a site took it. */
static int expand(int32_t *lab, const struct fct_labeling *L, int32_t alpha, uint32_t *node,
                  int32_t *prev, double *c0, double *c1, int *changed, struct fct_err *err)
{
	size_t m = 0, ne = 0;
	for (size_t p = 0; p < L->n; p++) {
		node[p] = NONE;
		if (lab[p] >= 0 && lab[p] != alpha && !isnan(data_cost(L, p, alpha))) {
			node[p] = (uint32_t)m++;
			ne += L->nb_start[p + 1] - L->nb_start[p];
		}
	}
	*changed = 0;
	if (!m)
		return 0;
	struct fct_maxflow g;
	if (fct_maxflow_init(&g, m, ne / 2 + 1, err))
		return -1;
	for (size_t p = 0; p < L->n; p++) {
		uint32_t u = node[p];
		if (u == NONE)
			continue;
		c0[u] = data_cost(L, p, lab[p]);
		c1[u] = data_cost(L, p, alpha);
	}
	int rc = 0;
	for (size_t p = 0; p < L->n && !rc; p++) {
		uint32_t u = node[p];
		if (u == NONE)
			continue;
		for (size_t k = L->nb_start[p]; k < L->nb_start[p + 1]; k++) {
			size_t q = L->nb[k];
			double w = L->nb_w[k];
			if (lab[q] < 0 || !(w > 0))
				continue;
			if (node[q] == NONE) {
				/* q keeps its label: p pays w for differing from it. */
				c0[u] += lab[p] != lab[q] ? w : 0;
				c1[u] += alpha != lab[q] ? w : 0;
			} else if (q > p) {
				/* E(0,0) = A, E(0,1) = E(1,0) = w, E(1,1) = 0:
				 * A + (w - A) x_p - w x_q + (2w - A)(1 - x_p) x_q. */
				double A0 = lab[p] != lab[q] ? w : 0;
				c1[u] += w - A0;
				c1[node[q]] -= w;
				if (fct_maxflow_add_edge(&g, u, node[q], 2 * w - A0, 0, err))
					rc = -1;
			}
		}
	}
	if (!rc) {
		for (size_t u = 0; u < m; u++) {
			double d = c1[u] - c0[u];
			fct_maxflow_add_terminal(&g, u, d > 0 ? d : 0, d < 0 ? -d : 0);
		}
		fct_maxflow_solve(&g);
		/* Take the move only when it lowers the energy: a cut that ties
		 * would let two labels trade sites back and forth forever. */
		double before = local_energy(L, lab, node);
		for (size_t p = 0; p < L->n; p++) {
			prev[p] = lab[p];
			if (node[p] != NONE && fct_maxflow_in_sink(&g, node[p]))
				lab[p] = alpha;
		}
		double after = local_energy(L, lab, node);
		if (after < before - 1e-12 * fabs(before))
			*changed = 1;
		else
			memcpy(lab, prev, L->n * sizeof *lab);
	}
	fct_maxflow_free(&g);
	return rc;
}

int fct_expansion(int32_t *lab, const struct fct_labeling *L, int32_t nlabels, int max_cycles,
                  int *cycles, struct fct_err *err)
{
	if (cycles)
		*cycles = 0;
	if (L->n >= (size_t)INT32_MAX - 2)
		return fct_fail(err, "labelling of %zu sites: too many", L->n);
	for (size_t p = 0; p < L->n; p++) {
		if (lab[p] < 0 && L->start[p + 1] > L->start[p])
			return fct_fail(err, "site %zu: no label among its %zu candidates", p,
			                L->start[p + 1] - L->start[p]);
		if (lab[p] >= 0 && isnan(data_cost(L, p, lab[p])))
			return fct_fail(err, "site %zu: label %d is not one of its candidates", p, (int)lab[p]);
	}
	uint32_t *node = fct_alloc_array(L->n, sizeof *node, err);
	double *c0 = fct_alloc_array(L->n, sizeof *c0, err);
	double *c1 = fct_alloc_array(L->n, sizeof *c1, err);
	int32_t *prev = fct_alloc_array(L->n, sizeof *prev, err);
	int rc = node && c0 && c1 && prev ? 0 : -1;
	int cycle = 0;
	for (; !rc && cycle < max_cycles; cycle++) {
		int any = 0;
		for (int32_t alpha = 0; alpha < nlabels && !rc; alpha++) {
			int changed;
			rc = expand(lab, L, alpha, node, prev, c0, c1, &changed, err);
			any |= changed;
		}
		if (!any) {
			cycle++;
			break;
		}
	}
	if (cycles)
		*cycles = cycle;
	free(node);
	free(c0);
	free(c1);
	free(prev);
	return rc;
}
