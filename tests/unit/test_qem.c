/* test_qem - quadric edge-collapse decimation against exact answers.
 *
 * A finely triangulated square (regular and jittered in its plane, also
 * tilted in space) goes to 2 triangles at its 4 corners with zero error and
 * the same area; a cube of many small triangles goes to 12 triangles on its
 * 8 exact corners; closed meshes (sphere, torus) stay closed, manifold, of
 * the same Euler characteristic, with no triangle turned inside out; the
 * face target is met exactly (one more on a closed mesh with an odd
 * target); the same input gives the same bytes; s t follow the collapses;
 * face rows follow their triangles; quads are fanned; borders stay on
 * their lines; an error bound holds; triangular holes close only when
 * asked; locked non-manifold edges stay; bad input fails cleanly. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "check.h"
#include "geom/geom.h"
#include "geom/qem.h"
#include "core/rng.h"

static struct fct_err err;

static void add_v(struct fct_mesh *m, double x, double y, double z)
{
	if (fct_mesh_add_vertex(m, x, y, z, &err) < 0)
		abort();
}

static void add_t(struct fct_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
	uint32_t t[3] = {a, b, c};
	if (fct_mesh_add_face(m, t, 3, &err) < 0)
		abort();
}

/* An n x n grid of squares over [0,1]^2 at z = 0, each cut along a
 * diagonal that alternates; interior points moved in the plane by up to
 * jitter of a cell when jitter > 0. */
static void make_grid(struct fct_mesh *m, int n, double jitter, uint64_t seed)
{
	struct fct_rng r;
	fct_rng_seed(&r, seed);
	fct_mesh_init(m);
	for (int j = 0; j <= n; j++)
		for (int i = 0; i <= n; i++) {
			double x = (double)i / n, y = (double)j / n;
			if (jitter > 0 && i > 0 && i < n && j > 0 && j < n) {
				x += jitter / n * (fct_rng_uniform(&r) - 0.5);
				y += jitter / n * (fct_rng_uniform(&r) - 0.5);
			}
			add_v(m, x, y, 0);
		}
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
			if ((i + j) % 2) {
				add_t(m, a, b, d);
				add_t(m, a, d, c);
			} else {
				add_t(m, a, b, c);
				add_t(m, b, d, c);
			}
		}
}

/* Map every vertex through p -> R p + t. */
static void transform(struct fct_mesh *m, const double R[9], const double t[3])
{
	for (size_t v = 0; v < m->nv; v++) {
		double *p = m->xyz + 3 * v, q[3];
		for (int k = 0; k < 3; k++)
			q[k] = R[3 * k] * p[0] + R[3 * k + 1] * p[1] + R[3 * k + 2] * p[2] + t[k];
		memcpy(p, q, sizeof q);
	}
}

/* The cube [0,1]^3, each side an n x n grid of squares cut in two,
 * outward winding, vertices shared along the edges. */
static void make_cube(struct fct_mesh *m, int n)
{
	fct_mesh_init(m);
	/* Vertex numbers by integer lattice position, so the sides share them. */
	int N = n + 1;
	long *id = malloc(sizeof *id * (size_t)(N * N * N));
	for (int i = 0; i < N * N * N; i++)
		id[i] = -1;
	for (int side = 0; side < 6; side++) {
		int ax = side / 2, hi = side % 2;
		int u = (ax + 1) % 3, w = (ax + 2) % 3;
		for (int j = 0; j < n; j++)
			for (int i = 0; i < n; i++) {
				uint32_t c[4];
				for (int k = 0; k < 4; k++) {
					int g[3];
					g[ax] = hi ? n : 0;
					g[u] = i + (k == 1 || k == 2);
					g[w] = j + (k >= 2);
					int key = (g[0] * N + g[1]) * N + g[2];
					if (id[key] < 0) {
						id[key] = (long)m->nv;
						add_v(m, (double)g[0] / n, (double)g[1] / n, (double)g[2] / n);
					}
					c[k] = (uint32_t)id[key];
				}
				/* (u, w) is right-handed with ax, so (c0 c1 c2) faces +ax. */
				if (hi) {
					add_t(m, c[0], c[1], c[2]);
					add_t(m, c[0], c[2], c[3]);
				} else {
					add_t(m, c[0], c[2], c[1]);
					add_t(m, c[0], c[3], c[2]);
				}
			}
	}
	free(id);
}

