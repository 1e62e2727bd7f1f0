/* ply.h - PLY reader and writer (ascii, binary_little_endian, binary_big_endian).
 *
 * Every scalar and list type is read; x y z become the mesh's positions, the
 * face element's vertex_indices (or vertex_index) its polygons, and every
 * other property and element is kept as typed columns and written back as it
 * was.  Hostile input is refused with a message, never trusted: counts are
 * checked against the bytes a regular file holds and storage grows only with
 * the rows actually read. */
#ifndef FCT_PLY_H
#define FCT_PLY_H

#include <stdio.h>

#include "core/mesh.h"
#include "io/reader.h"

enum fct_ply_format { FCT_PLY_ASCII, FCT_PLY_BINARY_LE, FCT_PLY_BINARY_BE };

/* Does the input start with the PLY magic ("ply" and LF or CRLF)? */
int fct_ply_detect(struct fct_reader *r);

/* Read a PLY file into m (initialised by the caller; freed on failure).
 * *fmt (may be NULL) gets the encoding. */
int fct_ply_read(struct fct_mesh *m, struct fct_reader *r, enum fct_ply_format *fmt,
                 struct fct_err *err);

/* Write m to f as PLY in the given encoding.  Reports write errors. */
int fct_ply_write(const struct fct_mesh *m, FILE *f, enum fct_ply_format fmt,
                  struct fct_err *err);

#endif
