/* test_mesh - what mesh.h promises, each with values worked out by hand:
 * the type table (sizes, names, both spellings parsed); an empty mesh
 * owning nothing and freed twice; vertices and faces appended (indices,
 * compressed rows, extra columns' new rows zeroed); bulk counts; scalar
 * columns (zero-filled, kept when asked again with their type, replaced
 * with another), per-corner lists in the faces' vertex order, other
 * elements, removal; values set with rounding to the column's type and
 * saturation of integers, NaN as 0; resize (new rows zeroed, list rows
 * empty) and gather of rows with repeats; keeping vertices (faces
 * renumbered, a face on a dropped vertex dropped with its properties) and
 * faces; columns sharing one block through all of that;
 * append (indices shifted, columns in step, double positions kept,
 * a difference named and dst unchanged); double positions chosen only
 * when float would move a coordinate by more than the resolution; a deep
 * copy that shares nothing; comments in order. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/mesh.h"

static void test_types(void)
{
	static const struct {
		enum fct_type t;
		size_t size;
		const char *name, *alias;
	} want[] = {
		{ FCT_INT8, 1, "char", "int8" },      { FCT_UINT8, 1, "uchar", "uint8" },
		{ FCT_INT16, 2, "short", "int16" },   { FCT_UINT16, 2, "ushort", "uint16" },
		{ FCT_INT32, 4, "int", "int32" },     { FCT_UINT32, 4, "uint", "uint32" },
		{ FCT_FLOAT32, 4, "float", "float32" }, { FCT_FLOAT64, 8, "double", "float64" },
	};
	for (size_t k = 0; k < sizeof want / sizeof *want; k++) {
		CHECK_INT(fct_type_size(want[k].t), want[k].size);
		CHECK_STR(fct_type_name(want[k].t), want[k].name);
		CHECK_INT(fct_type_parse(want[k].name), want[k].t);
		CHECK_INT(fct_type_parse(want[k].alias), want[k].t);
	}
	CHECK_INT(fct_type_size(FCT_NONE), 0);
	CHECK_INT(fct_type_parse("float16"), FCT_NONE);
	CHECK_INT(fct_type_parse(""), FCT_NONE);
	CHECK_INT(fct_type_parse("Float"), FCT_NONE);
}

/* A square (0 1 2 3) and a triangle (1 4 2) over five vertices. */
static void two_faces(struct fct_mesh *m)
{
	struct fct_err err;
	static const double v[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 2, 0.5, 0 } };
	fct_mesh_init(m);
	for (int i = 0; i < 5; i++)
		CHECK_INT(fct_mesh_add_vertex(m, v[i][0], v[i][1], v[i][2], &err), i);
	static const uint32_t quad[4] = { 0, 1, 2, 3 }, tri[3] = { 1, 4, 2 };
	CHECK_INT(fct_mesh_add_face(m, quad, 4, &err), 0);
	CHECK_INT(fct_mesh_add_face(m, tri, 3, &err), 1);
}

