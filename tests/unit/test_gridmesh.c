/* test_gridmesh.c - organised range data to triangles, depth images to
 * meshes, and the camera models, on grids whose answers are known by hand,
 * and the pieces kept against a count of the pieces of the whole mesh. */
#include <math.h>
#include <stdlib.h>

#include "io/camera.h"
#include "check.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "depth/gridmesh.h"
#include "core/unionfind.h"

static struct fct_err err;

/* A w x h grid seen by a pinhole camera with f = 100 at the grid's centre:
 * cell (i, j) is pixel (i, j), its depth depth_fn(x, y) for the normalised
 * ray (x, y, 1), or no data where depth_fn gives 0. */
struct test_grid {
	struct fct_range_grid g;
	double *xyz, *depth;
};

static void make_grid(struct test_grid *t, int w, int h, double (*depth_fn)(double, double))
{
	t->xyz = malloc(sizeof *t->xyz * 3 * (size_t)(w * h));
	t->depth = malloc(sizeof *t->depth * (size_t)(w * h));
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			size_t c = (size_t)(j * w + i);
			double x = (i - (w - 1) / 2.0) / 100, y = (j - (h - 1) / 2.0) / 100;
			double d = depth_fn(x, y);
			t->depth[c] = d;
			t->xyz[3 * c] = d * x, t->xyz[3 * c + 1] = d * y, t->xyz[3 * c + 2] = d;
		}
	t->g = (struct fct_range_grid){ w, h, t->xyz, NULL, NULL, t->depth, 0.01, 0, NULL, 0 };
}

static void free_grid(struct test_grid *t)
{
	free(t->xyz);
	free(t->depth);
}

static const struct fct_grid_params keep_all = { 20, 0 };

static double flat(double x, double y) { (void)x, (void)y; return 2; }

/* Every face's normal points at the camera at the origin. */
static int faces_face_camera(const struct fct_mesh *m)
{
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *v = &m->fvert[3 * f];
		double e1[3], e2[3], n[3], c[3];
		fct_v3_sub(e1, &m->xyz[3 * v[1]], &m->xyz[3 * v[0]]);
		fct_v3_sub(e2, &m->xyz[3 * v[2]], &m->xyz[3 * v[0]]);
		fct_v3_cross(n, e1, e2);
		for (int k = 0; k < 3; k++)
			c[k] = (m->xyz[3 * v[0] + k] + m->xyz[3 * v[1] + k] + m->xyz[3 * v[2] + k]) / 3;
		if (!(fct_v3_dot(n, c) < 0))
			return 0;
	}
	return 1;
}

static void test_full_grid(void)
{
	struct test_grid t;
	struct fct_mesh m;
	struct fct_grid_stats st;
	make_grid(&t, 4, 3, flat);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, &st, &err), 0);
	CHECK_INT(m.nv, 12);
	CHECK_INT(m.nf, 2 * 3 * 2);
	CHECK_INT(st.jump_faces, 0);
	CHECK(faces_face_camera(&m));
	/* Vertices keep the cells' order and positions. */
	CHECK_NEAR(m.xyz[3 * 5 + 2], 2, 0);
	CHECK_NEAR(m.xyz[3 * 5], 2 * (1 - 1.5) / 100, 1e-15);
	fct_mesh_free(&m);
	free_grid(&t);
}

static int hole_i, hole_j;
static double holed(double x, double y)
{
	return fabs(x - (hole_i - 2) / 100.0) < 1e-9 && fabs(y - (hole_j - 2) / 100.0) < 1e-9 ? 0 : 2;
}

