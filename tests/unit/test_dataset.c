/* test_dataset.c - sequence folders as 7-Scenes, TUM and Redwood lay them out: the
 * frames found, in order, each with its colour image and pose; TUM's
 * association by timestamp (frames without colour or pose left out); the
 * camera a folder's name tells; refusals with where and what. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "io/dataset.h"

static char top[] = "/tmp/facet-dataset.XXXXXX";

static void put(const char *dir, const char *name, const char *text)
{
	char p[512];
	snprintf(p, sizeof p, "%s/%s", dir, name);
	FILE *f = fopen(p, "wb");
	fputs(text, f);
	fclose(f);
}

static const char *sub(const char *name)
{
	static char p[4][512];
	static int slot;
	char *q = p[slot++ % 4];
	snprintf(q, 512, "%s/%s", top, name);
	mkdir(q, 0777);
	return q;
}

static const char *tail(const char *path)
{
	const char *s = strrchr(path, '/');
	return s ? s + 1 : path;
}

static void test_seven_scenes(void)
{
	const char *d = sub("seq-01");
	struct fct_dataset ds;
	struct fct_err err;
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "not a 7-Scenes, TUM or Redwood sequence folder"), "%s", err.msg);
	/* Written out of order: read in the order of the names. */
	put(d, "frame-000010.depth.png", "");
	put(d, "frame-000010.color.jpg", "");
	put(d, "frame-000010.pose.txt", "");
	put(d, "frame-000002.depth.png", "");
	put(d, "frame-000002.color.png", "");
	put(d, "frame-000002.color.jpg", "");
	put(d, "frame-000002.pose.txt", "");
	put(d, "notes.txt", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == 0);
	CHECK_INT(ds.n, 2);
	CHECK_INT(ds.nposes, 2);
	CHECK_STR(ds.layout, "7-Scenes");
	CHECK_STR(ds.camera, "7scenes");
	CHECK_STR(tail(ds.depth[0]), "frame-000002.depth.png");
	CHECK_STR(tail(ds.color[0]), "frame-000002.color.png");   /* PNG before JPEG */
	CHECK_STR(tail(ds.color[1]), "frame-000010.color.jpg");
	CHECK_STR(tail(ds.poses[1]), "frame-000010.pose.txt");
	fct_dataset_free(&ds);
	put(d, "frame-000005.depth.png", "");
	put(d, "frame-000005.pose.txt", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, ": frame-000005 has no colour image"), "%s", err.msg);
	put(d, "frame-000005.color.png", "");
	char p[600];
	snprintf(p, sizeof p, "%s/frame-000010.pose.txt", d);
	unlink(p);
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, ": frame-000010 has no pose (frame-000010.pose.txt)"), "%s", err.msg);
}

static void test_tum(void)
{
	const char *d = sub("rgbd_dataset_freiburg2_desk");
	put(d, "depth.txt", "# depth maps\n# timestamp filename\n"
	    "100.000 depth/100.000.png\n100.100 depth/100.100.png\n100.200 depth/100.200.png\n"
	    "100.300 depth/100.300.png\n");
	/* No colour near 100.200; the colour of 100.100 is the nearer one. */
	put(d, "rgb.txt", "# color images\n100.010 rgb/100.010.png\r\n100.090 rgb/100.090.png\n"
	    "100.105 rgb/100.105.png\n100.310 rgb/100.310.png\n");
	/* No pose near 100.300. */
	put(d, "groundtruth.txt", "# ground truth\n"
	    "99.995 0 0 0 0 0 0 1\n100.099 1 0 0 0 0 0 1\n100.205 2 0 0 0 0 0 1\n");
	struct fct_dataset ds;
	struct fct_err err;
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == 0);
	CHECK_STR(ds.layout, "TUM");
	CHECK_STR(ds.camera, "tum2");
	CHECK_INT(ds.n, 2);
	CHECK_INT(ds.nposes, 1);
	if (ds.n == 2) {
		CHECK_STR(tail(ds.depth[0]), "100.000.png");
		CHECK_STR(tail(ds.color[0]), "100.010.png");
		CHECK_STR(tail(ds.depth[1]), "100.100.png");
		CHECK_STR(tail(ds.color[1]), "100.105.png");
	}
	CHECK_STR(tail(ds.poses[0]), "groundtruth.txt");
	CHECK_NEAR(ds.max_diff, 0.010, 1e-9);
	fct_dataset_free(&ds);
	/* Nothing within 1 ms. */
	CHECK(fct_dataset_read(&ds, d, 0.001, &err) == -1);
	CHECK_MSG(strstr(err.msg, ": no depth frame has a colour image and a pose within 0.001 s"), "%s", err.msg);
	put(d, "rgb.txt", "100.010 rgb/a.png\nnot a line\n");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "rgb.txt:2: expected \"timestamp file\""), "%s", err.msg);
	put(d, "rgb.txt", "100.010\n");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "rgb.txt:1: expected \"timestamp file\""), "%s", err.msg);
	put(d, "rgb.txt", "100.010 rgb/a.png\n");
	put(d, "groundtruth.txt", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "groundtruth.txt: not a TUM trajectory"), "%s", err.msg);
}

