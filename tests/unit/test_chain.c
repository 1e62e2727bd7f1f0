/* test_chain.c - patch boundaries, chains and their simplification (chain.h)
 * on hand-made labelled meshes whose answers are known, and on a rendered
 * noisy view of mkscene's room labelled with the true patches. */
#include <stdlib.h>

#include "io/camera.h"
#include "planar/chain.h"
#include "check.h"
#include "depth/depthmesh.h"
#include "io/meshio.h"
#include "geom/planes.h"
#include "geom/predicates.h"
#include "core/rng.h"
#include "scene/scene.h"

static struct fct_err err;

/* A grid of (nx + 1) x (ny + 1) vertices at integer (x0 + i, y0 + j), moved by
 * uniform noise in [-noise, noise] on every axis, two triangles per cell
 * wound counter-clockwise seen from +z, the cell (i, j) labelled
 * label(x0 + i, y0 + j); nplanes planes z = 0 with normal +z. */
typedef int (*labeller)(int x, int y);

static void grid(struct fct_mesh *m, int x0, int y0, int nx, int ny, double noise, labeller label,
                 int nplanes)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	fct_mesh_init(m);
	for (int j = 0; j <= ny; j++)
		for (int i = 0; i <= nx; i++) {
			double n[3];
			for (int k = 0; k < 3; k++)
				n[k] = noise * (2 * fct_rng_uniform(&r) - 1);
			fct_mesh_add_vertex(m, x0 + i + n[0], y0 + j + n[1], n[2], &err);
		}
	int32_t *lab = malloc(sizeof *lab * 2 * (size_t)nx * (size_t)ny);
	size_t f = 0;
	for (int j = 0; j < ny; j++)
		for (int i = 0; i < nx; i++) {
			uint32_t a = (uint32_t)(j * (nx + 1) + i), b = a + 1, c = b + (uint32_t)nx + 1,
			         d = a + (uint32_t)nx + 1;
			uint32_t t1[3] = { a, b, c }, t2[3] = { a, c, d };
			fct_mesh_add_face(m, t1, 3, &err);
			fct_mesh_add_face(m, t2, 3, &err);
			lab[f++] = label(x0 + i, y0 + j);
			lab[f++] = label(x0 + i, y0 + j);
		}
	CHECK_INT(fct_patches_set(m, lab, &err), 0);
	free(lab);
	struct fct_plane *pl = calloc((size_t)nplanes + 1, sizeof *pl);
	for (int p = 0; p < nplanes; p++)
		pl[p].n[2] = 1;
	CHECK_INT(fct_planes_set(m, pl, (size_t)nplanes, &err), 0);
	free(pl);
}

/* The wireframe's edges. */
struct wire {
	size_t n;
	int32_t *v1, *v2, *p1, *p2;
};

static int wire_get(const struct fct_mesh *m, struct wire *w)
{
	const struct fct_elem *e = fct_mesh_find_elem(m, "edge");
	if (!e)
		return -1;
	w->n = e->count;
	const char *names[4] = { "vertex1", "vertex2", "patch1", "patch2" };
	int32_t **col[4] = { &w->v1, &w->v2, &w->p1, &w->p2 };
	for (int k = 0; k < 4; k++) {
		const struct fct_prop *p = fct_elem_find(e, names[k]);
		if (!p || p->type != FCT_INT32)
			return -1;
		*col[k] = p->data;
	}
	return 0;
}

static int edges_between(const struct wire *w, int32_t a, int32_t b)
{
	int n = 0;
	for (size_t i = 0; i < w->n; i++)
		n += (w->p1[i] == a && w->p2[i] == b) || (w->p1[i] == b && w->p2[i] == a);
	return n;
}

/* The invariants every output must meet: labels valid (patch1 >= 0,
 * patch2 >= -1, different, both < nplanes), vertex indices valid, no vertex
 * pair twice (each chain segment once), and every patch's edges closed: in-
 * and out-degree equal at each vertex, taking patch1's edges as they run and
 * patch2's reversed. */
static void check_wire(const struct fct_mesh *m, int nplanes)
{
	struct wire w;
	CHECK_INT(wire_get(m, &w), 0);
	int ok_lab = 1, ok_idx = 1, ok_once = 1, ok_deg = 1;
	for (size_t i = 0; i < w.n; i++) {
		ok_lab &= w.p1[i] >= 0 && w.p1[i] < nplanes && w.p2[i] >= -1 && w.p2[i] < nplanes &&
		          w.p1[i] != w.p2[i];
		ok_idx &= w.v1[i] >= 0 && (size_t)w.v1[i] < m->nv && w.v2[i] >= 0 && (size_t)w.v2[i] < m->nv &&
		          w.v1[i] != w.v2[i];
		for (size_t j = 0; j < i; j++) {
			ok_once &= !((w.v1[i] == w.v1[j] && w.v2[i] == w.v2[j]) ||
			             (w.v1[i] == w.v2[j] && w.v2[i] == w.v1[j]));
		}
	}
	CHECK(ok_lab);
	CHECK(ok_idx);
	CHECK(ok_once);
	if (!ok_idx)
		return;
	long *deg = calloc(m->nv + 1, sizeof *deg);
	for (int p = 0; p < nplanes; p++) {
		for (size_t i = 0; i < w.n; i++) {
			if (w.p1[i] == p)
				deg[w.v1[i]]++, deg[w.v2[i]]--;
			else if (w.p2[i] == p)
				deg[w.v2[i]]++, deg[w.v1[i]]--;
		}
		for (size_t v = 0; v < m->nv; v++)
			ok_deg &= deg[v] == 0;
	}
	CHECK(ok_deg);
	free(deg);
}

