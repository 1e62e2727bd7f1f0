/* qemdecim - decimate a triangle mesh by quadric edge collapse (Garland and
 * Heckbert 1997; see src/lib/geom/qem.h): the baseline the planar pipeline of
 * Kang et al. is measured against at the same face count. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "geom/qem.h"

static const char usage[] =
	"usage: qemdecim [-acqv] [-b weight] [-e error] [-o file] [-n faces | -r ratio]\n"
	"                [input]\n"
	"Decimate a triangle mesh by quadric edge collapse (Garland-Heckbert) to a\n"
	"face count or an error bound; vertex properties follow the collapses.\n"
	"  -a            write ascii PLY\n"
	"  -b weight     weight of the planes that hold the mesh border in place\n"
	"                (default 1; 0: the border moves freely)\n"
	"  -c            let collapses close holes of three edges (the topology then\n"
	"                changes; without -c every hole stays open)\n"
	"  -e error      refuse collapses whose quadric distance (area-weighted RMS\n"
	"                distance to the planes of the faces they replace) exceeds\n"
	"                error, in the units of the coordinates (default: no bound)\n"
	"  -n faces      target face count (default: half the triangles, or with -e\n"
	"                alone as few as the bound allows)\n"
	"  -o file       output file (default stdout); .obj writes OBJ\n"
	"  -q            quiet\n"
	"  -r ratio      target face count as a fraction of the triangles, in [0, 1]\n"
	"  -v            report counts, errors and times on stderr\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("qemdecim");
	const char *out = NULL;
	int ascii = 0, c;
	long faces = -1;
	double ratio = -1;
	struct fct_qem_params par;
	fct_qem_params_default(&par);
	static const char optstring[] = "ab:ce:hn:o:qr:v";
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'b': par.border_weight = fct_opt_double("-b", optarg, 0, 1e12); break;
		case 'c': par.close_holes = 1; break;
		case 'e': par.max_error = fct_opt_double("-e", optarg, 0, INFINITY); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'n': faces = fct_opt_long("-n", optarg, 0, 0x7fffffffL); break;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'r': ratio = fct_opt_double("-r", optarg, 0, 1); break;
		case 'v': fct_verbose = 1; break;
		case 'V': puts("qemdecim (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (faces >= 0 && ratio >= 0)
		fct_usage_error("-n and -r cannot both be given");
	const char *in = fct_one_operand(argc, argv, optind, NULL);
	const char *name = fct_path_display(in);

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now(), c0 = fct_cpu_time();
	if (fct_mesh_read_file(&m, in, NULL, &err))
		fct_die_err(&err);
	double t1 = fct_now(), c1 = fct_cpu_time();
	size_t nf = 0;   /* triangles the faces fan into */
	for (size_t f = 0; f < m.nf; f++)
		nf += fct_face_size(&m, f) >= 3 ? fct_face_size(&m, f) - 2 : 0;
	if (faces >= 0)
		par.target_faces = (size_t)faces;
	else if (ratio >= 0)
		par.target_faces = (size_t)floor(ratio * (double)nf + 0.5);
	else if (par.max_error > 0)
		par.target_faces = 0;
	else
		par.target_faces = nf / 2;

	struct fct_qem_stats st;
	if (fct_qem_decimate(&m, &par, &st, &err))
		fct_die_err_at(&err, "%s", name);
	double t2 = fct_now(), c2 = fct_cpu_time();
	if (fct_header_add_provenance(&m, "qemdecim", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err)) {
		fct_mesh_free(&m);
		fct_die_err(&err);
	}
	if (st.faces_out > par.target_faces + 1 && !(par.max_error > 0))
		fct_warn("stopped at %zu faces, above the target %zu: no further collapse keeps "
		         "the mesh valid%s", st.faces_out, par.target_faces,
		         par.close_holes ? "" : " (-c lets holes close)");
	fct_report("vertices_in", "%zu", st.vertices_in);
	fct_report("faces_in", "%zu", st.faces_in);
	fct_report("target", "%zu", par.target_faces);
	fct_report("vertices_out", "%zu", st.vertices_out);
	fct_report("faces_out", "%zu", st.faces_out);
	fct_report("dropped", "%zu", st.dropped);
	fct_report("locked", "%zu", st.locked);
	fct_report("collapses", "%zu", st.collapses);
	fct_report("refused_topology", "%zu", st.refused_topology);
	fct_report("refused_flip", "%zu", st.refused_flip);
	fct_report("refused_error", "%zu", st.refused_error);
	fct_report("passes", "%zu", st.passes);
	fct_report("holes_closed", "%zu", st.holes_closed);
	fct_report("max_error", "%.9g", st.max_error);
	fct_report("max_cost", "%.9g", st.max_cost);
	fct_report("read_s", "%.3f", t1 - t0);
	fct_report("decimate_s", "%.3f", t2 - t1);
	fct_report("decimate_cpu_s", "%.3f", c2 - c1);
	fct_report("write_s", "%.3f", fct_now() - t2);
	fct_report("cpu_s", "%.3f", fct_cpu_time() - c0);
	fct_mesh_free(&m);
	return 0;
}
