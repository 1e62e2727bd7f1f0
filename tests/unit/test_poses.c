/* test_poses.c - trajectory files of every format against hand-computed
 * poses, frames matched to them, refusals, and the real 7-Scenes pose
 * files (when /work/shared/data is there). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/camera.h"
#include "check.h"
#include "io/poses.h"

static char dir[] = "/tmp/facet-poses.XXXXXX";

/* Write text to dir/name; returns the path (static buffer per call slot). */
static const char *file(const char *name, const char *text, size_t len)
{
	static char paths[16][96];
	static int slot;
	char *p = paths[slot++ % 16];
	snprintf(p, 96, "%s/%s", dir, name);
	FILE *f = fopen(p, "wb");
	fwrite(text, 1, len ? len : strlen(text), f);
	fclose(f);
	return p;
}

/* A: 90 degrees about z, t = (1, 2, 3): x -> y.  B: identity, t = (-4, 5, 0.5). */
static const double A[12] = { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3 };
static const double B[12] = { 1, 0, 0, -4, 0, 1, 0, 5, 0, 0, 1, 0.5 };

static int same(const double *p, const double *q, double tol)
{
	for (int k = 0; k < 12; k++)
		if (!(fabs(p[k] - q[k]) <= tol))
			return 0;
	return 1;
}

static void check_two(const char *path, enum fct_traj_format f, double tol)
{
	struct fct_trajectory tr;
	struct fct_err err;
	int rc = fct_trajectory_read(&tr, path, &err);
	CHECK_MSG(rc == 0, "%s: %s", path, err.msg);
	if (rc)
		return;
	CHECK_MSG(tr.format == f, "%s: format %s", path, fct_traj_format_name(tr.format));
	CHECK_INT(tr.n, 2);
	if (tr.n == 2) {
		CHECK_MSG(same(&tr.pose[0], A, tol), "%s: pose 0", path);
		CHECK_MSG(same(&tr.pose[12], B, tol), "%s: pose 1", path);
	}
	CHECK(f == FCT_TRAJ_TUM ? tr.stamp != NULL : tr.stamp == NULL);
	fct_trajectory_free(&tr);
}

static void test_formats(void)
{
	/* tests/data: TUM (the quaternion of 90 degrees about z is (0, 0, sin
	 * 45, cos 45)), Redwood/Open3D .log (ids, then the 4x4), KITTI (12 a
	 * line), stacked 4x4 (a blank line between, CRLF), 16 a line. */
	check_two("tests/data/traj_tum.txt", FCT_TRAJ_TUM, 1e-15);
	check_two("tests/data/traj_redwood.log", FCT_TRAJ_LOG, 0);
	check_two("tests/data/traj_kitti.txt", FCT_TRAJ_KITTI, 0);
	check_two("tests/data/traj_stacked.txt", FCT_TRAJ_STACKED, 0);
	check_two("tests/data/traj_rows16.txt", FCT_TRAJ_STACKED, 0);
	/* One pose: 4x4, 3x4, a pose line, 12 numbers in one line. */
	static const char *const one[] = {
		"0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1\n", "0 -1 0 1\n1 0 0 2\n0 0 1 3\n",
		"comment pose 0 -1 0 1 1 0 0 2 0 0 1 3\n", "0 -1 0 1 1 0 0 2 0 0 1 3",
		"0 -1 0 1 1 0\n0 2 0 0 1 3\n",
	};
	for (size_t i = 0; i < sizeof one / sizeof *one; i++) {
		struct fct_trajectory tr;
		struct fct_err err;
		int rc = fct_trajectory_read(&tr, file("one.txt", one[i], 0), &err);
		CHECK_MSG(rc == 0, "one %zu: %s", i, err.msg);
		if (rc)
			continue;
		CHECK_MSG(tr.format == FCT_TRAJ_POSE && tr.n == 1 && same(tr.pose, A, 0), "one %zu", i);
		fct_trajectory_free(&tr);
	}
}

