/* test_graphcut.c - the max-flow against the minimum cut found by trying
 * every cut of small random networks (capacities with many ties and
 * zeros), the cut it reports against its flow; alpha-expansion against
 * the exact optimum of small Potts problems found by trying every
 * labelling (within the factor 2 the method guarantees, and equal on a
 * chain whose answer is worked out by hand), a result no single expansion
 * move improves, and a tie that must not make it cycle. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "render/graphcut.h"
#include "core/rng.h"

/* A random network of n nodes: terminal capacities and edges. */
struct net {
	int n, ne;
	double src[12], snk[12];
	int ei[64], ej[64];
	double cap[64], rev[64];
};

static double pick(struct fct_rng *r)
{
	/* Small integers, a third of them zero: many ties and saturations. */
	double u = fct_rng_uniform(r);
	return u < 0.33 ? 0 : floor(u * 9);
}

static void random_net(struct net *t, struct fct_rng *r, int n)
{
	t->n = n;
	for (int i = 0; i < n; i++)
		t->src[i] = pick(r), t->snk[i] = pick(r);
	t->ne = 0;
	for (int i = 0; i < n; i++)
		for (int j = i + 1; j < n; j++)
			if (fct_rng_uniform(r) < 0.5) {
				t->ei[t->ne] = i, t->ej[t->ne] = j;
				t->cap[t->ne] = pick(r), t->rev[t->ne] = pick(r);
				t->ne++;
			}
}

/* The capacity of the cut with the nodes of bitmask sink on the sink's side. */
static double cut_value(const struct net *t, unsigned sink)
{
	double c = 0;
	for (int i = 0; i < t->n; i++)
		c += (sink >> i & 1) ? t->src[i] : t->snk[i];
	for (int e = 0; e < t->ne; e++) {
		int a = sink >> t->ei[e] & 1, b = sink >> t->ej[e] & 1;
		if (!a && b)
			c += t->cap[e];
		if (a && !b)
			c += t->rev[e];
	}
	return c;
}

static void test_maxflow_random(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	int bad_flow = 0, bad_cut = 0;
	for (int trial = 0; trial < 400; trial++) {
		struct net t;
		random_net(&t, &r, 1 + trial % 10);
		double best = INFINITY;
		for (unsigned s = 0; s < 1u << t.n; s++) {
			double c = cut_value(&t, s);
			best = c < best ? c : best;
		}
		struct fct_maxflow g;
		struct fct_err err;
		CHECK(fct_maxflow_init(&g, (size_t)t.n, 0, &err) == 0);
		for (int i = 0; i < t.n; i++)
			fct_maxflow_add_terminal(&g, (size_t)i, t.src[i], t.snk[i]);
		for (int e = 0; e < t.ne; e++)
			fct_maxflow_add_edge(&g, (size_t)t.ei[e], (size_t)t.ej[e], t.cap[e], t.rev[e], &err);
		double flow = fct_maxflow_solve(&g);
		unsigned sink = 0;
		for (int i = 0; i < t.n; i++)
			sink |= (unsigned)fct_maxflow_in_sink(&g, (size_t)i) << i;
		bad_flow += flow != best;
		bad_cut += cut_value(&t, sink) != best;
		fct_maxflow_free(&g);
	}
	CHECK_INT(bad_flow, 0);
	CHECK_INT(bad_cut, 0);
}

/* A Potts problem on a grid of w x h sites with nl labels. */
struct potts {
	size_t n;
	size_t start[17], nb_start[17];
	int32_t label[17 * 4];
	double cost[17 * 4];
	uint32_t nb[64];
	double nb_w[64];
};

