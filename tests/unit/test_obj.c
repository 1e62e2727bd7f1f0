/* OBJ reader and writer: every face corner form, negative indices, vertex
 * identity kept with per-corner vt / vn where they differ, colours,
 * materials and texnumber,
 * comments, continuation lines, exact errors, and bit-exact round trips of
 * floats through the writer and the reader. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "io/header.h"
#include "io/meshio.h"
#include "io/obj.h"

/* Read a mesh from a string (fmemopen: like a pipe); dir as for a file. */
static int read_str_dir(struct fct_mesh *m, const char *text, size_t n, const char *dir,
                        struct fct_err *err)
{
	FILE *f = fmemopen((void *)text, n ? n : 1, "rb");
	if (!n)  /* fmemopen refuses size 0: read past the one byte first */
		fgetc(f);
	int rc = fct_mesh_read_stream(m, f, "mem", dir, NULL, err);
	fclose(f);
	return rc;
}

static int read_str(struct fct_mesh *m, const char *text, struct fct_err *err)
{
	return read_str_dir(m, text, strlen(text), NULL, err);
}

/* Write m as OBJ (and its material library when mtl_out) to strings. */
static char *write_obj(const struct fct_mesh *m, const char *mtl_name, char **mtl_out)
{
	char *buf = NULL, *mbuf = NULL;
	size_t n, mn;
	FILE *f = open_memstream(&buf, &n);
	FILE *mf = mtl_out ? open_memstream(&mbuf, &mn) : NULL;
	struct fct_err err;
	int rc = fct_obj_write(m, f, mtl_name, mf, &err);
	fclose(f);
	if (mf)
		fclose(mf);
	CHECK_MSG(rc == 0, "write: %s", err.msg);
	if (mtl_out)
		*mtl_out = mbuf;
	return buf;
}

static float col(const struct fct_mesh *m, const char *name, size_t i)
{
	const struct fct_prop *p = fct_elem_find(&m->vertex, name);
	return p ? (float)fct_prop_get(p, i) : NAN;
}

/* Face f's vertices as "a b c ..." for comparison. */
static const char *face_str(const struct fct_mesh *m, size_t f)
{
	static char buf[256];
	size_t n = 0;
	buf[0] = 0;
	for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1] && n < sizeof buf - 16; k++)
		n += (size_t)snprintf(buf + n, sizeof buf - n, k > m->fstart[f] ? " %u" : "%u", m->fvert[k]);
	return buf;
}

/* Value k of face f's list column name (NAN when absent). */
static float corner(const struct fct_mesh *m, const char *name, size_t f, size_t k)
{
	const struct fct_prop *p = fct_elem_find(&m->face, name);
	if (!p || !p->count_type || p->off[f] + k >= p->off[f + 1])
		return NAN;
	return (float)fct_prop_get(p, p->off[f] + k);
}

/* Face f's list column name as "a b c ..." for comparison. */
static const char *corner_str(const struct fct_mesh *m, const char *name, size_t f)
{
	static char buf[512];
	const struct fct_prop *p = fct_elem_find(&m->face, name);
	size_t n = 0;
	buf[0] = 0;
	for (size_t k = p ? p->off[f] : 0; p && k < p->off[f + 1] && n < sizeof buf - 32; k++)
		n += (size_t)snprintf(buf + n, sizeof buf - n, k > p->off[f] ? " %g" : "%g", fct_prop_get(p, k));
	return buf;
}