static void test_build(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	CHECK(m.nv == 0 && m.nf == 0 && m.xyz == NULL && m.fstart == NULL && m.nelems == 0);
	CHECK_INT(m.xyz_type, FCT_FLOAT32);
	CHECK_INT(m.fcount_type, FCT_UINT8);
	CHECK_INT(m.findex_type, FCT_INT32);
	CHECK_INT(m.has_faces, 0);
	fct_mesh_free(&m);
	fct_mesh_free(&m);   /* an emptied mesh frees again */
	fct_mesh_free(NULL);

	two_faces(&m);
	CHECK_INT(m.nv, 5);
	CHECK_INT(m.nf, 2);
	CHECK_INT(m.has_faces, 1);
	CHECK_INT(m.fstart[0], 0);
	CHECK_INT(m.fstart[1], 4);
	CHECK_INT(m.fstart[2], 7);
	CHECK_INT(fct_face_size(&m, 0), 4);
	CHECK_INT(fct_face_size(&m, 1), 3);
	CHECK_INT(m.fvert[5], 4);
	CHECK(m.xyz[3 * 4] == 2 && m.xyz[3 * 4 + 1] == 0.5);
	/* extra columns: existing rows zero, new rows zero */
	struct fct_prop *q = fct_elem_add_scalar(&m.vertex, "quality", FCT_FLOAT32, &err);
	CHECK(q != NULL && q->count_type == FCT_NONE);
	CHECK_INT(m.vertex.count, 5);
	fct_prop_set(q, 4, 7.5);
	CHECK_INT(fct_mesh_add_vertex(&m, 3, 3, 3, &err), 5);
	q = fct_elem_find(&m.vertex, "quality");
	CHECK(fct_prop_get(q, 4) == 7.5);
	CHECK(fct_prop_get(q, 0) == 0 && fct_prop_get(q, 5) == 0);
	CHECK_INT(m.vertex.count, 6);
	struct fct_prop *lab = fct_elem_add_scalar(&m.face, "label", FCT_INT32, &err);
	fct_prop_set(lab, 1, -3);
	static const uint32_t tri2[3] = { 2, 4, 5 };
	CHECK_INT(fct_mesh_add_face(&m, tri2, 3, &err), 2);
	lab = fct_elem_find(&m.face, "label");
	CHECK(fct_prop_get(lab, 1) == -3 && fct_prop_get(lab, 2) == 0);
	CHECK_INT(m.face.count, 3);
	CHECK_INT(m.fstart[3], 10);
	fct_mesh_free(&m);
	CHECK(m.nv == 0 && m.nf == 0 && m.vertex.nprops == 0 && m.face.nprops == 0);

	/* bulk counts: triangles' rows preset, extra columns zeroed */
	fct_mesh_init(&m);
	fct_elem_add_scalar(&m.vertex, "w", FCT_UINT16, &err);
	CHECK_INT(fct_mesh_set_vertex_count(&m, 4, &err), 0);
	CHECK_INT(m.nv, 4);
	CHECK_INT(m.vertex.count, 4);
	CHECK(fct_prop_get(fct_elem_find(&m.vertex, "w"), 3) == 0);
	CHECK_INT(fct_mesh_set_triangle_count(&m, 2, &err), 0);
	CHECK_INT(m.nf, 2);
	CHECK_INT(m.face.count, 2);
	CHECK_INT(m.has_faces, 1);
	CHECK(m.fstart[0] == 0 && m.fstart[1] == 3 && m.fstart[2] == 6);
	CHECK_INT(fct_mesh_set_triangle_count(&m, (size_t)UINT32_MAX, &err), -1);
	CHECK_STR(err.msg, "too many faces");
	fct_mesh_free(&m);

	/* the same in huge pages: 200k vertices (4.8 MB of xyz) and 400k
	 * triangles, and a float column added after them, zeroed */
	fct_mesh_init(&m);
	CHECK_INT(fct_mesh_set_counts_big(&m, 200000, 400000, &err), 0);
	CHECK(m.nv == 200000 && m.vertex.count == 200000 && m.nf == 400000 && m.face.count == 400000);
	CHECK(m.xyz_cap == 600000 && m.fstart_cap == 400001 && m.fvert_cap == 1200000);
	CHECK(m.fstart[0] == 0 && m.fstart[400000] == 1200000);
	m.xyz[599999] = 1, m.fvert[1199999] = 2;
	static const char *const st[] = { "s", "t" };
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, st, 2, FCT_FLOAT32, &err), 0);
	struct fct_prop *s = fct_elem_find(&m.vertex, "s"), *t = fct_elem_find(&m.vertex, "t");
	CHECK(s != NULL && s->cap == 200000 && t != NULL && t->cap == 200000);
	CHECK(s->block != NULL && s->block == t->block);
	CHECK((float *)t->data == (float *)s->data + 200000);   /* one block, one after the other */
	CHECK(fct_prop_get(s, 0) == 0 && fct_prop_get(s, 199999) == 0 && fct_prop_get(t, 199999) == 0);
	fct_prop_set(s, 199999, 0.5);
	fct_prop_set(t, 0, 0.25);
	CHECK(fct_prop_get(fct_elem_find(&m.vertex, "s"), 199999) == 0.5);
	CHECK(fct_prop_get(s, 199999) == 0.5 && fct_prop_get(t, 0) == 0.25);
	CHECK_INT(fct_mesh_set_counts_big(&m, 10, (size_t)UINT32_MAX, &err), -1);
	CHECK_STR(err.msg, "too many faces");
	fct_mesh_free(&m);
}

