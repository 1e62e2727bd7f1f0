/* fuse.h - multi-view fusion of range-image meshes in a sparse volume:
 * Sun, Paik, Koschan and Abidi, "3D Reconstruction of Indoor and Outdoor
 * Scenes Using a Mobile Range Scanner", sec. 3.
 *
 * - Hilton's implicit surface: for each voxel x near a view's mesh, its
 *   nearest point p on that mesh and the normal n there give the signed
 *   distance (x - p) . n (not the projective depth difference of Curless
 *   and Levoy, offered as the baseline); views are combined by the
 *   confidence-weighted average.  Voxels whose nearest point lies on the
 *   mesh's border are left alone, so surfaces do not grow past the data.
 * - Space carving: a voxel outside every view's band (not in Q) that some
 *   view saw through (R_v < R_i along its pixel's ray) is empty; the
 *   boundary between empty and never-seen space closes the occlusion holes,
 *   giving watertight indoor models.  The range image R_i of each view is
 *   recovered by rasterising its own mesh into its own camera.
 * - A level-set mean-curvature flow on the volume removes small outlier
 *   blobs afterwards.
 *
 * The volume is voxgrid.h's sparse block grid (sdf positive in free
 * space); marching cubes (mcubes.h) extracts the surface. */
#ifndef FCT_FUSE_H
#define FCT_FUSE_H

#include <stddef.h>

#include "io/camera.h"
#include "core/mesh.h"
#include "fusion/voxgrid.h"

/* One view: its mesh in the world frame and where it was seen from.  The
 * sensor is cam (pinhole or cylindrical) at pose (camera-to-world), or,
 * when cam.kind is FCT_CAMERA_NONE, an orthographic range scanner looking
 * along -z of the frame pose (a range-grid scan) with pixels of ortho_step
 * metres.
 *
 * depth, for a view that came as a depth image (NULL otherwise): its
 * cam.width x cam.height depths in metres along the sensor (camera z for
 * pinholes, rho for cylinders), row by row; a pixel has data when its
 * depth is above 0 and finite.  Projective fusion reads it as the view's
 * range image instead of rasterising the mesh (as KinectFusion and Open3D
 * do); true distance and carving use the mesh alone.  depth should hold
 * the pixels of the mesh's vertices and no others (fct_depth_mesh_kept):
 * a pixel without mesh around it is written only where the candidate
 * voxels reach.  Those come from the mesh's vertices and, for a pinhole
 * whose mesh has one vertex per pixel with data in row-major order (as
 * fct_depth_mesh_kept makes it, at step 1; checked: each vertex on its
 * pixel's ray at its depth), from the image's pixel cells instead of the
 * mesh's triangles.  The result then holds every voxel the
 * mesh view writes, with its value but for the rounding of the vertices'
 * depths through the pose and back, and some more in front of the surface
 * (truncated at +band), except voxels written only through the inside of
 * triangles over four voxels across, which no pixel measured (fuse.c,
 * image_cells).
 *
 * sigma, for a view whose sensor noise is known (NULL otherwise): per
 * vertex of the mesh, the standard deviation of its position along its
 * ray in metres (depthmesh.h's vertex property sigma).  True distance
 * weighs each voxel's distance by 1 / (1 + (2 s / voxel)^2) besides the
 * view's weight, s the mean sigma of the corners of the triangle nearest
 * it: inverse-variance weights, the sensor's variance plus (voxel / 2)^2
 * (what the volume resolves anyway) over the latter, so that data far
 * more precise than the voxels weigh 1 and a noisy far wall weighs less
 * than a near view of it.  Projective fusion, the baseline, ignores it.
 *
 * step: for a pinhole's depth image meshed every step pixels (0 or 1:
 * every pixel), the mesh's vertices on pixels (k step, l step) of the
 * image; true distance finds its grid at that step.  planes: for a view
 * that came as a depth image (fct_fuse_depth_view), true distance measures
 * to the tangent planes of its grid's vertices instead of searching the
 * mesh for each voxel's nearest point (fuseplane.c): a pinhole's view
 * whose mesh is a grid; others are searched.  plane_mean: those planes go
 * through the mean of the nine samples about each vertex, which averages
 * the sensor's noise; else through the vertex. */
struct fct_fuse_view {
	const struct fct_mesh *mesh;
	struct fct_camera cam;
	double pose[12];
	double ortho_step;
	const float *depth;
	const float *sigma;
	int step, planes, plane_mean;
};