static void test_hole(void)
{
	/* 5x5 cells, 16 squares; a missing inner cell takes one triangle from
	 * each of its four squares; a missing corner cell one from its one. */
	struct test_grid t;
	struct fct_mesh m;
	uint32_t *cell_of;
	hole_i = 2, hole_j = 2;
	make_grid(&t, 5, 5, holed);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, &cell_of, NULL, &err), 0);
	CHECK_INT(m.nf, 32 - 4);
	CHECK_INT(m.nv, 24);
	CHECK_INT(cell_of[11], 11);
	CHECK_INT(cell_of[12], 13);   /* cell 12 is the hole */
	CHECK(faces_face_camera(&m));
	free(cell_of);
	fct_mesh_free(&m);
	free_grid(&t);

	hole_i = 0, hole_j = 0;
	make_grid(&t, 5, 5, holed);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, NULL, &err), 0);
	CHECK_INT(m.nf, 31);
	CHECK(faces_face_camera(&m));
	fct_mesh_free(&m);
	free_grid(&t);
}

/* Two fronto-parallel planes, 2 m and 3 m away, meeting at x = 0. */
static double steps(double x, double y) { (void)y; return x < 0 ? 2 : 3; }

static void test_discontinuity(void)
{
	struct test_grid t;
	struct fct_mesh m;
	struct fct_grid_stats st;
	make_grid(&t, 10, 6, steps);   /* columns 0-4 near, 5-9 far */
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, &st, &err), 0);
	/* 4 x 5 squares on each side; the 5 squares between are cut. */
	CHECK_INT(m.nf, 2 * (4 * 5) * 2);
	CHECK_INT(st.jump_faces, 2 * 5);
	for (size_t f = 0; f < m.nf; f++) {
		const uint32_t *v = &m.fvert[3 * f];
		double z0 = m.xyz[3 * v[0] + 2];
		CHECK(m.xyz[3 * v[1] + 2] == z0 && m.xyz[3 * v[2] + 2] == z0);
	}
	fct_mesh_free(&m);
	/* With the test off the gap is bridged. */
	struct fct_grid_params off = { HUGE_VAL, 0 };
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &off, NULL, &st, &err), 0);
	CHECK_INT(m.nf, 2 * 9 * 5);
	fct_mesh_free(&m);
	free_grid(&t);
}

static void test_grazing(void)
{
	/* A plane seen at 80 degrees: depth changes by tan(80) = 5.67
	 * footprints per pixel.  max_jump 20 keeps it, 5 cuts all of it. */
	struct test_grid t;
	struct fct_mesh m;
	double k = tan(80 * M_PI / 180);
	make_grid(&t, 8, 8, flat);
	for (int j = 0; j < 8; j++)
		for (int i = 0; i < 8; i++) {
			size_t c = (size_t)(j * 8 + i);
			/* Depth grows geometrically so the jump per footprint is k. */
			t.depth[c] = 2 * pow(1 + k * 0.01, i);
		}
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, NULL, &err), 0);
	CHECK_INT(m.nf, 2 * 7 * 7);
	fct_mesh_free(&m);
	struct fct_grid_params steep = { 5, 0 };
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &steep, NULL, NULL, &err), 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);
	free_grid(&t);
}

/* A ridge along the image diagonal x = y (and one along x = -y): the depth
 * is a plane on each side of it, so only triangles whose diagonal follows
 * the ridge lie on the surface. */
static double ridge(double x, double y) { return 1 / (0.5 + 0.8 * fabs(x - y) + 0.1 * (x + y)); }
static double antiridge(double x, double y) { return 1 / (0.5 + 0.8 * fabs(x + y) + 0.1 * (x - y)); }

/* Largest distance of a face centroid from the true surface, along its
 * ray, over the faces off the grid's border (a border square lacks the
 * neighbours that show which way the surface bends). */
static double worst_centroid(const struct fct_mesh *m, double (*depth_fn)(double, double))
{
	double worst = 0;
	for (size_t f = 0; f < m->nf; f++) {
		int border = 0;
		for (int k = 0; k < 3; k++) {
			const double *p = &m->xyz[3 * m->fvert[3 * f + k]];
			border |= fabs(p[0] / p[2]) > 0.035 || fabs(p[1] / p[2]) > 0.035;
		}
		if (border)
			continue;
		double c[3] = { 0, 0, 0 };
		for (int k = 0; k < 3; k++)
			for (int a = 0; a < 3; a++)
				c[a] += m->xyz[3 * m->fvert[3 * f + k] + a] / 3;
		double d = depth_fn(c[0] / c[2], c[1] / c[2]);
		double e = fabs(d - c[2]);
		if (e > worst)
			worst = e;
	}
	return worst;
}