/* Columns in one block (fct_elem_add_scalars_big) behave as columns of
 * their own through every change: grown (copied out, values kept, the
 * other still in the block), replaced, gathered, appended to, copied,
 * removed and freed in any order (ASan and LSan in make sanitize see a
 * double free or a leak). */
static void test_block_columns(void)
{
	struct fct_mesh m, c;
	struct fct_err err;
	static const char *const uvw[] = { "u", "v", "w" };
	two_faces(&m);
	fct_elem_add_scalar(&m.vertex, "v", FCT_INT8, &err);   /* replaced by the block's */
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, uvw, 3, FCT_INT32, &err), 0);
	CHECK_INT(m.vertex.nprops, 3);
	CHECK_STR(m.vertex.props[0].name, "u");
	CHECK_STR(m.vertex.props[2].name, "w");
	struct fct_prop *u = fct_elem_find(&m.vertex, "u"), *v = fct_elem_find(&m.vertex, "v");
	CHECK(v->type == FCT_INT32 && v->block == u->block && (int32_t *)v->data == (int32_t *)u->data + 5);
	for (size_t i = 0; i < 5; i++) {
		fct_prop_set(u, i, (double)i);
		fct_prop_set(v, i, 10.0 + (double)i);
		fct_prop_set(fct_elem_find(&m.vertex, "w"), i, 20.0 + (double)i);
	}
	/* a copy shares nothing */
	CHECK_INT(fct_mesh_copy(&c, &m, &err), 0);
	CHECK(fct_elem_find(&c.vertex, "u")->block == NULL);
	CHECK(fct_prop_get(fct_elem_find(&c.vertex, "w"), 4) == 24);
	fct_mesh_free(&c);
	/* a new vertex grows every column: each its own copy, values kept,
	 * the new row zeroed */
	CHECK_INT(fct_mesh_add_vertex(&m, 0, 0, 0, &err), 5);
	u = fct_elem_find(&m.vertex, "u"), v = fct_elem_find(&m.vertex, "v");
	CHECK(u->block == NULL && v->block == NULL);
	CHECK(fct_prop_get(u, 4) == 4 && fct_prop_get(v, 4) == 14 && fct_prop_get(v, 5) == 0);
	CHECK(fct_prop_get(fct_elem_find(&m.vertex, "w"), 3) == 23);
	fct_mesh_free(&m);

	/* gathered, one removed, the rest freed with the mesh */
	two_faces(&m);
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, uvw, 3, FCT_FLOAT32, &err), 0);
	for (size_t i = 0; i < 5; i++)
		fct_prop_set(fct_elem_find(&m.vertex, "v"), i, 0.5 * (double)i);
	size_t keep[2] = { 3, 1 };
	CHECK_INT(fct_elem_gather(&m.vertex, keep, 2, &err), 0);
	v = fct_elem_find(&m.vertex, "v");
	CHECK(v->block == NULL && fct_prop_get(v, 0) == 1.5 && fct_prop_get(v, 1) == 0.5);
	fct_elem_remove(&m.vertex, "u");
	fct_mesh_free(&m);

	/* removed one by one, the block freed with the last; appended to */
	two_faces(&m);
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, uvw, 2, FCT_UINT16, &err), 0);
	fct_elem_remove(&m.vertex, "v");
	fct_prop_set(fct_elem_find(&m.vertex, "u"), 2, 7);
	struct fct_mesh b;
	two_faces(&b);
	fct_prop_set(fct_elem_add_scalar(&b.vertex, "u", FCT_UINT16, &err), 0, 9);
	CHECK_INT(fct_mesh_append(&m, &b, &err), 0);
	u = fct_elem_find(&m.vertex, "u");
	CHECK(u->block == NULL && fct_prop_get(u, 2) == 7 && fct_prop_get(u, 5) == 9);
	fct_elem_remove(&m.vertex, "u");
	CHECK_INT(m.vertex.nprops, 0);
	fct_mesh_free(&m);
	fct_mesh_free(&b);

	/* no rows: columns without data, grown later; none asked: nothing */
	fct_mesh_init(&m);
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, uvw, 3, FCT_FLOAT64, &err), 0);
	CHECK(m.vertex.nprops == 3 && m.vertex.props[1].cap == 0);
	CHECK_INT(fct_elem_add_scalars_big(&m.vertex, uvw, 0, FCT_FLOAT64, &err), 0);
	CHECK_INT(m.vertex.nprops, 3);
	CHECK_INT(fct_mesh_add_vertex(&m, 1, 2, 3, &err), 0);
	CHECK(fct_prop_get(fct_elem_find(&m.vertex, "w"), 0) == 0);
	fct_mesh_free(&m);
}