static void refuse(const char *name, const char *text, size_t len, const char *want)
{
	struct fct_trajectory tr;
	struct fct_err err;
	const char *p = file(name, text, len);
	CHECK_MSG(fct_trajectory_read(&tr, p, &err) == -1, "%s accepted", name);
	CHECK_MSG(strstr(err.msg, want) != NULL, "%s: \"%s\" lacks \"%s\"", name, err.msg, want);
	CHECK_MSG(strchr(err.msg, '\n') == NULL && strchr(err.msg, 1) == NULL, "%s: raw bytes", name);
}

static void test_refuse(void)
{
	refuse("nul.txt", "0 -1 0 1\n1 0\0 0 2\n0 0 1 3\n", 26, "nul.txt:2: binary data (a NUL byte)");
	refuse("mixed.txt", "1 2 3 0 0 0 0 1\n1 2 3 0 0 0 1\n", 0,
	       "mixed.txt:2: 7 numbers where line 1 has 8: not a trajectory");
	refuse("five.txt", "1 2 3 4 5\n", 0, "five.txt: 1 line of 5 numbers: not a pose or trajectory");
	refuse("scaled.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 0\n", 0,
	       "scaled.txt:1: pose: the 3x3 part is not a rotation");
	refuse("quat.txt", "1 0 0 0 0 0 0 2\n", 0, "quat.txt:1: not a unit quaternion (norm 2)");
	refuse("back.txt", "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", 0, "back.txt:2: timestamp 1 before");
	refuse("row.txt", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", 0,
	       "row.txt:1: the last row of a 4x4 pose must be 0 0 0 1");
	refuse("word.txt", "1 0 0 0 0 1 0 0 0 0 1 0\nfoo\x01\x02 bar\n", 0, "word.txt:2: \"foo\\x01\\x02 bar\": not a number");
	refuse("inf.txt", "1 0 0 inf 0 1 0 0 0 0 1 0\n", 0, "inf.txt:1: number 4 is not finite");
	refuse("empty.txt", "# nothing\n\n", 0, "empty.txt: no poses");
	refuse("many.txt", "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17\n", 0, "many.txt:1: more than 16 numbers");
	/* An endless stream of NUL bytes (/dev/zero) ends at the line limit. */
	struct fct_trajectory tr;
	struct fct_err err;
	if (access("/dev/zero", R_OK) == 0) {
		CHECK(fct_trajectory_read(&tr, "/dev/zero", &err) == -1);
		CHECK_MSG(strstr(err.msg, "/dev/zero:1: line longer than") != NULL, "%s", err.msg);
	}
}

static void test_associate(void)
{
	struct fct_trajectory tr;
	struct fct_err err;
	const char *p = file("t.txt", "1 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n1.5 2 0 0 0 0 0 1\n"
	                              "2 3 0 0 0 0 0 1\n", 0);
	CHECK(fct_trajectory_read(&tr, p, &err) == 0);
	/* 1.25 is as near 1 as 1.5: the earlier line, the first of the two at 1. */
	double t[] = { 1.25, 1.26, 2.01, 0.99, 3 };
	size_t idx[5];
	double most = fct_trajectory_associate(idx, &tr, t, 5, 0.3);
	CHECK_INT(idx[0], 0);
	CHECK_INT(idx[1], 2);
	CHECK_INT(idx[2], 3);
	CHECK_INT(idx[3], 0);
	CHECK_INT(idx[4], (size_t)-1);
	CHECK_NEAR(most, 0.25, 1e-15);
	fct_trajectory_associate(idx, &tr, t, 5, 0.02);
	CHECK_INT(idx[0], (size_t)-1);
	CHECK_INT(idx[2], 3);
	fct_trajectory_free(&tr);

	double s;
	size_t k;
	CHECK(fct_path_stamp("rgbd/depth/1305031102.160407.png", &s) && s == 1305031102.160407);
	CHECK(!fct_path_stamp("frame-000050.depth.png", &s));
	CHECK(!fct_path_stamp("view00.depth.pfm", &s));
	CHECK(fct_path_frame_number("seq-01/frame-000050.depth.png", &k) && k == 50);
	CHECK(fct_path_frame_number("depth/000010.png", &k) && k == 10);
	CHECK(!fct_path_frame_number("depth/a.png", &k));
	CHECK(!fct_path_frame_number("99999999999999999999.png", &k));
}

