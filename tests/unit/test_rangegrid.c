/* rangegrid: a hand-made 3x3 range grid meshed into the expected triangles
 * with its vertex properties and comments carried, and a .conf pose (the
 * quaternion applied conjugated) moving a known point to its hand-computed
 * place. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/camera.h"
#include "check.h"
#include "geom/geom.h"
#include "io/meshio.h"
#include "depth/rangegrid.h"

static int read_mem(struct fct_mesh *m, const char *text, struct fct_err *err)
{
	FILE *f = fmemopen((void *)text, strlen(text), "rb");
	int rc = fct_mesh_read_stream(m, f, "mem", NULL, NULL, err);
	fclose(f);
	return rc;
}

/* Cells (col i, row j), 1 mm apart, on the plane z = -0.5 facing the
 * scanner at +z; the centre cell (1, 1) has no data.  The vertex element
 * lists the cells in reverse order with a confidence of 0.1 * cell, plus a
 * vertex no cell uses (index 8); a second element rides along. */
static const char grid3[] =
	"ply\n"
	"format ascii 1.0\n"
	"comment made by hand\n"
	"obj_info num_cols 3\n"
	"obj_info num_rows 3\n"
	"element vertex 9\n"
	"property float x\n"
	"property float y\n"
	"property float z\n"
	"property float confidence\n"
	"element range_grid 9\n"
	"property list uchar int vertex_indices\n"
	"element extra 1\n"
	"property int k\n"
	"end_header\n"
	"0.002 -0.002 -0.5 0.8\n"   /* vertex 0: cell 8 (2, 2) */
	"0.001 -0.002 -0.5 0.7\n"   /* vertex 1: cell 7 (1, 2) */
	"0.000 -0.002 -0.5 0.6\n"   /* vertex 2: cell 6 (0, 2) */
	"0.002 -0.001 -0.5 0.5\n"   /* vertex 3: cell 5 (2, 1) */
	"0.000 -0.001 -0.5 0.3\n"   /* vertex 4: cell 3 (0, 1) */
	"0.002 0.000 -0.5 0.2\n"    /* vertex 5: cell 2 (2, 0) */
	"0.001 0.000 -0.5 0.1\n"    /* vertex 6: cell 1 (1, 0) */
	"0.000 0.000 -0.5 0.0\n"    /* vertex 7: cell 0 (0, 0) */
	"9 9 9 9\n"                 /* vertex 8: in no cell */
	"1 7\n1 6\n1 5\n1 4\n0\n1 3\n1 2\n1 1\n1 0\n"
	"42\n";

