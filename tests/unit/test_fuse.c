/* test_fuse.c - true signed distances of a hand-made view, the same view
 * twice, border voxels, a range image's grid against the general raster,
 * a concave corner,
 * the band's last layer, a plane across the axes, projective fusion of a
 * depth image against its mesh, slivers, a view too far out for the voxel
 * size, the .conf quaternion, and carving marks; a depth image's view by
 * its pixels' planes (fuseplane.c): its step, exact distances to a tilted
 * plane at steps 1 and 2, its borders, noise, any thread count. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "depth/depthsmooth.h"
#include "io/noise.h"
#include "depth/depthmesh.h"
#include "fusion/fuse.h"
#include "geom/geom.h"
#include "fusion/mcubes.h"
#include "depth/rangegrid.h"
#include "square.h"

/* v seeing the 64 x 64 depth image depth(x, y) of view_of's camera,
 * meshed into m as dm2mesh meshes it; with kept, a malloc'd copy of the
 * image holding the pixels of the mesh's vertices only (tsdfuse's
 * v->depth). */
static void depth_view_kept(struct fct_fuse_view *v, struct fct_mesh *m, float (*depth)(int x, int y),
                            float **kept)
{
	struct fct_err err;
	struct fct_image img;
	CHECK(fct_image_alloc(&img, 64, 64, 1, FCT_PIX_F32, &err) == 0);
	float *d = img.data;
	for (int y = 0; y < 64; y++)
		for (int x = 0; x < 64; x++)
			d[y * 64 + x] = depth(x, y);
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	dp.texcoords = 0;
	view_of(v, m);
	CHECK(fct_depth_mesh_kept(m, &img, &v->cam, &dp, NULL, kept, &err) == 0);
	fct_image_free(&img);
}

static void depth_view(struct fct_fuse_view *v, struct fct_mesh *m, float (*depth)(int x, int y))
{
	depth_view_kept(v, m, depth, NULL);
}

/* The pose of the depth-image tests: turned 30 degrees about y and moved. */
static void turned_pose(double pose[12])
{
	double a = M_PI / 6, c = cos(a), sn = sin(a);
	const double t[12] = { c, 0, sn, 0.1, 0, 1, 0, -0.05, -sn, 0, c, 0.2 };
	memcpy(pose, t, sizeof t);
}

/* depth_view_kept with the camera at pose, the mesh moved with it. */
static void posed_depth_view(struct fct_fuse_view *v, struct fct_mesh *m, float (*depth)(int x, int y),
                             const double pose[12], float **kept)
{
	depth_view_kept(v, m, depth, kept);
	for (size_t i = 0; i < m->nv; i++)
		fct_pose_apply(pose, &m->xyz[3 * i], &m->xyz[3 * i]);
	memcpy(v->pose, pose, sizeof v->pose);
}

/* A fresh volume of voxels of vox metres (fused: 1 cm) with v fused into
 * it: a band of band metres (3 cm in most tests), constant weights. */
static struct fct_voxgrid *fused_at(const struct fct_fuse_view *v, double vox, double band,
                                    struct fct_fuse_stats *st)
{
	struct fct_err err;
	struct fct_voxgrid *g = fct_voxgrid_new(vox, 0, &err);
	struct fct_fuse_params p = { band, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 0 };
	CHECK(g && fct_fuse_view(g, v, &p, st, &err) == 0);
	return g;
}

static struct fct_voxgrid *fused(const struct fct_fuse_view *v, double band, struct fct_fuse_stats *st)
{
	return fused_at(v, 0.01, band, st);
}

static void test_plane(void)
{
	struct fct_err err;
	struct fct_mesh m;
	square(&m, 40, 0.503);
	struct fct_fuse_view v;
	view_of(&v, &m);
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 0 };
	struct fct_fuse_stats st = { 0 };
	CHECK(fct_fuse_view(g, &v, &p, &st, &err) == 0);
	/* Voxel (0, 0, k) is at z = 0.01 k: sdf = 0.503 - z in front (free
	 * space towards the camera is positive), within the band only. */
	float s, w;
	for (int k = 48; k <= 53; k++) {
		CHECK(fct_voxgrid_get(g, 0, 0, k, &s, &w));
		CHECK_NEAR(s, 0.503 - 0.01 * k, 1e-6);
		CHECK_NEAR(w, 1, 0);
	}
	CHECK(fct_voxgrid_get(g, 0, 0, 54, &s, &w) == 0 || w == 0);
	/* Beyond the square's border (x > 1) nothing is written. */
	CHECK(fct_voxgrid_get(g, 102, 0, 50, &s, &w) == 0 || w == 0);
	CHECK(st.border > 0);
	/* The same view again: distances unchanged, weight 2. */
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	CHECK(fct_voxgrid_get(g, 3, -7, 52, &s, &w));
	CHECK_NEAR(s, 0.503 - 0.52, 1e-6);
	CHECK_NEAR(w, 2, 0);
	/* Marching cubes puts the surface back at z = 0.503. */
	struct fct_mesh out;
	CHECK(fct_mcubes(&out, g, 0, NULL, NULL, &err) == 0);
	CHECK(out.nv > 100);
	double worst = 0;
	for (size_t i = 0; i < out.nv; i++)
		worst = fmax(worst, fabs(out.xyz[3 * i + 2] - 0.503));
	CHECK_NEAR(worst, 0, 1e-6);
	fct_mesh_free(&out);
	/* Curvature flow leaves a plane where it is. */
	CHECK(fct_curvature_flow(g, 10, 0.03, &err) == 0);
	CHECK(fct_voxgrid_get(g, 3, -7, 52, &s, &w));
	CHECK_NEAR(s, 0.503 - 0.52, 1e-6);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* A view with per-vertex sigma: true distance weighs each voxel by
 * 1 / (1 + (2 s / voxel)^2), s the mean of its nearest triangle's
 * corners, and two views of the same square with different noise
 * average their distances by those weights (fuse.h); projective fusion
 * ignores sigma. */
