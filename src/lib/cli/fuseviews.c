/* fuseviews.c - tsdfuse's views, read one at a time (see fuseviews.h). */
#include "cli/fuseviews.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "depth/depthcode.h"
#include "geom/geom.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "io/poses.h"
#include "render/viewcolor.h"
#include "fusion/voxgrid.h"

/* The poses of the depth images among the operands (vs->depth), 12 per
 * image in operand order (poses.h matches them to --poses), into
 * vs->dposes (NULL when there are none). */
static void depth_poses(struct fct_fuse_views *vs)
{
	const struct fct_fuse_opts *o = vs->o;
	struct fct_err err;
	const char **frames = calloc(vs->ndepth + 1, sizeof *frames);
	if (!frames)
		fct_die(1, "out of memory");
	for (size_t i = 0; i < vs->npaths; i++)
		if (vs->depth[i])
			frames[vs->depth[i] - 1] = vs->paths[i];
	size_t n = vs->ndepth;
	vs->dposes = NULL;
	if (n == 0 && o->nposes)
		fct_usage_error("--poses is for depth images, and no view is one");
	if (n > 0) {
		if (vs->dcam->kind == FCT_CAMERA_NONE)
			fct_usage_error("%s: a depth image needs -K or --camera", frames[0]);
		if (!o->nposes)
			fct_usage_error("%s: a depth image needs --poses", frames[0]);
		if (o->nposes > 1 && o->nposes != n)
			fct_usage_error("%zu depth images but %zu --poses files (give one per image, or one "
			                "file of them all)", n, o->nposes);
		struct fct_frame_poses_stats st;
		if (!(vs->dposes = fct_alloc_array(n, 12 * sizeof *vs->dposes, &err)) ||
		    fct_frame_poses(vs->dposes, &st, o->poses, o->nposes, frames, n, o->max_diff, &err))
			fct_die_err(&err);
		static const char *const by[] = { "files", "order", "timestamp", "frame number" };
		fct_report("poses", "%s", fct_traj_format_name(st.format));
		fct_report("poses_matched_by", "%s", by[st.match]);
		if (st.match == FCT_MATCH_STAMP)
			fct_report("poses_max_difference_s", "%.6f", st.max_diff);
	}
	free(frames);
}

void fct_fuse_views_init(struct fct_fuse_views *vs, const struct fct_fuse_opts *o, char **paths,
                         size_t npaths, const struct fct_conf *conf, int color,
                         const struct fct_camera *dcam, const struct fct_depth_params *dp)
{
	memset(vs, 0, sizeof *vs);
	vs->o = o, vs->paths = paths, vs->npaths = npaths, vs->conf = conf, vs->color = color;
	vs->dcam = dcam, vs->dp = dp;
	vs->n = npaths + conf->n;
	vs->image = calloc(vs->n ? vs->n : 1, sizeof *vs->image);
	vs->depth = calloc(vs->n ? vs->n : 1, sizeof *vs->depth);
	if (!vs->image || !vs->depth)
		fct_die(1, "out of memory");
	size_t nimage = 0;
	for (size_t i = 0; i < npaths; i++)
		if (fct_path_is_image(paths[i])) {
			vs->depth[i] = ++vs->ndepth;
			vs->image[i] = nimage < o->nimages ? ++nimage : (nimage++, 0);
		}
	if (o->nimages && o->nimages != nimage)
		fct_usage_error("%zu depth views but %zu --image files", nimage, o->nimages);
	depth_poses(vs);
}

void fct_fuse_views_free(struct fct_fuse_views *vs)
{
	free(vs->image);
	free(vs->depth);
	free(vs->dposes);
	memset(vs, 0, sizeof *vs);
}

/* A range-grid scan of the .conf: meshed, moved by its pose. */
static void load_scan(struct fct_fuse_input *L, const struct fct_conf_scan *s)
{
	struct fct_err err;
	snprintf(L->name, sizeof L->name, "%s", s->path);
	struct fct_mesh raw;
	if (fct_mesh_read_file(&raw, s->path, NULL, &err))
		fct_die_err(&err);
	double step;
	int rc = fct_range_grid_mesh(&L->mesh, &raw, NULL, &step, &err);
	fct_mesh_free(&raw);
	if (rc)
		fct_die_err_at(&err, "%s", s->path);
	for (size_t v = 0; v < L->mesh.nv; v++)
		fct_pose_apply(s->pose, &L->mesh.xyz[3 * v], &L->mesh.xyz[3 * v]);
	memcpy(L->view.pose, s->pose, sizeof s->pose);
	L->view.cam.kind = FCT_CAMERA_NONE;
	L->view.ortho_step = step;
}

