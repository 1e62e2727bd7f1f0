/* planarize - a depth image (and its co-registered image) or any mesh to a
 * concise model of the scene's planes, in one process: the depth meshed
 * (dm2mesh), its faces grouped into planar patches (segplanes), the planar
 * model made (planedecim: planes where the world is planar, a decimated
 * surface elsewhere, one mesh), and the texture: Kang, Johnson and
 * Szeliski, "Extraction of Concise and Realistic 3-D Models from Real Data"
 * (DEC CRL 95/7), sections 2-7.  Every stage is a library call on one mesh
 * in memory; this is their command line. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/bakeopts.h"
#include "cli/cli.h"
#include "render/cylview.h"
#include "cli/depthopts.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "cli/planaropts.h"
#include "geom/adj.h"
#include "geom/pointdist.h"
#include "cli/segopts.h"

static const char usage[] =
	"usage: planarize [-aqv] [-o model] [-K fx,fy,cx,cy | name] [--camera file]\n"
	"                 [--cylindrical f,cy,theta0] [--depth-scale s] [--depth-code c]\n"
	"                 [--baseline b] [--focal f] [--doffs d] [--range min,max]\n"
	"                 [--step n]\n"
	"                 [-j jump] [--max-angle deg] [--noise model | file]\n"
	"                 [--pose file] [--image file] [-c factor | -n patches]\n"
	"                 [--area-weighted] [--fit k] [--max-dev k] [--max-rms r]\n"
	"                 [--min-extent k] [--min-faces k] [--tls] [-e error]\n"
	"                 [--border k] [--max-hole k] [--max-move k] [--min-free k]\n"
	"                 [--min-piece k] [--min-plane k] [--outline k] [--count n]\n"
	"                 [--fov deg] [--keep dir] [--texel size]\n"
	"                 [depth-image | mesh] [image]\n"
	"Make a concise model of a scene's planes from a depth image (PNG, PGM, PFM)\n"
	"and its co-registered image, or from a mesh (PLY, OBJ), told by content: the\n"
	"depth meshed (dm2mesh), its faces grouped into planar patches (segplanes),\n"
	"planes where the surface is planar and a decimated surface elsewhere, one\n"
	"mesh (planedecim), textured from the image, or from the mesh's vertex\n"
	"colours baked into an atlas.\n"
	"  -a                 write ascii PLY\n"
	"  -o model           name.obj (with name.mtl) or name.ply (s t, TextureFile);\n"
	"                     default standard output (PLY); a PGM/PPM image is\n"
	"                     written beside it as name_texture.png\n"
	"  -q                 quiet\n"
	"  -v                 each stage's figures, vertices, faces and CPU seconds, the\n"
	"                     reduction and E_mean E_stdev E_rms E_max (the dense mesh's\n"
	"                     vertex positions, each once, to the model)\n"
	"      --keep dir     write each stage into dir: 1-mesh.ply, 2-patches.ply,\n"
	"                     3-model.ply\n"
	"      --texel size   a mesh with vertex colours and no image, written to -o\n"
	"                     model: the texels, metres, of the atlas baked from its\n"
	"                     colours, name_atlas0.png (default half the mesh's mean\n"
	"                     edge; 0: no atlas, the model's vertex colours only)\n"
	"The depth image, as dm2mesh(1):\n"
	"  -K, --camera, --cylindrical\n"
	"                     the camera (a dataset's name also sets its depth scale,\n"
	"                     code and noise model; Middlebury's calib.txt, disparities)\n"
	"      --depth-scale, --depth-code, --baseline, --focal, --doffs, --range, --step\n"
	"                     depth units and encoding, disparities, depths kept,\n"
	"                     pixels used\n"
	"  -j jump, --max-angle deg\n"
	"                     no face across a depth jump (default 10, and the noise)\n"
	"      --noise model | file\n"
	"                     the sensor's noise model (vertex sigma); for a mesh as\n"
	"                     well (without a camera one figure: poly:A,0,0)\n"
	"      --pose file    camera-to-world pose: the model in world coordinates\n"
	"      --image file   the co-registered image (or the second operand)\n"
	"Planar patches, as segplanes(1):\n"
	FCT_SEG_USAGE
	"The planar model, as planedecim(1):\n"
	FCT_PLANAR_USAGE
	"A panorama's texture, as cyl2planar(1):\n"
	"      --count n, --fov deg\n"
	"                     n planar views of deg degrees, written beside the model\n"
	"                     (default 8 of 90)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

enum { OPT_VERSION = 256, OPT_COUNT, OPT_FOV, OPT_KEEP };

struct options {
	const char *out, *keep, *input, *image;
	int ascii;
	struct fct_bake_opts bake;
	struct fct_depth_opts d;
	struct fct_seg_opts s;
	struct fct_planar_params plan;
	struct fct_cylview_params view;
};

static void parse_options(int argc, char **argv, struct options *o)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, OPT_VERSION},
		FCT_DEPTH_LONGOPTS,
		FCT_SEG_LONGOPTS,
		FCT_PLANAR_LONGOPTS,
		{"count", required_argument, NULL, OPT_COUNT},
		{"fov", required_argument, NULL, OPT_FOV},
		{"keep", required_argument, NULL, OPT_KEEP},
		FCT_BAKE_LONGOPTS,
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ac:e:hj:K:n:o:qv";
	int c;
	memset(o, 0, sizeof *o);
	fct_depth_opts_init(&o->d);
	fct_seg_opts_init(&o->s);
	fct_planar_params_default(&o->plan);
	fct_cylview_params_default(&o->view);
	fct_bake_opts_init(&o->bake);
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_depth_opt(&o->d, c, optarg) || fct_seg_opt(&o->s, c, optarg) ||
		    fct_planar_opt(&o->plan, c, optarg) || fct_bake_opt(&o->bake, c, optarg))
			continue;
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case OPT_VERSION: puts("planarize (facet) " FCT_VERSION); exit(0);
		case OPT_COUNT: o->view.count = (int)fct_opt_long("--count", optarg, 1, FCT_CYLVIEW_MAX_COUNT); break;
		case OPT_FOV:
			o->view.fov = fct_opt_double("--fov", optarg, -HUGE_VAL, HUGE_VAL);
			if (!(o->view.fov > 0 && o->view.fov < 180))
				fct_usage_error("--fov: %s degrees: a planar view sees less than 180", optarg);
			break;
		case OPT_KEEP: o->keep = optarg; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (argc - optind > 2)
		fct_usage_error("too many operands: a depth image or a mesh, and an image");
	o->input = optind < argc ? argv[optind] : "-";
	o->image = optind + 1 < argc ? argv[optind + 1] : NULL;
	if (o->image && o->d.image_file)
		fct_usage_error("the image is given twice (--image and the second operand)");
	if (!o->image)
		o->image = o->d.image_file;
	if (o->image && fct_path_is_std(o->image))
		fct_usage_error("the image cannot be standard input: a model names its texture's file");
	fct_seg_opts_check(&o->s);
	fct_depth_opts_check(&o->d);
}

/* Each stage's size and CPU time, for the summary of -v. */
struct stage_line {
	const char *name;
	size_t vertices, faces;
	double cpu_s;
};

