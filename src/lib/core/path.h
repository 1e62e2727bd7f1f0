/* path.h - the little path arithmetic that TextureFile needs. */
#ifndef FCT_PATH_H
#define FCT_PATH_H

#include "core/err.h"

/* The folder part of path ("." when it has none); malloc'd. */
char *fct_path_dir(const char *path, struct fct_err *err);
/* dir/rel, or rel itself when rel is absolute or dir is "." or NULL, with
 * "." and "seg/.." collapsed lexically (a relative result keeps its leading
 * ".."); malloc'd. */
char *fct_path_join(const char *dir, const char *rel, struct fct_err *err);
/* The path of target relative to folder from (each relative to the current
 * folder or absolute), through the real folders where they exist (symbolic
 * links resolved), so that it leads to target from inside from; an
 * absolute target becomes relative too.  malloc'd. */
char *fct_path_relative(const char *target, const char *from, struct fct_err *err);
/* Is path standard input or output: NULL or "-"? */
int fct_path_is_std(const char *path);
/* The name of path in messages: "<stdin>" for standard input. */
const char *fct_path_display(const char *path);
/* Does path end in suffix, ignoring case (".obj")? */
int fct_path_has_suffix(const char *path, const char *suffix);
/* The length of path without the extension of its last component
 * ("out/m.obj" -> 5, for the files written beside it: out/m_atlas0.png). */
size_t fct_path_stem_length(const char *path);

#endif