/* Conflicting pairs of edges of one patch projected on its plane (the
 * plane frame of chain.c is not assumed: any frame of the plane will do),
 * or with image set, in the vertices' image coordinates s t. */
static size_t crossings_in(const struct fct_mesh *m, int nplanes, int image)
{
	const struct fct_prop *ps = fct_elem_find(&m->vertex, "s"), *pt = fct_elem_find(&m->vertex, "t");
	if (image && (!ps || !pt))
		return (size_t)-1;
	struct wire w;
	struct fct_plane *pl;
	size_t npl;
	if (wire_get(m, &w) || fct_planes_get(m, &pl, &npl, &err))
		return (size_t)-1;
	size_t bad = 0;
	for (int p = 0; p < nplanes && (size_t)p < npl; p++) {
		double u[3], v[3], *n = pl[p].n;
		double ax[3] = { fabs(n[0]) < 0.6, fabs(n[0]) >= 0.6, 0 };
		u[0] = ax[1] * n[2] - ax[2] * n[1];
		u[1] = ax[2] * n[0] - ax[0] * n[2];
		u[2] = ax[0] * n[1] - ax[1] * n[0];
		v[0] = n[1] * u[2] - n[2] * u[1];
		v[1] = n[2] * u[0] - n[0] * u[2];
		v[2] = n[0] * u[1] - n[1] * u[0];
		for (size_t i = 0; i < w.n; i++) {
			if (w.p1[i] != p && w.p2[i] != p)
				continue;
			for (size_t j = i + 1; j < w.n; j++) {
				if (w.p1[j] != p && w.p2[j] != p)
					continue;
				int32_t id[4] = { w.v1[i], w.v2[i], w.v1[j], w.v2[j] };
				double q[4][2];
				for (int k = 0; k < 4; k++) {
					const double *x = m->xyz + 3 * (size_t)id[k];
					q[k][0] = x[0] * u[0] + x[1] * u[1] + x[2] * u[2];
					q[k][1] = x[0] * v[0] + x[1] * v[1] + x[2] * v[2];
					if (image) {
						q[k][0] = fct_prop_get(ps, (size_t)id[k]);
						q[k][1] = fct_prop_get(pt, (size_t)id[k]);
					}
				}
				bad += (size_t)fct_segments_conflict(q[0], q[1], q[2], q[3], (uint32_t)id[0],
				                                     (uint32_t)id[1], (uint32_t)id[2], (uint32_t)id[3]);
			}
		}
	}
	free(pl);
	return bad;
}

static size_t crossings(const struct fct_mesh *m, int nplanes)
{
	return crossings_in(m, nplanes, 0);
}

/* Index of the output vertex nearest (x, y) in the plane z = 0, and its distance. */
static long nearest(const struct fct_mesh *m, double x, double y, double *dist)
{
	long best = -1;
	double bd = HUGE_VAL;
	for (size_t i = 0; i < m->nv; i++) {
		double d = hypot(m->xyz[3 * i] - x, m->xyz[3 * i + 1] - y);
		if (d < bd)
			bd = d, best = (long)i;
	}
	*dist = bd;
	return best;
}

static int simp(struct fct_mesh *m, double t, int topo, struct fct_chains *ch, struct fct_chain_stats *st)
{
	struct fct_chain_params p;
	fct_chain_params_default(&p);
	p.threshold = t;
	p.keep_topology = topo;
	p.keep_small_loops = 1;  /* these cases test the simplification itself */
	return fct_simpchain(m, &p, ch, st, &err);
}

static void test_conflict_predicate(void)
{
	double a[2] = { 0, 0 }, b[2] = { 2, 2 }, c[2] = { 0, 2 }, d[2] = { 2, 0 }, e[2] = { 3, 3 };
	double f[2] = { 1, 1 }, g[2] = { 4, 4 }, h[2] = { 1, 0 }, i[2] = { -1, -1 };
	CHECK_INT(fct_segments_conflict(a, b, c, d, 0, 1, 2, 3), 1);   /* X */
	CHECK_INT(fct_segments_conflict(a, c, b, d, 0, 2, 1, 3), 0);   /* parallel sides */
	CHECK_INT(fct_segments_conflict(a, b, b, d, 0, 1, 1, 3), 0);   /* corner */
	CHECK_INT(fct_segments_conflict(a, b, a, f, 0, 1, 0, 5), 1);   /* fold back at a shared end */
	CHECK_INT(fct_segments_conflict(a, b, a, i, 0, 1, 0, 5), 0);   /* straight on through a */
	CHECK_INT(fct_segments_conflict(a, b, b, a, 0, 1, 1, 0), 1);   /* the same pair */
	CHECK_INT(fct_segments_conflict(a, b, f, h, 0, 1, 5, 6), 1);   /* T: f on ab */
	CHECK_INT(fct_segments_conflict(a, f, b, g, 0, 5, 1, 6), 0);   /* collinear, apart */
	CHECK_INT(fct_segments_conflict(a, b, f, e, 0, 1, 5, 6), 1);   /* collinear, overlapping */
	CHECK_INT(fct_segments_conflict(a, b, b, e, 0, 1, 7, 6), 1);   /* touching at equal points, different ids */
	/* Exactness: (0.1, 0.1) is on the diagonal, one ulp above is not. */
	double p[2] = { 0.1, 0.1 }, q[2] = { 0.3, -1 }, r[2] = { 0.1, nextafter(0.1, 1) }, s[2] = { 0.3, 1 };
	double o[2] = { 0, 0 }, t[2] = { 1, 1 };
	CHECK_INT(fct_segments_conflict(o, t, p, q, 0, 1, 2, 3), 1);
	CHECK_INT(fct_segments_conflict(o, t, r, s, 0, 1, 2, 3), 0);
}