static void test_grid(void)
{
	struct fct_err err;
	struct fct_mesh raw, m;
	CHECK(read_mem(&raw, grid3, &err) == 0);
	/* No speck removal: the four triangles are a small piece. */
	struct fct_grid_params p = { FCT_RANGE_GRID_MAX_JUMP, 0 };
	double step = 0;
	int rc = fct_range_grid_mesh(&m, &raw, &p, &step, &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (rc) {
		fct_mesh_free(&raw);
		return;
	}
	CHECK_NEAR(step, 0.001, 1e-9);
	/* Every grid square has three corners with data: one triangle each, on
	 * those corners.  Vertices are the 8 cells with data in grid order. */
	CHECK_INT(m.nv, 8);
	CHECK_INT(m.nf, 4);
	static const int cell_of_vertex[8] = { 0, 1, 2, 3, 5, 6, 7, 8 };
	const struct fct_prop *conf = fct_elem_find(&m.vertex, "confidence");
	CHECK(conf != NULL);
	for (size_t v = 0; v < m.nv && v < 8; v++) {
		int c = cell_of_vertex[v];
		CHECK_NEAR(m.xyz[3 * v], 0.001 * (c % 3), 1e-9);
		CHECK_NEAR(m.xyz[3 * v + 1], -0.001 * (c / 3), 1e-9);
		CHECK_NEAR(m.xyz[3 * v + 2], -0.5, 1e-9);
		if (conf)
			CHECK_NEAR(fct_prop_get(conf, v), 0.1 * c, 1e-6);
	}
	/* The triangles as sorted cell triples: squares (0,0) (1,0) (0,1) (1,1)
	 * without the centre cell 4. */
	static const int want[4][3] = { { 0, 1, 3 }, { 1, 2, 5 }, { 3, 6, 7 }, { 5, 7, 8 } };
	int seen[4] = { 0 };
	for (size_t f = 0; f < m.nf; f++) {
		CHECK_INT(fct_face_size(&m, f), 3);
		const uint32_t *t = &m.fvert[m.fstart[f]];
		int c[3];
		for (int k = 0; k < 3; k++)
			c[k] = cell_of_vertex[t[k] < 8 ? t[k] : 0];
		for (int a = 0; a < 2; a++)
			for (int b = a + 1; b < 3; b++)
				if (c[b] < c[a]) {
					int x = c[a];
					c[a] = c[b];
					c[b] = x;
				}
		for (int w = 0; w < 4; w++)
			if (c[0] == want[w][0] && c[1] == want[w][1] && c[2] == want[w][2])
				seen[w]++;
		/* Facing the scanner: +z. */
		double a[3], b[3], n[3];
		fct_v3_sub(a, &m.xyz[3 * t[1]], &m.xyz[3 * t[0]]);
		fct_v3_sub(b, &m.xyz[3 * t[2]], &m.xyz[3 * t[0]]);
		fct_v3_cross(n, a, b);
		CHECK_NEAR(n[2], 1e-6, 1e-11);
	}
	for (int w = 0; w < 4; w++)
		CHECK_MSG(seen[w] == 1, "triangle %d %d %d made %d times", want[w][0], want[w][1],
		          want[w][2], seen[w]);
	/* range_grid dropped; the other element and the comments kept. */
	CHECK(fct_mesh_find_elem(&m, "range_grid") == NULL);
	const struct fct_elem *x = fct_mesh_find_elem(&m, "extra");
	CHECK(x && x->count == 1 && fct_prop_get(&x->props[0], 0) == 42);
	CHECK_INT(m.ncomments, 3);
	/* Default parameters drop the 4-triangle speck: nothing is left. */
	struct fct_mesh d;
	CHECK(fct_range_grid_mesh(&d, &raw, NULL, NULL, &err) == 0);
	CHECK_INT(d.nf, 0);
	fct_mesh_free(&d);
	/* An already meshed scan is refused. */
	CHECK(fct_range_grid_mesh(&d, &m, NULL, NULL, &err) == -1);
	fct_mesh_free(&m);
	fct_mesh_free(&raw);

	/* A cell pointing past the vertices is refused. */
	char *bad = strdup(grid3);
	char *hit = strstr(bad, "1 7\n1 6");
	hit[2] = '9';
	CHECK(read_mem(&raw, bad, &err) == -1 || fct_range_grid_mesh(&m, &raw, &p, NULL, &err) == -1);
	CHECK_MSG(strstr(err.msg, "out of range") != NULL, "%s", err.msg);
	fct_mesh_free(&raw);
	free(bad);
}

static void test_conf(void)
{
	char dir[] = "/tmp/facet-rangegrid.XXXXXX";
	CHECK(mkdtemp(dir) != NULL);
	char path[64];
	snprintf(path, sizeof path, "%s/a.conf", dir);
	FILE *f = fopen(path, "w");
	/* 90 degrees about z as (qx, qy, qz, qw); applied conjugated it turns x
	 * to -y, then t = (1, 2, 3) moves it. */
	fprintf(f, "camera 0 0 0 0 0 0 1\n"
	           "bmesh scan.ply 1 2 3 0 0 0.70710678118654752 0.70710678118654752\n");
	fclose(f);
	struct fct_conf c;
	struct fct_err err;
	int rc = fct_conf_read(&c, path, &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (!rc) {
		CHECK_INT(c.n, 1);
		char want[64];
		snprintf(want, sizeof want, "%s/scan.ply", dir);
		CHECK_STR(c.scans[0].path, want);
		CHECK_INT(c.scans[0].line, 2);
		double p[3] = { 1, 0, 0 }, q[3];
		fct_pose_apply(c.scans[0].pose, p, q);
		CHECK_NEAR(q[0], 1, 1e-15);
		CHECK_NEAR(q[1], 1, 1e-15);
		CHECK_NEAR(q[2], 3, 1e-15);
		double r[3] = { 0, 1, 0.5 };
		fct_pose_apply(c.scans[0].pose, r, q);
		CHECK_NEAR(q[0], 2, 1e-15);
		CHECK_NEAR(q[1], 2, 1e-15);
		CHECK_NEAR(q[2], 3.5, 1e-15);
		fct_conf_free(&c);
	}
	/* Not a unit quaternion. */
	f = fopen(path, "w");
	fprintf(f, "bmesh scan.ply 0 0 0 0 0 0 2\n");
	fclose(f);
	CHECK(fct_conf_read(&c, path, &err) == -1);
	CHECK_MSG(strstr(err.msg, ":1: ") != NULL, "%s", err.msg);
	/* The dragon_stand archive's form: a mesh line (a file the archive
	 * does not hold) before the bmesh lines is kept aside, as vrip leaves
	 * it; it stopped tsdfuse. */
	rc = fct_conf_read(&c, "tests/data/conf_dragon_stand.conf", &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (!rc) {
		CHECK_INT(c.n, 2);
		CHECK_STR(c.scans[1].path, "tests/data/dragonStandRight_24.ply");
		CHECK_INT(c.scans[0].line, 3);
		CHECK_INT(c.nskipped, 1);
		CHECK_INT(c.skipped[0].line, 2);
		CHECK_STR(c.skipped[0].text, "mesh dragonStandRight_cybcyl 0 0 0 0 0 0 1");
		fct_conf_free(&c);
	}
	/* NUL bytes, and a binary keyword quoted escaped */
	f = fopen(path, "wb");
	fwrite("bmesh a.ply 0 0 0\0 0 0 0 1\n", 1, 28, f);
	fclose(f);
	CHECK(fct_conf_read(&c, path, &err) == -1);
	CHECK_MSG(strstr(err.msg, ":1: binary data (a NUL byte)") != NULL, "%s", err.msg);
	f = fopen(path, "wb");
	fputs("\x1b]0;x\x07 1 2\n", f);
	fclose(f);
	CHECK(fct_conf_read(&c, path, &err) == -1);
	CHECK_MSG(strstr(err.msg, ":1: \"\\x1b]0;x\\x07\": expected camera, bmesh or mesh") != NULL,
	          "%s", err.msg);
	remove(path);
	rmdir(dir);
}

int main(void)
{
	test_grid();
	test_conf();
	CHECK_DONE();
}
