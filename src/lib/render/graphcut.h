/* graphcut.h - minimum s-t cuts, and the alpha-expansion labelling built on
 * them: the optimiser behind viewtex's choice of one view per face
 * (Waechter, Moehrle and Goesele, "Let There Be Color! Large-Scale
 * Texturing of 3D Reconstructions", ECCV 2014, sec. 3: a data term per
 * face and view, a Potts smoothness term between neighbouring faces).
 *
 * The max-flow is Boykov and Kolmogorov's ("An Experimental Comparison of
 * Min-Cut/Max-Flow Algorithms for Energy Minimization in Vision", PAMI
 * 26(9), 2004): two search trees grown from the terminals, augmentation
 * along the path where they meet, adoption of the orphans it leaves.
 * Capacities are doubles; the same graph built in the same order gives the
 * same cut.
 *
 * The labelling is Boykov, Veksler and Zabih's alpha-expansion ("Fast
 * Approximate Energy Minimization via Graph Cuts", PAMI 23(11), 2001) for
 * E(l) = sum_p D_p(l_p) + sum_{p~q} w_pq [l_p != l_q], with each site's
 * labels restricted to its candidates (a sparse data term: a face can only
 * take a view that sees it).  Each expansion move solves one cut exactly,
 * so the energy never rises; a cycle moves through the labels in order. */
#ifndef FCT_GRAPHCUT_H
#define FCT_GRAPHCUT_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"

struct fct_mf_node;
struct fct_mf_arc;

/* A flow network over nodes 0 .. n-1 and the two terminals. */
struct fct_maxflow {
	size_t nnodes;
	struct fct_mf_node *nodes;
	struct fct_mf_arc *arcs;      /* arcs 2k and 2k+1 are sisters */
	size_t narcs, arc_cap;
	double flow;                  /* the terminal capacities' shared part, then the max flow */
	uint32_t active_first, active_last, orphan_first, orphan_last;
	int32_t time;
};

/* A network of n nodes (n < 2^31 - 2) and no arcs; room for edges_hint
 * edges.  0 or -1 (out of memory). */
int fct_maxflow_init(struct fct_maxflow *g, size_t n, size_t edges_hint, struct fct_err *err);
/* Free what g owns; g may be NULL. */
void fct_maxflow_free(struct fct_maxflow *g);

/* Add capacity from the source to node i and from i to the sink (both >= 0,
 * finite); may be called more than once for a node. */
void fct_maxflow_add_terminal(struct fct_maxflow *g, size_t i, double source, double sink);
/* Add an edge i -> j of capacity cap and j -> i of rev (>= 0, finite,
 * i != j).  0 or -1 (out of memory, more than 2^31 arcs). */
int fct_maxflow_add_edge(struct fct_maxflow *g, size_t i, size_t j, double cap, double rev,
                         struct fct_err *err);

/* The maximum flow, which equals the minimum cut's capacity. */
double fct_maxflow_solve(struct fct_maxflow *g);

/* After solve: is node i on the sink's side of the minimum cut (1), or on
 * the source's (0)?  Nodes that neither terminal reaches go to the
 * source's side. */
int fct_maxflow_in_sink(const struct fct_maxflow *g, size_t i);

/* A sparse labelling problem over n sites.  Site p's candidate labels are
 * label[start[p] .. start[p+1]) (distinct, each >= 0) with data costs
 * cost[...] (>= 0, finite); a site without candidates keeps label -1 and
 * takes no part.  Neighbours: nb[nb_start[p] .. nb_start[p+1]) with
 * weights nb_w[...] (>= 0), each pair listed from both sides with the same
 * weight. */
struct fct_labeling {
	size_t n;
	const size_t *start;
	const int32_t *label;
	const double *cost;
	const size_t *nb_start;
	const uint32_t *nb;
	const double *nb_w;
};

/* The energy of labelling lab (lab[p] one of p's candidates, or -1 for a
 * site without them): data costs plus w for each neighbouring pair, both
 * labelled and with different labels. */
double fct_labeling_energy(const struct fct_labeling *L, const int32_t *lab);

/* Alpha-expansion from the labelling in lab (each site's label one of its
 * candidates, -1 for sites without): cycles over the labels 0 ..
 * nlabels-1 until a cycle changes nothing or max_cycles (>= 1) are done.
 * lab gets the result.  *cycles (may be NULL) gets the cycles run.  0 or
 * -1 (out of memory, a label outside its site's candidates). */
int fct_expansion(int32_t *lab, const struct fct_labeling *L, int32_t nlabels, int max_cycles,
                  int *cycles, struct fct_err *err);

#endif