static struct stage_line lines[5];
static size_t nlines;

static void stage_done(const char *name, const struct fct_mesh *m, double c0)
{
	lines[nlines++] = (struct stage_line){ name, m->nv, m->nf, fct_cpu_time() - c0 };
}

/* Open the input and tell a depth image from a mesh by its first byte:
 * the PNG signature's 0x89, JPEG's 0xFF, PFM's 'P' (a mesh is PLY, "ply",
 * or OBJ, whose keywords are lower case). */
static FILE *open_input(const char *path, int *is_image)
{
	FILE *f = fct_path_is_std(path) ? stdin : fopen(path, "rb");
	if (!f)
		fct_die(1, "%s: %s", path, strerror(errno));
	int c = getc(f);
	*is_image = c == 0x89 || c == 0xff || c == 'P';
	if (c != EOF)
		ungetc(c, f);
	return f;
}

/* Stage 1 from a depth image: its dense mesh (dm2mesh). */
static void mesh_depth(struct fct_mesh *m, struct fct_camera *cam, struct options *o, FILE *f)
{
	struct fct_err err;
	struct fct_image img;
	const char *name = fct_path_display(o->input);
	if (fct_image_read_stream(&img, f, name, NULL, &err))
		fct_die_err(&err);
	fct_depth_opts_resolve(&o->d, cam, &img, name);
	struct fct_grid_stats st;
	if (fct_depth_mesh(m, &img, cam, &o->d.depth, &st, &err))
		fct_die_err_at(&err, "dm2mesh: %s", name);
	fct_report_stage("dm2mesh", "pixels", "%zu", (size_t)img.width * (size_t)img.height);
	fct_image_free(&img);
	fct_report_stage("dm2mesh", "jump_faces", "%zu", st.jump_faces);
	fct_report_stage("dm2mesh", "speck_faces", "%zu", st.speck_faces);
	char noise[256];
	fct_noise_format(&o->d.depth.noise, noise, sizeof noise);
	fct_report_stage("dm2mesh", "noise", "%s", *noise ? noise : "unknown");
	o->d.image_file = o->image;
	if (fct_depth_opts_finish(&o->d, m, cam, &err))
		fct_die_err_at(&err, "dm2mesh");
	fct_report_stage("dm2mesh", "double_xyz", "%d", o->d.double_xyz);
}

