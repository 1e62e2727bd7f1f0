/* segopts.h - segplanes' options, which planarize and roommodel take too:
 * their getopt_long entries and their parsing into the segmentation's
 * parameters (segmesh.h).  One table, so that an option added to segplanes
 * reaches every program that runs the stage (segplanes(1) documents every
 * option; each program's --help says what it takes).
 *
 * Like cli.h this is command-line layer, for mains only: a malformed value
 * prints "prog: ..." and exits 2.
 *
 * Short options: -c and -n (put "c:n:" in the program's optstring). */
#ifndef FCT_SEGOPTS_H
#define FCT_SEGOPTS_H

#include <getopt.h>

#include "planar/segmesh.h"

/* getopt_long codes of the long options, above any program's own and the
 * other option modules'. */
enum {
	FCT_SOPT_AREA = 0x1200, FCT_SOPT_FIT, FCT_SOPT_MAXDEV, FCT_SOPT_MAXRMS, FCT_SOPT_MINEXTENT,
	FCT_SOPT_MINFACES, FCT_SOPT_TLS
};

/* The long options' entries, for a program's struct option table. */
#define FCT_SEG_LONGOPTS \
	{"area-weighted", no_argument, NULL, FCT_SOPT_AREA}, \
	{"fit", required_argument, NULL, FCT_SOPT_FIT}, \
	{"max-dev", required_argument, NULL, FCT_SOPT_MAXDEV}, \
	{"max-rms", required_argument, NULL, FCT_SOPT_MAXRMS}, \
	{"min-extent", required_argument, NULL, FCT_SOPT_MINEXTENT}, \
	{"min-faces", required_argument, NULL, FCT_SOPT_MINFACES}, \
	{"tls", no_argument, NULL, FCT_SOPT_TLS}

/* Their lines of --help in a program that runs the stage among others
 * (planarize, roommodel; segplanes' own says more), after a heading. */
#define FCT_SEG_USAGE \
	"  -c factor          merge while the smaller patch moves by at most factor\n" \
	"                     sigma, rms (default 3)\n" \
	"  -n patches         stop at this many patches instead\n" \
	"      --area-weighted\n" \
	"                     weight each face by its area\n" \
	"      --fit k        a patch's points stay within k sigma of its plane, rms\n" \
	"                     (default 1.5)\n" \
	"      --max-dev k    no face farther than k sigma from its patch's plane: it\n" \
	"                     is free-form (default 3)\n" \
	"      --max-rms r    never make a patch of rms above r (metres)\n" \
	"      --min-extent k a patch narrower than k sigma is free-form (default 10)\n" \
	"      --min-faces k  absorb patches of fewer faces (default: one in 600 of the\n" \
	"                     dense mesh's faces, at least 8)\n" \
	"      --tls          fit planes orthogonally, not along the camera's rays\n"

struct fct_seg_opts {
	struct fct_segment_params seg;
	int tls;                  /* --tls: fit planes orthogonally */
	int factor_given;         /* -c */
	int min_faces_given;      /* --min-faces */
};

/* The segmentation's defaults (fct_segment_params_default). */
void fct_seg_opts_init(struct fct_seg_opts *o);

/* Take getopt_long's c (with optarg arg) when it is a segplanes option ('c',
 * 'n' or a FCT_SOPT_ code): 1, or 0 when it is the program's own. */
int fct_seg_opt(struct fct_seg_opts *o, int c, const char *arg);

/* After the options: -c and -n exclude each other (exit 2). */
void fct_seg_opts_check(const struct fct_seg_opts *o);

#endif