static void test_sigma_weight(void)
{
	struct fct_err err;
	struct fct_mesh near, far;
	square(&near, 40, 0.503);
	square(&far, 40, 0.513);
	float sn[41 * 41], sf[41 * 41];
	for (int i = 0; i < 41 * 41; i++)
		sn[i] = 0.002f, sf[i] = 0.01f;
	struct fct_fuse_view v;
	view_of(&v, &near);
	v.sigma = sn;
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 0 };
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	float s, w;
	double wn = 1 / (1 + (2 * 0.002 / 0.01) * (2 * 0.002 / 0.01)), wf = 1 / (1 + 2.0 * 2.0);
	CHECK(fct_voxgrid_get(g, 3, -7, 51, &s, &w));
	CHECK_NEAR(s, 0.503 - 0.51, 1e-6);
	CHECK_NEAR(w, wn, 1e-6);   /* 0.862 */
	/* The far square, five times noisier, weighs 0.2: the voxel's
	 * distance moves a fifth of the way (weights 0.862 and 0.2). */
	view_of(&v, &far);
	v.sigma = sf;
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	CHECK(fct_voxgrid_get(g, 3, -7, 51, &s, &w));
	CHECK_NEAR(w, wn + wf, 1e-6);
	CHECK_NEAR(s, (wn * (0.503 - 0.51) + wf * (0.513 - 0.51)) / (wn + wf), 1e-6);
	fct_voxgrid_free(g);
	/* Projective: the baseline weighs 1 whatever the noise. */
	g = fct_voxgrid_new(0.01, 0, &err);
	p.projective = 1;
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	CHECK(fct_voxgrid_get(g, 3, -7, 51, &s, &w));
	CHECK_NEAR(w, 1, 0);
	fct_voxgrid_free(g);
	fct_mesh_free(&near);
	fct_mesh_free(&far);
}

/* Voxel l of block vb: its indices. */
static void voxel_index(const struct fct_voxblock *vb, int l, int32_t ijk[3])
{
	ijk[0] = vb->bx * 8 + l % 8, ijk[1] = vb->by * 8 + l / 8 % 8, ijk[2] = vb->bz * 8 + l / 64;
}

/* Voxel ijk of a 1 cm grid in the camera of the view at pose (inv: its
 * inverse, fct_pose_invert). */
static void voxel_in_camera(const double inv[12], const int32_t ijk[3], double c[3])
{
	double x[3] = { 0.01 * ijk[0], 0.01 * ijk[1], 0.01 * ijk[2] };
	fct_pose_apply(inv, x, c);
}

/* The voxels of g with a value, one by one: start from { 0, -1 }; each
 * call moves to the next one (its block, place and indices), 0 after the
 * last. */
struct written {
	size_t b;
	int l;
	const struct fct_voxblock *vb;
	int32_t ijk[3];
};

static int next_written(const struct fct_voxgrid *g, struct written *w)
{
	for (; w->b < fct_voxgrid_count(g); w->b++, w->l = -1) {
		w->vb = fct_voxgrid_at(g, w->b);
		while (++w->l < FCT_VOXBLOCK_N)
			if (w->vb->weight[w->l] > 0) {
				voxel_index(w->vb, w->l, w->ijk);
				return 1;
			}
	}
	return 0;
}

/* Voxels with a value in g: their count, and the largest difference of
 * distance from h's (which must have them too, else *missing counts). */
static size_t compare_grids(const struct fct_voxgrid *g, const struct fct_voxgrid *h, double *worst,
                            size_t *missing)
{
	size_t n = 0;
	*worst = 0, *missing = 0;
	for (struct written v = { 0, -1, NULL, { 0 } }; next_written(g, &v); n++) {
		float s, w;
		if (!fct_voxgrid_get(h, v.ijk[0], v.ijk[1], v.ijk[2], &s, &w) || !(w > 0))
			(*missing)++;
		else
			*worst = fmax(*worst, fabs((double)s - v.vb->sdf[v.l]));
	}
	return n;
}

/* A depth image meshed as dm2mesh does is a pixel grid, searched through
 * its cells; the same mesh with one triangle that is not (behind the
 * camera, never seen) goes through the general raster.  Both give the
 * distances of the scene: a plane at depth 0.5 on the left half of the
 * image, a step back to 0.8 on the right (a silhouette). */
static float step_depth(int x, int y)
{
	(void)y;
	return x < 32 ? 0.5f : 0.8f;
}

static void test_grid(void)
{
	struct fct_err err;
	struct fct_fuse_view v;
	struct fct_mesh m, m2;
	depth_view(&v, &m, step_depth);
	CHECK(m.nf > 3000);
	fct_mesh_init(&m2);
	for (size_t i = 0; i < m.nv; i++)
		fct_mesh_add_vertex(&m2, m.xyz[3 * i], m.xyz[3 * i + 1], m.xyz[3 * i + 2], &err);
	for (size_t f = 0; f < m.nf; f++)
		fct_mesh_add_face(&m2, &m.fvert[m.fstart[f]], 3, &err);
	uint32_t behind[3] = { (uint32_t)m2.nv, (uint32_t)m2.nv + 1, (uint32_t)m2.nv + 2 };
	fct_mesh_add_vertex(&m2, 0, 0, -1, &err);
	fct_mesh_add_vertex(&m2, 0.1, 0, -1, &err);
	fct_mesh_add_vertex(&m2, 0, 0.1, -1, &err);
	fct_mesh_add_face(&m2, behind, 3, &err);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 0 };
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err), *h = fct_voxgrid_new(0.01, 0, &err);
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	v.mesh = &m2;
	CHECK(fct_fuse_view(h, &v, &p, NULL, &err) == 0);
	/* On the axis of the near plane (x = -0.1): 0.5 - z within the band. */
	float s, w;
	for (int k = 48; k <= 52; k++) {
		CHECK(fct_voxgrid_get(g, -10, 0, k, &s, &w));
		CHECK_NEAR(s, 0.5 - 0.01 * k, 1e-6);
	}
	/* Beside the step, in front of the far plane and 2 cm right of the
	 * near plane's edge (x = 0): nearer that edge than the plane behind. */
	CHECK(fct_voxgrid_get(g, 2, 0, 78, &s, &w));
	CHECK(w > 0 && fabs(s) < 0.03 && s > 0);
	double worst;
	size_t missing, n = compare_grids(g, h, &worst, &missing);
	CHECK(n > 10000);
	CHECK_NEAR(worst, 0, 1e-5);
	/* Just out of the view, where the band's edge meets the frustum's:
	 * a voxel whose sample is off the image is searched from the nearest
	 * pixel's cell, a pixel away at most, but from the raster's sample
	 * half a pixel away at most. */
	CHECK_MSG(missing < n / 100, "%zu of %zu voxels not in the raster's", missing, n);
	compare_grids(h, g, &worst, &missing);
	CHECK_NEAR(worst, 0, 1e-5);
	CHECK_MSG(missing < n / 100, "%zu of %zu voxels not in the grid's", missing, n);
	fct_voxgrid_free(g);
	fct_voxgrid_free(h);
	fct_mesh_free(&m);
	fct_mesh_free(&m2);
}

