/* projverts - move the vertices of a planar-segmented mesh onto their
 * planes, and recompute their texture coordinates: Kang, Johnson and
 * Szeliski, "Extraction of Concise and Realistic 3-D Models from Real Data"
 * (DEC CRL 95/7), section 5 (vertex projection, eq. 2), section 6 (image
 * mapping) and section 8 (world knowledge: orthogonal planes, the depth
 * scale).  The library does the work (project.h). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "planar/project.h"

static const char usage[] =
	"usage: projverts [-aqv] [-o file] [--max-move d] [--orthogonal angle]\n"
	"                 [--depth-scale-fix] [--fallback] [--along-rays] [--no-tear]\n"
	"                 [input]\n"
	"Move each vertex of a mesh with face property patch (or of a wireframe with\n"
	"the edge element of simpchain) and a plane element onto its plane, onto the\n"
	"line of its two planes, or to the least-squares point of its k >= 3 planes;\n"
	"recompute s t from the camera and pose comments.\n"
	"  -a                  write ascii PLY\n"
	"  -o file             output file (default standard output)\n"
	"  -q                  quiet\n"
	"  -v                  report counts, moves, residuals and times on stderr\n"
	"      --depth-scale-fix\n"
	"                      first scale camera-frame depth so that adjacent planes\n"
	"                      become orthogonal (the focal length scales with it)\n"
	"      --fallback      a refused move falls back to the best lower-rank one\n"
	"                      within the bound (default: the vertex is kept)\n"
	"      --max-move d    refuse moves longer than d, in the units of the\n"
	"                      coordinates, or inf (default the mean edge length)\n"
	"      --orthogonal angle\n"
	"                      snap planes within angle degrees of orthogonal or\n"
	"                      parallel to an exact frame with a common up axis\n"
	"                      (0 < angle <= 40)\n"
	"      --along-rays    with a camera, move a vertex on one or two planes along\n"
	"                      its own ray (where range noise lies), keeping it on its\n"
	"                      pixel, instead of perpendicularly as the paper does\n"
	"      --no-tear       keep a wireframe vertex whose planes do not meet near it\n"
	"                      (default: tear it, one copy per plane along its ray)\n"
	"  -h, --help          this help\n"
	"      --version       print the version\n";

enum { OPT_MAXMOVE = 256, OPT_ORTHO, OPT_SCALE, OPT_FALLBACK, OPT_RAYS, OPT_NOTEAR, OPT_VERSION };

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"max-move", required_argument, NULL, OPT_MAXMOVE},
		{"orthogonal", required_argument, NULL, OPT_ORTHO},
		{"depth-scale-fix", no_argument, NULL, OPT_SCALE},
		{"fallback", no_argument, NULL, OPT_FALLBACK},
		{"along-rays", no_argument, NULL, OPT_RAYS},
		{"no-tear", no_argument, NULL, OPT_NOTEAR},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "aho:qv";
	fct_cli_init("projverts");
	struct fct_project_params par;
	fct_project_params_default(&par);
	par.scale_angle = 0;   /* the library's default, or the --orthogonal angle */
	const char *out = NULL;
	int ascii = 0, c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("projverts (facet) " FCT_VERSION); exit(0);
		case OPT_MAXMOVE:
			par.max_move = !strcmp(optarg, "inf") ? HUGE_VAL
			             : fct_opt_double("--max-move", optarg, 0, HUGE_VAL);
			break;
		case OPT_ORTHO:
			par.ortho_angle = fct_opt_double("--orthogonal", optarg, 0, 40);
			if (!(par.ortho_angle > 0))
				fct_usage_error("--orthogonal: the angle must be above 0");
			break;
		case OPT_SCALE: par.depth_scale_fix = 1; break;
		case OPT_FALLBACK: par.fallback = 1; break;
		case OPT_RAYS: par.along_rays = 1; break;
		case OPT_NOTEAR: par.tear = 0; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *input = fct_one_operand(argc, argv, optind, "-");

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now();
	if (fct_mesh_read_file(&m, input, NULL, &err))
		fct_die_err(&err);
	double read_s = fct_now() - t0;
	const char *name = fct_path_display(input);
	int had_st = fct_elem_find(&m.vertex, "s") && fct_elem_find(&m.vertex, "t");

	double t1 = fct_now();
	struct fct_project_stats st;
	if (fct_project_mesh(&m, &par, &st, &err))
		fct_die_err_at(&err, "%s", name);
	double project_s = fct_now() - t1;

	if (!st.texcoords && had_st && m.nv > 0)
		fct_warn("%s: no camera comment: texture coordinates s t left as they were", name);
	if (st.no_pixel)
		fct_warn("%s: %zu vertices have no pixel in the camera: their s t left as they were",
		         name, st.no_pixel);
	if (st.scaled && st.scale_res.pairs == 0)
		fct_warn("%s: no pair of adjacent planes constrains the depth scale: left at 1", name);
	else if (st.scaled && st.scale_res.inliers < 3)
		fct_warn("%s: depth scale %.6g rests on %zu pair%s of planes only", name,
		         st.scale_res.scale, st.scale_res.inliers, st.scale_res.inliers == 1 ? "" : "s");

	if (fct_header_add_provenance(&m, "projverts", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err)) {
		fct_mesh_free(&m);
		fct_die_err(&err);
	}

	fct_report("vertices", "%zu", st.nvert);
	fct_report("planes", "%zu", st.nplanes);
	for (int k = 0; k < 4; k++) {
		char key[32];
		snprintf(key, sizeof key, "vertices_k%d%s", k, k == 3 ? "+" : "");
		fct_report(key, "%zu", st.by_k[k]);
	}
	for (int k = 1; k < 4; k++) {
		char key[32];
		snprintf(key, sizeof key, "moved_k%d%s", k, k == 3 ? "+" : "");
		fct_report(key, "%zu", st.moved[k]);
	}
	fct_report("rejected", "%zu", st.rejected);
	fct_report("flip_refused", "%zu", st.flip_refused);
	fct_report("torn", "%zu", st.torn);
	fct_report("tear_copies", "%zu", st.tear_copies);
	fct_report("straightened", "%zu", st.straightened);
	fct_report("straight_refused", "%zu", st.straight_refused);
	fct_report("cross_refused", "%zu", st.cross_refused);
	fct_report("ray_fallback", "%zu", st.ray_fallback);
	fct_report("along_ray", "%zu", st.along_ray);
	fct_report("fallback", "%zu", st.fallback);
	fct_report("rank_deficient", "%zu", st.rank_deficient);
	fct_report("mean_edge", "%.9g", st.mean_edge);
	fct_report("bound", "%.9g", st.bound);
	fct_report("mean_move", "%.9g", st.mean_move);
	fct_report("max_move", "%.9g", st.max_move);
	fct_report("rms_before", "%.9g", st.rms_before);
	fct_report("rms_after", "%.9g", st.rms_after);
	fct_report("max_after", "%.9g", st.max_after);
	fct_report("texcoords", "%d", st.texcoords);
	fct_report("no_pixel", "%zu", st.no_pixel);
	if (st.scaled) {
		fct_report("depth_scale", "%.9g", st.scale_res.scale);
		fct_report("scale_pairs", "%zu", st.scale_res.pairs);
		fct_report("scale_inliers", "%zu", st.scale_res.inliers);
		fct_report("scale_rms_cos", "%.9g", st.scale_res.rms_cos);
	}
	if (st.ortho) {
		const struct fct_ortho_result *o = &st.ortho_res;
		fct_report("up", "%.9g,%.9g,%.9g", o->up[0], o->up[1], o->up[2]);
		fct_report("frames", "%zu", o->frames);
		fct_report("snapped_horizontal", "%zu", o->horizontal);
		fct_report("snapped_vertical", "%zu", o->vertical);
		fct_report("snapped_oblique", "%zu", o->oblique);
		fct_report("max_normal_change_deg", "%.9g", o->max_change);
	}
	fct_report("read_s", "%.4f", read_s);
	fct_report("project_s", "%.4f", project_s);
	fct_report("total_s", "%.4f", fct_now() - t0);
	fct_mesh_free(&m);
	return 0;
}
