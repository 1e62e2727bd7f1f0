/* PLY reader and writer: every scalar and list type, the three encodings,
 * exact round trips, CRLF headers, elements carried through, and hostile
 * counts read from a stream whose size is unknown. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/header.h"
#include "io/meshio.h"
#include "io/ply.h"

/* Read a mesh from memory (fmemopen: no file size, like a pipe). */
static int read_mem(struct fct_mesh *m, const void *data, size_t n, struct fct_err *err)
{
	FILE *f = fmemopen((void *)data, n, "rb");
	int rc = fct_mesh_read_stream(m, f, "mem", NULL, NULL, err);
	fclose(f);
	return rc;
}

/* Write m in fmt to a memory buffer (malloc'd, *n bytes). */
static char *write_mem(const struct fct_mesh *m, enum fct_format fmt, size_t *n)
{
	char *buf = NULL;
	FILE *f = open_memstream(&buf, n);
	struct fct_err err;
	int rc = fct_mesh_write_stream(m, f, fmt, &err);
	fclose(f);
	CHECK_MSG(rc == 0, "write: %s", err.msg);
	return buf;
}

/* A mesh with a column of every scalar type, a list column, a polygon, an
 * extra element and comments. */
static void build_rich(struct fct_mesh *m)
{
	struct fct_err err;
	fct_mesh_init(m);
	static const enum fct_type types[] = {FCT_INT8, FCT_UINT8, FCT_INT16, FCT_UINT16,
	                                      FCT_INT32, FCT_UINT32, FCT_FLOAT32, FCT_FLOAT64};
	static const char *names[] = {"c", "uc", "s", "us", "i", "ui", "f", "d"};
	for (int v = 0; v < 5; v++)
		fct_mesh_add_vertex(m, v * 0.1, v * -1e-7, 1e30 / (v + 1), &err);
	m->xyz_type = FCT_FLOAT64;
	for (int t = 0; t < 8; t++) {
		struct fct_prop *p = fct_elem_add_scalar(&m->vertex, names[t], types[t], &err);
		CHECK(p != NULL);
		for (int v = 0; v < 5; v++) {
			static const double vals[5][8] = {
				{-128, 0, -32768, 0, -2147483648.0, 0, -1.5f, -1e-300},
				{127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 3.4e38f, 1.7976931348623157e308},
				{0, 1, 2, 3, 4, 5, 0.1f, 0.1},
				{-1, 128, -1, 40000, -1, 3000000000.0, 1e-45f, 5e-324},
				{5, 6, 7, 8, 9, 10, -0.0f, -0.0},
			};
			fct_prop_set(p, (size_t)v, vals[v][t]);
		}
	}
	uint32_t quad[4] = {0, 1, 2, 3}, tri[3] = {2, 3, 4};
	fct_mesh_add_face(m, quad, 4, &err);
	fct_mesh_add_face(m, tri, 3, &err);
	struct fct_prop *patch = fct_elem_add_scalar(&m->face, "patch", FCT_INT32, &err);
	fct_prop_set(patch, 0, -1);
	fct_prop_set(patch, 1, 7);
	struct fct_elem *e = fct_mesh_add_elem(m, "plane", 2, &err);
	struct fct_prop *nx = fct_elem_add_scalar(e, "nx", FCT_FLOAT32, &err);
	fct_prop_set(nx, 0, 0.25);
	fct_prop_set(nx, 1, -0.75);
	fct_mesh_add_comment(m, "camera pinhole 640 480 525 525 319.5 239.5", 0, &err);
	fct_mesh_add_comment(m, "num_cols 512", 1, &err);
	fct_mesh_add_comment(m, "", 0, &err);
}

