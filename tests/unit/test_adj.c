/* test_adj.c - edge/face adjacency, components, isolated vertices,
 * degenerate and duplicate faces on hand-made meshes with known answers. */
#include <stdlib.h>

#include "geom/adj.h"
#include "check.h"

static struct fct_err err;

/* A mesh of nv vertices at pos (3 each; NULL: all at the origin) and faces
 * given as a -1-separated list of vertex indices. */
static void make_mesh(struct fct_mesh *m, size_t nv, const double *pos, const int *faces, size_t n)
{
	fct_mesh_init(m);
	for (size_t v = 0; v < nv; v++)
		if (fct_mesh_add_vertex(m, pos ? pos[3 * v] : 0, pos ? pos[3 * v + 1] : 0,
		                        pos ? pos[3 * v + 2] : 0, &err) < 0)
			abort();
	uint32_t buf[16];
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		if (faces[i] >= 0) {
			buf[k++] = (uint32_t)faces[i];
			continue;
		}
		if (fct_mesh_add_face(m, buf, k, &err) < 0)
			abort();
		k = 0;
	}
}

/* Edge number of {u, v}, or -1. */
static long find_edge(const struct fct_adj *a, uint32_t u, uint32_t v)
{
	uint32_t lo = u < v ? u : v, hi = u < v ? v : u;
	for (size_t e = 0; e < a->ne; e++)
		if (a->edge_v[2 * e] == lo && a->edge_v[2 * e + 1] == hi)
			return (long)e;
	return -1;
}

/* Invariants that hold for every mesh: edges strictly sorted, each face's
 * edge joins the corners it says, edge face lists ascending, counts add up. */
static void check_invariants(const struct fct_mesh *m, const struct fct_adj *a)
{
	int sorted = 1, corners = 1, ascending = 1;
	for (size_t e = 0; e < a->ne; e++) {
		const uint32_t *p = a->edge_v + 2 * e;
		if (p[0] >= p[1] || (e > 0 && (p[-2] > p[0] || (p[-2] == p[0] && p[-1] >= p[1]))))
			sorted = 0;
		for (uint32_t i = a->edge_fstart[e] + 1; i < a->edge_fstart[e + 1]; i++)
			if (a->edge_f[i - 1] > a->edge_f[i])
				ascending = 0;
	}
	size_t skipped = 0;
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], n = fct_face_size(m, f);
		for (uint32_t k = 0; k < n; k++) {
			uint32_t u = m->fvert[s + k], v = m->fvert[s + (k + 1) % n];
			uint32_t e = a->face_e[s + k];
			if (u == v) {
				skipped++;
				corners &= e == FCT_ADJ_NONE;
			} else {
				corners &= e < a->ne && (long)e == find_edge(a, u, v);
			}
		}
	}
	CHECK(sorted);
	CHECK(corners);
	CHECK(ascending);
	CHECK_INT(a->nskipped, skipped);
	CHECK_INT(a->nborder + a->nmanifold + a->nnonmanifold, a->ne);
}

static void test_cube(void)
{
	double pos[24];
	for (int v = 0; v < 8; v++)
		pos[3 * v] = v & 1, pos[3 * v + 1] = (v >> 1) & 1, pos[3 * v + 2] = (v >> 2) & 1;
	/* Six quads (a b c d) split into (a b c) (a c d). */
	static const int quads[6][4] = {
		{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5},
	};
	int faces[48], n = 0;
	for (int q = 0; q < 6; q++) {
		const int *v = quads[q];
		int t[8] = {v[0], v[1], v[2], -1, v[0], v[2], v[3], -1};
		for (int i = 0; i < 8; i++)
			faces[n++] = t[i];
	}
	struct fct_mesh m;
	make_mesh(&m, 8, pos, faces, (size_t)n);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 18);
	CHECK_INT(a.nborder, 0);
	CHECK_INT(a.nmanifold, 18);
	CHECK_INT(a.nnonmanifold, 0);
	CHECK_INT((long)m.nv - (long)a.ne + (long)m.nf, 2);  /* Euler, sphere */
	/* Vertex 0 has the edges to 1, 2, 3, 4, 5, 6, numbered first. */
	CHECK_INT(a.edge_v[0], 0);
	CHECK_INT(a.edge_v[1], 1);
	CHECK_INT(a.edge_v[10], 0);
	CHECK_INT(a.edge_v[11], 6);
	CHECK_INT(a.edge_v[12], 1);
	/* Edge (0,1) is walked by (0 3 1) and (0 1 5): faces 1 and 4. */
	CHECK_INT(fct_adj_edge_nfaces(&a, 0), 2);
	CHECK_INT(a.edge_f[a.edge_fstart[0]], 1);
	CHECK_INT(a.edge_f[a.edge_fstart[0] + 1], 4);
	/* Vertex 0 is in faces 0 1 4 5 8 9; vertex 7 in 2 3 6 7 10 11. */
	static const int vf0[] = {0, 1, 4, 5, 8, 9}, vf7[] = {2, 3, 6, 7, 10, 11};
	CHECK_INT(a.vert_fstart[1] - a.vert_fstart[0], 6);
	CHECK_INT(a.vert_fstart[8] - a.vert_fstart[7], 6);
	int same0 = 1, same7 = 1;
	for (int i = 0; i < 6; i++) {
		same0 &= (int)a.vert_f[a.vert_fstart[0] + i] == vf0[i];
		same7 &= (int)a.vert_f[a.vert_fstart[7] + i] == vf7[i];
	}
	CHECK(same0);
	CHECK(same7);
	uint32_t label[12];
	CHECK_INT(fct_adj_components(&a, label, &err), 1);
	CHECK_INT(label[11], 0);
	CHECK_INT(fct_adj_isolated_vertices(&a), 0);
	CHECK_INT(fct_mesh_degenerate_faces(&m, 1e-12, NULL, &err), 0);
	CHECK_INT(fct_mesh_duplicate_faces(&m, NULL, &err), 0);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