/* A concave corner: a wall at depth 0.8 and a floor at y = 0.2 below it,
 * which view_of's camera sees from image row 40 down (a strip between
 * rows 39 and 40 joins them).  The mesh is the extrusion along x of the
 * polyline of a column's vertices in (y, z), so the true distance is the
 * distance to that polyline.  Voxels whose rays meet the wall but which
 * are out of its band and within the band of the floor or the strip have
 * the distance to those: the search from the wall gives up, the probes
 * beside in the image find them.  Voxels out of every band stay out.  A
 * 5 cm band: the camera's pixels are 2.5 cm at the wall. */
static float corner_depth(int x, int y)
{
	(void)x;
	return y > 39.5 ? (float)(0.2 * 32 / (y - 31.5)) : 0.8f;
}

static double corner_distance(double y, double z)
{
	double best = INFINITY;
	for (int r = 0; r + 1 < 64; r++) {
		double z0 = corner_depth(0, r), z1 = corner_depth(0, r + 1);
		double y0 = (r - 31.5) / 32 * z0, y1 = (r - 30.5) / 32 * z1;
		double dy = y1 - y0, dz = z1 - z0;
		double t = ((y - y0) * dy + (z - z0) * dz) / (dy * dy + dz * dz);
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		best = fmin(best, hypot(y - y0 - t * dy, z - z0 - t * dz));
	}
	return best;
}

