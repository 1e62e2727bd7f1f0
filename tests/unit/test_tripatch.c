/* test_tripatch - tripatch on wireframes built here: chaining of outer
 * loops and holes, orientation against the plane normal (also mirrored
 * s t), the fallback from non-simple s t to the plane, a patch touching
 * itself at a vertex, open chains, slits, and the bad inputs.  The
 * triangulation itself (polytri.c) is tested in test_polytri.c. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/planes.h"
#include "core/rng.h"
#include "planar/tripatch.h"

/* A wireframe: vertices (x y z, then s t when w is 5), edges (v1 v2 p1
 * p2), planes (nx ny nz d); s t are written when st is set. */
static void wire_w(struct fct_mesh *m, const double *v, size_t w, size_t nv, int st, const int *e,
                   size_t ne, const double *pl, size_t npl)
{
	struct fct_err err;
	fct_mesh_init(m);
	for (size_t i = 0; i < nv; i++)
		fct_mesh_add_vertex(m, v[w * i], v[w * i + 1], v[w * i + 2], &err);
	if (st) {
		fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, &err);
		fct_elem_add_scalar(&m->vertex, "t", FCT_FLOAT32, &err);
		for (size_t i = 0; i < nv; i++) {
			fct_prop_set(fct_elem_find(&m->vertex, "s"), i, v[w * i + 3]);
			fct_prop_set(fct_elem_find(&m->vertex, "t"), i, v[w * i + 4]);
		}
	}
	struct fct_elem *el = fct_mesh_add_elem(m, "edge", ne, &err);
	static const char *const names[] = { "vertex1", "vertex2", "patch1", "patch2" };
	for (int k = 0; k < 4; k++)
		fct_elem_add_scalar(el, names[k], FCT_INT32, &err);
	for (int k = 0; k < 4; k++)
		for (size_t i = 0; i < ne; i++)
			fct_prop_set(fct_elem_find(el, names[k]), i, e[4 * i + k]);
	if (pl) {
		struct fct_plane *p = calloc(npl, sizeof *p);
		for (size_t i = 0; i < npl; i++)
			memcpy(p[i].n, pl + 4 * i, 3 * sizeof(double)), p[i].d = pl[4 * i + 3];
		fct_planes_set(m, p, npl, &err);
		free(p);
	}
}

static void wire(struct fct_mesh *m, const double *v, size_t nv, int st, const int *e, size_t ne,
                 const double *pl, size_t npl)
{
	wire_w(m, v, st ? 5 : 3, nv, st, e, ne, pl, npl);
}