static void test_forms_and_corners(void)
{
	struct fct_err err;
	struct fct_mesh m;
	/* Same as tests/data/obj_split.obj: counts worked out by hand there. */
	const char *text =
		"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\n"
		"vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nvn 0 0 -1\n"
		"f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4//1\n"
		"f 1/2/1 3/3/2 4/1/1\nf 1/2/1 2 4//1\n";
	CHECK_MSG(read_str(&m, text, &err) == 0, "%s", err.msg);
	/* A vertex is its v line, whatever vt / vn its corners name. */
	CHECK_INT(m.nv, 5);
	CHECK_INT(m.nf, 4);
	CHECK_STR(face_str(&m, 0), "0 1 2");
	CHECK_STR(face_str(&m, 1), "0 2 3");
	CHECK_STR(face_str(&m, 2), "0 2 3");
	CHECK_STR(face_str(&m, 3), "0 1 3");
	/* Positions 1, 2, 4 have two vt each, 2 and 3 two vn: both per corner,
	 * none as vertex columns; a corner without one has zeros. */
	CHECK(!fct_elem_find(&m.vertex, "s") && !fct_elem_find(&m.vertex, "nx"));
	CHECK_STR(corner_str(&m, "texcoord", 0), "0 0 1 0 1 1");
	CHECK_STR(corner_str(&m, "texcoord", 1), "0 0 1 1 0 0");
	CHECK_STR(corner_str(&m, "texcoord", 2), "1 0 1 1 0 0");
	CHECK_STR(corner_str(&m, "texcoord", 3), "1 0 0 0 0 0");
	CHECK_STR(corner_str(&m, "corner_normal", 2), "0 0 1 0 0 -1 0 0 1");
	CHECK_STR(corner_str(&m, "corner_normal", 3), "0 0 1 0 0 0 0 0 1");
	const struct fct_prop *tc = fct_elem_find(&m.face, "texcoord");
	CHECK(tc && tc->type == FCT_FLOAT32 && tc->count_type == FCT_UINT8);
	/* The unused position 5 is kept. */
	CHECK(m.xyz[12] == 5);
	CHECK(m.xyz_type == FCT_FLOAT32);
	CHECK(!fct_elem_find(&m.vertex, "red"));
	CHECK(!fct_elem_find(&m.face, "texnumber"));
	fct_mesh_free(&m);

	/* Matching indices (as facet writes them) keep order and count. */
	CHECK(read_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt .1 .2\nvt .3 .4\nvt .5 .6\nvt .7 .8\n"
	                   "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n", &err) == 0);
	CHECK_INT(m.nv, 4);
	CHECK_STR(face_str(&m, 1), "1 3 2");
	CHECK(col(&m, "s", 3) == 0.7f && col(&m, "t", 3) == 0.8f);
	CHECK(!fct_elem_find(&m.vertex, "nx"));
	CHECK(!fct_elem_find(&m.face, "texcoord"));
	fct_mesh_free(&m);

	/* Issue 24's reproduction: two normals of the same value under two
	 * indices do not split the shared edge: 4 vertices, one piece.  The
	 * normals differ by index only, so they go per corner (values equal). */
	CHECK(read_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 1\n"
	                   "f 1//1 2//1 3//1\nf 2//2 4//2 3//2\n", &err) == 0);
	CHECK_INT(m.nv, 4);
	CHECK_STR(face_str(&m, 1), "1 3 2");
	CHECK(corner(&m, "corner_normal", 1, 2) == 1);
	fct_mesh_free(&m);

	/* Indices that differ from the v indices but agree round every position
	 * (a smooth-shaded export): vertex columns, no per-corner list. */
	CHECK(read_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 -1\nvn 0 0 1\nvn 0 1 0\n"
	                   "vt 0.5 0.5\nvt 1 1\nf 1/2/2 2/1/3 3/1/2\nf 2/1/3 4/1/1 3/1/2\n", &err) == 0);
	CHECK_INT(m.nv, 4);
	CHECK(!fct_elem_find(&m.face, "texcoord") && !fct_elem_find(&m.face, "corner_normal"));
	CHECK(col(&m, "nz", 0) == 1 && col(&m, "ny", 1) == 1 && col(&m, "nz", 3) == -1);
	CHECK(col(&m, "s", 0) == 1 && col(&m, "s", 1) == 0.5f && col(&m, "t", 3) == 0.5f);
	fct_mesh_free(&m);
}

static void test_negative_and_polygons(void)
{
	struct fct_err err;
	struct fct_mesh m;
	CHECK(read_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nvt 0 0\nvt 1 0\nvt 0 1\nv 0 0 1\n"
	                   "f -4/-3 -2/-2 -1/-1\n", &err) == 0);
	CHECK_INT(m.nv, 4);
	CHECK_STR(face_str(&m, 0), "0 1 2");
	CHECK_STR(face_str(&m, 1), "0 2 3");
	CHECK_STR(corner_str(&m, "texcoord", 0), "0 0 0 0 0 0");
	CHECK_STR(corner_str(&m, "texcoord", 1), "0 0 1 0 0 1");
	fct_mesh_free(&m);

	/* Polygons are kept whole; "+1" and the "1/" form are accepted. */
	CHECK(read_str(&m, "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nv 9 9 9\n"
	                   "f +1 2/ 3 4 5\nf 5 4 3 2 1 6\n", &err) == 0);
	CHECK_INT(m.nf, 2);
	CHECK_INT(fct_face_size(&m, 0), 5);
	CHECK_INT(fct_face_size(&m, 1), 6);
	CHECK_STR(face_str(&m, 1), "4 3 2 1 0 5");
	fct_mesh_free(&m);
}

