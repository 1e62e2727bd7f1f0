/* segplanes - segment a mesh into planar patches by global region growing:
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D
 * Models from Real Data" (DEC CRL 95/7), section 2.  The algorithm is
 * fct_segment (segment.h); this is its command line. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "cli/segopts.h"

static const char usage[] =
	"usage: segplanes [-aqv] [-c factor] [-n patches] [-o file] [--area-weighted]\n"
	"                 [--fit f] [--max-dev d] [--max-rms r] [--min-extent e]\n"
	"                 [--min-faces k] [--tls] [input]\n"
	"Label the faces of a mesh with planar patches (face property patch, -1 for\n"
	"free-form faces no plane fits) and add their planes (element plane),\n"
	"merging the adjacent patches that fit one plane best until a criterion\n"
	"stops it; every bound in units of the vertices' noise (vertex property\n"
	"sigma, or estimated from the data).\n"
	"  -a                 write ascii PLY\n"
	"  -c factor          automatic criterion: merge while the smaller patch moves\n"
	"                     by at most factor sigma, rms (default 3)\n"
	"  -n patches         stop at this many patches instead (T_N)\n"
	"  -o file            output file (default standard output)\n"
	"      --area-weighted\n"
	"                     weight each face by its area, not each corner by 1\n"
	"      --fit f        a patch's points stay within f sigma of its plane, rms\n"
	"                     (default 1.5)\n"
	"      --max-dev d    no face farther than d sigma from its patch's plane: it\n"
	"                     is free-form (default 3)\n"
	"      --max-rms r    never make a patch of rms above r (units of the\n"
	"                     coordinates; default no bound)\n"
	"      --min-extent e a patch narrower than e sigma is free-form (default 10)\n"
	"      --min-faces k  absorb patches of fewer than k faces into the adjacent\n"
	"                     patch of k or more that fits them best; those left are\n"
	"                     free-form (default 8)\n"
	"      --tls          fit planes orthogonally (eq. 1) even with a camera\n"
	"  -q                 quiet\n"
	"  -v                 report patches, noise, rms, merges and times on stderr\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum { OPT_VERSION = 256 };

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		FCT_SEG_LONGOPTS,
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ac:hn:o:qv";
	fct_cli_init("segplanes");
	struct fct_seg_opts so;
	fct_seg_opts_init(&so);
	const char *out = NULL;
	int ascii = 0, c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_seg_opt(&so, c, optarg))
			continue;
		switch (c) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("segplanes (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *input = fct_one_operand(argc, argv, optind, "-");
	fct_seg_opts_check(&so);
	const char *name = fct_path_display(input);

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now(), c0 = fct_cpu_time();
	if (fct_mesh_read_file(&m, input, NULL, &err))
		fct_die_err(&err);
	double read_s = fct_now() - t0;
	struct fct_segment_stats st;
	if (fct_segment_mesh(&m, &so.seg, so.tls, &st, &err))
		fct_die_err_at(&err, "%s", name);
	double seg_s = fct_now() - t0 - read_s;
	if (fct_header_add_provenance(&m, "segplanes", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err))
		fct_die_err(&err);
	double total_s = fct_now() - t0, cpu_s = fct_cpu_time() - c0;

	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("welded_vertices", "%zu", st.welded);
	fct_report("adjacencies", "%zu", st.adjacencies);
	fct_report("patches", "%zu", st.patches);
	fct_report("noise", "%.9g", st.noise);
	fct_report("noise_estimated", "%d", st.noise_estimated);
	fct_report("max_rms", "%.9g", st.max_rms);
	fct_report("mean_rms", "%.9g", st.mean_rms);
	fct_report("last_ratio", "%.9g", st.last_ratio);
	fct_report("clusters", "%zu", st.clusters);
	fct_report("merges", "%zu", st.merges);
	fct_report("absorbed", "%zu", st.absorbed);
	fct_report("peeled", "%zu", st.peeled);
	fct_report("grown", "%zu", st.grown);
	fct_report("settled", "%zu", st.settled);
	fct_report("narrow_faces", "%zu", st.narrow_faces);
	fct_report("free_faces", "%zu", st.free_faces);
	fct_report("sweeps", "%zu", st.sweeps);
	fct_report("evaluations", "%zu", st.evaluations);
	fct_report("repushes", "%zu", st.repushes);
	fct_report("read_s", "%.4f", read_s);
	fct_report("segment_s", "%.4f", seg_s);
	fct_report("total_s", "%.4f", total_s);
	fct_report("cpu_s", "%.4f", cpu_s);
	fct_report("faces_per_s", "%.0f", seg_s > 0 ? m.nf / seg_s : 0);
	fct_mesh_free(&m);
	return 0;
}