/* --noise for a mesh: each vertex's sigma from the model (replacing any the
 * mesh has), as dm2mesh gives a view's, or one figure for a mesh without a
 * camera.  What another tool's fused scan needs: its own residuals are
 * smoothed by its fusion and say nothing of its registration's error (the
 * Open3D fragment of ../shared/data: a 0.43 mm estimate on a wall that bends
 * by 2-4 mm, cut into 53 patches). */
static void mesh_noise(struct fct_mesh *m, const struct fct_camera *cam, const struct options *o,
                       const char *name)
{
	struct fct_err err;
	struct fct_noise nz = o->d.depth.noise;
	if (!fct_noise_names_model(o->d.noise) && fct_noise_read_file(o->d.noise, &nz, &err))
		fct_die_err(&err);
	double pose[12], inv[12];
	int has_pose = cam->kind != FCT_CAMERA_NONE ? fct_header_pose(m, pose, &err) : 0;
	if (has_pose < 0)
		fct_die_err_at(&err, "%s", name);
	if (has_pose)
		fct_pose_invert(pose, inv);
	if (fct_mesh_noise_sigma(m, &nz, cam, has_pose ? inv : NULL, &err))
		fct_usage_error("--noise: %s: %s", name, err.msg);
	if (fct_header_set_noise(m, &nz, &err))
		fct_die_err(&err);
}

/* Stage 1 from a mesh: the mesh as it is, its camera if it has one; an
 * image given replaces its texture. */
static void mesh_read(struct fct_mesh *m, struct fct_camera *cam, const struct options *o, FILE *f)
{
	struct fct_err err;
	const char *name = fct_path_display(o->input);
	char *dir = fct_path_is_std(o->input) ? NULL : fct_path_dir(o->input, &err);
	if (!fct_path_is_std(o->input) && !dir)
		fct_die_err(&err);
	int rc = fct_mesh_read_stream(m, f, name, dir, NULL, &err);
	free(dir);
	if (rc) {
		/* The reader takes anything that is not PLY for OBJ: say what else
		 * the input could have been. */
		if (strstr(err.msg, "not a PLY or OBJ file"))
			fct_die(1, "%s: neither a depth image (PNG, PGM, JPEG or PFM) nor a mesh (PLY or OBJ)", name);
		fct_die_err(&err);
	}
	if (o->d.first)
		fct_usage_error("%s: for depth images, and %s is a mesh", o->d.first, name);
	if (fct_header_camera(m, cam, &err) < 0)
		fct_die_err_at(&err, "%s", name);
	if (o->d.noise)
		mesh_noise(m, cam, o, name);
	if (o->image && fct_header_set_texture(m, 0, o->image, &err))
		fct_die_err(&err);
}