/* Are two meshes equal in every stored bit? */
static int same_mesh(const struct fct_mesh *a, const struct fct_mesh *b)
{
	if (a->nv != b->nv || a->nf != b->nf || a->nelems != b->nelems || a->ncomments != b->ncomments)
		return 0;
	if (memcmp(a->xyz, b->xyz, 3 * a->nv * sizeof *a->xyz))
		return 0;
	if (a->nf && (memcmp(a->fstart, b->fstart, (a->nf + 1) * 4) ||
	              memcmp(a->fvert, b->fvert, a->fstart[a->nf] * 4)))
		return 0;
	const struct fct_elem *ea[16], *eb[16];
	size_t n = 2 + a->nelems;
	ea[0] = &a->vertex, eb[0] = &b->vertex, ea[1] = &a->face, eb[1] = &b->face;
	for (size_t i = 0; i < a->nelems; i++)
		ea[2 + i] = &a->elems[i], eb[2 + i] = &b->elems[i];
	for (size_t e = 0; e < n; e++) {
		if (ea[e]->nprops != eb[e]->nprops || ea[e]->count != eb[e]->count)
			return 0;
		for (size_t j = 0; j < ea[e]->nprops; j++) {
			const struct fct_prop *p = &ea[e]->props[j], *q = &eb[e]->props[j];
			if (strcmp(p->name, q->name) || p->type != q->type || p->count_type != q->count_type)
				return 0;
			size_t values = p->count_type ? p->off[ea[e]->count] : ea[e]->count;
			if (memcmp(p->data, q->data, values * fct_type_size(p->type)))
				return 0;
			if (p->count_type && memcmp(p->off, q->off, (ea[e]->count + 1) * sizeof *p->off))
				return 0;
		}
	}
	for (size_t i = 0; i < a->ncomments; i++)
		if (strcmp(a->comments[i].text, b->comments[i].text) || a->comments[i].obj_info != b->comments[i].obj_info)
			return 0;
	return 1;
}

static void test_round_trips(void)
{
	struct fct_mesh m, r, r2;
	struct fct_err err;
	build_rich(&m);
	for (int fmt = FCT_FORMAT_PLY_ASCII; fmt <= FCT_FORMAT_PLY_BE; fmt++) {
		size_t n;
		char *buf = write_mem(&m, (enum fct_format)fmt, &n);
		int rc = read_mem(&r, buf, n, &err);
		CHECK_MSG(rc == 0, "format %d: %s", fmt, err.msg);
		if (!rc) {
			CHECK_MSG(same_mesh(&m, &r), "format %d: round trip differs", fmt);
			/* and once more through the other encodings */
			for (int g = FCT_FORMAT_PLY_ASCII; g <= FCT_FORMAT_PLY_BE; g++) {
				size_t n2;
				char *b2 = write_mem(&r, (enum fct_format)g, &n2);
				CHECK(read_mem(&r2, b2, n2, &err) == 0 && same_mesh(&m, &r2));
				fct_mesh_free(&r2);
				free(b2);
			}
		}
		fct_mesh_free(&r);
		free(buf);
	}
	fct_mesh_free(&m);
}

