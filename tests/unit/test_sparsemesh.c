/* test_sparsemesh - sparse points with image coordinates to a mesh, by hand:
 * the text and PLY readers (comments and blank lines skipped, the numbers
 * kept exactly, every malformed line refused with its line number, points
 * that are not finite, no points, a PLY without u v, a missing file); and
 * the mesh of a square of four image points around a fifth: its four
 * Delaunay triangles, each facing the camera (clockwise in (u, v)), a
 * repeated image position left unused, s t from the pixel centres, the
 * depth-jump test on either side of its threshold, and the edge-length
 * limit on either side of its. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/predicates.h"
#include "depth/sparsemesh.h"

/* Read pts from the text s, called "pts.txt"; the call's status. */
static int read_text(struct fct_image_points *pts, const char *s, struct fct_err *err)
{
	FILE *f = fmemopen((void *)s, strlen(s), "rb");
	if (!f)
		abort();
	err->msg[0] = 0;
	int rc = fct_image_points_read_stream(pts, f, "pts.txt", err);
	fclose(f);
	return rc;
}

static void test_read(void)
{
	struct fct_image_points pts;
	struct fct_err err;
	CHECK_INT(read_text(&pts, "# u v x y z\n\n  0 0 1 2 3\n\t10.5 -2 4e-1 5 6\n# end\n", &err), 0);
	CHECK_INT(pts.n, 2);
	if (pts.n == 2) {
		CHECK(pts.uv[0] == 0 && pts.uv[1] == 0 && pts.uv[2] == 10.5 && pts.uv[3] == -2);
		CHECK(pts.xyz[0] == 1 && pts.xyz[2] == 3 && pts.xyz[3] == 0.4 && pts.xyz[5] == 6);
	}
	fct_image_points_free(&pts);
	CHECK(pts.n == 0 && pts.uv == NULL && pts.xyz == NULL);

	static const struct {
		const char *text, *msg;
	} bad[] = {
		{ "0 0 1 2 3\n1 2 3 4\n", "pts.txt:2: expected five numbers \"u v x y z\"" },
		{ "0 0 1 2 3 4\n", "pts.txt:1: more than five numbers" },
		{ "0 0 1 2 3x\n", "pts.txt:1: expected five numbers \"u v x y z\"" },
		{ "0,5 0 1 2 3\n", "pts.txt:1: expected five numbers \"u v x y z\"" },
		{ "# nothing\n\n", "pts.txt: no points" },
		{ "", "pts.txt: no points" },
		{ "0 0 1 2 3\n1 1 1e999 2 3\n", "pts.txt: point 1: not finite" },
		{ "0 0 1 2 3\n1 1 1 2 3\nnan 1 1 2 3\n", "pts.txt: point 2: not finite" },
	};
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
		CHECK_INT(read_text(&pts, bad[k].text, &err), -1);
		CHECK_STR(err.msg, bad[k].msg);
		CHECK(pts.n == 0 && pts.uv == NULL);
	}

	/* PLY: u v as vertex properties, in any order and type */
	static const char ply[] = "ply\nformat ascii 1.0\nelement vertex 2\n"
	                          "property float x\nproperty float y\nproperty float z\n"
	                          "property ushort v\nproperty double u\nend_header\n"
	                          "1 2 3 7 0.25\n4 5 6 8 -1.5\n";
	CHECK_INT(read_text(&pts, ply, &err), 0);
	CHECK_INT(pts.n, 2);
	if (pts.n == 2) {
		CHECK(pts.uv[0] == 0.25 && pts.uv[1] == 7 && pts.uv[2] == -1.5 && pts.uv[3] == 8);
		CHECK(pts.xyz[0] == 1 && pts.xyz[4] == 5 && pts.xyz[5] == 6);
	}
	fct_image_points_free(&pts);
	static const char no_u[] = "ply\nformat ascii 1.0\nelement vertex 1\n"
	                           "property float x\nproperty float y\nproperty float z\n"
	                           "property float v\nend_header\n1 2 3 4\n";
	CHECK_INT(read_text(&pts, no_u, &err), -1);
	CHECK_STR(err.msg, "pts.txt: the vertex element needs scalar properties u and v (image coordinates)");
	CHECK_INT(fct_image_points_read_file(&pts, "/nonexistent/pts.txt", &err), -1);
	CHECK_STR(err.msg, "/nonexistent/pts.txt: No such file or directory");
}

/* Image points 0-3 the corners of a 10-pixel square, 4 its centre; every
 * point at depth 1 on its pixel's ray through a pinhole camera (fx = fy =
 * 100, 20 x 20, cx = cy = 5), the centre at depth zc. */
static void square(struct fct_image_points *pts, double zc)
{
	static const double uv[] = { 0, 0, 10, 0, 10, 10, 0, 10, 5, 5 };
	pts->n = 5;
	pts->uv = malloc(sizeof uv);
	pts->xyz = malloc(15 * sizeof *pts->xyz);
	memcpy(pts->uv, uv, sizeof uv);
	for (int i = 0; i < 5; i++) {
		double z = i == 4 ? zc : 1;
		pts->xyz[3 * i] = (uv[2 * i] - 5) / 100 * z;
		pts->xyz[3 * i + 1] = (uv[2 * i + 1] - 5) / 100 * z;
		pts->xyz[3 * i + 2] = z;
	}
}

