/* texopts.c - viewtex's texture options (see texopts.h). */
#include "cli/texopts.h"

#include <math.h>
#include <string.h>

#include "cli/cli.h"

void fct_tex_write_atlas(struct fct_viewtex *T, struct fct_mesh *m, const char *out, int per_face)
{
	struct fct_err err;
	size_t npages = fct_viewtex_npages(T);
	char **names = fct_viewtex_page_names(out, npages, &err);
	if (!names)
		fct_die_err(&err);
	for (size_t i = 0; i < npages; i++)
		fct_write_image_or_die(fct_viewtex_page(T, i), names[i]);
	if (fct_viewtex_apply(T, m, names, per_face, &err))
		fct_die_err(&err);
	fct_viewtex_page_names_free(names, npages);
}

void fct_tex_opts_init(struct fct_tex_opts *o)
{
	fct_viewtex_params_default(&o->p);
	o->level_given = 0;
}

void fct_tex_opts_init_sequence(struct fct_tex_opts *o)
{
	fct_tex_opts_init(o);
	o->p.blend = 1;
	o->p.texel_scale = 2;
}

int fct_tex_opt(struct fct_tex_opts *o, int c, const char *arg)
{
	static const char *const levels[] = { "none", "gain", "seams" };
	struct fct_viewtex_params *p = &o->p;
	double v[3];
	long n;
	switch (c) {
	case FCT_TOPT_ATLAS:
		n = fct_opt_long("--atlas-size", arg, 64, 16384);
		if (n & (n - 1))
			fct_usage_error("--atlas-size: %ld is not a power of two", n);
		p->atlas_max = (int)n;
		break;
	case FCT_TOPT_BLEND: p->blend = 1; break;
	case FCT_TOPT_CANDIDATES: p->candidates = (int)fct_opt_long("--candidates", arg, 1, 32); break;
	case FCT_TOPT_FILL:
		fct_opt_doubles("--fill", arg, v, 3);
		for (int k = 0; k < 3; k++) {
			if (!(v[k] >= 0 && v[k] <= 255))
				fct_usage_error("--fill: \"%s\": each value must be in [0, 255]", arg);
			p->fill[k] = (uint8_t)lround(v[k]);
		}
		break;
	case FCT_TOPT_LEVEL:
		o->level_given = 1;
		p->level = -1;
		for (int k = 0; k < 3; k++)
			if (!strcmp(arg, levels[k]))
				p->level = k;
		if (p->level < 0)
			fct_usage_error("--level: \"%s\" is not none, gain or seams", arg);
		break;
	case FCT_TOPT_MAXPAGES: p->max_pages = (int)fct_opt_long("--max-pages", arg, 1, 1024); break;
	case FCT_TOPT_MINANGLE: p->min_cos = sin(fct_opt_double("--min-angle", arg, 0, 89) * M_PI / 180); break;
	case FCT_TOPT_NORECT: p->rectify = 0; break;
	case FCT_TOPT_ONEPHOTO: p->blend = 0; break;
	case FCT_TOPT_PADDING: p->padding = (int)fct_opt_long("--padding", arg, 0, 64); break;
	case FCT_TOPT_SCALE: p->texel_scale = fct_opt_double("--texel-scale", arg, 0.01, 4); break;
	default: return 0;
	}
	return 1;
}

void fct_tex_opts_check(struct fct_tex_opts *o)
{
	struct fct_viewtex_params *p = &o->p;
	if ((double)p->max_pages * p->atlas_max * p->atlas_max > (double)((size_t)1 << 29))
		fct_usage_error("--max-pages %d of --atlas-size %d: more than 2^29 texels", p->max_pages,
		                p->atlas_max);
	if (p->blend && !o->level_given)
		p->level = 0;           /* the mean of the photos is level enough */
}
