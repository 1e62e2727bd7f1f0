/* test_gridmesh.c - organised range data to triangles, depth images to
 * meshes, and the camera models, on grids whose answers are known by hand. */
#include <math.h>
#include <stdlib.h>

#include "io/camera.h"
#include "check.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "depth/gridmesh.h"

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

int main(void)
{
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
	CHECK_DONE();
}
