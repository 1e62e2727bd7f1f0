/* test_camera - the inverse of a pose (fct_pose_invert): the transpose for
 * a rotation, bit for bit, and the matrix's own inverse for a pose whose R
 * has drifted off a rotation, as 7-Scenes' do (R^T R - I about 1e-4), so
 * that a view's points go back onto their pixels.  The fixture of that
 * bug: a 7-Scenes depth image's mesh, moved by its pose and back by the
 * transpose, missed its pixels by 0.01 px, and fusion took it for a mesh
 * of no grid (a raster at 2 samples per pixel: 4x the instructions). */
#include <math.h>

#include "camera.h"
#include "check.h"

/* 7-Scenes redkitchen frame-000000.pose.txt, as written. */
static const double drifted[12] = {
	9.093128999999999795e-01, 2.726222899999999894e-01, -3.142243299999999961e-01, -3.404563400000000239e-01,
	-2.724861800000000223e-01, 9.610497999999999541e-01, 4.527962600000000337e-02, 1.646981800000000065e-02,
	3.143392500000000145e-01, 4.444964600000000238e-02, 9.482093499999999509e-01, 2.965691699999999931e-01,
};

static void round_trip(const double pose[12], double tol)
{
	double inv[12];
	fct_pose_invert(pose, inv);
	static const double pts[3][3] = { { 0.3, -0.2, 1.5 }, { -1.7, 0.9, 3.9 }, { 2.5, 1.8, 0.7 } };
	for (int i = 0; i < 3; i++) {
		double w[3], b[3];
		fct_pose_apply(pose, pts[i], w);
		fct_pose_apply(inv, w, b);
		for (int k = 0; k < 3; k++)
			CHECK_NEAR(b[k], pts[i][k], tol);
	}
}

static void test_invert(void)
{
	/* A rotation (about z by 0.3 rad, then x by -1.2) and a translation:
	 * the inverse is [R^T | -R^T t], exactly as those products give it. */
	double cz = cos(0.3), sz = sin(0.3), cx = cos(-1.2), sx = sin(-1.2);
	double rigid[12] = { cz, -sz, 0, 1.25, cx * sz, cx * cz, -sx, -0.5, sx * sz, sx * cz, cx, 2.0 };
	double inv[12];
	fct_pose_invert(rigid, inv);
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			CHECK(inv[4 * i + j] == rigid[4 * j + i]);
		CHECK(inv[4 * i + 3] == -(rigid[i] * rigid[3] + rigid[4 + i] * rigid[7] + rigid[8 + i] * rigid[11]));
	}
	round_trip(rigid, 1e-15);
	/* Drifted: the transpose would miss by about 1e-4 of the distance
	 * (0.4 mm at 4 m); the inverse comes back to rounding. */
	round_trip(drifted, 1e-14);
	double t[12];
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			t[4 * i + j] = drifted[4 * j + i];
		t[4 * i + 3] = -(drifted[i] * drifted[3] + drifted[4 + i] * drifted[7] + drifted[8 + i] * drifted[11]);
	}
	double p[3] = { -1.7, 0.9, 3.9 }, w[3], b[3];
	fct_pose_apply(drifted, p, w);
	fct_pose_apply(t, w, b);
	CHECK(fabs(b[2] - p[2]) > 1e-4);   /* what the transpose made of it */
}

int main(void)
{
	test_invert();
	CHECK_DONE();
}