static void test_diagonal_choice(void)
{
	/* 1/depth affine on each side: each side is a plane in 3-D. */
	struct test_grid t;
	struct fct_mesh m;
	make_grid(&t, 9, 9, ridge);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, NULL, &err), 0);
	CHECK_INT(m.nf, 2 * 8 * 8);
	CHECK_MSG(worst_centroid(&m, ridge) < 1e-12, "ridge: worst centroid %g", worst_centroid(&m, ridge));
	CHECK(faces_face_camera(&m));
	fct_mesh_free(&m);
	free_grid(&t);

	make_grid(&t, 9, 9, antiridge);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, NULL, &err), 0);
	CHECK_MSG(worst_centroid(&m, antiridge) < 1e-12, "antiridge: worst centroid %g",
	          worst_centroid(&m, antiridge));
	CHECK(faces_face_camera(&m));
	fct_mesh_free(&m);
	free_grid(&t);
}

static void test_specks(void)
{
	/* A 2x2 island (2 faces) beside a 4x4 piece (18 faces). */
	struct test_grid t;
	struct fct_mesh m;
	struct fct_grid_stats st;
	make_grid(&t, 8, 4, flat);
	for (int j = 0; j < 4; j++)
		for (int i = 4; i < 8; i++)
			if (!(i >= 6 && j < 2))
				t.depth[j * 8 + i] = 0;
	struct fct_grid_params p = { 20, 8 };
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &p, NULL, &st, &err), 0);
	CHECK_INT(m.nf, 18);
	CHECK_INT(m.nv, 16);
	CHECK_INT(st.speck_faces, 2);
	fct_mesh_free(&m);
	p.min_faces = 2;
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &p, NULL, &st, &err), 0);
	CHECK_INT(m.nf, 20);
	CHECK_INT(st.speck_faces, 0);
	fct_mesh_free(&m);
	free_grid(&t);
}

static void test_empty(void)
{
	struct test_grid t;
	struct fct_mesh m;
	make_grid(&t, 1, 1, flat);
	fct_mesh_init(&m);
	CHECK_INT(fct_grid_mesh(&m, &t.g, &keep_all, NULL, NULL, &err), 0);
	CHECK_INT(m.nf, 0);
	CHECK_INT(m.nv, 0);
	fct_mesh_free(&m);
	free_grid(&t);
}

