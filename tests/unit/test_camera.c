/* test_camera.c - intrinsics files (Open3D JSON, 3x3 K, camera line,
 * Middlebury calib.txt), dataset cameras known by their numbers, and the
 * inverse of a pose (fct_pose_invert): the transpose for a rotation, bit
 * for bit, and the matrix's own inverse for a pose whose R has drifted off
 * a rotation, as 7-Scenes' do (R^T R - I about 1e-4), so that a view's
 * points go back onto their pixels.  The fixture of that bug: a 7-Scenes
 * depth image's mesh, moved by its pose and back by the transpose, missed
 * its pixels by 0.01 px, and fusion took it for a mesh of no grid (a
 * raster at 2 samples per pixel: 4x the instructions). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/camera.h"
#include "check.h"

static char dir[] = "/tmp/facet-camera.XXXXXX";

static const char *file(const char *name, const char *text)
{
	static char path[96];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	FILE *f = fopen(path, "w");
	fputs(text, f);
	fclose(f);
	return path;
}

static void test_files(void)
{
	struct fct_camera c;
	struct fct_stereo st;
	struct fct_err err;
	/* Open3D stores K column by column. */
	CHECK(fct_camera_read_stereo(&c, &st, file("o3d.json", "{\"width\": 640, \"height\": 480, "
	      "\"intrinsic_matrix\": [525.0, 0.0, 0.0, 0.0, 526.0, 0.0, 319.5, 239.5, 1.0]}"), &err) == 0);
	CHECK(c.kind == FCT_CAMERA_PINHOLE && c.width == 640 && c.fx == 525 && c.fy == 526 &&
	      c.cx == 319.5 && c.cy == 239.5);
	CHECK(st.baseline == 0 && st.doffs == 0);
	/* 7-Scenes' camera-intrinsics.txt */
	CHECK(fct_camera_read_file(file("k.txt", "5.85e+02 0 3.2e+02\n0 5.85e+02 2.4e+02\n0 0 1\n"), &c,
	                           &err) == 0);
	CHECK(c.fx == 585 && c.cy == 240 && c.width == 0);
	/* Middlebury 2014 (Motorcycle's numbers): baseline in mm. */
	int rc = fct_camera_read_stereo(&c, &st, file("calib.txt",
	         "cam0=[3979.911 0 1244.772; 0 3979.911 1019.507; 0 0 1]\n"
	         "cam1=[3979.911 0 1369.115; 0 3979.911 1019.507; 0 0 1]\n"
	         "doffs=124.343\nbaseline=193.001\nwidth=2964\nheight=1988\nndisp=270\n"
	         "isint=0\nvmin=23\nvmax=245\ndyavg=0\ndymax=0\n"), &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	CHECK(c.kind == FCT_CAMERA_PINHOLE && c.width == 2964 && c.height == 1988);
	CHECK(c.fx == 3979.911 && c.fy == 3979.911 && c.cx == 1244.772 && c.cy == 1019.507);
	CHECK_NEAR(st.baseline, 0.193001, 1e-15);
	CHECK(st.doffs == 124.343);
	CHECK(fct_camera_read_stereo(&c, &st, file("bad.txt", "cam0=[1 0 1; 0 1 1]\ndoffs=1\n"
	                                          "baseline=1\nwidth=2\nheight=2\n"), &err) == -1);
	CHECK_MSG(strstr(err.msg, "cam0: expected [fx 0 cx; 0 fy cy; 0 0 1]") != NULL, "%s", err.msg);
	CHECK(fct_camera_read_stereo(&c, &st, file("nob.txt", "cam0=[1 0 1; 0 1 1; 0 0 1]\n"), &err) == -1);
	CHECK_MSG(strstr(err.msg, "needs cam0, width, height, doffs and baseline") != NULL, "%s", err.msg);
}

static void test_known(void)
{
	struct fct_camera c;
	double scale = 0;
	CHECK(fct_camera_named("tum3", &c, &scale) == 0 && scale == 5000);
	/* the same numbers typed as -K (no size yet) */
	struct fct_camera k = { FCT_CAMERA_PINHOLE, 0, 0, 535.4, 539.2, 320.1, 247.6, 0, 0 };
	CHECK_STR(fct_camera_known(&k, 1000, &scale), "tum3");
	CHECK(scale == 5000);
	/* 525 / 319.5 is TUM's default (5000) and Redwood's, Kinect's (1000):
	 * the one whose scale is not the one in use */
	struct fct_camera d = { FCT_CAMERA_PINHOLE, 640, 480, 525, 525, 319.5, 239.5, 0, 0 };
	CHECK_STR(fct_camera_known(&d, 1000, &scale), "tum");
	CHECK(scale == 5000);
	CHECK_STR(fct_camera_known(&d, 5000, &scale), "redwood");
	CHECK(scale == 1000);
	d.width = 1280;
	CHECK(fct_camera_known(&d, 1000, NULL) == NULL);
	struct fct_camera far = { FCT_CAMERA_PINHOLE, 640, 480, 600, 600, 319.5, 239.5, 0, 0 };
	CHECK(fct_camera_known(&far, 1000, NULL) == NULL);
}

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
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	test_files();
	test_known();
	test_invert();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	if (system(cmd) != 0)
		fprintf(stderr, "test_camera: could not remove %s\n", dir);
	CHECK_DONE();
}
