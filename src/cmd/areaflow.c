/* areaflow - crease-preserving mesh smoothing by area decreasing flow: Sun,
 * Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor Scenes
 * Using a Mobile Range Scanner", sec. 2.  The algorithm (and the Laplacian
 * and Taubin baselines) is fct_areaflow (areaflow.h); this is its command
 * line. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fusion/areaflow.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"

static const char usage[] =
	"usage: areaflow [-aqv] [-o file] [--method name] [--iterations n]\n"
	"                [--lambda l] [--mu m] [--max-iterations n] [--tol t]\n"
	"                [--window w] [--sigma s] [--delta d] [--guide mode]\n"
	"                [--passes n] [--rings n] [--vote-rings n] [--crease-lo a]\n"
	"                [--crease-hi b] [--along dir] [--no-crease] [--write-crease]\n"
	"                [--threads n] [input]\n"
	"Smooth a triangle mesh by area decreasing flow: each vertex moves along its\n"
	"normal to the least area of its umbrella held by its distance from the input\n"
	"(eqs. 2 and 3), less where the tensor vote of the normals around it finds a\n"
	"crease (eq. 4).  When the noise is comparable to the sample spacing a\n"
	"smoothed guide gives the normals, the weights and the vote.  Every other\n"
	"property, element and comment is kept.\n"
	"  -a                 write ascii PLY\n"
	"  -o file            output file (default standard output)\n"
	"      --method name  areaflow (default), laplacian or taubin\n"
	"      --iterations n exactly n iterations (0: none; default: until the mean\n"
	"                     move is below --tol, at most --max-iterations)\n"
	"      --lambda l     areaflow: weight of the squared distance from the input\n"
	"                     in squared median edge lengths (default 1, 0 with the\n"
	"                     guide); laplacian and taubin: the step factor (0.5)\n"
	"      --mu m         taubin: the negative step factor (default -0.53)\n"
	"      --max-iterations n\n"
	"                     bound of the automatic stop (default 10)\n"
	"      --tol t        stop when the mean move is below t median edge\n"
	"                     (default 0.02)\n"
	"      --window w     geodesic radius of the crease vote without the guide,\n"
	"                     in median edge lengths (default 2.5)\n"
	"      --sigma s      vote weight exp(-(d/s)^2), s in median edge lengths\n"
	"                     (default 1.5)\n"
	"      --delta d      eq. 4: crease when the mean voted normal is within d of\n"
	"                     perpendicular to the main direction (default 0.3)\n"
	"      --guide mode   auto (default: on when 5 Laplacian passes shorten the\n"
	"                     median edge below 0.93 of the input's), on or off (the\n"
	"                     paper as written); the next five options turn it on\n"
	"      --passes n     guide: Laplacian passes of the copy that gives normals\n"
	"                     and umbrella shapes (default 5)\n"
	"      --rings n      guide: normals as area vectors averaged over n rings\n"
	"                     (default 8)\n"
	"      --vote-rings n guide: the vote as face tensors n n^T averaged over n\n"
	"                     rings (default 8; 0: the window walk)\n"
	"      --crease-lo a, --crease-hi b\n"
	"                     guide: s = (s - a) / (b - a) held to [0, 1]\n"
	"                     (defaults 0.05 and 0.15)\n"
	"      --along dir    guide: ray (default when the header has a pose or a\n"
	"                     pinhole camera: along the sensor's ray, as far as\n"
	"                     makes the move along the normal eq. 3's) or normal\n"
	"      --no-crease    no adaptive term: s = 0 everywhere\n"
	"      --write-crease add the float vertex property crease (s of the output)\n"
	"      --threads n    threads (default 0: one per processor)\n"
	"  -q                 quiet\n"
	"  -v                 report iterations, moves, crease, guide and times\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum {
	OPT_VERSION = 256, OPT_METHOD, OPT_ITER, OPT_LAMBDA, OPT_MU, OPT_MAXIT, OPT_TOL,
	OPT_WINDOW, OPT_SIGMA, OPT_DELTA, OPT_NOCREASE, OPT_WRITE, OPT_THREADS, OPT_RINGS, OPT_PASSES, OPT_VRINGS,
	OPT_CLO, OPT_CHI, OPT_ALONG, OPT_GUIDE
};

/* Keep nx ny nz true to the moved surface, on the side they pointed to. */
static void update_normals(struct fct_mesh *m, const char *name)
{
	struct fct_prop *px = fct_elem_find(&m->vertex, "nx");
	struct fct_prop *py = fct_elem_find(&m->vertex, "ny");
	struct fct_prop *pz = fct_elem_find(&m->vertex, "nz");
	if (!px || !py || !pz || px->count_type || py->count_type || pz->count_type)
		return;
	double *vn = malloc(sizeof *vn * 3 * (m->nv ? m->nv : 1));
	if (!vn)
		fct_die(1, "%s: out of memory for the normals of %zu vertices", name, m->nv);
	fct_vertex_normals(m, vn);
	for (size_t v = 0; v < m->nv; v++) {
		double *n = vn + 3 * v;
		if (n[0] == 0 && n[1] == 0 && n[2] == 0)
			continue;   /* no faces: keep the given normal */
		double old[3] = { fct_prop_get(px, v), fct_prop_get(py, v), fct_prop_get(pz, v) };
		double dot = old[0] * n[0] + old[1] * n[1] + old[2] * n[2];
		double sg = dot < 0 ? -1 : 1;
		fct_prop_set(px, v, sg * n[0]);
		fct_prop_set(py, v, sg * n[1]);
		fct_prop_set(pz, v, sg * n[2]);
	}
	free(vn);
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		{"method", required_argument, NULL, OPT_METHOD},
		{"iterations", required_argument, NULL, OPT_ITER},
		{"lambda", required_argument, NULL, OPT_LAMBDA},
		{"mu", required_argument, NULL, OPT_MU},
		{"max-iterations", required_argument, NULL, OPT_MAXIT},
		{"tol", required_argument, NULL, OPT_TOL},
		{"window", required_argument, NULL, OPT_WINDOW},
		{"sigma", required_argument, NULL, OPT_SIGMA},
		{"delta", required_argument, NULL, OPT_DELTA},
		{"rings", required_argument, NULL, OPT_RINGS},
		{"passes", required_argument, NULL, OPT_PASSES},
		{"vote-rings", required_argument, NULL, OPT_VRINGS},
		{"crease-lo", required_argument, NULL, OPT_CLO},
		{"crease-hi", required_argument, NULL, OPT_CHI},
		{"along", required_argument, NULL, OPT_ALONG},
		{"guide", required_argument, NULL, OPT_GUIDE},
		{"no-crease", no_argument, NULL, OPT_NOCREASE},
		{"write-crease", no_argument, NULL, OPT_WRITE},
		{"threads", required_argument, NULL, OPT_THREADS},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "aho:qv";
	fct_cli_init("areaflow");
	struct fct_areaflow_params p;
	fct_areaflow_params_default(&p);
	const char *out = NULL;
	int ascii = 0, c, write_crease = 0, lambda_given = 0, mu_given = 0, along = -1, guide_opt = 0,
	    guide_given = 0;
	double lambda = 0;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("areaflow (facet) " FCT_VERSION); return 0;
		case OPT_METHOD:
			if (!strcmp(optarg, "areaflow"))
				p.method = FCT_SMOOTH_AREAFLOW;
			else if (!strcmp(optarg, "laplacian"))
				p.method = FCT_SMOOTH_LAPLACIAN;
			else if (!strcmp(optarg, "taubin"))
				p.method = FCT_SMOOTH_TAUBIN;
			else
				fct_usage_error("--method: \"%s\" is not areaflow, laplacian or taubin", optarg);
			break;
		case OPT_ITER: p.iterations = (int)fct_opt_long("--iterations", optarg, 0, 1000000); break;
		case OPT_LAMBDA:
			lambda = fct_opt_double("--lambda", optarg, 0, 1e12);
			lambda_given = 1;
			break;
		case OPT_MU:
			p.taubin_mu = fct_opt_double("--mu", optarg, -1e3, 1e3);
			mu_given = 1;
			break;
		case OPT_MAXIT: p.max_iterations = (int)fct_opt_long("--max-iterations", optarg, 0, 1000000); break;
		case OPT_TOL: p.tol = fct_opt_double("--tol", optarg, 0, 1e12); break;
		case OPT_WINDOW: p.window = fct_opt_double("--window", optarg, 0, 100); break;
		case OPT_SIGMA: p.sigma = fct_opt_double("--sigma", optarg, 1e-6, 1e6); break;
		case OPT_DELTA: p.delta = fct_opt_double("--delta", optarg, 0, 1); break;
		case OPT_PASSES: p.passes = (int)fct_opt_long("--passes", optarg, 0, 1000); guide_opt = 1; break;
		case OPT_CLO: p.crease_lo = fct_opt_double("--crease-lo", optarg, 0, 1); guide_opt = 1; break;
		case OPT_CHI: p.crease_hi = fct_opt_double("--crease-hi", optarg, 0, 1); guide_opt = 1; break;
		case OPT_ALONG:
			if (!strcmp(optarg, "ray"))
				along = 1;
			else if (!strcmp(optarg, "normal"))
				along = 0;
			else
				fct_usage_error("--along: \"%s\" is not ray or normal", optarg);
			break;
		case OPT_GUIDE:
			guide_given = 1;
			if (!strcmp(optarg, "auto"))
				p.guide = -1;
			else if (!strcmp(optarg, "on"))
				p.guide = 1;
			else if (!strcmp(optarg, "off"))
				p.guide = 0;
			else
				fct_usage_error("--guide: \"%s\" is not auto, on or off", optarg);
			break;
		case OPT_VRINGS: p.vote_rings = (int)fct_opt_long("--vote-rings", optarg, 0, 1000); guide_opt = 1; break;
		case OPT_RINGS: p.rings = (int)fct_opt_long("--rings", optarg, 0, 1000); guide_opt = 1; break;
		case OPT_NOCREASE: p.crease = 0; break;
		case OPT_WRITE: write_crease = 1; break;
		case OPT_THREADS: p.threads = (int)fct_opt_long("--threads", optarg, 0, 64); break;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *input = fct_one_operand(argc, argv, optind, "-");
	if (mu_given && p.method != FCT_SMOOTH_TAUBIN)
		fct_usage_error("--mu: only with --method taubin");
	if (lambda_given) {
		if (p.method == FCT_SMOOTH_AREAFLOW)
			p.lambda = lambda;
		else if (lambda > 1)
			fct_usage_error("--lambda: %g: a Laplacian step factor must be in [0, 1]", lambda);
		else
			p.lap_lambda = lambda;
	}
	if (guide_opt && !guide_given)
		p.guide = 1;   /* an option of the guide turns it on */
	const char *name = fct_path_display(input);

	struct fct_err err;
	struct fct_mesh m;
	double t0 = fct_now(), c0 = fct_cpu_time();
	if (fct_mesh_read_file(&m, input, NULL, &err))
		fct_die_err(&err);
	double read_s = fct_now() - t0;
	/* The viewpoint: the pose's origin, else the pinhole camera's. */
	struct fct_camera cam;
	double pose[12];
	int has_cam = fct_header_camera(&m, &cam, &err) == 1 && cam.kind == FCT_CAMERA_PINHOLE;
	int has_pose = fct_header_pose(&m, pose, &err) == 1;
	if (along == 1 && !has_cam && !has_pose)
		fct_die(1, "%s: --along ray: no pose and no pinhole camera in the header", name);
	if (along != 0 && (has_cam || has_pose)) {
		p.along_ray = 1;
		if (has_pose)
			p.origin[0] = pose[3], p.origin[1] = pose[7], p.origin[2] = pose[11];
	}
	if (m.nf == 0 && !fct_quiet)
		fct_warn("%s: no faces: the vertices are written unchanged", name);
	double *crease = NULL;
	if (write_crease && !(crease = malloc(sizeof *crease * (m.nv ? m.nv : 1))))
		fct_die(1, "%s: out of memory for %zu vertices", name, m.nv);
	struct fct_areaflow_stats st;
	double t1 = fct_now();
	if (fct_areaflow(&m, &p, crease, &st, &err))
		fct_die_err_at(&err, "%s", name);
	double smooth_s = fct_now() - t1;
	update_normals(&m, name);
	if (crease) {
		struct fct_prop *pc = fct_elem_add_scalar(&m.vertex, "crease", FCT_FLOAT32, &err);
		if (!pc)
			fct_die_err(&err);
		for (size_t v = 0; v < m.nv; v++)
			fct_prop_set(pc, v, crease[v]);
	}
	if (fct_header_add_provenance(&m, "areaflow", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, out, ascii, &err))
		fct_die_err(&err);
	double total_s = fct_now() - t0, cpu_s = fct_cpu_time() - c0;

	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("moving", "%zu", st.moving);
	fct_report("held", "%zu", st.held);
	fct_report("isolated", "%zu", st.isolated);
	fct_report("iterations", "%d", st.iterations);
	fct_report("median_edge", "%.9g", st.edge);
	fct_report("last_move", "%.9g", st.last_move);
	fct_report("mean_offset", "%.9g", st.mean_offset);
	fct_report("max_offset", "%.9g", st.max_offset);
	fct_report("mean_crease", "%.9g", st.mean_crease);
	fct_report("threads", "%zu", st.threads);
	fct_report("window_ids", "%zu", st.window_ids);
	fct_report("window_walks", "%zu", st.window_walks);
	fct_report("guide", "%d", st.guide);
	fct_report("edge_ratio", "%.6g", st.edge_ratio);
	fct_report("along_ray", "%d", st.guide && p.along_ray);
	fct_report("read_s", "%.4f", read_s);
	fct_report("smooth_s", "%.4f", smooth_s);
	fct_report("total_s", "%.4f", total_s);
	fct_report("cpu_s", "%.4f", cpu_s);
	fct_report("vertex_updates_per_s", "%.0f",
	           smooth_s > 0 ? (double)st.moving * st.iterations / smooth_s : 0);
	free(crease);
	fct_mesh_free(&m);
	return 0;
}