/* fct_frame_poses: rc, and the match and first pose when it succeeds. */
static void frames(const char *const *files, size_t nf, const char *const *fr, size_t n,
                   enum fct_pose_match match, const double *first, const char *want)
{
	double poses[12 * 8];
	struct fct_frame_poses_stats st;
	struct fct_err err;
	int rc = fct_frame_poses(poses, &st, files, nf, fr, n, 0.02, &err);
	if (want) {
		CHECK_MSG(rc == -1 && strstr(err.msg, want), "\"%s\" lacks \"%s\"", rc ? err.msg : "", want);
		return;
	}
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (rc)
		return;
	CHECK_INT(st.match, match);
	CHECK(same(poses, first, 1e-15));
}

static void test_frames(void)
{
	const char *a = file("pa.txt", "0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1\n", 0);
	const char *b = file("pb.txt", "1 0 0 -4 0 1 0 5 0 0 1 0.5\n", 0);
	const char *st = file("st.txt", "0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1\n"
	                                "1 0 0 -4\n0 1 0 5\n0 0 1 0.5\n0 0 0 1\n", 0);
	const char *log = file("traj.log", "0 0 1\n1 0 0 -4\n0 1 0 5\n0 0 1 0.5\n0 0 0 1\n"
	                                   "1 1 2\n1 0 0 -4\n0 1 0 5\n0 0 1 0.5\n0 0 0 1\n"
	                                   "2 2 3\n0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1\n", 0);
	const char *tum = file("gt.txt", "1305031102.1758 1 2 3 0 0 0.70710678118654752 0.70710678118654752\n"
	                                 "1305031102.2 -4 5 0.5 0 0 0 1\n", 0);
	const char *two[] = { a, b }, *ba[] = { b, a }, *one_st[] = { st }, *one_log[] = { log };
	const char *one_tum[] = { tum }, *st_a[] = { st, a };
	const char *f2[] = { "d/x.png", "d/y.png" }, *f3[] = { "x.png", "y.png", "z.png" };
	frames(two, 2, f2, 2, FCT_MATCH_FILES, A, NULL);
	frames(ba, 2, f2, 2, FCT_MATCH_FILES, B, NULL);
	frames(two, 2, f3, 3, 0, NULL, "3 depth frames but 2 pose files");
	frames(st_a, 2, f2, 2, 0, NULL, "st.txt holds 2 poses (stacked 4x4 matrices): with a pose file per frame");
	/* The case: one file holding every pose was "5 depth views but
	 * 1 --poses files". */
	frames(one_st, 1, f2, 2, FCT_MATCH_ORDER, A, NULL);
	frames(one_st, 1, f3, 3, 0, NULL, "3 depth frames but " );
	frames(one_st, 1, f3, 3, 0, NULL, "st.txt holds 2 poses (stacked 4x4 matrices)");
	/* Frame numbers in a longer trajectory. */
	const char *f20[] = { "seq/frame-000002.depth.png", "seq/frame-000000.depth.png" };
	frames(one_log, 1, f20, 2, FCT_MATCH_NUMBER, A, NULL);
	const char *f7[] = { "frame-000007.depth.png" };
	frames(one_log, 1, f7, 1, 0, NULL, "frame-000007.depth.png: frame 7, but");
	frames(one_log, 1, f2, 2, 0, NULL, "2 depth frames but");
	frames(one_log, 1, f2, 2, 0, NULL, "traj.log holds 3 poses (a Redwood .log trajectory), and d/x.png has no frame number");
	/* TUM by timestamp (0.0008 s off), in any order; unnamed in order. */
	const char *ft[] = { "depth/1305031102.2008.png", "depth/1305031102.175.png" };
	frames(one_tum, 1, ft, 2, FCT_MATCH_STAMP, B, NULL);
	frames(one_tum, 1, f2, 2, FCT_MATCH_ORDER, A, NULL);
	frames(one_tum, 1, f3, 3, 0, NULL, "carry no timestamps to match them by");
	const char *far[] = { "depth/1305031105.png" };
	frames(one_tum, 1, far, 1, 0, NULL, "depth/1305031105.png: no pose in");
	const char *mix[] = { "depth/1305031102.2.png", "depth/x.png" };
	frames(one_tum, 1, mix, 2, 0, NULL, "depth/x.png: no timestamp in its name");
}

