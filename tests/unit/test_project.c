/* test_project.c - vertex projection (Kang et al. sec. 5), texture
 * coordinates (sec. 6), snapping and the depth scale (sec. 8): hand cases
 * with closed-form answers, and mkscene's room with its exact planes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "planar/chain.h"
#include "check.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "io/header.h"
#include "geom/planes.h"
#include "planar/project.h"
#include "core/rng.h"
#include "scene/scene.h"

static struct fct_err err;

static void unit(double v[3])
{
	double l = sqrt(fct_v3_dot(v, v));
	v[0] /= l, v[1] /= l, v[2] /= l;
}

/* 3x3 inverse by cofactors (for independent closed forms). */
static void inv3(const double a[9], double r[9])
{
	double c[9] = {
		a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
		a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
		a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3],
	};
	double det = a[0] * c[0] + a[1] * c[3] + a[2] * c[6];
	for (int i = 0; i < 9; i++)
		r[i] = c[i] / det;
}

static double dist(const double *n, double d, const double p[3])
{
	return fct_v3_dot(n, p) + d;
}

/* k = 0 and k = 1: unchanged, and the perpendicular foot. */
static void test_one_plane(void)
{
	double n[3] = { 1, 2, 2 }, d = -1.3, p[3] = { 0.3, -0.7, 2.1 }, out[3];
	unit(n);   /* (1, 2, 2) / 3 */
	struct fct_point_fit fit;
	CHECK_INT(fct_project_point(n, &d, 0, p, 1, 1e-2, 0, out, &fit, &err), 0);
	CHECK(out[0] == p[0] && out[1] == p[1] && out[2] == p[2] && fit.rank == 0 && fit.used == 0);
	CHECK_INT(fct_project_point(n, &d, 1, p, 10, 1e-2, 0, out, &fit, &err), 0);
	/* n.p + d = (0.3 - 1.4 + 4.2) / 3 - 1.3 = -0.26667: the foot is p + 0.26667 n. */
	double r = (0.3 - 1.4 + 4.2) / 3 - 1.3;
	CHECK_NEAR(out[0], 0.3 - r / 3, 1e-15);
	CHECK_NEAR(out[1], -0.7 - 2 * r / 3, 1e-15);
	CHECK_NEAR(out[2], 2.1 - 2 * r / 3, 1e-15);
	CHECK(fabs(dist(n, d, out)) <= 4.5e-16);
	CHECK_NEAR(fit.move, fabs(r), 1e-15);
	CHECK_INT(fit.used, 1);
	/* Beyond the bound: kept exactly. */
	CHECK_INT(fct_project_point(n, &d, 1, p, 0.2, 1e-2, 0, out, &fit, &err), 0);
	CHECK(out[0] == p[0] && out[1] == p[1] && out[2] == p[2]);
	CHECK_INT(fit.used, 0);
	CHECK_NEAR(fit.want, fabs(r), 1e-15);
}

