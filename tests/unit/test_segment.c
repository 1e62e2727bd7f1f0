/* test_segment.c - planar segmentation (segment.h) on hand-made meshes with
 * known answers: a cube, disconnected coplanar squares, a folded strip, a
 * noisy corner of three planes and its rotated and scaled copy, area
 * weighting against subdivision, non-manifold edges, polygons, degenerate
 * faces, and the 3x3 eigen helpers. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "core/rng.h"
#include "planar/segment.h"

static struct fct_err err;

static void add_vertex(struct fct_mesh *m, double x, double y, double z)
{
	if (fct_mesh_add_vertex(m, x, y, z, &err) < 0)
		abort();
}

static void add_face(struct fct_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
	uint32_t v[3] = { a, b, c };
	if (fct_mesh_add_face(m, v, 3, &err) < 0)
		abort();
}

/* Segment m; patch (m->nf) and planes are the caller's to free. */
static size_t segment(const struct fct_mesh *m, const struct fct_segment_params *p,
                      int32_t **patch, struct fct_plane **planes, struct fct_segment_stats *st)
{
	size_t np = 0;
	*patch = malloc((m->nf ? m->nf : 1) * sizeof **patch);
	if (!*patch || fct_segment(*patch, planes, &np, m, p, st, &err)) {
		fprintf(stderr, "fct_segment: %s\n", err.msg);
		abort();
	}
	return np;
}

/* The unit cube, each square face two outward-wound triangles. */
static void make_cube(struct fct_mesh *m)
{
	static const int quads[6][4] = {
		{ 0, 2, 3, 1 }, { 4, 5, 7, 6 },   /* z = 0, z = 1 */
		{ 0, 1, 5, 4 }, { 2, 6, 7, 3 },   /* y = 0, y = 1 */
		{ 0, 4, 6, 2 }, { 1, 3, 7, 5 },   /* x = 0, x = 1 */
	};
	fct_mesh_init(m);
	for (int v = 0; v < 8; v++)
		add_vertex(m, v & 1, (v >> 1) & 1, (v >> 2) & 1);
	for (int q = 0; q < 6; q++) {
		add_face(m, quads[q][0], quads[q][1], quads[q][2]);
		add_face(m, quads[q][0], quads[q][2], quads[q][3]);
	}
}

/* Each pair of triangles of the cube is one patch with the exact outward
 * normal, d and rms 0; patches numbered by their first face. */
static void check_cube(const int32_t *patch, const struct fct_plane *pl, size_t np)
{
	static const double normal[6][3] = {
		{ 0, 0, -1 }, { 0, 0, 1 }, { 0, -1, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 1, 0, 0 },
	};
	static const double d[6] = { 0, -1, 0, -1, 0, -1 };
	CHECK_INT(np, 6);
	if (np != 6)
		return;
	for (int q = 0; q < 6; q++) {
		CHECK_INT(patch[2 * q], q);
		CHECK_INT(patch[2 * q + 1], q);
		for (int i = 0; i < 3; i++)
			CHECK_NEAR(pl[q].n[i], normal[q][i], 1e-15);
		CHECK_NEAR(pl[q].d, d[q], 1e-15);
		CHECK_NEAR(pl[q].rms, 0, 1e-15);
		CHECK_INT(pl[q].count, 4);
	}
}

/* The largest distance of face f's corners from plane pl. */
static double plane_distance(const struct fct_plane *pl, const struct fct_mesh *m, size_t f)
{
	double worst = 0;
	for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++) {
		const double *x = &m->xyz[3 * m->fvert[k]];
		worst = fmax(worst, fabs(fct_plane_distance(pl, x)));
	}
	return worst;
}