static void keep_stage(const struct options *o, const struct fct_mesh *m, const char *file)
{
	if (!o->keep)
		return;
	struct fct_err err;
	char *path = fct_path_join(o->keep, file, &err);
	if (!path || fct_mesh_write_file(m, path, o->ascii, &err))
		fct_die_err(&err);
	free(path);
}

/* The positions of m's vertices, each once (a triangle soup holds each
 * position once per corner, which would weigh the errors): *n of them. */
static double *distinct_positions(const struct fct_mesh *m, size_t *n)
{
	struct fct_err err;
	uint32_t *first = fct_alloc_array(m->nv ? m->nv : 1, sizeof *first, &err);
	double *xyz = fct_alloc_array(3 * (m->nv ? m->nv : 1), sizeof *xyz, &err);
	if (!first || !xyz || fct_mesh_duplicate_vertices(m, first, &err) < 0)
		fct_die_err(&err);
	*n = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (first[v] == v)
			memcpy(xyz + 3 * (*n)++, m->xyz + 3 * v, 3 * sizeof *xyz);
	free(first);
	return xyz;
}

/* Table 1 of Kang et al.: the distances of the dense mesh's vertices
 * (xyz, nv of them) to the model's faces. */
static void report_errors(const double *xyz, size_t nv, const struct fct_mesh *model)
{
	struct fct_err err;
	struct fct_dist_stats st;
	if (fct_point_distances(&st, xyz, nv, model, &err))
		fct_die_err(&err);
	fct_report("E_mean", "%.9g", st.mean);
	fct_report("E_stdev", "%.9g", st.stdev);
	fct_report("E_rms", "%.9g", st.rms);
	fct_report("E_max", "%.9g", st.max);
}

/* The figures of the planar model's steps. */
static void report_model(const struct fct_planar_stats *st)
{
	fct_report_stage("planedecim", "planes", "%zu", st->planes);
	fct_report_stage("planedecim", "sigma_estimated", "%d", st->sigma_estimated);
	fct_report_stage("planedecim", "facets", "%zu", st->facets);
	fct_report_stage("planedecim", "small_faces", "%zu", st->tidy.small_faces);
	fct_report_stage("planedecim", "debris_pieces", "%zu", st->debris_pieces);
	fct_report_stage("planedecim", "debris_faces", "%zu", st->debris_faces);
	fct_report_stage("planedecim", "speck_faces", "%zu", st->tidy.speck_faces);
	fct_report_stage("planedecim", "off_plane_faces", "%zu", st->tidy.off_plane_faces);
	fct_report_stage("planedecim", "closed_faces", "%zu", st->tidy.closed_faces);
	fct_report_stage("planedecim", "seam_faces", "%zu", st->tidy.seam_faces);
	fct_report_stage("planedecim", "holes_filled", "%zu", st->holes_filled);
	fct_report_stage("planedecim", "free_holes_filled", "%zu", st->free_holes_filled);
	fct_report_stage("planedecim", "collapses", "%zu", st->qem.collapses);
	fct_report_stage("planedecim", "max_error", "%.9g", st->qem.max_error);
	fct_report_stage("planedecim", "planar_triangles", "%zu", st->planar_triangles);
	fct_report_stage("planedecim", "free_faces", "%zu", st->free_faces);
	fct_report_stage("planedecim", "border_free_faces", "%zu", st->border_free_faces);
	fct_report_stage("planedecim", "unclean_patches", "%zu", st->unclean_patches);
	fct_report_stage("planedecim", "reprojected", "%zu", st->reprojected);
	fct_report_stage("planedecim", "moved_line", "%zu", st->meet.lines);
	fct_report_stage("planedecim", "moved_corner", "%zu", st->meet.corners);
	fct_report_stage("planedecim", "torn", "%zu", st->meet.torn);
}

