/* test_camera.c - intrinsics files (Open3D JSON, 3x3 K, camera line,
 * Middlebury calib.txt), dataset cameras known by their numbers, poses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "camera.h"
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

int main(void)
{
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	test_files();
	test_known();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	if (system(cmd) != 0)
		fprintf(stderr, "test_camera: could not remove %s\n", dir);
	CHECK_DONE();
}
