/* bakeopts.h - the atlas baked from a mesh's vertex colours (colbake.h) on
 * the command line of the programs that make a model from a coloured mesh,
 * planarize and planedecim: the --texel option, whether a run bakes, and
 * the bake itself with its pages written beside the model.  One module, so
 * that the two programs bake alike (segplanes | planedecim -o gives
 * planarize -o's model and atlas).
 *
 * Like cli.h this is command-line layer, for mains only: a malformed value
 * prints "prog: ..." and exits 2, bad data "prog: bake: ..." and exits 1. */
#ifndef FCT_BAKEOPTS_H
#define FCT_BAKEOPTS_H

#include <getopt.h>

#include "core/mesh.h"
#include "render/colbake.h"

/* getopt_long code of the long option, above any program's own and the
 * other option modules'. */
enum { FCT_BOPT_TEXEL = 0x1500 };

#define FCT_BAKE_LONGOPTS {"texel", required_argument, NULL, FCT_BOPT_TEXEL}

struct fct_bake_opts {
	double texel;            /* --texel, metres; -1 when not given */
};

void fct_bake_opts_init(struct fct_bake_opts *o);

/* Take getopt_long's c (with optarg arg) when it is --texel: 1, or 0. */
int fct_bake_opt(struct fct_bake_opts *o, int c, const char *arg);

/* Does a run that writes its model to out (NULL or "-": standard output)
 * from the mesh m bake?  m has vertex colours, faces and no texture, out
 * names a file (the atlas is written beside it) and --texel is not 0. */
int fct_bake_wanted(const struct fct_bake_opts *o, const char *out, const struct fct_mesh *m);

/* Bake model's atlas from B (fct_colbake_texture), write its pages beside
 * out (fct_viewtex_page_names), and give model per-corner texture
 * coordinates and their TextureFile comments; -v figures as "bake: key".
 * Dies on error. */
void fct_bake_model(struct fct_mesh *model, const struct fct_colbake *B,
                    const struct fct_bake_opts *o, const char *out);

#endif