static void test_camera(void)
{
	struct fct_camera pin = { FCT_CAMERA_PINHOLE, 640, 480, 500, 400, 320, 240, 0, 0 };
	struct fct_camera cyl = { FCT_CAMERA_CYLINDRICAL, 1000, 200, 0, 0, 0, 99.5, 159.15494309189535, 0.25 };
	double ray[3], p[3], u, v, d;
	fct_camera_ray(&pin, 420, 140, ray);
	CHECK_NEAR(ray[0], 0.2, 1e-15);
	CHECK_NEAR(ray[1], -0.25, 1e-15);
	CHECK_NEAR(ray[2], 1, 0);
	for (int k = 0; k < 3; k++)
		p[k] = 3 * ray[k];
	CHECK_INT(fct_camera_project(&pin, p, &u, &v, &d), 1);
	CHECK_NEAR(u, 420, 1e-12);
	CHECK_NEAR(v, 140, 1e-12);
	CHECK_NEAR(d, 3, 1e-15);
	p[2] = -1;
	CHECK_INT(fct_camera_project(&pin, p, &u, &v, &d), 0);

	/* Cylindrical: u = 250 is a quarter turn past theta0. */
	fct_camera_ray(&cyl, 250, 99.5, ray);
	CHECK_NEAR(ray[0], sin(0.25 + M_PI / 2), 1e-15);
	CHECK_NEAR(ray[1], 0, 0);
	CHECK_NEAR(ray[2], cos(0.25 + M_PI / 2), 1e-15);
	fct_camera_ray(&cyl, 999.7, 20, ray);
	for (int k = 0; k < 3; k++)
		p[k] = 2.5 * ray[k];
	CHECK_INT(fct_camera_project(&cyl, p, &u, &v, &d), 1);
	CHECK_NEAR(u, -0.3, 1e-9);   /* wrapped to [-0.5, W - 0.5) */
	CHECK_NEAR(v, 20, 1e-12);
	CHECK_NEAR(d, 2.5, 1e-15);

	struct fct_camera c;
	double scale;
	CHECK_INT(fct_camera_named("tum3", &c, &scale), 0);
	CHECK_NEAR(c.fx, 535.4, 0);
	CHECK_NEAR(scale, 5000, 0);
	CHECK_INT(fct_camera_named("nope", &c, &scale), -1);
	CHECK_INT(fct_camera_parse("pinhole 640 480 525 525 319.5 239.5", &c, &err), 0);
	CHECK_NEAR(c.cy, 239.5, 0);
	CHECK_INT(fct_camera_parse("pinhole 640 480 525 525 319.5", &c, &err), -1);
	CHECK_INT(fct_camera_parse("cylindrical 640 0 100 5 0", &c, &err), -1);

	double pose[12] = { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3 }, inv[12], q[3], r[3];
	CHECK_INT(fct_pose_check(pose, 1e-12, &err), 0);
	fct_pose_invert(pose, inv);
	double x[3] = { 0.5, -0.25, 4 };
	fct_pose_apply(pose, x, q);
	CHECK_NEAR(q[0], 1.25, 1e-15);
	CHECK_NEAR(q[1], 2.5, 1e-15);
	CHECK_NEAR(q[2], 7, 1e-15);
	fct_pose_apply(inv, q, r);
	CHECK(fct_v3_dist2(r, x) < 1e-28);
	pose[0] = 1;
	CHECK_INT(fct_pose_check(pose, 1e-3, &err), -1);
}

static void test_depth_image(void)
{
	/* A 16-bit 4x3 image in millimetres with 0 and 65535 holes, through
	 * the camera: positions, holes and texture coordinates by hand. */
	uint16_t px[12] = { 2000, 2000, 2000, 2000,
	                    2000, 0,    2000, 2000,
	                    2000, 2000, 2000, 65535 };
	struct fct_image img = { 4, 3, 1, FCT_PIX_U16, px };
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 4, 3, 10, 10, 1.5, 1, 0, 0 };
	struct fct_depth_params p;
	struct fct_mesh m;
	fct_depth_params_default(&p);
	p.grid.min_faces = 0;
	CHECK_NEAR(fct_depth_at(&img, 0, 0, &p), 2, 0);
	CHECK_NEAR(fct_depth_at(&img, 1, 1, &p), 0, 0);
	CHECK_NEAR(fct_depth_at(&img, 3, 2, &p), 0, 0);
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), 0);
	/* 6 squares: the hole at (1,1) takes one triangle from each of the 4
	 * it touches, 65535 at (3,2) one from the fifth; the sixth is whole. */
	CHECK_INT(m.nv, 10);
	CHECK_INT(m.nf, 7);
	CHECK_NEAR(m.xyz[0], 2 * (0 - 1.5) / 10, 1e-15);
	CHECK_NEAR(m.xyz[1], 2 * (0 - 1.0) / 10, 1e-15);
	CHECK_NEAR(m.xyz[2], 2, 0);
	const struct fct_prop *s = fct_elem_find(&m.vertex, "s"), *t = fct_elem_find(&m.vertex, "t");
	CHECK(s && t);
	if (s && t) {
		CHECK_NEAR(fct_prop_get(s, 0), 0.125, 1e-7);
		CHECK_NEAR(fct_prop_get(t, 0), 1 - 0.5 / 3, 1e-7);
	}
	CHECK(faces_face_camera(&m));
	fct_mesh_free(&m);

	/* Disparity: depth = baseline * focal / d. */
	float disp[4] = { 10, 20, 0, 40 };
	struct fct_image dimg = { 2, 2, 1, FCT_PIX_F32, disp };
	p.baseline = 0.1, p.focal = 500;
	CHECK_NEAR(fct_depth_at(&dimg, 0, 0, &p), 5, 1e-15);
	CHECK_NEAR(fct_depth_at(&dimg, 1, 1, &p), 1.25, 1e-15);
	CHECK_NEAR(fct_depth_at(&dimg, 0, 1, &p), 0, 0);

	/* Wrong size and channels are refused. */
	p.baseline = 0;
	cam.width = 5;
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), -1);
	img.channels = 3;
	cam.width = 4;
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), -1);
}