/* k = 2: the closest point of the line, against x = p - N^T (N N^T)^-1 (N p + d). */
static void test_two_planes(void)
{
	double n[6] = { 1, 1, 0, 0, 0.6, 0.8 }, d[2] = { -0.5, 0.3 }, p[3] = { 0.4, 0.9, -1.1 };
	unit(n);
	double out[3];
	struct fct_point_fit fit;
	CHECK_INT(fct_project_point(n, d, 2, p, 10, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 2);
	CHECK_INT(fit.used, 2);
	CHECK(fabs(dist(n, d[0], out)) < 1e-12);
	CHECK(fabs(dist(n + 3, d[1], out)) < 1e-12);
	double dir[3], mv[3];
	fct_v3_cross(dir, n, n + 3);
	fct_v3_sub(mv, out, p);
	CHECK(fabs(fct_v3_dot(dir, mv)) < 1e-12);   /* perpendicular onto the line */
	double g = fct_v3_dot(n, n + 3), r0 = dist(n, d[0], p), r1 = dist(n + 3, d[1], p);
	double det = 1 - g * g, l0 = (r0 - g * r1) / det, l1 = (r1 - g * r0) / det;
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(out[c], p[c] - l0 * n[c] - l1 * n[3 + c], 1e-14);

	/* The same plane twice (two patches): rank 1, on the plane. */
	double nn[6] = { 0, 0.6, 0.8, 0, 0.6, 0.8 }, dd[2] = { 0.3, 0.3 };
	CHECK_INT(fct_project_point(nn, dd, 2, p, 10, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 1);
	CHECK(fabs(dist(nn, dd[0], out)) < 1e-15);
	CHECK_NEAR(out[0], p[0], 0);
}

/* k >= 3: three orthogonal planes (rotated) meet at the exact corner; four
 * planes give the least-squares point (N^T N)^-1 N^T (-d); three planes
 * through one line give the line's closest point. */
static void test_corner(void)
{
	/* A rotation: unit axes rotated about (1, 2, 3) by 0.7 rad (Rodrigues). */
	double k[3] = { 1, 2, 3 }, R[9], th = 0.7;
	unit(k);
	double K[9] = { 0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0 };
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			double kk = 0;
			for (int q = 0; q < 3; q++)
				kk += K[3 * i + q] * K[3 * q + j];
			R[3 * i + j] = (i == j) + sin(th) * K[3 * i + j] + (1 - cos(th)) * kk;
		}
	/* Corner c; planes x' = c.e_i through it with normals the rotated axes. */
	double c[3] = { 1.5, -2, 3.25 }, n[12], d[4], p[3] = { 1.7, -1.8, 3.1 }, out[3];
	for (int i = 0; i < 3; i++) {
		for (int q = 0; q < 3; q++)
			n[3 * i + q] = R[3 * q + i];
		d[i] = -fct_v3_dot(n + 3 * i, c);
	}
	struct fct_point_fit fit;
	CHECK_INT(fct_project_point(n, d, 3, p, 10, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 3);
	for (int q = 0; q < 3; q++)
		CHECK_NEAR(out[q], c[q], 1e-14);

	/* A fourth plane that misses the corner by 0.01: least squares. */
	double n4[3] = { 1, 1, 1 };
	unit(n4);
	memcpy(n + 9, n4, sizeof n4);
	d[3] = -fct_v3_dot(n4, c) + 0.01;
	double ata[9] = { 0 }, atb[3] = { 0 }, ai[9], want[3];
	for (int i = 0; i < 4; i++)
		for (int r = 0; r < 3; r++) {
			atb[r] += -d[i] * n[3 * i + r];
			for (int q = 0; q < 3; q++)
				ata[3 * r + q] += n[3 * i + r] * n[3 * i + q];
		}
	inv3(ata, ai);
	for (int r = 0; r < 3; r++)
		want[r] = ai[3 * r] * atb[0] + ai[3 * r + 1] * atb[1] + ai[3 * r + 2] * atb[2];
	CHECK_INT(fct_project_point(n, d, 4, p, 10, 1e-2, 0, out, &fit, &err), 0);
	for (int q = 0; q < 3; q++)
		CHECK_NEAR(out[q], want[q], 1e-13);
	CHECK(fct_v3_dist2(out, c) > 1e-6);   /* it did move off the corner */

	/* Three planes through the z axis: rank 2, the closest point of the axis. */
	double nz[9] = { 1, 0, 0, 0, 1, 0, 1, 1, 0 }, dz[3] = { 0, 0, 0 };
	unit(nz + 6);
	CHECK_INT(fct_project_point(nz, dz, 3, p, 10, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 2);
	CHECK(fabs(out[0]) < 1e-15 && fabs(out[1]) < 1e-15);
	CHECK_NEAR(out[2], p[2], 1e-15);

	/* Many planes (beyond the stack rows): 40 copies of the three corner planes. */
	double *nm = malloc(120 * 3 * sizeof *nm), *dm = malloc(120 * sizeof *dm);
	for (int i = 0; i < 120; i++) {
		memcpy(nm + 3 * i, n + 3 * (i % 3), 3 * sizeof *nm);
		dm[i] = d[i % 3];
	}
	CHECK_INT(fct_project_point(nm, dm, 120, p, 10, 1e-2, 0, out, &fit, &err), 0);
	for (int q = 0; q < 3; q++)
		CHECK_NEAR(out[q], c[q], 1e-13);
	free(nm);
	free(dm);
}

/* Near-parallel planes: 5 degrees apart, meeting 0.229 from the origin; a
 * vertex 1.2 from that line is kept; with fallback it goes to the rank-1
 * solution (along the mean normal).  Within the rank tolerance (0.5 degrees)
 * the two act as one plane. */
static void test_near_parallel(void)
{
	double a = 5 * M_PI / 180;
	double n[6] = { 0, 0, 1, sin(a), 0, cos(a) }, d[2] = { 0, -0.02 };
	double p[3] = { -1, 0, 0.01 }, out[3];
	struct fct_point_fit fit;
	CHECK_INT(fct_project_point(n, d, 2, p, 0.1, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 2);
	CHECK_INT(fit.used, 0);
	CHECK(out[0] == p[0] && out[1] == p[1] && out[2] == p[2]);
	/* The line: z = 0, x = 0.02 / sin 5 = 0.22947; the vertex is 1.2295 from it in x
	 * and 0.01 in z. */
	double xl = 0.02 / sin(a);
	CHECK_NEAR(fit.want, sqrt((xl + 1) * (xl + 1) + 0.01 * 0.01), 1e-12);
	/* Fallback: rank 1 along u1 (the mean normal direction). */
	CHECK_INT(fct_project_point(n, d, 2, p, 0.1, 1e-2, 1, out, &fit, &err), 0);
	CHECK_INT(fit.used, 1);
	CHECK(fit.move <= 0.1);
	double m[3] = { sin(a) / 2, 0, (1 + cos(a)) / 2 }, mv[3], cr[3];
	unit(m);
	fct_v3_sub(mv, out, p);
	fct_v3_cross(cr, mv, m);
	CHECK(sqrt(fct_v3_dot(cr, cr)) < 1e-15);   /* moved along the mean normal */
	/* Its residuals r1 = -(n1.x + d1), r2 sum to zero after a rank-1 move
	 * along u1 = (n1 + n2)/|n1 + n2| (the minimum-norm solution). */
	CHECK_NEAR(dist(n, d[0], out) + dist(n + 3, d[1], out), 0, 1e-15);

	/* 0.5 degrees: below the rank tolerance (sigma ratio tan 0.25 deg = 0.0044). */
	double b = 0.5 * M_PI / 180;
	double n2[6] = { 0, 0, 1, sin(b), 0, cos(b) };
	CHECK_INT(fct_project_point(n2, d, 2, p, 0.1, 1e-2, 0, out, &fit, &err), 0);
	CHECK_INT(fit.rank, 1);
	CHECK_INT(fit.used, 1);
	CHECK(fit.move < 0.02);
}

/* Section 6: s t by hand, pinhole and cylindrical, with and without a pose. */
static void test_texcoord(void)
{
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 640, 480, 500, 510, 320, 240, 0, 0 };
	double p[3] = { 0.2, -0.1, 2.0 }, s, t;
	CHECK_INT(fct_project_texcoord(&cam, NULL, p, &s, &t), 1);
	/* u = 500 * 0.1 + 320 = 370, v = 510 * -0.05 + 240 = 214.5 */
	CHECK_NEAR(s, 370.5 / 640, 1e-15);
	CHECK_NEAR(t, 1 - 215.0 / 480, 1e-15);
	double behind[3] = { 0, 0, -1 };
	CHECK_INT(fct_project_texcoord(&cam, NULL, behind, &s, &t), 0);

	/* Pose: camera-to-world rotation of 90 degrees about x, then a shift;
	 * the world point is R p + t, and its pixel must be p's. */
	double pose[12] = { 1, 0, 0, 1, 0, 0, -1, 2, 0, 1, 0, 3 }, inv[12], w[3];
	fct_pose_apply(pose, p, w);   /* (1.2, 2 - 2, 3 - 0.1) */
	CHECK_NEAR(w[0], 1.2, 1e-15);
	CHECK_NEAR(w[1], 0, 1e-15);
	CHECK_NEAR(w[2], 2.9, 1e-15);
	fct_pose_invert(pose, inv);
	CHECK_INT(fct_project_texcoord(&cam, inv, w, &s, &t), 1);
	CHECK_NEAR(s, 370.5 / 640, 1e-15);
	CHECK_NEAR(t, 1 - 215.0 / 480, 1e-15);

	/* Cylindrical 720 x 180, f = 720 / 2 pi, cy = 89.5, theta0 = 0.3: the
	 * point at u = 100, v = 50, rho = 2. */
	struct fct_camera cyl = { FCT_CAMERA_CYLINDRICAL, 720, 180, 0, 0, 0, 89.5, 720 / (2 * M_PI), 0.3 };
	double th = 0.3 + 2 * M_PI * 100 / 720, h = (50 - 89.5) / cyl.f;
	double q[3] = { 2 * sin(th), 2 * h, 2 * cos(th) };
	CHECK_INT(fct_project_texcoord(&cyl, NULL, q, &s, &t), 1);
	CHECK_NEAR(s, 100.5 / 720, 1e-13);
	CHECK_NEAR(t, 1 - 50.5 / 180, 1e-13);
	fct_pose_apply(pose, q, w);
	CHECK_INT(fct_project_texcoord(&cyl, inv, w, &s, &t), 1);
	CHECK_NEAR(s, 100.5 / 720, 1e-13);
	/* Across the seam: u = 719.7 wraps to -0.3, s = 0.2 / 720. */
	th = 0.3 + 2 * M_PI * 719.7 / 720;
	double q2[3] = { sin(th), 0, cos(th) };
	CHECK_INT(fct_project_texcoord(&cyl, NULL, q2, &s, &t), 1);
	CHECK_NEAR(s, 0.2 / 720, 1e-12);
}

/* A hand mesh: a tent of two planes (roof slopes) over the ridge line, in a
 * camera with a pose; vertices off the planes.  After the stage: each
 * vertex where the hand projection puts it, s t those of the new positions
 * through the camera (hand-computed pixel of the ridge vertex). */
static void test_mesh_tent(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	/* Planes z = 2 + 0.5 x (left, x < 0) and z = 2 - 0.5 x (right); ridge at x = 0, z = 2. */
	double xs[6][3] = { { -1, -0.5, 1.52 }, { -1, 0.5, 1.47 }, { 0.01, -0.5, 2.03 },
	                    { -0.02, 0.5, 1.98 }, { 1, -0.5, 1.49 }, { 1, 0.5, 1.51 } };
	for (int i = 0; i < 6; i++)
		fct_mesh_add_vertex(&m, xs[i][0], xs[i][1], xs[i][2], &err);
	uint32_t f[4][3] = { { 0, 2, 1 }, { 1, 2, 3 }, { 2, 4, 3 }, { 3, 4, 5 } };
	for (int i = 0; i < 4; i++)
		fct_mesh_add_face(&m, f[i], 3, &err);
	int32_t lab[4] = { 0, 0, 1, 1 };
	CHECK_INT(fct_patches_set(&m, lab, &err), 0);
	double s5 = sqrt(1.25);
	struct fct_plane pl[2] = { { { 0.5 / s5, 0, -1 / s5 }, 2 / s5, 2, 0 },
	                           { { -0.5 / s5, 0, -1 / s5 }, 2 / s5, 2, 0 } };
	CHECK_INT(fct_planes_set(&m, pl, 2, &err), 0);
	struct fct_elem *ve = &m.vertex;
	CHECK(fct_elem_add_scalar(ve, "s", FCT_FLOAT32, &err) != NULL);
	CHECK(fct_elem_add_scalar(ve, "t", FCT_FLOAT32, &err) != NULL);
	CHECK(fct_elem_add_scalar(ve, "red", FCT_UINT8, &err) != NULL);
	fct_prop_set(fct_elem_find(ve, "red"), 3, 200);
	/* The camera at the world origin looking along +z, pose: a shift of (0, 0, -1)
	 * (camera-to-world: world = cam + (0, 0, -1)). */
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 100, 80, 50, 50, 49.5, 39.5, 0, 0 };
	double pose[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -1 };
	CHECK_INT(fct_header_set_camera(&m, &cam, &err), 0);
	CHECK_INT(fct_header_set_pose(&m, pose, &err), 0);

	struct fct_project_params par;
	fct_project_params_default(&par);
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.by_k[1], 4);
	CHECK_INT(st.by_k[2], 2);
	CHECK_INT(st.moved[2], 2);
	CHECK_INT(st.rejected, 0);
	CHECK_INT(st.texcoords, 1);
	/* Ridge vertices: onto the line x = 0, z = 2, y unchanged. */
	CHECK_NEAR(m.xyz[3 * 2 + 0], 0, 1e-15);
	CHECK_NEAR(m.xyz[3 * 2 + 1], -0.5, 1e-15);
	CHECK_NEAR(m.xyz[3 * 2 + 2], 2, 1e-15);
	CHECK_NEAR(m.xyz[3 * 3 + 2], 2, 1e-15);
	/* Vertex 0 (-1, -0.5, 1.52) onto z = 2 + 0.5 x: its offset 1.52 - 1.5 = 0.02
	 * along z, the foot moves by 0.02 * n_z * n: (-1 + 0.02 * 0.4 * 0.5 / ...). */
	double r = -(pl[0].n[0] * -1 + pl[0].n[2] * 1.52 + pl[0].d);
	CHECK_NEAR(m.xyz[0], -1 + r * pl[0].n[0], 1e-15);
	CHECK_NEAR(m.xyz[2], 1.52 + r * pl[0].n[2], 1e-15);
	CHECK_NEAR(m.xyz[1], -0.5, 0);
	/* s t of the ridge vertex (0, -0.5, 2): camera frame (0, -0.5, 3):
	 * u = 49.5, v = 50 * -0.5 / 3 + 39.5 = 31.1667. */
	const struct fct_prop *ps = fct_elem_find(ve, "s"), *pt = fct_elem_find(ve, "t");
	CHECK_NEAR(fct_prop_get(ps, 2), 50.0 / 100, 1e-7);
	CHECK_NEAR(fct_prop_get(pt, 2), 1 - (50 * -0.5 / 3 + 39.5 + 0.5) / 80, 1e-7);
	CHECK_NEAR(fct_prop_get(fct_elem_find(ve, "red"), 3), 200, 0);   /* kept */
	CHECK_INT(m.nf, 4);
	CHECK(st.rms_after < 1e-15 && st.rms_before > 0.01);

	/* Without a camera: s t untouched. */
	fct_header_set_camera(&m, &(struct fct_camera){ FCT_CAMERA_NONE, 0, 0, 0, 0, 0, 0, 0, 0 }, &err);
	fct_prop_set(fct_elem_find(ve, "s"), 0, 0.125);
	m.xyz[0] += 0.01;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.texcoords, 0);
	CHECK_NEAR(fct_prop_get(fct_elem_find(ve, "s"), 0), 0.125, 0);

	/* A tight bound: a ridge vertex 0.05 off its line is kept. */
	m.xyz[3 * 3 + 0] = 0.05;
	par.max_move = 0.001;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.rejected, 1);
	CHECK_NEAR(m.xyz[3 * 3 + 0], 0.05, 0);
	fct_mesh_free(&m);
}