static int lab_half(int x, int y)
{
	(void)y;
	return x < 20 ? 0 : 1;
}

static int lab_stairs(int x, int y)
{
	return x < 20 + (y % 2) ? 0 : 1;
}

/* Two patches meeting along a straight noisy line: the line becomes one
 * segment between its two junctions on the border; the border of each
 * patch its corners. */
static void test_straight(void)
{
	struct fct_mesh m;
	struct fct_chains ch;
	struct fct_chain_stats st;
	grid(&m, 0, 0, 40, 10, 0.1, lab_half, 2);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.junctions, 2);
	CHECK_INT(ch.n, 3);
	CHECK_INT(ch.loops, 0);
	CHECK_INT(ch.boundary_edges, 10 + 2 * 40 + 2 * 10);
	CHECK_INT(ch.boundary_vertices, 11 + 2 * 40 + 2 * 10 - 2);
	CHECK_INT(m.nv, 6);
	CHECK_INT(st.segments, 7);
	check_wire(&m, 2);
	struct wire w;
	wire_get(&m, &w);
	CHECK_INT(edges_between(&w, 0, 1), 1);
	CHECK_INT(edges_between(&w, 0, -1), 3);
	CHECK_INT(edges_between(&w, 1, -1), 3);
	for (size_t i = 0; i < w.n; i++)
		if (w.p2[i] == 1) {
			/* Patch 0 (x < 20) on the left: the line runs up, y 0 -> 10. */
			const double *a = m.xyz + 3 * (size_t)w.v1[i], *b = m.xyz + 3 * (size_t)w.v2[i];
			CHECK(fabs(a[0] - 20) <= 0.1 && fabs(a[1]) <= 0.1);
			CHECK(fabs(b[0] - 20) <= 0.1 && fabs(b[1] - 10) <= 0.1);
		}
	CHECK(st.max_dev <= st.tolerance);
	CHECK(st.max_dev > 0.05);   /* the noise is there */
	CHECK_INT(crossings(&m, 2), 0);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* A staircase of one-cell steps: one segment with t = 2; at t = 0.25 the
	 * steps' corners (distance 0.5 from the line and more) stay. */
	grid(&m, 0, 0, 40, 10, 0, lab_stairs, 2);
	CHECK_INT(simp(&m, 2, 1, &ch, &st), 0);
	wire_get(&m, &w);
	CHECK_INT(edges_between(&w, 0, 1), 1);
	CHECK(st.max_dev <= st.tolerance);
	CHECK(st.max_dev > 0.4);
	check_wire(&m, 2);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
	grid(&m, 0, 0, 40, 10, 0, lab_stairs, 2);
	CHECK_INT(simp(&m, 0.25, 1, &ch, &st), 0);
	wire_get(&m, &w);
	CHECK(edges_between(&w, 0, 1) >= 10);
	CHECK(st.max_dev <= st.tolerance);
	check_wire(&m, 2);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
}

static int lab_square(int x, int y)
{
	return x >= 10 && x < 20 && y >= 10 && y < 20;
}

/* A square patch inside another: a closed loop of 40 points that keeps
 * exactly its 4 corners; with a huge threshold, 3 points, and the outer
 * border's triangle must still leave the inner loop inside. */
