/* test_meshio - reading and writing meshes by name, by hand: the format
 * names and the format a path gets; which files start like an image; a
 * mesh written as binary and ascii PLY and as OBJ and read back (format
 * detected from the content, positions and faces equal); a stream that is
 * neither PLY nor OBJ refused; TextureFile paths rewritten relative to the
 * written file's folder (the caller's mesh untouched), joined to the folder
 * of a file read from elsewhere; a textured OBJ's material library beside
 * it; a file in a folder that does not exist refused, nothing left;
 * fct_mesh_round_xyz: positions rounded to float as a PLY of float x y z
 * holds them, left as they are for a mesh written as double. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "io/header.h"
#include "io/meshio.h"

static char dir[64];

static char *at(const char *name)
{
	static char buf[4][256];
	static int k;
	k = (k + 1) % 4;
	snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
	return buf[k];
}

static void put(const char *path, const void *data, size_t n)
{
	FILE *f = fopen(path, "wb");
	if (!f || fwrite(data, 1, n, f) != n || fclose(f))
		abort();
}

/* A square (0 1 2 3) and a triangle (1 4 2), coordinates exact in float. */
static void two_faces(struct fct_mesh *m)
{
	struct fct_err err;
	static const double v[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0.5 }, { 0, 1, 0 }, { 2, 0.25, -1 } };
	fct_mesh_init(m);
	for (int i = 0; i < 5; i++)
		fct_mesh_add_vertex(m, v[i][0], v[i][1], v[i][2], &err);
	static const uint32_t quad[4] = { 0, 1, 2, 3 }, tri[3] = { 1, 4, 2 };
	fct_mesh_add_face(m, quad, 4, &err);
	fct_mesh_add_face(m, tri, 3, &err);
}

/* Positions and faces of a and b equal (count of differences). */
static size_t differences(const struct fct_mesh *a, const struct fct_mesh *b)
{
	if (a->nv != b->nv || a->nf != b->nf)
		return 1000;
	size_t d = 0;
	for (size_t i = 0; i < 3 * a->nv; i++)
		d += a->xyz[i] != b->xyz[i];
	for (size_t f = 0; f <= a->nf; f++)
		d += a->fstart[f] != b->fstart[f];
	for (size_t k = 0; k < a->fstart[a->nf]; k++)
		d += a->fvert[k] != b->fvert[k];
	return d;
}

static void test_names(void)
{
	CHECK_STR(fct_format_name(FCT_FORMAT_PLY_ASCII), "ply ascii");
	CHECK_STR(fct_format_name(FCT_FORMAT_PLY_LE), "ply binary_little_endian");
	CHECK_STR(fct_format_name(FCT_FORMAT_PLY_BE), "ply binary_big_endian");
	CHECK_STR(fct_format_name(FCT_FORMAT_OBJ), "obj");
	CHECK_INT(fct_format_for_path("a.obj", 0), FCT_FORMAT_OBJ);
	CHECK_INT(fct_format_for_path("a.OBJ", 1), FCT_FORMAT_OBJ);
	CHECK_INT(fct_format_for_path("a.ply", 0), FCT_FORMAT_PLY_LE);
	CHECK_INT(fct_format_for_path("a.ply", 1), FCT_FORMAT_PLY_ASCII);
	CHECK_INT(fct_format_for_path("x.obj/a", 0), FCT_FORMAT_PLY_LE);
	CHECK_INT(fct_format_for_path("-", 1), FCT_FORMAT_PLY_ASCII);
	CHECK_INT(fct_format_for_path(NULL, 0), FCT_FORMAT_PLY_LE);
}

