/* roommodel - an RGB-D sequence to one concise textured model of the room,
 * in one process: the depth images fused by true signed distance with the
 * sensor's noise model (tsdfuse; Sun, Paik, Koschan and Abidi, sec. 3), the
 * fused surface grouped into planar patches (segplanes) and made planes
 * plus a decimated free-form surface (planedecim; Kang, Johnson and
 * Szeliski, DEC CRL 95/7, sec. 2-5), textured from the colour images
 * (viewtex; Waechter, Moehrle and Goesele, ECCV 2014).  Every stage is a
 * library call; one view is held at a time. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "dataset.h"
#include "depthsmooth.h"
#include "fuse.h"
#include "header.h"
#include "mcubes.h"
#include "meshio.h"
#include "path.h"
#include "photo.h"
#include "planemodel.h"
#include "poses.h"
#include "segmesh.h"
#include "viewtex.h"

static const char usage[] =
	"usage: roommodel [-qv] [-o model.obj] [-K fx,fy,cx,cy | name] [--camera file]\n"
	"                 [--depth-scale s] [--noise model | file] [--smooth px]\n"
	"                 [--poses file ...] [--image file ...] [--max-difference s]\n"
	"                 [--voxel size] [--trunc n] [--threads n] [-c factor]\n"
	"                 [-e error] [--min-plane k] [--atlas-size n] [--blend]\n"
	"                 [--level none | gain | seams] [--texel-scale s]\n"
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
	"The planar model, as segplanes(1) and planedecim(1):\n"
	"  -c factor          merge patches while the smaller moves by at most factor\n"
	"                     sigma, rms (default 3)\n"
	"  -e error           the free-form decimation's bound in sigma (default 1.5)\n"
	"      --min-plane k  a patch of fewer faces is free-form (default 64)\n"
	"The texture, as viewtex(1):\n"
	"      --atlas-size n largest atlas side, a power of two (default 4096)\n"
	"      --blend        each texel the mean of the photos that see it\n"
	"      --level how    colour levelling: none, gain, seams (default seams,\n"
	"                     none with --blend)\n"
	"      --texel-scale s\n"
	"                     texels per photo pixel, 0.01 to 4 (default 1)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum { OPT_VERSION = 256, OPT_CAMERA, OPT_SCALE, OPT_NOISE, OPT_SMOOTH, OPT_POSES, OPT_IMAGE,
       OPT_MAXDIFF, OPT_VOXEL, OPT_TRUNC, OPT_THREADS, OPT_MINPLANE, OPT_ATLAS, OPT_BLEND,
       OPT_LEVEL, OPT_TEXEL, OPT_KEEP };

struct options {
	const char *out, *keep, *K, *camera, *noise, *folder;
	const char **poses, **images, **depths;
	size_t nposes, nimages, ndepths;
	int scale_given;
	double depth_scale, voxel, trunc, max_diff;
	struct fct_depth_smooth smooth;
	struct fct_fuse_params fp;
	struct fct_segment_params seg;
	struct fct_planar_params plan;
	struct fct_viewtex_params tex;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, OPT_VERSION},
		{"camera", required_argument, NULL, OPT_CAMERA},
		{"depth-scale", required_argument, NULL, OPT_SCALE},
		{"noise", required_argument, NULL, OPT_NOISE}, {"smooth", required_argument, NULL, OPT_SMOOTH},
		{"poses", required_argument, NULL, OPT_POSES}, {"image", required_argument, NULL, OPT_IMAGE},
		{"max-difference", required_argument, NULL, OPT_MAXDIFF},
		{"voxel", required_argument, NULL, OPT_VOXEL}, {"trunc", required_argument, NULL, OPT_TRUNC},
		{"threads", required_argument, NULL, OPT_THREADS},
		{"min-plane", required_argument, NULL, OPT_MINPLANE},
		{"atlas-size", required_argument, NULL, OPT_ATLAS}, {"blend", no_argument, NULL, OPT_BLEND},
		{"level", required_argument, NULL, OPT_LEVEL},
		{"texel-scale", required_argument, NULL, OPT_TEXEL},
		{"keep", required_argument, NULL, OPT_KEEP},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "c:e:hK:o:qv";
	static const char *const levels[] = { "none", "gain", "seams" };
	int c, level_given = 0;
	long n;
	memset(o, 0, sizeof *o);
	o->out = "model.obj";
	o->voxel = 0.02;
	o->trunc = 3;
	o->depth_scale = 1000;
	o->max_diff = 0.02;
	fct_depth_smooth_default(&o->smooth);
	fct_segment_params_default(&o->seg);
	fct_planar_params_default(&o->plan);
	fct_viewtex_params_default(&o->tex);
	o->poses = calloc((size_t)argc + 1, sizeof *o->poses);
	o->images = calloc((size_t)argc + 1, sizeof *o->images);
	if (!o->poses || !o->images)
		fct_die(1, "out of memory");
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'c': o->seg.factor = fct_opt_double("-c", optarg, 0, HUGE_VAL); break;
		case 'e': o->plan.max_error = fct_opt_double("-e", optarg, 0, INFINITY); break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'K': o->K = optarg; break;
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("roommodel (facet) " FCT_VERSION); exit(0);
		case OPT_CAMERA: o->camera = optarg; break;
		case OPT_SCALE:
			o->depth_scale = fct_opt_double("--depth-scale", optarg, 1e-300, 1e300);
			o->scale_given = 1;
			break;
		case OPT_NOISE: o->noise = optarg; break;
		case OPT_SMOOTH: o->smooth.radius = (int)fct_opt_long("--smooth", optarg, 0, 64); break;
		case OPT_POSES: o->poses[o->nposes++] = optarg; break;
		case OPT_IMAGE: o->images[o->nimages++] = optarg; break;
		case OPT_MAXDIFF: o->max_diff = fct_opt_double("--max-difference", optarg, 0, 1e9); break;
		case OPT_VOXEL: o->voxel = fct_opt_double("--voxel", optarg, 1e-4, 1); break;
		case OPT_TRUNC: o->trunc = fct_opt_double("--trunc", optarg, 1, 100); break;
		case OPT_THREADS: o->fp.threads = (int)fct_opt_long("--threads", optarg, 0, 64); break;
		case OPT_MINPLANE:
			o->plan.min_plane = (size_t)fct_opt_long("--min-plane", optarg, 0, 0x7fffffffL);
			break;
		case OPT_ATLAS:
			n = fct_opt_long("--atlas-size", optarg, 64, 16384);
			if (n & (n - 1))
				fct_usage_error("--atlas-size: %ld is not a power of two", n);
			o->tex.atlas_max = (int)n;
			break;
		case OPT_BLEND: o->tex.blend = 1; break;
		case OPT_LEVEL:
			level_given = 1;
			o->tex.level = -1;
			for (int k = 0; k < 3; k++)
				if (!strcmp(optarg, levels[k]))
					o->tex.level = k;
			if (o->tex.level < 0)
				fct_usage_error("--level: \"%s\" is not none, gain or seams", optarg);
			break;
		case OPT_TEXEL: o->tex.texel_scale = fct_opt_double("--texel-scale", optarg, 0.01, 4); break;
		case OPT_KEEP: o->keep = optarg; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (o->tex.blend && !level_given)
		o->tex.level = 0;       /* viewtex's rule: the mean of the photos is level enough */
	if ((double)o->tex.max_pages * o->tex.atlas_max * o->tex.atlas_max > (double)((size_t)1 << 29))
		fct_usage_error("--atlas-size %d: more than 2^29 texels in %d pages", o->tex.atlas_max,
		                o->tex.max_pages);
	if (optind >= argc)
		fct_usage_error("no sequence: give a 7-Scenes, TUM or Redwood folder, or depth images");
	if (fct_path_is_std(o->out))
		fct_usage_error("-o: the model must be a named file (the atlas is written beside it)");
	if (o->K && o->camera)
		fct_usage_error("-K and --camera exclude each other");
	struct stat sb;
	if (argc - optind == 1 && stat(argv[optind], &sb) == 0 && S_ISDIR(sb.st_mode)) {
		o->folder = argv[optind];
		if (o->nimages || o->nposes)
			fct_usage_error("%s: a folder names its own images and poses (no --image, --poses)",
			                o->folder);
	} else {
		o->depths = (const char **)argv + optind;
		o->ndepths = (size_t)(argc - optind);
		if (o->nimages != o->ndepths)
			fct_usage_error("%zu depth images but %zu --image files (one colour image each)",
			                o->ndepths, o->nimages);
		if (!o->nposes)
			fct_usage_error("depth images need --poses");
		if (!o->K && !o->camera)
			fct_usage_error("depth images need -K or --camera");
	}
	o->fp.band = o->trunc * o->voxel;
	o->smooth.voxel = o->voxel;
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
		if (fct_dataset_read(&s->ds, o->folder, o->max_diff, &err))
			fct_die_err(&err);
		s->depth = (const char *const *)s->ds.depth, s->color = (const char *const *)s->ds.color;
		s->pose_files = (const char *const *)s->ds.poses;
		s->n = s->ds.n, s->nposes = s->ds.nposes;
		if (!o->K && !o->camera) {
			o->K = s->ds.camera;
			intrinsics = s->ds.intrinsics;
		}
		fct_report("sequence", "%s, %zu frames", s->ds.layout, s->n);
	} else {
		s->depth = o->depths, s->color = o->images, s->pose_files = o->poses;
		s->n = o->ndepths, s->nposes = o->nposes;
	}
	/* The camera, the depth units and the noise: -K's dataset name sets
	 * the last two unless given. */
	double named_scale;
	fct_opt_camera(&s->cam, &named_scale, NULL, o->K, o->camera);
	if (intrinsics && fct_camera_read_file(intrinsics, &s->cam, &err))
		fct_die_err(&err);
	fct_depth_params_default(&s->dp);
	s->dp.texcoords = 0;
	s->dp.depth_scale = o->scale_given || !(named_scale > 0) ? o->depth_scale : named_scale;
	s->dp.scale_float = o->scale_given;
	s->dp.focal = s->cam.fx;
	if (o->noise && fct_noise_names_model(o->noise)) {
		if (fct_noise_parse(&s->dp.noise, o->noise, &err))
			fct_usage_error("--%s", err.msg);
	} else if (o->noise) {
		if (fct_noise_read_file(o->noise, &s->dp.noise, &err))
			fct_die_err(&err);
	} else if (o->K)
		fct_noise_named(o->K, &s->dp.noise);
	/* Every file is there and an image before the work starts. */
	for (size_t i = 0; i < s->n; i++) {
		struct fct_image probe;
		if (fct_image_probe_file(&probe, s->depth[i], NULL, &err) ||
		    fct_image_probe_file(&probe, s->color[i], NULL, &err))
			fct_die_err(&err);
	}
	struct fct_frame_poses_stats st;
	if (!(s->pose = fct_alloc_array(s->n, 12 * sizeof *s->pose, &err)) ||
	    fct_frame_poses(s->pose, &st, s->pose_files, s->nposes, s->depth, s->n, o->max_diff, &err) ||
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

/* Stage figures under -v: "roommodel: STAGE: key=value". */
static void figure(const char *stage, const char *key, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
static void figure(const char *stage, const char *key, const char *fmt, ...)
{
	char k[64], v[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(v, sizeof v, fmt, ap);
	va_end(ap);
	snprintf(k, sizeof k, "%s: %s", stage, key);
	fct_report(k, "%s", v);
}

/* A stage's end: its mesh and its CPU and wall seconds under -v. */
static void stage_end(const char *stage, const struct fct_mesh *m, double cpu0, double wall0)
{
	if (fct_verbose)
		fprintf(stderr, "%s: %-10s %9zu vertices %9zu faces %8.3f s CPU %8.3f s\n", fct_prog, stage,
		        m->nv, m->nf, fct_cpu_time() - cpu0, fct_now() - wall0);
}

static _Noreturn void stage_die(const char *stage, struct fct_err *err)
{
	fct_err_prefix(err, "%s", stage);
	fct_die_err(err);
}

/* Stage 1: the depth images fused one at a time, the surface extracted. */
static void fuse(struct fct_mesh *out, struct sequence *s, const struct options *o)
{
	struct fct_err err;
	struct fct_voxgrid *g = fct_voxgrid_new(o->voxel, 0, &err);
	if (!g)
		stage_die("tsdfuse", &err);
	long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
	if (pages > 0 && page > 0)
		fct_voxgrid_set_limit(g, (size_t)(0.85 * (double)pages * (double)page));
	struct fct_fuse_stats st = { 0 };
	struct fct_progress pr;
	fct_progress_start(&pr, "fusing");
	for (size_t i = 0; i < s->n; i++) {
		struct fct_image img;
		if (fct_image_read_file(&img, s->depth[i], NULL, &err))
			fct_die_err(&err);
		struct fct_camera cam = s->cam;
		if (cam.width == 0)
			cam.width = img.width, cam.height = img.height;
		if (cam.width != img.width || cam.height != img.height)
			fct_die(1, "%s: image is %dx%d, the camera %dx%d", s->depth[i], img.width, img.height,
			        cam.width, cam.height);
		char why[300];
		if (i == 0 && fct_depth_implausible(why, sizeof why, &img, &cam, &s->dp))
			fct_warn("%s: %s", s->depth[i], why);
		struct fct_mesh mesh;
		struct fct_fuse_view view;
		int rc = fct_fuse_depth_view(&view, &mesh, NULL, &img, &cam, &s->dp, &o->smooth,
		                             &s->pose[12 * i], &err);
		fct_image_free(&img);
		if (rc || fct_fuse_view(g, &view, &o->fp, &st, &err)) {
			fct_err_prefix(&err, "%s", s->depth[i]);
			stage_die("tsdfuse", &err);
		}
		fct_mesh_free(&mesh);
		fct_progress_update(&pr, (double)i + 1, (double)s->n);
	}
	fct_progress_end(&pr);
	if (fct_mcubes_stats(out, g, 0, NULL, NULL, o->fp.threads, NULL, &err))
		stage_die("tsdfuse", &err);
	char noise[256];
	fct_noise_format(&s->dp.noise, noise, sizeof noise);
	figure("tsdfuse", "views", "%zu", s->n);
	figure("tsdfuse", "noise", "%s", *noise ? noise : "unknown");
	figure("tsdfuse", "voxels_updated", "%zu", st.voxels);
	figure("tsdfuse", "memory_mb", "%.1f", (double)fct_voxgrid_bytes(g) / 1048576);
	fct_voxgrid_free(g);
	if (out->nf == 0)
		fct_die(1, "tsdfuse: the views fused into no surface (check the poses, the camera and "
		        "--depth-scale)");
	/* Coordinates as a file holds them: the stages give what the programs
	 * give on a pipe and on the files of --keep. */
	if (out->xyz_type == FCT_FLOAT32)
		for (size_t i = 0; i < 3 * out->nv; i++)
			out->xyz[i] = (float)out->xyz[i];
}

/* Stages 2 and 3: planar patches, then the planar model. */
static void planar_model(struct fct_mesh *m, struct options *o, const char *keep_patches)
{
	struct fct_err err;
	/* Patches of fewer faces than one in 600 of the mesh's (at least 8)
	 * are specks of noise (planarize's rule). */
	o->seg.min_faces = m->nf / 600 > 8 ? (long)(m->nf / 600) : 8;
	double c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_segment_stats sst;
	if (fct_segment_mesh(m, &o->seg, 0, &sst, &err))
		stage_die("segplanes", &err);
	figure("segplanes", "patches", "%zu", sst.patches);
	figure("segplanes", "noise", "%.9g", sst.noise);
	figure("segplanes", "free_faces", "%zu", sst.free_faces);
	stage_end("segplanes", m, c0, t0);
	if (keep_patches && fct_mesh_write_file(m, keep_patches, 0, &err))
		fct_die_err(&err);
	c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_planar_stats pst;
	if (fct_planar_model(m, &o->plan, &pst, &err))
		stage_die("planedecim", &err);
	figure("planedecim", "planes", "%zu", pst.planes);
	figure("planedecim", "planar_triangles", "%zu", pst.planar_triangles);
	figure("planedecim", "free_faces", "%zu", pst.free_faces);
	figure("planedecim", "collapses", "%zu", pst.qem.collapses);
	stage_end("planedecim", m, c0, t0);
}

/* Stage 4: the texture, the model and its atlas written. */
static void texture(struct fct_mesh *m, const struct sequence *s, const struct options *o,
                    int argc, char **argv)
{
	struct fct_err err;
	double c0 = fct_cpu_time(), t0 = fct_now();
	struct fct_viewtex *T = fct_viewtex_new(m, s->n, &o->tex, &err);
	size_t any = 0, *seen = fct_alloc_array(s->n, sizeof *seen, &err);
	if (!T || !seen || fct_viewtex_add_photos(T, s->photo, s->n, seen, &err))
		stage_die("viewtex", &err);
	for (size_t i = 0; i < s->n; i++)
		any += seen[i];
	free(seen);
	if (!any)
		fct_die(1, "viewtex: no colour image sees any face of the model whole (check the poses "
		        "and the camera)");
	if (fct_viewtex_label(T, &err) || fct_viewtex_layout(T, &err) ||
	    fct_viewtex_sample_photos(T, s->photo, s->n, &err) || fct_viewtex_finish(T, &err))
		stage_die("viewtex", &err);
	size_t npages = fct_viewtex_npages(T);
	char **names = fct_viewtex_page_names(o->out, npages, &err);
	if (!names)
		fct_die_err(&err);
	for (size_t i = 0; i < npages; i++)
		fct_write_image_or_die(fct_viewtex_page(T, i), names[i]);
	if (fct_viewtex_apply(T, m, names, 1, &err) ||
	    fct_header_add_provenance(m, "roommodel", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(m, o->out, 0, &err))
		fct_die_err(&err);
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	figure("viewtex", "photos_used", "%zu", st.views_used);
	figure("viewtex", "faces_unseen", "%zu", st.unseen);
	figure("viewtex", "charts", "%zu", st.charts);
	figure("viewtex", "charts_rectified", "%zu", st.rectified);
	figure("viewtex", "atlas_pages", "%zu", st.pages);
	figure("viewtex", "atlas_size", "%dx%d", st.page_width, st.page_height);
	figure("viewtex", "seam_rms_after", "%.3f", st.seam_rms_after);
	stage_end("viewtex", m, c0, t0);
	fct_viewtex_page_names_free(names, npages);
	fct_viewtex_free(T);
}

/* The folder of --keep, made when missing; path of file in it. */
static char *keep_path(const char *dir, const char *file)
{
	struct fct_err err;
	char *path = fct_path_join(dir, file, &err);
	if (!path)
		fct_die_err(&err);
	return path;
}

static void make_folder(const char *dir)
{
	struct stat sb;
	if (mkdir(dir, 0777) == 0)
		return;
	if (errno == EEXIST && stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode))
		return;
	fct_die(1, "--keep: %s: %s", dir, errno == EEXIST ? "exists and is not a folder" : strerror(errno));
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
	char *keep[3] = { NULL, NULL, NULL };
	if (o.keep) {
		make_folder(o.keep);
		keep[0] = keep_path(o.keep, "1-fused.ply");
		keep[1] = keep_path(o.keep, "2-patches.ply");
		keep[2] = keep_path(o.keep, "3-model.ply");
	}

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
	free(o.poses);
	free(o.images);
	return 0;
}