/* --along-rays: the tent's vertices move along their rays from the camera
 * centre (0, 0, -1): a vertex on one plane lands where its ray meets the
 * plane, and keeps its s t. */
static void test_along_rays(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	double xs[4][3] = { { -1, -0.5, 1.52 }, { -1, 0.5, 1.47 }, { -0.9, -0.4, 1.56 }, { -0.8, 0.45, 1.6 } };
	for (int i = 0; i < 4; i++)
		fct_mesh_add_vertex(&m, xs[i][0], xs[i][1], xs[i][2], &err);
	uint32_t f[2][3] = { { 0, 2, 1 }, { 1, 2, 3 } };
	for (int i = 0; i < 2; i++)
		fct_mesh_add_face(&m, f[i], 3, &err);
	int32_t lab[2] = { 0, 0 };
	CHECK_INT(fct_patches_set(&m, lab, &err), 0);
	double s5 = sqrt(1.25);
	struct fct_plane pl[1] = { { { 0.5 / s5, 0, -1 / s5 }, 2 / s5, 2, 0 } };
	CHECK_INT(fct_planes_set(&m, pl, 1, &err), 0);
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 100, 80, 50, 50, 49.5, 39.5, 0, 0 };
	double pose[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -1 };
	CHECK_INT(fct_header_set_camera(&m, &cam, &err), 0);
	CHECK_INT(fct_header_set_pose(&m, pose, &err), 0);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.along_rays = 1;
	par.max_move = HUGE_VAL;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.along_ray, 4);
	/* Vertex 0: ray (-1, -0.5, 2.52) from (0, 0, -1); on z = 2 + 0.5 x at
	 * lambda with -1 + 2.52 lambda = 2 - 0.5 lambda: lambda = 3 / 3.02. */
	double lambda = 3 / 3.02;
	CHECK_NEAR(m.xyz[0], -lambda, 1e-15);
	CHECK_NEAR(m.xyz[1], -0.5 * lambda, 1e-15);
	CHECK_NEAR(m.xyz[2], -1 + 2.52 * lambda, 1e-15);
	/* Its pixel is unchanged: u = 49.5 + 50 * x / z_cam. */
	const struct fct_prop *ps = fct_elem_find(&m.vertex, "s");
	CHECK_NEAR(fct_prop_get(ps, 0), (49.5 + 50 * -1 / 2.52 + 0.5) / 100, 1e-7);
	CHECK(st.rms_after < 1e-15);
	fct_mesh_free(&m);
}

/* Malformed input: no patch property, no plane element, an empty mesh. */
static void test_bad(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	struct fct_project_params par;
	fct_project_params_default(&par);
	struct fct_project_stats st;
	struct fct_plane pl = { { 0, 0, 1 }, 0, 0, 0 };
	/* Empty, with planes and labels declared: nothing to do. */
	CHECK_INT(fct_planes_set(&m, &pl, 1, &err), 0);
	CHECK_INT(fct_patches_set(&m, NULL, &err), 0);
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.nvert, 0);
	fct_mesh_free(&m);

	fct_mesh_init(&m);
	uint32_t tri[3] = { 0, 1, 2 };
	for (int i = 0; i < 3; i++)
		fct_mesh_add_vertex(&m, i == 1, i == 2, 0.1, &err);
	fct_mesh_add_face(&m, tri, 3, &err);
	CHECK_INT(fct_planes_set(&m, &pl, 1, &err), 0);
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), -1);
	CHECK(strstr(err.msg, "no face property patch") != NULL);
	int32_t lab = 0;
	CHECK_INT(fct_patches_set(&m, &lab, &err), 0);
	fct_mesh_remove_elem(&m, "plane");
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), -1);
	CHECK(strstr(err.msg, "no plane element") != NULL);
	/* A label beyond the planes. */
	CHECK_INT(fct_planes_set(&m, &pl, 1, &err), 0);
	lab = 3;
	CHECK_INT(fct_patches_set(&m, &lab, &err), 0);
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), -1);
	lab = 0;
	CHECK_INT(fct_patches_set(&m, &lab, &err), 0);
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_NEAR(m.xyz[2], 0, 0);
	fct_mesh_free(&m);
}

/* Vertices of the labelled faces of the room. */
static unsigned char *labelled_vertices(const struct fct_mesh *m)
{
	unsigned char *on = calloc(m->nv, 1);
	int32_t *lab;
	int present;
	fct_patches_get(m, &lab, &present, -1, &err);
	for (size_t f = 0; f < m->nf; f++)
		if (lab[f] >= 0)
			for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++)
				on[m->fvert[k]] = 1;
	free(lab);
	return on;
}

/* mkscene's room: its planar vertices moved by noise (sigma 5 mm) and
 * projected back onto the true planes.  Noise within the span of a vertex's
 * plane normals (across its plane, its line, anywhere at a corner) is undone
 * exactly: the vertices land on scene.ply's.  Noise in any direction leaves
 * every vertex on all of its true planes. */
