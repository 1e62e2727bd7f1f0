/* meshio.h - read a mesh from any supported format, write it where asked.
 *
 * Reading detects the format from the content: PLY when it starts with the
 * PLY magic, otherwise OBJ, which must hold at least one vertex.  Writing
 * picks OBJ (with a .mtl beside it when textured) for names ending in .obj
 * and PLY otherwise; named outputs are atomic (output.h).
 *
 * TextureFile paths follow DESIGN.md: on the pipes they are kept as given
 * (relative to the current folder, or absolute); reading a file from
 * another folder prefixes that folder to a relative one, and writing a
 * named file rewrites every one, absolute included, relative to the file's
 * folder (an OBJ's map_Kd too), so that the folder can be moved. */
#ifndef FCT_MESHIO_H
#define FCT_MESHIO_H

#include <stdio.h>

#include "core/mesh.h"

enum fct_format {
	FCT_FORMAT_PLY_ASCII, FCT_FORMAT_PLY_LE, FCT_FORMAT_PLY_BE, FCT_FORMAT_OBJ
};

/* "ply ascii", "ply binary_little_endian", "ply binary_big_endian", "obj". */
const char *fct_format_name(enum fct_format fmt);

/* Does the file at path start like an image (PNG, PFM or JPEG) rather than
 * a mesh?  0 when it does not or cannot be read.  For programs that take
 * meshes and depth images as operands alike (tsdfuse). */
int fct_path_is_image(const char *path);

/* Round m's positions to what a file holds (float, unless m->xyz_type is
 * double): a program that runs several stages in memory gives what the
 * stage programs give on a pipe. */
void fct_mesh_round_xyz(struct fct_mesh *m);

/* Read from path ("-" or NULL: stdin, named "<stdin>"); m is initialised
 * here.  fmt (may be NULL) gets the format read. */
int fct_mesh_read_file(struct fct_mesh *m, const char *path, enum fct_format *fmt,
                       struct fct_err *err);

/* Read from an open stream called name; dir is the folder of the file (NULL
 * for the current one). */
int fct_mesh_read_stream(struct fct_mesh *m, FILE *f, const char *name, const char *dir,
                         enum fct_format *fmt, struct fct_err *err);

/* Write m to path ("-" or NULL: stdout as PLY): OBJ when path ends in .obj,
 * otherwise ascii PLY when ascii is set, binary little-endian PLY if not. */
int fct_mesh_write_file(const struct fct_mesh *m, const char *path, int ascii,
                        struct fct_err *err);

/* The format fct_mesh_write_file picks for path. */
enum fct_format fct_format_for_path(const char *path, int ascii);

/* Write m to path ("-" or NULL: stdout) in the given format; the material
 * library of a textured OBJ is written only for a named file. */
int fct_mesh_write_file_as(const struct fct_mesh *m, const char *path, enum fct_format fmt,
                           struct fct_err *err);

/* Write m to a stream in the given format (OBJ without a material library). */
int fct_mesh_write_stream(const struct fct_mesh *m, FILE *f, enum fct_format fmt,
                          struct fct_err *err);

#endif
