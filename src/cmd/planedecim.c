/* planedecim - the planar model of a segmented mesh: planes where the
 * surface is planar, a decimated surface elsewhere, one connected mesh.
 * segplanes' patches (Kang, Johnson and Szeliski, DEC CRL 95/7, sec. 3)
 * become quadric proxies of Garland and Heckbert's edge collapse, which
 * keeps every patch boundary and decimates the free-form faces (sec. 9's
 * open case) to the same error bound, in units of the sensor's noise.  The
 * algorithm is fct_qem_decimate with planes (qem.h); this is its command
 * line. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "cli.h"
#include "header.h"
#include "meshio.h"
#include "path.h"
#include "planes.h"
#include "project.h"
#include "planemodel.h"
#include "qem.h"

static const char usage[] =
	"usage: planedecim [-aqv] [-e error] [-n faces] [-o file] [--max-move k]\n"
	"                  [--min-free k] [--min-plane k] [input]\n"
	"Make the planar model of a mesh segmented by segplanes: every vertex on\n"
	"its patch's plane (on two patches' line, three patches' corner), each\n"
	"patch decimated to its boundary, the free-form faces (patch -1) by\n"
	"quadric edge collapse to the error bound, all one connected mesh.\n"
	"  -a             write ascii PLY\n"
	"  -e error       the largest quadric distance of a collapse, in units of\n"
	"                 the vertices' sigma (default 1)\n"
	"  -n faces       stop at this many triangles (default: the bound alone)\n"
	"  -o file        output file (default standard output)\n"
	"      --max-move k\n"
	"                 move a vertex to a line or corner by at most k sigma,\n"
	"                 else onto its nearest plane (default 4)\n"
	"      --min-free k\n"
	"                 a speck of fewer than k free-form faces inside one patch\n"
	"                 joins it (default 64)\n"
	"      --min-plane k\n"
	"                 a patch of fewer than k faces is free-form (default 64)\n"
	"  -q             quiet\n"
	"  -v             report counts, errors and times on stderr\n"
	"  -h, --help     this help\n"
	"      --version  print the version\n";

enum { OPT_MAXMOVE = 256, OPT_MINFREE, OPT_MINPLANE, OPT_BORDER, OPT_MAXHOLE, OPT_VERSION };

/* Each vertex's sigma: the property, or the planes' median rms for all. */
static double *vertex_sigma(const struct fct_mesh *m, const struct fct_plane *pl, size_t np,
                            const char *name)
{
	double *sigma = malloc((m->nv ? m->nv : 1) * sizeof *sigma);
	if (!sigma)
		fct_die(1, "%s: out of memory for %zu vertices", name, m->nv);
	const struct fct_prop *p = fct_elem_find(&m->vertex, "sigma");
	if (p && p->count_type == FCT_NONE) {
		for (size_t v = 0; v < m->nv; v++)
			sigma[v] = fct_prop_get(p, v);
		return sigma;
	}
	double *r = malloc((np ? np : 1) * sizeof *r), s = 0;
	if (!r)
		fct_die(1, "%s: out of memory", name);
	size_t n = 0;
	for (size_t l = 0; l < np; l++)
		if (pl[l].rms > 0)
			r[n++] = pl[l].rms;
	for (size_t i = 1; i < n; i++)
		for (size_t j = i; j > 0 && r[j - 1] > r[j]; j--) {
			double t = r[j];
			r[j] = r[j - 1], r[j - 1] = t;
		}
	s = n ? r[n / 2] : 0;
	free(r);
	for (size_t v = 0; v < m->nv; v++)
		sigma[v] = s;
	return sigma;
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"max-move", required_argument, NULL, OPT_MAXMOVE},
		{"min-free", required_argument, NULL, OPT_MINFREE},
		{"border", required_argument, NULL, OPT_BORDER},
		{"max-hole", required_argument, NULL, OPT_MAXHOLE},
		{"min-plane", required_argument, NULL, OPT_MINPLANE},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ae:hn:o:qv";
	fct_cli_init("planedecim");
	struct fct_qem_params par;
	fct_qem_params_default(&par);
	par.max_error = 1;
	const char *out = NULL;
	int ascii = 0, c;
	long min_free = 64, min_plane = 64, max_hole = 64;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'e': par.max_error = fct_opt_double("-e", optarg, 0, INFINITY); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'n': par.target_faces = (size_t)fct_opt_long("-n", optarg, 0, 0x7fffffffL); break;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_MAXMOVE: par.max_move = fct_opt_double("--max-move", optarg, 0, INFINITY); break;
		case OPT_MAXHOLE: max_hole = fct_opt_long("--max-hole", optarg, 0, 0x7fffffffL); break;
		case OPT_BORDER: par.border_tol = fct_opt_double("--border", optarg, 0, INFINITY); break;
		case OPT_MINFREE: min_free = fct_opt_long("--min-free", optarg, 0, 0x7fffffffL); break;
		case OPT_MINPLANE: min_plane = fct_opt_long("--min-plane", optarg, 0, 0x7fffffffL); break;
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
	struct fct_plane *pl = NULL;
	size_t np = 0;
	int32_t *patch = NULL;
	int present = 0;
	if (fct_planes_get(&m, &pl, &np, &err) ||
	    fct_patches_get(&m, &patch, &present, (long)np, &err)) {
		fct_err_prefix(&err, "%s", name);
		fct_die_err(&err);
	}
	if (!present)
		fct_die(1, "%s: no face property patch: segment it first (segplanes)", name);
	double *sigma = vertex_sigma(&m, pl, np, name);
	struct fct_tidy_stats ts;
	size_t holes = 0;
	if (fct_patches_tidy(patch, &m, (size_t)min_plane, (size_t)min_free, &ts, &err) ||
	    (max_hole >= 3 && fct_fill_plane_holes(&m, &patch, pl, np, (size_t)max_hole, &holes, &err)) ||
	    fct_patches_set(&m, patch, &err)) {
		fct_err_prefix(&err, "%s", name);
		fct_die_err(&err);
	}
	struct fct_camera cam;
	double pose[12], inv[12];
	int have_cam = fct_header_camera(&m, &cam, &err), have_pose = 0;
	if (have_cam > 0 && (have_pose = fct_header_pose(&m, pose, &err)) > 0)
		fct_pose_invert(pose, inv);
	if (have_cam < 0 || have_pose < 0) {
		fct_err_prefix(&err, "%s", name);
		fct_die_err(&err);
	}
	if (have_cam > 0) {
		par.use_viewpoint = 1;
		if (have_pose > 0)
			par.viewpoint[0] = pose[3], par.viewpoint[1] = pose[7], par.viewpoint[2] = pose[11];
	}
	double t1 = fct_now();
	par.patch = patch;
	par.planes = pl;
	par.nplanes = np;
	par.sigma = sigma;
	struct fct_qem_stats st;
	if (fct_qem_decimate(&m, &par, &st, &err)) {
		fct_err_prefix(&err, "%s", name);
		fct_die_err(&err);
	}
	size_t no_pixel = 0;
	int had_st = fct_elem_find(&m.vertex, "s") && fct_elem_find(&m.vertex, "t");
	if (have_cam > 0 && had_st && fct_camera_texcoords(&m, &cam, have_pose ? inv : NULL, &no_pixel, &err))
		fct_die_err(&err);
	double t2 = fct_now();
	if (fct_header_add_provenance(&m, "planedecim", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err))
		fct_die_err(&err);
	fct_report("vertices_in", "%zu", st.vertices_in);
	fct_report("faces_in", "%zu", st.faces_in);
	fct_report("vertices_out", "%zu", st.vertices_out);
	fct_report("faces_out", "%zu", st.faces_out);
	fct_report("reduction", "%.1f", st.faces_out ? (double)st.faces_in / st.faces_out : 0);
	fct_report("planes", "%zu", np);
	fct_report("small_faces", "%zu", ts.small_faces);
	fct_report("speck_faces", "%zu", ts.speck_faces);
	fct_report("holes_filled", "%zu", holes);
	fct_report("corners", "%zu", st.corners);
	fct_report("moved_line", "%zu", st.moved_line);
	fct_report("moved_corner", "%zu", st.moved_corner);
	fct_report("kept_plane", "%zu", st.kept_plane);
	fct_report("collapses", "%zu", st.collapses);
	fct_report("refused_topology", "%zu", st.refused_topology);
	fct_report("refused_flip", "%zu", st.refused_flip);
	fct_report("refused_error", "%zu", st.refused_error);
	fct_report("max_error", "%.9g", st.max_error);
	fct_report("no_pixel", "%zu", no_pixel);
	fct_report("read_s", "%.3f", t1 - t0);
	fct_report("decimate_s", "%.3f", t2 - t1);
	fct_report("total_s", "%.3f", fct_now() - t0);
	fct_report("cpu_s", "%.3f", fct_cpu_time() - c0);
	free(sigma);
	free(patch);
	free(pl);
	fct_mesh_free(&m);
	return 0;
}