/* An n x n grid of unit squares in z = 0, as quads or split in triangles. */
static void make_grid(struct fct_mesh *m, int n, int triangles)
{
	fct_mesh_init(m);
	for (int y = 0; y <= n; y++)
		for (int x = 0; x <= n; x++)
			fct_mesh_add_vertex(m, x, y, 0, &err);
	for (int y = 0; y < n; y++)
		for (int x = 0; x < n; x++) {
			uint32_t a = (uint32_t)(y * (n + 1) + x), b = a + 1, c = b + (uint32_t)n + 1, d = c - 1;
			uint32_t q[4] = {a, b, c, d}, t1[3] = {a, b, c}, t2[3] = {a, c, d};
			if (triangles) {
				fct_mesh_add_face(m, t1, 3, &err);
				fct_mesh_add_face(m, t2, 3, &err);
			} else {
				fct_mesh_add_face(m, q, 4, &err);
			}
		}
}

static void test_grid(void)
{
	struct fct_mesh m;
	struct fct_adj a;
	/* 2 x 2 triangles: 12 sides of squares + 4 diagonals; 8 on the border. */
	make_grid(&m, 2, 1);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 16);
	CHECK_INT(a.nborder, 8);
	CHECK_INT(a.nmanifold, 8);
	CHECK_INT((long)m.nv - (long)a.ne + (long)m.nf, 1);  /* Euler, disc */
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);

	/* 2 x 2 quads: a quad has 4 edges; 12 edges, 8 border, 4 inner. */
	make_grid(&m, 2, 0);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 12);
	CHECK_INT(a.nborder, 8);
	CHECK_INT(a.nmanifold, 4);
	/* The centre vertex 4 is in all four quads; the corner 0 in quad 0. */
	CHECK_INT(a.vert_fstart[5] - a.vert_fstart[4], 4);
	CHECK_INT(a.vert_fstart[1] - a.vert_fstart[0], 1);
	/* Quad 0 is (0 1 4 3): edges (0,1) (1,4) (3,4) (0,3). */
	CHECK_INT(a.face_e[0], find_edge(&a, 0, 1));
	CHECK_INT(a.face_e[1], find_edge(&a, 1, 4));
	CHECK_INT(a.face_e[2], find_edge(&a, 3, 4));
	CHECK_INT(a.face_e[3], find_edge(&a, 0, 3));
	CHECK(find_edge(&a, 0, 4) < 0);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);

	/* 50 x 50 triangles: E = 2n(n+1) + n^2, border 4n, one component. */
	make_grid(&m, 50, 1);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 2 * 50 * 51 + 50 * 50);
	CHECK_INT(a.nborder, 200);
	CHECK_INT(a.nnonmanifold, 0);
	uint32_t *label = malloc(m.nf * sizeof *label);
	CHECK_INT(fct_adj_components(&a, label, &err), 1);
	CHECK_INT(fct_mesh_degenerate_faces(&m, 1e-12, NULL, &err), 0);
	check_invariants(&m, &a);
	free(label);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