static void test_cube_with_material(void)
{
	char dir[] = "/tmp/test_obj.XXXXXX";
	CHECK(mkdtemp(dir) != NULL);
	char path[512];
	snprintf(path, sizeof path, "%s/lib.mtl", dir);
	FILE *f = fopen(path, "w");
	fputs("newmtl wood\nKd 1 1 1\nmap_Kd -s 1 1 1 -o 0 0 0 img\\wood.png\n"
	      "newmtl stone\nmap_Kd stone.png\nnewmtl plain\nKd 0.5 0.5 0.5\n"
	      "newmtl same\nmap_kd img/wood.png\n", f);
	fclose(f);
	struct fct_err err;
	struct fct_mesh m;
	const char *text =
		"mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
		"usemtl plain\nf 1 2 3\n"
		"usemtl stone\nf 1/1 2/2 3/3\n"
		"usemtl wood\nf 1/1 3/3 4/1\n"
		"usemtl same\nf 1/1 2/2 4/1\n"
		"usemtl nowhere\nf 2 3 4\n"
		"usemtl stone\nf 4 3 2\n";
	CHECK_MSG(read_str_dir(&m, text, strlen(text), dir, &err) == 0, "%s", err.msg);
	/* Textures in order of first use; two materials of one path share it. */
	CHECK_INT(fct_header_texture_count(&m), 2);
	char want[600];
	snprintf(want, sizeof want, "%s/stone.png", dir);
	CHECK_STR(fct_header_texture(&m, 0), want);
	snprintf(want, sizeof want, "%s/img/wood.png", dir);
	CHECK_STR(fct_header_texture(&m, 1), want);
	const struct fct_prop *tn = fct_elem_find(&m.face, "texnumber");
	CHECK(tn && tn->type == FCT_INT32);
	static const int want_tn[6] = {-1, 0, 1, 1, -1, 0};
	for (size_t i = 0; tn && i < 6; i++)
		CHECK_INT(fct_prop_get(tn, i), want_tn[i]);
	fct_mesh_free(&m);

	/* One texture for every face: no texnumber. */
	const char *one = "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nusemtl wood\nf 1/1 2/1 3/1\n";
	CHECK(read_str_dir(&m, one, strlen(one), dir, &err) == 0);
	CHECK_INT(fct_header_texture_count(&m), 1);
	CHECK(!fct_elem_find(&m.face, "texnumber"));
	fct_mesh_free(&m);

	/* A missing library is skipped: no textures, no error. */
	const char *missing = "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl wood\nf 1 2 3\n";
	CHECK(read_str_dir(&m, missing, strlen(missing), dir, &err) == 0);
	CHECK_INT(fct_header_texture_count(&m), 0);
	CHECK_INT(m.nf, 1);
	fct_mesh_free(&m);
	unlink(path);
	rmdir(dir);
}

static void test_colours_and_numbers(void)
{
	struct fct_err err;
	struct fct_mesh m;
	CHECK(read_str(&m, "v 0.1 -2e3 7 1 0.5 0.2\nv 1 2 3 4\nv 0 0 1 0 1.5 -1\n", &err) == 0);
	CHECK_INT(m.nv, 3);
	CHECK(!m.has_faces);
	CHECK(m.xyz[0] == (double)0.1f && m.xyz[1] == -2000 && m.xyz[5] == 3);
	/* 0.5 * 255 = 127.5 rounds to even; 0.2 * 255 = 51; the v without colour is black. */
	CHECK(col(&m, "red", 0) == 255 && col(&m, "green", 0) == 128 && col(&m, "blue", 0) == 51);
	CHECK(col(&m, "red", 1) == 0 && col(&m, "green", 1) == 0 && col(&m, "blue", 1) == 0);
	CHECK(col(&m, "green", 2) == 255 && col(&m, "blue", 2) == 0);
	CHECK(fct_elem_find(&m.vertex, "red")->type == FCT_UINT8);
	fct_mesh_free(&m);

	/* More digits than a float holds: positions stay double. */
	CHECK(read_str(&m, "v 0.10000000000000001 1 2\nv 123456.789012 0 0\n", &err) == 0);
	CHECK(m.xyz_type == FCT_FLOAT64);
	CHECK(m.xyz[0] == 0.1 && m.xyz[3] == 123456.789012);
	fct_mesh_free(&m);
	/* Beyond the float range: double, so the value stays finite. */
	CHECK(read_str(&m, "v 1e39 0 0\n", &err) == 0);
	CHECK(m.xyz_type == FCT_FLOAT64 && m.xyz[0] == 1e39);
	fct_mesh_free(&m);
	/* Trailing zeros are not precision. */
	CHECK(read_str(&m, "v 0.1000000000 1 2\n", &err) == 0);
	CHECK(m.xyz_type == FCT_FLOAT32);
	fct_mesh_free(&m);

	/* Point cloud: no face, one vn and vt per v: taken by index. */
	CHECK(read_str(&m, "vn 0 0 1\nv 1 2 3\nvn 0 1 0\nv 4 5 6\nvt 0.25 0.5\nvt 0.75 1 0\n", &err) == 0);
	CHECK_INT(m.nv, 2);
	CHECK(col(&m, "nz", 0) == 1 && col(&m, "ny", 1) == 1 && col(&m, "s", 1) == 0.75f && col(&m, "t", 0) == 0.5f);
	fct_mesh_free(&m);
}