static void test_props(void)
{
	struct fct_mesh m;
	struct fct_err err;
	two_faces(&m);
	struct fct_prop *a = fct_elem_add_scalar(&m.vertex, "a", FCT_UINT8, &err);
	fct_prop_set(a, 2, 9);
	/* asked again with its type: the same column, values kept */
	a = fct_elem_add_scalar(&m.vertex, "a", FCT_UINT8, &err);
	CHECK(fct_prop_get(a, 2) == 9);
	CHECK_INT(m.vertex.nprops, 1);
	/* with another type: replaced, zeroed */
	fct_elem_add_scalar(&m.vertex, "b", FCT_INT16, &err);
	a = fct_elem_add_scalar(&m.vertex, "a", FCT_FLOAT64, &err);
	CHECK_INT(a->type, FCT_FLOAT64);
	CHECK(fct_prop_get(a, 2) == 0);
	CHECK_INT(m.vertex.nprops, 2);
	CHECK_STR(m.vertex.props[0].name, "b");   /* the replacement goes last */
	CHECK_STR(m.vertex.props[1].name, "a");
	CHECK(fct_elem_find(&m.vertex, "c") == NULL);
	fct_elem_remove(&m.vertex, "c");   /* absent: nothing happens */
	fct_elem_remove(&m.vertex, "b");
	CHECK_INT(m.vertex.nprops, 1);
	CHECK(fct_elem_find(&m.vertex, "b") == NULL);
	CHECK(fct_elem_find(&m.vertex, "a") == &m.vertex.props[0]);

	/* per-corner lists: 2 values per corner, rows by the faces' corners */
	struct fct_prop *tc = fct_mesh_add_corner_list(&m, "texcoord", FCT_FLOAT32, 2, &err);
	CHECK(tc != NULL);
	CHECK_INT(tc->count_type, FCT_UINT8);
	CHECK(tc->off[0] == 0 && tc->off[1] == 8 && tc->off[2] == 14);
	float *d = tc->data;
	size_t zero = 0;
	for (size_t i = 0; i < 14; i++)
		zero += d[i] == 0;
	CHECK_INT(zero, 14);
	d[9] = 0.25f;   /* face 1, corner 0 (vertex 1), t */
	tc = fct_mesh_add_corner_list(&m, "texcoord", FCT_FLOAT64, 1, &err);
	CHECK_INT(m.face.nprops, 1);
	CHECK_INT(tc->type, FCT_FLOAT64);
	CHECK(tc->off[1] == 4 && tc->off[2] == 7);

	/* other elements */
	struct fct_elem *e = fct_mesh_add_elem(&m, "edge", 3, &err);
	CHECK(e != NULL && e->count == 3 && e->nprops == 0);
	fct_mesh_add_elem(&m, "plane", 1, &err);
	CHECK_INT(m.nelems, 2);
	CHECK(fct_mesh_find_elem(&m, "edge") == &m.elems[0]);
	CHECK(fct_mesh_find_elem(&m, "plane") == &m.elems[1]);
	CHECK(fct_mesh_find_elem(&m, "vertex") == NULL);
	fct_mesh_remove_elem(&m, "edge");
	fct_mesh_remove_elem(&m, "none");
	CHECK_INT(m.nelems, 1);
	CHECK_STR(m.elems[0].name, "plane");
	fct_mesh_free(&m);
}