/* Three triangles on the edge (0,1). */
static void test_fan(void)
{
	static const int faces[] = {0, 1, 2, -1, 0, 1, 3, -1, 1, 0, 4, -1};
	struct fct_mesh m;
	make_mesh(&m, 5, NULL, faces, sizeof faces / sizeof *faces);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 7);
	CHECK_INT(a.nnonmanifold, 1);
	CHECK_INT(a.nborder, 6);
	CHECK_INT(a.nmanifold, 0);
	CHECK_INT(find_edge(&a, 0, 1), 0);
	CHECK_INT(fct_adj_edge_nfaces(&a, 0), 3);
	uint32_t label[3];
	CHECK_INT(fct_adj_components(&a, label, &err), 1);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

/* A closed fan of 100 triangles around vertex 0, its rim visited out of
 * index order, and 40 more triangles on the spoke (0 1): vertex 0 starts
 * 140 edges (more than the sort's insertion runs take) and the spoke has
 * 42 faces, which must stay in face order. */
static void test_wide_fan(void)
{
	enum { RIM = 100, EXTRA = 40 };
	int faces[4 * (RIM + EXTRA)], n = 0;
	for (int i = 0; i < RIM; i++) {
		faces[n++] = 0;
		faces[n++] = 1 + (i * 37) % RIM;
		faces[n++] = 1 + ((i + 1) * 37) % RIM;
		faces[n++] = -1;
	}
	for (int j = 0; j < EXTRA; j++) {
		faces[n++] = j % 2 ? 1 : 0;
		faces[n++] = j % 2 ? 0 : 1;
		faces[n++] = RIM + 1 + j;
		faces[n++] = -1;
	}
	struct fct_mesh m;
	make_mesh(&m, RIM + 1 + EXTRA, NULL, faces, (size_t)n);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 2 * RIM + 2 * EXTRA);
	CHECK_INT(a.nnonmanifold, 1);
	CHECK_INT(a.nmanifold, RIM - 1);        /* the spokes; the rim is border */
	CHECK_INT(a.nborder, RIM + 2 * EXTRA);
	long spoke = find_edge(&a, 0, 1);
	CHECK_INT(fct_adj_edge_nfaces(&a, (size_t)spoke), 2 + EXTRA);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

/* Triangles (3 4 5), (0 1 2), (2 1 7) and (5 8 9): the second and third
 * share an edge, the fourth touches the first at a vertex only; vertex 6 is
 * isolated. */
static void test_components(void)
{
	static const int faces[] = {3, 4, 5, -1, 0, 1, 2, -1, 2, 1, 7, -1, 5, 8, 9, -1};
	struct fct_mesh m;
	make_mesh(&m, 10, NULL, faces, sizeof faces / sizeof *faces);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	uint32_t label[4];
	CHECK_INT(fct_adj_components(&a, label, &err), 3);
	CHECK_INT(label[0], 0);
	CHECK_INT(label[1], 1);
	CHECK_INT(label[2], 1);
	CHECK_INT(label[3], 2);
	CHECK_INT(fct_adj_isolated_vertices(&a), 1);
	CHECK_INT(a.vert_fstart[7] - a.vert_fstart[6], 0);
	CHECK_INT(a.vert_fstart[6] - a.vert_fstart[5], 2);   /* vertex 5: faces 0 and 3 */
	CHECK_INT(a.ne, 11);
	CHECK_INT(a.nmanifold, 1);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);

	/* Two disjoint triangles and an isolated vertex. */
	static const int two[] = {0, 1, 2, -1, 3, 4, 5, -1};
	make_mesh(&m, 7, NULL, two, sizeof two / sizeof *two);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(fct_adj_components(&a, label, &err), 2);
	CHECK_INT(fct_adj_isolated_vertices(&a), 1);
	CHECK_INT(a.nborder, 6);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

/* (0 1 2) and the degenerate (1 2 2): the zero-length step is skipped and
 * (1 2) is walked three times. */
