/* planaropts.c - planedecim's options (see planaropts.h). */
#include "cli/planaropts.h"

#include <math.h>

#include "cli/cli.h"

int fct_planar_opt(struct fct_planar_params *p, int c, const char *arg)
{
	switch (c) {
	case 'e': p->max_error = fct_opt_double("-e", arg, 0, INFINITY); break;
	case FCT_POPT_BORDER: p->border_tol = fct_opt_double("--border", arg, 0, INFINITY); break;
	case FCT_POPT_MAXHOLE: p->max_hole = (size_t)fct_opt_long("--max-hole", arg, 0, 0x7fffffffL); break;
	case FCT_POPT_MAXMOVE: p->max_move = fct_opt_double("--max-move", arg, 0, INFINITY); break;
	case FCT_POPT_MINFREE: p->min_free = (size_t)fct_opt_long("--min-free", arg, 0, 0x7fffffffL); break;
	case FCT_POPT_MINPIECE:
		p->min_piece = (size_t)fct_opt_long("--min-piece", arg, 0, 0x7fffffffL);
		break;
	case FCT_POPT_MINPLANE:
		p->min_plane = (size_t)fct_opt_long("--min-plane", arg, 0, 0x7fffffffL);
		break;
	case FCT_POPT_OUTLINE: p->outline_tol = fct_opt_double("--outline", arg, 0, INFINITY); break;
	default: return 0;
	}
	return 1;
}