/* A panorama's model textured through planar views written beside it
 * (cyl2planar): from the image given, else the mesh's TextureFile. */
static void texture_panorama(struct fct_mesh *m, const struct fct_camera *cam,
                             const struct options *o)
{
	struct fct_err err;
	const char *path = o->image ? o->image : fct_header_texture(m, 0);
	if (!path)
		return;
	if (!o->out || fct_path_is_std(o->out))
		fct_usage_error("-o model is needed: a panorama's model has its views beside it");
	struct fct_image img;
	if (fct_image_read_file(&img, path, NULL, &err))
		fct_die_err(&err);
	if (img.type == FCT_PIX_F32)
		fct_die(1, "%s: a PFM image cannot texture a model: give a PNG or JPEG", path);
	double pose[12];
	int hp = fct_header_pose(m, pose, &err);
	struct fct_cylview_model_stats st;
	if (hp < 0)
		fct_die_err_at(&err, "cyl2planar");
	if (fct_cylview_check_panorama(&img, cam, 1, NULL, &err))
		fct_die_err_at(&err, "cyl2planar: %s", path);
	if (fct_cylview_texture_model(m, &img, cam, hp ? pose : NULL, &o->view, 1, "the model", o->out,
	                              &st, &err))
		fct_die_err_at(&err, "cyl2planar");
	fct_image_free(&img);
	fct_report_stage("cyl2planar", "views_used", "%zu", st.assign.views_used);
	fct_report_stage("cyl2planar", "splits", "%zu", st.assign.splits);
	fct_report_stage("cyl2planar", "max_depth_ratio", "%.9g", st.assign.max_ratio);
}

/* A PGM or PPM image (NYU Depth v2's colour frames) written as a PNG beside
 * the model, whose texture it becomes: MeshLab opens netpbm, Blender and
 * Open3D do not.  Its path, name_texture.png for a model name.obj/.ply. */
static char *texture_as_png(const char *image, const char *out)
{
	if (!out || fct_path_is_std(out))
		fct_usage_error("-o model is needed: a PGM or PPM image is written beside it as the PNG texture");
	size_t stem = fct_path_stem_length(out);
	char *png = malloc(stem + sizeof "_texture.png");
	if (!png)
		fct_die(1, "out of memory");
	memcpy(png, out, stem);
	memcpy(png + stem, "_texture.png", sizeof "_texture.png");
	struct fct_image img;
	struct fct_err err;
	if (fct_image_read_file(&img, image, NULL, &err))
		fct_die_err(&err);
	fct_write_image_or_die(&img, png);
	fct_image_free(&img);
	return png;
}