static void test_cube(void)
{
	struct fct_mesh m;
	make_cube(&m);
	struct fct_segment_params p;
	struct fct_segment_stats st;
	int32_t *patch;
	struct fct_plane *pl;

	fct_segment_params_default(&p);   /* automatic */
	size_t np = segment(&m, &p, &patch, &pl, &st);
	check_cube(patch, pl, np);
	CHECK_INT(st.merges, 6);
	CHECK_INT(st.absorbed, 0);        /* no patch of 8 faces to absorb into */
	CHECK_NEAR(st.noise, 1e-7 * sqrt(3), 1e-13);   /* exact data: the floor, 1e-7 of the diagonal */
	CHECK_NEAR(st.max_rms, 0, 1e-15);
	free(patch), free(pl);

	p.target = 6;                     /* T_N */
	np = segment(&m, &p, &patch, &pl, &st);
	check_cube(patch, pl, np);
	free(patch), free(pl);

	p.target = 3;                     /* fewer: merged across edges, then the guarantee */
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(st.merges, 9);
	CHECK(np < 3);                    /* faces of exact data off a bent patch's plane peeled */
	CHECK(st.peeled > 0);
	for (int f = 0; f < 12; f++)      /* every face left lies on its patch's plane */
		if (patch[f] >= 0)
			CHECK(fabs(plane_distance(&pl[patch[f]], &m, (size_t)f)) < 1e-6);
	free(patch), free(pl);

	p.max_dev = 0;                    /* no peeling: T_N patches, all faces labelled */
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 3);
	CHECK_INT(st.merges, 9);
	CHECK_INT(st.free_faces, 0);
	free(patch), free(pl);

	/* One patch asked: without a viewpoint a mesh is two-sided, and no
	 * patch joins faces turned opposite ways (three sides of the cube's
	 * corner face (1, 1, 1) together, the other three (-1, -1, -1)). */
	p.target = 1;
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 2);
	if (np == 2) {
		CHECK(pl[0].rms > 0.2);   /* a cube's half is far from a plane */
		CHECK_NEAR(pl[0].n[0] * pl[1].n[0] + pl[0].n[1] * pl[1].n[1] + pl[0].n[2] * pl[1].n[2], -1, 1e-12);
	}
	free(patch), free(pl);

	fct_segment_params_default(&p);   /* area weighting: the same patches */
	p.area_weighted = 1;
	np = segment(&m, &p, &patch, &pl, &st);
	check_cube(patch, pl, np);
	free(patch), free(pl);

	fct_segment_params_default(&p);   /* a hard bound of 0 allows only exact planes */
	p.max_rms = 0;
	p.target = 1;
	np = segment(&m, &p, &patch, &pl, &st);
	check_cube(patch, pl, np);
	free(patch), free(pl);
	fct_mesh_free(&m);
}

/* A w x h grid of unit cells in the plane z = 0 starting at (x0, y0), two
 * triangles a cell, wound to face +z. */
static void add_grid(struct fct_mesh *m, int w, int h, double x0, double y0)
{
	uint32_t base = (uint32_t)m->nv;
	for (int j = 0; j <= h; j++)
		for (int i = 0; i <= w; i++)
			add_vertex(m, x0 + i, y0 + j, 0);
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			uint32_t a = base + (uint32_t)(j * (w + 1) + i), b = a + 1;
			uint32_t c = a + (uint32_t)(w + 1), d = c + 1;
			add_face(m, a, b, d);
			add_face(m, a, d, c);
		}
}

/* Two coplanar squares that share no edge stay two patches; one square is
 * one patch (all faces coplanar), with n = +z from the winding. */
static void test_coplanar(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	add_grid(&m, 3, 3, 0, 0);
	add_grid(&m, 3, 3, 5, 0);   /* same plane, apart */
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	int32_t *patch;
	struct fct_plane *pl;
	struct fct_segment_stats st;
	size_t np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 2);
	int split = 1;
	for (size_t f = 0; f < m.nf; f++)
		split &= patch[f] == (f < 18 ? 0 : 1);
	CHECK(split);
	for (size_t l = 0; l < np && l < 2; l++) {
		CHECK_NEAR(pl[l].n[2], 1, 0);
		CHECK_NEAR(pl[l].d, 0, 0);
		CHECK_INT(pl[l].count, 16);
	}
	free(patch), free(pl);
	p.target = 1;               /* not even on request: they are not adjacent */
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 2);
	free(patch), free(pl);
	fct_mesh_free(&m);

	/* A single face, and a 10 x 10 grid: one patch. */
	fct_mesh_init(&m);
	add_vertex(&m, 0, 0, 0), add_vertex(&m, 2, 0, 0), add_vertex(&m, 0, 0, 3);
	add_face(&m, 0, 1, 2);
	fct_segment_params_default(&p);
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 1);
	CHECK_INT(patch[0], 0);
	CHECK_NEAR(pl[0].n[1], -1, 1e-15);   /* (2,0,0) x (0,0,3) = (0,-6,0) */
	CHECK_INT(pl[0].count, 3);
	free(patch), free(pl);
	fct_mesh_free(&m);

	fct_mesh_init(&m);
	add_grid(&m, 10, 10, -3, 7);
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 1);
	CHECK_INT(st.merges, 199);
	CHECK_NEAR(pl[0].rms, 0, 0);
	free(patch), free(pl);
	fct_mesh_free(&m);

	/* No faces at all: no patches, no planes. */
	fct_mesh_init(&m);
	add_vertex(&m, 1, 2, 3);
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 0);
	CHECK(pl == NULL);
	free(patch);
	fct_mesh_free(&m);
}