static const struct fct_camera pinhole = { FCT_CAMERA_PINHOLE, 20, 20, 100, 100, 5, 5, 0, 0 };

/* Faces of m clockwise in the image (facing the camera), each with the
 * centre 4: the count of those that are not. */
static size_t bad_faces(const struct fct_mesh *m, const struct fct_image_points *pts)
{
	size_t bad = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *t = &m->fvert[3 * f];
		bad += !(fct_orient2d(&pts->uv[2 * t[0]], &pts->uv[2 * t[1]], &pts->uv[2 * t[2]]) < 0);
		bad += t[0] != 4 && t[1] != 4 && t[2] != 4;
	}
	return bad;
}

static void test_mesh(void)
{
	struct fct_image_points pts;
	struct fct_mesh m;
	struct fct_err err;
	struct fct_sparse_stats st;
	struct fct_sparse_params p = { 0, INFINITY };   /* no jump test, no edge limit */
	struct fct_camera none = { 0 };
	square(&pts, 1);
	CHECK_INT(fct_sparse_mesh(&m, &pts, &none, &p, &st, &err), 0);
	CHECK_INT(m.nv, 5);
	CHECK_INT(m.nf, 4);
	CHECK_INT(bad_faces(&m, &pts), 0);
	CHECK(m.xyz[3 * 4 + 2] == 1 && m.xyz[3] == 0.05);
	CHECK(fct_elem_find(&m.vertex, "s") == NULL);   /* no camera, no s t */
	CHECK(st.duplicates == 0 && st.jump_faces == 0 && st.long_faces == 0);
	fct_mesh_free(&m);

	/* s t at the pixel centres: (u + 0.5) / 20, 1 - (v + 0.5) / 20 */
	CHECK_INT(fct_sparse_mesh(&m, &pts, &pinhole, &p, NULL, &err), 0);
	const struct fct_prop *s = fct_elem_find(&m.vertex, "s"), *t = fct_elem_find(&m.vertex, "t");
	CHECK(s && t);
	if (s && t) {
		CHECK(fct_prop_get(s, 4) == (float)0.275 && fct_prop_get(t, 4) == (float)0.725);
		CHECK(fct_prop_get(s, 1) == (float)0.525 && fct_prop_get(t, 1) == (float)0.975);
	}
	fct_mesh_free(&m);
	fct_image_points_free(&pts);

	/* The centre 0.2 deeper: each triangle has an edge from it to a corner,
	 * sqrt 50 = 7.07 pixels long, whose depth changes by 0.2 against
	 * max_jump * 0.01 (the pixel angle) * 7.07 * 1: cut at max_jump 2
	 * (0.141), kept at 3 (0.212). */
	square(&pts, 1.2);
	p.max_jump = 2;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &pinhole, &p, &st, &err), 0);
	CHECK_INT(m.nf, 0);
	CHECK_INT(st.jump_faces, 4);
	CHECK_INT(m.nv, 5);
	fct_mesh_free(&m);
	p.max_jump = 3;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &pinhole, &p, &st, &err), 0);
	CHECK_INT(m.nf, 4);
	CHECK_INT(st.jump_faces, 0);
	fct_mesh_free(&m);
	/* without a camera there is no footprint: no jump test */
	p.max_jump = 2;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &none, &p, &st, &err), 0);
	CHECK_INT(m.nf, 4);
	fct_mesh_free(&m);
	fct_image_points_free(&pts);

	/* Edge lengths at depth 1: corner to corner 0.1, centre to corner
	 * 0.0707; every triangle has a side of the square. */
	square(&pts, 1);
	p.max_jump = 0;
	p.max_edge = 0.099;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &none, &p, &st, &err), 0);
	CHECK_INT(m.nf, 0);
	CHECK_INT(st.long_faces, 4);
	fct_mesh_free(&m);
	p.max_edge = 0.101;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &none, &p, &st, &err), 0);
	CHECK_INT(m.nf, 4);
	CHECK_INT(st.long_faces, 0);
	fct_mesh_free(&m);
	fct_image_points_free(&pts);

	/* A sixth point at the centre's image position: counted, unused. */
	square(&pts, 1);
	pts.n = 6;
	pts.uv = realloc(pts.uv, 12 * sizeof *pts.uv);
	pts.xyz = realloc(pts.xyz, 18 * sizeof *pts.xyz);
	pts.uv[10] = 5, pts.uv[11] = 5;
	pts.xyz[15] = 9, pts.xyz[16] = 9, pts.xyz[17] = 9;
	p.max_edge = INFINITY;
	CHECK_INT(fct_sparse_mesh(&m, &pts, &none, &p, &st, &err), 0);
	CHECK_INT(st.duplicates, 1);
	CHECK_INT(m.nv, 6);
	CHECK_INT(m.nf, 4);
	CHECK_INT(bad_faces(&m, &pts), 0);
	size_t uses5 = 0;
	for (size_t k = 0; k < 3 * m.nf; k++)
		uses5 += m.fvert[k] == 5;
	CHECK_INT(uses5, 0);
	fct_mesh_free(&m);
	fct_image_points_free(&pts);
}

int main(void)
{
	test_read();
	test_mesh();
	CHECK_DONE();
}
