/* test_pointdist - the distances of points to a mesh summed up, on
 * hand-computed cases: points straight above the square [-1,1]^2 (z = 0) at
 * heights 0, 1, 2 and 3, points beside it (to its nearest edge or corner),
 * the same distance four times (no spread), and a mesh without faces. */
#include <math.h>

#include "check.h"
#include "geom/pointdist.h"
#include "square.h"

static void test_above(void)
{
	struct fct_mesh m;
	struct fct_err err;
	struct fct_dist_stats st;
	square(&m, 4, 0);
	/* Heights 0..3 over the square: mean 1.5, variance (2.25 + 0.25 +
	 * 0.25 + 2.25) / 4 = 1.25, rms^2 = (0 + 1 + 4 + 9) / 4 = 3.5. */
	const double p[] = { 0, 0, 0, 0.5, 0.5, 1, -0.25, 0.75, -2, 0.9, -0.9, 3 };
	CHECK(fct_point_distances(&st, p, 4, &m, &err) == 0);
	CHECK_INT(st.count, 4);
	CHECK_NEAR(st.mean, 1.5, 1e-12);
	CHECK_NEAR(st.stdev, sqrt(1.25), 1e-12);
	CHECK_NEAR(st.rms, sqrt(3.5), 1e-12);
	CHECK_NEAR(st.max, 3, 1e-12);
	fct_mesh_free(&m);
}

static void test_beside(void)
{
	struct fct_mesh m;
	struct fct_err err;
	struct fct_dist_stats st;
	square(&m, 2, 0);
	/* (3, 0, 0) is 2 from the edge x = 1; (4, 5, 0) is 5 from the corner
	 * (1, 1) (3-4-5); (1, 1, 2) is 2 above that corner. */
	const double p[] = { 3, 0, 0, 4, 5, 0, 1, 1, 2 };
	CHECK(fct_point_distances(&st, p, 3, &m, &err) == 0);
	CHECK_INT(st.count, 3);
	CHECK_NEAR(st.mean, 3, 1e-12);
	CHECK_NEAR(st.max, 5, 1e-12);
	CHECK_NEAR(st.rms, sqrt((4 + 25 + 4) / 3.0), 1e-12);
	/* The same distance four times (above and below vertices): no spread. */
	const double q[] = { 0, 0, 0.7, 1, 0, -0.7, 0, 1, 0.7, -1, -1, -0.7 };
	CHECK(fct_point_distances(&st, q, 4, &m, &err) == 0);
	CHECK_NEAR(st.stdev, 0, 1e-15);
	CHECK_NEAR(st.mean, 0.7, 1e-15);
	fct_mesh_free(&m);
}

static void test_no_faces(void)
{
	struct fct_mesh m;
	struct fct_err err;
	struct fct_dist_stats st = { 7, 7, 7, 7, 7 };
	fct_mesh_init(&m);
	const double p[] = { 1, 2, 3 };
	CHECK(fct_point_distances(&st, p, 1, &m, &err) == 0);
	CHECK_INT(st.count, 0);
	CHECK(st.mean == 0 && st.stdev == 0 && st.rms == 0 && st.max == 0);
	fct_mesh_free(&m);
}

int main(void)
{
	test_above();
	test_beside();
	test_no_faces();
	CHECK_DONE();
}
