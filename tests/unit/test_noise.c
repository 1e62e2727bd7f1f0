/* test_noise - the sensor noise models (noise.h): sigma of every model at a
 * few depths against values worked out by hand, the kinect model's depth
 * steps against ICL-NUIM's d = 35130 / z (z in cm), parse errors, the text
 * form read back, the header comment; the estimate from the data against
 * the noise mkscene's room was given. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "depth/depthmesh.h"
#include "io/header.h"
#include "io/noise.h"
#include "noisy_view.h"

static struct fct_noise parsed(const char *text)
{
	struct fct_noise nz;
	struct fct_err err;
	int rc = fct_noise_parse(&nz, text, &err);
	CHECK_MSG(rc == 0, "parse \"%s\": %s", text, rc ? err.msg : "");
	return nz;
}

/* Hand-computed: kinect with F B = 585 * 0.075 = 43.875 px m, SD 0.051 px,
 * STEP 1/8 px: g = 0.051 z^2 / 43.875, q = z^2 / (8 * 43.875),
 * sigma = sqrt(g^2 + q^2 / 12), about 1.425e-3 z^2. */
static void test_sigma(void)
{
	struct fct_noise k = parsed("kinect");
	CHECK_INT(k.model, FCT_NOISE_KINECT);
	CHECK_NEAR(k.fb, 43.875, 1e-12);
	CHECK_NEAR(fct_noise_sigma(&k, 1), 0.0014239239095239274, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&k, 2), 0.00569569563809571, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&k, 3), 0.012815315185715347, 1e-15);
	CHECK_NEAR(fct_noise_sigma_gaussian(&k, 2), 0.004649572649572649, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&k, 2) / 4, 1.425e-3, 2e-6);
	/* With the depth's 1 mm encoding: + 1e-6 / 12 under the root. */
	struct fct_noise ku = parsed("kinect 585 0.075 0.051 0.125 unit 0.001");
	CHECK_NEAR(fct_noise_sigma(&ku, 1), 0.0014528911292479004, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&ku, 2), 0.00570300641198621, 1e-15);
	/* Without quantisation, the Gaussian part alone: 4 * 0.1 / 43.875. */
	struct fct_noise kq = parsed("kinect:585,0.075,0.1,0");
	CHECK_NEAR(fct_noise_sigma(&kq, 2), 0.4 / 43.875, 1e-15);
	CHECK_NEAR(fct_noise_step(&kq, 2), 0, 0);

	struct fct_noise t = parsed("tof");
	CHECK_NEAR(fct_noise_sigma(&t, 1), 0.0012, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&t, 3), 0.0028, 1e-15);
	struct fct_noise tu = parsed("tof:0.0004,0.0008 unit 0.001");
	CHECK_NEAR(fct_noise_sigma(&tu, 3), 0.0028148416178061125, 1e-15);
	CHECK_NEAR(fct_noise_step(&tu, 3), 0.001, 0);

	struct fct_noise p = parsed("poly:0.001,0.002,0.003");
	CHECK_NEAR(fct_noise_sigma(&p, 0), 0.001, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&p, 2), 0.017, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&p, 4), 0.057, 1e-15);

	/* Stereo: 25 * 0.2 / 100 at 5 m; doffs changes the disparity, not the
	 * derivative of depth by it. */
	struct fct_noise s = parsed("stereo:100,0.2,130.5");
	CHECK_NEAR(s.doffs, 130.5, 0);
	CHECK_NEAR(fct_noise_sigma(&s, 5), 0.05, 1e-15);
	CHECK_NEAR(fct_noise_sigma(&s, 1), 0.002, 1e-15);

	struct fct_noise n = parsed("none");
	CHECK_NEAR(fct_noise_sigma(&n, 4), 4e-6, 1e-20);
	CHECK_NEAR(fct_noise_step(&n, 4), 0, 0);
	struct fct_noise e = parsed("exact unit 0.0002");
	CHECK_INT(e.model, FCT_NOISE_NONE);
	CHECK_NEAR(fct_noise_sigma(&e, 1), sqrt(1e-12 + 4e-8 / 12), 1e-18);

	struct fct_noise u;
	memset(&u, 0, sizeof u);
	CHECK_NEAR(fct_noise_sigma(&u, 2), 0, 0);
}