static void test_square(void)
{
	struct fct_mesh m;
	struct fct_chains ch;
	struct fct_chain_stats st;
	grid(&m, 0, 0, 30, 30, 0, lab_square, 2);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.junctions, 0);
	CHECK_INT(ch.loops, 2);
	CHECK_INT(ch.n, 2);
	CHECK_INT(m.nv, 8);
	CHECK_INT(st.segments, 8);
	CHECK_INT(st.loop_points, 0);
	CHECK_INT(st.topology_points, 0);
	CHECK_NEAR(st.max_dev, 0, 0);
	double corners[8][2] = { { 0, 0 }, { 30, 0 }, { 30, 30 }, { 0, 30 },
	                         { 10, 10 }, { 20, 10 }, { 20, 20 }, { 10, 20 } };
	for (int k = 0; k < 8; k++) {
		double d;
		nearest(&m, corners[k][0], corners[k][1], &d);
		CHECK_NEAR(d, 0, 0);
	}
	struct wire w;
	wire_get(&m, &w);
	CHECK_INT(edges_between(&w, 0, 1), 4);
	CHECK_INT(edges_between(&w, 0, -1), 4);
	check_wire(&m, 2);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* Threshold 100 edge lengths: each loop would keep 3 points; the outer
	 * triangle's diagonal would cut the inner square, so points are added
	 * until nothing crosses. */
	grid(&m, 0, 0, 30, 30, 0, lab_square, 2);
	CHECK_INT(simp(&m, 100, 0, &ch, &st), 0);
	CHECK_INT(m.nv, 6);
	CHECK_INT(st.loop_points, 2);
	CHECK(crossings(&m, 2) > 0);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
	grid(&m, 0, 0, 30, 30, 0, lab_square, 2);
	CHECK_INT(simp(&m, 100, 1, &ch, &st), 0);
	CHECK_INT(st.loop_points, 2);
	CHECK(st.conflicts_plain > 0);
	CHECK(st.topology_points > 0);
	CHECK_INT(st.conflicts_left, 0);
	CHECK_INT(crossings(&m, 2), 0);
	check_wire(&m, 2);
	/* The inner loop is inside the outer one: its vertices are inside the
	 * polygon of the 0|-1 edges (even-odd, exact). */
	wire_get(&m, &w);
	int inside_all = 1;
	for (size_t i = 0; i < w.n; i++) {
		if (w.p2[i] != 1)
			continue;
		const double *q = m.xyz + 3 * (size_t)w.v1[i];
		int in = 0;
		for (size_t j = 0; j < w.n; j++) {
			if (w.p2[j] != -1)
				continue;
			const double *u = m.xyz + 3 * (size_t)w.v1[j], *v = m.xyz + 3 * (size_t)w.v2[j];
			double uu[2] = { u[0], u[1] }, vv[2] = { v[0], v[1] }, qq[2] = { q[0], q[1] };
			if ((u[1] > q[1]) != (v[1] > q[1])) {
				double o = fct_orient2d(uu, vv, qq);
				if (v[1] > u[1] ? o > 0 : o < 0)
					in ^= 1;
			}
		}
		inside_all &= in;
	}
	CHECK(inside_all);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
}

static int lab_three(int x, int y)
{
	return x < 15 ? 0 : y < 15 ? 1 : 2;
}

/* Three patches meeting at (15, 15): that junction and the three on the
 * border are kept, every chain between them is one straight segment. */
static void test_junction(void)
{
	struct fct_mesh m;
	struct fct_chains ch;
	struct fct_chain_stats st;
	grid(&m, 0, 0, 30, 30, 0.1, lab_three, 3);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.junctions, 4);
	CHECK_INT(ch.n, 6);
	CHECK_INT(ch.loops, 0);
	CHECK_INT(m.nv, 8);
	CHECK_INT(st.segments, 10);
	double d;
	nearest(&m, 15, 15, &d);
	CHECK(d <= 0.15);
	struct wire w;
	wire_get(&m, &w);
	CHECK_INT(edges_between(&w, 0, 1), 1);
	CHECK_INT(edges_between(&w, 0, 2), 1);
	CHECK_INT(edges_between(&w, 1, 2), 1);
	CHECK_INT(edges_between(&w, 0, -1), 3);
	CHECK_INT(edges_between(&w, 1, -1), 2);
	CHECK_INT(edges_between(&w, 2, -1), 2);
	check_wire(&m, 3);
	CHECK_INT(crossings(&m, 3), 0);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
}

/* Patch 0 above a boundary with patch 1 at y = 0 that dips to y = -2 for
 * x in [17, 23]; in the dip, patch 2 is the square [19, 21] x [-1, 1].  At
 * threshold 2.5 (2.85 units) plain end-point fit makes the 0|1 boundary the
 * straight line y = 0, through the square; ours must not. */
static int lab_dip(int x, int y)
{
	if (x >= 19 && x < 21 && y >= -1 && y < 1)
		return 2;
	int floor_y = x >= 17 && x < 23 ? -2 : 0;
	return y < floor_y ? 1 : 0;
}

static void test_dip(void)
{
	struct fct_mesh m;
	struct fct_chains ch;
	struct fct_chain_stats st;
	grid(&m, 0, -5, 40, 10, 0, lab_dip, 3);
	CHECK_INT(simp(&m, 2.5, 0, &ch, &st), 0);
	CHECK(crossings(&m, 3) > 0);
	struct wire w;
	wire_get(&m, &w);
	CHECK_INT(edges_between(&w, 0, 1), 1);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	grid(&m, 0, -5, 40, 10, 0, lab_dip, 3);
	CHECK_INT(simp(&m, 2.5, 1, &ch, &st), 0);
	CHECK_INT(crossings(&m, 3), 0);
	CHECK(st.conflicts_plain > 0);
	CHECK(st.topology_points >= 1);
	CHECK_INT(st.conflicts_left, 0);
	wire_get(&m, &w);
	CHECK(edges_between(&w, 0, 1) >= 2);
	CHECK(st.max_dev <= st.tolerance);
	check_wire(&m, 3);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
}

static int lab_one(int x, int y)
{
	(void)x, (void)y;
	return 0;
}

static int lab_unlabelled(int x, int y)
{
	(void)y;
	return x < 5 ? 0 : -1;
}