static void test_room_noise(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_plane *pl;
	size_t npl;
	CHECK_INT(fct_planes_get(&s.mesh, &pl, &npl, &err), 0);
	int32_t *lab;
	int present;
	CHECK_INT(fct_patches_get(&s.mesh, &lab, &present, (long)npl, &err), 0);
	for (int iso = 0; iso < 2; iso++) {
		struct fct_mesh m;
		CHECK_INT(fct_mesh_copy(&m, &s.mesh, &err), 0);
		unsigned char *on = labelled_vertices(&m);
		struct fct_rng rng;
		fct_rng_seed(&rng, 4);
		size_t non = 0;
		if (iso) {
			for (size_t v = 0; v < m.nv; v++)
				if (on[v]) {
					non++;
					for (int c = 0; c < 3; c++)
						m.xyz[3 * v + c] += 0.005 * fct_rng_normal(&rng);
				}
		} else {
			/* Noise along the normals of each face's plane at its corners,
			 * once per vertex and plane. */
			unsigned char *done = calloc(m.nv * npl, 1);
			for (size_t f = 0; f < m.nf; f++)
				for (uint32_t k = m.fstart[f]; k < m.fstart[f + 1] && lab[f] >= 0; k++) {
					uint32_t v = m.fvert[k];
					if (done[v * npl + (size_t)lab[f]]++)
						continue;
					double g = 0.005 * fct_rng_normal(&rng);
					for (int c = 0; c < 3; c++)
						m.xyz[3 * v + c] += g * pl[lab[f]].n[c];
				}
			for (size_t v = 0; v < m.nv; v++)
				non += on[v];
			free(done);
		}
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.max_move = 0.1;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		double maxd = 0, maxoff = 0, maxpl = 0;
		for (size_t v = 0; v < m.nv; v++) {
			double d = sqrt(fct_v3_dist2(m.xyz + 3 * v, s.mesh.xyz + 3 * v));
			if (on[v] && d > maxd)
				maxd = d;
			if (!on[v] && d > maxoff)
				maxoff = d;
		}
		for (size_t f = 0; f < m.nf; f++)
			for (uint32_t k = m.fstart[f]; k < m.fstart[f + 1] && lab[f] >= 0; k++) {
				double d = fabs(fct_plane_distance(&pl[lab[f]], m.xyz + 3 * m.fvert[k]));
				if (d > maxpl)
					maxpl = d;
			}
		/* Corners of three planes (room and box tops), edges of two (box
		 * bottoms, ramp), faces of one. */
		CHECK(st.by_k[3] >= 20 && st.by_k[2] >= 16 && st.by_k[1] > 0);
		CHECK_INT(st.rejected, 0);
		CHECK_INT(st.moved[1] + st.moved[2] + st.moved[3], non);
		if (!iso)
			CHECK_MSG(maxd < 1e-12, "room: %g from scene.ply", maxd);
		else
			CHECK(maxd > 1e-3);   /* along lines and planes, the noise stays */
		CHECK_MSG(maxpl < 1e-12, "room: %g from the true planes", maxpl);
		CHECK_NEAR(maxoff, 0, 0);   /* curved surfaces untouched */
		CHECK(st.rms_before > 0.002 && st.rms_after < 1e-14);
		free(on);
		fct_mesh_free(&m);
	}
	free(pl);
	free(lab);
	fct_scene_free(&s);
}

/* Rotate unit n by angle a about an axis perpendicular to it chosen by rng. */
static void tilt(double n[3], double a, struct fct_rng *rng)
{
	double r[3] = { fct_rng_normal(rng), fct_rng_normal(rng), fct_rng_normal(rng) }, ax[3];
	fct_v3_cross(ax, n, r);
	unit(ax);
	double b[3];
	fct_v3_cross(b, ax, n);   /* unit, perpendicular to n */
	for (int c = 0; c < 3; c++)
		n[c] = cos(a) * n[c] + sin(a) * b[c];
}

/* Tilt every plane by deg degrees (random axes from seed) about its point
 * nearest the origin. */
static void tilt_planes(struct fct_plane *pl, size_t n, double deg, uint64_t seed)
{
	struct fct_rng rng;
	fct_rng_seed(&rng, seed);
	for (size_t i = 0; i < n; i++) {
		double q[3] = { -pl[i].d * pl[i].n[0], -pl[i].d * pl[i].n[1], -pl[i].d * pl[i].n[2] };
		tilt(pl[i].n, deg * M_PI / 180, &rng);
		pl[i].d = -fct_v3_dot(pl[i].n, q);
	}
}

/* --orthogonal on the room's planes each tilted by 2 degrees: pairs that
 * were orthogonal or parallel are exactly so again (1e-9), with the true up;
 * the normals are back within 2 degrees of the truth; the vertices lie on
 * the snapped planes. */
static void test_room_orthogonal(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_mesh m;
	CHECK_INT(fct_mesh_copy(&m, &s.mesh, &err), 0);
	struct fct_plane *truth, *pl;
	size_t n, n2;
	CHECK_INT(fct_planes_get(&m, &truth, &n, &err), 0);
	CHECK_INT(fct_planes_get(&m, &pl, &n2, &err), 0);
	tilt_planes(pl, n, 2, 9);
	CHECK_INT(fct_planes_set(&m, pl, n, &err), 0);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.ortho_angle = 5;
	par.max_move = 1;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.ortho, 1);
	free(pl);
	CHECK_INT(fct_planes_get(&m, &pl, &n2, &err), 0);
	CHECK_INT(n2, n);
	CHECK(st.ortho_res.up[2] > cos(1 * M_PI / 180));   /* z up, within a degree */
	/* The room frame and box3's own (30 degrees turned). */
	CHECK_INT(st.ortho_res.frames, 2);
	size_t orth = 0, par_ = 0;
	double worst_orth = 0, worst_par = 0, worst_truth = 0;
	for (size_t i = 0; i < n; i++) {
		double ct = fct_v3_dot(pl[i].n, truth[i].n);
		double ang = acos(ct > 1 ? 1 : ct) * 180 / M_PI;
		if (ang > worst_truth)
			worst_truth = ang;
		for (size_t j = i + 1; j < n; j++) {
			double t = fct_v3_dot(truth[i].n, truth[j].n), c = fct_v3_dot(pl[i].n, pl[j].n);
			if (fabs(t) < 1e-9) {
				orth++;
				if (fabs(c) > worst_orth)
					worst_orth = fabs(c);
			} else if (fabs(fabs(t) - 1) < 1e-9) {
				double cr[3];
				fct_v3_cross(cr, pl[i].n, pl[j].n);
				par_++;
				if (sqrt(fct_v3_dot(cr, cr)) > worst_par)
					worst_par = sqrt(fct_v3_dot(cr, cr));
			}
		}
	}
	CHECK(orth > 100 && par_ > 50);
	CHECK_MSG(worst_orth < 1e-9, "orthogonal pairs: worst |cos| %g", worst_orth);
	CHECK_MSG(worst_par < 1e-9, "parallel pairs: worst |sin| %g", worst_par);
	CHECK_MSG(worst_truth < 2, "normals within 2 degrees of the truth: %g", worst_truth);
	CHECK(st.ortho_res.max_change > 1 && st.ortho_res.max_change < 4);
	/* Horizontal: floor, ceiling, 3 box tops, cylinder top; the ramp is oblique. */
	CHECK_INT(st.ortho_res.horizontal, 6);
	CHECK_INT(st.ortho_res.oblique, 1);
	CHECK_INT(st.ortho_res.vertical, 18);
	CHECK(st.max_after < 1e-12);   /* re-projected onto the snapped planes */
	CHECK_INT(st.rejected, 0);
	free(pl);
	free(truth);
	fct_mesh_free(&m);
	fct_scene_free(&s);
}

/* --depth-scale-fix: the room seen from view 0 with camera-frame depth
 * divided by 1.6 (the focal length with it); the stage finds 1.6 and puts
 * the vertices back. */