/* The unit sphere: an octahedron whose faces are split into n^2 triangles,
 * projected onto the sphere. */
static void make_sphere(struct fct_mesh *m, int n)
{
	static const double oct[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
	static const int of[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
	                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
	fct_mesh_init(m);
	/* Points by rounded coordinates, so neighbouring faces share them. */
	size_t cap = 8 * (size_t)(n + 1) * (size_t)(n + 2) / 2;
	double *key = malloc(sizeof *key * 3 * cap);
	size_t nkey = 0;
	for (int f = 0; f < 8; f++) {
		const double *A = oct[of[f][0]], *B = oct[of[f][1]], *C = oct[of[f][2]];
		uint32_t *idx = malloc(sizeof *idx * (size_t)(n + 1) * (size_t)(n + 1));
		for (int i = 0; i <= n; i++)
			for (int j = 0; i + j <= n; j++) {
				double p[3];
				for (int k = 0; k < 3; k++)
					p[k] = (A[k] * (n - i - j) + B[k] * i + C[k] * j) / n;
				size_t found = nkey;
				for (size_t q = 0; q < nkey; q++)
					if (fabs(key[3 * q] - p[0]) + fabs(key[3 * q + 1] - p[1]) + fabs(key[3 * q + 2] - p[2]) < 1e-9) {
						found = q;
						break;
					}
				if (found == nkey) {
					memcpy(key + 3 * nkey, p, sizeof p);
					nkey++;
					double l = sqrt(fct_v3_dot(p, p));
					add_v(m, p[0] / l, p[1] / l, p[2] / l);
				}
				idx[i * (n + 1) + j] = (uint32_t)found;
			}
		for (int i = 0; i < n; i++)
			for (int j = 0; i + j < n; j++) {
				add_t(m, idx[i * (n + 1) + j], idx[(i + 1) * (n + 1) + j], idx[i * (n + 1) + j + 1]);
				if (i + j + 1 < n)
					add_t(m, idx[(i + 1) * (n + 1) + j], idx[(i + 1) * (n + 1) + j + 1],
					      idx[i * (n + 1) + j + 1]);
			}
		free(idx);
	}
	free(key);
}

/* A torus of radii R, r with nu x nv quads cut in two, outward winding. */
static void make_torus(struct fct_mesh *m, int nu, int nv, double R, double r)
{
	fct_mesh_init(m);
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++) {
			double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
			add_v(m, (R + r * cos(v)) * cos(u), (R + r * cos(v)) * sin(u), r * sin(v));
		}
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++) {
			uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j);
			uint32_t c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), d = (uint32_t)(i * nv + (j + 1) % nv);
			add_t(m, a, b, c);
			add_t(m, a, c, d);
		}
}

/* Topology figures: border and non-manifold edges, non-manifold vertices
 * (triangles around a vertex in more than one fan), Euler characteristic. */
struct topo {
	size_t border, nonmanifold, pinched;
	long euler;
	long components;
};

