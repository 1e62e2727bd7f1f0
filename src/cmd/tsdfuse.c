/* tsdfuse - several registered range-image meshes fused into one surface:
 * Sun, Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor
 * Scenes Using a Mobile Range Scanner", sec. 3: Hilton's true signed
 * distance in a sparse volume, confidence-weighted averaging, optional
 * space carving, marching cubes, and level-set curvature flow. */
#include <getopt.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "cli/cli.h"
#include "fusion/fuse.h"
#include "geom/adj.h"
#include "cli/fuseopts.h"
#include "cli/fuseviews.h"
#include "io/header.h"
#include "fusion/mcubes.h"
#include "io/meshio.h"

static const char usage[] =
	"usage: tsdfuse [-aqv] [-o file] [--voxel size] [--trunc n] [--bbox x0,y0,z0,x1,y1,z1]\n"
	"               [--carve] [--exact] [--weight constant | incidence | depth2]\n"
	"               [--curvature-flow iter] [--min-piece k] [--min-weight w]\n"
	"               [--projective] [-K fx,fy,cx,cy | name | --camera file]\n"
	"               [--depth-scale s] [--depth-code c] [--baseline b] [--doffs d]\n"
	"               [--noise model | file] [--smooth px] [--poses file ...]\n"
	"               [--max-difference s] [--color] [--image file ...]\n"
	"               [--conf file] [--threads n] [view ...]\n"
	"Fuse registered views (meshes carrying their camera and pose comments, depth\n"
	"images with -K and --poses, or the range-grid scans of a --conf file) by\n"
	"the true signed distance to each view's surface, and extract the surface.\n"
	"  -a                 write ascii PLY\n"
	"  -K fx,fy,cx,cy     camera of the depth-image views (or a dataset name)\n"
	"      --baseline b   the depth images hold disparities: depth = b * fx /\n"
	"                     (disparity + doffs)\n"
	"      --camera file  camera of the depth images from a file: Open3D intrinsic\n"
	"                     JSON, a 3x3 K, a camera line, Middlebury's calib.txt\n"
	"      --doffs d      disparity offset (Middlebury; default 0 or calib.txt's)\n"
	"  -o file            output file (default standard output)\n"
	"  -q                 quiet\n"
	"  -v                 progress per view, then figures on stderr\n"
	"      --bbox x0,y0,z0,x1,y1,z1\n"
	"                     fuse and extract only inside this box (metres); tiles\n"
	"                     sharing faces join without cracks\n"
	"      --carve        space carving: close occlusion holes (watertight rooms)\n"
	"      --color        vertex colour from the views' images (TextureFile\n"
	"                     comments, --image); unseen vertices are grey 128\n"
	"      --conf file    Stanford/VRIP .conf naming range-grid PLY scans\n"
	"      --curvature-flow iter\n"
	"                     level-set mean-curvature steps after fusion (default 0)\n"
	"      --depth-code c the depth images' encoding (as dm2mesh; default none, or\n"
	"                     the -K name's)\n"
	"      --depth-scale s\n"
	"                     PNG depth units per metre (default 1000, or the -K name's)\n"
	"      --exact        true distance from depth images to the nearest point of\n"
	"                     their mesh at every pixel, searched (slower), not to the\n"
	"                     tangent planes of samples 0.6 voxels apart\n"
	"      --image file   colour image of the depth-image views, in their order\n"
	"                     (repeated; implies --color)\n"
	"      --max-difference s\n"
	"                     TUM trajectory: a depth image's pose is the nearest in\n"
	"                     time to the timestamp in its name, within s (default 0.02)\n"
	"      --min-piece k  drop the extracted surface's pieces of fewer than k\n"
	"                     faces, the floating debris of noise (default 0: keep\n"
	"                     all; the largest piece always stays)\n"
	"      --min-weight w extract only voxels of at least this weight (default 0)\n"
	"      --noise model  the depth images' noise: none, kinect[:F,B[,SD[,STEP]]],\n"
	"                     tof[:A,B], poly:A,B,C, stereo:FB,SD[,DOFFS], or a file\n"
	"                     holding a line \"noise ...\"; smooths and meshes them\n"
	"                     with it and weighs true distance by it (default: kinect\n"
	"                     for a -K dataset name, else none)\n"
	"      --poses file   camera-to-world poses of the depth images: one file of\n"
	"                     them all (TUM trajectory, Redwood .log, KITTI poses,\n"
	"                     stacked 4x4), or a 4x4 or 3x4 file per image (repeated)\n"
	"      --projective   Curless-Levoy depth difference instead of true distance\n"
	"      --smooth px    half-width of the noise-aware smoothing of depth images\n"
	"                     with a noise model (default 2; 0: none)\n"
	"      --threads n    threads (default 0: one per processor)\n"
	"      --trunc n      band half-width in voxels (default 3)\n"
	"      --voxel size   voxel size in metres (default 0.01)\n"
	"      --weight w     confidence of a view: constant (default), incidence\n"
	"                     (cosine of the viewing angle), depth2 (1/depth^2)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum { OPT_BBOX = 256, OPT_CARVE, OPT_EXACT, OPT_WEIGHT, OPT_FLOW, OPT_MINW, OPT_PROJ, OPT_CONF, OPT_VERSION,
       OPT_COLOR, OPT_BASELINE, OPT_DOFFS, OPT_MINPIECE };