static void test_cylinder(void)
{
	/* A cylindrical depth map of a round room of radius 3: every vertex at
	 * distance 3 from the axis, the seam closed (W squares per row), faces
	 * toward the axis. */
	enum { W = 36, H = 5 };
	float px[W * H];
	for (int i = 0; i < W * H; i++)
		px[i] = 3;
	struct fct_image img = { W, H, 1, FCT_PIX_F32, px };
	struct fct_camera cam = { FCT_CAMERA_CYLINDRICAL, W, H, 0, 0, 0, 2, W / (2 * M_PI), 0 };
	struct fct_depth_params p;
	struct fct_mesh m;
	fct_depth_params_default(&p);
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), 0);
	CHECK_INT(m.nv, W * H);
	CHECK_INT(m.nf, 2 * W * (H - 1));
	for (size_t v = 0; v < m.nv; v++)
		CHECK_NEAR(hypot(m.xyz[3 * v], m.xyz[3 * v + 2]), 3, 1e-12);
	for (size_t f = 0; f < m.nf; f++) {
		const uint32_t *v = &m.fvert[3 * f];
		double e1[3], e2[3], n[3], c[3] = { 0, 0, 0 };
		fct_v3_sub(e1, &m.xyz[3 * v[1]], &m.xyz[3 * v[0]]);
		fct_v3_sub(e2, &m.xyz[3 * v[2]], &m.xyz[3 * v[0]]);
		fct_v3_cross(n, e1, e2);
		for (int k = 0; k < 3; k++)
			c[0] += m.xyz[3 * v[k]] / 3, c[2] += m.xyz[3 * v[k] + 2] / 3;
		if (!(n[0] * c[0] + n[2] * c[2] < 0)) {
			CHECK_MSG(0, "cylinder face %zu faces away from the axis", f);
			break;
		}
	}
	fct_mesh_free(&m);
}

/* The rules of gridmesh.h worked square by square, against which the
 * mesher's row passes (positions, bends, join tests and diagonal choices
 * made two cells at a time, the odd last one alone) are checked: a grid of
 * w x h cells with ray (col x, row y, col z) and depth, sigma or not. */
struct rule_grid {
	int w, h;
	const double *col, *row, *depth;
	const float *sigma;
	double limit, noise;   /* max_jump * footprint, noise_jump * sqrt(2) */
};

static int rule_has(const struct rule_grid *r, int i, int j)
{
	if (i < 0 || j < 0 || i >= r->w || j >= r->h)
		return 0;
	double d = r->depth[j * r->w + i];
	return d > 0 && d < HUGE_VAL;
}

static void rule_position(const struct rule_grid *r, int i, int j, double p[3])
{
	double d = r->depth[j * r->w + i];
	p[0] = d * r->col[3 * i], p[1] = d * r->row[j], p[2] = d * r->col[3 * i + 2];
}

static int rule_joined(const struct rule_grid *r, int i0, int j0, int i1, int j1)
{
	if (!rule_has(r, i0, j0) || !rule_has(r, i1, j1))
		return 0;
	size_t a = (size_t)(j0 * r->w + i0), b = (size_t)(j1 * r->w + i1);
	double allow = 0;
	if (r->sigma)
		allow = r->noise * (r->sigma[a] > r->sigma[b] ? r->sigma[a] : r->sigma[b]);
	double steps = i0 != i1 && j0 != j1 ? M_SQRT2 : 1;
	return fct_depth_joined(r->depth[a], r->depth[b], r->limit, steps, allow);
}

