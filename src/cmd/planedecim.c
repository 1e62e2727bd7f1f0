/* planedecim - the planar model of a segmented mesh: planes where the
 * surface is planar, a decimated surface elsewhere, one connected mesh.
 * segplanes' patches (Kang, Johnson and Szeliski, DEC CRL 95/7, sec. 3)
 * guide a quadric edge collapse (Garland and Heckbert 1997) that decimates
 * the free-form faces (sec. 9's open case) to an error bound in units of
 * the sensor's noise; each patch is then the polygon of its simplified
 * outline, triangulated (sec. 4), its vertices on the planes' lines and
 * corners (sec. 5).  The algorithm is fct_planar_model (planemodel.h);
 * this is its command line.  A mesh with vertex colours written to a file
 * gets an atlas baked from them (colbake.h), as planarize's does. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli/bakeopts.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "cli/planaropts.h"

static const char usage[] =
	"usage: planedecim [-aqv] [-e error] [-o file] [--border k]\n"
	"                  [--max-hole k] [--max-move k] [--min-free k] [--min-piece k]\n"
	"                  [--min-plane k] [--outline k] [--texel size] [input]\n"
	"Make the planar model of a mesh segmented by segplanes: the free-form faces\n"
	"(patch -1) decimated to an error bound, each patch the polygon of its\n"
	"simplified outline in its plane, vertices where patches meet on their line\n"
	"or corner, all one connected mesh; a mesh with vertex colours written to a\n"
	"file, textured by an atlas baked from them.\n"
	"  -a             write ascii PLY\n"
	"  -e error       the free-form decimation's bound: the largest quadric\n"
	"                 distance of a collapse, in units of sigma (default 1.5)\n"
	"  -o file        output file (default standard output)\n"
	"      --border k a border may move by k edge lengths (default 1)\n"
	"      --max-hole k\n"
	"                 fill the holes of at most k edges inside one patch and,\n"
	"                 without a camera, those of the surface within the noise\n"
	"                 of a plane (default 64; 0: none)\n"
	"      --max-move k\n"
	"                 move a vertex onto a line or corner by at most k sigma,\n"
	"                 and a speck onto the plane around it only when most of\n"
	"                 it is within k sigma of it (default 4)\n"
	"      --min-free k\n"
	"                 a speck of fewer than k faces joins the label around it\n"
	"                 (default 64)\n"
	"      --min-piece k\n"
	"                 without a camera (a fused scan), drop the pieces of fewer\n"
	"                 than k faces: the fusion's floating debris (default 64;\n"
	"                 0: keep every piece)\n"
	"      --min-plane k\n"
	"                 a patch of fewer than k faces is free-form (default 64)\n"
	"      --outline k\n"
	"                 simplify the patches' outlines to k sample spacings\n"
	"                 (pixels at the vertex's distance; default 3)\n"
	"      --texel size\n"
	"                 the texels, metres, of the atlas baked from the mesh's\n"
	"                 vertex colours, file_atlas0.png beside -o file (default\n"
	"                 half the mesh's mean edge; 0: vertex colours only)\n"
	"  -q             quiet\n"
	"  -v             report counts, errors and times on stderr\n"
	"  -h, --help     this help\n"
	"      --version  print the version\n";

enum { OPT_VERSION = 256 };

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		FCT_PLANAR_LONGOPTS,
		FCT_BAKE_LONGOPTS,
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ae:ho:qv";
	fct_cli_init("planedecim");
	struct fct_planar_params par;
	fct_planar_params_default(&par);
	struct fct_bake_opts bo;
	fct_bake_opts_init(&bo);
	const char *out = NULL;
	int ascii = 0, c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_planar_opt(&par, c, optarg) || fct_bake_opt(&bo, c, optarg))
			continue;
		switch (c) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("planedecim (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *in = fct_one_operand(argc, argv, optind, "-");
	const char *name = fct_path_display(in);

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now(), c0 = fct_cpu_time();
	if (fct_mesh_read_file(&m, in, NULL, &err))
		fct_die_err(&err);
	/* The input's colours, kept for the model's atlas. */
	struct fct_colbake bake = { 0 };
	int baking = fct_bake_wanted(&bo, out, &m);
	if (baking && fct_colbake_init(&bake, &m, &err))
		fct_die_err_at(&err, "bake");
	double t1 = fct_now();
	struct fct_planar_stats st;
	if (fct_planar_model(&m, &par, &st, &err))
		fct_die_err_at(&err, "%s", name);
	double t2 = fct_now();
	if (baking && fct_colbake_applies(&m))
		fct_bake_model(&m, &bake, &bo, out);
	fct_colbake_free(&bake);
	double t3 = fct_now();
	if (fct_header_add_provenance(&m, "planedecim", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err)) {
		fct_mesh_free(&m);
		fct_die_err(&err);
	}
	fct_report("vertices_in", "%zu", st.vertices_in);
	fct_report("faces_in", "%zu", st.faces_in);
	fct_report("vertices", "%zu", st.vertices_out);
	fct_report("faces", "%zu", st.faces_out);
	fct_report("reduction", "%.1f", st.faces_out ? (double)st.faces_in / (double)st.faces_out : 0);
	fct_report("planes", "%zu", st.planes);
	fct_report("sigma_estimated", "%d", st.sigma_estimated);
	fct_report("facets", "%zu", st.facets);
	fct_report("small_faces", "%zu", st.tidy.small_faces);
	fct_report("debris_pieces", "%zu", st.debris_pieces);
	fct_report("debris_faces", "%zu", st.debris_faces);
	fct_report("speck_faces", "%zu", st.tidy.speck_faces);
	fct_report("off_plane_faces", "%zu", st.tidy.off_plane_faces);
	fct_report("closed_faces", "%zu", st.tidy.closed_faces);
	fct_report("seam_faces", "%zu", st.tidy.seam_faces);
	fct_report("holes_filled", "%zu", st.holes_filled);
	fct_report("free_holes_filled", "%zu", st.free_holes_filled);
	fct_report("projected", "%zu", st.projected);
	fct_report("creased", "%zu", st.creased);
	fct_report("split", "%zu", st.split);
	fct_report("uncreased", "%zu", st.uncreased);
	fct_report("collapses", "%zu", st.qem.collapses);
	fct_report("corners", "%zu", st.qem.corners);
	fct_report("refused_topology", "%zu", st.qem.refused_topology);
	fct_report("refused_flip", "%zu", st.qem.refused_flip);
	fct_report("refused_error", "%zu", st.qem.refused_error);
	fct_report("max_error", "%.9g", st.qem.max_error);
	fct_report("free_faces_in", "%zu", st.qem.faces_in);
	fct_report("free_faces", "%zu", st.free_faces);
	fct_report("border_free_faces", "%zu", st.border_free_faces);
	fct_report("outline_vertices", "%zu", st.chains.kept_vertices);
	fct_report("outline_tolerance", "%.9g", st.chains.tolerance);
	fct_report("planar_triangles", "%zu", st.planar_triangles);
	fct_report("rounds", "%zu", st.rounds);
	fct_report("dense_patches", "%zu", st.dense_patches);
	fct_report("pinned", "%zu", st.pinned);
	fct_report("mended", "%zu", st.mended);
	fct_report("tightened", "%zu", st.tightened);
	fct_report("unclean_patches", "%zu", st.unclean_patches);
	fct_report("reprojected", "%zu", st.reprojected);
	fct_report("moved_line", "%zu", st.meet.lines);
	fct_report("moved_corner", "%zu", st.meet.corners);
	fct_report("stayed", "%zu", st.meet.stayed);
	fct_report("moves_undone", "%zu", st.meet.undone);
	fct_report("torn", "%zu", st.meet.torn);
	fct_report("no_pixel", "%zu", st.no_pixel);
	fct_report("read_s", "%.3f", t1 - t0);
	fct_report("model_s", "%.3f", t2 - t1);
	fct_report("bake_s", "%.3f", t3 - t2);
	fct_report("total_s", "%.3f", fct_now() - t0);
	fct_report("cpu_s", "%.3f", fct_cpu_time() - c0);
	fct_mesh_free(&m);
	return 0;
}
