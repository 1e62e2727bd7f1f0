/* test_texmap.c - texture coordinates per corner: two triangles sharing an
 * edge whose corners on it disagree in one vertex and agree in the other;
 * written as face lists they read back exactly, written per vertex the
 * disagreeing vertex (index 0, whose first copy keeps its place) is copied
 * once, the agreeing one is not, and the corners read back the same; a
 * list of the wrong length is refused. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "render/texmap.h"

static void two_triangles(struct fct_mesh *m)
{
	struct fct_err err;
	fct_mesh_init(m);
	fct_mesh_add_vertex(m, 0, 0, 0, &err);
	fct_mesh_add_vertex(m, 1, 0, 0, &err);
	fct_mesh_add_vertex(m, 0, 1, 0, &err);
	fct_mesh_add_vertex(m, 1, 1, 0, &err);
	fct_mesh_add_vertex(m, 5, 5, 5, &err);          /* used by no face */
	static const uint32_t a[3] = { 0, 1, 2 }, b[3] = { 1, 3, 0 };
	fct_mesh_add_face(m, a, 3, &err);
	fct_mesh_add_face(m, b, 3, &err);
	struct fct_prop *c = fct_elem_add_scalar(&m->vertex, "confidence", FCT_FLOAT32, &err);
	for (size_t i = 0; i < m->nv; i++)
		fct_prop_set(c, i, (double)i);
}

static void test_round_trips(void)
{
	/* Vertex 1 agrees between the faces, vertex 0 does not. */
	static const float st[12] = { 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f,
	                              0.3f, 0.4f, 0.7f, 0.8f, 0.9f, 0.25f };
	static const int32_t tn[2] = { 0, 1 };
	struct fct_mesh m;
	struct fct_err err;
	two_triangles(&m);
	float *got;
	int32_t *gtn;
	CHECK(fct_texmap_corners(&m, &got, &gtn, &err) == 0);
	CHECK(got == NULL && gtn == NULL);

	CHECK(fct_texmap_set_corners(&m, st, tn, 1, &err) == 0);
	CHECK(fct_elem_find(&m.face, "texcoord") != NULL);
	CHECK(fct_elem_find(&m.vertex, "s") == NULL);
	CHECK(fct_texmap_corners(&m, &got, &gtn, &err) == 1);
	CHECK(!memcmp(got, st, sizeof st));
	CHECK(gtn[0] == 0 && gtn[1] == 1);
	free(got);
	free(gtn);

	CHECK(fct_texmap_set_corners(&m, st, NULL, 0, &err) == 0);
	CHECK_INT(m.nv, 6);
	CHECK(fct_elem_find(&m.face, "texcoord") == NULL);
	CHECK_INT(m.fvert[5], 5);                       /* vertex 0's copy */
	CHECK_INT(m.fvert[3], 1);                       /* vertex 1 shared */
	CHECK_NEAR(m.xyz[3 * 5], 0, 0);
	CHECK_NEAR(fct_prop_get(fct_elem_find(&m.vertex, "confidence"), 5), 0, 0);
	CHECK_NEAR(fct_prop_get(fct_elem_find(&m.vertex, "s"), 4), 0, 0);
	CHECK(fct_texmap_corners(&m, &got, &gtn, &err) == 1);
	CHECK(!memcmp(got, st, sizeof st));
	CHECK(gtn[0] == 0 && gtn[1] == 1);              /* texnumber kept */
	free(got);
	free(gtn);
	fct_mesh_free(&m);
}

static void test_bad_length(void)
{
	static const float st[12] = { 0 };
	struct fct_mesh m;
	struct fct_err err;
	two_triangles(&m);
	CHECK(fct_texmap_set_corners(&m, st, NULL, 1, &err) == 0);
	struct fct_prop *tc = fct_elem_find(&m.face, "texcoord");
	tc->off[1] = 4;                                 /* face 0: 4 numbers */
	float *got;
	int32_t *gtn;
	CHECK(fct_texmap_corners(&m, &got, &gtn, &err) == -1);
	CHECK(strstr(err.msg, "face 0: texcoord has 4 numbers for 3 corners") != NULL);
	fct_mesh_free(&m);
}

int main(void)
{
	test_round_trips();
	test_bad_length();
	CHECK_DONE();
}