/* The small and odd cases. */
static void test_edge_cases(void)
{
	struct fct_mesh m;
	struct fct_chains ch;
	struct fct_chain_stats st;
	struct wire w;

	/* No patch property. */
	fct_mesh_init(&m);
	uint32_t tri[3] = { 0, 1, 2 };
	fct_mesh_add_vertex(&m, 0, 0, 0, &err);
	fct_mesh_add_vertex(&m, 1, 0, 0, &err);
	fct_mesh_add_vertex(&m, 0, 1, 0, &err);
	fct_mesh_add_face(&m, tri, 3, &err);
	CHECK_INT(simp(&m, 1, 1, NULL, &st), -1);
	CHECK(strstr(err.msg, "no patch property") != NULL);

	/* One face of patch 0: a loop of its three corners, in its winding. */
	int32_t lab0 = 0;
	fct_patches_set(&m, &lab0, &err);
	struct fct_plane pl = { { 0, 0, 1 }, 0, 1, 0 };
	fct_planes_set(&m, &pl, 1, &err);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(m.nv, 3);
	CHECK_INT(m.nf, 0);
	CHECK_INT(ch.loops, 1);
	CHECK_INT(wire_get(&m, &w), 0);
	CHECK_INT(w.n, 3);
	int ok = 1;
	for (size_t i = 0; i < w.n; i++)
		ok &= w.v2[i] == (w.v1[i] + 1) % 3 && w.p1[i] == 0 && w.p2[i] == -1;
	CHECK(ok);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* An empty labelled mesh: an empty wireframe. */
	fct_mesh_init(&m);
	fct_patches_set(&m, NULL, &err);
	CHECK(fct_elem_find(&m.face, "patch") != NULL);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(m.nv, 0);
	CHECK_INT(wire_get(&m, &w), 0);
	CHECK_INT(w.n, 0);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* All faces one patch: the border alone, its 4 corners. */
	grid(&m, 0, 0, 10, 10, 0.05, lab_one, 1);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.loops, 1);
	CHECK_INT(ch.junctions, 0);
	CHECK_INT(m.nv, 4);
	check_wire(&m, 1);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* Unlabelled faces (-1) beside patch 0: 0|-1 is a boundary with patch2
	 * -1; -1 against the outside is nobody's boundary.  Junctions where 0,
	 * -1 and the outside meet. */
	grid(&m, 0, 0, 10, 10, 0, lab_unlabelled, 1);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.junctions, 2);
	CHECK_INT(m.nv, 4);
	CHECK_INT(wire_get(&m, &w), 0);
	CHECK_INT(w.n, 4);
	CHECK_INT(edges_between(&w, 0, -1), 4);
	check_wire(&m, 1);
	fct_chains_free(&ch);
	fct_mesh_free(&m);

	/* A non-manifold fin: three faces of patches 0, 1, 2 on edge 0-1 (0 and
	 * 2 walk it 0 -> 1, 1 walks 1 -> 0): 0 pairs with 1, 2 faces the outside;
	 * with the six border edges, 8 boundary edges. */
	fct_mesh_init(&m);
	double vx[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, 1, 0 }, { 0.5, -1, 0 }, { 0.5, 0, 1 } };
	for (int i = 0; i < 5; i++)
		fct_mesh_add_vertex(&m, vx[i][0], vx[i][1], vx[i][2], &err);
	uint32_t f0[3] = { 0, 1, 2 }, f1[3] = { 1, 0, 3 }, f2[3] = { 0, 1, 4 };
	fct_mesh_add_face(&m, f0, 3, &err);
	fct_mesh_add_face(&m, f1, 3, &err);
	fct_mesh_add_face(&m, f2, 3, &err);
	int32_t lab3[3] = { 0, 1, 2 };
	fct_patches_set(&m, lab3, &err);
	struct fct_plane pl3[3] = { { { 0, 0, 1 }, 0, 1, 0 }, { { 0, 0, 1 }, 0, 1, 0 }, { { 0, -1, 0 }, 0, 1, 0 } };
	fct_planes_set(&m, pl3, 3, &err);
	CHECK_INT(simp(&m, 1, 1, &ch, &st), 0);
	CHECK_INT(ch.nonmanifold_edges, 1);
	CHECK_INT(ch.boundary_edges, 8);
	CHECK_INT(m.nv, 5);
	CHECK_INT(wire_get(&m, &w), 0);
	CHECK_INT(w.n, 8);
	int found01 = 0, found2 = 0;
	for (size_t i = 0; i < w.n; i++) {
		found01 += w.v1[i] == 0 && w.v2[i] == 1 && w.p1[i] == 0 && w.p2[i] == 1;
		found2 += w.v1[i] == 0 && w.v2[i] == 1 && w.p1[i] == 2 && w.p2[i] == -1;
	}
	CHECK_INT(found01, 1);
	CHECK_INT(found2, 1);
	fct_chains_free(&ch);
	fct_mesh_free(&m);
}

/* One polygon of 3000 points along y = exp(40 x), closed by a point above
 * the first: nearly all points crowd one corner of the bounding box (the
 * uniform grid of an earlier version put them in one cell and took
 * quadratic time).  Whatever is kept, nothing may cross. */