static struct topo topology(const struct fct_mesh *m)
{
	struct topo t = {0, 0, 0, 0, 0};
	struct fct_adj a;
	if (fct_adj_build(&a, m, &err))
		abort();
	t.border = a.nborder;
	t.nonmanifold = a.nnonmanifold;
	size_t used = 0;
	for (size_t v = 0; v < m->nv; v++) {
		uint32_t f0 = a.vert_fstart[v], f1 = a.vert_fstart[v + 1];
		if (f0 == f1)
			continue;
		used++;
		/* Walk from the first triangle across the edges at v. */
		uint32_t *fan = malloc(sizeof *fan * (f1 - f0)), nf = 0, visited = 0;
		fan[nf++] = a.vert_f[f0];
		while (visited < nf) {
			uint32_t f = fan[visited++];
			for (uint32_t k = 0; k < 3; k++) {
				if (m->fvert[3 * f + k] != v && m->fvert[3 * f + (k + 1) % 3] != v)
					continue;
				uint32_t e = a.face_e[3 * f + k];
				for (uint32_t i = a.edge_fstart[e]; i < a.edge_fstart[e + 1]; i++) {
					uint32_t g = a.edge_f[i], seen = 0;
					for (uint32_t q = 0; q < nf; q++)
						seen |= fan[q] == g;
					if (!seen && nf < f1 - f0)
						fan[nf++] = g;
				}
			}
		}
		t.pinched += nf != f1 - f0;
		free(fan);
	}
	t.euler = (long)used - (long)a.ne + (long)m->nf;
	uint32_t *label = malloc(sizeof *label * (m->nf ? m->nf : 1));
	t.components = fct_adj_components(&a, label, &err);
	free(label);
	fct_adj_free(&a);
	return t;
}

static double mesh_area(const struct fct_mesh *m)
{
	double s = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *t = m->fvert + m->fstart[f];
		s += 0.5 * fct_triangle_area2(m->xyz + 3 * (size_t)t[0], m->xyz + 3 * (size_t)t[1],
		                              m->xyz + 3 * (size_t)t[2]);
	}
	return s;
}

static void face_normal(const struct fct_mesh *m, size_t f, double n[3])
{
	const uint32_t *t = m->fvert + m->fstart[f];
	double e1[3], e2[3];
	fct_v3_sub(e1, m->xyz + 3 * (size_t)t[1], m->xyz + 3 * (size_t)t[0]);
	fct_v3_sub(e2, m->xyz + 3 * (size_t)t[2], m->xyz + 3 * (size_t)t[0]);
	fct_v3_cross(n, e1, e2);
}

static int run(struct fct_mesh *m, size_t target, struct fct_qem_stats *st)
{
	struct fct_qem_params p;
	fct_qem_params_default(&p);
	p.target_faces = target;
	return fct_qem_decimate(m, &p, st, &err);
}