static void test_room_depth_scale(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_mesh m;
	CHECK_INT(fct_mesh_copy(&m, &s.mesh, &err), 0);
	double pose[12];
	fct_scene_view_pose(&s, 0, 1, pose);
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 640, 480, 525, 525, 319.5, 239.5, 0, 0 };
	struct fct_plane *pl, *truth;
	size_t n;
	CHECK_INT(fct_planes_get(&m, &pl, &n, &err), 0);
	CHECK_INT(fct_planes_get(&m, &truth, &n, &err), 0);
	const double lambda0 = 1.6;
	struct fct_camera cam2 = cam;
	fct_depth_scale_apply(1 / lambda0, pose, 0, m.xyz, m.nv, pl, n, &cam2);
	CHECK_NEAR(cam2.fx, 525 / lambda0, 1e-12);
	/* Independent checks of the transform: vertices stay on their planes,
	 * pixels are unchanged (the focal length scales with depth), and the
	 * camera-frame z of a vertex is divided by 1.6. */
	double inv[12];
	fct_pose_invert(pose, inv);
	int32_t *lab;
	int present;
	fct_patches_get(&m, &lab, &present, -1, &err);
	double worst = 0, worst_px = 0, worst_z = 0;
	for (size_t f = 0; f < m.nf; f++) {
		if (lab[f] < 0)
			continue;
		for (uint32_t k = m.fstart[f]; k < m.fstart[f + 1]; k++) {
			double d = fabs(fct_plane_distance(&pl[lab[f]], m.xyz + 3 * m.fvert[k]));
			if (d > worst)
				worst = d;
		}
	}
	for (size_t v = 0; v < m.nv; v++) {
		double a[3], b[3], sa, ta, sb, tb;
		fct_pose_apply(inv, s.mesh.xyz + 3 * v, a);
		fct_pose_apply(inv, m.xyz + 3 * v, b);
		if (a[2] <= 0)
			continue;
		if (fabs(b[2] - a[2] / lambda0) > worst_z)
			worst_z = fabs(b[2] - a[2] / lambda0);
		fct_project_texcoord(&cam, inv, s.mesh.xyz + 3 * v, &sa, &ta);
		fct_project_texcoord(&cam2, inv, m.xyz + 3 * v, &sb, &tb);
		if (fabs(sa - sb) + fabs(ta - tb) > worst_px)
			worst_px = fabs(sa - sb) + fabs(ta - tb);
	}
	CHECK(worst < 1e-12);
	CHECK(worst_px < 1e-12);
	CHECK(worst_z < 1e-12);
	free(lab);
	CHECK_INT(fct_planes_set(&m, pl, n, &err), 0);
	CHECK_INT(fct_header_set_camera(&m, &cam2, &err), 0);
	CHECK_INT(fct_header_set_pose(&m, pose, &err), 0);

	struct fct_mesh m2;
	CHECK_INT(fct_mesh_copy(&m2, &m, &err), 0);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.depth_scale_fix = 1;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_MSG(fabs(st.scale_res.scale / lambda0 - 1) < 1e-9, "scale %.12g", st.scale_res.scale);
	CHECK(st.scale_res.inliers >= 12);   /* walls, floor and ceiling: the boxes are under 1% */
	double maxd = 0;
	for (size_t v = 0; v < m.nv; v++) {
		double d = sqrt(fct_v3_dist2(m.xyz + 3 * v, s.mesh.xyz + 3 * v));
		if (d > maxd)
			maxd = d;
	}
	CHECK_MSG(maxd < 1e-9, "vertices back: %g", maxd);
	struct fct_camera got;
	CHECK_INT(fct_header_camera(&m, &got, &err), 1);
	CHECK_NEAR(got.fx, 525, 1e-6);
	free(pl);
	CHECK_INT(fct_planes_get(&m, &pl, &n, &err), 0);
	for (size_t i = 0; i < n; i++)
		CHECK(fct_v3_dot(pl[i].n, truth[i].n) > 1 - 1e-12);

	/* Noisy planes (each tilted by 0.5 degrees): the scale within 1%. */
	free(pl);
	CHECK_INT(fct_planes_get(&m2, &pl, &n, &err), 0);
	tilt_planes(pl, n, 0.5, 3);
	CHECK_INT(fct_planes_set(&m2, pl, n, &err), 0);
	par.max_move = HUGE_VAL;
	CHECK_INT(fct_project_mesh(&m2, &par, &st, &err), 0);
	CHECK_MSG(fabs(st.scale_res.scale / lambda0 - 1) < 0.01, "noisy scale %.12g", st.scale_res.scale);
	free(pl);
	free(truth);
	fct_mesh_free(&m);
	fct_mesh_free(&m2);
	fct_scene_free(&s);
}

/* View 0 of the room rendered through camera `truth` with Kinect-class
 * noise, meshed as dm2mesh does through camera `cam` (the same, or a wrong
 * focal length), in the world frame; faces labelled with the true patch of
 * two or three of their pixels (-1 when all three differ); vpatch gets each
 * vertex's own pixel's patch.  pose gets the view's pose. */
static void labelled_view(const struct fct_scene *s, const struct fct_camera *truth,
                          const struct fct_camera *cam, struct fct_mesh *m, int32_t **vpatch_out,
                          double pose[12])
{
	fct_scene_view_pose(s, 0, 1, pose);
	struct fct_render r;
	CHECK_INT(fct_scene_render(s, truth, pose, &r, &err), 0);
	struct fct_scene_noise nz = { 0, 0.0025, 0, 0, 90, 0, 0 , {0}};
	double *noisy = malloc((size_t)r.width * r.height * sizeof *noisy);
	fct_depth_noise(&nz, 5, 0, r.depth, NULL, r.cosine, noisy, (size_t)r.width * r.height, NULL);
	struct fct_image img;
	CHECK_INT(fct_image_alloc(&img, r.width, r.height, 1, FCT_PIX_F32, &err), 0);
	for (int i = 0; i < r.width * r.height; i++)
		((float *)img.data)[i] = (float)noisy[i];
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	CHECK_INT(fct_depth_mesh(m, &img, cam, &dp, NULL, &err), 0);
	m->xyz_type = FCT_FLOAT64;
	const struct fct_prop *ps = fct_elem_find(&m->vertex, "s"), *pt = fct_elem_find(&m->vertex, "t");
	int32_t *vpatch = malloc(m->nv * sizeof *vpatch), *fpatch = malloc(m->nf * sizeof *fpatch);
	for (size_t v = 0; v < m->nv; v++) {
		int u = (int)lround(fct_prop_get(ps, v) * r.width - 0.5);
		int w = (int)lround((1 - fct_prop_get(pt, v)) * r.height - 0.5);
		int32_t f = r.face[(size_t)w * r.width + u];
		vpatch[v] = f >= 0 ? s->surf[s->face_surface[f]].patch : -1;
		fct_pose_apply(pose, m->xyz + 3 * v, m->xyz + 3 * v);
	}
	size_t labelled = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *fv = m->fvert + m->fstart[f];
		fpatch[f] = vpatch[fv[0]] == vpatch[fv[1]] || vpatch[fv[0]] == vpatch[fv[2]] ? vpatch[fv[0]]
		          : vpatch[fv[1]] == vpatch[fv[2]] ? vpatch[fv[1]] : -1;
		labelled += fpatch[f] >= 0;
	}
	CHECK(labelled > m->nf * 9 / 10);
	CHECK_INT(fct_patches_set(m, fpatch, &err), 0);
	CHECK_INT(fct_header_set_camera(m, cam, &err), 0);
	CHECK_INT(fct_header_set_pose(m, pose, &err), 0);
	*vpatch_out = vpatch;
	free(fpatch);
	free(noisy);
	fct_image_free(&img);
	fct_render_free(&r);
}

/* A dense mesh labelled with the true patches and given the true planes:
 * projection brings the vertices much closer to the true surface, and s t
 * are those of the new positions. */
static void test_dense_view(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 160, 120, 131.25, 131.25, 79.5, 59.5, 0, 0 };
	struct fct_mesh m;
	int32_t *vpatch;
	double pose[12], inv[12];
	labelled_view(&s, &cam, &cam, &m, &vpatch, pose);
	fct_pose_invert(pose, inv);
	struct fct_plane *pl;
	size_t npl;
	CHECK_INT(fct_planes_get(&s.mesh, &pl, &npl, &err), 0);
	CHECK_INT(fct_planes_set(&m, pl, npl, &err), 0);

	/* Distance of each vertex to its pixel's true plane, before and after. */
	double before = 0, after = 0;
	size_t cnt = 0;
	for (size_t v = 0; v < m.nv; v++)
		if (vpatch[v] >= 0)
			before += fabs(fct_plane_distance(&pl[vpatch[v]], m.xyz + 3 * v)), cnt++;
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.max_move = 0.2;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	for (size_t v = 0; v < m.nv; v++)
		if (vpatch[v] >= 0)
			after += fabs(fct_plane_distance(&pl[vpatch[v]], m.xyz + 3 * v));
	before /= (double)cnt, after /= (double)cnt;
	/* Measured: 22.9 mm before, 0.33 mm after. */
	CHECK_MSG(after < 0.05 * before, "mean distance to the true plane: %g before, %g after", before, after);
	CHECK_MSG(st.by_k[1] > st.by_k[2] && st.by_k[2] > 100, "k: %zu %zu %zu %zu", st.by_k[0],
	          st.by_k[1], st.by_k[2], st.by_k[3]);
	CHECK_INT(st.texcoords, 1);
	const struct fct_prop *ps = fct_elem_find(&m.vertex, "s"), *pt = fct_elem_find(&m.vertex, "t");
	double worst = 0;
	int all = 1;
	for (size_t v = 0; v < m.nv; v++) {
		double sv, tv;
		all &= fct_project_texcoord(&cam, inv, m.xyz + 3 * v, &sv, &tv);
		double e = fabs(sv - fct_prop_get(ps, v)) + fabs(tv - fct_prop_get(pt, v));
		if (e > worst)
			worst = e;
	}
	CHECK(all);
	CHECK(worst < 1e-7);   /* float s t */
	free(pl);
	free(vpatch);
	fct_mesh_free(&m);
	fct_scene_free(&s);
}

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

/* Least-squares planes of the labelled vertices of each patch (each vertex
 * once per patch): through the centroid, normal the scatter matrix's
 * eigenvector of the smallest eigenvalue. */
