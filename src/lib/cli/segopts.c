/* segopts.c - segplanes' options (see segopts.h). */
#include "cli/segopts.h"

#include <math.h>
#include <stdint.h>

#include "cli/cli.h"

void fct_seg_opts_init(struct fct_seg_opts *o)
{
	fct_segment_params_default(&o->seg);
	o->tls = o->factor_given = o->min_faces_given = 0;
}

int fct_seg_opt(struct fct_seg_opts *o, int c, const char *arg)
{
	struct fct_segment_params *p = &o->seg;
	switch (c) {
	case 'c':
		p->factor = fct_opt_double("-c", arg, 0, HUGE_VAL);
		o->factor_given = 1;
		break;
	case 'n': p->target = fct_opt_long("-n", arg, 1, INT32_MAX); break;
	case FCT_SOPT_AREA: p->area_weighted = 1; break;
	case FCT_SOPT_FIT: p->fit = fct_opt_double("--fit", arg, 0, HUGE_VAL); break;
	case FCT_SOPT_MAXDEV: p->max_dev = fct_opt_double("--max-dev", arg, 0, HUGE_VAL); break;
	case FCT_SOPT_MAXRMS: p->max_rms = fct_opt_double("--max-rms", arg, 0, HUGE_VAL); break;
	case FCT_SOPT_MINEXTENT: p->min_extent = fct_opt_double("--min-extent", arg, 0, HUGE_VAL); break;
	case FCT_SOPT_MINFACES:
		p->min_faces = fct_opt_long("--min-faces", arg, 0, INT32_MAX);
		o->min_faces_given = 1;
		break;
	case FCT_SOPT_TLS: o->tls = 1; break;
	default: return 0;
	}
	return 1;
}

void fct_seg_opts_check(const struct fct_seg_opts *o)
{
	if (o->factor_given && o->seg.target > 0)
		fct_usage_error("-c and -n exclude each other");
}
