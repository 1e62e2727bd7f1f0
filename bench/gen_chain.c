/* gen_chain - a labelled mesh for simpchain: a pinhole view of mkscene's
 * room (scene.h) with Kinect-class depth noise, meshed as dm2mesh does
 * (depthmesh.h) in the world frame, every face labelled with the true patch
 * of the majority of its corners' pixels (the first corner's when all
 * differ; -1 on the curved surfaces), the room's exact planes as the plane
 * element: what segplanes would write if it were perfect.
 *
 *   gen_chain [-k kinect_a] [-s WxH] [-v view] > labelled.ply
 *
 * -k: sigma = a z^2 (default 0.0015; 0: no noise); -s: image size (default
 * 640x480, focal length 525 scaled with the width); -v: view 0..3 of 4
 * (default: the single default view). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/camera.h"
#include "depth/depthmesh.h"
#include "io/header.h"
#include "io/meshio.h"
#include "geom/planes.h"
#include "scene/scene.h"

static void die(const struct fct_err *err)
{
	fprintf(stderr, "gen_chain: %s\n", err->msg);
	exit(1);
}

int main(int argc, char **argv)
{
	double kinect = 0.0015;
	int w = 640, h = 480, view = -1;
	for (int i = 1; i + 1 < argc; i += 2) {
		if (!strcmp(argv[i], "-k"))
			kinect = atof(argv[i + 1]);
		else if (!strcmp(argv[i], "-s") && sscanf(argv[i + 1], "%dx%d", &w, &h) == 2)
			;
		else if (!strcmp(argv[i], "-v"))
			view = atoi(argv[i + 1]);
		else {
			fprintf(stderr, "usage: gen_chain [-k kinect_a] [-s WxH] [-v view]\n");
			return 2;
		}
	}
	if (w < 8 || h < 8 || w > 8192 || h > 8192) {
		fprintf(stderr, "gen_chain: -s: size out of range\n");
		return 2;
	}
	struct fct_err err;
	struct fct_scene s;
	if (fct_scene_build(&s, "room", &err))
		die(&err);
	double f = 525.0 * w / 640;
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, w, h, f, f, 0.5 * (w - 1), 0.5 * (h - 1), 0, 0 };
	double pose[12];
	if (view < 0)
		fct_scene_view_pose(&s, 0, 1, pose);
	else
		fct_scene_view_pose(&s, view % 4, 4, pose);
	struct fct_render r;
	if (fct_scene_render(&s, &cam, pose, &r, &err))
		die(&err);
	size_t npx = (size_t)w * (size_t)h;
	struct fct_scene_noise nz = { 0, kinect, 0, 0, 90, 0, 0 , {0}};
	double *noisy = malloc(npx * sizeof *noisy);
	struct fct_image img;
	if (!noisy || fct_image_alloc(&img, w, h, 1, FCT_PIX_F32, &err))
		return 1;
	fct_depth_noise(&nz, 1, 0, r.depth, NULL, r.cosine, noisy, npx, NULL);
	for (size_t i = 0; i < npx; i++)
		((float *)img.data)[i] = (float)noisy[i];
	free(noisy);
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	struct fct_mesh m;
	if (fct_depth_mesh(&m, &img, &cam, &dp, NULL, &err))
		die(&err);
	fct_image_free(&img);
	for (size_t v = 0; v < m.nv; v++)
		fct_pose_apply(pose, m.xyz + 3 * v, m.xyz + 3 * v);

	int32_t *truth, *lab = malloc((m.nf ? m.nf : 1) * sizeof *lab);
	int present;
	if (!lab || fct_patches_get(&s.mesh, &truth, &present, -1, &err))
		return 1;
	const struct fct_prop *ps = fct_elem_find(&m.vertex, "s"), *pt = fct_elem_find(&m.vertex, "t");
	for (size_t fi = 0; fi < m.nf; fi++) {
		int32_t l[3];
		for (int k = 0; k < 3; k++) {
			uint32_t v = m.fvert[m.fstart[fi] + (uint32_t)k];
			long u = lround(fct_prop_get(ps, v) * w - 0.5), y = lround((1 - fct_prop_get(pt, v)) * h - 0.5);
			int32_t face = r.face[(size_t)y * (size_t)w + (size_t)u];
			l[k] = face < 0 ? -1 : truth[face];
		}
		lab[fi] = l[1] == l[2] ? l[1] : l[0];
	}
	free(truth);
	fct_render_free(&r);
	struct fct_plane *pl;
	size_t npl;
	if (fct_patches_set(&m, lab, &err) || fct_planes_get(&s.mesh, &pl, &npl, &err) ||
	    fct_planes_set(&m, pl, npl, &err) || fct_header_set_camera(&m, &cam, &err) ||
	    fct_header_set_pose(&m, pose, &err) || fct_mesh_write_file(&m, "-", 0, &err))
		die(&err);
	free(lab);
	free(pl);
	fct_scene_free(&s);
	fct_mesh_free(&m);
	return 0;
}