/* The diagonal of full square (i, j): along which the surface bends less
 * when the four cells beyond its corners along the diagonals have data
 * (and the bends differ by more than rounding), else the shorter. */
static int rule_prefer_ad(const struct rule_grid *r, int i, int j)
{
	double a[3], b[3], c[3], d[3];
	rule_position(r, i, j, a), rule_position(r, i + 1, j, b);
	rule_position(r, i, j + 1, c), rule_position(r, i + 1, j + 1, d);
	double lad = fct_v3_dist2(a, d), lbc = fct_v3_dist2(b, c);
	if (rule_has(r, i - 1, j - 1) && rule_has(r, i + 2, j + 2) && rule_has(r, i + 2, j - 1) &&
	    rule_has(r, i - 1, j + 2)) {
		double aa[3], dd[3], bb[3], cc[3];
		rule_position(r, i - 1, j - 1, aa), rule_position(r, i + 2, j + 2, dd);
		rule_position(r, i + 2, j - 1, bb), rule_position(r, i - 1, j + 2, cc);
		double bad = fct_v3_line_distance2(a, aa, d) + fct_v3_line_distance2(d, a, dd);
		double bbc = fct_v3_line_distance2(b, bb, c) + fct_v3_line_distance2(c, b, cc);
		if (fabs(bad - bbc) > 1e-18 * (lad > lbc ? lad : lbc))
			return bad < bbc;
	}
	return lad < lbc;
}

/* Every face of m joins its corners by the rules, and every square whose
 * four corners and six edges are joined has its two triangles, along the
 * diagonal the rules prefer. */
static int follows_rules(const struct fct_mesh *m, const uint32_t *cell_of,
                         const struct rule_grid *r)
{
	size_t nsq = (size_t)r->w * (size_t)r->h;
	unsigned char *faces = calloc(nsq, 1), *along_ad = calloc(nsq, 1);
	int ok = faces && along_ad;
	for (size_t f = 0; ok && f < m->nf; f++) {
		int ci[3], cj[3], i = r->w, j = r->h;
		for (int k = 0; k < 3; k++) {
			uint32_t c = cell_of[m->fvert[3 * f + (size_t)k]];
			ci[k] = (int)(c % (uint32_t)r->w), cj[k] = (int)(c / (uint32_t)r->w);
			i = ci[k] < i ? ci[k] : i, j = cj[k] < j ? cj[k] : j;
		}
		for (int k = 0; k < 3; k++)
			ok &= rule_joined(r, ci[k], cj[k], ci[(k + 1) % 3], cj[(k + 1) % 3]);
		int has_a = 0, has_d = 0;
		for (int k = 0; k < 3; k++)
			has_a |= ci[k] == i && cj[k] == j, has_d |= ci[k] == i + 1 && cj[k] == j + 1;
		faces[j * r->w + i]++;
		along_ad[j * r->w + i] = (unsigned char)(has_a && has_d);
	}
	for (int j = 0; ok && j + 1 < r->h; j++)
		for (int i = 0; ok && i + 1 < r->w; i++) {
			int full = rule_joined(r, i, j, i + 1, j) && rule_joined(r, i, j + 1, i + 1, j + 1) &&
			           rule_joined(r, i, j, i, j + 1) && rule_joined(r, i + 1, j, i + 1, j + 1) &&
			           rule_joined(r, i, j, i + 1, j + 1) && rule_joined(r, i + 1, j, i, j + 1);
			if (full)
				ok &= faces[j * r->w + i] == 2 && along_ad[j * r->w + i] == rule_prefer_ad(r, i, j);
		}
	free(faces);
	free(along_ad);
	return ok;
}