/* ICL-NUIM (Handa et al. 2014) reports depth 35130 / k cm for integers k:
 * neighbouring levels about z are 35130 / k - 35130 / (k + 1) apart, which
 * the kinect model's step z^2 STEP / (F B) gives to first order (within
 * 1% up to 3 m) with the B that fct_noise_named gives ICL-NUIM and with
 * the defaults. */
static void test_steps(void)
{
	struct fct_noise icl, def;
	CHECK_INT(fct_noise_named("icl-nuim", &icl), 0);
	fct_noise_kinect(&def);
	for (int z = 1; z <= 3; z++) {
		double k = floor(35130.0 / (100 * z));
		double level_step = (35130 / k - 35130 / (k + 1)) / 100;
		CHECK_MSG(fabs(fct_noise_step(&icl, z) / level_step - 1) < 0.01, "z %d: %g vs %g", z,
		          fct_noise_step(&icl, z), level_step);
		CHECK_MSG(fabs(fct_noise_step(&def, z) / level_step - 1) < 0.01, "z %d: %g vs %g", z,
		          fct_noise_step(&def, z), level_step);
	}
	/* At 2 m: 11.4 mm (the ICL-NUIM levels 2.0074 and 1.9960 m). */
	CHECK_NEAR(fct_noise_step(&def, 2), 0.011396011396011397, 1e-15);

	/* Every dataset name gives kinect; 7-Scenes' measured level spacing. */
	struct fct_noise k7;
	CHECK_INT(fct_noise_named("7scenes", &k7), 0);
	CHECK_INT(k7.model, FCT_NOISE_KINECT);
	CHECK_NEAR(8 * k7.fb, 345.5, 0.2);
	const char *names[] = {"tum", "tum1", "tum2", "tum3", "redwood", "primesense", "kinect"};
	for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
		struct fct_noise x;
		CHECK_INT(fct_noise_named(names[i], &x), 0);
		CHECK_INT(x.model, FCT_NOISE_KINECT);
	}
	CHECK_INT(fct_noise_named("bogus", &k7), -1);
}

static void expect_error(const char *text, const char *msg)
{
	struct fct_noise nz;
	struct fct_err err;
	int rc = fct_noise_parse(&nz, text, &err);
	CHECK_MSG(rc == -1, "\"%s\" parsed", text);
	if (rc == -1)
		CHECK_MSG(!strcmp(err.msg, msg), "\"%s\": \"%s\", expected \"%s\"", text, err.msg, msg);
}

static void test_parse_errors(void)
{
	expect_error("", "noise: \"\" is not a model (none kinect tof poly stereo)");
	expect_error("gaussian:0.01", "noise: \"gaussian\" is not a model (none kinect tof poly stereo)");
	expect_error("kinectx", "noise: \"kinectx\" is not a model (none kinect tof poly stereo)");
	expect_error("poly:1,2", "noise: expected poly:A,B,C");
	expect_error("poly:1,2,3,4", "noise: expected poly:A,B,C");
	expect_error("poly:0,0,0", "noise poly: A, B and C must be at least 0, not all 0");
	expect_error("poly:1,-2,3", "noise poly: A, B and C must be at least 0, not all 0");
	expect_error("poly:1,2,x", "noise: expected poly:A,B,C");
	expect_error("poly:1,2,3,x", "noise: expected poly:A,B,C, then optionally \"unit U\"");
	expect_error("poly:1,2,3e", "noise: expected poly:A,B,C");
	expect_error("poly:1,2,nan", "noise: expected poly:A,B,C");
	expect_error("kinect:1,2,3,4,5", "noise: expected kinect[:F,B[,SD[,STEP]]]");
	expect_error("kinect:0,0.075", "noise kinect: F and B must be positive");
	expect_error("kinect:585,0.075,-1", "noise kinect: SD and STEP must be at least 0");
	expect_error("stereo:100", "noise: expected stereo:FB,SD[,DOFFS]");
	expect_error("stereo:100,0", "noise stereo: FB and SD must be positive");
	expect_error("tof:0,0", "noise tof: A and B must be at least 0, not both 0");
	expect_error("none:1", "noise: expected none");
	expect_error("none unit", "noise: expected none, then optionally \"unit U\"");
	expect_error("none unit -1", "noise: unit must be in [0, 1000) metres");
	expect_error("none unit 0.001 0.002", "noise: expected none, then optionally \"unit U\"");
	expect_error("tof units 1", "noise: expected tof[:A,B], then optionally \"unit U\"");
}