int fct_fuse_read_depth(struct fct_image *img, struct fct_camera *cam, const char *path,
                        const struct fct_camera *dcam, const struct fct_depth_params *dp, int may_warn)
{
	struct fct_err err;
	if (fct_image_read_file(img, path, NULL, &err))
		fct_die_err(&err);
	if (fct_depth_decode(img, dp->code, &err))
		fct_die_err_at(&err, "%s", path);
	*cam = *dcam;
	if (cam->width == 0)
		cam->width = img->width, cam->height = img->height;
	if (cam->width != img->width || cam->height != img->height)
		fct_die(1, "%s: image is %dx%d, the camera %dx%d", path, img->width, img->height,
		        cam->width, cam->height);
	char why[300];
	if (!may_warn || !fct_depth_implausible(why, sizeof why, img, cam, dp))
		return 0;
	fct_warn("%s: %s", path, why);
	return 1;
}

/* A depth image with pose dpose: smoothed, meshed and moved to the world. */
static void load_depth_image(struct fct_fuse_input *L, const struct fct_fuse_views *vs,
                             const char *path, const double *dpose)
{
	struct fct_err err;
	snprintf(L->name, sizeof L->name, "%s", path);
	struct fct_image img;
	struct fct_camera cam;
	static int warned;      /* a wrong depth scale, once for all views */
	warned |= fct_fuse_read_depth(&img, &cam, path, vs->dcam, vs->dp, !warned);
	int rc = fct_fuse_depth_view(&L->view, &L->mesh, vs->o->fp.projective ? &L->depth : NULL, &img, &cam,
	                             vs->dp, &vs->o->smooth, dpose, vs->o->exact ? 0 : vs->o->voxel, &err);
	fct_image_free(&img);
	if (rc)
		fct_die_err_at(&err, "%s", path);
	L->depth_image = 1;
}

/* A mesh carrying its camera and pose comments (dm2mesh's); with colour,
 * its TextureFile. */
static void load_mesh(struct fct_fuse_input *L, const struct fct_fuse_views *vs, const char *path)
{
	struct fct_err err;
	snprintf(L->name, sizeof L->name, "%s", fct_path_display(path));
	if (fct_mesh_read_file(&L->mesh, path, NULL, &err))
		fct_die_err(&err);
	int c = fct_header_camera(&L->mesh, &L->view.cam, &err);
	if (c < 0)
		fct_die_err_at(&err, "%s", L->name);
	if (c == 0)
		fct_die(1, "%s: no camera comment: tsdfuse needs each view's camera (dm2mesh writes it)", L->name);
	c = fct_header_pose(&L->mesh, L->view.pose, &err);
	if (c < 0)
		fct_die_err_at(&err, "%s", L->name);
	if (c == 0)
		fct_die(1, "%s: no pose comment: tsdfuse needs each view's camera-to-world pose (dm2mesh --pose)", L->name);
	if (fct_pose_check(L->view.pose, 1e-3, &err))
		fct_die_err_at(&err, "%s: pose", L->name);
	if (vs->color && fct_header_texture_count(&L->mesh)) {
		/* On disk a TextureFile is relative to its mesh's folder. */
		char *dir = fct_path_dir(path, &err);
		if (!dir || !(L->image = fct_path_join(dir, fct_header_texture(&L->mesh, 0), &err)))
			fct_die_err(&err);
		free(dir);
	}
}

void fct_fuse_input_open(struct fct_fuse_views *vs, size_t i, struct fct_fuse_input *L)
{
	double t = fct_now();
	struct fct_err err;
	memset(L, 0, sizeof *L);
	if (i >= vs->npaths)
		load_scan(L, &vs->conf->scans[i - vs->npaths]);
	else if (vs->depth[i])
		load_depth_image(L, vs, vs->paths[i], &vs->dposes[12 * (vs->depth[i] - 1)]);
	else
		load_mesh(L, vs, vs->paths[i]);
	if (L->mesh.nf == 0)
		fct_die(1, "%s: empty view (no faces)", L->name);
	for (size_t v = 0; v < L->mesh.nv; v++)
		if (!(isfinite(L->mesh.xyz[3 * v]) && isfinite(L->mesh.xyz[3 * v + 1]) &&
		      isfinite(L->mesh.xyz[3 * v + 2])))
			fct_die(1, "%s: vertex %zu is not finite", L->name, v);
	L->view.mesh = &L->mesh;
	/* A view's noise, where its mesh carries it (a depth image meshed
	 * with a model here, or dm2mesh's mesh of one): the fusion weighs by
	 * it (fuse.h). */
	struct fct_prop *sp = fct_elem_find(&L->mesh.vertex, "sigma");
	L->view.sigma = sp && sp->type == FCT_FLOAT32 ? sp->data : NULL;
	if (L->depth_image && vs->image[i] &&
	    !(L->image = fct_strdup(vs->o->images[vs->image[i] - 1], &err)))
		fct_die_err(&err);
	vs->read_s += fct_now() - t;
}