/* Sum over faces of patch p of (b - a) x (c - a) . n, and the area. */
static double patch_dot(const struct fct_mesh *m, int patch, const double n[3], double *area)
{
	const struct fct_prop *pp = fct_elem_find(&m->face, "patch");
	double s = 0;
	*area = 0;
	for (size_t f = 0; f < m->nf; f++) {
		if (fct_prop_get(pp, f) != patch)
			continue;
		const double *a = &m->xyz[3 * m->fvert[3 * f]], *b = &m->xyz[3 * m->fvert[3 * f + 1]],
		             *c = &m->xyz[3 * m->fvert[3 * f + 2]];
		double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
		double x[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
		double d = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
		s += d;
		*area += sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / 2;
		if (d <= 0)
			s -= 1e300;   /* one face against the normal spoils the sum */
	}
	return s;
}

static void test_wire_hole(void)
{
	/* The 4 x 4 square (patch 0) around the 2 x 2 square (patch 1) in the
	 * plane x = 1, normal +x, the inner square with s t seen mirrored. */
	static const double v[] = {
		1, 0, 0, 0.0, 1.0,  1, 4, 0, 1.0, 1.0,  1, 4, 4, 1.0, 0.0,  1, 0, 4, 0.0, 0.0,
		1, 1, 1, 0.25, 0.75, 1, 3, 1, 0.75, 0.75, 1, 3, 3, 0.75, 0.25, 1, 1, 3, 0.25, 0.25,
	};
	/* (y, z) counter-clockwise seen from +x: (0,0) (4,0) (4,4) (0,4) */
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1,
	                         4, 5, 1, 0, 5, 6, 1, 0, 6, 7, 1, 0, 7, 4, 1, 0 };
	static const double pl[] = { 1, 0, 0, -1, 1, 0, 0, -1 };
	for (int method = 0; method < 2; method++)
		for (int st = 0; st < 2; st++) {
			struct fct_mesh m;
			struct fct_err err;
			struct fct_tripatch_params p;
			struct fct_tripatch_stats s;
			wire_w(&m, v, 5, 8, st, e, 8, pl, 2);
			fct_tripatch_params_default(&p);
			p.method = method;
			CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
			CHECK_INT(m.nf, 10);
			CHECK_INT(s.triangles, 10);
			CHECK_INT(s.patches, 2);
			CHECK_INT(s.polygons, 2);
			CHECK_INT(s.holes, 1);
			CHECK_INT(s.in_st, st ? 2 : 0);
			CHECK_INT(s.in_plane, st ? 0 : 2);
			CHECK_INT(s.failures + s.repairs + s.fallbacks + s.reversed, 0);
			CHECK(fct_mesh_find_elem(&m, "edge") == NULL);
			CHECK(fct_mesh_find_elem(&m, "plane") != NULL);
			CHECK_INT(m.nv, 8);
			if (st)
				CHECK(fct_elem_find(&m.vertex, "s") != NULL);
			double area, n[3] = { 1, 0, 0 };
			CHECK(patch_dot(&m, 0, n, &area) > 0);
			CHECK(area == 12);
			CHECK(patch_dot(&m, 1, n, &area) > 0);
			CHECK(area == 4);
			fct_mesh_free(&m);
		}
}

/* One square patch in z = 0 seen from -z (normal -z, edges clockwise in
 * x, y), whose s t make a bow tie: s t refused, the plane used. */
static void test_wire_fallback(void)
{
	static const double v[] = {
		0, 0, 0, 0, 0,  0, 2, 0, 1, 1,  2, 2, 0, 1, 0,  2, 0, 0, 0, 1,
	};
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
	static const double pl[] = { 0, 0, -1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v, 4, 1, e, 4, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.fallbacks, 1);
	CHECK_INT(s.in_plane, 1);
	CHECK_INT(s.in_st, 0);
	CHECK_INT(m.nf, 2);
	double area, n[3] = { 0, 0, -1 };
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	CHECK(area == 4);
	fct_mesh_free(&m);

	/* The same with a plane normal of +z (against the edges): the patch is
	 * reversed to agree with the plane. */
	static const double up[] = { 0, 0, 1, 0 };
	wire_w(&m, v, 5, 4, 0, e, 4, up, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.reversed, 1);
	double n2[3] = { 0, 0, 1 };
	CHECK(patch_dot(&m, 0, n2, &area) > 0);
	fct_mesh_free(&m);

	/* No plane element: the Newell normal of the edges decides. */
	wire_w(&m, v, 5, 4, 0, e, 4, NULL, 0);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 2);
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	fct_mesh_free(&m);
}

/* Patch 0 is two squares meeting at the vertex (1,1) (a bow-tie-shaped
 * patch touching itself); patch 1 fills the rest of the 2 x 2 square as
 * two squares too.  Plus an open chain and a slit. */