/* Grids of every width 1-19 and height 1-6 (odd and even counts of the
 * row passes' pairs, runs of eight squares and the rest, 1 x N), a rough
 * surface of random bends and jumps with holes of 0, NaN and infinite
 * depth and planar stretches (ties between the diagonals' bends), with and
 * without sigma: the mesh follows the rules square by square. */
static void test_rules_by_square(void)
{
	uint32_t seed = 11;
	for (int with_sigma = 0; with_sigma < 2; with_sigma++)
		for (int h = 1; h <= 6; h++)
			for (int w = 1; w <= 19; w++) {
				size_t n = (size_t)w * (size_t)h;
				double *depth = malloc(n * sizeof *depth), *col = malloc(3 * (size_t)w * sizeof *col);
				double *row = malloc((size_t)h * sizeof *row);
				float *sigma = malloc(n * sizeof *sigma);
				if (!depth || !col || !row || !sigma)
					abort();
				for (int i = 0; i < w; i++)
					col[3 * i] = (i - w / 2) * 0.01, col[3 * i + 1] = 0, col[3 * i + 2] = 1;
				for (int j = 0; j < h; j++)
					row[j] = (j - h / 2) * 0.01;
				int planar = (w + h) % 3 == 0;
				for (size_t c = 0; c < n; c++) {
					seed = seed * 1664525u + 1013904223u;
					double u = (seed >> 8) / 16777216.0;
					/* rough: neighbours differ by up to 0.1, around the
					 * limit of 0.06, and the noise term (up to 0.03)
					 * decides many of the join tests */
					depth[c] = planar ? 2 + 0.01 * (double)(c % (size_t)w) : 2 + 0.1 * u;
					if (seed % 11 == 0)
						depth[c] = 0;
					else if (seed % 23 == 0)
						depth[c] = NAN;
					else if (seed % 29 == 0)
						depth[c] = HUGE_VAL;
					else if (seed % 7 == 0)
						depth[c] += 0.2;   /* a jump beyond the limit */
					sigma[c] = (float)(0.0002 + 0.01 * ((seed >> 4) % 1024) / 1024.0);
				}
				struct fct_range_grid g = { w, h, NULL, col, row, depth, 0.01, 0,
				                            with_sigma ? sigma : NULL, with_sigma ? 2 : 0 };
				struct fct_grid_params p = { 3, 0 };
				struct rule_grid r = { w, h, col, row, depth, with_sigma ? sigma : NULL,
				                       p.max_jump * g.footprint, M_SQRT2 * g.noise_jump };
				struct fct_mesh m;
				uint32_t *cell_of = NULL;
				fct_mesh_init(&m);
				CHECK_INT(fct_grid_mesh(&m, &g, &p, &cell_of, NULL, &err), 0);
				CHECK_MSG(follows_rules(&m, cell_of, &r), "%dx%d sigma %d: a square breaks the rules",
				          w, h, with_sigma);
				CHECK_MSG(m.nf > 0 || w < 4 || h < 4, "%dx%d: no faces", w, h);
				fct_mesh_free(&m);
				free(cell_of);
				free(depth), free(col), free(row), free(sigma);
			}
}

/* The pieces a mesher with min_faces keeps, worked out from the mesh with
 * every piece: its faces' corners joined (fct_uf_root over its vertices),
 * each piece's faces counted; the faces of pieces of at least min_faces,
 * in order, as cells.  Checked against the mesher's faces as cells, and
 * its vertices against the cells its faces use, ascending, on rough grids
 * with holes, open and closed around a cylinder (the seam's squares). */