static void test_redwood(void)
{
	const char *d = sub("livingroom1");
	char depth[512], colour[512], scene[512];
	snprintf(depth, sizeof depth, "%s", sub("livingroom1/depth"));
	struct fct_dataset ds;
	struct fct_err err;
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "livingroom1: depth/ but no colour images beside it (color/, image/ or rgb/)"),
	          "%s", err.msg);
	snprintf(colour, sizeof colour, "%s", sub("livingroom1/image"));
	/* Paired in the order of the names, whatever they are; other files aside. */
	put(depth, "00010.png", "");
	put(depth, "00002.png", "");
	put(depth, ".hidden.png", "");
	put(depth, "README", "");
	put(colour, "00010.JPG", "");
	put(colour, "00002.jpg", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "livingroom1: no trajectory (trajectory.log, scene/trajectory.log or one .log file)"),
	          "%s", err.msg);
	put(d, "livingroom1-traj.log", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == 0);
	CHECK_STR(ds.layout, "Redwood");
	CHECK_STR(ds.camera, "redwood");
	CHECK(ds.intrinsics == NULL);
	CHECK_INT(ds.n, 2);
	CHECK_INT(ds.nposes, 1);
	if (ds.n == 2) {
		CHECK_STR(tail(ds.depth[0]), "00002.png");
		CHECK_STR(tail(ds.color[0]), "00002.jpg");
		CHECK_STR(tail(ds.depth[1]), "00010.png");
		CHECK_STR(tail(ds.color[1]), "00010.JPG");
	}
	CHECK_STR(tail(ds.poses[0]), "livingroom1-traj.log");
	fct_dataset_free(&ds);
	/* Two .log files: which one is not guessed ... */
	put(d, "odometry.log", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, ": 2 .log files (livingroom1-traj.log, odometry.log, ...): which is the trajectory?"),
	          "%s", err.msg);
	/* ... but Open3D's reconstruction output is, and its intrinsics taken. */
	snprintf(scene, sizeof scene, "%s", sub("livingroom1/scene"));
	put(scene, "trajectory.log", "");
	put(d, "camera_intrinsic.json", "{}");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == 0);
	CHECK(ds.poses && !strcmp(ds.poses[0] + strlen(ds.poses[0]) - 20, "scene/trajectory.log"));
	CHECK(ds.intrinsics && !strcmp(tail(ds.intrinsics), "camera_intrinsic.json"));
	fct_dataset_free(&ds);
	/* A colour image short. */
	put(depth, "00011.png", "");
	CHECK(fct_dataset_read(&ds, d, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, ": 3 depth images in depth/ but 2 colour images in image/"), "%s", err.msg);
}

int main(void)
{
	if (!mkdtemp(top)) {
		perror("mkdtemp");
		return 1;
	}
	test_seven_scenes();
	test_tum();
	test_redwood();
	char cmd[600];
	snprintf(cmd, sizeof cmd, "rm -rf %s", top);
	if (system(cmd) != 0)
		fprintf(stderr, "test_dataset: could not remove %s\n", top);
	CHECK_DONE();
}