int main(int argc, char **argv)
{
	fct_cli_init("planarize");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	int is_image;
	char *png_texture = NULL;   /* a PGM/PPM image's PNG beside the model */
	FILE *in = open_input(o.input, &is_image);
	if (o.d.cylindrical && o.image && (!o.out || fct_path_is_std(o.out)))
		fct_usage_error("-o model is needed: a panorama's model has its views beside it");
	if (o.image) {
		/* The texture's file must be an image now, not when a viewer opens
		 * the model. */
		struct fct_image probe;
		enum fct_image_format fmt;
		if (fct_image_probe_file(&probe, o.image, &fmt, &err))
			fct_die_err(&err);
		if (fmt == FCT_IMAGE_PNM)
			o.image = png_texture = texture_as_png(o.image, o.out);
	}
	fct_depth_opts_read_pose(&o.d);
	if (o.keep)
		fct_make_folder("--keep", o.keep);

	double t0 = fct_now(), c0 = fct_cpu_time(), c1;
	struct fct_mesh m;
	struct fct_camera cam;
	if (is_image)
		mesh_depth(&m, &cam, &o, in);
	else
		mesh_read(&m, &cam, &o, in);
	if (in != stdin)
		fclose(in);
	if (fct_header_add_provenance(&m, "planarize", argc - 1, argv + 1, &err))
		fct_die_err(&err);
	/* Coordinates as a file holds them, so that the stages give what the
	 * programs give on a pipe (and on the files of --keep). */
	fct_mesh_round_xyz(&m);
	stage_done(is_image ? "dm2mesh" : "read", &m, c0);
	keep_stage(&o, &m, "1-mesh.ply");
	size_t dense_faces = m.nf, dense_nv = m.nv;
	/* The dense mesh's colours, kept for the model's atlas. */
	struct fct_colbake bake = { 0 };
	int baking = !is_image && !o.image && fct_bake_wanted(&o.bake, o.out, &m);
	if (baking && fct_colbake_init(&bake, &m, &err))
		fct_die_err_at(&err, "bake");
	double *dense = NULL;
	if (fct_verbose)
		dense = distinct_positions(&m, &dense_nv);

	/* Patches of fewer faces than one in 600 of the mesh's (at least 8) go
	 * to their best neighbour: below that they are specks of noise. */
	if (!o.s.min_faces_given)
		o.s.seg.min_faces = m.nf / 600 > 8 ? (long)(m.nf / 600) : 8;
	c1 = fct_cpu_time();
	struct fct_segment_stats sst;
	if (fct_segment_mesh(&m, &o.s.seg, o.s.tls, &sst, &err))
		fct_die_err_at(&err, "segplanes: %s", fct_path_display(o.input));
	fct_report_stage("segplanes", "min_faces", "%ld", o.s.seg.min_faces);
	fct_report_stage("segplanes", "welded_vertices", "%zu", sst.welded);
	fct_report_stage("segplanes", "patches", "%zu", sst.patches);
	fct_report_stage("segplanes", "noise", "%.9g", sst.noise);
	fct_report_stage("segplanes", "clusters", "%zu", sst.clusters);
	fct_report_stage("segplanes", "merges", "%zu", sst.merges);
	fct_report_stage("segplanes", "absorbed", "%zu", sst.absorbed);
	fct_report_stage("segplanes", "free_faces", "%zu", sst.free_faces);
	stage_done("segplanes", &m, c1);
	keep_stage(&o, &m, "2-patches.ply");

	c1 = fct_cpu_time();
	struct fct_planar_stats pst;
	if (fct_planar_model(&m, &o.plan, &pst, &err))
		fct_die_err_at(&err, "planedecim: %s", fct_path_display(o.input));
	report_model(&pst);
	stage_done("planedecim", &m, c1);
	keep_stage(&o, &m, "3-model.ply");

	if (cam.kind == FCT_CAMERA_CYLINDRICAL) {
		c1 = fct_cpu_time();
		texture_panorama(&m, &cam, &o);
		stage_done("cyl2planar", &m, c1);
	}
	if (baking && fct_colbake_applies(&m)) {
		c1 = fct_cpu_time();
		fct_bake_model(&m, &bake, &o.bake, o.out);
		stage_done("bake", &m, c1);
	}
	fct_colbake_free(&bake);
	if (fct_mesh_write_file(&m, o.out, o.ascii, &err))
		fct_die_err(&err);

	for (size_t i = 0; fct_verbose && i < nlines; i++)
		fprintf(stderr, "%s: %-10s %9zu vertices %9zu faces %8.3f s\n", fct_prog, lines[i].name,
		        lines[i].vertices, lines[i].faces, lines[i].cpu_s);
	fct_report("reduction", "%.1f", pst.faces_out ? (double)dense_faces / (double)pst.faces_out : 0);
	if (dense)
		report_errors(dense, dense_nv, &m);
	fct_report("cpu_s", "%.3f", fct_cpu_time() - c0);
	fct_report("total_s", "%.3f", fct_now() - t0);
	free(dense);
	fct_mesh_free(&m);
	free(png_texture);
	return 0;
}
