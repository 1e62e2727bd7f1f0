/* viewtex - texture a mesh from registered colour photographs: one photo
 * per face by a graph cut, the faces' texture packed into atlas pages,
 * colour levelled across the seams (Waechter, Moehrle and Goesele, "Let
 * There Be Color!", ECCV 2014; Kang et al., DEC CRL 95/7, sec. 6, 7 and 9).
 * The library does the work (viewtex.h). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "render/photo.h"
#include "cli/texopts.h"

static const char usage[] =
	"usage: viewtex [-aqv] [-K fx,fy,cx,cy | name] [--camera file] [--poses file ...]\n"
	"               [--image file ...] [--atlas-size n] [--blend] [--candidates n]\n"
	"               [--fill r,g,b] [--level none | gain | seams] [--max-pages n]\n"
	"               [--min-angle deg] [--no-rectify] [--one-photo] [--padding n]\n"
	"               [--per-vertex] [--smooth w] [--texel-scale s] -o model mesh\n"
	"               [image ...]\n"
	"Texture a mesh (PLY or OBJ) from registered colour photos: each face from\n"
	"one photo chosen for visibility, resolution, sharpness and distance from\n"
	"depth edges, neighbours kept on the same photo by a graph cut; the faces'\n"
	"texture packed into atlas images beside the model, colour levelled across\n"
	"the seams.  Planar patches (face patch, element plane) get undistorted\n"
	"texture in their plane's frame.\n"
	"  -a                 write ascii PLY\n"
	"  -K fx,fy,cx,cy     the photos' camera (or a dataset name)\n"
	"  -o model           the model: name.obj (with name.mtl, a vt per face\n"
	"                     corner) or name.ply (per-face texcoord and texnumber);\n"
	"                     the atlas beside it as name_atlasN.png\n"
	"  -q                 quiet\n"
	"  -v                 progress per photo, then figures on stderr\n"
	"      --atlas-size n largest atlas side, a power of two, 64 to 16384\n"
	"                     (default 4096)\n"
	"      --blend        each texel the mean of its face's candidate photos that\n"
	"                     see it, weighed by their resolution, instead of its one\n"
	"                     photo: softer, robust to misregistered photos (implies\n"
	"                     --level none unless given)\n"
	"      --camera file  the photos' camera: an intrinsics file (see dm2mesh)\n"
	"      --candidates n photos kept per face, 1 to 32 (default 6)\n"
	"      --fill r,g,b   colour of faces no photo sees (default 128,128,128)\n"
	"      --image file   a photo (repeated; or as operands after the mesh)\n"
	"      --level how    colour levelling: none, gain (a gain per photo and\n"
	"                     channel, from the faces' colours in all photos), seams\n"
	"                     (and offsets per vertex that close each seam; the\n"
	"                     default)\n"
	"      --max-pages n  most atlas images (default 16); the texture is drawn\n"
	"                     smaller until it fits\n"
	"      --min-angle deg\n"
	"                     photos seeing a face at less than this angle to its\n"
	"                     plane are a last resort (default 5.7: cosine 0.1)\n"
	"      --no-rectify   texture planar patches from the photo's projection too\n"
	"      --one-photo    each face from its one photo (the default; roommodel's\n"
	"                     is --blend)\n"
	"      --padding n    texels padded around each chart (default 4)\n"
	"      --per-vertex   PLY with vertex s t (vertices copied at chart borders)\n"
	"                     instead of per-face texcoord\n"
	"      --poses file   camera-to-world poses: one file per photo (4x4 or 3x4),\n"
	"                     or one trajectory (TUM, Redwood .log, KITTI, stacked 4x4)\n"
	"      --smooth w     cost of a seam per pixel of its length, in pixels of\n"
	"                     lost quality (default 10)\n"
	"      --texel-scale s\n"
	"                     texels per photo pixel, 0.01 to 4 (default 1)\n"
	"  -h, --help         this help\n"
	"      --version      print the version\n";

struct options {
	const char *K, *camera, *mesh, *out;
	const char **poses, **images;
	size_t nposes, nimages;
	int ascii, per_vertex;
	struct fct_tex_opts t;    /* the texture's options, shared with roommodel */
};

static void parse_options(int argc, char **argv, struct options *o)
{
	enum { CAMERA = 256, POSES, IMAGE, PERVERTEX, SMOOTH, VERSION };
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, VERSION},
		{"camera", required_argument, NULL, CAMERA}, {"poses", required_argument, NULL, POSES},
		{"image", required_argument, NULL, IMAGE}, FCT_TEX_LONGOPTS,
		{"per-vertex", no_argument, NULL, PERVERTEX}, {"smooth", required_argument, NULL, SMOOTH},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "ahK:o:qv";
	memset(o, 0, sizeof *o);
	fct_tex_opts_init(&o->t);
	o->poses = calloc((size_t)argc + 1, sizeof *o->poses);
	o->images = calloc((size_t)argc + 1, sizeof *o->images);
	if (!o->poses || !o->images)
		fct_die(1, "out of memory");
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		if (fct_tex_opt(&o->t, c, optarg))
			continue;
		switch (c) {
		case 'a': o->ascii = 1; break;
		case 'h': fputs(usage, stdout); exit(0);
		case 'K': o->K = optarg; break;
		case 'o': o->out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case CAMERA: o->camera = optarg; break;
		case POSES: o->poses[o->nposes++] = optarg; break;
		case IMAGE: o->images[o->nimages++] = optarg; break;
		case PERVERTEX: o->per_vertex = 1; break;
		case SMOOTH: o->t.p.smooth = fct_opt_double("--smooth", optarg, 0, 1e6); break;
		case VERSION: puts("viewtex (facet) " FCT_VERSION); exit(0);
		default: fct_bad_option(optstring, argv);
		}
	}
	fct_tex_opts_check(&o->t);
	if (optind >= argc)
		fct_usage_error("no mesh");
	o->mesh = argv[optind++];
	for (; optind < argc; optind++)
		o->images[o->nimages++] = argv[optind];
	if (!o->out)
		fct_usage_error("-o model is needed (the atlas is written beside it)");
	if (fct_path_is_std(o->out))
		fct_usage_error("-o: the model must be a named file (the atlas is written beside it)");
	if (!o->nimages)
		fct_usage_error("no photos: give them with --image or after the mesh");
	if (o->K && o->camera)
		fct_usage_error("-K and --camera exclude each other");
	if (!o->K && !o->camera)
		fct_usage_error("no camera: give -K or --camera");
}