/* A flat square to two triangles: zero error, area 1, the four corners. */
static void square_case(double jitter, int tilt)
{
	struct fct_mesh m;
	struct fct_qem_stats st;
	make_grid(&m, 24, jitter, 7);
	double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, t[3] = {0, 0, 0};
	if (tilt) {
		/* a rotation about (1, 2, 2)/3 by 40 degrees, and an offset */
		double ax[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, c = cos(0.7), s = sin(0.7);
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				R[3 * i + j] = (i == j ? c : 0) + (1 - c) * ax[i] * ax[j];
		R[1] -= s * ax[2], R[2] += s * ax[1], R[3] += s * ax[2];
		R[5] -= s * ax[0], R[6] -= s * ax[1], R[7] += s * ax[0];
		t[0] = 1000, t[1] = -250, t[2] = 3;
		transform(&m, R, t);
	}
	double area0 = mesh_area(&m);
	CHECK_INT(m.nf, 2 * 24 * 24);
	CHECK(run(&m, 2, &st) == 0);
	CHECK_INT(m.nf, 2);
	CHECK_INT(m.nv, 4);
	CHECK_INT(st.faces_out, 2);
	CHECK(st.max_error < 1e-7 * (tilt ? 1000 : 1));   /* the root of rounding */
	CHECK_NEAR(mesh_area(&m), area0, 1e-9 * (tilt ? 1000 : 1));
	CHECK_NEAR(area0, 1, 1e-9);
	/* Each output vertex is an input corner, exactly (they never move). */
	int corners = 0;
	for (size_t v = 0; v < m.nv; v++)
		for (int k = 0; k < 4; k++) {
			double c[3] = {k & 1, k >> 1, 0}, q[3];
			for (int i = 0; i < 3; i++)
				q[i] = R[3 * i] * c[0] + R[3 * i + 1] * c[1] + R[3 * i + 2] * c[2] + t[i];
			corners += fct_v3_dist2(m.xyz + 3 * v, q) == 0;
		}
	CHECK_INT(corners, 4);
	/* Both triangles keep the winding (normal along R's z axis). */
	for (size_t f = 0; f < m.nf; f++) {
		double n[3], z[3] = {R[2], R[5], R[8]};
		face_normal(&m, f, n);
		CHECK(fct_v3_dot(n, z) > 0);
	}
	struct topo tp = topology(&m);
	CHECK_INT(tp.border, 4);
	CHECK_INT(tp.euler, 1);
	fct_mesh_free(&m);
}

/* The cube to 12 triangles on its 8 corners. */
static void test_cube(void)
{
	struct fct_mesh m;
	struct fct_qem_stats st;
	make_cube(&m, 10);
	CHECK_INT(m.nf, 6 * 2 * 100);
	CHECK_INT(m.nv, 6 * 100 + 2);
	CHECK(run(&m, 12, &st) == 0);
	CHECK_INT(m.nf, 12);
	CHECK_INT(m.nv, 8);
	int corner_mask = 0;
	double worst = 0;
	for (size_t v = 0; v < m.nv; v++) {
		const double *p = m.xyz + 3 * v;
		int k = (p[0] > 0.5) | (p[1] > 0.5) << 1 | (p[2] > 0.5) << 2;
		corner_mask |= 1 << k;
		double c[3] = {k & 1, (k >> 1) & 1, (k >> 2) & 1};
		double d = sqrt(fct_v3_dist2(p, c));
		worst = d > worst ? d : worst;
	}
	CHECK_INT(corner_mask, 255);
	CHECK(worst <= 1e-9);
	CHECK(st.max_error <= 1e-7);   /* the square root of rounding */
	CHECK_NEAR(mesh_area(&m), 6, 1e-9);
	/* Every triangle lies on a side and faces out of it. */
	int out = 0;
	for (size_t f = 0; f < m.nf; f++) {
		double n[3], c[3] = {0, 0, 0};
		face_normal(&m, f, n);
		for (int k = 0; k < 3; k++)
			fct_v3_axpy(c, c, 1.0 / 3, m.xyz + 3 * (size_t)m.fvert[3 * f + (size_t)k]);
		double r[3] = {c[0] - 0.5, c[1] - 0.5, c[2] - 0.5};
		out += fct_v3_dot(n, r) > 0;
	}
	CHECK_INT(out, 12);
	struct topo tp = topology(&m);
	CHECK_INT(tp.border, 0);
	CHECK_INT(tp.nonmanifold, 0);
	CHECK_INT(tp.pinched, 0);
	CHECK_INT(tp.euler, 2);
	fct_mesh_free(&m);
}

/* Closed meshes stay closed and manifold, with their Euler characteristic,
 * and no triangle turns over; exact counts, +1 for odd targets. */
static void test_closed(void)
{
	struct fct_mesh m;
	struct fct_qem_stats st;
	make_sphere(&m, 16);
	CHECK_INT(m.nf, 8 * 256);
	struct topo t0 = topology(&m);
	CHECK_INT(t0.euler, 2);
	CHECK_INT(t0.border, 0);
	CHECK(run(&m, 100, &st) == 0);
	CHECK_INT(m.nf, 100);
	struct topo t1 = topology(&m);
	CHECK_INT(t1.border, 0);
	CHECK_INT(t1.nonmanifold, 0);
	CHECK_INT(t1.pinched, 0);
	CHECK_INT(t1.euler, 2);
	CHECK_INT(t1.components, 1);
	/* Outward: every triangle's normal points away from the centre, and
	 * the vertices stay near the sphere (the quadric error is small). */
	int out = 0;
	double far = 0;
	for (size_t f = 0; f < m.nf; f++) {
		double n[3], c[3] = {0, 0, 0};
		face_normal(&m, f, n);
		for (int k = 0; k < 3; k++)
			fct_v3_axpy(c, c, 1.0 / 3, m.xyz + 3 * (size_t)m.fvert[3 * f + (size_t)k]);
		out += fct_v3_dot(n, c) > 0;
	}
	for (size_t v = 0; v < m.nv; v++) {
		double d = fabs(sqrt(fct_v3_dot(m.xyz + 3 * v, m.xyz + 3 * v)) - 1);
		far = d > far ? d : far;
	}
	CHECK_INT(out, 100);
	CHECK(far < 0.05);
	/* An odd target on a closed mesh: one more (counts stay even). */
	CHECK(run(&m, 41, &st) == 0);
	CHECK_INT(m.nf, 42);
	/* Down to the tetrahedron, no further. */
	CHECK(run(&m, 0, &st) == 0);
	CHECK_INT(m.nf, 4);
	CHECK_INT(topology(&m).euler, 2);
	fct_mesh_free(&m);

	make_torus(&m, 40, 20, 1, 0.3);
	CHECK_INT(topology(&m).euler, 0);
	CHECK(run(&m, 200, &st) == 0);
	CHECK_INT(m.nf, 200);
	struct topo tt = topology(&m);
	CHECK_INT(tt.euler, 0);
	CHECK_INT(tt.border, 0);
	CHECK_INT(tt.nonmanifold, 0);
	CHECK_INT(tt.pinched, 0);
	/* Coarsest: a torus cannot go below 14 triangles (7 vertices); the
	 * link condition stops before any fold. */
	CHECK(run(&m, 0, &st) == 0);
	tt = topology(&m);
	CHECK_INT(tt.euler, 0);
	CHECK_INT(tt.nonmanifold, 0);
	CHECK_INT(tt.pinched, 0);
	CHECK(m.nf >= 14);
	fct_mesh_free(&m);
}

/* Targets on an open mesh are met exactly, odd or even. */
static void test_targets(void)
{
	static const size_t targets[] = {1000, 777, 101, 33, 7, 3};
	for (size_t i = 0; i < sizeof targets / sizeof *targets; i++) {
		struct fct_mesh m;
		struct fct_qem_stats st;
		make_grid(&m, 30, 0.6, 3);
		/* a bump, so costs differ */
		for (size_t v = 0; v < m.nv; v++) {
			double *p = m.xyz + 3 * v;
			p[2] = 0.2 * exp(-10 * ((p[0] - 0.4) * (p[0] - 0.4) + (p[1] - 0.6) * (p[1] - 0.6)));
		}
		CHECK(run(&m, targets[i], &st) == 0);
		CHECK_INT(m.nf, targets[i]);
		struct topo tp = topology(&m);
		CHECK_INT(tp.euler, 1);
		CHECK_INT(tp.nonmanifold, 0);
		CHECK_INT(tp.pinched, 0);
		fct_mesh_free(&m);
	}
}

/* The same input gives the same result, bit for bit. */
static void test_deterministic(void)
{
	struct fct_mesh a, b;
	make_sphere(&a, 12);
	make_sphere(&b, 12);
	CHECK(run(&a, 150, NULL) == 0);
	CHECK(run(&b, 150, NULL) == 0);
	CHECK_INT(a.nv, b.nv);
	CHECK_INT(a.nf, b.nf);
	CHECK(!memcmp(a.xyz, b.xyz, 3 * a.nv * sizeof *a.xyz));
	CHECK(!memcmp(a.fvert, b.fvert, 3 * a.nf * sizeof *a.fvert));
	fct_mesh_free(&a);
	fct_mesh_free(&b);
}

/* s t = x y on a curved sheet over the unit square: a vertex that kept
 * its place keeps its s t exactly; one that moved has s t interpolated at
 * its projection on the edge it came from, within a small part of a cell
 * of its own x y (the off-edge part of its move); the patch label of each surviving face is that of an
 * input face, each once; a uchar column is that of the kept end. */
static void test_properties(void)
{
	struct fct_mesh m;
	make_grid(&m, 16, 0.5, 11);
	for (size_t v = 0; v < m.nv; v++)
		m.xyz[3 * v + 2] = 0.3 * m.xyz[3 * v] * m.xyz[3 * v + 1];   /* curved: vertices move */
	CHECK(fct_elem_add_scalar(&m.vertex, "s", FCT_FLOAT64, &err) != NULL);
	CHECK(fct_elem_add_scalar(&m.vertex, "t", FCT_FLOAT64, &err) != NULL);
	CHECK(fct_elem_add_scalar(&m.vertex, "red", FCT_UINT8, &err) != NULL);
	struct fct_prop *ps = fct_elem_find(&m.vertex, "s"), *pt = fct_elem_find(&m.vertex, "t");
	struct fct_prop *pr = fct_elem_find(&m.vertex, "red");
	for (size_t v = 0; v < m.nv; v++) {
		fct_prop_set(ps, v, m.xyz[3 * v]);
		fct_prop_set(pt, v, m.xyz[3 * v + 1]);
		fct_prop_set(pr, v, (double)(v % 200));
	}
	struct fct_prop *pp = fct_elem_add_scalar(&m.face, "patch", FCT_INT32, &err);
	for (size_t f = 0; f < m.nf; f++)
		fct_prop_set(pp, f, (double)f);
	size_t nf0 = m.nf, nv0 = m.nv;
	double *orig = malloc(sizeof *orig * 3 * m.nv);
	memcpy(orig, m.xyz, sizeof *orig * 3 * m.nv);
	struct fct_qem_stats st;
	CHECK(run(&m, 60, &st) == 0);
	CHECK_INT(m.nf, 60);
	ps = fct_elem_find(&m.vertex, "s");
	pt = fct_elem_find(&m.vertex, "t");
	pp = fct_elem_find(&m.face, "patch");
	pr = fct_elem_find(&m.vertex, "red");
	CHECK(ps && pt && pp && pr);
	double worst_moved = 0;
	int moved = 0, kept_exact = 1, red_ok = 1;
	for (size_t v = 0; v < m.nv; v++) {
		double ds = fabs(fct_prop_get(ps, v) - m.xyz[3 * v]);
		double dt = fabs(fct_prop_get(pt, v) - m.xyz[3 * v + 1]);
		size_t u = 0;
		while (u < nv0 && fct_v3_dist2(orig + 3 * u, m.xyz + 3 * v) != 0)
			u++;
		if (u == nv0) {
			moved++;
			worst_moved = fmax(worst_moved, fmax(ds, dt));
		} else {
			kept_exact &= ds == 0 && dt == 0;
			red_ok &= (size_t)fct_prop_get(pr, v) == u % 200;
		}
	}
	CHECK(moved > 0);   /* some vertices took optimal positions */
	CHECK(kept_exact);
	CHECK(red_ok);
	CHECK(worst_moved < 0.1);   /* the final edges are about 0.2 long */
	unsigned char *seen = calloc(nf0, 1);
	int labels_ok = 1;
	for (size_t f = 0; f < m.nf; f++) {
		long l = (long)fct_prop_get(pp, f);
		labels_ok &= l >= 0 && (size_t)l < nf0 && !seen[l];
		if (l >= 0 && (size_t)l < nf0)
			seen[l] = 1;
	}
	CHECK(labels_ok);
	free(seen);
	free(orig);
	fct_mesh_free(&m);
}

/* Quads are fanned; a face of two corners and a triangle with a repeated
 * corner are dropped; an edge element goes. */
static void test_polygons(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	int n = 8;
	for (int j = 0; j <= n; j++)
		for (int i = 0; i <= n; i++)
			add_v(&m, i, j, 0);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			uint32_t a = (uint32_t)(j * (n + 1) + i), q[4] = {a, a + 1, a + (uint32_t)n + 2, a + (uint32_t)n + 1};
			CHECK(fct_mesh_add_face(&m, q, 4, &err) >= 0);
		}
	uint32_t two[2] = {0, 1}, rep[3] = {2, 2, 3};
	CHECK(fct_mesh_add_face(&m, two, 2, &err) >= 0);
	CHECK(fct_mesh_add_face(&m, rep, 3, &err) >= 0);
	CHECK(fct_mesh_add_elem(&m, "edge", 3, &err) != NULL);
	CHECK(fct_mesh_add_elem(&m, "plane", 1, &err) != NULL);
	struct fct_qem_stats st;
	CHECK(run(&m, 2, &st) == 0);
	CHECK_INT(st.faces_in, 2 * n * n);
	CHECK_INT(st.dropped, 1);
	CHECK_INT(m.nf, 2);
	CHECK_NEAR(mesh_area(&m), n * n, 1e-9);
	CHECK(fct_mesh_find_elem(&m, "edge") == NULL);
	CHECK(fct_mesh_find_elem(&m, "plane") != NULL);
	for (size_t f = 0; f < m.nf; f++)
		CHECK_INT(fct_face_size(&m, f), 3);
	fct_mesh_free(&m);
}