/* The 7-Scenes redkitchen frames' own pose files, one per frame, against
 * the same numbers stacked in one file and as KITTI lines. */
static void test_7scenes(void)
{
	const char *d = "/work/shared/data/7scenes_redkitchen/frames";
	char names[20][128];
	const char *pf[20], *fr[20];
	for (int i = 0; i < 20; i++) {
		snprintf(names[i], sizeof names[i], "%s/frame-%06d.pose.txt", d, 50 * i);
		pf[i] = names[i];
	}
	if (access(pf[0], R_OK) != 0) {
		fprintf(stderr, "test_poses: %s absent: 7-Scenes cases skipped\n", pf[0]);
		return;
	}
	char depth[20][128];
	for (int i = 0; i < 20; i++) {
		snprintf(depth[i], sizeof depth[i], "%s/frame-%06d.depth.png", d, 50 * i);
		fr[i] = depth[i];
	}
	double *p1 = malloc(20 * 12 * sizeof *p1), *p2 = malloc(20 * 12 * sizeof *p2);
	double *p3 = malloc(20 * 12 * sizeof *p3);
	struct fct_frame_poses_stats st;
	struct fct_err err;
	CHECK_MSG(fct_frame_poses(p1, &st, pf, 20, fr, 20, 0.02, &err) == 0, "%s", err.msg);
	CHECK_INT(st.match, FCT_MATCH_FILES);
	/* frame 50's file, read by hand (camera-to-world, README "verified") */
	CHECK(p1[12 * 1 + 0] == 8.753341399999999828e-01);
	CHECK(p1[12 * 1 + 3] == -4.922181400000000262e-01);
	CHECK(p1[12 * 1 + 11] == 3.674409100000000095e-01);
	/* stacked and KITTI forms of the same numbers */
	char *stacked = malloc(20 * 400), *kitti = malloc(20 * 400);
	size_t ns = 0, nk = 0;
	for (int i = 0; i < 20; i++) {
		FILE *f = fopen(pf[i], "r");
		double v[16];
		for (int k = 0; k < 16; k++)
			CHECK(fscanf(f, "%lf", &v[k]) == 1);
		fclose(f);
		for (int k = 0; k < 16; k++)
			ns += (size_t)sprintf(stacked + ns, "%.17g%c", v[k], k % 4 == 3 ? '\n' : ' ');
		for (int k = 0; k < 12; k++)
			nk += (size_t)sprintf(kitti + nk, "%.17g%c", v[k], k == 11 ? '\n' : ' ');
	}
	const char *sf[] = { file("7s-stacked.txt", stacked, ns) };
	const char *kf[] = { file("7s-kitti.txt", kitti, nk) };
	CHECK_MSG(fct_frame_poses(p2, &st, sf, 1, fr, 20, 0.02, &err) == 0, "%s", err.msg);
	CHECK_INT(st.format, FCT_TRAJ_STACKED);
	CHECK_INT(st.match, FCT_MATCH_ORDER);
	CHECK(memcmp(p1, p2, 20 * 12 * sizeof *p1) == 0);
	CHECK_MSG(fct_frame_poses(p3, &st, kf, 1, fr, 20, 0.02, &err) == 0, "%s", err.msg);
	CHECK_INT(st.format, FCT_TRAJ_KITTI);
	CHECK(memcmp(p1, p3, 20 * 12 * sizeof *p1) == 0);
	/* five of the frames from the 20-pose file: by order they would take
	 * poses 0-4; their names say 0, 50, ... which the file does not hold */
	CHECK(fct_frame_poses(p2, &st, sf, 1, fr, 5, 0.02, &err) == -1);
	CHECK_MSG(strstr(err.msg, "frame-000050.depth.png: frame 50, but") != NULL, "%s", err.msg);
	free(stacked), free(kitti), free(p1), free(p2), free(p3);
}

int main(void)
{
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	test_formats();
	test_refuse();
	test_associate();
	test_frames();
	test_7scenes();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	if (system(cmd) != 0)
		fprintf(stderr, "test_poses: could not remove %s\n", dir);
	CHECK_DONE();
}
