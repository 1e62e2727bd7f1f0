/* texopts.h - viewtex's options for the texture itself (the atlas, the
 * choice of photos, the levelling), which roommodel takes too: their
 * getopt_long entries and their parsing into the texture's parameters
 * (viewtex.h).  One table, so that an option added to viewtex reaches every
 * program that runs the stage (viewtex(1) documents every option; each
 * program's --help says what it takes).  viewtex's --smooth, --per-vertex
 * and its photos' options are its own (roommodel's --smooth is the depth
 * smoothing's).
 *
 * Like cli.h this is command-line layer, for mains only: a malformed value
 * prints "prog: ..." and exits 2. */
#ifndef FCT_TEXOPTS_H
#define FCT_TEXOPTS_H

#include <getopt.h>

#include "render/viewtex.h"

/* getopt_long codes of the long options, above any program's own and the
 * other option modules'. */
enum {
	FCT_TOPT_ATLAS = 0x1400, FCT_TOPT_BLEND, FCT_TOPT_CANDIDATES, FCT_TOPT_FILL, FCT_TOPT_LEVEL,
	FCT_TOPT_MAXPAGES, FCT_TOPT_MINANGLE, FCT_TOPT_NORECT, FCT_TOPT_PADDING, FCT_TOPT_SCALE,
	FCT_TOPT_ONEPHOTO
};

/* The long options' entries, for a program's struct option table. */
#define FCT_TEX_LONGOPTS \
	{"atlas-size", required_argument, NULL, FCT_TOPT_ATLAS}, \
	{"blend", no_argument, NULL, FCT_TOPT_BLEND}, \
	{"candidates", required_argument, NULL, FCT_TOPT_CANDIDATES}, \
	{"fill", required_argument, NULL, FCT_TOPT_FILL}, \
	{"level", required_argument, NULL, FCT_TOPT_LEVEL}, \
	{"max-pages", required_argument, NULL, FCT_TOPT_MAXPAGES}, \
	{"min-angle", required_argument, NULL, FCT_TOPT_MINANGLE}, \
	{"no-rectify", no_argument, NULL, FCT_TOPT_NORECT}, \
	{"one-photo", no_argument, NULL, FCT_TOPT_ONEPHOTO}, \
	{"padding", required_argument, NULL, FCT_TOPT_PADDING}, \
	{"texel-scale", required_argument, NULL, FCT_TOPT_SCALE}

/* Their lines of --help in a program that runs the stage among others on a
 * whole sequence, with fct_tex_opts_init_sequence's defaults (roommodel;
 * viewtex's own says more), after a heading. */
#define FCT_TEX_USAGE \
	"      --atlas-size n largest atlas side, a power of two (default 4096)\n" \
	"      --blend        each texel the mean of the photos that see it, weighed\n" \
	"                     by their resolution (default)\n" \
	"      --candidates n photos kept per face, 1 to 32 (default 6)\n" \
	"      --fill r,g,b   colour of faces no photo sees (default 128,128,128)\n" \
	"      --level how    colour levelling: none, gain, seams (default seams,\n" \
	"                     none with --blend)\n" \
	"      --max-pages n  most atlas images (default 16)\n" \
	"      --min-angle deg\n" \
	"                     photos seeing a face at less than this angle to its\n" \
	"                     plane are a last resort (default 5.7)\n" \
	"      --no-rectify   texture planar patches from the photo's projection too\n" \
	"      --one-photo    each face from its one best photo, not blended\n" \
	"      --padding n    texels padded around each chart (default 4)\n" \
	"      --texel-scale s\n" \
	"                     texels per photo pixel, 0.01 to 4 (default 2)\n"

struct fct_tex_opts {
	struct fct_viewtex_params p;
	int level_given;          /* --level */
};

/* The texture's defaults (fct_viewtex_params_default). */
void fct_tex_opts_init(struct fct_tex_opts *o);

/* The defaults for a model made from a whole sequence (roommodel): blended,
 * at 2 texels per photo pixel.  Many photos see each face there, and their
 * mean at the finer grid beats the one best photo at the views left out:
 * on the demo's 24-view sequence 31.48 dB against 30.56 (tsdfuse's 1 cm
 * vertex colour 31.24), on the shared 7-Scenes frames 16.44 against 14.79
 * (15.77), on mkscene's room at 640x480 33.22 against 32.23 (30.07). */
void fct_tex_opts_init_sequence(struct fct_tex_opts *o);

/* Take getopt_long's c (with optarg arg) when it is one of these options
 * (a FCT_TOPT_ code): 1, or 0 when it is the program's own. */
int fct_tex_opt(struct fct_tex_opts *o, int c, const char *arg);

/* After the options: more than 2^29 texels in the pages is a usage error;
 * --blend implies --level none unless given. */
void fct_tex_opts_check(struct fct_tex_opts *o);

/* Write T's atlas pages beside the model file out (name_atlasN.png,
 * fct_viewtex_page_names) and give m their mapping (fct_viewtex_apply,
 * per_face as there).  Dies on error ("prog: PATH: ..."). */
void fct_tex_write_atlas(struct fct_viewtex *T, struct fct_mesh *m, const char *out, int per_face);

#endif