enum fct_fuse_weight {
	FCT_FUSE_CONSTANT,      /* 1 */
	FCT_FUSE_INCIDENCE,     /* |cos| of the angle between the ray and the normal */
	FCT_FUSE_DEPTH2         /* (1 m / depth)^2 */
};

struct fct_fuse_params {
	double band;            /* truncation: voxels within band (metres) of a view's surface */
	enum fct_fuse_weight weight;
	int projective;         /* Curless-Levoy depth difference along the ray instead */
	int has_clip;           /* update only voxels in [lo, hi] (voxel indices) */
	int32_t clip_lo[3], clip_hi[3];
	int threads;            /* 0: one per processor; the result is the same for any count */
};

struct fct_fuse_stats {
	size_t voxels;          /* voxels updated */
	size_t border;          /* voxels skipped because their nearest point is on a border */
	size_t faces;           /* triangles used */
	size_t plane_views;     /* views fused by their planes (fuseplane.c) */
	/* Seconds in fct_fuse_view's phases: the view's triangles (with their
	 * normals for true distance), its raster or pixel grid, its candidate
	 * voxels, and their distances put into the volume. */
	double triangles_s, raster_s, candidates_s, distances_s;
};

/* Fuse view v into g.  stats may be NULL (or is added to).  0 or -1
 * (out of memory, the grid's memory limit). */
int fct_fuse_view(struct fct_voxgrid *g, const struct fct_fuse_view *v,
                  const struct fct_fuse_params *p, struct fct_fuse_stats *stats,
                  struct fct_err *err);

struct fct_depth_params;
struct fct_depth_smooth;
struct fct_image;

/* The view of depth image img (seen by cam, a camera of its size, at
 * camera-to-world pose) for fusion: smoothed by smooth in units of dp's
 * noise model when it has one (depthsmooth.h; not when smooth->radius is
 * 0), meshed with it (fct_depth_mesh_kept: the jump test's noise term and
 * each vertex's sigma, which v->sigma points into), the mesh moved to the
 * world into mesh (v->mesh; the caller frees it).  depth, when not NULL,
 * gets the depths the mesh keeps (malloc'd; v->depth, what --projective
 * fusion reads), and the mesh has a vertex on every pixel with data.
 * Without it the view is for true distance into voxels of vox metres:
 * where fct_fuse_depth_step gives a step, meshed at that step and fused by
 * its planes (v->step and v->planes; v->plane_mean where the sensor's
 * noise at the image's median depth is at least a tenth of a voxel); else,
 * or with vox 0, meshed at every pixel and searched (tsdfuse --exact).
 * 0 or -1. */
int fct_fuse_depth_view(struct fct_fuse_view *v, struct fct_mesh *mesh, float **depth,
                        const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *dp, const struct fct_depth_smooth *smooth,
                        const double pose[12], double vox, struct fct_err *err);

/* The pixel step at which true distance meshes depth image img for voxels
 * of vox metres and fuses it by its planes (fuseplane.c), or 0 to mesh it
 * at every pixel and search the mesh.  Planes where dp has a noise model
 * (a sensor's, or none: exact data) and the image's pixels are at most 0.6
 * voxels apart at its median depth; they cost a part of the search (within
 * 1.5 times --projective, the search 3 to 10 times).  Where the model's
 * noise there is at least a tenth of a voxel, the mesh's nearest points
 * follow the noise, and planes through the mean of nine samples average it
 * (mkscene's room, 24 views under Kinect noise at 2 cm: 1.29 mm from the
 * true surface and 55 components, against 1.69 and 33 by the search and
 * 1.97 and 176 by --projective).  With less noise, or none, the planes go
 * through their vertices, and the search is a little more complete at
 * silhouettes (the room's 24 views without noise: accuracy 0.14 mm,
 * completeness 0.24, 18 components, against the search's 0.15, 0.18 and
 * 15 and --projective's 0.65, 0.55 and 313; Gaussian noise of 3 mm at 4 cm
 * voxels, 12 views of 320x240: 0.99, 1.46 and 18 against 0.87, 0.98 and 20
 * and 2.07, 1.79 and 70): tsdfuse --exact searches.  Without a model the
 * noise is unknown and the mesh is searched as it is (raw Kinect frames at
 * 2 cm, planes through their vertices: 8% fewer faces than the search).
 * The step: samples about 0.6 voxels apart
 * at the median depth, round(0.6 vox f / median) for a pinhole of focal
 * length f (the smaller of fx and fy); finer ones add nothing the volume
 * keeps (Kinect-class sensors measure coarser than their pixels anyway: a
 * correlation window of 9 pixels), samples a voxel apart lose surfaces
 * (the noisy room: step 2 1.29 mm, 3 1.33, 4 2.50).  0 for cameras other
 * than pinholes. */