/* Borders: a grid with a bump inside a flat rim, decimated hard: the
 * border stays exactly on the square's outline, with its four corners. */
static void test_border(void)
{
	struct fct_mesh m;
	make_grid(&m, 30, 0.5, 5);
	for (size_t v = 0; v < m.nv; v++) {
		double *p = m.xyz + 3 * v, r2 = (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5);
		p[2] = r2 < 0.09 ? 0.2 * (0.09 - r2) : 0;
	}
	struct fct_qem_stats st;
	CHECK(run(&m, 80, &st) == 0);
	CHECK_INT(m.nf, 80);
	struct fct_adj a;
	CHECK(fct_adj_build(&a, &m, &err) == 0);
	double off = 0;
	for (size_t e = 0; e < a.ne; e++) {
		if (fct_adj_edge_nfaces(&a, e) != 1)
			continue;
		for (int k = 0; k < 2; k++) {
			const double *p = m.xyz + 3 * (size_t)a.edge_v[2 * e + (size_t)k];
			double d = fmin(fmin(fabs(p[0]), fabs(1 - p[0])), fmin(fabs(p[1]), fabs(1 - p[1])));
			off = fmax(off, d);
		}
	}
	CHECK(off == 0);
	fct_adj_free(&a);
	int corners = 0;
	for (size_t v = 0; v < m.nv; v++) {
		const double *p = m.xyz + 3 * v;
		corners += (p[0] == 0 || p[0] == 1) && (p[1] == 0 || p[1] == 1);
	}
	CHECK_INT(corners, 4);
	fct_mesh_free(&m);
}