static void test_corner(void)
{
	struct fct_fuse_view v;
	struct fct_mesh m;
	depth_view(&v, &m, corner_depth);
	double band = 0.05, worst = 0;
	struct fct_voxgrid *g = fused(&v, band, NULL);
	size_t probed = 0, wrong = 0;
	for (int k = 60; k <= 79; k++)
		for (int j = 10; j <= 25; j++) {
			double y = 0.01 * j, z = 0.01 * k, d = corner_distance(y, z);
			if (!(31.5 + 32 * y / z < 38.9 && 0.8 - z > band + 1e-3))
				continue;   /* the ray meets the wall out of its band */
			for (int i = -10; i <= 10; i += 5) {
				float s, w;
				int got = fct_voxgrid_get(g, i, j, k, &s, &w) && w > 0;
				if (d < band - 1e-3) {
					probed++;
					if (!got)
						wrong++;
					else
						worst = fmax(worst, fabs(s - d));
				} else if (d > band + 1e-3 && got) {
					wrong++;
				}
			}
		}
	CHECK_MSG(probed >= 20, "%zu voxels for the probes", probed);
	CHECK_MSG(wrong == 0, "%zu voxels wrongly in or out of the band", wrong);
	CHECK_NEAR(worst, 0, 1e-5);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* A plane a hair in front of a voxel layer: the layers at band distance
 * stay in (the search compares the squared distance as a float, so the
 * one 0.0300000001 away is in the band; the candidate boxes keep a little
 * more than the band for that), the next ones are not written. */
static void test_band_edge(void)
{
	struct fct_mesh m;
	square(&m, 60, 0.5 - 1e-10);   /* 3.3 cm triangles: their boxes, no samples */
	struct fct_fuse_view v;
	view_of(&v, &m);
	struct fct_voxgrid *g = fused(&v, 0.03, NULL);
	float s, w;
	for (int j = -30; j <= 30; j += 10)
		for (int k = 46; k <= 54; k++) {
			int got = fct_voxgrid_get(g, 7, j, k, &s, &w) && w > 0;
			CHECK_MSG(got == (k >= 47 && k <= 53), "voxel (7, %d, %d): %s", j, k, got ? "written" : "not written");
			if (got)
				CHECK_NEAR(s, 0.5 - 0.01 * k, 1e-6);
		}
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* A plane across all three axes, z = 0.5 + 0.3 x + 0.2 y, meshed from its
 * depth image: inside the view every voxel within the band of it has its
 * distance, none beyond does (the candidates keep to a slab around each
 * block's points, and must not lose a voxel of the band to it). */
static float tilted_depth(int x, int y)
{
	return (float)(0.5 / (1 - 0.3 * (x - 31.5) / 32 - 0.2 * (y - 31.5) / 32));
}

/* The voxels (i, j, k) of g (voxels of vox metres), i and j within r of 0
 * and k in k0 .. k1, against tilted_depth's plane seen by view_of's camera
 * at the pose whose inverse is inv: those whose foot on the plane and whose
 * projection lie between pixels lo and hi along both axes, within the band
 * (inside; worse: not written) or beyond it (worse: written), and the
 * largest error of those written. */
struct band_tally {
	size_t inside, worse;
	double worst;
};

static struct band_tally tilted_band(const struct fct_voxgrid *g, double vox, double band, const double inv[12],
                                     int r, int k0, int k1, double lo, double hi)
{
	struct band_tally t = { 0, 0, 0 };
	double norm = sqrt(1 + 0.09 + 0.04);
	for (int k = k0; k <= k1; k++)
		for (int j = -r; j <= r; j++)
			for (int i = -r; i <= r; i++) {
				double x[3] = { vox * i, vox * j, vox * k }, c[3];
				fct_pose_apply(inv, x, c);   /* in the camera's frame, where the plane is */
				double sdf = (0.5 - (c[2] - 0.3 * c[0] - 0.2 * c[1])) / norm;
				double f[3] = { c[0] + 0.3 * sdf / norm, c[1] + 0.2 * sdf / norm, c[2] - sdf / norm };
				double u = 32 * f[0] / f[2] + 31.5, w = 32 * f[1] / f[2] + 31.5;
				double pu = 32 * c[0] / c[2] + 31.5, pw = 32 * c[1] / c[2] + 31.5;
				if (!(c[2] > 0.1 && u > lo && u < hi && w > lo && w < hi && pu > lo && pu < hi && pw > lo &&
				      pw < hi))
					continue;
				float s, wt;
				int got = fct_voxgrid_get(g, i, j, k, &s, &wt) && wt > 0;
				if (fabs(sdf) < band - 1e-3) {
					t.inside++;
					if (!got)
						t.worse++;
					else
						t.worst = fmax(t.worst, fabs(s - sdf));
				} else if (fabs(sdf) > band + 1e-3 && got) {
					t.worse++;
				}
			}
	return t;
}

static void test_tilted_plane(void)
{
	struct fct_fuse_view v;
	struct fct_mesh m;
	depth_view(&v, &m, tilted_depth);
	double band = 0.03;
	const double identity[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
	struct fct_voxgrid *g = fused(&v, 0.03, NULL);
	/* Its foot on the plane, well inside the image. */
	struct band_tally t = tilted_band(g, 0.01, band, identity, 60, 20, 110, 6, 57);
	CHECK_MSG(t.inside > 20000, "%zu voxels inside the band", t.inside);
	CHECK_MSG(t.worse == 0, "%zu voxels wrongly in or out of the band", t.worse);
	CHECK_NEAR(t.worst, 0, 1e-5);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* Projective fusion of a view given as a depth image reads the image
 * itself: a plane at depth 0.5 seen by view_of's camera turned 30 degrees
 * about y and moved, every voxel written has 0.5 - its camera depth
 * (truncated at +band in front); and a tilted plane gives what the same
 * view gives as a mesh (the mesh's depths went through the pose and
 * back: a few float roundings) on the voxels both write.  The image's
 * candidates come from its pixel cells, which hold the mesh's triangles'
 * boxes, so it writes more voxels in front (truncated), and fewer only
 * where the mesh's triangles are over four voxels across (the far corner
 * of the tilted plane, at depth 1 m and 3 cm pixels: 13 voxels in front,
 * written through the triangles' insides alone; fuse.c, image_cells). */
static float flat_depth(int x, int y)
{
	(void)x, (void)y;
	return 0.5f;
}

static void test_projective_depth(void)
{
	struct fct_err err;
	double pose[12];
	turned_pose(pose);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 1, 0, { 0 }, { 0 }, 0 };
	for (int tilted = 0; tilted < 2; tilted++) {
		struct fct_fuse_view v;
		struct fct_mesh m;
		float *kept;
		posed_depth_view(&v, &m, tilted ? tilted_depth : flat_depth, pose, &kept);
		CHECK_INT(m.nv, 64 * 64);   /* every pixel a vertex */
		struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err), *h = fct_voxgrid_new(0.01, 0, &err);
		struct fct_fuse_stats sg = { 0 }, sh = { 0 };
		CHECK(fct_fuse_view(g, &v, &p, &sg, &err) == 0);   /* the mesh, rasterised */
		v.depth = kept;
		CHECK(fct_fuse_view(h, &v, &p, &sh, &err) == 0);   /* the image */
		double worst;
		size_t missing, n = compare_grids(g, h, &worst, &missing);
		CHECK_MSG(n > 20000, "%zu voxels", n);
		CHECK_INT(missing, tilted ? 13 : 0);
		CHECK_NEAR(worst, 0, 1e-6);
		compare_grids(h, g, &worst, &missing);
		CHECK_INT(sh.voxels, sg.voxels - (tilted ? 13 : 0) + missing);
		CHECK_INT(missing, tilted ? 907 : 0);
		if (!tilted) {
			/* A voxel at depth z in the camera: its sdf 0.5 - z. */
			double inv[12];
			fct_pose_invert(pose, inv);
			size_t bad = 0;
			double err_max = 0;
			for (struct written v = { 0, -1, NULL, { 0 } }; next_written(h, &v);) {
				double c[3];
				voxel_in_camera(inv, v.ijk, c);
				double z = c[2];
				double want = fmin(0.5 - z, 0.03);
				bad += !(0.5 - z >= -0.03 - 1e-9) || v.vb->weight[v.l] != 1;
				err_max = fmax(err_max, fabs(v.vb->sdf[v.l] - want));
			}
			CHECK_INT(bad, 0);
			CHECK_NEAR(err_max, 0, 1e-6);
		}
		fct_voxgrid_free(g);
		fct_voxgrid_free(h);
		fct_mesh_free(&m);
		free(kept);
	}
	/* An orthographic view has no depth image. */
	struct fct_fuse_view v;
	struct fct_mesh m;
	square(&m, 4, 0.5);
	view_of(&v, &m);
	float img[64 * 64] = { 0 };
	v.cam.kind = FCT_CAMERA_NONE;
	v.ortho_step = 0.01;
	v.depth = img;
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err);
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == -1);
	CHECK_MSG(strcmp(err.msg, "a depth image needs a camera with its size") == 0, "%s", err.msg);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* m's vertices in another order: new vertex k is old vertex order[k]. */
static void reorder_vertices(struct fct_mesh *m, const uint32_t *order)
{
	double *xyz = malloc(3 * m->nv * sizeof *xyz);
	uint32_t *new_of = malloc(m->nv * sizeof *new_of);
	CHECK(xyz && new_of);
	for (size_t k = 0; k < m->nv; k++) {
		memcpy(&xyz[3 * k], &m->xyz[3 * (size_t)order[k]], 3 * sizeof *xyz);
		new_of[order[k]] = (uint32_t)k;
	}
	memcpy(m->xyz, xyz, 3 * m->nv * sizeof *xyz);
	for (size_t i = 0; i < m->fstart[m->nf]; i++)
		m->fvert[i] = new_of[m->fvert[i]];
	free(xyz);
	free(new_of);
}

/* A depth image whose mesh has a vertex per pixel with data but not in the
 * image's order is not taken for its pixel grid: the voxels written are
 * the mesh's own, as rasterised (for this flat view the image path writes
 * the same voxels and values).  Rows 0, 32, 1, 33, ... make cells of
 * points 32 rows apart, whose boxes are too large to add: taken for the
 * grid, the view would lose the candidates of its cells across blocks. */
static void test_projective_order(void)
{
	struct fct_err err;
	double pose[12];
	turned_pose(pose);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 1, 0, { 0 }, { 0 }, 0 };
	struct fct_fuse_view v;
	struct fct_mesh m;
	float *kept;
	posed_depth_view(&v, &m, flat_depth, pose, &kept);
	CHECK_INT(m.nv, 64 * 64);
	uint32_t order[64 * 64];
	for (uint32_t k = 0; k < 64 * 64; k++)
		order[k] = (k / 64 % 2 ? 32 + k / 128 : k / 128) * 64 + k % 64;
	reorder_vertices(&m, order);
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err), *h = fct_voxgrid_new(0.01, 0, &err);
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == 0);   /* the mesh, rasterised */
	v.depth = kept;
	CHECK(fct_fuse_view(h, &v, &p, NULL, &err) == 0);   /* the image, candidates from the mesh */
	double worst;
	size_t missing, n = compare_grids(g, h, &worst, &missing);
	CHECK_MSG(n > 20000, "%zu voxels", n);
	CHECK_INT(missing, 0);
	CHECK_NEAR(worst, 0, 1e-6);
	CHECK_INT(compare_grids(h, g, &worst, &missing), n);
	CHECK_INT(missing, 0);
	fct_voxgrid_free(g);
	fct_voxgrid_free(h);
	fct_mesh_free(&m);
	free(kept);
}