static void test_big_endian_bytes(void)
{
	/* Hand-made: one vertex (1.5, -2, 0.25) as big-endian floats, a ushort
	 * property 0x0102, a face element with list ushort uint. */
	static const char head[] = "ply\r\nformat binary_big_endian 1.0\r\nelement vertex 3\r\n"
		"property float x\r\nproperty float y\r\nproperty float z\r\nproperty ushort q\r\n"
		"element face 1\r\nproperty list ushort uint vertex_index\r\nend_header\r\n";
	unsigned char body[] = {
		0x3f, 0xc0, 0, 0, 0xc0, 0, 0, 0, 0x3e, 0x80, 0, 0, 0x01, 0x02,
		0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
		0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff,
		0, 3, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 0,
	};
	size_t n = strlen(head) + sizeof body;
	char *buf = malloc(n);
	memcpy(buf, head, strlen(head));
	memcpy(buf + strlen(head), body, sizeof body);
	struct fct_mesh m;
	struct fct_err err;
	int rc = read_mem(&m, buf, n, &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (!rc) {
		CHECK(m.xyz[0] == 1.5 && m.xyz[1] == -2 && m.xyz[2] == 0.25);
		struct fct_prop *q = fct_elem_find(&m.vertex, "q");
		CHECK(q && fct_prop_get(q, 0) == 0x0102 && fct_prop_get(q, 2) == 0xffff);
		CHECK_INT(m.nf, 1);
		CHECK_INT(fct_face_size(&m, 0), 3);
		CHECK(m.fvert[0] == 2 && m.fvert[1] == 1 && m.fvert[2] == 0);
		CHECK(m.fcount_type == FCT_UINT16 && m.findex_type == FCT_UINT32);
	}
	fct_mesh_free(&m);
	free(buf);
}

static void test_ascii_layouts(void)
{
	/* Rows split over lines and several rows on a line are the same tokens. */
	static const char a[] = "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\n"
		"property double x\nproperty double y\nproperty double z\nelement face 1\n"
		"property list uchar int vertex_indices\nproperty int patch\nend_header\n"
		"0 0 0 1 0\n0\n0.1 0.2 0.3\n3 0 1 2 -1\n";
	struct fct_mesh m;
	struct fct_err err;
	int rc = read_mem(&m, a, strlen(a), &err);
	CHECK_MSG(rc == 0, "%s", err.msg);
	if (!rc) {
		CHECK_INT(m.nv, 3);
		CHECK(m.xyz_type == FCT_FLOAT64 && m.xyz[3] == 1 && m.xyz[6] == 0.1 && m.xyz[8] == 0.3);
		CHECK(fct_prop_get(fct_elem_find(&m.face, "patch"), 0) == -1);
		CHECK_STR(m.comments[0].text, "made by hand");
	}
	fct_mesh_free(&m);
}

static void test_long_polygon(void)
{
	/* A 300-gon no longer fits a uchar count: the writer widens the type. */
	struct fct_mesh m, r;
	struct fct_err err;
	fct_mesh_init(&m);
	uint32_t idx[300];
	for (int i = 0; i < 300; i++) {
		fct_mesh_add_vertex(&m, i, i * i, 0, &err);
		idx[i] = (uint32_t)i;
	}
	fct_mesh_add_face(&m, idx, 300, &err);
	size_t n;
	char *buf = write_mem(&m, FCT_FORMAT_PLY_LE, &n);
	CHECK(strstr(buf, "property list int int vertex_indices") != NULL);
	CHECK(read_mem(&r, buf, n, &err) == 0 && r.nf == 1 && fct_face_size(&r, 0) == 300 && r.fvert[299] == 299);
	fct_mesh_free(&r);
	fct_mesh_free(&m);
	free(buf);
}

/* A mesh of nf <= 20 faces of the given sizes, face f from vertex f on. */
static void faces_of_sizes(struct fct_mesh *m, const uint32_t *sizes, size_t nf)
{
	struct fct_err err;
	fct_mesh_init(m);
	uint32_t idx[320];
	for (int i = 0; i < 320; i++) {
		fct_mesh_add_vertex(m, i, 0, 0, &err);
		idx[i] = (uint32_t)i;
	}
	for (size_t f = 0; f < nf; f++)
		fct_mesh_add_face(m, idx + f, sizes[f], &err);
}

static void test_face_sizes(void)
{
	/* The writer's triangle test goes four faces a step, then one: a
	 * quad among triangles in either part keeps its size, and a 300-gon
	 * its wider count type. */
	static const uint32_t mixed[] = {3, 3, 3, 3, 4, 3, 3, 3, 3},
		big_tail[] = {3, 3, 3, 3, 3, 3, 3, 3, 3, 300},
		big_lane[] = {3, 3, 300, 3, 3, 3, 3, 3, 3},
		big_lane0[] = {3, 3, 3, 3, 300, 3, 3, 3, 3},
		tail_pair[] = {3, 3, 3, 3, 3, 3, 3, 3, 3, 4};
	static const struct { const uint32_t *sizes; size_t nf; int uchar; } cases[] = {
		{mixed, 9, 1}, {big_tail, 10, 0}, {big_lane, 9, 0}, {big_lane0, 9, 0}, {tail_pair, 10, 1},
	};
	for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
		struct fct_mesh m, r;
		struct fct_err err;
		faces_of_sizes(&m, cases[c].sizes, cases[c].nf);
		size_t n;
		char *buf = write_mem(&m, FCT_FORMAT_PLY_LE, &n);
		CHECK_INT(strstr(buf, "property list uchar int vertex_indices") != NULL, cases[c].uchar);
		int same = read_mem(&r, buf, n, &err) == 0 && r.nf == cases[c].nf;
		for (size_t f = 0; same && f < r.nf; f++)
			same = fct_face_size(&r, f) == cases[c].sizes[f] && r.fvert[r.fstart[f]] == f;
		CHECK_MSG(same, "case %zu: face sizes read back", c);
		fct_mesh_free(&r);
		fct_mesh_free(&m);
		free(buf);
	}
}