static void test_uneven(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	size_t n = 3000;
	uint32_t *f = malloc((n + 1) * sizeof *f);
	for (size_t i = 0; i < n; i++) {
		double x = (double)i / (double)n;
		fct_mesh_add_vertex(&m, x, exp(40 * x), 0, &err);
		f[i] = (uint32_t)i;
	}
	fct_mesh_add_vertex(&m, 0, exp(40), 0, &err);
	f[n] = (uint32_t)n;
	fct_mesh_add_face(&m, f, n + 1, &err);
	free(f);
	int32_t lab = 0;
	fct_patches_set(&m, &lab, &err);
	struct fct_plane pl = { { 0, 0, 1 }, 0, 1, 0 };
	fct_planes_set(&m, &pl, 1, &err);
	for (int pass = 0; pass < 2; pass++) {
		struct fct_mesh w;
		struct fct_chains ch;
		struct fct_chain_stats st;
		CHECK_INT(fct_mesh_copy(&w, &m, &err), 0);
		CHECK_INT(simp(&w, pass ? 1 : 0, 1, &ch, &st), 0);
		CHECK_INT(ch.loops, 1);
		CHECK(w.nv >= 3);
		CHECK(st.max_dev <= st.tolerance);
		CHECK_INT(crossings(&w, 1), 0);
		check_wire(&w, 1);
		fct_chains_free(&ch);
		fct_mesh_free(&w);
	}
	fct_mesh_free(&m);
}

static int lab_wiggle(int x, int y)
{
	return x < 20 + 3 * ((y / 4) % 2) ? 0 : 1;
}

/* A boundary that wiggles by 3 units between two patches: the default
 * threshold (1 mean edge) keeps its steps; a tolerance of its own for the
 * chain between the patches (as planedecim gives a crease that will be
 * moved onto its planes' line) keeps its two ends only, and the other
 * chains keep the default. */
static void test_chain_tolerance(void)
{
	struct fct_mesh m;
	struct fct_chains c;
	struct fct_chain_stats st;
	grid(&m, 0, 0, 40, 24, 0, lab_wiggle, 2);
	int32_t *patch = NULL;
	int present = 0;
	CHECK_INT(fct_patches_get(&m, &patch, &present, 2, &err), 0);
	for (int own = 0; own < 2; own++) {
		CHECK_INT(fct_chains_extract(&c, &m, patch, &err), 0);
		double *tol = calloc(c.n, sizeof *tol);
		size_t between = c.n;
		for (size_t i = 0; i < c.n; i++)
			if (c.left[i] >= 0 && c.right[i] >= 0)
				between = i, tol[i] = own ? 10 : 0;
		CHECK(between < c.n);
		struct fct_chain_params p;
		fct_chain_params_default(&p);
		p.threshold = 1;
		p.tolerance = tol;
		CHECK_INT(fct_chains_simplify(&c, &m, patch, NULL, 0, &p, &st, &err), 0);
		size_t kept = 0, kept_other = 0;
		for (size_t i = 0; i < c.n; i++)
			for (size_t q = c.start[i]; q < c.start[i + 1]; q++)
				*(i == between ? &kept : &kept_other) += c.keep[q];
		if (own)
			CHECK_INT(kept, 2);
		else
			CHECK(kept > 10);
		CHECK(kept_other >= 8);  /* the outer border's corners and junctions */
		free(tol);
		fct_chains_free(&c);
	}
	free(patch);
	fct_mesh_free(&m);
}

/* The same wiggling boundary with a tolerance that keeps its two ends
 * only, and a stretch of it forced (keep_vertex: the points with y in
 * 10..13, as planedecim mends an outline where it crossed): those points
 * are kept, and nothing else changes, on that chain or the others. */
static void test_keep_vertex(void)
{
	struct fct_mesh m;
	struct fct_chains c;
	struct fct_chain_stats st;
	grid(&m, 0, 0, 40, 24, 0, lab_wiggle, 2);
	int32_t *patch = NULL;
	int present = 0;
	CHECK_INT(fct_patches_get(&m, &patch, &present, 2, &err), 0);
	unsigned char *force = calloc(m.nv, 1);
	size_t kept_other[2] = { 0, 0 }, nforced = 0;
	for (int forced = 0; forced < 2; forced++) {
		CHECK_INT(fct_chains_extract(&c, &m, patch, &err), 0);
		double *tol = calloc(c.n, sizeof *tol);
		size_t between = c.n;
		for (size_t i = 0; i < c.n; i++)
			if (c.left[i] >= 0 && c.right[i] >= 0)
				between = i, tol[i] = 10;
		CHECK(between < c.n);
		if (forced)
			for (size_t q = c.start[between] + 1; q + 1 < c.start[between + 1]; q++) {
				double y = m.xyz[3 * (size_t)c.vert[q] + 1];
				if (y >= 10 && y <= 13)
					force[c.vert[q]] = 1, nforced++;
			}
		struct fct_chain_params p;
		fct_chain_params_default(&p);
		p.threshold = 1;
		p.tolerance = tol;
		p.keep_vertex = force;
		CHECK_INT(fct_chains_simplify(&c, &m, patch, NULL, 0, &p, &st, &err), 0);
		size_t kept = 0, kept_forced = 0;
		for (size_t i = 0; i < c.n; i++)
			for (size_t q = c.start[i]; q < c.start[i + 1]; q++) {
				if (i != between) {
					kept_other[forced] += c.keep[q];
					continue;
				}
				kept += c.keep[q];
				kept_forced += c.keep[q] && force[c.vert[q]];
			}
		CHECK_INT(kept, 2 + nforced);
		CHECK_INT(kept_forced, nforced);
		free(tol);
		fct_chains_free(&c);
	}
	CHECK(nforced >= 5);   /* 10..13 and the step at y = 12 */
	CHECK_INT(kept_other[1], kept_other[0]);
	free(force);
	free(patch);
	fct_mesh_free(&m);
}