/* A --noise argument names a model, or a file holding one. */
static void test_names_model(void)
{
	CHECK(fct_noise_names_model("kinect"));
	CHECK(fct_noise_names_model("kinect:585,0.075"));
	CHECK(fct_noise_names_model("poly 0 0 0.0012"));
	CHECK(fct_noise_names_model("none"));
	CHECK(!fct_noise_names_model("kinectx"));
	CHECK(!fct_noise_names_model("view00.noise"));
	CHECK(!fct_noise_names_model("dir/kinect"));
	CHECK(!fct_noise_names_model(""));
}

/* The header form reads back to the same model, for every model, and the
 * command-line and header spellings agree. */
static void test_round_trip(void)
{
	const char *specs[] = {
		"none", "none unit 0.001", "kinect", "kinect:580,0.0738", "kinect:585,0.075,0.05,0.125 unit 0.0002",
		"tof", "tof:0.01,0.002", "poly:0.0012,0,0.0019", "stereo:3997.684,0.25,131.111 unit 0.5",
	};
	for (size_t i = 0; i < sizeof specs / sizeof *specs; i++) {
		struct fct_noise a = parsed(specs[i]), b;
		char text[256];
		fct_noise_format(&a, text, sizeof text);
		b = parsed(text);
		CHECK_MSG(!memcmp(&a, &b, sizeof a), "\"%s\" -> \"%s\" reads back differently", specs[i], text);
		for (double z = 0.5; z < 6; z += 0.5)
			CHECK(fct_noise_sigma(&a, z) == fct_noise_sigma(&b, z));
	}
	char text[256];
	struct fct_noise k = parsed("kinect:585,0.0738");
	k.unit = 0.001;
	fct_noise_format(&k, text, sizeof text);
	CHECK_STR(text, "kinect 585 0.0738 0.051 0.125 unit 0.001");
	struct fct_noise unknown;
	memset(&unknown, 0, sizeof unknown);
	fct_noise_format(&unknown, text, sizeof text);
	CHECK_STR(text, "");

	/* On a mesh: set, read back, replace, remove; a malformed comment. */
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	struct fct_noise got;
	CHECK_INT(fct_header_noise(&m, &got, &err), 0);
	CHECK_INT(got.model, FCT_NOISE_UNKNOWN);
	CHECK_INT(fct_header_set_noise(&m, &k, &err), 0);
	CHECK_STR(m.comments[0].text, "noise kinect 585 0.0738 0.051 0.125 unit 0.001");
	CHECK_INT(fct_header_noise(&m, &got, &err), 1);
	CHECK(!memcmp(&got, &k, sizeof k));
	struct fct_noise t = parsed("tof");
	CHECK_INT(fct_header_set_noise(&m, &t, &err), 0);
	CHECK_INT(m.ncomments, 1);
	CHECK_STR(m.comments[0].text, "noise tof 0.0004 0.0008");
	CHECK_INT(fct_header_set_noise(&m, &unknown, &err), 0);
	CHECK_INT(m.ncomments, 0);
	CHECK_INT(fct_mesh_add_comment(&m, "noise poly 1", 0, &err), 0);
	CHECK_INT(fct_header_noise(&m, &got, &err), -1);
	CHECK_STR(err.msg, "comment: noise: expected poly:A,B,C");
	fct_mesh_free(&m);
}

static int compare_float(const void *a, const void *b)
{
	float x = *(const float *)a, y = *(const float *)b;
	return (x > y) - (x < y);
}

/* The median of v[0..n) (sorted in place). */
static double median_float(float *v, size_t n)
{
	qsort(v, n, sizeof *v, compare_float);
	return v[(n - 1) / 2];
}

/* View 0 of mkscene's room (640x480) with sensor's noise, meshed as dm2mesh
 * does with that model (the true sigma of each vertex), the camera and
 * pose in the header; then the estimate from the mesh without its sigma:
 * the law (p), the one figure against the median true sigma within 15%,
 * each vertex's estimate against its true sigma (median ratio within 15%).
 * Quantised depth (kinect) comes in plateaus whose one-ring residuals are
 * 0; the estimate's scale is above them. */