/* A strip of n x 2 cells folded along x = n/2 by the angle fold (radians):
 * two patches, split exactly at the fold, normals exact to rounding. */
static void test_fold(double fold)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	int n = 12;
	for (int j = 0; j <= 2; j++)
		for (int i = 0; i <= n; i++) {
			double x = i - n / 2.0;
			if (x <= 0)
				add_vertex(&m, x, j, 0);
			else
				add_vertex(&m, x * cos(fold), j, x * sin(fold));
		}
	for (int j = 0; j < 2; j++)
		for (int i = 0; i < n; i++) {
			uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)(n + 1), d = c + 1;
			add_face(&m, a, b, d);
			add_face(&m, a, d, c);
		}
	/* Exact data, and known to be: estimated from so few samples, the
	 * noise would be the fold itself (noise.h looks beyond the one-ring). */
	double *sigma = malloc(m.nv * sizeof *sigma);
	for (size_t v = 0; v < m.nv; v++)
		sigma[v] = 1e-9;
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	p.sigma = sigma;
	for (int pass = 0; pass < 2; pass++) {
		p.target = pass ? 2 : 0;
		int32_t *patch;
		struct fct_plane *pl;
		struct fct_segment_stats st;
		size_t np = segment(&m, &p, &patch, &pl, &st);
		CHECK_INT(np, 2);
		int exact = 1;
		for (size_t f = 0; f < m.nf; f++)
			exact &= patch[f] == ((f / 2) % n < (size_t)n / 2 ? 0 : 1);
		CHECK_MSG(exact, "fold %g: split at the fold", fold);
		if (np == 2) {
			CHECK_NEAR(pl[0].n[2], 1, 1e-12);
			CHECK_NEAR(pl[1].n[0], -sin(fold), 1e-12);
			CHECK_NEAR(pl[1].n[2], cos(fold), 1e-12);
			CHECK_NEAR(pl[1].d, 0, 1e-12);
			CHECK(pl[0].rms < 1e-12 && pl[1].rms < 1e-12);
		}
		free(patch), free(pl);
	}
	free(sigma);
	fct_mesh_free(&m);
}

/* A board thinner than its noise: an n x n grid whose inner vertices are at
 * z = +t on top (faces wound to +z) and z = -t below (wound to -z), its
 * border shared.  Every point lies within the noise of z = 0, so one plane
 * fits the whole; but a mesh without a viewpoint is two-sided, its top and
 * bottom face opposite ways, and one patch of both would fold over itself
 * in the plane: two patches, normals +z and -z, and no face of one turned
 * against its plane.  Seen from a viewpoint (a view's mesh faces it), the
 * same faces are one plane. */