/* The candidates of a depth image reach the band: for a tilted plane and
 * a step edge (turned and moved as in test_projective_depth), every voxel
 * within the band's three voxels along each axis of a pixel's point, or of
 * the centre of a pixel cell of the plane (one to four voxels across), that
 * its own pixel sees (data there, the voxel at most the band behind it) is
 * written, and every voxel written is one its pixel sees, with the depth
 * difference truncated at +band. */
static size_t reach(float (*depth)(int x, int y), const double pose[12], int cells, size_t *bad)
{
	struct fct_err err;
	struct fct_fuse_view v;
	struct fct_mesh m;
	float *kept;
	posed_depth_view(&v, &m, depth, pose, &kept);
	v.depth = kept;
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err);
	struct fct_fuse_params p = { 0.03, FCT_FUSE_CONSTANT, 1, 0, { 0 }, { 0 }, 0 };
	CHECK(g && fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	double inv[12];
	fct_pose_invert(pose, inv);
	size_t reached = 0;
	*bad = 0;
	/* The points: pixels with data, and centres of the cells whose four
	 * corners have data and lie one to four voxels apart. */
	for (int y = 0; y < 64; y++)
		for (int x = 0; x < 64; x++) {
			double pts[2][3];
			int np = 0;
			if (kept[y * 64 + x] > 0) {
				double d = kept[y * 64 + x], c[3] = { d * (x - 31.5) / 32, d * (y - 31.5) / 32, d };
				fct_pose_apply(pose, c, pts[np++]);
			}
			if (cells && x < 63 && y < 63) {
				double q[4][3], lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { -1e9, -1e9, -1e9 }, e = 0;
				int all = 1;
				for (int n = 0; n < 4; n++) {
					int u = x + n % 2, w = y + n / 2;
					double d = kept[w * 64 + u], c[3] = { d * (u - 31.5) / 32, d * (w - 31.5) / 32, d };
					all &= d > 0;
					fct_pose_apply(pose, c, q[n]);
					for (int a = 0; a < 3; a++)
						lo[a] = fmin(lo[a], q[n][a]), hi[a] = fmax(hi[a], q[n][a]);
				}
				for (int a = 0; a < 3; a++)
					e = fmax(e, hi[a] - lo[a]);
				if (all && e > 0.01 * (1 + 1e-6) && e < 0.04 * (1 - 1e-6)) {
					for (int a = 0; a < 3; a++)
						pts[np][a] = (q[0][a] + q[1][a] + q[2][a] + q[3][a]) / 4;
					np++;
				}
			}
			for (int n = 0; n < np; n++) {
				int32_t lo[3], hi[3];
				for (int a = 0; a < 3; a++)
					lo[a] = (int32_t)ceil(pts[n][a] / 0.01 - 3), hi[a] = (int32_t)floor(pts[n][a] / 0.01 + 3);
				for (int32_t k = lo[2]; k <= hi[2]; k++)
					for (int32_t j = lo[1]; j <= hi[1]; j++)
						for (int32_t i = lo[0]; i <= hi[0]; i++) {
							int32_t ijk[3] = { i, j, k };
							double c[3];
							voxel_in_camera(inv, ijk, c);
							double u = 32 * c[0] / c[2] + 31.5, w = 32 * c[1] / c[2] + 31.5;
							double fu = floor(u + 0.5), fw = floor(w + 0.5);
							if (!(c[2] > 0) || fabs(u + 0.5 - fu) < 1e-6 || fabs(w + 0.5 - fw) < 1e-6 ||
							    fu < 0 || fw < 0 || fu > 63 || fw > 63)
								continue;
							double R = kept[(int)fw * 64 + (int)fu];
							if (!(R > 0) || fabs(R - c[2] + 0.03) < 1e-6 || R - c[2] < -0.03)
								continue;
							float sdf, wt;
							reached++;
							if (!fct_voxgrid_get(g, i, j, k, &sdf, &wt) || wt != 1 ||
							    fabs(sdf - fmin(R - c[2], 0.03)) > 1e-6)
								(*bad)++;
						}
			}
		}
	/* Every voxel written is seen by its pixel, with its distance. */
	for (struct written v = { 0, -1, NULL, { 0 } }; next_written(g, &v);) {
		double c[3];
		voxel_in_camera(inv, v.ijk, c);
		double u = floor(32 * c[0] / c[2] + 32), w = floor(32 * c[1] / c[2] + 32);
		double R = u >= 0 && w >= 0 && u < 64 && w < 64 ? kept[(int)w * 64 + (int)u] : 0;
		if (!(R > 0) || R - c[2] < -0.03 - 1e-6 || fabs(v.vb->sdf[v.l] - fmin(R - c[2], 0.03)) > 1e-6)
			(*bad)++;
	}
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
	free(kept);
	return reached;
}