static void test_degenerate(void)
{
	static const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
	static const int faces[] = {0, 1, 2, -1, 1, 2, 2, -1, 0, 1, 3, -1, 3, -1};
	struct fct_mesh m;
	make_mesh(&m, 4, pos, faces, sizeof faces / sizeof *faces);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	long e12 = find_edge(&a, 1, 2);
	CHECK_INT(a.nskipped, 2);    /* (2 2) in face 1 and the one-corner face 3 */
	CHECK_INT(a.face_e[4], FCT_ADJ_NONE);
	CHECK_INT(a.face_e[3], e12);
	CHECK_INT(a.face_e[5], e12);
	CHECK_INT(fct_adj_edge_nfaces(&a, (size_t)e12), 3);
	CHECK_INT(a.edge_f[a.edge_fstart[e12] + 1], 1);
	CHECK_INT(a.edge_f[a.edge_fstart[e12] + 2], 1);
	CHECK_INT(a.nnonmanifold, 1);
	/* Vertex 2 lists face 1 once. */
	CHECK_INT(a.vert_fstart[3] - a.vert_fstart[2], 2);
	uint32_t label[4];
	/* Face 2, collinear (0 1 3), shares (0,1) with face 0; face 3 has no edge. */
	CHECK_INT(fct_adj_components(&a, label, &err), 2);
	CHECK_INT(label[3], 1);
	/* Degenerate: the repeated vertex, the zero-area face, the one-corner face. */
	unsigned char flag[4];
	CHECK_INT(fct_mesh_degenerate_faces(&m, 1e-12, flag, &err), 3);
	CHECK_INT(flag[0], 0);
	CHECK_INT(flag[1], 1);
	CHECK_INT(flag[2], 1);
	CHECK_INT(flag[3], 1);
	/* The threshold is inclusive: area 0.5 is degenerate at 0.5, not below. */
	CHECK_INT(fct_mesh_degenerate_faces(&m, 0.5, flag, &err), 4);
	CHECK_INT(fct_mesh_degenerate_faces(&m, 0.4999, flag, &err), 3);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

static void test_duplicates(void)
{
	/* Faces 2 (reversed), 3 (equal) and 4 (repeated vertex) repeat earlier sets. */
	static const int faces[] = {0, 1, 2, -1, 0, 2, 3, -1, 2, 1, 0, -1, 0, 2, 3, -1,
	                            1, 2, 0, 0, -1, 0, 1, 3, -1};
	struct fct_mesh m;
	make_mesh(&m, 4, NULL, faces, sizeof faces / sizeof *faces);
	uint32_t first[6];
	CHECK_INT(fct_mesh_duplicate_faces(&m, first, &err), 3);
	static const uint32_t want[6] = {0, 1, 0, 1, 0, 5};
	CHECK(!memcmp(first, want, sizeof want));
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	/* (0,1) is walked by faces 0, 2, 4 and 5. */
	long e01 = find_edge(&a, 0, 1);
	CHECK_INT(e01, 0);
	CHECK_INT(fct_adj_edge_nfaces(&a, 0), 4);
	CHECK_INT(a.edge_f[3], 5);
	uint32_t label[6];
	CHECK_INT(fct_adj_components(&a, label, &err), 1);
	check_invariants(&m, &a);
	fct_adj_free(&a);
	fct_mesh_free(&m);
}

static void test_empty(void)
{
	struct fct_mesh m;
	struct fct_adj a;
	make_mesh(&m, 0, NULL, NULL, 0);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.ne, 0);
	CHECK_INT(fct_adj_components(&a, NULL, &err), 0);
	CHECK_INT(fct_adj_isolated_vertices(&a), 0);
	CHECK_INT(fct_mesh_duplicate_faces(&m, NULL, &err), 0);
	fct_adj_free(&a);
	fct_mesh_free(&m);

	make_mesh(&m, 3, NULL, NULL, 0);
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(fct_adj_isolated_vertices(&a), 3);
	fct_adj_free(&a);
	fct_adj_free(&a);   /* freeing twice and freeing NULL are harmless */
	fct_adj_free(NULL);
	fct_mesh_free(&m);
}

/* Small pieces dropped: a strip of three quads (6 triangles), a triangle
 * apart, a quad of two triangles apart and an isolated vertex; each face
 * labelled with its index, each vertex with its own, to see what follows. */