/* Values are rounded to the column's type; integers saturate; NaN is 0. */
static void test_values(void)
{
	struct fct_elem e = { 0 };
	struct fct_err err;
	e.count = 1;
	static const struct {
		enum fct_type t;
		double in, out;
	} c[] = {
		{ FCT_UINT8, 300, 255 },     { FCT_UINT8, -5, 0 },         { FCT_UINT8, 2.5, 2 },
		{ FCT_UINT8, 3.5, 4 },       { FCT_UINT8, 2.6, 3 },        { FCT_INT8, -200, -128 },
		{ FCT_INT8, 127.4, 127 },    { FCT_INT16, -40000, -32768 }, { FCT_UINT16, 70000, 65535 },
		{ FCT_INT32, 3e9, 2147483647 }, { FCT_INT32, -3e9, -2147483648.0 },
		{ FCT_UINT32, 5e9, 4294967295.0 }, { FCT_UINT32, -1, 0 },  { FCT_INT32, -2.5, -2 },
		{ FCT_INT32, NAN, 0 },       { FCT_UINT8, HUGE_VAL, 255 },  { FCT_FLOAT32, 0.1, (float)0.1 },
		{ FCT_FLOAT32, 16777217, 16777216 }, { FCT_FLOAT64, 0.1, 0.1 },
	};
	for (size_t k = 0; k < sizeof c / sizeof *c; k++) {
		struct fct_prop *p = fct_elem_add_scalar(&e, "v", c[k].t, &err);
		fct_prop_set(p, 0, c[k].in);
		CHECK_MSG(fct_prop_get(p, 0) == c[k].out, "%s %.17g: got %.17g, want %.17g", fct_type_name(c[k].t),
		          c[k].in, fct_prop_get(p, 0), c[k].out);
	}
	struct fct_prop *p = fct_elem_add_scalar(&e, "v", FCT_FLOAT64, &err);
	fct_prop_set(p, 0, NAN);
	CHECK(isnan(fct_prop_get(p, 0)));
	fct_elem_remove(&e, "v");
	CHECK_INT(e.nprops, 0);
	free(e.props);
}

/* Resize zeroes new rows and leaves new list rows empty; gather keeps rows
 * in the order asked, repeats included, lists with them. */
static void test_rows(void)
{
	struct fct_mesh m;
	struct fct_err err;
	two_faces(&m);
	struct fct_prop *c = fct_elem_add_scalar(&m.face, "c", FCT_INT32, &err);
	fct_prop_set(c, 0, 10);
	fct_prop_set(c, 1, 11);
	struct fct_prop *l = fct_mesh_add_corner_list(&m, "k", FCT_UINT8, 1, &err);
	uint8_t *ld = l->data;
	for (int i = 0; i < 7; i++)
		ld[i] = (uint8_t)(100 + i);   /* face 0: 100..103, face 1: 104..106 */
	size_t src[3] = { 1, 1, 0 };
	CHECK_INT(fct_elem_gather(&m.face, src, 3, &err), 0);
	c = fct_elem_find(&m.face, "c");
	l = fct_elem_find(&m.face, "k");
	CHECK_INT(m.face.count, 3);
	CHECK(fct_prop_get(c, 0) == 11 && fct_prop_get(c, 1) == 11 && fct_prop_get(c, 2) == 10);
	CHECK(l->off[0] == 0 && l->off[1] == 3 && l->off[2] == 6 && l->off[3] == 10);
	ld = l->data;
	CHECK(ld[0] == 104 && ld[3] == 104 && ld[5] == 106 && ld[6] == 100 && ld[9] == 103);
	CHECK_INT(fct_elem_resize(&m.face, 1, &err), 0);
	CHECK_INT(fct_elem_resize(&m.face, 4, &err), 0);
	c = fct_elem_find(&m.face, "c");
	l = fct_elem_find(&m.face, "k");
	CHECK(fct_prop_get(c, 0) == 11 && fct_prop_get(c, 1) == 0 && fct_prop_get(c, 3) == 0);
	CHECK(l->off[1] == 3 && l->off[2] == 3 && l->off[4] == 3);
	/* face element and faces disagree now; only the columns were asked */
	fct_mesh_free(&m);
}

