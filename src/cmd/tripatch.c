/* tripatch - triangulate each planar patch of a simplified wireframe:
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D
 * Models from Real Data" (DEC CRL 95/7), section 4.  The library does the
 * work (tripatch.h, polytri.h). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "planar/tripatch.h"

static const char usage[] =
	"usage: tripatch [-aqv] [-o file] [--cdt] [--plane] [input]\n"
	"Triangulate each planar patch of a wireframe (simpchain's output: vertices,\n"
	"the edge element with patch1/patch2, planes): its boundary loops, outer and\n"
	"holes, mapped to image coordinates s t (else to the patch plane) and filled\n"
	"with triangles by the greedy shortest-diagonal method.\n"
	"  -a             write ascii PLY\n"
	"      --cdt      constrained Delaunay triangulation instead of greedy\n"
	"  -o file        output file (default standard output)\n"
	"      --plane    map every patch to its plane, ignoring s t\n"
	"  -q             quiet\n"
	"  -v             report counts and times on stderr\n"
	"  -h, --help     this help\n"
	"      --version  print the version\n";

enum { OPT_CDT = 256, OPT_PLANE, OPT_VERSION };

int main(int argc, char **argv)
{
	fct_cli_init("tripatch");
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"cdt", no_argument, NULL, OPT_CDT},
		{"plane", no_argument, NULL, OPT_PLANE},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "aho:qv";
	struct fct_tripatch_params p;
	fct_tripatch_params_default(&p);
	const char *out = NULL;
	int ascii = 0, c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_CDT: p.method = FCT_POLYTRI_CDT; break;
		case OPT_PLANE: p.plane_only = 1; break;
		case OPT_VERSION: puts("tripatch (facet) " FCT_VERSION); exit(0);
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *in = fct_one_operand(argc, argv, optind, "-");

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now();
	if (fct_mesh_read_file(&m, in, NULL, &err))
		fct_die_err(&err);
	double t1 = fct_now();
	struct fct_tripatch_stats st;
	if (fct_tripatch(&m, &p, &st, &err))
		fct_die_err_at(&err, "%s", fct_path_display(in));
	double t2 = fct_now();
	if (st.edges == 0)
		fct_warn("no edges: no faces written");
	if (st.failures)
		fct_warn("%zu patches (the first %ld) have no closed boundary and got no triangles",
		         st.failures, st.first_failure);
	if (st.open_edges)
		fct_warn("%zu patch edges close no loop and were left out", st.open_edges);
	if (fct_header_add_provenance(&m, "tripatch", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err))
		fct_die_err(&err);
	double t3 = fct_now();

	fct_report("method", "%s", p.method == FCT_POLYTRI_CDT ? "cdt" : "greedy");
	fct_report("vertices", "%zu", m.nv);
	fct_report("edges", "%zu", st.edges);
	fct_report("patches", "%zu", st.patches);
	fct_report("polygons", "%zu", st.polygons);
	fct_report("holes", "%zu", st.holes);
	fct_report("triangles", "%zu", st.triangles);
	fct_report("in_st", "%zu", st.in_st);
	fct_report("in_plane", "%zu", st.in_plane);
	fct_report("fallbacks", "%zu", st.fallbacks);
	fct_report("repairs", "%zu", st.repairs);
	fct_report("earclipped", "%zu", st.earclipped);
	fct_report("failures", "%zu", st.failures);
	fct_report("open_edges", "%zu", st.open_edges);
	fct_report("slits", "%zu", st.slits);
	fct_report("duplicates", "%zu", st.duplicates);
	fct_report("degenerate_loops", "%zu", st.degenerate);
	fct_report("reversed", "%zu", st.reversed);
	fct_report("slivers_flipped", "%zu", st.slivers_flipped);
	fct_report("candidates", "%zu", st.tri.candidates);
	fct_report("walk_steps", "%zu", st.tri.walk_steps);
	fct_report("budget_hits", "%zu", st.tri.budget_hits);
	fct_report("read_s", "%.4f", t1 - t0);
	fct_report("triangulate_s", "%.4f", t2 - t1);
	fct_report("total_s", "%.4f", t3 - t0);
	fct_mesh_free(&m);
	return 0;
}