static struct fct_plane *fit_planes(const struct fct_mesh *m, size_t np)
{
	int32_t *lab;
	int present;
	fct_patches_get(m, &lab, &present, (long)np, &err);
	double (*mom)[10] = calloc(np, sizeof *mom);   /* n, sx sy sz, sxx sxy sxz syy syz szz */
	unsigned char *seen = calloc(m->nv * np, 1);
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1] && lab[f] >= 0; k++) {
			uint32_t v = m->fvert[k];
			if (seen[v * np + (size_t)lab[f]]++)
				continue;
			double *q = mom[lab[f]];
			const double *p = m->xyz + 3 * v;
			q[0] += 1, q[1] += p[0], q[2] += p[1], q[3] += p[2];
			q[4] += p[0] * p[0], q[5] += p[0] * p[1], q[6] += p[0] * p[2];
			q[7] += p[1] * p[1], q[8] += p[1] * p[2], q[9] += p[2] * p[2];
		}
	struct fct_plane *pl = calloc(np, sizeof *pl);
	for (size_t i = 0; i < np; i++) {
		double *q = mom[i], n = q[0] > 0 ? q[0] : 1, c[3] = { q[1] / n, q[2] / n, q[3] / n };
		double a[9] = { q[4] / n - c[0] * c[0], q[5] / n - c[0] * c[1], q[6] / n - c[0] * c[2],
		                0, q[7] / n - c[1] * c[1], q[8] / n - c[1] * c[2],
		                0, 0, q[9] / n - c[2] * c[2] };
		a[3] = a[1], a[6] = a[2], a[7] = a[5];
		double w[3], work[64];
		int three = 3, lwork = 64, info;
		dsyev_("V", "U", &three, a, &three, w, work, &lwork, &info);
		pl[i].n[0] = a[0], pl[i].n[1] = a[1], pl[i].n[2] = a[2];
		if (q[0] < 3)
			pl[i].n[0] = 0, pl[i].n[1] = 0, pl[i].n[2] = 1;
		pl[i].d = -fct_v3_dot(pl[i].n, c);
		pl[i].count = (long)q[0];
	}
	free(lab);
	free(mom);
	free(seen);
	return pl;
}

/* The depth scale of a real-looking mesh: the room seen through a camera of
 * focal length 75 but meshed with 131.25 (1.75 times too long: the
 * reconstruction's depth is 1.75 times too deep for its width), planes
 * fitted to the noisy labelled vertices.  The fix finds 1 / 1.75 within 1%
 * and the camera's focal length comes back to 75 within 1%.  With the right
 * focal length it finds 1 within 1%. */
static void test_dense_scale(void)
{
	struct fct_scene s;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	struct fct_camera truth = { FCT_CAMERA_PINHOLE, 160, 120, 75, 75, 79.5, 59.5, 0, 0 };
	struct fct_camera wrong = truth;
	wrong.fx = wrong.fy = 131.25;
	for (int right = 0; right < 2; right++) {
		struct fct_mesh m;
		int32_t *vpatch;
		double pose[12];
		labelled_view(&s, &truth, right ? &truth : &wrong, &m, &vpatch, pose);
		struct fct_plane *pl = fit_planes(&m, s.nplanes);
		CHECK_INT(fct_planes_set(&m, pl, s.nplanes, &err), 0);
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.depth_scale_fix = 1;
		par.max_move = 0.2;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		double want = right ? 1 : 75 / 131.25;
		CHECK_MSG(fabs(st.scale_res.scale / want - 1) < 0.01, "scale %.9g, want %.9g",
		          st.scale_res.scale, want);
		struct fct_camera got;
		CHECK_INT(fct_header_camera(&m, &got, &err), 1);
		CHECK_MSG(fabs(got.fx / 75 - 1) < 0.01, "focal length %.9g", got.fx);
		free(pl);
		free(vpatch);
		fct_mesh_free(&m);
	}
	fct_scene_free(&s);
}

/* A wireframe (simpchain's edge element, no faces) seen by a camera at the
 * origin looking along +z.  The planes are given as n.p + d = 0 facing the
 * camera. */
static void wire_mesh(struct fct_mesh *m, const double (*xs)[3], size_t nv, const struct fct_wire *w,
                      size_t nw, const struct fct_plane *pl, size_t npl, int camera)
{
	fct_mesh_init(m);
	for (size_t i = 0; i < nv; i++)
		fct_mesh_add_vertex(m, xs[i][0], xs[i][1], xs[i][2], &err);
	CHECK_INT(fct_wires_set(m, w, nw, &err), 0);
	CHECK_INT(fct_planes_set(m, pl, npl, &err), 0);
	if (camera) {
		struct fct_camera cam = { FCT_CAMERA_PINHOLE, 100, 100, 100, 100, 49.5, 49.5, 0, 0 };
		CHECK_INT(fct_header_set_camera(m, &cam, &err), 0);
	}
}

static struct fct_wire *wires_of(const struct fct_mesh *m, size_t *n)
{
	struct fct_wire *w = NULL;
	int present = 0;
	CHECK_INT(fct_wires_get(m, -1, &w, n, &present, &err), 0);
	CHECK_INT(present, 1);
	return w;
}

/* A crease: planes y = 0 (patch 0, a floor) and z = 3 (patch 1, a wall)
 * meet on the line y = 0, z = 3.  A noisy chain of five vertices along it
 * goes onto the line; without a camera the three inner ones are then
 * straight and dropped, leaving one edge between the exact ends; with
 * straightening off they stay, on the line. */
static void test_wire_crease(void)
{
	double xs[5][3] = { { -1, 0.02, 3.01 }, { -0.5, -0.01, 2.98 }, { 0, 0.03, 3.02 },
	                    { 0.5, 0.0, 2.99 }, { 1, -0.02, 3.0 } };
	struct fct_wire w[4];
	for (uint32_t i = 0; i < 4; i++)
		w[i] = (struct fct_wire){ i, i + 1, 0, 1 };
	struct fct_plane pl[2] = { { { 0, -1, 0 }, 0, 10, 0 }, { { 0, 0, -1 }, 3, 10, 0 } };
	for (int straight = 0; straight < 2; straight++) {
		struct fct_mesh m;
		wire_mesh(&m, xs, 5, w, 4, pl, 2, 0);
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.straighten = straight;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		CHECK_INT(st.by_k[2], 5);
		CHECK_INT(st.moved[2], 5);
		/* k = 2: the foot on the line keeps x. */
		for (size_t v = 0; v < m.nv; v++) {
			CHECK_NEAR(m.xyz[3 * v + 1], 0, 1e-15);
			CHECK_NEAR(m.xyz[3 * v + 2], 3, 1e-15);
		}
		size_t nw = 0;
		struct fct_wire *got = wires_of(&m, &nw);
		if (straight) {
			CHECK_INT(st.straightened, 3);
			CHECK_INT(m.nv, 2);
			CHECK_INT(nw, 1);
			CHECK_NEAR(m.xyz[0], -1, 0);
			CHECK_NEAR(m.xyz[3], 1, 0);
			CHECK(nw == 1 && got[0].v1 == 0 && got[0].v2 == 1 && got[0].p1 == 0 && got[0].p2 == 1);
		} else {
			CHECK_INT(st.straightened, 0);
			CHECK_INT(m.nv, 5);
			CHECK_INT(nw, 4);
		}
		free(got);
		fct_mesh_free(&m);
	}
}

/* An occlusion: a box face on the plane z = 2 (patch 0) before a wall z = 4
 * (patch 1), both facing the camera (normal -z).  The depth map joined them,
 * so the silhouette chain (vertices 0-2, at depth 2.5 between the two) has
 * patch 0 on one side and 1 on the other.  The planes are parallel: the
 * vertices are torn, the box keeps each vertex on z = 2 along its ray and
 * the wall gets a copy on z = 4 along the same ray -- the same pixel.  The
 * two border chains of the box (patch 0 / -1) keep their vertices 3, 4. */
static const struct fct_wire silhouette[5] = { { 0, 1, 0, 1 }, { 1, 2, 0, 1 }, { 2, 3, 0, -1 },
                                                { 3, 4, 0, -1 }, { 4, 0, 0, -1 } };
static const struct fct_plane box_wall[2] = { { { 0, 0, -1 }, 2, 10, 0 }, { { 0, 0, -1 }, 4, 10, 0 } };