static void test_gather_mesh(void)
{
	struct fct_mesh m;
	struct fct_err err;
	two_faces(&m);
	struct fct_prop *id = fct_elem_add_scalar(&m.vertex, "id", FCT_INT32, &err);
	for (int i = 0; i < 5; i++)
		fct_prop_set(id, (size_t)i, 10 * i);
	struct fct_prop *fid = fct_elem_add_scalar(&m.face, "fid", FCT_INT32, &err);
	fct_prop_set(fid, 0, 7);
	fct_prop_set(fid, 1, 8);
	/* keep vertices 4, 2, 1 (dropping 0 and 3): the square goes, the
	 * triangle 1 4 2 becomes 2 0 1 */
	size_t keep[3] = { 4, 2, 1 };
	CHECK_INT(fct_mesh_gather_vertices(&m, keep, 3, &err), 0);
	CHECK_INT(m.nv, 3);
	CHECK_INT(m.nf, 1);
	CHECK_INT(fct_face_size(&m, 0), 3);
	CHECK(m.fvert[0] == 2 && m.fvert[1] == 0 && m.fvert[2] == 1);
	CHECK(m.xyz[0] == 2 && m.xyz[1] == 0.5 && m.xyz[3] == 1 && m.xyz[4] == 1 && m.xyz[6] == 1 && m.xyz[7] == 0);
	id = fct_elem_find(&m.vertex, "id");
	CHECK(fct_prop_get(id, 0) == 40 && fct_prop_get(id, 1) == 20 && fct_prop_get(id, 2) == 10);
	CHECK(fct_prop_get(fct_elem_find(&m.face, "fid"), 0) == 8);
	CHECK_INT(m.vertex.count, 3);
	CHECK_INT(m.face.count, 1);
	fct_mesh_free(&m);

	/* keep faces 1, 0, 1 */
	two_faces(&m);
	fid = fct_elem_add_scalar(&m.face, "fid", FCT_INT32, &err);
	fct_prop_set(fid, 0, 7);
	fct_prop_set(fid, 1, 8);
	size_t fk[3] = { 1, 0, 1 };
	CHECK_INT(fct_mesh_gather_faces(&m, fk, 3, &err), 0);
	CHECK_INT(m.nf, 3);
	CHECK_INT(m.nv, 5);
	CHECK(m.fstart[1] == 3 && m.fstart[2] == 7 && m.fstart[3] == 10);
	CHECK(m.fvert[0] == 1 && m.fvert[1] == 4 && m.fvert[3] == 0 && m.fvert[6] == 3 && m.fvert[9] == 2);
	fid = fct_elem_find(&m.face, "fid");
	CHECK(fct_prop_get(fid, 0) == 8 && fct_prop_get(fid, 1) == 7 && fct_prop_get(fid, 2) == 8);
	fct_mesh_free(&m);
}

static void test_append(void)
{
	struct fct_mesh a, b;
	struct fct_err err;
	two_faces(&a);
	two_faces(&b);
	fct_elem_add_scalar(&a.vertex, "q", FCT_FLOAT32, &err);
	struct fct_prop *q = fct_elem_add_scalar(&b.vertex, "q", FCT_FLOAT32, &err);
	fct_prop_set(q, 3, 0.5);
	b.xyz[0] = 1e7;
	b.xyz_type = FCT_FLOAT64;
	CHECK_INT(fct_mesh_append(&a, &b, &err), 0);
	CHECK_INT(a.nv, 10);
	CHECK_INT(a.nf, 4);
	CHECK_INT(a.vertex.count, 10);
	CHECK_INT(a.face.count, 4);
	CHECK(a.fstart[2] == 7 && a.fstart[3] == 11 && a.fstart[4] == 14);
	CHECK(a.fvert[7] == 5 && a.fvert[10] == 8 && a.fvert[12] == 9);   /* shifted by 5 */
	CHECK(a.xyz[15] == 1e7);
	CHECK_INT(a.xyz_type, FCT_FLOAT64);
	q = fct_elem_find(&a.vertex, "q");
	CHECK(fct_prop_get(q, 8) == 0.5 && fct_prop_get(q, 3) == 0);
	/* a difference is named and leaves dst as it was */
	fct_elem_add_scalar(&b.face, "label", FCT_INT32, &err);
	CHECK_INT(fct_mesh_append(&a, &b, &err), -1);
	CHECK_STR(err.msg, "face property label: not in both meshes alike");
	CHECK_INT(a.nv, 10);
	CHECK_INT(a.nf, 4);
	fct_elem_remove(&b.face, "label");
	fct_elem_add_scalar(&b.vertex, "q", FCT_FLOAT64, &err);   /* q retyped */
	CHECK_INT(fct_mesh_append(&a, &b, &err), -1);
	CHECK_STR(err.msg, "vertex property q: not in both meshes alike");
	CHECK_INT(a.nv, 10);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
	/* into an empty mesh */
	fct_mesh_init(&a);
	two_faces(&b);
	CHECK_INT(fct_mesh_append(&a, &b, &err), 0);
	CHECK(a.nv == 5 && a.nf == 2 && a.has_faces && a.fvert[4] == 1);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
}

