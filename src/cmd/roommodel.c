/* roommodel - an RGB-D sequence to one concise textured model of the room,
 * in one process: the depth images fused by true signed distance with the
 * sensor's noise model (tsdfuse; Sun, Paik, Koschan and Abidi, sec. 3), the
 * fused surface grouped into planar patches (segplanes) and made planes
 * plus a decimated free-form surface (planedecim; Kang, Johnson and
 * Szeliski, DEC CRL 95/7, sec. 2-5), textured from the colour images
 * (viewtex; Waechter, Moehrle and Goesele, ECCV 2014).  Every stage is a
 * library call; one view is held at a time. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/fuseviews.h"
#include "io/dataset.h"
#include "fusion/fuse.h"
#include "cli/fuseopts.h"
#include "io/header.h"
#include "fusion/mcubes.h"
#include "io/meshio.h"
#include "core/path.h"
#include "render/photo.h"
#include "cli/planaropts.h"
#include "io/poses.h"
#include "cli/segopts.h"
#include "cli/texopts.h"

static const char usage[] =
	"usage: roommodel [-qv] [-o model.obj] [-K fx,fy,cx,cy | name] [--camera file]\n"
	"                 [--depth-scale s] [--depth-code c] [--noise model | file]\n"
	"                 [--smooth px]\n"
	"                 [--poses file ...] [--image file ...] [--max-difference s]\n"
	"                 [--voxel size] [--trunc n] [--threads n]\n"
	"                 [-c factor | -n patches] [--area-weighted] [--fit k]\n"
	"                 [--max-dev k] [--max-rms r] [--min-extent k] [--min-faces k]\n"
	"                 [--tls] [-e error] [--border k] [--max-hole k] [--max-move k]\n"
	"                 [--min-free k] [--min-piece k] [--min-plane k] [--outline k]\n"
	"                 [--atlas-size n] [--blend] [--candidates n] [--fill r,g,b]\n"
	"                 [--level none | gain | seams] [--max-pages n] [--min-angle deg]\n"
	"                 [--no-rectify] [--one-photo] [--padding n] [--texel-scale s]\n"
	"                 [--keep dir] folder | depth-image ...\n"
	"Make one concise textured model of a room from an RGB-D sequence: the depth\n"
	"images fused (tsdfuse, with the sensor's noise model), the fused surface\n"
	"made planes plus a decimated free-form surface (segplanes, planedecim), and\n"
	"textured from the colour images (viewtex).  The sequence is a 7-Scenes, TUM\n"
	"or Redwood folder, or depth images with -K, --poses and an --image each.\n"
	"  -o model.obj       the model (OBJ with its .mtl and atlas PNGs beside it,\n"
	"                     or .ply); default model.obj\n"
	"  -q                 quiet\n"
	"  -v                 progress, each stage's figures and CPU seconds\n"
	"      --keep dir     write the stages into dir: 1-fused.ply, 2-patches.ply,\n"
	"                     3-model.ply\n"
	"The views, as tsdfuse(1):\n"
	"  -K fx,fy,cx,cy     the camera (or a dataset name, which sets the depth\n"
	"                     scale and the noise model; a folder names its own)\n"
	"      --camera file  the camera from a file (see dm2mesh)\n"
	"      --depth-code c the depth images' encoding (as dm2mesh; default the name's)\n"
	"      --depth-scale s\n"
	"                     PNG depth units per metre (default 1000, or the name's)\n"
	"      --image file   the colour image of each depth image, in their order\n"
	"      --max-difference s\n"
	"                     TUM: time matching frames to poses and colour (0.02)\n"
	"      --noise model  the depth noise (as tsdfuse; default: the dataset's)\n"
	"      --poses file   camera-to-world poses: one trajectory file (TUM, Redwood\n"
	"                     .log, KITTI, stacked 4x4) or one file per image\n"
	"      --smooth px    the noise-aware smoothing's half-width (default 2)\n"
	"      --threads n    threads of the fusion (default 0: one per processor)\n"
	"      --trunc n      band half-width in voxels (default 3)\n"
	"      --voxel size   voxel size in metres (default 0.02)\n"
	"Planar patches, as segplanes(1):\n"
	FCT_SEG_USAGE
	"The planar model, as planedecim(1):\n"
	FCT_PLANAR_USAGE
	"The texture, as viewtex(1):\n"
	FCT_TEX_USAGE
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum { OPT_VERSION = 256, OPT_KEEP };

struct options {
	const char *out, *keep, *folder;
	const char **depths;
	size_t ndepths;
	struct fct_fuse_opts f;  /* tsdfuse's, 2 cm voxels */
	struct fct_seg_opts s;
	struct fct_planar_params plan;
	struct fct_tex_opts t;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, OPT_VERSION},
		FCT_FUSE_LONGOPTS,
		FCT_SEG_LONGOPTS,
		FCT_PLANAR_LONGOPTS,
		FCT_TEX_LONGOPTS,
		{"keep", required_argument, NULL, OPT_KEEP},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "c:e:hK:n:o:qv";
	int c;
	memset(o, 0, sizeof *o);
	o->out = "model.obj";
	fct_fuse_opts_init(&o->f, argc, 0.02, 1e-4, 1);
	fct_seg_opts_init(&o->s);
	fct_planar_params_default(&o->plan);
	fct_tex_opts_init_sequence(&o->t);
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_fuse_opt(&o->f, c, optarg) || fct_seg_opt(&o->s, c, optarg) ||
		    fct_planar_opt(&o->plan, c, optarg) || fct_tex_opt(&o->t, c, optarg))
			continue;
		switch (c) {
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("roommodel (facet) " FCT_VERSION); exit(0);
		case OPT_KEEP: o->keep = optarg; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	fct_seg_opts_check(&o->s);
	fct_tex_opts_check(&o->t);
	if (optind >= argc)
		fct_usage_error("no sequence: give a 7-Scenes, TUM or Redwood folder, or depth images");
	if (fct_path_is_std(o->out))
		fct_usage_error("-o: the model must be a named file (the atlas is written beside it)");
	if (o->f.K && o->f.camera)
		fct_usage_error("-K and --camera exclude each other");
	struct stat sb;
	if (argc - optind == 1 && stat(argv[optind], &sb) == 0 && S_ISDIR(sb.st_mode)) {
		o->folder = argv[optind];
		if (o->f.nimages || o->f.nposes)
			fct_usage_error("%s: a folder names its own images and poses (no --image, --poses)",
			                o->folder);
	} else {
		o->depths = (const char **)argv + optind;
		o->ndepths = (size_t)(argc - optind);
		if (o->f.nimages != o->ndepths)
			fct_usage_error("%zu depth images but %zu --image files (one colour image each)",
			                o->ndepths, o->f.nimages);
		if (!o->f.nposes)
			fct_usage_error("depth images need --poses");
		if (!o->f.K && !o->f.camera)
			fct_usage_error("depth images need -K or --camera");
	}
	fct_fuse_opts_check(&o->f);
}