/* A rendered view of mkscene's room with Kinect-class noise, meshed like
 * dm2mesh, each face labelled with the true patch of the majority of its
 * corners' pixels: the invariants on a real-sized boundary.  FCT_TEST_DUMP=
 * file writes the labelled mesh; FCT_TEST_VERBOSE prints the figures. */
static int same_chains(const struct fct_chains *a, const struct fct_chains *b);

/* The chains of m's patches simplified with its planes and the cache. */
static void simplify_with(const struct fct_mesh *m, struct fct_chain_cache *cache,
                          struct fct_chains *c, struct fct_chain_stats *st)
{
	int32_t *patch;
	int present;
	struct fct_plane *pl;
	size_t npl;
	CHECK_INT(fct_patches_get(m, &patch, &present, -1, &err), 0);
	CHECK_INT(fct_planes_get(m, &pl, &npl, &err), 0);
	CHECK_INT(fct_chains_extract(c, m, patch, &err), 0);
	struct fct_chain_params p;
	fct_chain_params_default(&p);
	p.cache = cache;
	CHECK_INT(fct_chains_simplify(c, m, patch, pl, npl, &p, st, &err), 0);
	free(patch);
	free(pl);
}

/* The crossings cached from one simplification serve the next only where
 * its chains are the same bit for bit: the result is a fresh
 * simplification's, with the cache, after it, and with half the points
 * moved 5 cm (which changes the crossings the input has). */
static void check_cache(struct fct_mesh *m)
{
	struct fct_chain_cache cache = { NULL, 0 };
	struct fct_chains c0, c1;
	struct fct_chain_stats s0, s1;
	simplify_with(m, NULL, &c0, &s0);
	for (int pass = 0; pass < 2; pass++) {
		simplify_with(m, &cache, &c1, &s1);
		CHECK(same_chains(&c0, &c1));
		CHECK_INT(s1.conflicts_left, s0.conflicts_left);
		CHECK_INT(s1.conflicts_left_image, s0.conflicts_left_image);
		CHECK_INT(s1.topology_points, s0.topology_points);
		CHECK_INT(s1.cached_checks, pass ? cache.n : 0);
		CHECK(cache.n > 10);
		fct_chains_free(&c1);
	}
	size_t made = cache.n;
	for (size_t v = 0; v < m->nv / 2; v++)
		m->xyz[3 * v + 2] += 0.05 * sin(12.9898 * (double)v);
	struct fct_chains c2;
	struct fct_chain_stats s2;
	simplify_with(m, NULL, &c2, &s2);
	simplify_with(m, &cache, &c1, &s1);
	CHECK(same_chains(&c2, &c1));
	CHECK(s2.conflicts_left != s0.conflicts_left);
	CHECK_INT(s1.conflicts_left, s2.conflicts_left);
	CHECK_INT(s1.topology_points, s2.topology_points);
	CHECK(s1.cached_checks > 0 && s1.cached_checks < made);
	fct_chains_free(&c0), fct_chains_free(&c1), fct_chains_free(&c2);
	fct_chain_cache_free(&cache);
}