int fct_fuse_depth_step(const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *dp, double vox);

/* A view's range image, from its mesh rasterised into its own camera. */
struct fct_range_image {
	struct fct_fuse_view view;
	double inv[12];          /* world-to-sensor */
	int width, height;
	double u0, v0;           /* orthographic: pixel (0, 0) is at (u0, v0) * step */
	float *range;            /* depth (camera z, cylinder rho, or -z); 0: no data */
};

/* Rasterise v's mesh.  Orthographic views get a raster covering the mesh
 * with pixels of v->ortho_step, at most max_pixels.  0 or -1. */
int fct_range_image_make(struct fct_range_image *r, const struct fct_fuse_view *v,
                         size_t max_pixels, struct fct_err *err);
void fct_range_image_free(struct fct_range_image *r);

/* The range image of depth image img itself, seen by cam (a pinhole or
 * cylindrical camera of its size) at camera-to-world pose: each pixel's
 * depth as it is (fct_depth_at under dp), no mesh rasterised (view.mesh is
 * NULL).  What tells whether a view sees a point where its raw depth will
 * do (fct_viewnoise_add), at the cost of decoding the image.  0 or -1. */
int fct_range_image_depth(struct fct_range_image *r, const struct fct_image *img,
                          const struct fct_camera *cam, const struct fct_depth_params *dp,
                          const double pose[12], struct fct_err *err);

/* Bytes that fct_carve would use for the bitsets over lo..hi. */
size_t fct_carve_bytes(const int32_t lo[3], const int32_t hi[3]);

/* Space carving over voxels lo..hi (inclusive) of g, after fusion: every
 * voxel with weight 0 that a range image saw through is empty, every other
 * voxel with weight 0 unknown (solid); the empty and unknown voxels next to
 * a change of state (26-neighbourhood) are written with sdf +band (empty)
 * or -band (unknown) and weight mark_weight, so that marching cubes closes
 * the surface between them.  The outermost layer of the box stays unknown.
 * Bubbles of unknown voxels are empty too: a 6-connected group of unknown
 * voxels within 3 voxels of its first that touches no observed voxel
 * behind the surface (sdf <= 0, 26-neighbourhood) lies between the views' rays in carved space, and
 * would otherwise come out as a closed speck.  *carved gets the number of
 * empty voxels (may be NULL).  0 or -1. */
int fct_carve(struct fct_voxgrid *g, const struct fct_range_image *views, size_t nviews,
              const int32_t lo[3], const int32_t hi[3], double band, float mark_weight,
              size_t *carved, struct fct_err *err);

/* fct_carve a view at a time, for views that come one by one: the
 * voxels of lo..hi each view saw through, kept as one bit each (seen),
 * then carving with them once the views are fused.  The result is
 * fct_carve's with the same views and box. */
struct fct_carving {
	int32_t lo[3];
	size_t nx, ny, nz, nw, words;   /* the box in voxels; rows of nw 64-bit words */
	double vox;
	uint64_t *seen;
};

/* An empty carving over voxels lo..hi (inclusive) of size vox; it holds
 * one of fct_carve_bytes' three bitsets.  0 or -1. */
int fct_carving_init(struct fct_carving *c, const int32_t lo[3], const int32_t hi[3], double vox,
                     struct fct_err *err);
/* The voxels range image r saw through, into c. */
void fct_carving_add(struct fct_carving *c, const struct fct_range_image *r);
/* fct_carve's carving of g with the views added to c (the other two
 * bitsets are allocated here).  c is spent: free it after.  0 or -1. */
int fct_carving_finish(struct fct_carving *c, struct fct_voxgrid *g, double band, float mark_weight,
                       size_t *carved, struct fct_err *err);
void fct_carving_free(struct fct_carving *c);

/* Level-set mean-curvature flow phi_t = |grad phi| div(grad phi / |grad phi|)
 * for iters explicit steps of dt = voxel^2 / 8 on the observed voxels
 * (unobserved neighbours mirror the voxel: no flux across the edge of the
 * data).  0 or -1. */
int fct_curvature_flow(struct fct_voxgrid *g, int iters, double band, struct fct_err *err);

#endif