struct options {
	const char *out, *conf;
	int color;
	int ascii, carve, flow, has_bbox, doffs_given;
	double min_weight, bbox[6], baseline, doffs;
	size_t min_piece;         /* --min-piece: smaller pieces dropped (0: none) */
	struct fct_fuse_opts f;   /* shared with roommodel; f.fp the fusion's parameters */
	char **views;
	size_t nviews;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		FCT_FUSE_LONGOPTS,
		{"bbox", required_argument, NULL, OPT_BBOX},
		{"carve", no_argument, NULL, OPT_CARVE},
		{"exact", no_argument, NULL, OPT_EXACT},
		{"weight", required_argument, NULL, OPT_WEIGHT},
		{"curvature-flow", required_argument, NULL, OPT_FLOW},
		{"min-piece", required_argument, NULL, OPT_MINPIECE},
		{"min-weight", required_argument, NULL, OPT_MINW},
		{"projective", no_argument, NULL, OPT_PROJ},
		{"conf", required_argument, NULL, OPT_CONF},
		{"color", no_argument, NULL, OPT_COLOR},
		{"baseline", required_argument, NULL, OPT_BASELINE},
		{"doffs", required_argument, NULL, OPT_DOFFS},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ahK:o:qv";
	int c;
	memset(o, 0, sizeof *o);
	fct_fuse_opts_init(&o->f, argc, 0.01, 1e-6, 1e6);
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_fuse_opt(&o->f, c, optarg))
			continue;
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("tsdfuse (facet) " FCT_VERSION); exit(0);
		case OPT_BBOX:
			fct_opt_doubles("--bbox", optarg, o->bbox, 6);
			o->has_bbox = 1;
			for (int k = 0; k < 3; k++)
				if (!(o->bbox[k + 3] > o->bbox[k]))
					fct_usage_error("--bbox: the box has zero volume (need x0 < x1, y0 < y1, z0 < z1)");
			break;
		case OPT_CARVE: o->carve = 1; break;
		case OPT_WEIGHT:
			if (!strcmp(optarg, "constant"))
				o->f.fp.weight = FCT_FUSE_CONSTANT;
			else if (!strcmp(optarg, "incidence"))
				o->f.fp.weight = FCT_FUSE_INCIDENCE;
			else if (!strcmp(optarg, "depth2"))
				o->f.fp.weight = FCT_FUSE_DEPTH2;
			else
				fct_usage_error("--weight: \"%s\": expected constant, incidence or depth2", optarg);
			break;
		case OPT_FLOW: o->flow = (int)fct_opt_long("--curvature-flow", optarg, 0, 10000); break;
		case OPT_MINPIECE: o->min_piece = (size_t)fct_opt_long("--min-piece", optarg, 0, 0x7fffffffL); break;
		case OPT_MINW: o->min_weight = fct_opt_double("--min-weight", optarg, 0, 1e30); break;
		case OPT_PROJ: o->f.fp.projective = 1; break;
		case OPT_EXACT: o->f.exact = 1; break;
		case OPT_CONF: o->conf = optarg; break;
		case OPT_COLOR: o->color = 1; break;
		case OPT_BASELINE: o->baseline = fct_opt_double("--baseline", optarg, 1e-300, 1e300); break;
		case OPT_DOFFS:
			o->doffs = fct_opt_double("--doffs", optarg, -1e9, 1e9);
			o->doffs_given = 1;
			break;
		default: fct_bad_option(optstring, argv);
		}
	}
	o->color |= o->f.nimages > 0;   /* --image implies --color */
	o->views = argv + optind;
	o->nviews = (size_t)(argc - optind);
	if (!o->nviews && !o->conf)
		fct_usage_error("no views: give meshes, depth images or --conf");
	fct_fuse_opts_check(&o->f);
	/* Voxel indices are int32 (and the volume's blocks keep to 2^23 voxels
	 * each way): a box beyond overflowed them into an empty model. */
	double vox = o->f.voxel;
	for (int k = 0; o->has_bbox && k < 6; k++)
		if (!(fabs(o->bbox[k]) / vox < FCT_FUSE_VOXEL_RANGE))
			fct_usage_error("--bbox: %g m is %.3g voxels of %g m from the origin: beyond the "
			                "volume's %d (%g m at this voxel size)", o->bbox[k],
			                fabs(o->bbox[k]) / vox, vox, FCT_FUSE_VOXEL_RANGE, FCT_FUSE_VOXEL_RANGE * vox);
}

