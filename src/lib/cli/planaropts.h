/* planaropts.h - planedecim's options, which planarize and roommodel take
 * too: their getopt_long entries and their parsing into the planar model's
 * parameters (planemodel.h).  One table, so that an option added to
 * planedecim reaches every program that runs the stage (planedecim(1)
 * documents every option; each program's --help says what it takes).
 *
 * Like cli.h this is command-line layer, for mains only: a malformed value
 * prints "prog: ..." and exits 2.
 *
 * Short option: -e (put "e:" in the program's optstring). */
#ifndef FCT_PLANAROPTS_H
#define FCT_PLANAROPTS_H

#include <getopt.h>

#include "planar/planemodel.h"

/* getopt_long codes of the long options, above any program's own and the
 * other option modules'. */
enum {
	FCT_POPT_BORDER = 0x1300, FCT_POPT_MAXHOLE, FCT_POPT_MAXMOVE, FCT_POPT_MINFREE,
	FCT_POPT_MINPLANE, FCT_POPT_OUTLINE, FCT_POPT_MINPIECE
};

/* The long options' entries, for a program's struct option table. */
#define FCT_PLANAR_LONGOPTS \
	{"border", required_argument, NULL, FCT_POPT_BORDER}, \
	{"max-hole", required_argument, NULL, FCT_POPT_MAXHOLE}, \
	{"max-move", required_argument, NULL, FCT_POPT_MAXMOVE}, \
	{"min-free", required_argument, NULL, FCT_POPT_MINFREE}, \
	{"min-piece", required_argument, NULL, FCT_POPT_MINPIECE}, \
	{"min-plane", required_argument, NULL, FCT_POPT_MINPLANE}, \
	{"outline", required_argument, NULL, FCT_POPT_OUTLINE}

/* Their lines of --help in a program that runs the stage among others
 * (planarize, roommodel; planedecim's own says more), after a heading. */
#define FCT_PLANAR_USAGE \
	"  -e error           the free-form decimation's bound: the largest quadric\n" \
	"                     distance of a collapse, in sigma (default 1.5)\n" \
	"      --border k     a border may move by k edge lengths (default 1)\n" \
	"      --max-hole k   fill holes of at most k edges inside a patch (64)\n" \
	"      --max-move k   move a vertex onto a line or corner by at most k sigma\n" \
	"                     (default 4)\n" \
	"      --min-free k   a speck of fewer faces joins the label around it (64)\n" \
	"      --min-piece k  without a camera, drop pieces of fewer faces (64; 0:\n" \
	"                     keep all)\n" \
	"      --min-plane k  a patch of fewer faces is free-form (default 64)\n" \
	"      --outline k    simplify outlines to k sample spacings (default 3)\n"

/* Take getopt_long's c (with optarg arg) when it is a planedecim option
 * ('e' or a FCT_POPT_ code) into p (fct_planar_params_default first): 1,
 * or 0 when it is the program's own. */
int fct_planar_opt(struct fct_planar_params *p, int c, const char *arg);

#endif