static void test_projective_reach(void)
{
	double pose[12];
	turned_pose(pose);
	size_t bad, n = reach(tilted_depth, pose, 1, &bad);
	CHECK_MSG(n > 100000, "%zu voxels reached", n);
	CHECK_INT(bad, 0);
	n = reach(step_depth, pose, 0, &bad);
	CHECK_MSG(n > 50000, "%zu voxels reached", n);
	CHECK_INT(bad, 0);
}

/* Triangles with (nearly) no area have no normal and are not counted:
 * a sliver 1e-14 wide (degenerate), and one 1e-6 wide (not), added to a
 * square of 32 triangles, well inside its box. */
static void test_sliver(void)
{
	struct fct_err err;
	struct fct_mesh m;
	square(&m, 4, 0.5);
	uint32_t v0 = (uint32_t)m.nv;
	fct_mesh_add_vertex(&m, 0, 0, 0.6, &err);
	fct_mesh_add_vertex(&m, 0.5, 0, 0.6, &err);
	fct_mesh_add_vertex(&m, 0.25, 1e-14, 0.6, &err);
	fct_mesh_add_vertex(&m, 0.25, 1e-6, 0.6, &err);
	uint32_t thin[3] = { v0, v0 + 1, v0 + 2 }, thick[3] = { v0, v0 + 1, v0 + 3 };
	fct_mesh_add_face(&m, thin, 3, &err);
	fct_mesh_add_face(&m, thick, 3, &err);
	CHECK(fct_triangle_degenerate(&m.xyz[3 * v0], &m.xyz[3 * (v0 + 1)], &m.xyz[3 * (v0 + 2)]));
	CHECK(!fct_triangle_degenerate(&m.xyz[3 * v0], &m.xyz[3 * (v0 + 1)], &m.xyz[3 * (v0 + 3)]));
	struct fct_fuse_view v;
	view_of(&v, &m);
	struct fct_fuse_stats st = { 0 };
	struct fct_voxgrid *g = fused(&v, 0.03, &st);
	CHECK_INT(st.faces, 33);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

/* A vertex too far out for the voxel size (its y and z beyond 2^23
 * voxels): the message names its first axis out, and the volume keeps
 * nothing of the view. */
static void test_too_far(void)
{
	struct fct_err err;
	struct fct_mesh m;
	square(&m, 4, 0.5);
	m.xyz[3 * 7 + 1] = 1e5;
	m.xyz[3 * 7 + 2] = 2e5;
	struct fct_fuse_view v;
	view_of(&v, &m);
	struct fct_voxgrid *g = fct_voxgrid_new(0.001, 0, &err);
	struct fct_fuse_params p = { 0.003, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 0 };
	CHECK(fct_fuse_view(g, &v, &p, NULL, &err) == -1);
	CHECK_MSG(strcmp(err.msg, "the view reaches 100000 m: too far from the origin for the voxel size") == 0,
	          "%s", err.msg);
	CHECK_INT(fct_voxgrid_count(g), 0);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

static void test_carve(void)
{
	struct fct_err err;
	struct fct_mesh m;
	square(&m, 40, 0.5);
	struct fct_fuse_view v;
	view_of(&v, &m);
	struct fct_voxgrid *g = fused(&v, 0.03, NULL);
	struct fct_range_image r;
	CHECK(fct_range_image_make(&r, &v, 1 << 20, &err) == 0);
	/* The centre pixel sees the square at depth 0.5. */
	CHECK_NEAR(r.range[32 * 64 + 32], 0.5, 1e-6);
	int32_t lo[3] = { -20, -20, 0 }, hi[3] = { 20, 20, 60 };
	size_t carved = 0;
	CHECK(fct_carve(g, &r, 1, lo, hi, 0.03, 1e-3f, &carved, &err) == 0);
	CHECK(carved > 1000);
	/* The voxel at z = 0.1 on the axis is empty space, not marked (all its
	 * neighbours are empty too); the marks sit at the frustum's edge. */
	float s, w;
	int got = fct_voxgrid_get(g, 0, 0, 10, &s, &w);
	CHECK_MSG(got == 0 || w == 0, "voxel (0, 0, 10): sdf %g weight %g", s, w);
	fct_range_image_free(&r);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
}

static void test_quat(void)
{
	double P[12];
	/* 90 degrees about z: x -> y. */
	fct_quat_pose(0, 0, sqrt(0.5), sqrt(0.5), P);
	CHECK_NEAR(P[0], 0, 1e-15);
	CHECK_NEAR(P[4], 1, 1e-15);
	CHECK_NEAR(P[1], -1, 1e-15);
	CHECK_NEAR(P[10], 1, 1e-15);
	struct fct_conf c;
	struct fct_err err;
	CHECK(fct_conf_read(&c, "/nonexistent/x.conf", &err) == -1);
}

/* The 64 x 64 float image of depth(x, y) (noise: Gaussian of that many
 * metres added, from a fixed seed). */
static void depth_image(struct fct_image *img, float (*depth)(int x, int y), double noise)
{
	struct fct_err err;
	struct fct_rng rng;
	fct_rng_seed(&rng, 7);
	CHECK(fct_image_alloc(img, 64, 64, 1, FCT_PIX_F32, &err) == 0);
	float *d = img->data;
	for (int y = 0; y < 64; y++)
		for (int x = 0; x < 64; x++)
			d[y * 64 + x] = (float)(depth(x, y) + noise * fct_rng_normal(&rng));
}

/* Depth parameters with a sensor noise of 1 cm at any depth (poly), at
 * least a tenth of the voxels these tests fuse into; exact data (none)
 * when exact; no model when exact is -1. */
static void depth_params(struct fct_depth_params *dp, int exact)
{
	struct fct_err err;
	fct_depth_params_default(dp);
	dp->texcoords = 0;
	if (exact >= 0)
		CHECK(fct_noise_parse(&dp->noise, exact ? "none" : "poly:0.01,0,0", &err) == 0);
}

/* v: the view of img through fct_fuse_depth_view (view_of's camera at
 * pose, no smoothing, depth_params) for true distance into voxels of vox
 * metres, its mesh in m. */
static void image_view(struct fct_fuse_view *v, struct fct_mesh *m, const struct fct_image *img,
                       const double pose[12], double vox, int exact)
{
	struct fct_err err;
	struct fct_depth_params dp;
	depth_params(&dp, exact);
	struct fct_depth_smooth sm = { 0, 2, 0 };
	struct fct_fuse_view cam;
	view_of(&cam, NULL);
	CHECK(fct_fuse_depth_view(v, m, NULL, img, &cam.cam, &dp, &sm, pose, vox, &err) == 0);
}

/* image_view of depth(x, y) (with noise, depth_image) seen from the
 * origin along +z, its planes checked for. */
static void front_view(struct fct_fuse_view *v, struct fct_mesh *m, struct fct_image *img,
                       float (*depth)(int x, int y), double noise, double vox)
{
	const double identity[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
	depth_image(img, depth, noise);
	image_view(v, m, img, identity, vox, 0);
	CHECK(v->planes);
}

static float at_half(int x, int y)
{
	(void)x, (void)y;
	return 0.5f;
}

/* The step of the view fct_fuse_depth_view makes of img for voxels of vox
 * with noise model `noise` (NULL: none; 1 when not by planes: every
 * pixel), and its planes and plane_mean. */
static int planned_step(const struct fct_image *img, const char *noise, double vox, int *planes, int *mean)
{
	struct fct_err err;
	struct fct_depth_params dp;
	depth_params(&dp, -1);
	if (noise)
		CHECK(fct_noise_parse(&dp.noise, noise, &err) == 0);
	struct fct_depth_smooth sm = { 0, 2, 0 };
	struct fct_fuse_view cam, v;
	view_of(&cam, NULL);
	struct fct_mesh m;
	const double identity[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
	CHECK(fct_fuse_depth_view(&v, &m, NULL, img, &cam.cam, &dp, &sm, identity, vox, &err) == 0);
	*planes = v.planes, *mean = v.plane_mean;
	fct_mesh_free(&m);
	return v.step;
}

/* The step a depth image is meshed at for true distance by its planes:
 * samples 0.6 voxels apart at the median depth, rounded, and 0 (every
 * pixel, the mesh searched) where its pixels are farther apart than that
 * or its noise is unknown (no model): view_of's focal length is 32, so at
 * 0.5 m a pixel is 1/64 m across; the planes through the mean of nine
 * samples where the noise is a tenth of a voxel or more (1 cm at 5 cm
 * voxels), else through the vertices (1 mm; none, exact data); voxels of
 * 0 (tsdfuse --exact): searched. */
static void test_depth_step(void)
{
	struct fct_err err;
	struct fct_image img;
	depth_image(&img, at_half, 0);
	struct fct_fuse_view cam;
	view_of(&cam, NULL);
	struct fct_depth_params dp;
	depth_params(&dp, 0);
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.01) == 0);    /* 0.38 pixels */
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.03) == 1);    /* 1.15 */
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.05) == 2);    /* 1.92 */
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.1) == 4);     /* 3.84 */
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0) == 0);
	CHECK(fct_noise_parse(&dp.noise, "poly:0.001,0,0", &err) == 0);
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.05) == 2);    /* noise a fiftieth */
	fct_depth_params_default(&dp);
	CHECK(fct_fuse_depth_step(&img, &cam.cam, &dp, 0.05) == 0);    /* no model */
	int planes, mean;
	CHECK(planned_step(&img, "poly:0.01,0,0", 0.05, &planes, &mean) == 2 && planes && mean);
	CHECK(planned_step(&img, "poly:0.001,0,0", 0.05, &planes, &mean) == 2 && planes && !mean);
	CHECK(planned_step(&img, "none", 0.05, &planes, &mean) == 2 && planes && !mean);
	CHECK(planned_step(&img, NULL, 0.05, &planes, &mean) == 1 && !planes && !mean);    /* every pixel */
	CHECK(planned_step(&img, "none", 0, &planes, &mean) == 1 && !planes && !mean);
	CHECK(planned_step(&img, "poly:0.01,0,0", 0.01, &planes, &mean) == 1 && !planes);   /* 0.38 pixels */
	struct fct_camera cyl = cam.cam;
	cyl.kind = FCT_CAMERA_CYLINDRICAL;
	CHECK(fct_fuse_depth_step(&img, &cyl, &dp, 0.1) == 0);
	fct_image_free(&img);
}