/* The camera, depth and noise parameters of the depth-image operands: the
 * shared options', and disparities from --baseline or a stereo
 * calibration's. */
static void depth_params(const struct options *o, struct fct_camera *dcam, struct fct_depth_params *dp)
{
	struct fct_stereo stereo;
	fct_fuse_opts_depth(&o->f, dcam, dp, &stereo);
	dp->baseline = o->baseline > 0 ? o->baseline : stereo.baseline;
	dp->doffs = o->doffs_given ? o->doffs : stereo.doffs;
	if (o->doffs_given && !(dp->baseline > 0))
		fct_usage_error("--doffs is for disparities and needs --baseline");
}

/* Fuse the views into g, one at a time; with carving, each view's range
 * image goes into it as soon as the view is fused.  Without it, the
 * views' extent is gathered here (carving needs it before: pre, or NULL)
 * and the memory checked as it grows. */
static void fuse_views(const struct options *o, struct fct_fuse_views *vs, struct fct_voxgrid *g,
                       struct fct_carving *carving, struct fct_fuse_extent *e, int pre,
                       struct fct_fuse_stats *st, double *fuse_s, double *carve_s)
{
	struct fct_err err;
	for (size_t i = 0; i < vs->n; i++) {
		struct fct_fuse_input L;
		fct_fuse_input_open(vs, i, &L);
		if (!pre) {
			int32_t clo[3], chi[3];
			fct_fuse_extent_add(e, &L.mesh);
			fct_fuse_extent_volume(e, o->f.voxel, o->f.fp.band, o->has_bbox ? o->bbox : NULL, o->carve, clo, chi);
		}
		double tv = fct_now();
		size_t before = st->voxels, planes_before = st->plane_views;
		if (fct_fuse_view(g, &L.view, &o->f.fp, st, &err))
			fct_die_err_at(&err, "%s", L.name);
		if (st->voxels == before)
			fct_fuse_input_warn_unused(&L, o->has_bbox);
		double dt = fct_now() - tv;
		*fuse_s += dt;
		if (fct_verbose && st->plane_views > planes_before)
			fprintf(stderr, "tsdfuse: view %zu/%zu %s: %zu faces, planes at step %d, %.1f ms\n", i + 1,
			        vs->n, L.name, L.mesh.nf, L.view.step, 1e3 * dt);
		else if (fct_verbose)
			fprintf(stderr, "tsdfuse: view %zu/%zu %s: %zu faces, %.1f ms\n", i + 1, vs->n, L.name,
			        L.mesh.nf, 1e3 * dt);
		if (carving) {
			double tc = fct_now();
			struct fct_range_image ri;
			double vox = o->f.voxel;
			if (L.view.cam.kind == FCT_CAMERA_NONE && L.view.ortho_step < vox / 2)
				L.view.ortho_step = vox / 2;
			if (fct_range_image_make(&ri, &L.view, (size_t)1 << 26, &err))
				fct_die_err_at(&err, "%s", L.name);
			fct_carving_add(carving, &ri);
			fct_range_image_free(&ri);
			*carve_s += fct_now() - tc;
		}
		fct_fuse_input_close(&L);
	}
}

#ifdef __GLIBC__
/* Keep freed memory for reuse instead of faulting fresh pages in:
 * - each view allocates and frees arrays of several MB (its mesh, normals,
 *   projections, cells); glibc would give them back to the kernel and
 *   fault them in afresh, zeroed, for the next view;
 * - marching cubes' output can reuse the last view's memory only if that
 *   memory is one free run.  The small allocations made while a view is
 *   read (header strings, element tables) come from the top of the heap
 *   when no free chunk is below, between a view's arrays, and once freed
 *   they stay in glibc's per-thread cache, which never coalesces.  A block
 *   freed now, below everything else, serves those small allocations
 *   instead.
 * The measurements are in bench/NOTES.md. */
static void *volatile heap_pin;         /* holds the pool out of the top chunk */