int main(int argc, char **argv)
{
	fct_cli_init("viewtex");
	struct options o;
	parse_options(argc, argv, &o);
	struct fct_err err;
	double t0 = fct_now();
	struct fct_camera cam;
	fct_opt_camera(&cam, NULL, NULL, o.K, o.camera);
	struct fct_photo *ph;
	if (fct_photos_make(&ph, &cam, o.images, o.nimages, o.poses, o.nposes, &err))
		fct_die_err(&err);
	struct fct_mesh m;
	if (fct_mesh_read_file(&m, o.mesh, NULL, &err))
		fct_die_err(&err);
	const char *name = fct_path_display(o.mesh);
	struct fct_viewtex *T = fct_viewtex_new(&m, o.nimages, &o.t.p, &err);
	if (!T)
		fct_die_err_at(&err, "%s", name);
	double read_s = fct_now() - t0;

	/* Candidates, one photo at a time. */
	double t1 = fct_now();
	size_t any = 0, *seen = fct_alloc_array(o.nimages, sizeof *seen, &err);
	if (!seen || fct_viewtex_add_photos(T, ph, o.nimages, seen, &err))
		fct_die_err(&err);
	for (size_t i = 0; i < o.nimages; i++) {
		any += seen[i];
		if (fct_verbose)
			fprintf(stderr, "viewtex: photo %zu/%zu %s: sees %zu faces whole\n", i + 1, o.nimages,
			        ph[i].path, seen[i]);
	}
	free(seen);
	if (!any)
		fct_die(1, "%s: no photo sees any face whole (check the poses and the camera)", name);
	double see_s = fct_now() - t1;
	t1 = fct_now();
	if (fct_viewtex_label(T, &err) || fct_viewtex_layout(T, &err))
		fct_die_err(&err);
	double label_s = fct_now() - t1;

	/* Texels, one photo at a time, each photo that textures faces. */
	t1 = fct_now();
	if (fct_viewtex_sample_photos(T, ph, o.nimages, &err))
		fct_die_err(&err);
	if (fct_viewtex_finish(T, &err))
		fct_die_err(&err);
	double sample_s = fct_now() - t1;

	t1 = fct_now();
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	fct_tex_write_atlas(T, &m, o.out, fct_path_has_suffix(o.out, ".obj") || !o.per_vertex);
	if (fct_header_add_provenance(&m, "viewtex", argc - 1, argv + 1, &err) ||
	    fct_mesh_write_file(&m, o.out, o.ascii, &err))
		fct_die_err(&err);
	double write_s = fct_now() - t1;

	if (fct_verbose)
		for (size_t i = 0; i < o.nimages; i++)
			fprintf(stderr, "viewtex: photo %s textures %zu faces\n", ph[i].path,
			        fct_viewtex_view_faces(T, i));
	fct_report("photos", "%zu", o.nimages);
	fct_report("photos_used", "%zu", st.views_used);
	fct_report("faces", "%zu", st.faces);
	fct_report("faces_unseen", "%zu", st.unseen);
	fct_report("candidates", "%zu", st.candidates);
	fct_report("outliers", "%zu", st.outliers);
	fct_report("cycles", "%d", st.cycles);
	fct_report("energy_start", "%.6g", st.energy_start);
	fct_report("energy", "%.6g", st.energy);
	fct_report("charts", "%zu", st.charts);
	fct_report("charts_rectified", "%zu", st.rectified);
	fct_report("seam_edges", "%zu", st.seam_edges);
	fct_report("atlas_pages", "%zu", st.pages);
	fct_report("atlas_size", "%dx%d", st.page_width, st.page_height);
	fct_report("texel_scale", "%.4g", st.scale);
	fct_report("fill_ratio", "%.4f", st.fill_ratio);
	fct_report("seam_rms_before", "%.3f", st.seam_rms_before);
	fct_report("seam_rms_after", "%.3f", st.seam_rms_after);
	fct_report("read_s", "%.3f", read_s);
	fct_report("see_s", "%.3f", see_s);
	fct_report("label_s", "%.3f", label_s);
	fct_report("sample_s", "%.3f", sample_s);
	fct_report("write_s", "%.3f", write_s);
	fct_report("total_s", "%.3f", fct_now() - t0);
	fct_viewtex_free(T);
	fct_mesh_free(&m);
	free(ph);
	free(o.poses);
	free(o.images);
	return 0;
}
