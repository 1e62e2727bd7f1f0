/* bakeopts.c - the vertex-colour bake on the command line; see bakeopts.h. */
#include "cli/bakeopts.h"

#include <stdlib.h>

#include "cli/cli.h"
#include "cli/texopts.h"
#include "core/path.h"
#include "render/viewtex.h"

void fct_bake_opts_init(struct fct_bake_opts *o)
{
	o->texel = -1;
}

int fct_bake_opt(struct fct_bake_opts *o, int c, const char *arg)
{
	if (c != FCT_BOPT_TEXEL)
		return 0;
	o->texel = fct_opt_double("--texel", arg, 0, 1e9);
	return 1;
}

int fct_bake_wanted(const struct fct_bake_opts *o, const char *out, const struct fct_mesh *m)
{
	return o->texel != 0 && out && !fct_path_is_std(out) && fct_colbake_applies(m);
}

void fct_bake_model(struct fct_mesh *model, const struct fct_colbake *B,
                    const struct fct_bake_opts *o, const char *out)
{
	struct fct_err err;
	struct fct_colbake_params p;
	fct_colbake_params_default(&p);
	if (o->texel > 0)
		p.texel = o->texel;
	double texel = fct_colbake_texel(B, model, &p);
	struct fct_viewtex *T = fct_colbake_texture(B, model, &p, &err);
	if (!T)
		fct_die_err_at(&err, "bake");
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	fct_tex_write_atlas(T, model, out, 1);
	/* The texel used: the packing shrinks the scale when a page is full. */
	fct_report_stage("bake", "texel", "%.9g", texel / st.scale);
	fct_report_stage("bake", "charts", "%zu", st.charts);
	fct_report_stage("bake", "charts_rectified", "%zu", st.rectified);
	fct_report_stage("bake", "atlas_size", "%dx%d", st.page_width, st.page_height);
	fct_report_stage("bake", "fill_ratio", "%.4f", st.fill_ratio);
	fct_viewtex_free(T);
}