static void test_two_sided(void)
{
	const int n = 8;
	const double t = 0.001;
	struct fct_mesh m;
	fct_mesh_init(&m);
	uint32_t top[9][9], bot[9][9];
	for (int j = 0; j <= n; j++)
		for (int i = 0; i <= n; i++) {
			int border = i == 0 || j == 0 || i == n || j == n;
			top[j][i] = (uint32_t)m.nv;
			add_vertex(&m, i, j, border ? 0 : t);
			if (border) {
				bot[j][i] = top[j][i];
			} else {
				bot[j][i] = (uint32_t)m.nv;
				add_vertex(&m, i, j, -t);
			}
		}
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			add_face(&m, top[j][i], top[j][i + 1], top[j + 1][i + 1]);
			add_face(&m, top[j][i], top[j + 1][i + 1], top[j + 1][i]);
			add_face(&m, bot[j][i], bot[j + 1][i + 1], bot[j][i + 1]);
			add_face(&m, bot[j][i], bot[j + 1][i], bot[j + 1][i + 1]);
		}
	double *sigma = malloc(m.nv * sizeof *sigma);
	for (size_t v = 0; v < m.nv; v++)
		sigma[v] = 0.01;   /* the board's 2 mm are a fifth of the noise */
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	p.sigma = sigma;
	p.min_faces = 0;
	int32_t *patch;
	struct fct_plane *pl;
	struct fct_segment_stats st;
	size_t np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 2);
	int split = np == 2;
	for (size_t f = 0; split && f < m.nf; f++) {
		int is_top = f % 4 < 2;
		split &= patch[f] >= 0 && pl[patch[f]].n[2] * (is_top ? 1 : -1) > 0.99;
	}
	CHECK_MSG(split, "top and bottom apart, each facing its way");
	free(patch), free(pl);

	p.use_viewpoint = 1;   /* one side seen: one plane */
	p.viewpoint[0] = p.viewpoint[1] = n / 2.0, p.viewpoint[2] = 10;
	np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(np, 1);
	free(patch), free(pl);
	free(sigma);
	fct_mesh_free(&m);
}

/* Three noisy 24 x 24 grids meeting in a corner (floor and two walls),
 * Gaussian noise of a tenth of the cell along each normal. */
static void make_corner(struct fct_mesh *m, const double rot[9], double scale, const double t[3])
{
	struct fct_rng r;
	fct_rng_seed(&r, 42);
	fct_mesh_init(m);
	int n = 24;
	for (int side = 0; side < 3; side++) {
		uint32_t base = (uint32_t)m->nv;
		for (int j = 0; j <= n; j++)
			for (int i = 0; i <= n; i++) {
				double u = i * 0.1, v = j * 0.1, e = 0.01 * fct_rng_normal(&r);
				double p[3];
				if (side == 0)
					p[0] = u, p[1] = v, p[2] = e;
				else if (side == 1)
					p[0] = u, p[1] = e, p[2] = v;
				else
					p[0] = e, p[1] = u, p[2] = v;
				double q[3];
				for (int k = 0; k < 3; k++)
					q[k] = scale * (rot[3 * k] * p[0] + rot[3 * k + 1] * p[1] + rot[3 * k + 2] * p[2]) + t[k];
				add_vertex(m, q[0], q[1], q[2]);
			}
		for (int j = 0; j < n; j++)
			for (int i = 0; i < n; i++) {
				uint32_t a = base + (uint32_t)(j * (n + 1) + i), b = a + 1;
				uint32_t c = a + (uint32_t)(n + 1), d = c + 1;
				add_face(m, a, b, d);
				add_face(m, a, d, c);
			}
	}
}

/* The three planes of the corner are found (they share no edge in this
 * mesh, so the test is that noise does not split them), and rotating,
 * scaling and moving the input changes no label. */