static void test_lines_and_comments(void)
{
	struct fct_err err;
	struct fct_mesh m;
	const char *text =
		"\xEF\xBB\xBF# facet\r\n"
		"# comment camera pinhole 640 480 525 525 319.5 239.5\r\n"
		"# obj_info scanner 3\r\n"
		"#comment  two blanks kept\r\n"
		"# just a remark\r\n"
		"# comment facet prog C:\\dir\\\r\n"
		"  \t\r\n"
		"v 0 0 \\\r\n 0\r\n"
		"v 1 0 0\nv 0 1 0\n"
		"f 1 \\\n2 \\\n3\n"
		"vp 0.5\ncstype bezier\nl 1 2\ng a b\no x\ns 1\n";
	CHECK_MSG(read_str(&m, text, &err) == 0, "%s", err.msg);
	CHECK_INT(m.nv, 3);
	CHECK_INT(m.nf, 1);
	CHECK_STR(face_str(&m, 0), "0 1 2");
	CHECK_INT(m.ncomments, 4);
	if (m.ncomments == 4) {
		CHECK_STR(m.comments[0].text, "camera pinhole 640 480 525 525 319.5 239.5");
		CHECK(!m.comments[0].obj_info);
		CHECK_STR(m.comments[1].text, "scanner 3");
		CHECK(m.comments[1].obj_info);
		CHECK_STR(m.comments[2].text, " two blanks kept");
		CHECK_STR(m.comments[3].text, "facet prog C:\\dir\\");  /* no continuation */
	}
	fct_mesh_free(&m);

	/* A TextureFile comment is made relative to the current folder. */
	const char *tex = "# comment TextureFile img/t.png\nv 0 0 0\n";
	CHECK(read_str_dir(&m, tex, strlen(tex), "models", &err) == 0);
	CHECK_STR(fct_header_texture(&m, 0), "models/img/t.png");
	fct_mesh_free(&m);
}