static void test_wire_touch(void)
{
	/* 0 (0,0) 1 (1,0) 2 (2,0) 3 (0,1) 4 (1,1) 5 (2,1) 6 (0,2) 7 (1,2) 8 (2,2) */
	static const double v[] = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 0, 2, 0, 1, 2, 0, 2, 2, 0 };
	static const int e[] = {
		0, 1, 0, -1, 1, 4, 0, 1, 4, 3, 0, 1, 3, 0, 0, -1,     /* patch 0: lower left */
		4, 5, 0, 1, 5, 8, 0, -1, 8, 7, 0, -1, 7, 4, 0, 1,     /* patch 0: upper right */
		1, 2, 1, -1, 2, 5, 1, -1, 7, 6, 1, -1, 6, 3, 1, -1,   /* patch 1's border edges */
	};
	static const double pl[] = { 0, 0, 1, 0, 0, 0, 1, 0 };
	for (int method = 0; method < 2; method++) {
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, 9, 0, e, 12, pl, 2);
		fct_tripatch_params_default(&p);
		p.method = method;
		CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
		CHECK_INT(s.polygons, 4);
		CHECK_INT(s.holes, 0);
		CHECK_INT(m.nf, 8);
		CHECK_INT(s.failures + s.repairs + s.open_edges, 0);
		double area, n[3] = { 0, 0, 1 };
		CHECK(patch_dot(&m, 0, n, &area) > 0);
		CHECK(area == 2);
		CHECK(patch_dot(&m, 1, n, &area) > 0);
		CHECK(area == 2);
		fct_mesh_free(&m);
	}

	/* A square with a dangling edge and a slit (an edge with patch 0 on
	 * both sides) into its middle. */
	static const double v2[] = { 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 1, 0, 3, 3, 0 };
	static const int e2[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1,
	                          2, 4, 0, 0, 2, 5, 0, -1 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v2, 6, 0, e2, 6, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.open_edges, 1);
	CHECK_INT(s.slits, 1);
	CHECK_INT(m.nf, 2);
	fct_mesh_free(&m);

	/* Only a dangling edge: the patch fails, clearly counted. */
	static const int e3[] = { 0, 1, 0, -1 };
	wire(&m, v2, 6, 0, e3, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.failures, 1);
	CHECK_INT(s.first_failure, 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);

	/* A closed triangle whose corners projection put on one point and a
	 * line (two copies at one position, as on the TUM frame): no area in
	 * either frame, so a degenerate loop, not a failure. */
	static const double v4[] = { 0, 0, 0, 0, 0, 0, 1, 0, 0 };
	static const int e4[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 0, 0, -1 };
	wire(&m, v4, 3, 0, e4, 3, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.failures, 0);
	CHECK_INT(s.degenerate, 1);
	CHECK_INT(s.open_edges, 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);
}

/* A B C on one line in space but not in the image (B a little below A-C
 * there), D far above: the greedy method cuts the short diagonal A-C, so
 * A-B-C is a triangle of no area in space; its longest edge A-C is flipped
 * with A-C-D into A-B-D and B-C-D, of area 2.5 each. */
static void test_wire_sliver(void)
{
	static const double v[] = { 0, 0, 0, 0, 0, 1, 0, 0, 1, -0.01, 2, 0, 0, 2, 0, 1, 5, 0, 1, 5 };
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
	static const double pl[] = { 0, 0, 1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v, 4, 1, e, 4, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.in_st, 1);
	CHECK_INT(s.slivers_flipped, 1);
	CHECK_INT(m.nf, 2);
	double area, n[3] = { 0, 0, 1 };
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	CHECK_NEAR(area, 5, 1e-12);
	for (size_t f = 0; f < m.nf; f++) {
		int has_b = 0;
		for (int q = 0; q < 3; q++)
			has_b |= m.fvert[3 * f + q] == 1;
		CHECK(has_b);   /* both faces use B: the diagonal is B-D */
	}
	fct_mesh_free(&m);
}

/* Three boundary vertices on one image line at pixel centres (as dm2mesh
 * makes them), stored as float s t of a 640 x 480 camera: snapped to the
 * centres they are exactly collinear, so the greedy method cannot cut the
 * zero-area ear A-B-C through the short A-C and takes B-D instead (without
 * the snap, 17 of these 40 placements came out as slivers). */
