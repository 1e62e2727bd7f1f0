/* test_header.c - the header comments as written: every line at most
 * FCT_HEADER_LINE_MAX bytes (MeshLab refuses 510, Open3D's RPly 1024), a
 * long provenance abbreviated to its program, leading arguments, the count
 * left out and the last argument; a pose in its shortest exact form; data
 * (camera, TextureFile) never cut. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/header.h"
#include "io/ply.h"
#include "io/reader.h"

static const char *line_of(const char *text, int obj_info, size_t max, char *buf)
{
	struct fct_comment c = { obj_info, (char *)text };
	return fct_comment_line(&c, max, buf);
}

/* tsdfuse naming 30 views, as the 22-view fusion did (2359 bytes). */
static void test_provenance(void)
{
	char text[4096], buf[FCT_HEADER_LINE_MAX + 64];
	int n = snprintf(text, sizeof text, "facet tsdfuse --voxel 0.02 --carve -o room.ply");
	for (int i = 0; i < 30; i++)
		n += snprintf(text + n, sizeof text - (size_t)n, " views/view%02d.depth.ply", i);
	const char *got = line_of(text, 0, FCT_HEADER_LINE_MAX - 8, buf);
	CHECK(strlen(got) <= FCT_HEADER_LINE_MAX - 8);
	/* 46 bytes of head and options, 8 views of 24 bytes (238), then
	 * " ... (22 more) " and the last view: 238 + 15 + 23 > 247 leaves 7. */
	CHECK_STR(got, "facet tsdfuse --voxel 0.02 --carve -o room.ply views/view00.depth.ply "
	          "views/view01.depth.ply views/view02.depth.ply views/view03.depth.ply "
	          "views/view04.depth.ply views/view05.depth.ply views/view06.depth.ply "
	          "... (22 more) views/view29.depth.ply");
	/* A short one is left alone (the same pointer). */
	CHECK(line_of("facet dm2mesh -K tum d.png", 0, 247, buf) != buf);

	/* A last argument longer than a third of the line: its end is kept. */
	char last[400];
	memset(last, 'p', 300);
	strcpy(last + 300, "/tail.ply");
	snprintf(text, sizeof text, "facet meshconv a.ply b.ply %s", last);
	got = line_of(text, 0, 247, buf);
	CHECK(strlen(got) <= 247);
	CHECK(!strncmp(got, "facet meshconv a.ply b.ply ... (0 more) ...", 43));
	CHECK(strlen(got) > 9 && !strcmp(got + strlen(got) - 9, "/tail.ply"));
}

static void test_other_lines(void)
{
	char text[600], buf[FCT_HEADER_LINE_MAX + 64];
	/* Free text (another tool's comment, an obj_info) is cut with "...". */
	memset(text, 'w', 400);
	text[400] = 0;
	const char *got = line_of(text, 1, 246, buf);
	CHECK_INT(strlen(got), 246);
	CHECK(!strcmp(got + 243, "..."));
	/* A TextureFile path is data: whole, however long. */
	memcpy(text, "TextureFile ", 12);
	strcpy(text + 300, ".png");
	CHECK(line_of(text, 0, 247, buf) != buf);

	/* A pose in %.17g (264 bytes as "comment pose ...", a rotation with a
	 * translation): the same 12 numbers in their shortest exact form. */
	static const double pose[12] = {
		0.57735026918962573, -0.70710678118654746, 0.40824829046386302, -123.45678901234567,
		0.57735026918962573, 0.70710678118654757, 0.40824829046386307, -2.5e-05,
		-0.57735026918962573, 6.123233995736766e-17, 0.81649658092772603, -0.00012345678901234567,
	};
	int n = snprintf(text, sizeof text, "pose");
	for (int k = 0; k < 12; k++)
		n += snprintf(text + n, sizeof text - (size_t)n, " %.17g", pose[k]);
	CHECK_INT(n + 8, 264);
	got = line_of(text, 0, 247, buf);
	CHECK(got == buf);
	CHECK_INT(strlen(got) + 8, 239);
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	double back[12];
	CHECK(fct_mesh_add_comment(&m, got, 0, &err) == 0);
	CHECK(fct_header_pose(&m, back, &err) == 1);
	CHECK(!memcmp(back, pose, sizeof pose));
	/* fct_header_set_pose writes the short form itself. */
	CHECK(fct_header_set_pose(&m, pose, &err) == 0);
	CHECK_STR(m.comments[0].text, got);
	fct_mesh_free(&m);
}

/* A whole PLY header through the writer: no line over the limit. */
static void test_written_header(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	CHECK(fct_mesh_add_vertex(&m, 0, 0, 0, &err) == 0);
	char *argv[40];
	char names[40][32];
	for (int i = 0; i < 40; i++) {
		snprintf(names[i], sizeof names[i], "fragment_%03d_of_the_room.ply", i);
		argv[i] = names[i];
	}
	CHECK(fct_header_add_provenance(&m, "tsdfuse", 40, argv, &err) == 0);
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	CHECK(f && fct_ply_write(&m, f, FCT_PLY_ASCII, &err) == 0);
	if (f)
		fclose(f);
	size_t longest = 0, lines = 0;
	for (char *p = buf; p && *p;) {
		char *nl = strchr(p, '\n');
		size_t l = nl ? (size_t)(nl - p) : strlen(p);
		longest = l > longest ? l : longest;
		lines++;
		if (!nl || !strncmp(p, "end_header", 10))
			break;
		p = nl + 1;
	}
	CHECK(lines >= 6);
	CHECK_MSG(longest <= FCT_HEADER_LINE_MAX, "longest header line %zu bytes", longest);
	CHECK(buf && strstr(buf, "(") && strstr(buf, "fragment_039_of_the_room.ply\n"));
	free(buf);
	fct_mesh_free(&m);
}

/* A texture path too long for one header line cannot be shortened: the
 * PLY writer refuses it, with the figure, before writing anything (it was
 * written whole: 267 bytes for a 240-character image name). */
static void test_long_texture(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	CHECK(fct_mesh_add_vertex(&m, 0, 0, 0, &err) == 0);
	char path[300];
	memset(path, 'a', 250);
	strcpy(path + 250, ".png");
	CHECK(fct_header_set_texture(&m, 0, path, &err) == 0);
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	CHECK(f && fct_ply_write(&m, f, FCT_PLY_ASCII, &err) == -1);
	CHECK_MSG(strstr(err.msg, "comment TextureFile") && strstr(err.msg, "274 bytes, over the 255"), "%s", err.msg);
	if (f)
		fclose(f);
	CHECK_INT(len, 0);
	free(buf);
	/* 230 characters fit: "comment TextureFile " and the path, 250 bytes. */
	path[226] = 0;
	strcat(path, ".png");
	CHECK(fct_header_set_texture(&m, 0, path, &err) == 0);
	buf = NULL, len = 0;
	f = open_memstream(&buf, &len);
	CHECK(f && fct_ply_write(&m, f, FCT_PLY_ASCII, &err) == 0);
	if (f)
		fclose(f);
	CHECK(buf && strstr(buf, path));
	free(buf);
	fct_mesh_free(&m);
}

int main(void)
{
	test_provenance();
	test_other_lines();
	test_written_header();
	test_long_texture();
	CHECK_DONE();
}