static void test_wire_tear(void)
{
	const struct fct_wire *w = silhouette;
	const struct fct_plane *pl = box_wall;
	double xs[5][3] = { { 0.5, -0.5, 2.5 }, { 0.5, 0, 2.5 }, { 0.5, 0.5, 2.5 }, { -0.5, 0.5, 2 },
	                    { -0.5, -0.5, 2 } };
	struct fct_mesh m;
	wire_mesh(&m, xs, 5, w, 5, pl, 2, 1);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.max_move = 0.4;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.torn, 3);
	CHECK_INT(st.tear_copies, 3);
	CHECK_INT(st.rejected, 0);
	CHECK_INT(m.nv, 8);
	/* Vertex i (i < 3) on the box: (0.5, y, 2.5) * 2 / 2.5; its copy 5 + i on
	 * the wall: * 4 / 2.5. */
	for (int i = 0; i < 3; i++) {
		for (int q = 0; q < 3; q++) {
			CHECK_NEAR(m.xyz[3 * i + q], xs[i][q] * 2 / 2.5, 1e-15);
			CHECK_NEAR(m.xyz[3 * (5 + i) + q], xs[i][q] * 4 / 2.5, 1e-15);
		}
	}
	/* The box's own corners, on one plane, go onto it. */
	CHECK_NEAR(m.xyz[3 * 3 + 2], 2, 0);
	/* The two silhouette edges split: 0-1, 1-2 on the box side (0 / -1) and
	 * 5-6, 6-7 on the wall side (-1 / 1); the border edges are kept. */
	size_t nw = 0;
	struct fct_wire *got = wires_of(&m, &nw);
	CHECK_INT(nw, 7);
	int box = 0, wall = 0;
	for (size_t e = 0; e < nw; e++) {
		if (got[e].p1 == 0 && got[e].p2 == -1 && got[e].v1 < 3 && got[e].v2 < 3)
			box++;
		if (got[e].p1 == -1 && got[e].p2 == 1 && got[e].v1 >= 5 && got[e].v2 >= 5)
			wall++;
	}
	CHECK_INT(box, 2);
	CHECK_INT(wall, 2);
	/* Copies share their pixel: s t equal. */
	struct fct_prop *ps = fct_elem_find(&m.vertex, "s"), *pt = fct_elem_find(&m.vertex, "t");
	CHECK(ps && pt);
	if (ps && pt)
		for (int i = 0; i < 3; i++) {
			CHECK_NEAR(fct_prop_get(ps, 5 + (size_t)i), fct_prop_get(ps, (size_t)i), 1e-7);
			CHECK_NEAR(fct_prop_get(pt, 5 + (size_t)i), fct_prop_get(pt, (size_t)i), 1e-7);
		}
	free(got);
	fct_mesh_free(&m);

	/* --no-tear: the vertices stay where they were. */
	wire_mesh(&m, xs, 5, w, 5, pl, 2, 1);
	par.tear = 0;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.torn, 0);
	CHECK_INT(m.nv, 5);
	CHECK_NEAR(m.xyz[2], 2.5, 0);
	fct_mesh_free(&m);
}

/* The image guard: patch 0 (plane z = 2) is a polygon 0-4-3-1-2 whose
 * vertex 1 lies off the plane at (0.3, 0, 1), pixel (79.5, 49.5).  Its
 * perpendicular foot (0.3, 0, 2) is at pixel (64.5, 49.5), from where the
 * edge 1-2 to (37, 62) passes u = 62 at v = 50.6, across the edge 4-3
 * (u = 62, v from 44.5 to 54.5): the boundary would cross itself.  From
 * the vertex's own pixel it passes at v = 54.6, clear of it.  So the foot
 * is refused and the vertex goes along its ray onto the plane instead:
 * (0.6, 0, 2), the same pixel. */
static double wire_crossings(const struct fct_mesh *m, const struct fct_wire *w, size_t nw)
{
	double (*px)[2] = calloc(m->nv, sizeof *px);
	for (size_t i = 0; i < m->nv; i++)
		px[i][0] = 100 * m->xyz[3 * i] / m->xyz[3 * i + 2] + 49.5,
		px[i][1] = 100 * m->xyz[3 * i + 1] / m->xyz[3 * i + 2] + 49.5;
	int n = 0;
	for (size_t a = 0; a < nw; a++)
		for (size_t b = a + 1; b < nw; b++)
			n += fct_segments_conflict(px[w[a].v1], px[w[a].v2], px[w[b].v1], px[w[b].v2], w[a].v1,
			                           w[a].v2, w[b].v1, w[b].v2);
	free(px);
	return n;
}

static void test_wire_guard(void)
{
	double xs[5][3] = { { -0.25, -0.25, 2 }, { 0.3, 0, 1 }, { -0.25, 0.25, 2 }, { 0.25, 0.1, 2 },
	                    { 0.25, -0.1, 2 } };
	struct fct_wire w[5] = { { 0, 4, 0, -1 }, { 4, 3, 0, -1 }, { 3, 1, 0, -1 }, { 1, 2, 0, -1 },
	                         { 2, 0, 0, -1 } };
	struct fct_plane pl[1] = { { { 0, 0, -1 }, 2, 10, 0 } };
	struct fct_mesh m;
	wire_mesh(&m, xs, 5, w, 5, pl, 1, 1);
	CHECK_INT(wire_crossings(&m, w, 5), 0);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.max_move = 2;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.cross_refused, 1);
	CHECK_INT(st.ray_fallback, 1);
	CHECK_NEAR(m.xyz[3], 0.6, 1e-15);
	CHECK_NEAR(m.xyz[4], 0, 1e-15);
	CHECK_NEAR(m.xyz[5], 2, 1e-15);
	CHECK_INT(wire_crossings(&m, w, 5), 0);
	fct_mesh_free(&m);

	/* Without tearing (which includes the ray fallback) the vertex keeps its
	 * place; the boundary still does not cross. */
	wire_mesh(&m, xs, 5, w, 5, pl, 1, 1);
	par.tear = 0;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.cross_refused, 1);
	CHECK_NEAR(m.xyz[3], 0.3, 0);
	CHECK_NEAR(m.xyz[5], 1, 0);
	CHECK_INT(wire_crossings(&m, w, 5), 0);
	fct_mesh_free(&m);
}

/* The flip rule: vertex 0 at (0.3, 0, 0) lies on the floor z = 0 (patch 0,
 * normal +z) and the wall x = 0 (patch 1, normal -x), so it goes to the
 * nearest point of their line, the origin.  Its floor face (0, 2, 1) has
 * its other corners at (0.1, -+1, 0): the origin lies beyond their edge,
 * so the move would turn that face from +0.4 (area vector along +z) to
 * -0.2 and is refused, the vertex kept.  With those corners at x = -0.1
 * the face stays up (+0.8, then +0.2) and the vertex moves. */
static void test_flip_refused(void)
{
	for (int beyond = 0; beyond < 2; beyond++) {
		double cx = beyond ? 0.1 : -0.1;
		double xs[5][3] = { { 0.3, 0, 0 }, { cx, -1, 0 }, { cx, 1, 0 }, { 0, -1, 1 }, { 0, 1, 1 } };
		struct fct_mesh m;
		fct_mesh_init(&m);
		for (int i = 0; i < 5; i++)
			fct_mesh_add_vertex(&m, xs[i][0], xs[i][1], xs[i][2], &err);
		/* The wall face (0, 3, 4): area vector (-2, 0, 0) before and after,
		 * along its normal -x. */
		uint32_t f[2][3] = { { 0, 2, 1 }, { 0, 3, 4 } };
		for (int i = 0; i < 2; i++)
			fct_mesh_add_face(&m, f[i], 3, &err);
		int32_t lab[2] = { 0, 1 };
		CHECK_INT(fct_patches_set(&m, lab, &err), 0);
		struct fct_plane pl[2] = { { { 0, 0, 1 }, 0, 1, 0 }, { { -1, 0, 0 }, 0, 1, 0 } };
		CHECK_INT(fct_planes_set(&m, pl, 2, &err), 0);
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.max_move = HUGE_VAL;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		CHECK_INT(st.by_k[2], 1);
		CHECK_INT(st.flip_refused, beyond);
		CHECK_INT(st.moved[2], !beyond);
		CHECK_INT(st.rejected, 0);
		CHECK_NEAR(m.xyz[0], beyond ? 0.3 : 0, 0);
		CHECK_NEAR(m.xyz[1], 0, 0);
		CHECK_NEAR(m.xyz[2], 0, 0);
		fct_mesh_free(&m);
	}
}

/* A vertex of one plane refused for its distance goes along its ray, at
 * most FCT_PROJECT_RAY_EDGES bounds.  The notch 0-1-2-3-4 of patch 0
 * (plane z = 2) has vertex 2 at (0.1, 0, 2.5), 0.5 off the plane; its ray
 * from the camera at the origin meets the plane at 0.8 times it,
 * (0.08, 0, 2), 0.2 |(0.1, 0, 2.5)| = 0.50040 away.  Bound 0.2: the foot
 * (0.5) is refused, the ray (0.5004 <= 0.6) taken, pixel (53.5, 49.5)
 * kept.  Bound 0.15: the ray is too long too (> 0.45), the vertex kept. */