void fct_fuse_input_close(struct fct_fuse_input *L)
{
	fct_mesh_free(&L->mesh);
	free(L->depth);
	free(L->image);
	memset(L, 0, sizeof *L);
}

void fct_fuse_input_warn_unused(const struct fct_fuse_input *L, int has_bbox)
{
	const double *t = &L->view.pose[3];
	double near = HUGE_VAL;
	if (L->view.cam.kind != FCT_CAMERA_NONE)
		for (size_t v = 0; v < L->mesh.nv; v++) {
			const double *p = &L->mesh.xyz[3 * v];
			near = fmin(near, hypot(hypot(p[0] - t[0], p[1] - t[4]), p[2] - t[8]));
		}
	if (near > 1e6 && near < HUGE_VAL)
		fct_warn("%s: the view adds nothing: its camera is %.3g m from its nearest point", L->name,
		         near);
	else
		fct_warn("%s: the view adds nothing%s", L->name, has_bbox ? " inside --bbox" : "");
}

/* The area of m's faces, each polygon a fan of triangles from its first
 * corner (non-finite triangles left out). */
static double mesh_area(const struct fct_mesh *m)
{
	double a = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *v = &m->fvert[m->fstart[f]];
		for (uint32_t k = 2; k < fct_face_size(m, f); k++) {
			double l = fct_triangle_area2(&m->xyz[3 * (size_t)v[0]], &m->xyz[3 * (size_t)v[k - 1]],
			                              &m->xyz[3 * (size_t)v[k]]);
			if (isfinite(l))
				a += l / 2;
		}
	}
	return a;
}

void fct_fuse_extent_init(struct fct_fuse_extent *e)
{
	*e = (struct fct_fuse_extent){ { HUGE_VAL, HUGE_VAL, HUGE_VAL }, { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL }, 0, 0 };
}

void fct_fuse_extent_add(struct fct_fuse_extent *e, const struct fct_mesh *m)
{
	e->n++;
	e->area += mesh_area(m);
	for (size_t v = 0; v < m->nv; v++)
		for (int k = 0; k < 3; k++) {
			double x = m->xyz[3 * v + k];
			e->lo[k] = x < e->lo[k] ? x : e->lo[k];
			e->hi[k] = x > e->hi[k] ? x : e->hi[k];
		}
}

double fct_fuse_machine_bytes(void)
{
	long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
	return pages > 0 && size > 0 ? (double)pages * (double)size : 4e9;
}


/* The volume holds voxels to 2^23 from the origin each way (fuse.c's block
 * keys): say whether the views' span or their offset is beyond. */
static _Noreturn void too_far(double vox, double lo, double hi)
{
	double span = (hi - lo) / vox, off = fmax(fabs(lo), fabs(hi));
	if (span < FCT_FUSE_VOXEL_RANGE)
		fct_die(1, "--voxel %g: the views lie %g m from the origin, %.3g voxels: beyond the "
		        "volume's %d each way (their span, %g m, fits: move the poses nearer the origin)",
		        vox, off, off / vox, FCT_FUSE_VOXEL_RANGE, hi - lo);
	fct_die(1, "--voxel %g: the views span %g m, %.3g voxels: beyond the volume's %d each way",
	        vox, hi - lo, span, FCT_FUSE_VOXEL_RANGE);
}


double fct_fuse_extent_volume(const struct fct_fuse_extent *e, double vox, double band,
                              const double *bbox, int carve, int32_t clo[3], int32_t chi[3])
{
	double lo[3], hi[3];
	for (int k = 0; k < 3; k++) {
		lo[k] = e->lo[k], hi[k] = e->hi[k];
		if (bbox) {
			lo[k] = fmax(lo[k], bbox[k] - 3 * vox);
			hi[k] = fmin(hi[k], bbox[k + 3] + 3 * vox);
		}
	}
	double bs = 8 * vox, bbox_blocks = 1;
	for (int k = 0; k < 3; k++)
		bbox_blocks *= fmax(hi[k] - lo[k], 0) / bs + 3;
	double band_blocks = 2 * e->area / (bs * bs) * (1 + 2 * band / bs) + 27.0 * (double)e->n;
	double est = fmin(band_blocks, bbox_blocks) * (double)fct_voxgrid_block_bytes(0);
	for (int k = 0; k < 3; k++) {
		double a = floor((lo[k] - band) / vox) - 2, b = ceil((hi[k] + band) / vox) + 2;
		if (!(fabs(a) < FCT_FUSE_VOXEL_RANGE && fabs(b) < FCT_FUSE_VOXEL_RANGE))
			too_far(vox, lo[k], hi[k]);
		clo[k] = (int32_t)a, chi[k] = (int32_t)b;
	}
	if (carve)
		est += (double)fct_carve_bytes(clo, chi);
	double have = fct_fuse_machine_bytes();
	if (est > 0.8 * have)
		fct_die(1, "--voxel %g: needs about %.1f GB, the machine has %.1f GB", vox, est / 1e9, have / 1e9);
	return est;
}