/* The tilted plane of test_tilted_plane as a depth image's view fused by
 * its planes, camera turned and moved (turned_pose), a band of 3 voxels:
 * every voxel within the band whose foot and projection are well inside
 * the image (off the far corner, where the jump test cuts cells at step 2
 * and a foot within half a sample of a border vertex is left alone) has
 * the plane's distance (the planes are exact on a plane:
 * their normals the triangles', their points means of points on it),
 * none beyond the band has a value; at 3 cm voxels (step 1) and 5 cm
 * (step 2), with the noise model (planes through the means of nine
 * samples) and declared exact (none: through the vertices); one thread or
 * two, the same volume. */
static void plane_field_case(double vox, int want_step, int threads, int exact)
{
	struct fct_err err;
	struct fct_image img;
	depth_image(&img, tilted_depth, 0);
	double pose[12], inv[12];
	turned_pose(pose);
	fct_pose_invert(pose, inv);
	struct fct_fuse_view v;
	struct fct_mesh m;
	image_view(&v, &m, &img, pose, vox, exact);
	CHECK(v.planes && v.step == want_step && v.plane_mean == !exact);
	double band = 3 * vox;
	struct fct_voxgrid *g = fct_voxgrid_new(vox, 0, &err);
	struct fct_fuse_params p = { band, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, threads };
	CHECK(g && fct_fuse_view(g, &v, &p, NULL, &err) == 0);
	int r = (int)(1.3 / vox);
	struct band_tally t = tilted_band(g, vox, band, inv, r, 0, r, 8, 48);
	CHECK_MSG(t.inside > 500, "%zu voxels inside the band", t.inside);
	CHECK_MSG(t.worse == 0, "%zu voxels wrongly in or out of the band", t.worse);
	CHECK_NEAR(t.worst, 0, 2e-6);
	if (threads == 1) {
		struct fct_voxgrid *h = fct_voxgrid_new(vox, 0, &err);
		p.threads = 2;
		CHECK(h && fct_fuse_view(h, &v, &p, NULL, &err) == 0);
		double worst;
		size_t missing, n = compare_grids(g, h, &worst, &missing);
		CHECK(n > 0 && missing == 0 && worst == 0);
		compare_grids(h, g, &worst, &missing);
		CHECK(missing == 0);
		fct_voxgrid_free(h);
	}
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
	fct_image_free(&img);
}