static void test_drop_small_pieces(void)
{
	static const int faces[] = {
		0, 1, 5, -1, 0, 5, 4, -1, 1, 2, 6, -1, 1, 6, 5, -1, 2, 3, 7, -1, 2, 7, 6, -1,  /* strip */
		8, 9, 10, -1,                                                              /* triangle */
		11, 12, 13, -1, 11, 13, 14, -1,                                            /* quad */
	};
	struct fct_mesh m;
	make_mesh(&m, 16, NULL, faces, sizeof faces / sizeof *faces);   /* 15: isolated */
	struct fct_prop *fl = fct_elem_add_scalar(&m.face, "label", FCT_INT32, &err);
	struct fct_prop *vl = fct_elem_add_scalar(&m.vertex, "label", FCT_INT32, &err);
	CHECK(fl && vl);
	for (size_t f = 0; f < m.nf; f++)
		fct_prop_set(fl, f, (double)f);
	for (size_t v = 0; v < m.nv; v++)
		fct_prop_set(vl, v, (double)v);
	size_t pieces = 99;
	/* 0 and 1 drop nothing. */
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 1, &pieces, &err), 0);
	CHECK_INT(pieces, 0);
	CHECK_INT(m.nf, 9);
	/* Fewer than 3 faces: the triangle and the quad go, with their 7
	 * vertices; the isolated vertex stays. */
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 3, &pieces, &err), 3);
	CHECK_INT(pieces, 2);
	CHECK_INT(m.nf, 6);
	CHECK_INT(m.nv, 9);
	fl = fct_elem_find(&m.face, "label");
	vl = fct_elem_find(&m.vertex, "label");
	for (size_t f = 0; f < m.nf; f++)
		CHECK_INT((long)fct_prop_get(fl, f), (long)f);
	for (size_t v = 0; v < 8; v++)
		CHECK_INT((long)fct_prop_get(vl, v), (long)v);
	CHECK_INT((long)fct_prop_get(vl, 8), 15);
	CHECK_INT(m.fvert[m.fstart[5] + 2], 6);
	fct_mesh_free(&m);
	/* Every piece small: the largest stays (the first of equals). */
	make_mesh(&m, 16, NULL, faces, sizeof faces / sizeof *faces);
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 100, &pieces, &err), 3);
	CHECK_INT(pieces, 2);
	CHECK_INT(m.nf, 6);
	fct_mesh_free(&m);
	/* Two lone triangles, or three and a piece of two: the small pieces
	 * hold half the faces or more, they are the surface and stay. */
	static const int two[] = { 0, 1, 2, -1, 3, 4, 5, -1 };
	make_mesh(&m, 6, NULL, two, sizeof two / sizeof *two);
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 2, &pieces, &err), 0);
	CHECK_INT(pieces, 0);
	CHECK_INT(m.nf, 2);
	CHECK_INT(m.nv, 6);
	fct_mesh_free(&m);
	static const int scattered[] = { 0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1, 10, 12, 11, -1 };
	make_mesh(&m, 13, NULL, scattered, sizeof scattered / sizeof *scattered);
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 2, &pieces, &err), 0);
	CHECK_INT(m.nf, 5);
	fct_mesh_free(&m);
	/* Two lone triangles beside a piece of three: 2 of 5 faces, debris. */
	static const int beside[] = { 0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 7, 9, 8, -1, 8, 9, 10, -1 };
	make_mesh(&m, 11, NULL, beside, sizeof beside / sizeof *beside);
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 2, &pieces, &err), 2);
	CHECK_INT(pieces, 2);
	CHECK_INT(m.nf, 3);
	CHECK_INT(m.nv, 5);
	fct_mesh_free(&m);
	/* No faces: nothing to do. */
	fct_mesh_init(&m);
	CHECK_INT(fct_mesh_drop_small_pieces(&m, 5, &pieces, &err), 0);
	fct_mesh_free(&m);
}

/* Vertices at one position: counted after the first, each pointed at the
 * first; welding them joins a soup's two triangles along their diagonal. */
static void test_duplicate_vertices(void)
{
	static const double pos[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, -0.0, 0, 0 };
	static const int soup[] = { 0, 1, 2, -1, 3, 4, 5, -1 };
	struct fct_mesh m;
	make_mesh(&m, 7, pos, soup, sizeof soup / sizeof *soup);
	uint32_t first[7];
	/* -0.0 is another bit pattern than 0: no duplicate of vertex 0 */
	CHECK_INT(fct_mesh_duplicate_vertices(&m, first, &err), 2);
	static const uint32_t want[] = { 0, 1, 2, 0, 2, 5, 6 };
	for (int v = 0; v < 7; v++)
		CHECK_INT(first[v], want[v]);
	CHECK_INT(fct_mesh_weld_exact(&m, &err), 2);
	CHECK_INT(m.nv, 5);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	CHECK_INT(a.nmanifold, 1);   /* the diagonal, shared now */
	CHECK_INT(a.nborder, 4);
	fct_adj_free(&a);
	CHECK_INT(fct_mesh_duplicate_vertices(&m, NULL, &err), 0);
	fct_mesh_free(&m);
}

int main(void)
{
	test_cube();
	test_grid();
	test_fan();
	test_wide_fan();
	test_components();
	test_degenerate();
	test_duplicates();
	test_empty();
	test_drop_small_pieces();
	test_duplicate_vertices();
	CHECK_DONE();
}
