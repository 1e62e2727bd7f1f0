/* fusedepth.c - a depth image made a view for fusion (fct_fuse_depth_view,
 * fuse.h): smoothed and meshed with the sensor's noise model, moved to the
 * world frame.  tsdfuse and roommodel read their depth images through it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "depth/depthmesh.h"
#include "depth/depthsmooth.h"
#include "fusion/fuse.h"

/* fct_fuse_depth_step, and in *mean whether the planes go through the
 * mean of nine samples (fct_fuse_view's plane_mean). */
static int depth_plan(const struct fct_image *img, const struct fct_camera *cam,
                      const struct fct_depth_params *dp, double vox, int *mean)
{
	*mean = 0;
	/* Noise unknown: the mesh as it is, searched; a sensor's noise the
	 * planes would average, or exact data (--noise none), is declared. */
	if (cam->kind != FCT_CAMERA_PINHOLE || !(vox > 0) || dp->noise.model == FCT_NOISE_UNKNOWN)
		return 0;
	double med = fct_depth_median(img, dp), f = cam->fx < cam->fy ? cam->fx : cam->fy;
	double s = 0.6 * vox * f / med;
	if (!(s >= 1))
		return 0;
	*mean = fct_noise_sigma(&dp->noise, med) >= vox / 10;
	return s >= 64 ? 64 : (int)floor(s + 0.5);
}

int fct_fuse_depth_step(const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *dp, double vox)
{
	int mean;
	return depth_plan(img, cam, dp, vox, &mean);
}

int fct_fuse_depth_view(struct fct_fuse_view *v, struct fct_mesh *mesh, float **depth,
                        const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *dp, const struct fct_depth_smooth *smooth,
                        const double pose[12], double vox, struct fct_err *err)
{
	memset(v, 0, sizeof *v);
	if (depth)
		*depth = NULL;
	/* With a noise model: smoothed in units of it, then meshed with it
	 * (the jump test's noise term and each vertex's sigma, which the
	 * fusion weighs by; depthsmooth.h, depthmesh.h). */
	struct fct_depth_params vp = *dp;
	fct_depth_noise_unit(&vp, img);
	int mean = 0, step = depth ? 0 : depth_plan(img, cam, &vp, vox, &mean);
	if (step)
		vp.step = step;
	struct fct_image sm;
	const struct fct_image *src = img;
	if (smooth->radius > 0 && vp.noise.model != FCT_NOISE_UNKNOWN) {
		if (fct_depth_smooth_image(&sm, img, cam, &vp, smooth, err))
			return -1;
		src = &sm;
	}
	int rc = fct_depth_mesh_kept(mesh, src, cam, &vp, NULL, depth, err);
	if (src == &sm)
		fct_image_free(&sm);
	if (rc)
		return -1;
	for (size_t i = 0; i < mesh->nv; i++)
		fct_pose_apply(pose, &mesh->xyz[3 * i], &mesh->xyz[3 * i]);
	v->mesh = mesh;
	v->cam = *cam;
	memcpy(v->pose, pose, sizeof v->pose);
	v->depth = depth ? *depth : NULL;
	v->step = vp.step;
	v->planes = step > 0;
	v->plane_mean = mean;
	struct fct_prop *sp = fct_elem_find(&mesh->vertex, "sigma");
	v->sigma = sp && sp->type == FCT_FLOAT32 ? sp->data : NULL;
	return 0;
}

int fct_range_image_depth(struct fct_range_image *r, const struct fct_image *img,
                          const struct fct_camera *cam, const struct fct_depth_params *dp,
                          const double pose[12], struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	if (cam->kind == FCT_CAMERA_NONE || cam->width != img->width || cam->height != img->height)
		return fct_fail(err, "a range image of a depth image needs its pinhole or cylindrical camera");
	r->view.cam = *cam;
	memcpy(r->view.pose, pose, sizeof r->view.pose);
	fct_pose_invert(pose, r->inv);
	r->width = img->width, r->height = img->height;
	if (!(r->range = fct_alloc_array((size_t)r->width * (size_t)r->height, sizeof *r->range, err)))
		return -1;
	for (int y = 0; y < r->height; y++)
		for (int x = 0; x < r->width; x++) {
			double z = fct_depth_at(img, x, y, dp);
			r->range[(size_t)y * (size_t)r->width + (size_t)x] = z > 0 && z < INFINITY ? (float)z : 0;
		}
	return 0;
}