static void test_room(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 320, 240, 262.5, 262.5, 159.5, 119.5, 0, 0 };
	double pose[12];
	fct_scene_view_pose(&s, 0, 1, pose);
	struct fct_render r;
	CHECK_INT(fct_scene_render(&s, &cam, pose, &r, &err), 0);
	struct fct_scene_noise nz = { 0, 0.0015, 0, 0, 90, 0, 0 , {0}};
	size_t npx = (size_t)cam.width * (size_t)cam.height;
	struct fct_image img;
	CHECK_INT(fct_image_alloc(&img, cam.width, cam.height, 1, FCT_PIX_F32, &err), 0);
	double *noisy = malloc(npx * sizeof *noisy);
	fct_depth_noise(&nz, 1, 0, r.depth, NULL, r.cosine, noisy, npx, NULL);
	for (size_t i = 0; i < npx; i++)
		((float *)img.data)[i] = (float)noisy[i];
	free(noisy);
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	struct fct_mesh m;
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &dp, NULL, &err), 0);
	fct_image_free(&img);
	for (size_t v = 0; v < m.nv; v++)
		fct_pose_apply(pose, m.xyz + 3 * v, m.xyz + 3 * v);

	int32_t *truth, *lab = malloc((m.nf ? m.nf : 1) * sizeof *lab);
	int present;
	CHECK_INT(fct_patches_get(&s.mesh, &truth, &present, -1, &err), 0);
	const struct fct_prop *ps = fct_elem_find(&m.vertex, "s"), *pt = fct_elem_find(&m.vertex, "t");
	CHECK(ps && pt);
	for (size_t f = 0; f < m.nf; f++) {
		int32_t l[3];
		for (int k = 0; k < 3; k++) {
			uint32_t v = m.fvert[m.fstart[f] + (uint32_t)k];
			long u = lround(fct_prop_get(ps, v) * cam.width - 0.5);
			long w = lround((1 - fct_prop_get(pt, v)) * cam.height - 0.5);
			int32_t face = r.face[(size_t)w * (size_t)cam.width + (size_t)u];
			l[k] = face < 0 ? -1 : truth[face];
		}
		lab[f] = l[1] == l[2] ? l[1] : l[0];
	}
	free(truth);
	fct_render_free(&r);
	CHECK_INT(fct_patches_set(&m, lab, &err), 0);
	free(lab);
	struct fct_plane *pl;
	size_t npl;
	CHECK_INT(fct_planes_get(&s.mesh, &pl, &npl, &err), 0);
	CHECK_INT(fct_planes_set(&m, pl, npl, &err), 0);
	free(pl);
	fct_scene_free(&s);
	size_t nv = m.nv;
	if (getenv("FCT_TEST_DUMP"))
		fct_mesh_write_file(&m, getenv("FCT_TEST_DUMP"), 0, &err);

	/* Simplified at thresholds 1 and 3 (the default). */
	for (int pass = 0; pass < 2; pass++) {
		struct fct_mesh w;
		CHECK_INT(fct_mesh_copy(&w, &m, &err), 0);
		struct fct_chains ch;
		struct fct_chain_stats st;
		double t = pass ? 3 : 1;
		CHECK_INT(simp(&w, t, 1, &ch, &st), 0);
		if (getenv("FCT_TEST_VERBOSE"))
			printf("t %g: boundary vertices %zu kept %zu junctions %zu chains %zu loops %zu plain %zu "
			       "topology %zu left %zu/%zu dev %g tol %g\n", t, ch.boundary_vertices, w.nv,
			       ch.junctions, ch.n, ch.loops, st.conflicts_plain, st.topology_points,
			       st.conflicts_left, st.conflicts_left_image, st.max_dev, st.tolerance);
		CHECK(ch.boundary_vertices > 3500);
		CHECK(ch.junctions >= 30);
		CHECK(st.max_dev <= st.tolerance);
		CHECK(st.max_dev >= 0.9 * st.tolerance);
		/* The pixel staircases collapse: at t = 1 at least 3 times fewer
		 * vertices than the boundary had, at t = 3 at least 8 times. */
		CHECK(w.nv * (pass ? 8 : 3) < ch.boundary_vertices);
		CHECK(w.nv * (pass ? 60 : 25) < nv);
		/* In image coordinates the pixel grid's boundary is simple, and so
		 * the simplified one must be; in the patch planes the noise folds a
		 * few original edges over each other, and exactly those conflicts
		 * remain. */
		CHECK_INT(st.conflicts_left_image, 0);
		CHECK_INT(crossings_in(&w, (int)npl, 1), 0);
		CHECK(st.conflicts_left > 0);
		CHECK_INT(crossings(&w, (int)npl), st.conflicts_left);
		CHECK(st.topology_points > 0);
		check_wire(&w, (int)npl);
		fct_chains_free(&ch);
		fct_mesh_free(&w);
	}
	check_cache(&m);
	fct_mesh_free(&m);
}

/* Two chains are the same, point for point and side for side. */
static int same_chains(const struct fct_chains *a, const struct fct_chains *b)
{
	if (a->n != b->n || a->mean_edge != b->mean_edge || a->boundary_edges != b->boundary_edges ||
	    a->junctions != b->junctions || a->loops != b->loops)
		return 0;
	size_t np = a->start[a->n];
	return !memcmp(a->start, b->start, (a->n + 1) * sizeof *a->start) &&
	       !memcmp(a->vert, b->vert, np * sizeof *a->vert) && !memcmp(a->keep, b->keep, np) &&
	       !memcmp(a->left, b->left, a->n * sizeof *a->left) &&
	       !memcmp(a->right, b->right, a->n * sizeof *a->right) && !memcmp(a->closed, b->closed, a->n);
}

/* Extraction with the caller's adjacency, reused for two labellings, gives
 * fct_chains_extract's chains; a copy is the same chains, frozen and all. */
static void test_extract_adj_copy(void)
{
	struct fct_mesh m;
	grid(&m, 0, 0, 40, 24, 0, lab_wiggle, 2);
	int32_t *patch = NULL;
	int present = 0;
	CHECK_INT(fct_patches_get(&m, &patch, &present, 2, &err), 0);
	struct fct_adj a;
	CHECK_INT(fct_adj_build(&a, &m, &err), 0);
	for (int pass = 0; pass < 2; pass++) {
		if (pass)
			for (size_t f = 0; f < m.nf; f += 7)
				patch[f] = -1;
		struct fct_chains c1, c2, c3;
		CHECK_INT(fct_chains_extract(&c1, &m, patch, &err), 0);
		CHECK_INT(fct_chains_extract_adj(&c2, &m, &a, patch, &err), 0);
		CHECK(c1.n > 2 && same_chains(&c1, &c2));
		c2.frozen = calloc(c2.n, 1);
		c2.frozen[1] = 1;
		c2.keep[c2.start[1] + 1] = 0;
		CHECK_INT(fct_chains_copy(&c3, &c2, &err), 0);
		CHECK(same_chains(&c2, &c3) && c3.frozen && c3.frozen[1] == 1 && c3.frozen[0] == 0);
		CHECK(c3.vert != c2.vert && c3.keep[c3.start[1] + 1] == 0);
		fct_chains_free(&c1), fct_chains_free(&c2), fct_chains_free(&c3);
	}
	fct_adj_free(&a);
	free(patch);
	fct_mesh_free(&m);
}

int main(void)
{
	test_conflict_predicate();
	test_straight();
	test_square();
	test_junction();
	test_dip();
	test_edge_cases();
	test_uneven();
	test_chain_tolerance();
	test_keep_vertex();
	test_room();
	test_extract_adj_copy();
	CHECK_DONE();
}