static void test_invariance(void)
{
	static const double id[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }, t0[3] = { 0, 0, 0 };
	/* A rotation about (1, 2, 2)/3 by 50 degrees. */
	double ax[3] = { 1 / 3.0, 2 / 3.0, 2 / 3.0 }, c = cos(50 * M_PI / 180), s = sin(50 * M_PI / 180);
	double rot[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			rot[3 * i + j] = (i == j ? c : 0) + (1 - c) * ax[i] * ax[j];
	rot[1] -= s * ax[2], rot[2] += s * ax[1], rot[3] += s * ax[2];
	rot[5] -= s * ax[0], rot[6] -= s * ax[1], rot[7] += s * ax[0];
	const double t1[3] = { 1000, -250, 3.5 };

	struct fct_mesh a, b;
	make_corner(&a, id, 1, t0);
	make_corner(&b, rot, 37.5, t1);
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	int32_t *pa, *pb;
	struct fct_plane *la, *lb;
	struct fct_segment_stats sa, sb;
	size_t na = segment(&a, &p, &pa, &la, &sa);
	size_t nb = segment(&b, &p, &pb, &lb, &sb);
	CHECK_INT(na, 3);
	CHECK_INT(nb, na);
	size_t same = 0;
	for (size_t f = 0; f < a.nf; f++)
		same += pa[f] == pb[f];
	CHECK_INT(same, a.nf);
	for (size_t f = 0; f < a.nf; f++)
		if (pa[f] != (int32_t)(f / 1152)) {
			CHECK_MSG(0, "face %zu in patch %d", f, pa[f]);
			break;
		}
	CHECK_NEAR(sb.noise, 37.5 * sa.noise, 1e-6 * sb.noise);   /* kept as a float */
	if (na == 3 && nb == 3) {
		/* Normals within the noise of the axes, rotated with the input. */
		CHECK(la[0].n[2] > 0.9999 && la[1].n[1] < -0.9999 && la[2].n[0] > 0.9999);
		for (int l = 0; l < 3; l++) {
			for (int k = 0; k < 3; k++) {
				double r = rot[3 * k] * la[l].n[0] + rot[3 * k + 1] * la[l].n[1] + rot[3 * k + 2] * la[l].n[2];
				CHECK_NEAR(lb[l].n[k], r, 1e-9);
			}
			CHECK_NEAR(lb[l].rms, 37.5 * la[l].rms, 1e-9 * lb[l].rms);
			CHECK(la[l].rms > 0.008 && la[l].rms < 0.012);   /* the noise, 0.01 */
		}
	}
	free(pa), free(pb), free(la), free(lb);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
}

/* The rms distance of all of m's face corners from plane pl. */
static double corner_rms(const struct fct_plane *pl, const struct fct_mesh *m)
{
	double sum = 0;
	for (size_t k = 0; k < m->fstart[m->nf]; k++) {
		const double *x = &m->xyz[3 * m->fvert[k]];
		double d = fct_plane_distance(pl, x);
		sum += d * d;
	}
	return sqrt(sum / m->fstart[m->nf]);
}

/* Area weighting fits the surface, not its sampling: a bent quad and the
 * same surface with one triangle split in four give the same plane; the
 * corner-weighted fit does not. */
static void test_area(void)
{
	struct fct_mesh m, s;
	fct_mesh_init(&m);
	add_vertex(&m, 0, 0, 0), add_vertex(&m, 1, 0, 0);
	add_vertex(&m, 1, 1, 0.3), add_vertex(&m, 0, 1, 0);
	add_face(&m, 0, 1, 2);
	add_face(&m, 0, 2, 3);
	fct_mesh_init(&s);
	add_vertex(&s, 0, 0, 0), add_vertex(&s, 1, 0, 0);
	add_vertex(&s, 1, 1, 0.3), add_vertex(&s, 0, 1, 0);
	add_vertex(&s, 0.5, 0, 0), add_vertex(&s, 1, 0.5, 0.15), add_vertex(&s, 0.5, 0.5, 0.15);
	add_face(&s, 0, 4, 6), add_face(&s, 4, 1, 5), add_face(&s, 4, 5, 6), add_face(&s, 6, 5, 2);
	add_face(&s, 0, 6, 3), add_face(&s, 6, 2, 3);   /* the other half split at 6 too */
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	p.target = 1;
	p.max_dev = 0;   /* the fit itself: no face peeled off the bent quad's plane */
	p.area_weighted = 1;
	int32_t *pm, *ps;
	struct fct_plane *lm, *ls;
	struct fct_segment_stats st;
	segment(&m, &p, &pm, &lm, &st);
	segment(&s, &p, &ps, &ls, &st);
	for (int k = 0; k < 3; k++)
		CHECK_NEAR(ls[0].n[k], lm[0].n[k], 1e-14);
	CHECK_NEAR(ls[0].d, lm[0].d, 1e-14);
	/* rms: the residual of each mesh's own corners from that plane */
	CHECK_NEAR(lm[0].rms, corner_rms(&lm[0], &m), 1e-15);
	CHECK_NEAR(ls[0].rms, corner_rms(&ls[0], &s), 1e-15);
	/* The bent quad is symmetric in x and y: so is its plane. */
	CHECK_NEAR(lm[0].n[0], lm[0].n[1], 1e-15);
	CHECK(lm[0].n[2] > 0.97);
	free(pm), free(ps), free(lm), free(ls);

	p.area_weighted = 0;   /* corners: the denser half pulls */
	segment(&m, &p, &pm, &lm, &st);
	segment(&s, &p, &ps, &ls, &st);
	CHECK(fabs(ls[0].n[0] - lm[0].n[0]) > 1e-3);
	free(pm), free(ps), free(lm), free(ls);
	fct_mesh_free(&m);
	fct_mesh_free(&s);
}

/* Three triangles on one edge (one pair coplanar), a quad and a pentagon,
 * and degenerate faces: no crash, every face labelled, exact planes. */
static void test_topology(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	add_vertex(&m, 0, 0, 0), add_vertex(&m, 0, 1, 0);   /* the shared edge */
	add_vertex(&m, 1, 0.5, 0), add_vertex(&m, -1, 0.5, 0), add_vertex(&m, 0, 0.5, 1);
	add_face(&m, 0, 1, 2), add_face(&m, 1, 0, 3), add_face(&m, 0, 1, 4);
	struct fct_segment_params p;
	fct_segment_params_default(&p);
	int32_t *patch;
	struct fct_plane *pl;
	struct fct_segment_stats st;
	size_t np = segment(&m, &p, &patch, &pl, &st);
	CHECK_INT(st.adjacencies, 3);       /* all pairs around the edge */
	CHECK_INT(np, 2);
	CHECK(patch[0] == 0 && patch[1] == 0 && patch[2] == 1);
	free(patch), free(pl);
	fct_mesh_free(&m);

	/* A quad and a pentagon in z = 2 next to a triangle in x = 0. */
	fct_mesh_init(&m);
	add_vertex(&m, 0, 0, 2), add_vertex(&m, 1, 0, 2), add_vertex(&m, 1, 1, 2), add_vertex(&m, 0, 1, 2);
	add_vertex(&m, 2, 0, 2), add_vertex(&m, 2.5, 0.5, 2), add_vertex(&m, 2, 1, 2);
	add_vertex(&m, 0, 0.5, 3);
	uint32_t quad[4] = { 0, 1, 2, 3 }, pent[5] = { 1, 4, 5, 6, 2 }, tri[3] = { 3, 7, 0 };
	fct_mesh_add_face(&m, quad, 4, &err);
	fct_mesh_add_face(&m, pent, 5, &err);
	fct_mesh_add_face(&m, tri, 3, &err);
	for (int area = 0; area < 2; area++) {
		p.area_weighted = area;
		np = segment(&m, &p, &patch, &pl, &st);
		CHECK_INT(np, 2);
		CHECK(patch[0] == 0 && patch[1] == 0 && patch[2] == 1);
		if (np == 2) {
			CHECK_NEAR(pl[0].n[2], 1, 1e-15);
			CHECK_NEAR(pl[0].d, -2, 1e-15);
			CHECK_NEAR(pl[1].n[0], 1, 1e-15);   /* (7-3) x (0-3) = (1, 0, 0) */
			CHECK_INT(pl[0].count, 7);
		}
		free(patch), free(pl);
	}
	fct_mesh_free(&m);

	/* Degenerate faces: a repeated vertex, a zero-area sliver, a 2-gon,
	 * a face using one vertex thrice; all but the last (no edge to any
	 * other) get labels. */
	fct_mesh_init(&m);
	add_grid(&m, 2, 2, 0, 0);
	uint32_t rep[3] = { 0, 1, 1 }, two[2] = { 3, 4 }, one[3] = { 5, 5, 5 };
	fct_mesh_add_face(&m, rep, 3, &err);
	add_face(&m, 0, 1, 2);   /* collinear: area 0 */
	fct_mesh_add_face(&m, two, 2, &err);
	fct_mesh_add_face(&m, one, 3, &err);
	for (int area = 0; area < 2; area++) {
		p.area_weighted = area;
		np = segment(&m, &p, &patch, &pl, &st);
		/* The face of one vertex shares no edge: a patch of one face,
		 * smaller than min_faces, may be free-form (-1). */
		int labelled = 1;
		for (size_t f = 0; f < m.nf; f++)
			labelled &= (patch[f] >= 0 || f == m.nf - 1) && patch[f] < (int32_t)np;
		CHECK(labelled);
		CHECK(np >= 1 && np <= 4);
		CHECK_INT(patch[0], 0);
		for (size_t l = 0; l < np; l++)
			CHECK(isfinite(pl[l].n[0]) && isfinite(pl[l].d) && isfinite(pl[l].rms));
		free(patch), free(pl);
	}
	fct_mesh_free(&m);

	/* Non-finite coordinates are refused. */
	fct_mesh_init(&m);
	add_vertex(&m, 0, 0, 0), add_vertex(&m, 1, 0, 0), add_vertex(&m, 0, NAN, 0);
	add_face(&m, 0, 1, 2);
	int32_t lab[1];
	size_t n;
	CHECK_INT(fct_segment(lab, &pl, &n, &m, &p, NULL, &err), -1);
	CHECK(strstr(err.msg, "vertex 2") != NULL);
	fct_mesh_free(&m);
}

/* The eigen helpers against known spectra. */
static void test_eigen(void)
{
	/* R diag(l) R^T for a rotation R and several spectra. */
	static const double spectra[][3] = {
		{ 3, 2, 1 }, { 1, 1, 1 }, { 5, 5, 1e-9 }, { 1, 1e-6, 1e-12 }, { 2, 0, 0 }, { 0, 0, 0 }, { 4, 1, 1 },
	};
	double c = cos(0.7), s = sin(0.7), c2 = cos(1.9), s2 = sin(1.9);
	double R[3][3] = { { c, -s, 0 }, { s * c2, c * c2, -s2 }, { s * s2, c * s2, c2 } };
	for (size_t k = 0; k < sizeof spectra / sizeof *spectra; k++) {
		double M[3][3] = { { 0 } };
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				for (int q = 0; q < 3; q++)
					M[i][j] += R[i][q] * spectra[k][q] * R[j][q];
		double sm[6] = { M[0][0], M[1][1], M[2][2], M[0][1], M[1][2], M[0][2] };
		double lmin = spectra[k][0];
		for (int q = 1; q < 3; q++)
			lmin = fmin(lmin, spectra[k][q]);
		double mid = spectra[k][0] + spectra[k][1] + spectra[k][2] - lmin -
		             fmax(spectra[k][0], fmax(spectra[k][1], spectra[k][2]));
		double tol = 4e-16 * spectra[k][0] * (mid > 0 ? fmax(1, spectra[k][0] / mid) : 1);
		CHECK_NEAR(fct_sym3_min_eigenvalue(sm), lmin, tol + 1e-300);
		struct fct_plane pl;
		double cen[3] = { 1, 2, 3 };
		double l = fct_plane_fit(&pl, cen, sm);
		CHECK_NEAR(l, lmin, 4e-16 * spectra[k][0] + 1e-300);
		CHECK_NEAR(pl.n[0] * pl.n[0] + pl.n[1] * pl.n[1] + pl.n[2] * pl.n[2], 1, 1e-15);
		CHECK_NEAR(pl.n[0] * cen[0] + pl.n[1] * cen[1] + pl.n[2] * cen[2] + pl.d, 0, 1e-14);
		if (spectra[k][2] < spectra[k][1]) {   /* a unique smallest: its axis */
			double dot = fabs(pl.n[0] * R[0][2] + pl.n[1] * R[1][2] + pl.n[2] * R[2][2]);
			CHECK_NEAR(dot, 1, 1e-12);
		}
	}
}

int main(void)
{
	test_cube();
	test_coplanar();
	test_two_sided();
	test_fold(M_PI / 2);
	test_fold(0.3);
	test_fold(M_PI * 0.9);   /* a sharp V: the halves nearly face each other */
	test_invariance();
	test_area();
	test_topology();
	test_eigen();
	CHECK_DONE();
}