static void test_ray_reach(void)
{
	double xs[5][3] = { { -0.5, -0.5, 2 }, { 0.5, -0.5, 2 }, { 0.1, 0, 2.5 }, { 0.5, 0.5, 2 },
	                    { -0.5, 0.5, 2 } };
	struct fct_wire w[5];
	for (uint32_t i = 0; i < 5; i++)
		w[i] = (struct fct_wire){ i, (i + 1) % 5, 0, -1 };
	struct fct_plane pl[1] = { { { 0, 0, -1 }, 2, 10, 0 } };
	for (int far = 0; far < 2; far++) {
		struct fct_mesh m;
		wire_mesh(&m, xs, 5, w, 5, pl, 1, 1);
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.max_move = far ? 0.15 : 0.2;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		CHECK_INT(st.by_k[1], 5);
		CHECK_INT(st.moved[1], 4);
		CHECK_INT(st.ray_fallback, !far);
		CHECK_INT(st.rejected, far);
		CHECK_INT(st.torn, 0);
		CHECK_INT(m.nv, 5);
		CHECK_NEAR(m.xyz[6], far ? 0.1 : 0.08, 1e-15);
		CHECK_NEAR(m.xyz[7], 0, 0);
		CHECK_NEAR(m.xyz[8], far ? 2.5 : 2, 1e-15);
		const struct fct_prop *ps = fct_elem_find(&m.vertex, "s");
		CHECK(ps != NULL);
		if (ps)
			CHECK_NEAR(fct_prop_get(ps, 2), (53.5 + 0.5) / 100, 1e-7);
		fct_mesh_free(&m);
	}
}

/* Between parallel planes: test_wire_tear's silhouette chain at depth 3,
 * midway between the box z = 2 and the wall z = 4.  The two normals are one
 * line (rank 1), whose least-squares move from z = 3 is nil, and the point
 * stays 1 from both planes.  With tearing, its copies lie 1/3 of the ray
 * away (|(0.5, y, 3)| / 3 > 1.01): beyond 10 bounds of 0.05, so the vertex
 * is put back and refused; without tearing that nil move stands. */
static void test_between_parallels(void)
{
	const struct fct_wire *w = silhouette;
	const struct fct_plane *pl = box_wall;
	double xs[5][3] = { { 0.5, -0.5, 3 }, { 0.5, 0, 3 }, { 0.5, 0.5, 3 }, { -0.5, 0.5, 2 },
	                    { -0.5, -0.5, 2 } };
	for (int tear = 0; tear < 2; tear++) {
		struct fct_mesh m;
		wire_mesh(&m, xs, 5, w, 5, pl, 2, 1);
		struct fct_project_params par;
		fct_project_params_default(&par);
		par.max_move = 0.05;
		par.tear = tear;
		struct fct_project_stats st;
		CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
		CHECK_INT(st.by_k[2], 3);
		CHECK_INT(st.rank_deficient, 3);
		CHECK_INT(st.torn, 0);
		CHECK_INT(st.rejected, tear ? 3 : 0);
		CHECK_INT(st.moved[2], tear ? 0 : 3);
		CHECK_INT(m.nv, 5);
		for (int i = 0; i < 3; i++)
			for (int q = 0; q < 3; q++)
				CHECK_NEAR(m.xyz[3 * i + q], xs[i][q], 1e-15);
		CHECK_NEAR(st.max_after, 1, 1e-15);
		fct_mesh_free(&m);
	}
}

/* Snapping by hand (fct_planes_orthogonalize, angle 5): the floor z = 0
 * is up (step 1); the walls of azimuths 2 and 90 degrees (that is 0,
 * modulo 90) make one frame (step 2) at their circular mean, 1 degree;
 * step 3 turns each wall onto the nearer axis of that frame, (cos 1,
 * sin 1, 0) and (-sin 1, cos 1, 0), and takes from the roof (1, 0, 1) /
 * sqrt 2 its component along the axis it is nearly perpendicular to:
 * (cos^2 1, sin 1 cos 1, 1) / sqrt(cos^2 1 + 1).  Step 4: the first wall,
 * x cos 2 + y sin 2 = 3 cos 2, turns about its point nearest the pivot
 * (3, 5, 7), (3, 5, 7) - 5 sin 2 (cos 2, sin 2, 0); the others, without a
 * pivot, about their point nearest the origin. */
static void test_snap_by_hand(void)
{
	const double a2 = 2 * M_PI / 180, a1 = M_PI / 180;
	struct fct_plane pl[4] = { { { 0, 0, 1 }, 0, 1, 0 },
	                           { { cos(a2), sin(a2), 0 }, -3 * cos(a2), 1, 0 },
	                           { { 0, 1, 0 }, -1, 1, 0 },
	                           { { M_SQRT1_2, 0, M_SQRT1_2 }, -1, 1, 0 } };
	double pivot[12] = { NAN, NAN, NAN, 3, 5, 7, NAN, 0, 0, NAN, NAN, NAN };
	double prior[3] = { 0, 0, 1 };
	struct fct_ortho_result r;
	CHECK_INT(fct_planes_orthogonalize(pl, 4, NULL, pivot, prior, 5, &r, &err), 0);
	CHECK_NEAR(r.up[2], 1, 1e-15);
	CHECK_INT(r.frames, 1);
	CHECK_INT(r.horizontal, 1);
	CHECK_INT(r.vertical, 2);
	CHECK_INT(r.oblique, 1);
	CHECK_NEAR(r.max_change, 1, 1e-12);
	double want[4][3] = { { 0, 0, 1 }, { cos(a1), sin(a1), 0 }, { -sin(a1), cos(a1), 0 },
	                      { cos(a1) * cos(a1), sin(a1) * cos(a1), 1 } };
	double l = sqrt(cos(a1) * cos(a1) + 1);
	for (int q = 0; q < 3; q++)
		want[3][q] /= l;
	for (int i = 0; i < 4; i++)
		for (int q = 0; q < 3; q++)
			CHECK_NEAR(pl[i].n[q], want[i][q], 1e-14);
	double foot[3] = { 3 - 5 * sin(a2) * cos(a2), 5 - 5 * sin(a2) * sin(a2), 7 };
	CHECK_NEAR(pl[1].d, -(cos(a1) * foot[0] + sin(a1) * foot[1]), 1e-14);
	CHECK_NEAR(pl[2].d, -cos(a1), 1e-14);   /* about (0, 1, 0) */
	CHECK_NEAR(pl[3].d, -(want[3][0] + want[3][2]) * M_SQRT1_2, 1e-14);   /* about (1, 0, 1) / sqrt 2 */
	CHECK_NEAR(pl[0].d, 0, 0);
}

/* A mesh with faces but no patch property, and a wireframe: the vertices
 * take their planes from the wires, and the faces, with no patch, have no
 * plane to turn against (the flip rule read the missing patches: a crash).
 * Each vertex goes onto z = 2. */
static void test_faces_without_patches(void)
{
	double xs[3][3] = { { 0, 0, 2.1 }, { 1, 0, 2.05 }, { 0, 1, 1.9 } };
	struct fct_wire w[3] = { { 0, 1, 0, -1 }, { 1, 2, 0, -1 }, { 2, 0, 0, -1 } };
	struct fct_plane pl[1] = { { { 0, 0, -1 }, 2, 3, 0 } };
	struct fct_mesh m;
	wire_mesh(&m, xs, 3, w, 3, pl, 1, 0);
	uint32_t f[3] = { 0, 1, 2 };
	fct_mesh_add_face(&m, f, 3, &err);
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.max_move = HUGE_VAL;
	struct fct_project_stats st;
	CHECK_INT(fct_project_mesh(&m, &par, &st, &err), 0);
	CHECK_INT(st.moved[1], 3);
	CHECK_INT(st.flip_refused, 0);
	for (int i = 0; i < 3; i++) {
		CHECK_NEAR(m.xyz[3 * i], xs[i][0], 0);
		CHECK_NEAR(m.xyz[3 * i + 1], xs[i][1], 0);
		CHECK_NEAR(m.xyz[3 * i + 2], 2, 1e-15);
	}
	fct_mesh_free(&m);
}

int main(void)
{
	test_one_plane();
	test_two_planes();
	test_corner();
	test_near_parallel();
	test_texcoord();
	test_mesh_tent();
	test_along_rays();
	test_bad();
	test_room_noise();
	test_room_orthogonal();
	test_room_depth_scale();
	test_dense_view();
	test_dense_scale();
	test_wire_crease();
	test_wire_tear();
	test_wire_guard();
	test_flip_refused();
	test_ray_reach();
	test_between_parallels();
	test_snap_by_hand();
	test_faces_without_patches();
	CHECK_DONE();
}