/* The error bound: with max_error, no collapse beyond it; a smaller bound
 * keeps more faces. */
static void test_max_error(void)
{
	struct fct_mesh m;
	struct fct_qem_params p;
	struct fct_qem_stats st1, st2;
	fct_qem_params_default(&p);
	make_sphere(&m, 32);
	p.max_error = 1e-3;
	CHECK(fct_qem_decimate(&m, &p, &st1, &err) == 0);
	CHECK(st1.max_error <= 1e-3);
	CHECK(st1.max_error > 1e-4);
	CHECK(st1.refused_error > 0);
	size_t nf1 = m.nf;
	fct_mesh_free(&m);
	make_sphere(&m, 32);
	p.max_error = 1e-2;
	CHECK(fct_qem_decimate(&m, &p, &st2, &err) == 0);
	CHECK(st2.max_error <= 1e-2);
	CHECK(m.nf < nf1);
	CHECK(nf1 < 8 * 1024 / 2);
	/* Every vertex is within the bound's order of the sphere. */
	double far = 0;
	for (size_t v = 0; v < m.nv; v++)
		far = fmax(far, fabs(sqrt(fct_v3_dot(m.xyz + 3 * v, m.xyz + 3 * v)) - 1));
	CHECK(far < 3e-2);
	fct_mesh_free(&m);
}