/* The sequence: the frames' depth and colour images and their poses. */
struct sequence {
	struct fct_dataset ds;   /* a folder's (else empty) */
	const char *const *depth, *const *color, *const *pose_files;
	size_t n, nposes;
	struct fct_camera cam;
	struct fct_depth_params dp;
	double *pose;            /* 12 per frame */
	struct fct_photo *photo;
};

static void sequence_open(struct sequence *s, struct options *o)
{
	struct fct_err err;
	const char *intrinsics = NULL; /* a folder's own, when no camera is given */
	memset(s, 0, sizeof *s);
	if (o->folder) {
		if (fct_dataset_read(&s->ds, o->folder, o->f.max_diff, &err))
			fct_die_err(&err);
		s->depth = (const char *const *)s->ds.depth, s->color = (const char *const *)s->ds.color;
		s->pose_files = (const char *const *)s->ds.poses;
		s->n = s->ds.n, s->nposes = s->ds.nposes;
		if (!o->f.K && !o->f.camera) {
			o->f.K = s->ds.camera;
			intrinsics = s->ds.intrinsics;
		}
		fct_report("sequence", "%s, %zu frames", s->ds.layout, s->n);
	} else {
		s->depth = o->depths, s->color = o->f.images, s->pose_files = o->f.poses;
		s->n = o->ndepths, s->nposes = o->f.nposes;
	}
	/* The camera, the depth units and the noise: -K's dataset name sets
	 * the last two unless given. */
	fct_fuse_opts_depth(&o->f, &s->cam, &s->dp, NULL);
	if (intrinsics) {       /* the folder's own focal lengths and centre */
		if (fct_camera_read_file(intrinsics, &s->cam, &err))
			fct_die_err(&err);
		s->dp.focal = s->cam.fx;
	}
	/* Every file is there and an image before the work starts. */
	for (size_t i = 0; i < s->n; i++) {
		struct fct_image probe;
		if (fct_image_probe_file(&probe, s->depth[i], NULL, &err) ||
		    fct_image_probe_file(&probe, s->color[i], NULL, &err))
			fct_die_err(&err);
	}
	struct fct_frame_poses_stats st;
	if (!(s->pose = fct_alloc_array(s->n, 12 * sizeof *s->pose, &err)) ||
	    fct_frame_poses(s->pose, &st, s->pose_files, s->nposes, s->depth, s->n, o->f.max_diff, &err) ||
	    fct_photos_make(&s->photo, &s->cam, s->color, s->n, s->pose_files, s->nposes, &err))
		fct_die_err(&err);
	fct_report("poses", "%s", fct_traj_format_name(st.format));
}