static void test_hostile_stream(void)
{
	/* Unknown size (a stream): a lying count must fail at the end of the
	 * data, after allocating only in proportion to what was read. */
	static const char h[] = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\n"
		"property float x\nproperty float y\nproperty float z\nend_header\n";
	char buf[sizeof h - 1 + 120] = {0};
	memcpy(buf, h, sizeof h - 1);
	struct fct_mesh m;
	struct fct_err err;
	CHECK(read_mem(&m, buf, sizeof buf, &err) == -1);
	CHECK_MSG(strstr(err.msg, "element vertex 10: unexpected end of file") != NULL, "%s", err.msg);
	CHECK_MSG(!strncmp(err.msg, "mem: byte ", 10), "binary errors give the byte offset: %s", err.msg);
}

static void test_header_comments(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	struct fct_camera cam = {FCT_CAMERA_PINHOLE, 640, 480, 585, 586, 320, 240.5, 0, 0}, got;
	CHECK(fct_header_set_camera(&m, &cam, &err) == 0);
	CHECK(fct_header_camera(&m, &got, &err) == 1);
	CHECK(got.kind == FCT_CAMERA_PINHOLE && got.width == 640 && got.fy == 586 && got.cy == 240.5);
	double pose[12] = {0, -1, 0, 0.1, 1, 0, 0, 1.0 / 3, 0, 0, 1, -2}, p2[12];
	CHECK(fct_header_set_pose(&m, pose, &err) == 0);
	CHECK(fct_header_pose(&m, p2, &err) == 1 && !memcmp(pose, p2, sizeof pose));
	CHECK(fct_header_set_texture(&m, 0, "a b.png", &err) == 0);
	CHECK(fct_header_set_texture(&m, 1, "c.png", &err) == 0);
	CHECK_INT(fct_header_texture_count(&m), 2);
	CHECK_STR(fct_header_texture(&m, 0), "a b.png");
	CHECK(fct_header_set_texture(&m, 0, "d.png", &err) == 0);
	CHECK_STR(fct_header_texture(&m, 0), "d.png");
	CHECK_STR(fct_header_texture(&m, 1), "c.png");
	char *argv[] = {"-t", "0.5", "in file.ply"};
	CHECK(fct_header_add_provenance(&m, "simpchain", 3, argv, &err) == 0);
	CHECK_STR(m.comments[m.ncomments - 1].text, "facet simpchain -t 0.5 in_file.ply");
	struct fct_camera cyl = {FCT_CAMERA_CYLINDRICAL, 4096, 1024, 0, 0, 0, 511.5, 651.9, 0.25};
	CHECK(fct_header_set_camera(&m, &cyl, &err) == 0);
	CHECK(fct_header_camera(&m, &got, &err) == 1 && got.kind == FCT_CAMERA_CYLINDRICAL &&
	      got.f == 651.9 && got.theta0 == 0.25 && got.cy == 511.5);
	CHECK_INT(fct_header_texture_count(&m), 2);
	fct_mesh_free(&m);
	fct_mesh_init(&m);
	fct_mesh_add_comment(&m, "pose 1 2 3", 0, &err);
	CHECK(fct_header_pose(&m, p2, &err) == -1);
	fct_mesh_free(&m);
}

static void test_gather(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	for (int i = 0; i < 4; i++)
		fct_mesh_add_vertex(&m, i, 0, 0, &err);
	struct fct_prop *c = fct_elem_add_scalar(&m.vertex, "confidence", FCT_FLOAT32, &err);
	for (int i = 0; i < 4; i++)
		fct_prop_set(c, (size_t)i, i * 10);
	uint32_t f0[3] = {0, 1, 2}, f1[3] = {1, 2, 3};
	fct_mesh_add_face(&m, f0, 3, &err);
	fct_mesh_add_face(&m, f1, 3, &err);
	size_t keep[3] = {3, 2, 1};  /* drop vertex 0: face 0 goes, face 1 is renumbered */
	CHECK(fct_mesh_gather_vertices(&m, keep, 3, &err) == 0);
	CHECK_INT(m.nv, 3);
	CHECK_INT(m.nf, 1);
	CHECK(m.xyz[0] == 3 && fct_prop_get(c = fct_elem_find(&m.vertex, "confidence"), 0) == 30);
	CHECK(m.fvert[0] == 2 && m.fvert[1] == 1 && m.fvert[2] == 0);
	struct fct_mesh copy;
	CHECK(fct_mesh_copy(&copy, &m, &err) == 0 && same_mesh(&copy, &m));
	fct_mesh_free(&copy);
	fct_mesh_free(&m);
}

