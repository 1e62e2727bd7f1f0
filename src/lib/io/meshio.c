/* meshio.c - format detection, TextureFile paths and atomic mesh output. */
#include "io/meshio.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/header.h"
#include "io/image.h"
#include "io/obj.h"
#include "io/output.h"
#include "core/path.h"
#include "io/ply.h"
#include "io/reader.h"

const char *fct_format_name(enum fct_format fmt)
{
	static const char *names[] = {"ply ascii", "ply binary_little_endian", "ply binary_big_endian", "obj"};
	return names[fmt];
}

/* Rewrite the TextureFile paths of m: a relative one joined to dir
 * (reading a file from another folder), or every one, absolute included,
 * made relative to dir (writing a file), so that a model and its images
 * move together.  One pass over the comments, so thousands of textures
 * stay linear. */
static int map_textures(struct fct_mesh *m, const char *dir, int to_relative, struct fct_err *err)
{
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *p = fct_comment_texture(&m->comments[i]);
		if (!p || !p[0] || (!to_relative && p[0] == '/'))
			continue;
		char *q = to_relative ? fct_path_relative(p, dir, err) : fct_path_join(dir, p, err);
		if (!q)
			return -1;
		int rc = fct_comment_set_texture(&m->comments[i], q, err);
		free(q);
		if (rc)
			return -1;
	}
	return 0;
}

int fct_mesh_read_stream(struct fct_mesh *m, FILE *f, const char *name, const char *dir,
                         enum fct_format *fmt, struct fct_err *err)
{
	struct fct_reader r;
	fct_mesh_init(m);
	if (fct_reader_init(&r, f, name, err))
		return -1;
	int rc;
	enum fct_format got;
	if (fct_ply_detect(&r)) {
		enum fct_ply_format pf;
		rc = fct_ply_read(m, &r, &pf, err);
		got = (enum fct_format)pf;
		if (!rc && dir && strcmp(dir, ".") && map_textures(m, dir, 0, err)) {
			fct_mesh_free(m);
			rc = -1;
		}
	} else {
		rc = fct_obj_read(m, &r, dir, err);
		got = FCT_FORMAT_OBJ;
	}
	fct_reader_free(&r);
	if (!rc && fmt)
		*fmt = got;
	return rc;
}

int fct_path_is_image(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return 0;
	unsigned char head[8];
	size_t n = fread(head, 1, sizeof head, f);
	fclose(f);
	return fct_image_magic(head, n) >= 0;
}

void fct_mesh_round_xyz(struct fct_mesh *m)
{
	if (m->xyz_type == FCT_FLOAT32)
		for (size_t i = 0; i < 3 * m->nv; i++)
			m->xyz[i] = (float)m->xyz[i];
}

int fct_mesh_read_file(struct fct_mesh *m, const char *path, enum fct_format *fmt,
                       struct fct_err *err)
{
	fct_mesh_init(m);
	if (fct_path_is_std(path))
		return fct_mesh_read_stream(m, stdin, "<stdin>", NULL, fmt, err);
	FILE *f = fopen(path, "rb");
	if (!f)
		return fct_fail(err, "%s: %s", path, strerror(errno));
	char *dir = fct_path_dir(path, err);
	int rc = dir ? fct_mesh_read_stream(m, f, path, dir, fmt, err) : -1;
	free(dir);
	fclose(f);
	return rc;
}

int fct_mesh_write_stream(const struct fct_mesh *m, FILE *f, enum fct_format fmt,
                          struct fct_err *err)
{
	if (fmt == FCT_FORMAT_OBJ)
		return fct_obj_write(m, f, NULL, NULL, err);
	return fct_ply_write(m, f, (enum fct_ply_format)fmt, err);
}

/* "model.obj" -> "model.mtl"; any other name gets ".mtl" appended. */
static char *mtl_path_for(const char *obj, struct fct_err *err)
{
	size_t n = strlen(obj);
	int swap = fct_path_has_suffix(obj, ".obj");
	char *p = malloc(n + 5);
	if (!p) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	memcpy(p, obj, n + 1);
	strcpy(p + (swap ? n - 4 : n), ".mtl");
	return p;
}

enum fct_format fct_format_for_path(const char *path, int ascii)
{
	if (path && strcmp(path, "-") && fct_path_has_suffix(path, ".obj"))
		return FCT_FORMAT_OBJ;
	return ascii ? FCT_FORMAT_PLY_ASCII : FCT_FORMAT_PLY_LE;
}

int fct_mesh_write_file(const struct fct_mesh *m, const char *path, int ascii,
                        struct fct_err *err)
{
	return fct_mesh_write_file_as(m, path, fct_format_for_path(path, ascii), err);
}

int fct_mesh_write_file_as(const struct fct_mesh *m, const char *path, enum fct_format fmt,
                           struct fct_err *err)
{
	struct fct_out out, mtl = {0};
	int named = path && strcmp(path, "-");
	struct fct_mesh copy;
	const struct fct_mesh *w = m;
	char *dir = NULL, *mtl_path = NULL;
	int rc = -1;
	fct_mesh_init(&copy);
	if (named && fct_header_texture_count(m)) {
		/* Only the comments change: copy the mesh shallowly with its own comments. */
		if (!(dir = fct_path_dir(path, err)))
			return -1;
		copy = *m;
		copy.comments = NULL, copy.ncomments = 0;
		w = &copy;
		for (size_t i = 0; i < m->ncomments; i++)
			if (fct_mesh_add_comment(&copy, m->comments[i].text, m->comments[i].obj_info, err))
				goto out;
		if (map_textures(&copy, dir, 1, err))
			goto out;
	}
	if (fct_out_open(&out, path, err))
		goto out;
	if (fmt == FCT_FORMAT_OBJ) {
		const char *mtl_name = NULL;
		if (named && fct_obj_wants_mtl(w)) {
			if (!(mtl_path = mtl_path_for(path, err)) || fct_out_open(&mtl, mtl_path, err)) {
				fct_out_abort(&out);
				goto out;
			}
			mtl_name = strrchr(mtl_path, '/') ? strrchr(mtl_path, '/') + 1 : mtl_path;
		}
		rc = fct_obj_write(w, out.f, mtl_name, mtl.f, err);
	} else {
		rc = fct_ply_write(w, out.f, (enum fct_ply_format)fmt, err);
	}
	if (rc) {
		fct_err_prefix(err, "%s", named ? path : "<stdout>");
		fct_out_abort(&out);
		fct_out_abort(&mtl);
		goto out;
	}
	rc = -1;
	if (mtl.f && fct_out_commit(&mtl, err)) {
		fct_out_abort(&out);
		goto out;
	}
	rc = fct_out_commit(&out, err);
out:
	if (w == &copy) {
		for (size_t i = 0; i < copy.ncomments; i++)
			free(copy.comments[i].text);
		free(copy.comments);
	}
	free(dir);
	free(mtl_path);
	return rc;
}
