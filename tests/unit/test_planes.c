/* test_planes.c - the patch property and plane element round trip, and
 * malformed ones are refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/planes.h"

static struct fct_err err;

int main(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	uint32_t tri[3] = { 0, 1, 2 };
	for (int i = 0; i < 3; i++)
		fct_mesh_add_vertex(&m, i == 1, i == 2, 0, &err);
	fct_mesh_add_face(&m, tri, 3, &err);
	fct_mesh_add_face(&m, tri, 3, &err);

	struct fct_plane in[2] = { { { 0, 0, 1 }, -2, 7, 0.25 }, { { 0.6, 0.8, 0 }, 1.5, 3, 0 } }, *out;
	size_t n;
	CHECK_INT(fct_planes_get(&m, &out, &n, &err), 0);
	CHECK(out == NULL && n == 0);
	CHECK_INT(fct_planes_set(&m, in, 2, &err), 0);
	CHECK_INT(fct_planes_set(&m, in, 2, &err), 0);   /* replaces, not appends */
	CHECK_INT(m.nelems, 1);
	CHECK_INT(fct_planes_get(&m, &out, &n, &err), 0);
	CHECK_INT(n, 2);
	CHECK_NEAR(out[1].n[1], 0.8, 0);
	CHECK_NEAR(out[0].d, -2, 0);
	CHECK_INT(out[0].count, 7);
	CHECK_NEAR(out[0].rms, 0.25, 0);
	double p[3] = { 1, 1, 3 };
	CHECK_NEAR(fct_plane_distance(&out[0], p), 1, 0);
	free(out);

	int32_t lab[2] = { 1, -1 }, *got;
	int present;
	CHECK_INT(fct_patches_get(&m, &got, &present, 2, &err), 0);
	CHECK(!present && !got);
	CHECK_INT(fct_patches_set(&m, lab, &err), 0);
	CHECK_INT(fct_patches_get(&m, &got, &present, 2, &err), 0);
	CHECK(present && got && got[0] == 1 && got[1] == -1);
	free(got);
	/* A label past the planes is refused. */
	CHECK_INT(fct_patches_get(&m, &got, &present, 1, &err), -1);
	CHECK(strstr(err.msg, "face 0: patch 1") != NULL);
	/* A plane with a normal that is not unit is refused. */
	in[1].n[0] = 0.5;
	CHECK_INT(fct_planes_set(&m, in, 2, &err), 0);
	CHECK_INT(fct_planes_get(&m, &out, &n, &err), -1);
	CHECK(strstr(err.msg, "element plane 1") != NULL);
	/* A count that no long holds (NaN, 1e300, negative, fractional) is
	 * refused before the cast, not cast. */
	in[1].n[0] = 0.6;
	CHECK_INT(fct_planes_set(&m, in, 2, &err), 0);
	const double bad[4] = { NAN, 1e300, -1, 2.5 };
	for (int k = 0; k < 4; k++) {
		struct fct_elem *e = fct_mesh_find_elem(&m, "plane");
		struct fct_prop *c = fct_elem_add_scalar(e, "count", FCT_FLOAT64, &err);
		fct_prop_set(c, 1, bad[k]);
		CHECK_INT(fct_planes_get(&m, &out, &n, &err), -1);
		CHECK_MSG(strstr(err.msg, "element plane 1: count ") != NULL, "%s", err.msg);
	}
	fct_mesh_free(&m);
	CHECK_DONE();
}