static void keep_freed_memory(void)
{
	mallopt(M_MMAP_THRESHOLD, 32 << 20);
	mallopt(M_TRIM_THRESHOLD, 1 << 30);
	void *volatile small_pool = malloc(256 << 10);
	heap_pin = malloc(16);
	free(small_pool);
}
#endif

int main(int argc, char **argv)
{
	fct_cli_init("tsdfuse");
#ifdef __GLIBC__
	keep_freed_memory();
#endif
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	struct fct_conf conf = { 0 };
	if (o.conf && fct_conf_read(&conf, o.conf, &err))
		fct_die_err(&err);
	for (size_t i = 0; i < conf.nskipped; i++)
		if (fct_verbose)
			fprintf(stderr, "tsdfuse: %s:%ld: skipped \"%s\" (vrip fuses bmesh lines only)\n",
			        o.conf, conf.skipped[i].line, conf.skipped[i].text);
	fct_report("conf_skipped", "%zu", conf.nskipped);
	struct fct_camera dcam;
	struct fct_depth_params dp;
	depth_params(&o, &dcam, &dp);
	struct fct_fuse_views vs;
	fct_fuse_views_init(&vs, &o.f, o.views, o.nviews, &conf, o.color, &dcam, &dp);
	size_t nv = vs.n;
	double t0 = fct_now();
	struct fct_fuse_extent e;
	fct_fuse_extent_init(&e);
	if (o.carve)            /* the carving box first: the views' extent */
		for (size_t i = 0; i < nv; i++) {
			struct fct_fuse_input L;
			fct_fuse_input_open(&vs, i, &L);
			fct_fuse_extent_add(&e, &L.mesh);
			fct_fuse_input_close(&L);
		}
	double reread_s = vs.read_s;
	vs.read_s = 0;
	int32_t clo[3] = { 0, 0, 0 }, chi[3] = { 0, 0, 0 };
	double est = o.carve ? fct_fuse_extent_volume(&e, o.f.voxel, o.f.fp.band, o.has_bbox ? o.bbox : NULL, o.carve, clo, chi) : 0;
	double vox = o.f.voxel, band = o.f.fp.band, have = fct_fuse_machine_bytes();
	struct fct_voxgrid *g = fct_voxgrid_new(vox, 0, &err);
	if (!g)
		fct_die_err(&err);
	fct_voxgrid_set_limit(g, (size_t)(0.85 * have));
	if (o.has_bbox) {
		o.f.fp.has_clip = 1;
		for (int k = 0; k < 3; k++) {
			o.f.fp.clip_lo[k] = (int32_t)ceil(o.bbox[k] / vox) - 2;
			o.f.fp.clip_hi[k] = (int32_t)ceil(o.bbox[k + 3] / vox) + 2;
			clo[k] = clo[k] > o.f.fp.clip_lo[k] ? clo[k] : o.f.fp.clip_lo[k];
			chi[k] = chi[k] < o.f.fp.clip_hi[k] ? chi[k] : o.f.fp.clip_hi[k];
		}
	}
	struct fct_carving carving;
	if (o.carve && fct_carving_init(&carving, clo, chi, vox, &err))
		fct_die_err(&err);

	struct fct_fuse_stats st = { 0 };
	double fuse_s = 0, carve_s = 0;
	fuse_views(&o, &vs, g, o.carve ? &carving : NULL, &e, o.carve, &st, &fuse_s, &carve_s);
	double read_s = vs.read_s;
	if (!o.carve)
		est = fct_fuse_extent_volume(&e, o.f.voxel, o.f.fp.band, o.has_bbox ? o.bbox : NULL, o.carve, clo, chi);
	fct_report("memory_estimate_mb", "%.1f", est / 1048576);
	size_t ncarved = 0;
	if (o.carve) {
		double tc = fct_now();
		float mark = o.min_weight > 0 ? (float)o.min_weight : 1e-3f;
		if (fct_carving_finish(&carving, g, band, mark, &ncarved, &err))
			fct_die_err(&err);
		fct_carving_free(&carving);
		carve_s += fct_now() - tc;
	}
	double flow_s = 0;
	if (o.flow) {
		double tf = fct_now();
		if (fct_curvature_flow(g, o.flow, band, &err))
			fct_die_err(&err);
		flow_s = fct_now() - tf;
	}
	struct rusage ru;   /* ru_maxrss: kilobytes on Linux and the BSDs */
	long faults0 = getrusage(RUSAGE_SELF, &ru) ? 0 : ru.ru_minflt;
	double tm = fct_now();
	struct fct_mesh out;
	int32_t mlo[3], mhi[3];
	for (int k = 0; k < 3; k++) {
		mlo[k] = (int32_t)ceil(o.bbox[k] / vox);
		mhi[k] = (int32_t)ceil(o.bbox[k + 3] / vox);
	}
	if (fct_mcubes_stats(&out, g, (float)o.min_weight, o.has_bbox ? mlo : NULL,
	                     o.has_bbox ? mhi : NULL, o.f.fp.threads, NULL, &err))
		fct_die_err(&err);
	double mc_s = fct_now() - tm, color_s = 0;
	/* The pages marching cubes faulted in: its output where the memory
	 * the views freed does not hold it (bench/NOTES.md). */
	long mc_faults = getrusage(RUSAGE_SELF, &ru) ? 0 : ru.ru_minflt - faults0;
	size_t nblocks = fct_voxgrid_count(g), gbytes = fct_voxgrid_bytes(g), ncolor = 0;
	fct_voxgrid_free(g);    /* before the colour pass reads the views again */
	if (o.color) {
		double tc = fct_now(), r0 = vs.read_s;
		fct_fuse_views_color(&vs, &out, &ncolor);
		reread_s += vs.read_s - r0;
		color_s = fct_now() - tc;
	}
	size_t npieces = 0;
	long ndebris = fct_mesh_drop_small_pieces(&out, o.min_piece, &npieces, &err);
	if (ndebris < 0)
		fct_die_err(&err);
	/* Each vertex's noise, where every view is a depth image of a known
	 * sensor: what segplanes judges the surface's planes by, a far wall
	 * by its own noise and a near table by its own. */
	double sigma_s = 0, sigma_level = 0;
	size_t sigma_seen = 0;
	if (vs.n > 0 && vs.ndepth == vs.n) {
		double ts = fct_now();
		fct_fuse_depth_sigma(&out, (const char *const *)vs.paths, vs.dposes, vs.n, &dcam, &dp, &o.f,
		                     &sigma_seen, &sigma_level);
		sigma_s = fct_now() - ts;
	}
	fct_report("views", "%zu", nv);
	fct_report("plane_views", "%zu", st.plane_views);
	fct_report("view_faces", "%zu", st.faces);
	fct_report("debris_pieces", "%zu", npieces);
	fct_report("debris_faces", "%ld", ndebris);
	fct_report("voxels_updated", "%zu", st.voxels);
	fct_report("border_skipped", "%zu", st.border);
	fct_report("blocks", "%zu", nblocks);
	fct_report("memory_mb", "%.1f", (double)gbytes / 1048576);
	if (fct_header_add_provenance(&out, "tsdfuse", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&out, o.out, o.ascii, &err))
		fct_die_err(&err);
	fct_report("carved", "%zu", ncarved);
	fct_report("vertices", "%zu", out.nv);
	fct_report("faces", "%zu", out.nf);
	fct_report("read_s", "%.4f", read_s);
	fct_report("reread_s", "%.4f", reread_s);
	fct_report("fuse_s", "%.4f", fuse_s);
	fct_report("ms_per_view", "%.2f", nv ? 1e3 * fuse_s / (double)nv : 0);
	/* Its phases (fuse.h), per view too. */
	double per_view = nv ? 1e3 / (double)nv : 0;
	fct_report("triangles_ms", "%.2f", st.triangles_s * per_view);
	fct_report("raster_ms", "%.2f", st.raster_s * per_view);
	fct_report("candidates_ms", "%.2f", st.candidates_s * per_view);
	fct_report("distances_ms", "%.2f", st.distances_s * per_view);
	fct_report("carve_s", "%.4f", carve_s);
	fct_report("flow_s", "%.4f", flow_s);
	fct_report("mcubes_s", "%.4f", mc_s);
	fct_report("mcubes_faults", "%ld", mc_faults);
	if (o.color) {
		fct_report("color_views", "%zu", ncolor);
		fct_report("color_s", "%.4f", color_s);
	}
	if (sigma_level > 0) {
		fct_report("sigma_seen", "%zu", sigma_seen);
		fct_report("sigma_level", "%.9g", sigma_level);
		fct_report("sigma_s", "%.4f", sigma_s);
	}
	fct_report("total_s", "%.4f", fct_now() - t0);
	if (!getrusage(RUSAGE_SELF, &ru))
		fct_report("peak_rss_mb", "%.1f", (double)ru.ru_maxrss / 1024);
	fct_mesh_free(&out);
	fct_fuse_views_free(&vs);
	fct_fuse_opts_free(&o.f);
	fct_conf_free(&conf);
	return 0;
}