static void test_pieces(void)
{
	uint32_t seed = 5;
	size_t dropped[2] = { 0, 0 };   /* faces dropped, open and closed */
	for (int wrap = 0; wrap < 2; wrap++)
		for (int h = 2; h <= 7; h++)
			for (int w = 3; w <= 17; w += 2) {
				size_t n = (size_t)w * (size_t)h;
				double *depth = malloc(n * sizeof *depth), *col = malloc(3 * (size_t)w * sizeof *col);
				double *row = malloc((size_t)h * sizeof *row);
				if (!depth || !col || !row)
					abort();
				for (int i = 0; i < w; i++)
					col[3 * i] = sin(2 * M_PI * i / w), col[3 * i + 1] = 0, col[3 * i + 2] = cos(2 * M_PI * i / w);
				for (int j = 0; j < h; j++)
					row[j] = (j - h / 2) * 0.01;
				for (size_t c = 0; c < n; c++) {
					seed = seed * 1664525u + 1013904223u;
					depth[c] = seed % 5 == 0 ? 0 : 2 + (seed % 3 == 0 ? 0.3 : 0.001 * (seed >> 28));
				}
				struct fct_range_grid g = { w, h, NULL, col, row, depth, 0.01, wrap, NULL, 0 };
				struct fct_grid_params all = { 5, 0 };
				struct fct_mesh m0;
				uint32_t *cell0 = NULL;
				fct_mesh_init(&m0);
				CHECK_INT(fct_grid_mesh(&m0, &g, &all, &cell0, NULL, &err), 0);
				int32_t *parent = malloc((m0.nv + 1) * sizeof *parent);
				size_t *faces = calloc(m0.nv + 1, sizeof *faces);
				if (!parent || !faces)
					abort();
				for (size_t v = 0; v < m0.nv; v++)
					parent[v] = -1;
				for (size_t f = 0; f < m0.nf; f++)
					for (int k = 1; k < 3; k++) {
						uint32_t a = fct_uf_root(parent, m0.fvert[3 * f]);
						uint32_t b = fct_uf_root(parent, m0.fvert[3 * f + k]);
						if (a != b)
							parent[b] = (int32_t)a;
					}
				for (size_t f = 0; f < m0.nf; f++)
					faces[fct_uf_root(parent, m0.fvert[3 * f])]++;
				for (size_t min = 2; min <= 9; min += 3) {
					struct fct_grid_params p = { 5, min };
					struct fct_mesh m;
					uint32_t *cell = NULL;
					fct_mesh_init(&m);
					CHECK_INT(fct_grid_mesh(&m, &g, &p, &cell, NULL, &err), 0);
					size_t k = 0;
					int same = 1;
					for (size_t f = 0; f < m0.nf && same; f++) {
						if (faces[fct_uf_root(parent, m0.fvert[3 * f])] < min)
							continue;
						for (int c = 0; c < 3 && same; c++)
							same = k < m.nf && cell[m.fvert[3 * k + c]] == cell0[m0.fvert[3 * f + c]];
						k++;
					}
					CHECK_MSG(same && k == m.nf, "%dx%d wrap %d min_faces %zu: %zu faces, not the %zu "
					          "of the pieces kept", w, h, wrap, min, m.nf, k);
					dropped[wrap] += m0.nf - m.nf;
					/* vertices: exactly the cells the faces use, ascending */
					unsigned char *used = calloc(n, 1);
					if (!used)
						abort();
					for (size_t i = 0; i < 3 * m.nf; i++)
						used[cell[m.fvert[i]]] = 1;
					size_t v = 0;
					for (size_t c = 0; c < n && same; c++)
						if (used[c])
							same = v < m.nv && cell[v++] == c;
					CHECK_MSG(same && v == m.nv, "%dx%d wrap %d min_faces %zu: vertices not the cells "
					          "used", w, h, wrap, min);
					free(used);
					fct_mesh_free(&m);
					free(cell);
				}
				fct_mesh_free(&m0);
				free(cell0), free(parent), free(faces);
				free(depth), free(col), free(row);
			}
	/* the grids are rough enough that pieces of every size occur */
	CHECK(dropped[0] > 100 && dropped[1] > 100);
}

int main(void)
{
	test_rules_by_square();
	test_full_grid();
	test_hole();
	test_discontinuity();
	test_grazing();
	test_diagonal_choice();
	test_specks();
	test_empty();
	test_camera();
	test_depth_image();
	test_cylinder();
	test_pieces();
	CHECK_DONE();
}