/* Each bad input: the exact message. */
static void test_errors(void)
{
	static const struct {
		const char *text, *msg;
	} cases[] = {
		{"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "mem:3: face: vertex index 3 out of range (2 vertices)"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n", "mem:4: face: vertex index 0 out of range (3 vertices)"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 99999999999\n",
		 "mem:4: face: vertex index 99999999999 out of range (3 vertices)"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 -4\n", "mem:4: face: vertex index -4 out of range (3 vertices)"},
		{"f -1 -2 -3\nv 0 0 0\n", "mem:1: face: vertex index -1 out of range (0 vertices)"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
		 "mem:5: face: texture coordinate index 2 out of range (1 texture coordinates)"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1//1 2//1 3//1\n", "mem:4: face: normal index 1 out of range (0 normals)"},
		{"v 0 0 0\nv 1 0 0\nf 1 2\n", "mem:3: face: a face needs 3 or more vertices, got 2"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1/x/2 2 3\n", "mem:4: face: \"1/x/2\" is not a vertex reference"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf a b c\n", "mem:4: face: \"a\" is not a vertex reference"},
		{"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3x\n", "mem:4: face: \"3x\" is not a vertex reference"},
		{"v 1 2\n", "mem:1: v: expected 3, 4 or 6 numbers, got 2"},
		{"v 1 2 3 4 5\n", "mem:1: v: expected 3, 4 or 6 numbers, got 5"},
		{"v 1 nan 3\n", "mem:1: v: coordinate is not a finite number"},
		{"v 1 2 inf\n", "mem:1: v: coordinate is not a finite number"},
		{"v 1 2 3 0 nan 1\n", "mem:1: v: colour is not a finite number"},
		{"v 1 2 3,5\n", "mem:1: v: \"3,5\" is not a number"},
		{"v 1 2 3\nvn 1 2\n", "mem:2: vn: expected 3 numbers, got 2"},
		{"v 1 2 3\nvt\n", "mem:2: vt: expected 1 to 3 numbers, got 0"},
		{"v 1 2 3\nv 1\x01 2 3\n", "mem:2: v: \"1\x01\" is not a number"},
		{"", "mem: not a PLY or OBJ file (no vertex)"},
		{"# only\n# comments\n\n", "mem: not a PLY or OBJ file (no vertex)"},
		{"hello world\n", "mem: not a PLY or OBJ file (no vertex)"},
		{"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR", "mem: not a PLY or OBJ file (no vertex)"},
		{"v 0 0 0\n\x7f\x45LF\n", "mem:2: binary data in a text file"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
		struct fct_err err;
		struct fct_mesh m;
		size_t n = strlen(cases[i].text);
		if (i == 23)
			n = 16;  /* the PNG signature holds NUL bytes */
		int rc = read_str_dir(&m, cases[i].text, n, NULL, &err);
		CHECK_MSG(rc == -1, "case %zu read", i);
		if (rc == -1)
			CHECK_STR(err.msg, cases[i].msg);
		CHECK_INT(m.nv, 0);  /* freed on failure */
	}
	/* A NUL byte inside a v or f line, and in a comment. */
	static const char nul1[] = "v 1 2 3\nv 1 2\0 3\n", nul2[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\0 9\n",
	                  nul3[] = "v 0 0 0\n# x\0y\n";
	struct fct_err err;
	struct fct_mesh m;
	CHECK(read_str_dir(&m, nul1, sizeof nul1 - 1, NULL, &err) == -1);
	CHECK_STR(err.msg, "mem:2: binary data in a text file");
	CHECK(read_str_dir(&m, nul2, sizeof nul2 - 1, NULL, &err) == -1);
	CHECK_STR(err.msg, "mem:4: binary data in a text file");
	CHECK(read_str_dir(&m, nul3, sizeof nul3 - 1, NULL, &err) == -1);
	CHECK_STR(err.msg, "mem:2: binary data in a text file");
}

/* A mesh with every column the writer knows. */
static void build_textured(struct fct_mesh *m, int two_textures)
{
	struct fct_err err;
	fct_mesh_init(m);
	for (int v = 0; v < 4; v++)
		fct_mesh_add_vertex(m, v * 0.1, v == 2 ? -1e-7 : v, 0.5 * v, &err);
	static const char *names[] = {"nx", "ny", "nz", "s", "t", "red", "green", "blue"};
	struct fct_prop *p[8];
	for (int k = 0; k < 8; k++)
		fct_elem_add_scalar(&m->vertex, names[k], k < 5 ? FCT_FLOAT32 : FCT_UINT8, &err);
	for (int k = 0; k < 8; k++)  /* after adding: each new column moves the others */
		p[k] = fct_elem_find(&m->vertex, names[k]);
	for (size_t v = 0; v < 4; v++) {
		fct_prop_set(p[2], v, 1);
		fct_prop_set(p[3], v, v * 0.25);
		fct_prop_set(p[4], v, 1 - v * 0.25);
		fct_prop_set(p[5], v, 255);
		fct_prop_set(p[6], v, 17 * v);
		fct_prop_set(p[7], v, 1);
	}
	uint32_t quad[4] = {0, 1, 2, 3}, tri[3] = {3, 2, 0};
	fct_mesh_add_face(m, quad, 4, &err);
	fct_mesh_add_face(m, tri, 3, &err);
	fct_mesh_add_face(m, tri, 3, &err);
	fct_mesh_add_comment(m, "camera pinhole 640 480 525 525 319.5 239.5", 0, &err);
	fct_mesh_add_comment(m, "TextureFile a.png", 0, &err);
	if (two_textures) {
		fct_mesh_add_comment(m, "TextureFile b.png", 0, &err);
		struct fct_prop *tn = fct_elem_add_scalar(&m->face, "texnumber", FCT_INT32, &err);
		fct_prop_set(tn, 0, 1);
		fct_prop_set(tn, 1, -1);
		fct_prop_set(tn, 2, 0);
	}
	fct_mesh_add_comment(m, "num_cols 2", 1, &err);
}

static void test_writer(void)
{
	struct fct_mesh m;
	build_textured(&m, 1);
	CHECK(fct_obj_wants_mtl(&m));
	char *mtl = NULL;
	char *obj = write_obj(&m, "m.mtl", &mtl);
	const char *want =
		"# facet\n"
		"# comment camera pinhole 640 480 525 525 319.5 239.5\n"
		"# comment TextureFile a.png\n"
		"# comment TextureFile b.png\n"
		"# obj_info num_cols 2\n"
		"mtllib m.mtl\n"
		"v 0 0 0 1 0 0.003921569\n"
		"v 0.1 1 0.5 1 0.06666667 0.003921569\n"
		"v 0.2 -1e-07 1 1 0.13333334 0.003921569\n"
		"v 0.3 3 1.5 1 0.2 0.003921569\n"
		"vt 0 1\nvt 0.25 0.75\nvt 0.5 0.5\nvt 0.75 0.25\n"
		"vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
		"usemtl material_1\n"
		"f 1/1/1 2/2/2 3/3/3 4/4/4\n"
		"usemtl untextured\n"
		"f 4/4/4 3/3/3 1/1/1\n"
		"usemtl material_0\n"
		"f 4/4/4 3/3/3 1/1/1\n";
	CHECK_STR(obj, want);
	CHECK_STR(mtl, "# facet\n"
	               "newmtl material_0\nKa 1 1 1\nKd 1 1 1\nmap_Kd a.png\n\n"
	               "newmtl material_1\nKa 1 1 1\nKd 1 1 1\nmap_Kd b.png\n\n"
	               "newmtl untextured\nKa 1 1 1\nKd 1 1 1\n");
	free(obj);
	free(mtl);

	/* No material library named: no mtllib, no usemtl; the comments still say it. */
	obj = write_obj(&m, NULL, NULL);
	CHECK(!strstr(obj, "mtllib") && !strstr(obj, "usemtl") && strstr(obj, "# comment TextureFile b.png\n"));
	free(obj);
	fct_mesh_free(&m);

	/* Plain mesh: "f a b c", doubles in shortest form, no mtl wanted. */
	struct fct_err err;
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0.1, 1.0 / 3, 1e300, &err);
	fct_mesh_add_vertex(&m, 1, 2, 3, &err);
	fct_mesh_add_vertex(&m, -0.0, 5e-324, 1, &err);
	m.xyz_type = FCT_FLOAT64;
	uint32_t tri[3] = {2, 0, 1};
	fct_mesh_add_face(&m, tri, 3, &err);
	CHECK(!fct_obj_wants_mtl(&m));
	obj = write_obj(&m, "x.mtl", NULL);
	CHECK_STR(obj, "# facet\nv 0.1 0.3333333333333333 1e+300\nv 1 2 3\nv -0 4.94065645841247e-324 1\nf 3 1 2\n");
	free(obj);
	fct_mesh_free(&m);
}

/* Write as OBJ, read back: the same mesh, bit for bit. */
static void test_round_trip(void)
{
	struct fct_mesh m, back;
	struct fct_err err;
	build_textured(&m, 1);
	char *obj = write_obj(&m, NULL, NULL);
	CHECK_MSG(read_str(&back, obj, &err) == 0, "%s", err.msg);
	CHECK_INT(back.nv, 4);
	CHECK_INT(back.nf, 3);
	CHECK_INT(back.ncomments, 4);
	for (size_t i = 0; i < 3 * m.nv; i++)
		CHECK((float)m.xyz[i] == back.xyz[i]);
	for (size_t k = 0; k < m.vertex.nprops; k++) {
		const struct fct_prop *a = &m.vertex.props[k], *b = fct_elem_find(&back.vertex, a->name);
		CHECK_MSG(b && b->type == a->type, "column %s", a->name);
		for (size_t i = 0; b && i < m.nv; i++)
			CHECK(fct_prop_get(a, i) == fct_prop_get(b, i));
	}
	for (size_t f = 0; f < m.nf; f++)
		CHECK(!strcmp(face_str(&m, f), face_str(&back, f)));
	free(obj);
	fct_mesh_free(&back);
	fct_mesh_free(&m);

	/* Many awkward floats (random bit patterns, subnormals, extremes) and
	 * doubles survive the shortest-form output. */
	fct_mesh_init(&m);
	uint64_t s = 88172645463325252u;
	for (int i = 0; i < 20000; i++) {
		double c[3];
		for (int k = 0; k < 3; k++) {
			s ^= s << 13, s ^= s >> 7, s ^= s << 17;
			uint32_t bits = (uint32_t)s;
			float fv;
			memcpy(&fv, &bits, 4);
			c[k] = isfinite(fv) ? fv : (float)(i * 1e-3);
		}
		fct_mesh_add_vertex(&m, c[0], c[1], c[2], &err);
	}
	float edge[] = {1.17549435e-38f, 1.4e-45f, 3.40282347e38f, 16777217.0f, 0.1f, 1.0f / 3};
	for (size_t k = 0; k < sizeof edge / sizeof *edge; k++)
		fct_mesh_add_vertex(&m, edge[k], -edge[k], 0, &err);
	obj = write_obj(&m, NULL, NULL);
	CHECK(read_str(&back, obj, &err) == 0);
	size_t bad = 0;
	for (size_t i = 0; back.nv == m.nv && i < 3 * m.nv; i++)
		bad += memcmp(&m.xyz[i], &back.xyz[i], sizeof(double)) != 0;
	CHECK_INT(back.nv, m.nv);
	CHECK_INT(bad, 0);
	CHECK(back.xyz_type == FCT_FLOAT32);
	free(obj);
	fct_mesh_free(&back);

	/* Now as doubles. */
	for (size_t i = 0; i < 3 * m.nv; i++) {
		s ^= s << 13, s ^= s >> 7, s ^= s << 17;
		double d;
		memcpy(&d, &s, 8);
		m.xyz[i] = isfinite(d) ? d : 1.0 / (double)(i + 3);
	}
	m.xyz_type = FCT_FLOAT64;
	obj = write_obj(&m, NULL, NULL);
	CHECK(read_str(&back, obj, &err) == 0);
	bad = 0;
	for (size_t i = 0; back.nv == m.nv && i < 3 * m.nv; i++)
		bad += memcmp(&m.xyz[i], &back.xyz[i], sizeof(double)) != 0;
	CHECK_INT(bad, 0);
	CHECK(back.xyz_type == FCT_FLOAT64);
	free(obj);
	fct_mesh_free(&back);
	fct_mesh_free(&m);
}

/* Per-corner texcoord and corner_normal lists are written as vt / vn
 * indices per corner (distinct values once, in order of first use), and
 * read back as the same lists: OBJ -> mesh -> OBJ is a fixed point. */
static void test_corner_writer(void)
{
	struct fct_err err;
	struct fct_mesh m, back;
	/* Blender's default cube as its OBJ exporter writes it (normals on,
	 * UVs, flat shading): 8 v, 6 vn, 14 vt, every corner its own pair. */
	const char *cube =
		"# Blender 5.0.1\n# www.blender.org\nmtllib untitled.mtl\no Cube\n"
		"v 1.000000 1.000000 -1.000000\nv 1.000000 -1.000000 -1.000000\n"
		"v 1.000000 1.000000 1.000000\nv 1.000000 -1.000000 1.000000\n"
		"v -1.000000 1.000000 -1.000000\nv -1.000000 -1.000000 -1.000000\n"
		"v -1.000000 1.000000 1.000000\nv -1.000000 -1.000000 1.000000\n"
		"vn -0.0000 1.0000 -0.0000\nvn -0.0000 -0.0000 1.0000\nvn -1.0000 -0.0000 -0.0000\n"
		"vn -0.0000 -1.0000 -0.0000\nvn 1.0000 -0.0000 -0.0000\nvn -0.0000 -0.0000 -1.0000\n"
		"vt 0.625000 0.500000\nvt 0.875000 0.500000\nvt 0.875000 0.750000\nvt 0.625000 0.750000\n"
		"vt 0.375000 0.750000\nvt 0.625000 1.000000\nvt 0.375000 1.000000\nvt 0.375000 0.000000\n"
		"vt 0.625000 0.000000\nvt 0.625000 0.250000\nvt 0.375000 0.250000\nvt 0.125000 0.500000\n"
		"vt 0.375000 0.500000\nvt 0.125000 0.750000\n"
		"s 0\nusemtl Material\n"
		"f 1/1/1 5/2/1 7/3/1 3/4/1\nf 4/5/2 3/4/2 7/6/2 8/7/2\nf 8/8/3 7/9/3 5/10/3 6/11/3\n"
		"f 6/12/4 2/13/4 4/5/4 8/14/4\nf 2/13/5 1/1/5 3/4/5 4/5/5\nf 6/11/6 5/10/6 1/1/6 2/13/6\n";
	CHECK_MSG(read_str(&m, cube, &err) == 0, "%s", err.msg);
	CHECK_INT(m.nv, 8);
	CHECK_INT(m.nf, 6);
	CHECK_STR(corner_str(&m, "texcoord", 1), "0.375 0.75 0.625 0.75 0.625 1 0.375 1");
	CHECK_STR(corner_str(&m, "corner_normal", 2), "-1 -0 -0 -1 -0 -0 -1 -0 -0 -1 -0 -0");
	char *obj = write_obj(&m, NULL, NULL);
	/* The distinct values only, in order of first use: Blender's own. */
	const char *want_tail =
		"vt 0.625 0.5\nvt 0.875 0.5\nvt 0.875 0.75\nvt 0.625 0.75\nvt 0.375 0.75\nvt 0.625 1\n"
		"vt 0.375 1\nvt 0.375 0\nvt 0.625 0\nvt 0.625 0.25\nvt 0.375 0.25\nvt 0.125 0.5\n"
		"vt 0.375 0.5\nvt 0.125 0.75\n"
		"vn -0 1 -0\nvn -0 -0 1\nvn -1 -0 -0\nvn -0 -1 -0\nvn 1 -0 -0\nvn -0 -0 -1\n"
		"f 1/1/1 5/2/1 7/3/1 3/4/1\nf 4/5/2 3/4/2 7/6/2 8/7/2\nf 8/8/3 7/9/3 5/10/3 6/11/3\n"
		"f 6/12/4 2/13/4 4/5/4 8/14/4\nf 2/13/5 1/1/5 3/4/5 4/5/5\nf 6/11/6 5/10/6 1/1/6 2/13/6\n";
	CHECK_MSG(strstr(obj, want_tail) != NULL, "%s", obj);
	CHECK_MSG(read_str(&back, obj, &err) == 0, "%s", err.msg);
	char *again = write_obj(&back, NULL, NULL);
	CHECK_STR(again, obj);
	free(again);
	free(obj);
	fct_mesh_free(&back);

	/* Vertex s t with per-corner normals: vt by vertex, vn by corner. */
	struct fct_prop *s = fct_elem_add_scalar(&m.vertex, "s", FCT_FLOAT32, &err);
	fct_prop_set(s, 7, 0.5);
	CHECK(fct_elem_add_scalar(&m.vertex, "t", FCT_FLOAT32, &err) != NULL);
	fct_elem_remove(&m.face, "texcoord");
	obj = write_obj(&m, NULL, NULL);
	CHECK(strstr(obj, "vt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\nvt 0.5 0\nvn -0 1 -0\n") != NULL);
	CHECK(strstr(obj, "\nf 8/8/3 7/7/3 5/5/3 6/6/3\n") != NULL);
	free(obj);
	/* A list of the wrong length for some face is not per-corner data. */
	struct fct_prop *cn = fct_elem_find(&m.face, "corner_normal");
	cn->off[6] -= 1;
	obj = write_obj(&m, NULL, NULL);
	CHECK(!strstr(obj, "vn ") && strstr(obj, "\nf 8/8 7/7 5/5 6/6\n"));
	free(obj);
	fct_mesh_free(&m);
}

/* A hostile face list: one position with a new texture coordinate at every
 * corner stays one vertex, with every corner's own value, and the writer's
 * table of distinct values stays linear (hash, not a chain). */
static void test_many_corners(void)
{
	enum { N = 30000 };
	size_t cap = (size_t)N * 40 + 100, n = 0;
	char *text = malloc(cap);
	n += (size_t)snprintf(text + n, cap - n, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
	for (int i = 0; i < N; i++)
		n += (size_t)snprintf(text + n, cap - n, "vt %d 0\n", i);
	for (int i = 0; i < N; i++)
		n += (size_t)snprintf(text + n, cap - n, "f 1/%d 2/1 3/1\n", i + 1);
	struct fct_mesh m;
	struct fct_err err;
	CHECK(read_str_dir(&m, text, n, NULL, &err) == 0);
	CHECK_INT(m.nv, 3);
	CHECK_STR(face_str(&m, N - 1), "0 1 2");
	CHECK(corner(&m, "texcoord", N - 1, 0) == N - 1 && corner(&m, "texcoord", N - 1, 2) == 0);
	char *obj = write_obj(&m, NULL, NULL);
	size_t vts = 0;
	for (const char *p = obj; (p = strstr(p, "\nvt ")); p++)
		vts++;
	CHECK_INT(vts, N);
	CHECK(strstr(obj, "\nf 1/30000 2/1 3/1\n") != NULL);
	free(obj);
	fct_mesh_free(&m);
	free(text);
}

int main(void)
{
	test_forms_and_corners();
	test_negative_and_polygons();
	test_cube_with_material();
	test_colours_and_numbers();
	test_lines_and_comments();
	test_errors();
	test_writer();
	test_round_trip();
	test_many_corners();
	test_corner_writer();
	CHECK_DONE();
}
