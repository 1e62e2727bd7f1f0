/* header.h - the header comments of DESIGN.md that travel with a mesh.
 *
 *   comment camera pinhole W H fx fy cx cy
 *   comment camera cylindrical W H f cy theta0
 *   comment pose r11 r12 r13 t1 r21 r22 r23 t2 r31 r32 r33 t3   (camera-to-world)
 *   comment TextureFile image.png
 *   comment noise <model> <numbers...>   (the sensor's noise model, noise.h)
 *   comment facet <program> <arguments...>
 *
 * Numbers are written with %.17g so they survive any number of stages. */
#ifndef FCT_HEADER_H
#define FCT_HEADER_H

#include "io/camera.h"
#include "core/mesh.h"
#include "io/noise.h"

/* The camera comment of m: 1 found, 0 none, -1 malformed (message set). */
int fct_header_camera(const struct fct_mesh *m, struct fct_camera *cam, struct fct_err *err);
/* Replace any camera comment of m with cam (kind NONE removes it). */
int fct_header_set_camera(struct fct_mesh *m, const struct fct_camera *cam, struct fct_err *err);

/* The camera-to-world pose as a row-major 3x4 matrix [R | t]: 1, 0 or -1. */
int fct_header_pose(const struct fct_mesh *m, double pose[12], struct fct_err *err);
/* Replace any pose comment (pose NULL removes it). */
int fct_header_set_pose(struct fct_mesh *m, const double pose[12], struct fct_err *err);

/* The noise model of m's noise comment: 1 found, 0 none (nz's model is then
 * FCT_NOISE_UNKNOWN), -1 malformed (message set). */
int fct_header_noise(const struct fct_mesh *m, struct fct_noise *nz, struct fct_err *err);
/* Replace any noise comment of m with nz (FCT_NOISE_UNKNOWN removes it). */
int fct_header_set_noise(struct fct_mesh *m, const struct fct_noise *nz, struct fct_err *err);

/* The path of a TextureFile comment, or NULL for any other comment. */
const char *fct_comment_texture(const struct fct_comment *c);
/* Number of TextureFile comments, and the i-th path (NULL past the end). */
size_t fct_header_texture_count(const struct fct_mesh *m);
const char *fct_header_texture(const struct fct_mesh *m, size_t i);
/* Make comment c say "TextureFile path". */
int fct_comment_set_texture(struct fct_comment *c, const char *path, struct fct_err *err);
/* Remove every TextureFile comment of m. */
void fct_header_remove_textures(struct fct_mesh *m);
/* Replace the i-th TextureFile path (i == count appends one). */
int fct_header_set_texture(struct fct_mesh *m, size_t i, const char *path, struct fct_err *err);

/* Append "facet PROG ARGS..." (arguments separated by blanks; blanks and
 * newlines inside an argument become '_' so the line stays one line).  The
 * whole line is kept in m; the writers abbreviate it (fct_comment_line). */
int fct_header_add_provenance(struct fct_mesh *m, const char *prog, int argc, char **argv,
                              struct fct_err *err);

/* The longest header line facet writes: MeshLab refuses lines of 510 bytes
 * or more and Open3D's reader (RPly) of 1024; 255 leaves room for both. */
#define FCT_HEADER_LINE_MAX 255

/* The text to write for comment c where the line's keyword leaves max
 * bytes (FCT_HEADER_LINE_MAX minus "comment ", "# comment ", ...): a pose
 * in its shortest exact form (at most 12 x 24 + 16 bytes; a rotation in
 * %.17g took 260); a longer provenance line with its middle arguments
 * left out and counted ("facet tsdfuse -o room.ply v00.ply ... (19 more)
 * ... v21.ply"); other free text cut with "..."; camera and TextureFile
 * lines whole (data: a texture path over max is returned as it is, and
 * fct_ply_write refuses a line it makes longer than FCT_HEADER_LINE_MAX).
 * Returns c->text or buf, which must hold FCT_HEADER_LINE_MAX + 64 bytes. */
const char *fct_comment_line(const struct fct_comment *c, size_t max, char *buf);

#endif