void fct_fuse_views_color(struct fct_fuse_views *vs, struct fct_mesh *out, size_t *ncolor)
{
	struct fct_err err;
	struct fct_viewcolor acc;
	if (fct_viewcolor_init(&acc, out->nv, &err))
		fct_die_err(&err);
	struct fct_viewcolor_params cp = { vs->o->fp.band, vs->o->fp.weight, 4 };
	*ncolor = 0;
	for (size_t i = 0; i < vs->n; i++) {
		struct fct_fuse_input L;
		fct_fuse_input_open(vs, i, &L);
		if (L.image && L.view.cam.kind != FCT_CAMERA_NONE) {
			++*ncolor;
			struct fct_range_image ri;
			struct fct_image img;
			size_t seen;
			if (fct_range_image_make(&ri, &L.view, (size_t)1 << 26, &err))
				fct_die_err_at(&err, "%s", L.name);
			if (fct_image_read_file(&img, L.image, NULL, &err))
				fct_die_err(&err);
			int rc = fct_viewcolor_add(&acc, out, &ri, &img, &cp, &seen, &err);
			fct_image_free(&img);
			fct_range_image_free(&ri);
			if (rc)
				fct_die_err_at(&err, "%s", L.name);
			if (fct_verbose)
				fprintf(stderr, "tsdfuse: colour from %s: %zu vertices seen\n", L.name, seen);
		}
		fct_fuse_input_close(&L);
	}
	if (!*ncolor)
		fct_warn("--color: no view has a colour image (TextureFile comment or --image): "
		         "every vertex gets the fallback grey");
	static const uint8_t grey[3] = { 128, 128, 128 };
	struct fct_viewcolor_stats st;
	if (fct_viewcolor_write(&acc, out, grey, &st, &err))
		fct_die_err(&err);
	fct_viewcolor_free(&acc);
	fct_report("colored_vertices", "%zu", st.colored);
	fct_report("uncolored_vertices", "%zu", st.unseen);
	fct_report("views_per_vertex", "%.2f", st.views_per_vertex);
}

int fct_fuse_depth_sigma(struct fct_mesh *out, const char *const *depth, const double *pose, size_t n,
                         const struct fct_camera *dcam, const struct fct_depth_params *dp,
                         const struct fct_fuse_opts *o, size_t *seen, double *level)
{
	struct fct_err err;
	*seen = 0, *level = 0;
	/* Exact data (--noise none): the fused surface's error is the
	 * volume's, the same everywhere, which segplanes estimates. */
	if (dp->noise.model == FCT_NOISE_UNKNOWN || dp->noise.model == FCT_NOISE_NONE)
		return -1;
	if (fct_noise_estimate(level, out, &err) || !(*level > 0)) {
		if (fct_verbose)
			fprintf(stderr, "%s: no sigma for the fused surface: %s\n", fct_prog, err.msg);
		return -1;
	}
	struct fct_viewnoise acc;
	if (fct_viewnoise_init(&acc, out->nv, &err))
		fct_die_err(&err);
	struct fct_viewcolor_params cp = { o->fp.band, o->fp.weight, 0 };
	for (size_t i = 0; i < n; i++) {
		struct fct_image img;
		struct fct_camera cam;
		fct_fuse_read_depth(&img, &cam, depth[i], dcam, dp, 0);
		/* The noise as the fusion took it (fct_fuse_depth_view). */
		struct fct_depth_params vp = *dp;
		fct_depth_noise_unit(&vp, &img);
		struct fct_range_image ri;
		int rc = fct_range_image_depth(&ri, &img, &cam, dp, &pose[12 * i], &err) ||
		         fct_viewnoise_add(&acc, out, &ri, &vp.noise, o->voxel, &cp, o->fp.threads, NULL, &err);
		fct_range_image_free(&ri);
		fct_image_free(&img);
		if (rc)
			fct_die_err_at(&err, "%s", depth[i]);
	}
	if (fct_viewnoise_write(&acc, out, *level, o->voxel / 20, seen, &err))
		fct_die_err(&err);
	fct_viewnoise_free(&acc);
	return 0;
}