static void test_plane_field(void)
{
	plane_field_case(0.03, 1, 1, 0);
	plane_field_case(0.05, 2, 0, 0);
	plane_field_case(0.03, 1, 1, 1);
	plane_field_case(0.05, 2, 0, 1);
}

/* The step of step_depth (0.5 on the left half, 0.8 on the right) by its
 * planes at 5 cm voxels (step 1 at the median depth, 0.8): the near
 * plane's distances where its foot is inside the data; beyond the image
 * nothing, and voxels whose plane is on the data's border (the near
 * plane's edge) are left alone (counted), as the mesh search leaves those
 * whose nearest point is on a border. */
static void test_plane_border(void)
{
	struct fct_image img;
	struct fct_fuse_view v;
	struct fct_mesh m;
	front_view(&v, &m, &img, step_depth, 0, 0.05);
	struct fct_fuse_stats st = { 0 };
	struct fct_voxgrid *g = fused_at(&v, 0.05, 0.15, &st);
	float s, w;
	for (int k = 8; k <= 12; k++) {
		CHECK(fct_voxgrid_get(g, -2, 0, k, &s, &w) && w > 0);
		CHECK_NEAR(s, 0.5 - 0.05 * k, 1e-6);
	}
	CHECK(st.border > 0);
	/* Out past the image's left edge (x / z below -1): nothing. */
	CHECK(!fct_voxgrid_get(g, -18, 0, 10, &s, &w) || w == 0);
	fct_voxgrid_free(g);
	fct_mesh_free(&m);
	fct_image_free(&img);
}

/* A plane at 0.5 m under 3 mm of Gaussian noise per pixel at 3 cm voxels
 * (step 1, a band of 9 cm): the planes' distances (each through the mean
 * of nine samples) are nearer the true plane's than the search of the
 * noisy mesh for the nearest point, which follows the noise (measured:
 * 0.97 mm against 2.09 mean over the 1009 voxels both write). */
static void test_plane_noise(void)
{
	struct fct_image img;
	struct fct_fuse_view v;
	struct fct_mesh m;
	front_view(&v, &m, &img, at_half, 0.003, 0.03);
	struct fct_voxgrid *g = fused_at(&v, 0.03, 0.09, NULL);
	v.planes = 0;
	struct fct_voxgrid *h = fused_at(&v, 0.03, 0.09, NULL);
	double eg = 0, eh = 0;
	size_t n = 0;
	for (struct written a = { 0, -1, NULL, { 0 } }; next_written(g, &a);) {
		float s, w;
		if (abs(a.ijk[0]) > 6 || abs(a.ijk[1]) > 6 || !fct_voxgrid_get(h, a.ijk[0], a.ijk[1], a.ijk[2], &s, &w) ||
		    !(w > 0))
			continue;
		double truth = 0.5 - 0.03 * a.ijk[2];
		eg += fabs(a.vb->sdf[a.l] - truth), eh += fabs(s - truth), n++;
	}
	CHECK_MSG(n > 500, "%zu voxels both write", n);
	CHECK_MSG(eg < 0.8 * eh, "planes %.3g mm, mesh search %.3g mm", 1e3 * eg / (double)n, 1e3 * eh / (double)n);
	fct_voxgrid_free(g);
	fct_voxgrid_free(h);
	fct_mesh_free(&m);
	fct_image_free(&img);
}

/* A view to be fused by its planes whose mesh is no pixel grid (a vertex
 * moved off its pixel, as a library caller's mesh may be): its triangles'
 * normals are made after all and the mesh is searched, the same volume
 * as with the planes off. */
static void test_plane_no_grid(void)
{
	struct fct_image img;
	struct fct_fuse_view v;
	struct fct_mesh m;
	front_view(&v, &m, &img, at_half, 0.003, 0.03);
	m.xyz[3 * (m.nv / 2)] += 0.01;   /* 0.6 pixels at 0.5 m */
	struct fct_fuse_stats st = { 0 };
	struct fct_voxgrid *g = fused_at(&v, 0.03, 0.09, &st);
	CHECK(st.plane_views == 0 && st.faces == m.nf);
	v.planes = 0;
	struct fct_voxgrid *h = fused_at(&v, 0.03, 0.09, NULL);
	double worst;
	size_t missing, n = compare_grids(g, h, &worst, &missing);
	CHECK_MSG(n > 500 && missing == 0 && worst == 0, "%zu voxels, %zu missing, worst %g", n, missing, worst);
	compare_grids(h, g, &worst, &missing);
	CHECK(missing == 0);
	fct_voxgrid_free(g);
	fct_voxgrid_free(h);
	fct_mesh_free(&m);
	fct_image_free(&img);
}

int main(void)
{
	test_plane();
	test_sigma_weight();
	test_grid();
	test_corner();
	test_band_edge();
	test_tilted_plane();
	test_projective_depth();
	test_projective_reach();
	test_projective_order();
	test_sliver();
	test_too_far();
	test_carve();
	test_quat();
	test_depth_step();
	test_plane_field();
	test_plane_border();
	test_plane_noise();
	test_plane_no_grid();
	CHECK_DONE();
}