/* A square with a triangular hole: it stays open without close_holes and
 * closes with it. */
static void test_holes(void)
{
	for (int close = 0; close < 2; close++) {
		struct fct_mesh m;
		make_grid(&m, 12, 0, 1);
		/* remove one triangle in the middle */
		size_t keep[2 * 12 * 12], n = 0, hole = 2 * (6 * 12 + 6);
		for (size_t f = 0; f < m.nf; f++)
			if (f != hole)
				keep[n++] = f;
		CHECK(fct_mesh_gather_faces(&m, keep, n, &err) == 0);
		struct topo t0 = topology(&m);
		CHECK_INT(t0.border, 4 * 12 + 3);
		CHECK_INT(t0.euler, 0);
		struct fct_qem_params p;
		struct fct_qem_stats st;
		fct_qem_params_default(&p);
		p.close_holes = close;
		p.target_faces = 2;
		CHECK(fct_qem_decimate(&m, &p, &st, &err) == 0);
		struct topo t1 = topology(&m);
		CHECK_INT(t1.nonmanifold, 0);
		CHECK_INT(t1.pinched, 0);
		if (close) {
			CHECK_INT(m.nf, 2);
			CHECK_INT(t1.euler, 1);
			CHECK_INT(st.holes_closed, 1);
			CHECK_NEAR(mesh_area(&m), 1, 1e-12);   /* the hole's area is filled */
		} else {
			CHECK(m.nf > 2);
			CHECK_INT(t1.euler, 0);
			CHECK_INT(st.holes_closed, 0);
			CHECK(t1.border >= 3 + 3);   /* the outline and the hole, at their smallest */
		}
		fct_mesh_free(&m);
	}
}