static void test_is_image(void)
{
	put(at("a.png"), "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
	put(at("a.pfm"), "PF\n4 4\n-1\n", 10);
	put(at("a.jpg"), "\xff\xd8\xff\xe0\0\x10JFIF", 10);
	put(at("a.ply"), "ply\nformat ascii 1.0\n", 21);
	put(at("short"), "\x89PN", 3);
	put(at("empty"), "", 0);
	CHECK_INT(fct_path_is_image(at("a.png")), 1);
	CHECK_INT(fct_path_is_image(at("a.pfm")), 1);
	CHECK_INT(fct_path_is_image(at("a.jpg")), 1);
	CHECK_INT(fct_path_is_image(at("a.ply")), 0);
	CHECK_INT(fct_path_is_image(at("short")), 0);
	CHECK_INT(fct_path_is_image(at("empty")), 0);
	CHECK_INT(fct_path_is_image(at("missing")), 0);
}

static void test_round_trip(void)
{
	struct fct_mesh m, r;
	struct fct_err err;
	enum fct_format fmt;
	two_faces(&m);
	static const struct {
		const char *name;
		int ascii;
		enum fct_format fmt;
	} c[] = {
		{ "b.ply", 0, FCT_FORMAT_PLY_LE }, { "t.ply", 1, FCT_FORMAT_PLY_ASCII }, { "o.obj", 0, FCT_FORMAT_OBJ },
	};
	for (size_t k = 0; k < 3; k++) {
		CHECK_INT(fct_mesh_write_file(&m, at(c[k].name), c[k].ascii, &err), 0);
		fmt = (enum fct_format)-1;
		CHECK_INT(fct_mesh_read_file(&r, at(c[k].name), &fmt, &err), 0);
		CHECK_MSG(fmt == c[k].fmt, "%s: format %d", c[k].name, (int)fmt);
		CHECK_MSG(differences(&m, &r) == 0, "%s: %zu differences", c[k].name, differences(&m, &r));
		fct_mesh_free(&r);
	}
	/* big-endian, named explicitly */
	CHECK_INT(fct_mesh_write_file_as(&m, at("be.ply"), FCT_FORMAT_PLY_BE, &err), 0);
	CHECK_INT(fct_mesh_read_file(&r, at("be.ply"), &fmt, &err), 0);
	CHECK_INT(fmt, FCT_FORMAT_PLY_BE);
	CHECK_INT(differences(&m, &r), 0);
	fct_mesh_free(&r);
	/* a stream: OBJ text detected as OBJ */
	static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
	FILE *f = fmemopen((void *)obj, sizeof obj - 1, "rb");
	CHECK_INT(fct_mesh_read_stream(&r, f, "s.obj", NULL, &fmt, &err), 0);
	fclose(f);
	CHECK_INT(fmt, FCT_FORMAT_OBJ);
	CHECK(r.nv == 3 && r.nf == 1 && r.fvert[2] == 2 && r.xyz[3] == 1);
	fct_mesh_free(&r);
	/* neither: refused */
	static const char text[] = "hello\nworld\n";
	f = fmemopen((void *)text, sizeof text - 1, "rb");
	CHECK_INT(fct_mesh_read_stream(&r, f, "x.txt", NULL, &fmt, &err), -1);
	fclose(f);
	CHECK_STR(err.msg, "x.txt: not a PLY or OBJ file (no vertex)");
	CHECK_INT(fct_mesh_read_file(&r, at("missing.ply"), NULL, &err), -1);
	CHECK(strstr(err.msg, "missing.ply: No such file or directory") != NULL);
	/* a folder that does not exist: refused, nothing written */
	CHECK_INT(fct_mesh_write_file(&m, at("nowhere/x.ply"), 0, &err), -1);
	CHECK(strstr(err.msg, "nowhere") != NULL);
	CHECK(access(at("nowhere"), F_OK) != 0);
	fct_mesh_free(&m);
}

/* The texture dir/img/a.png, given absolute; the mesh written to dir/sub
 * names it ../img/a.png, and read back from there names it through dir/sub
 * again. */
static void test_textures(void)
{
	struct fct_mesh m, r;
	struct fct_err err;
	char tex[256], sub[256], want[256];
	snprintf(tex, sizeof tex, "%s/img/a.png", dir);
	snprintf(sub, sizeof sub, "%s/sub", dir);
	if (mkdir(at("img"), 0700) || mkdir(sub, 0700))
		abort();
	put(tex, "\x89PNG\r\n\x1a\n", 8);
	two_faces(&m);
	CHECK_INT(fct_header_set_texture(&m, 0, tex, &err), 0);
	CHECK_INT(fct_mesh_write_file(&m, at("sub/m.ply"), 1, &err), 0);
	CHECK_STR(fct_header_texture(&m, 0), tex);   /* the caller's mesh keeps its path */
	FILE *f = fopen(at("sub/m.ply"), "rb");
	char line[512];
	int found = 0;
	while (f && fgets(line, sizeof line, f))
		found += !strcmp(line, "comment TextureFile ../img/a.png\n");
	if (f)
		fclose(f);
	CHECK_INT(found, 1);
	CHECK_INT(fct_mesh_read_file(&r, at("sub/m.ply"), NULL, &err), 0);
	snprintf(want, sizeof want, "%s/img/a.png", dir);
	CHECK_STR(fct_header_texture(&r, 0), want);
	fct_mesh_free(&r);
	/* a stream read with no folder keeps the path as written */
	f = fopen(at("sub/m.ply"), "rb");
	CHECK_INT(fct_mesh_read_stream(&r, f, "<stdin>", NULL, NULL, &err), 0);
	fclose(f);
	CHECK_STR(fct_header_texture(&r, 0), "../img/a.png");
	fct_mesh_free(&r);

	/* textured OBJ (s t per vertex): the material library m.mtl beside it,
	 * its map_Kd relative to sub */
	struct fct_prop *s = fct_elem_add_scalar(&m.vertex, "s", FCT_FLOAT32, &err);
	fct_elem_add_scalar(&m.vertex, "t", FCT_FLOAT32, &err);
	s = fct_elem_find(&m.vertex, "s");
	fct_prop_set(s, 1, 1);
	CHECK_INT(fct_mesh_write_file(&m, at("sub/m.obj"), 0, &err), 0);
	CHECK(access(at("sub/m.mtl"), R_OK) == 0);
	f = fopen(at("sub/m.mtl"), "rb");
	found = 0;
	while (f && fgets(line, sizeof line, f))
		found += !strcmp(line, "map_Kd ../img/a.png\n");
	if (f)
		fclose(f);
	CHECK_INT(found, 1);
	CHECK_INT(fct_mesh_read_file(&r, at("sub/m.obj"), NULL, &err), 0);
	CHECK_INT(differences(&m, &r), 0);
	CHECK_STR(fct_header_texture(&r, 0), want);
	fct_mesh_free(&r);
	fct_mesh_free(&m);
}

static void test_round_xyz(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	CHECK(fct_mesh_add_vertex(&m, 0.1, -1e-9, 4e6 + 0.3, &err) == 0);
	CHECK(m.xyz_type == FCT_FLOAT32);
	fct_mesh_round_xyz(&m);
	CHECK(m.xyz[0] == (double)0.1f && m.xyz[0] != 0.1);
	CHECK(m.xyz[1] == (double)-1e-9f);
	CHECK(m.xyz[2] == 4000000.25);   /* float's step at 4e6 is 0.25 */
	m.xyz[0] = 0.1;
	m.xyz_type = FCT_FLOAT64;
	fct_mesh_round_xyz(&m);
	CHECK(m.xyz[0] == 0.1);
	fct_mesh_free(&m);
}

int main(void)
{
	snprintf(dir, sizeof dir, "%s/facet-meshio.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (strlen(dir) >= sizeof dir - 1 || !mkdtemp(dir))
		abort();
	test_names();
	test_is_image();
	test_round_trip();
	test_textures();
	test_round_xyz();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
	if (system(cmd))
		fprintf(stderr, "test_meshio: could not remove %s\n", dir);
	CHECK_DONE();
}