static void sequence_close(struct sequence *s)
{
	fct_dataset_free(&s->ds);
	free(s->pose);
	free(s->photo);
}

/* A stage's end: its mesh and its CPU and wall seconds under -v. */
static void stage_end(const char *stage, const struct fct_mesh *m, double cpu0, double wall0)
{
	if (fct_verbose)
		fprintf(stderr, "%s: %-10s %9zu vertices %9zu faces %8.3f s CPU %8.3f s\n", fct_prog, stage,
		        m->nv, m->nf, fct_cpu_time() - cpu0, fct_now() - wall0);
}

/* Stage 1: the depth images fused one at a time, the surface extracted. */
static void fuse(struct fct_mesh *out, struct sequence *s, const struct options *o)
{
	struct fct_err err;
	struct fct_voxgrid *g = fct_voxgrid_new(o->f.voxel, 0, &err);
	if (!g)
		fct_die_err_at(&err, "tsdfuse");
	long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
	if (pages > 0 && page > 0)
		fct_voxgrid_set_limit(g, (size_t)(0.85 * (double)pages * (double)page));
	struct fct_fuse_stats st = { 0 };
	struct fct_progress pr;
	fct_progress_start(&pr, "fusing");
	for (size_t i = 0; i < s->n; i++) {
		struct fct_image img;
		struct fct_camera cam;
		fct_fuse_read_depth(&img, &cam, s->depth[i], &s->cam, &s->dp, i == 0);
		struct fct_mesh mesh;
		struct fct_fuse_view view;
		int rc = fct_fuse_depth_view(&view, &mesh, NULL, &img, &cam, &s->dp, &o->f.smooth,
		                             &s->pose[12 * i], o->f.voxel, &err);
		fct_image_free(&img);
		if (rc || fct_fuse_view(g, &view, &o->f.fp, &st, &err))
			fct_die_err_at(&err, "tsdfuse: %s", s->depth[i]);
		fct_mesh_free(&mesh);
		fct_progress_update(&pr, (double)i + 1, (double)s->n);
	}
	fct_progress_end(&pr);
	if (fct_mcubes_stats(out, g, 0, NULL, NULL, o->f.fp.threads, NULL, &err))
		fct_die_err_at(&err, "tsdfuse");
	char noise[256];
	fct_noise_format(&s->dp.noise, noise, sizeof noise);
	fct_report_stage("tsdfuse", "views", "%zu", s->n);
	fct_report_stage("tsdfuse", "noise", "%s", *noise ? noise : "unknown");
	fct_report_stage("tsdfuse", "voxels_updated", "%zu", st.voxels);
	fct_report_stage("tsdfuse", "plane_views", "%zu", st.plane_views);
	fct_report_stage("tsdfuse", "memory_mb", "%.1f", (double)fct_voxgrid_bytes(g) / 1048576);
	fct_voxgrid_free(g);
	if (out->nf == 0)
		fct_die(1, "tsdfuse: the views fused into no surface (check the poses, the camera and "
		        "--depth-scale)");
	/* Coordinates as a file holds them: the stages give what the programs
	 * give on a pipe and on the files of --keep. */
	fct_mesh_round_xyz(out);
	/* Each vertex's noise from the views that saw it, so that the planes
	 * judge a far wall by its own noise and a near table by its own. */
	size_t seen;
	double level;
	if (!fct_fuse_depth_sigma(out, s->depth, s->pose, s->n, &s->cam, &s->dp, &o->f, &seen, &level)) {
		fct_report_stage("tsdfuse", "sigma_seen", "%zu", seen);
		fct_report_stage("tsdfuse", "sigma_level", "%.9g", level);
	}
}

/* Stages 2 and 3: planar patches, then the planar model. */
static void planar_model(struct fct_mesh *m, struct options *o, const char *keep_patches)
{
	struct fct_err err;
	/* Patches of fewer faces than one in 600 of the mesh's (at least 8)
	 * are specks of noise (planarize's rule). */
	if (!o->s.min_faces_given)
		o->s.seg.min_faces = m->nf / 600 > 8 ? (long)(m->nf / 600) : 8;
	double c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_segment_stats sst;
	if (fct_segment_mesh(m, &o->s.seg, o->s.tls, &sst, &err))
		fct_die_err_at(&err, "segplanes");
	fct_report_stage("segplanes", "patches", "%zu", sst.patches);
	fct_report_stage("segplanes", "noise", "%.9g", sst.noise);
	fct_report_stage("segplanes", "free_faces", "%zu", sst.free_faces);
	stage_end("segplanes", m, c0, t0);
	if (keep_patches && fct_mesh_write_file(m, keep_patches, 0, &err))
		fct_die_err(&err);
	c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_planar_stats pst;
	if (fct_planar_model(m, &o->plan, &pst, &err))
		fct_die_err_at(&err, "planedecim");
	fct_report_stage("planedecim", "planes", "%zu", pst.planes);
	fct_report_stage("planedecim", "debris_pieces", "%zu", pst.debris_pieces);
	fct_report_stage("planedecim", "debris_faces", "%zu", pst.debris_faces);
	fct_report_stage("planedecim", "planar_triangles", "%zu", pst.planar_triangles);
	fct_report_stage("planedecim", "free_faces", "%zu", pst.free_faces);
	fct_report_stage("planedecim", "collapses", "%zu", pst.qem.collapses);
	stage_end("planedecim", m, c0, t0);
}