/* float's error at |x| is at most |x| 2^-24: 4e6 m moves by up to 0.24 m. */
static void test_precision(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 1, 2, 3, &err);
	CHECK_INT(fct_mesh_keep_precision(&m, 1e-3), 0);
	CHECK_INT(m.xyz_type, FCT_FLOAT32);
	fct_mesh_add_vertex(&m, 0, -4e6, 0, &err);
	CHECK_INT(fct_mesh_keep_precision(&m, 0.5), 0);     /* 0.238 <= 0.5 */
	CHECK_INT(m.xyz_type, FCT_FLOAT32);
	CHECK_INT(fct_mesh_keep_precision(&m, 0), 0);       /* no resolution: nothing */
	CHECK_INT(fct_mesh_keep_precision(&m, 1e-3), 1);
	CHECK_INT(m.xyz_type, FCT_FLOAT64);
	fct_mesh_free(&m);
}

static void test_copy_comments(void)
{
	struct fct_mesh a, b;
	struct fct_err err;
	two_faces(&a);
	struct fct_prop *q = fct_elem_add_scalar(&a.vertex, "q", FCT_UINT8, &err);
	fct_prop_set(q, 1, 5);
	fct_mesh_add_corner_list(&a, "tc", FCT_FLOAT32, 2, &err);
	struct fct_elem *e = fct_mesh_add_elem(&a, "plane", 2, &err);
	struct fct_prop *d = fct_elem_add_scalar(e, "d", FCT_FLOAT64, &err);
	fct_prop_set(d, 1, -2.5);
	CHECK_INT(fct_mesh_add_comment(&a, "camera 1 2 3", 0, &err), 0);
	CHECK_INT(fct_mesh_add_comment(&a, "made by hand", 1, &err), 0);
	a.fcount_type = FCT_UINT16;
	CHECK_INT(a.ncomments, 2);
	CHECK_STR(a.comments[0].text, "camera 1 2 3");
	CHECK(a.comments[0].obj_info == 0 && a.comments[1].obj_info == 1);

	CHECK_INT(fct_mesh_copy(&b, &a, &err), 0);
	CHECK(b.nv == 5 && b.nf == 2 && b.xyz != a.xyz && b.fvert != a.fvert);
	CHECK(!memcmp(b.xyz, a.xyz, 15 * sizeof *b.xyz));
	CHECK(!memcmp(b.fvert, a.fvert, 7 * sizeof *b.fvert));
	CHECK_INT(b.fcount_type, FCT_UINT16);
	CHECK_INT(b.has_faces, 1);
	struct fct_prop *bq = fct_elem_find(&b.vertex, "q");
	CHECK(bq && bq != q && fct_prop_get(bq, 1) == 5);
	struct fct_prop *btc = fct_elem_find(&b.face, "tc");
	CHECK(btc && btc->count_type == FCT_UINT8 && btc->off[2] == 14);
	struct fct_elem *be = fct_mesh_find_elem(&b, "plane");
	CHECK(be && be->count == 2 && fct_prop_get(fct_elem_find(be, "d"), 1) == -2.5);
	CHECK_INT(b.ncomments, 2);
	CHECK_STR(b.comments[1].text, "made by hand");
	CHECK(b.comments[1].text != a.comments[1].text);
	/* changing the copy leaves the original */
	fct_prop_set(bq, 1, 6);
	b.xyz[0] = 9;
	CHECK(fct_prop_get(q, 1) == 5 && a.xyz[0] == 0);
	fct_mesh_free(&a);
	CHECK_INT(b.nv, 5);   /* b survives a's release */
	CHECK(fct_prop_get(fct_elem_find(&b.vertex, "q"), 1) == 6);
	fct_mesh_free(&b);
	/* a copy of an empty mesh */
	fct_mesh_init(&a);
	CHECK_INT(fct_mesh_copy(&b, &a, &err), 0);
	CHECK(b.nv == 0 && b.nf == 0 && b.xyz == NULL);
	fct_mesh_free(&b);
}

int main(void)
{
	test_types();
	test_build();
	test_props();
	test_block_columns();
	test_values();
	test_rows();
	test_gather_mesh();
	test_append();
	test_precision();
	test_copy_comments();
	CHECK_DONE();
}