static void grid_problem(struct potts *P, struct fct_rng *r, int w, int h, int nl, double wt)
{
	P->n = (size_t)(w * h);
	size_t k = 0, e = 0;
	for (int p = 0; p < w * h; p++) {
		P->start[p] = k;
		for (int l = 0; l < nl; l++)
			if (fct_rng_uniform(r) < 0.7 || (l == nl - 1 && k == P->start[p])) {
				P->label[k] = l;
				P->cost[k++] = floor(fct_rng_uniform(r) * 10);
			}
		P->nb_start[p] = e;
		int x = p % w, y = p / w;
		static const int d[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
		for (int j = 0; j < 4; j++) {
			int xx = x + d[j][0], yy = y + d[j][1];
			if (xx < 0 || yy < 0 || xx >= w || yy >= h)
				continue;
			P->nb[e] = (uint32_t)(yy * w + xx);
			P->nb_w[e++] = wt;
		}
	}
	P->start[w * h] = k;
	P->nb_start[w * h] = e;
}

static void as_labeling(const struct potts *P, struct fct_labeling *L)
{
	L->n = P->n;
	L->start = P->start;
	L->label = P->label;
	L->cost = P->cost;
	L->nb_start = P->nb_start;
	L->nb = P->nb;
	L->nb_w = P->nb_w;
}

/* The lowest energy over every labelling from the candidates. */
static double brute_energy(const struct fct_labeling *L)
{
	int32_t lab[16];
	size_t idx[16] = { 0 };
	double best = INFINITY;
	for (;;) {
		for (size_t p = 0; p < L->n; p++)
			lab[p] = L->label[L->start[p] + idx[p]];
		double e = fct_labeling_energy(L, lab);
		best = e < best ? e : best;
		size_t p = 0;
		while (p < L->n && ++idx[p] == L->start[p + 1] - L->start[p])
			idx[p++] = 0;
		if (p == L->n)
			return best;
	}
}

/* Is there an expansion move (any subset of sites switching to alpha)
 * that lowers the energy of lab? */
static int improvable(const struct fct_labeling *L, const int32_t *lab, int nl)
{
	double e0 = fct_labeling_energy(L, lab);
	for (int a = 0; a < nl; a++) {
		for (unsigned s = 1; s < 1u << L->n; s++) {
			int32_t t[16];
			int ok = 1;
			for (size_t p = 0; p < L->n; p++) {
				t[p] = lab[p];
				if (s >> p & 1) {
					int cand = 0;
					for (size_t k = L->start[p]; k < L->start[p + 1]; k++)
						cand |= L->label[k] == a;
					ok &= cand;
					t[p] = a;
				}
			}
			if (ok && fct_labeling_energy(L, t) < e0 - 1e-9)
				return 1;
		}
	}
	return 0;
}

static void test_expansion_random(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 11);
	int worse = 0, local = 0, rose = 0;
	double ratio = 1;
	for (int trial = 0; trial < 60; trial++) {
		struct potts P;
		int w = 2 + trial % 3, h = 2 + (trial / 3) % 2, nl = 2 + trial % 3;
		grid_problem(&P, &r, w, h, nl, 1 + trial % 4);
		struct fct_labeling L;
		as_labeling(&P, &L);
		int32_t lab[16];
		for (size_t p = 0; p < P.n; p++)
			lab[p] = P.label[P.start[p]];
		double e0 = fct_labeling_energy(&L, lab);
		struct fct_err err;
		int cycles;
		CHECK(fct_expansion(lab, &L, nl, 20, &cycles, &err) == 0);
		double e = fct_labeling_energy(&L, lab), opt = brute_energy(&L);
		rose += e > e0;
		worse += e > 2 * opt + 1e-9;
		if (opt > 0 && e / opt > ratio)
			ratio = e / opt;
		local += improvable(&L, lab, nl);
		CHECK(cycles < 20);
	}
	CHECK_INT(rose, 0);
	CHECK_INT(worse, 0);
	CHECK_INT(local, 0);
	CHECK(ratio < 1.5);     /* in practice far inside the bound */
}

/* A chain of 6 sites, labels 0 and 1: the first three prefer 0 by 3, the
 * last three prefer 1 by 3, except site 1, which prefers 1 by 1.  With
 * pair weight 2 the best labelling is 000111: energy 1 (site 1's data)
 * + 2 (one seam), where following the data alone (010111) costs three
 * seams, 6, and the all-zero start 9. */
static void test_expansion_chain(void)
{
	size_t start[7], nb_start[7];
	int32_t label[12];
	double cost[12];
	uint32_t nb[10];
	double nb_w[10];
	static const double c0[6] = { 0, 1, 0, 3, 3, 3 }, c1[6] = { 3, 0, 3, 0, 0, 0 };
	size_t e = 0;
	for (int p = 0; p < 6; p++) {
		start[p] = (size_t)(2 * p);
		label[2 * p] = 0, cost[2 * p] = c0[p];
		label[2 * p + 1] = 1, cost[2 * p + 1] = c1[p];
		nb_start[p] = e;
		if (p > 0)
			nb[e] = (uint32_t)(p - 1), nb_w[e++] = 2;
		if (p < 5)
			nb[e] = (uint32_t)(p + 1), nb_w[e++] = 2;
	}
	start[6] = 12, nb_start[6] = e;
	struct fct_labeling L = { 6, start, label, cost, nb_start, nb, nb_w };
	int32_t lab[6] = { 0, 0, 0, 0, 0, 0 };
	struct fct_err err;
	CHECK(fct_expansion(lab, &L, 2, 10, NULL, &err) == 0);
	static const int32_t want[6] = { 0, 0, 0, 1, 1, 1 };
	CHECK(!memcmp(lab, want, sizeof want));
	CHECK_NEAR(fct_labeling_energy(&L, lab), 3, 1e-12);

	/* Equal costs everywhere: every labelling of one label ties; the
	 * start must stay and the run end after one cycle. */
	for (int k = 0; k < 12; k++)
		cost[k] = 1;
	int32_t same[6] = { 1, 1, 1, 1, 1, 1 };
	int cycles;
	CHECK(fct_expansion(same, &L, 2, 10, &cycles, &err) == 0);
	CHECK_INT(cycles, 1);
	for (int p = 0; p < 6; p++)
		CHECK_INT(same[p], 1);

	/* A label that is not a candidate is refused. */
	label[0] = 1;
	int32_t badlab[6] = { 0, 0, 0, 0, 0, 0 };
	CHECK(fct_expansion(badlab, &L, 2, 10, NULL, &err) == -1);
	CHECK(strstr(err.msg, "site 0") != NULL);
}

int main(void)
{
	test_maxflow_random();
	test_expansion_random();
	test_expansion_chain();
	CHECK_DONE();
}