static void check_estimate(const struct fct_scene *s, const char *model, double jitter, int want_p)
{
	struct fct_noise sensor = parsed(model);
	struct fct_camera cam;
	memset(&cam, 0, sizeof cam);
	cam.kind = FCT_CAMERA_PINHOLE;
	cam.width = 640, cam.height = 480;
	cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5;
	double pose[12], *sampled;
	fct_scene_view_pose(s, 0, 1, pose);
	struct fct_image img;
	noisy_view(s, &cam, pose, &sensor, jitter, &sampled, &img);
	struct fct_depth_params p;
	fct_depth_params_default(&p);
	p.noise = sensor;
	struct fct_mesh m;
	struct fct_err err;
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), 0);
	for (size_t v = 0; v < m.nv; v++)
		fct_pose_apply(pose, m.xyz + 3 * v, m.xyz + 3 * v);
	CHECK_INT(fct_header_set_camera(&m, &cam, &err), 0);
	CHECK_INT(fct_header_set_pose(&m, pose, &err), 0);
	const struct fct_prop *ps = fct_elem_find(&m.vertex, "sigma");
	float *truth = malloc(m.nv * sizeof *truth), *est = malloc(m.nv * sizeof *est);
	float *ratio = malloc(m.nv * sizeof *ratio);
	if (!ps || !truth || !est || !ratio)
		abort();
	memcpy(truth, ps->data, m.nv * sizeof *truth);
	fct_elem_remove(&m.vertex, "sigma");

	struct fct_noise_fit fit;
	CHECK_INT(fct_noise_fit(&fit, &m, &err), 0);
	CHECK_INT(fit.camera, 1);
	CHECK_MSG(fit.p == want_p, "%s: sigma grows as z^%d", model, fit.p);
	CHECK_MSG(fit.seeds > 3500, "%s: %zu seeds", model, fit.seeds);
	CHECK_INT(fct_noise_estimate_vertices(est, &m, &err), 0);
	for (size_t v = 0; v < m.nv; v++)
		ratio[v] = est[v] / truth[v];
	double r = median_float(ratio, m.nv), t = median_float(truth, m.nv);
	CHECK_MSG(fabs(fit.sigma / t - 1) < 0.15, "%s: estimate %g, true median %g", model, fit.sigma, t);
	CHECK_MSG(fabs(r - 1) < 0.15, "%s: vertices' estimates %g of the truth", model, r);
	double one;
	CHECK_INT(fct_noise_estimate(&one, &m, &err), 0);
	CHECK(one == fit.sigma);

	/* Without the camera: one figure along the normals, smaller than along
	 * the rays by the cosines of the view's incidence (here 0.66). */
	CHECK_INT(fct_header_set_camera(&m, &(struct fct_camera){FCT_CAMERA_NONE, 0, 0, 0, 0, 0, 0, 0, 0}, &err), 0);
	CHECK_INT(fct_noise_fit(&fit, &m, &err), 0);
	CHECK(fit.camera == 0 && fit.p == 0 && fit.c == fit.sigma);
	if (sensor.model == FCT_NOISE_POLY)
		CHECK_MSG(fit.sigma > 0.5 * t && fit.sigma < t, "%s without camera: %g, true %g", model, fit.sigma, t);
	fct_mesh_free(&m);
	fct_image_free(&img);
	free(sampled);
	free(truth);
	free(est);
	free(ratio);
}

static void test_estimate(void)
{
	struct fct_scene s;
	struct fct_err err;
	CHECK_INT(fct_scene_build(&s, "room", &err), 0);
	check_estimate(&s, "poly:0.01,0,0", 0, 0);
	check_estimate(&s, "kinect", 0.5, 2);
	fct_scene_free(&s);

	/* Too little to estimate from: 12 faces of a cube. */
	struct fct_mesh m;
	fct_mesh_init(&m);
	for (int i = 0; i < 8; i++)
		fct_mesh_add_vertex(&m, i & 1, (i >> 1) & 1, i >> 2, &err);
	static const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
	for (int f = 0; f < 6; f++) {
		uint32_t t1[3] = {q[f][0], q[f][1], q[f][2]}, t2[3] = {q[f][0], q[f][2], q[f][3]};
		fct_mesh_add_face(&m, t1, 3, &err);
		fct_mesh_add_face(&m, t2, 3, &err);
	}
	double sigma = 1;
	CHECK_INT(fct_noise_estimate(&sigma, &m, &err), -1);
	CHECK_STR(err.msg, "noise estimate: 0 neighbourhoods with a plane, 20 needed");
	CHECK(sigma == 0);
	fct_mesh_free(&m);
}

int main(void)
{
	test_sigma();
	test_steps();
	test_parse_errors();
	test_names_model();
	test_round_trip();
	test_estimate();
	CHECK_DONE();
}