/* A fin: three triangles on one edge.  Its ends are locked, the edge
 * stays, the rest decimates around it. */
static void test_nonmanifold(void)
{
	struct fct_mesh m;
	make_grid(&m, 10, 0, 1);
	size_t a = 5 * 11 + 5, b = a + 1;   /* an interior horizontal edge */
	add_v(&m, 0.55, 0.5, 0.3);
	add_t(&m, (uint32_t)a, (uint32_t)b, (uint32_t)(m.nv - 1));
	double pa[3], pb[3];
	memcpy(pa, m.xyz + 3 * a, sizeof pa);
	memcpy(pb, m.xyz + 3 * b, sizeof pb);
	struct fct_qem_stats st;
	CHECK(run(&m, 20, &st) == 0);
	CHECK_INT(st.locked, 2);
	struct topo tp = topology(&m);
	CHECK_INT(tp.nonmanifold, 1);
	int found = 0;
	for (size_t v = 0; v < m.nv; v++)
		found += fct_v3_dist2(m.xyz + 3 * v, pa) == 0 || fct_v3_dist2(m.xyz + 3 * v, pb) == 0;
	CHECK_INT(found, 2);
	fct_mesh_free(&m);
}

/* Empty, no faces, a single triangle, NaN. */
static void test_bad_input(void)
{
	struct fct_mesh m;
	struct fct_qem_stats st;
	fct_mesh_init(&m);
	CHECK(run(&m, 0, &st) == 0);
	CHECK_INT(m.nv, 0);
	CHECK_INT(m.nf, 0);
	add_v(&m, 0, 0, 0);
	add_v(&m, 1, 0, 0);
	CHECK(run(&m, 0, &st) == 0);
	CHECK_INT(m.nv, 2);   /* points without faces are kept */
	add_v(&m, 0, 1, 0);
	add_t(&m, 0, 1, 2);
	CHECK(run(&m, 0, &st) == 0);
	CHECK_INT(m.nf, 1);   /* a lone triangle does not vanish */
	CHECK_INT(m.nv, 3);
	m.xyz[4] = NAN;
	CHECK(run(&m, 0, &st) == -1);
	CHECK_STR(err.msg, "vertex 1: coordinate is not finite");
	CHECK_INT(m.nf, 1);
	fct_mesh_free(&m);
	/* Coincident vertices (a zero-area triangle) decimate without harm. */
	make_grid(&m, 6, 0, 1);
	memcpy(m.xyz + 3 * 8, m.xyz + 3 * 9, 3 * sizeof *m.xyz);
	CHECK(run(&m, 2, &st) == 0);
	CHECK(m.nf <= 3);
	CHECK_INT(topology(&m).nonmanifold, 0);
	fct_mesh_free(&m);
}

int main(void)
{
	square_case(0, 0);
	square_case(0.5, 0);
	square_case(0.5, 1);
	test_cube();
	test_closed();
	test_targets();
	test_deterministic();
	test_properties();
	test_polygons();
	test_border();
	test_max_error();
	test_holes();
	test_nonmanifold();
	test_bad_input();
	CHECK_DONE();
}
