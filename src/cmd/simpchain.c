/* simpchain - the boundaries of the planar patches of a labelled mesh,
 * simplified by iterative end-point fit in 3-D, written as a wireframe:
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D
 * Models from Real Data" (DEC CRL 95/7), section 3.  The algorithm is in
 * src/lib/planar/chain.c. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "planar/chain.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"

static const char usage[] =
	"usage: simpchain [-aqv] [-o file] [-t threshold] [--keep-small-loops] [input]\n"
	"Extract the boundaries of the planar patches of a labelled mesh (face property\n"
	"patch and element plane, as segplanes writes them), cut them into chains\n"
	"between junctions, simplify each chain once by iterative end-point fit in 3-D\n"
	"without letting chains cross in a patch's plane, and write the wireframe: the\n"
	"kept vertices with all their properties, element edge (vertex1 vertex2 patch1\n"
	"patch2), the planes and the comments; no faces.\n"
	"  -a            write ascii PLY\n"
	"  -o file       output file (default standard output; PLY only)\n"
	"  -q            quiet\n"
	"  -t threshold  drop a chain point only within threshold mean edge lengths of\n"
	"                its simplified segment (default 3)\n"
	"      --keep-small-loops\n"
	"                keep a loop (a hole or an island) that lies within the\n"
	"                tolerance of its centre (default: drop it, filling the hole)\n"
	"  -v            report chains, junctions, vertices kept, the largest deviation\n"
	"                and the crossings prevented on stderr\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

int main(int argc, char **argv)
{
	fct_cli_init("simpchain");
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{"keep-small-loops", no_argument, NULL, 'L'},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "aho:qt:v";
	const char *out = NULL;
	int ascii = 0, ch;
	struct fct_chain_params params;
	fct_chain_params_default(&params);
	while ((ch = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (ch) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 't': params.threshold = fct_opt_double("-t", optarg, 0, 1e12); break;
		case 'v': fct_verbose = 1; break;
		case 'V': puts("simpchain (facet) " FCT_VERSION); exit(0);
		case 'L': params.keep_small_loops = 1; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *input = fct_one_operand(argc, argv, optind, "-");
	if (out && fct_format_for_path(out, ascii) == FCT_FORMAT_OBJ)
		fct_usage_error("-o %s: OBJ cannot hold the edge element; write PLY", out);

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now(), c0 = fct_cpu_time();
	if (fct_mesh_read_file(&m, input, NULL, &err))
		fct_die_err(&err);
	double read_s = fct_now() - t0;
	size_t nv = m.nv, nf = m.nf;
	struct fct_chains chains;
	struct fct_chain_stats st;
	double t1 = fct_now();
	if (fct_simpchain(&m, &params, &chains, &st, &err))
		fct_die_err_at(&err, "%s", fct_path_display(input));
	double simp_s = fct_now() - t1;
	if (fct_header_add_provenance(&m, "simpchain", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err))
		fct_die_err(&err);
	double total_s = fct_now() - t0, cpu_s = fct_cpu_time() - c0;

	/* Warn about the map tripatch triangulates in: the image when there is
	 * one, else the patch planes. */
	int image = fct_elem_find(&m.vertex, "s") && fct_elem_find(&m.vertex, "t");
	size_t left = image ? st.conflicts_left_image : st.conflicts_left;
	if (left)
		fct_warn("%zu crossings of the input's own boundary edges remain in the %s", left,
		         image ? "image" : "patch planes");
	double me = chains.mean_edge;
	fct_report("vertices_in", "%zu", nv);
	fct_report("faces_in", "%zu", nf);
	fct_report("mean_edge", "%.9g", me);
	fct_report("tolerance", "%.9g", st.tolerance);
	fct_report("boundary_edges", "%zu", chains.boundary_edges);
	fct_report("boundary_vertices", "%zu", chains.boundary_vertices);
	fct_report("nonmanifold_edges", "%zu", chains.nonmanifold_edges);
	fct_report("junctions", "%zu", chains.junctions);
	fct_report("chains", "%zu", chains.n - chains.loops);
	fct_report("loops", "%zu", chains.loops);
	fct_report("vertices_kept", "%zu", st.kept_vertices);
	fct_report("edges", "%zu", st.segments);
	fct_report("max_dev", "%.9g", st.max_dev);
	fct_report("max_dev_edges", "%.6g", me > 0 ? st.max_dev / me : 0);
	fct_report("loop_points", "%zu", st.loop_points);
	fct_report("crossings_plain", "%zu", st.conflicts_plain);
	fct_report("crossing_points", "%zu", st.topology_points);
	fct_report("crossings_left", "%zu", st.conflicts_left);
	fct_report("crossings_left_image", "%zu", st.conflicts_left_image);
	fct_report("rounds", "%zu", st.rounds);
	fct_report("loops_dropped", "%zu", st.loops_dropped);
	fct_report("read_s", "%.4f", read_s);
	fct_report("simplify_s", "%.4f", simp_s);
	fct_report("total_s", "%.4f", total_s);
	fct_report("cpu_s", "%.4f", cpu_s);
	fct_chains_free(&chains);
	fct_mesh_free(&m);
	return 0;
}