static void test_wire_snap(void)
{
	size_t good = 0, runs = 0;
	for (int k = 0; k < 40; k++) {
		/* the same shape moved by k pixels: the float rounding differs */
		double px[] = { 100.5, 461.5, 101.5, 460.5, 102.5, 459.5, 102.5, 500.5 };
		double v[20];
		for (int i = 0; i < 4; i++) {
			px[2 * i] += 7 * k, px[2 * i + 1] -= 9 * k;
			v[5 * i] = px[2 * i] / 100, v[5 * i + 1] = px[2 * i + 1] / 100, v[5 * i + 2] = 1;
			v[5 * i + 3] = (float)(px[2 * i] / 640), v[5 * i + 4] = (float)(px[2 * i + 1] / 480);
		}
		static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
		static const double pl[] = { 0, 0, 1, -1 };
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, 4, 1, e, 4, pl, 1);
		fct_mesh_add_comment(&m, "camera pinhole 640 480 500 500 319.5 239.5", 0, &err);
		fct_tripatch_params_default(&p);
		if (fct_tripatch(&m, &p, &s, &err) == 0 && s.in_st == 1 && m.nf == 2) {
			size_t withd = 0;
			for (size_t f = 0; f < m.nf; f++)
				withd += m.fvert[3 * f] == 3 || m.fvert[3 * f + 1] == 3 || m.fvert[3 * f + 2] == 3;
			good += withd == 2;
		}
		runs++;
		fct_mesh_free(&m);
	}
	CHECK_INT(good, runs);
}