/* A triangle mesh larger than the writer's buffer, with scalar columns of
 * 1, 2, 4 and 8 bytes on vertices and faces: the binary rows it writes a
 * chunk at a time, column by column, hold the values where a row-by-row
 * layout puts them (checked byte by byte at rows in several chunks), and
 * read back the same from both byte orders. */
static void test_chunked_rows(void)
{
	struct fct_mesh m, r;
	struct fct_err err;
	fct_mesh_init(&m);
	size_t nv = 30000, nf = 40000;
	CHECK(fct_mesh_set_vertex_count(&m, nv, &err) == 0 && fct_mesh_set_triangle_count(&m, nf, &err) == 0);
	struct fct_prop *q = fct_elem_add_scalar(&m.vertex, "q", FCT_UINT8, &err);
	struct fct_prop *h = fct_elem_add_scalar(&m.vertex, "h", FCT_INT16, &err);
	struct fct_prop *d = fct_elem_add_scalar(&m.vertex, "d", FCT_FLOAT64, &err);
	q = fct_elem_find(&m.vertex, "q"), h = fct_elem_find(&m.vertex, "h");
	struct fct_prop *lab = fct_elem_add_scalar(&m.face, "label", FCT_INT32, &err);
	for (size_t v = 0; v < nv; v++) {
		m.xyz[3 * v] = v * 0.25, m.xyz[3 * v + 1] = -(double)v, m.xyz[3 * v + 2] = 1.5;
		((uint8_t *)q->data)[v] = (uint8_t)v;
		((int16_t *)h->data)[v] = (int16_t)(v - 15000);
		((double *)d->data)[v] = v / 3.0;
	}
	for (size_t f = 0; f < nf; f++) {
		for (int k = 0; k < 3; k++)
			m.fvert[3 * f + k] = (uint32_t)((f + (size_t)k) % nv);
		((int32_t *)lab->data)[f] = -(int32_t)f;
	}
	size_t n;
	char *buf = write_mem(&m, FCT_FORMAT_PLY_LE, &n);
	const char *body = strstr(buf, "end_header\n") + 11;
	size_t vs = 12 + 1 + 2 + 8, fs = 13 + 4;
	CHECK_INT(n - (size_t)(body - buf), nv * vs + nf * fs);
	static const size_t rows[] = {0, 1, 2849, 2850, 12345, 29999};
	for (size_t k = 0; k < sizeof rows / sizeof *rows; k++) {
		size_t v = rows[k];
		unsigned char want[23];
		float xyz[3] = {(float)(v * 0.25), -(float)v, 1.5f};
		int16_t hv = (int16_t)(v - 15000);
		double dv = v / 3.0;
		memcpy(want, xyz, 12);
		want[12] = (uint8_t)v;
		memcpy(want + 13, &hv, 2);
		memcpy(want + 15, &dv, 8);
		CHECK_MSG(!memcmp(body + v * vs, want, vs), "vertex %zu", v);
		size_t f = rows[k] + 10000;
		unsigned char fw[17];
		uint32_t idx[3] = {(uint32_t)(f % nv), (uint32_t)((f + 1) % nv), (uint32_t)((f + 2) % nv)};
		int32_t lv = -(int32_t)f;
		fw[0] = 3;
		memcpy(fw + 1, idx, 12);
		memcpy(fw + 13, &lv, 4);
		CHECK_MSG(!memcmp(body + nv * vs + f * fs, fw, fs), "face %zu", f);
	}
	for (int fmt = FCT_FORMAT_PLY_LE; fmt <= FCT_FORMAT_PLY_BE; fmt++) {
		char *b = fmt == FCT_FORMAT_PLY_LE ? buf : write_mem(&m, (enum fct_format)fmt, &n);
		int rc = read_mem(&r, b, n, &err);
		CHECK_MSG(rc == 0 && same_mesh(&m, &r), "format %d: round trip differs", fmt);
		fct_mesh_free(&r);
		if (b != buf)
			free(b);
	}
	free(buf);
	fct_mesh_free(&m);
}

int main(void)
{
	test_round_trips();
	test_big_endian_bytes();
	test_ascii_layouts();
	test_long_polygon();
	test_face_sizes();
	test_hostile_stream();
	test_header_comments();
	test_gather();
	test_chunked_rows();
	CHECK_DONE();
}