/* Stage 4: the texture, the model and its atlas written. */
static void texture(struct fct_mesh *m, const struct sequence *s, const struct options *o,
                    int argc, char **argv)
{
	struct fct_err err;
	double c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_viewtex *T = fct_viewtex_new(m, s->n, &o->t.p, &err);
	size_t any = 0, *seen = fct_alloc_array(s->n, sizeof *seen, &err);
	if (!T || !seen || fct_viewtex_add_photos(T, s->photo, s->n, seen, &err))
		fct_die_err_at(&err, "viewtex");
	for (size_t i = 0; i < s->n; i++)
		any += seen[i];
	free(seen);
	if (!any)
		fct_die(1, "viewtex: no colour image sees any face of the model whole (check the poses "
		        "and the camera)");
	if (fct_viewtex_label(T, &err) || fct_viewtex_layout(T, &err) ||
	    fct_viewtex_sample_photos(T, s->photo, s->n, &err) || fct_viewtex_finish(T, &err))
		fct_die_err_at(&err, "viewtex");
	fct_tex_write_atlas(T, m, o->out, 1);
	if (fct_header_add_provenance(m, "roommodel", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(m, o->out, 0, &err))
		fct_die_err(&err);
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	fct_report_stage("viewtex", "photos_used", "%zu", st.views_used);
	fct_report_stage("viewtex", "faces_unseen", "%zu", st.unseen);
	fct_report_stage("viewtex", "charts", "%zu", st.charts);
	fct_report_stage("viewtex", "charts_rectified", "%zu", st.rectified);
	fct_report_stage("viewtex", "atlas_pages", "%zu", st.pages);
	fct_report_stage("viewtex", "atlas_size", "%dx%d", st.page_width, st.page_height);
	fct_report_stage("viewtex", "seam_rms_after", "%.3f", st.seam_rms_after);
	stage_end("viewtex", m, c0, t0);
	fct_viewtex_free(T);
}

int main(int argc, char **argv)
{
	fct_cli_init("roommodel");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	double t0 = fct_now(), c0 = fct_cpu_time();
	/* The model's folder, before the work: a missing one failed at the end. */
	char *out_dir = fct_path_dir(o.out, &err);
	struct stat sb;
	if (!out_dir)
		fct_die_err(&err);
	if (stat(out_dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
		fct_die(1, "%s: no such folder for the model", out_dir);
	free(out_dir);
	struct sequence s;
	sequence_open(&s, &o);
	static const char *const stages[3] = { "1-fused.ply", "2-patches.ply", "3-model.ply" };
	char *keep[3] = { NULL, NULL, NULL };
	if (o.keep)
		fct_make_folder("--keep", o.keep);
	for (int i = 0; i < 3 && o.keep; i++)
		if (!(keep[i] = fct_path_join(o.keep, stages[i], &err)))
			fct_die_err(&err);

	struct fct_mesh m;
	double t1 = fct_now();
	fuse(&m, &s, &o);
	stage_end("tsdfuse", &m, c0, t1);
	if (keep[0] && fct_mesh_write_file(&m, keep[0], 0, &err))
		fct_die_err(&err);
	size_t fused_faces = m.nf;
	planar_model(&m, &o, keep[1]);
	if (keep[2] && fct_mesh_write_file(&m, keep[2], 0, &err))
		fct_die_err(&err);
	texture(&m, &s, &o, argc, argv);

	fct_report("fused_faces", "%zu", fused_faces);
	fct_report("faces", "%zu", m.nf);
	fct_report("reduction", "%.1f", m.nf ? (double)fused_faces / (double)m.nf : 0);
	fct_report("cpu_s", "%.3f", fct_cpu_time() - c0);
	fct_report("total_s", "%.3f", fct_now() - t0);
	for (int i = 0; i < 3; i++)
		free(keep[i]);
	fct_mesh_free(&m);
	sequence_close(&s);
	fct_fuse_opts_free(&o.f);
	return 0;
}