static void test_wire_bad(void)
{
	static const double v[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0 };
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 0, 0, -1 };
	static const double pl[] = { 0, 0, 1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	fct_tripatch_params_default(&p);
	/* no edge element */
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0, 0, 0, &err);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	CHECK(strstr(err.msg, "no edge element") != NULL);
	fct_mesh_free(&m);
	/* a patch that is not a plane */
	static const int e1[] = { 0, 1, 3, -1 };
	wire(&m, v, 3, 0, e1, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	CHECK(strstr(err.msg, "edge 0: patch 3") != NULL);
	fct_mesh_free(&m);
	/* a vertex out of range, equal ends, no patch */
	static const int e2[] = { 0, 7, 0, -1 }, e3[] = { 1, 1, 0, -1 }, e4[] = { 0, 1, -1, -1 };
	wire(&m, v, 3, 0, e2, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	wire(&m, v, 3, 0, e3, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	wire(&m, v, 3, 0, e4, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	/* empty: no vertices, no edges */
	wire(&m, v, 0, 0, e, 0, pl, 1);
	struct fct_tripatch_stats s;
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 0);
	CHECK(m.has_faces);
	fct_mesh_free(&m);
	/* the good triangle */
	wire(&m, v, 3, 0, e, 3, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 1);
	CHECK_INT(m.fvert[0], 0);
	CHECK_INT(m.fvert[1], 1);
	CHECK_INT(m.fvert[2], 2);
	fct_mesh_free(&m);
}

/* Random edge soups (crossing, open, duplicated, random s t) and random
 * loops of a few patches: tripatch never fails on them, every face uses
 * existing vertices and no face repeats a vertex; closed random loops are
 * triangulated (repaired when they cross) with n - 2 triangles each. */
static void test_wire_random(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	size_t bad = 0, faces = 0, repairs = 0, earclipped = 0, loops_ok = 0;
	for (int it = 0; it < 300; it++) {
		size_t nv = 3 + fct_rng_below(&r, 30), ne = 1 + fct_rng_below(&r, 40);
		int closed = it % 2;
		double *v = malloc(5 * nv * sizeof *v);
		int *e = malloc(4 * (ne + nv) * sizeof *e);
		for (size_t i = 0; i < nv; i++) {
			v[5 * i] = fct_rng_uniform(&r), v[5 * i + 1] = fct_rng_uniform(&r);
			v[5 * i + 2] = 0.1 * fct_rng_uniform(&r);
			v[5 * i + 3] = fct_rng_uniform(&r), v[5 * i + 4] = fct_rng_uniform(&r);
		}
		if (closed) {
			/* one random (usually self-crossing) loop through all vertices */
			ne = nv;
			for (size_t i = 0; i < nv; i++) {
				e[4 * i] = (int)i, e[4 * i + 1] = (int)((i + 1) % nv);
				e[4 * i + 2] = 0, e[4 * i + 3] = -1;
			}
		} else {
			for (size_t i = 0; i < ne; i++) {
				e[4 * i] = (int)fct_rng_below(&r, nv);
				e[4 * i + 1] = (int)((e[4 * i] + 1 + fct_rng_below(&r, nv - 1)) % nv);
				e[4 * i + 2] = (int)fct_rng_below(&r, 3);
				e[4 * i + 3] = (int)fct_rng_below(&r, 4) - 1;
			}
		}
		static const double pl[] = { 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0 };
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, nv, (int)fct_rng_below(&r, 2), e, ne, pl, 3);
		fct_tripatch_params_default(&p);
		p.method = (int)fct_rng_below(&r, 2);
		int rc = fct_tripatch(&m, &p, &s, &err);
		bad += rc != 0;
		if (rc == 0) {
			for (size_t f = 0; f < m.nf; f++) {
				const uint32_t *t = &m.fvert[3 * f];
				bad += t[0] >= nv || t[1] >= nv || t[2] >= nv || t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
			}
			faces += m.nf, repairs += s.repairs, earclipped += s.earclipped;
			loops_ok += closed && m.nf == nv - 2;
		}
		fct_mesh_free(&m);
		free(v), free(e);
	}
	CHECK_INT(bad, 0);
	CHECK(faces > 0);
	CHECK(repairs > 0);
	CHECK(earclipped > 0);
	CHECK_INT(loops_ok, 150);
}

/* A ceiling seen by a cylindrical panorama (64 x 16, f = 64 / 2 pi, the
 * seam at +x, the ceiling 1 above the camera, y down): the room's corners
 * (the outer loop, in s t a simple sliver between rows 4.66 and 4.67)
 * and the panorama's top row (the hole: the disc overhead that no row
 * sees, in s t a line without area) both go round the camera, so in s t
 * neither is the polygon it is on the ceiling.  The 2048 x 512 room's
 * ceiling came out in s t as the corners' sliver without its hole: two
 * triangles over the zenith, which no planar view holds (cyl2planar
 * failed).  Triangulated in its plane it keeps the hole: 4 + 8 corners,
 * 12 triangles. */
static void test_wire_cylinder(void)
{
	const double W = 64, H = 16, f = W / (2 * M_PI), cy = 7.5;
	static const double corner[4][2] = { { 3, -2 }, { 3, 2 }, { -2.9, 2.1 }, { -2.9, -2.1 } };
	double v[12 * 5];
	for (int i = 0; i < 12; i++) {
		double x, z;
		if (i < 4) {
			x = corner[i][0], z = corner[i][1];
		} else {
			/* the top row's pixel edge: h = (-0.5 - cy) / f */
			double rho = -1 / ((-0.5 - cy) / f), th = 2 * M_PI * ((i - 4) * 8 + 0.5) / W;
			x = rho * sin(th), z = rho * cos(th);
		}
		double th = atan2(x, z), rho = hypot(x, z);
		double u = (th - M_PI / 2) * W / (2 * M_PI), row = cy + f * -1 / rho;
		u -= W * floor((u + 0.5) / W);
		v[5 * i] = x, v[5 * i + 1] = -1, v[5 * i + 2] = z;
		v[5 * i + 3] = (u + 0.5) / W, v[5 * i + 4] = 1 - (row + 0.5) / H;
	}
	/* outer: the corners in turn, clockwise in (x, z); hole: the octagon
	 * the other way round */
	int e[12 * 4], ne = 0;
	for (int i = 0; i < 4; i++) {
		int a[4] = { i, (i + 1) % 4, 0, -1 };
		memcpy(e + 4 * ne++, a, sizeof a);
	}
	for (int i = 0; i < 8; i++) {
		int a[4] = { 4 + i, 4 + (i + 1) % 8, 0, -1 };
		memcpy(e + 4 * ne++, a, sizeof a);
	}
	static const double pl[] = { 0, 1, 0, 1 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire_w(&m, v, 5, 12, 1, e, (size_t)ne, pl, 1);
	fct_mesh_add_comment(&m, "camera cylindrical 64 16 10.185916357881302 7.5 1.5707963267948966", 0, &err);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.holes, 1);
	CHECK_INT(s.in_plane, 1);
	CHECK_INT(m.nf, 12);
	double area, n[3] = { 0, 1, 0 };
	double rho = -1 / ((-0.5 - cy) / f);
	double octagon = 8 * 0.5 * rho * rho * sin(M_PI / 4), room = 0;
	for (int i = 0; i < 4; i++)
		room += corner[i][0] * corner[(i + 1) % 4][1] - corner[(i + 1) % 4][0] * corner[i][1];
	patch_dot(&m, 0, n, &area);
	CHECK_NEAR(area, fabs(room) / 2 - octagon, 1e-9);
	fct_mesh_free(&m);
}

/* A square outline whose top edge makes a small twist: edges 3-4 and 5-6
 * cross at (4.5, 11.5), in the plane (no s t).  The patch is unclean, and
 * trouble flags the ends of the two crossing edges, and only those: where
 * planedecim mends the outline.  With s t that cross in two places, the
 * plane's (fewer) crossings are flagged first. */
static void test_wire_trouble(void)
{
	static const double v[] = {
		0, 0, 0,  10, 0, 0,  10, 10, 0,  6, 10, 0,  4, 12, 0,  5, 12, 0,  3, 10, 0,  0, 10, 0,
	};
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 4, 0, -1,
	                         4, 5, 0, -1, 5, 6, 0, -1, 6, 7, 0, -1, 7, 0, 0, -1 };
	static const double pl[] = { 0, 0, 1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	unsigned char unclean[1] = { 0 }, trouble[8] = { 0 };
	wire(&m, v, 8, 0, e, 8, pl, 1);
	fct_tripatch_params_default(&p);
	p.unclean = unclean;
	p.trouble = trouble;
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.repairs, 1);
	CHECK_INT(unclean[0], 1);
	static const unsigned char want[8] = { 0, 0, 0, 1, 1, 1, 1, 0 };
	for (int i = 0; i < 8; i++)
		CHECK_INT(trouble[i], want[i]);
	fct_mesh_free(&m);

	/* With s t where it crosses twice (vertex 1 at (10, 11): edges 0-1 and
	 * 2-3 cross too): the plane's one crossing is where to mend first (bit
	 * 0), the image's two next (bit 1). */
	static const double vst[] = {
		0, 0, 0, 0, 0,  10, 0, 0, 10, 11,  10, 10, 0, 10, 10,  6, 10, 0, 6, 10,
		4, 12, 0, 4, 12,  5, 12, 0, 5, 12,  3, 10, 0, 3, 10,  0, 10, 0, 0, 10,
	};
	memset(trouble, 0, sizeof trouble);
	unclean[0] = 0;
	wire(&m, vst, 8, 1, e, 8, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.repairs, 1);
	CHECK_INT(unclean[0], 1);
	static const unsigned char want_st[8] = { 2, 2, 2, 3, 3, 3, 3, 0 };
	for (int i = 0; i < 8; i++)
		CHECK_INT(trouble[i], want_st[i]);
	fct_mesh_free(&m);

	/* Untwisted (5 and 4 swapped: 3-5-4-6), it is clean and flags nothing. */
	static const int e2[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 5, 0, -1,
	                          5, 4, 0, -1, 4, 6, 0, -1, 6, 7, 0, -1, 7, 0, 0, -1 };
	memset(trouble, 0, sizeof trouble);
	unclean[0] = 0;
	wire(&m, v, 8, 0, e2, 8, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.repairs, 0);
	CHECK_INT(unclean[0], 0);
	for (int i = 0; i < 8; i++)
		CHECK_INT(trouble[i], 0);
	fct_mesh_free(&m);
}

int main(void)
{
	test_wire_hole();
	test_wire_fallback();
	test_wire_touch();
	test_wire_bad();
	test_wire_random();
	test_wire_snap();
	test_wire_sliver();
	test_wire_cylinder();
	test_wire_trouble();
	CHECK_DONE();
}
