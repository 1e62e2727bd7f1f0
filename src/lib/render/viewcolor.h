/* viewcolor.h - what the views saw of a fused surface, vertex by vertex:
 * its colour from the views' images, each vertex the weighted average of
 * what the views that see it saw there (the optional colour of tsdfuse,
 * issue 7 item 3; Sun et al. fuse geometry only, so this is the usual
 * texture-fusion step of volumetric pipelines, done per output vertex
 * rather than per voxel so that the colour is not blurred to the voxel
 * size), and its noise from their sensors' noise models (fct_viewnoise,
 * below).
 *
 * Visibility.  A view sees vertex p when p projects inside its camera, in
 * front of it, onto pixels whose range (the view's own range image,
 * fuse.h's fct_range_image_make: its mesh rasterised into its camera)
 * agrees with p's depth within band, and, when the mesh has normals
 * (marching cubes gives them, pointing to free space), when the camera is on
 * the normal's side.  Occluded vertices fail the depth test; the far side of
 * a thin object fails the normal test.
 *
 * Sampling.  The image is sampled bilinearly at p's pixel.  When the image
 * has the camera's size, the four texels are masked by the same depth test
 * and the weights renormalised, so a vertex beside a depth edge takes no
 * colour from the other surface; an image of another size (same field of
 * view, as dm2mesh's texture coordinates assume) is sampled plainly.
 *
 * Weights.  w = confidence x coverage x edge, where confidence is that of
 * fuse.h (1, |cos| between the ray and the normal, or 1/depth^2 in 1/m^2),
 * coverage is the bilinear weight of the texels that passed the depth test
 * (1 away from edges), and edge = (1 + d) / (1 + edge_px) for a pixel d <
 * edge_px pixels (chamfer distance) from a depth edge (no data, or a jump of
 * more than band between 4-neighbours), else 1: colour near silhouettes is
 * the least trustworthy (mixed pixels, registration error) but is still
 * used where nothing better sees the vertex.
 *
 * Views are added one at a time into an accumulator (sums in double, in
 * the order added), so only one image and one range image need be in memory
 * and the result is deterministic. */
#ifndef FCT_VIEWCOLOR_H
#define FCT_VIEWCOLOR_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "fusion/fuse.h"
#include "io/image.h"
#include "io/noise.h"
#include "core/mesh.h"

struct fct_viewcolor_params {
	double band;                /* depth agreement, metres (> 0) */
	enum fct_fuse_weight weight;
	double edge_px;             /* falloff width near depth edges, pixels (0: none) */
};

/* Sums of one mesh's vertices: 4 doubles per vertex (w r, w g, w b, w). */
struct fct_viewcolor {
	size_t nv;
	double *sum;
	size_t samples;             /* (vertex, view) pairs that were seen */
};

struct fct_viewcolor_stats {
	size_t colored;             /* vertices seen by at least one view */
	size_t unseen;              /* vertices given the fallback */
	double views_per_vertex;    /* mean number of views over the colored ones */
};

/* An empty accumulator for nv vertices.  0 or -1 (out of memory). */
int fct_viewcolor_init(struct fct_viewcolor *c, size_t nv, struct fct_err *err);
void fct_viewcolor_free(struct fct_viewcolor *c);

/* Add what view r (a range image of a pinhole or cylindrical camera; its
 * mesh pointer is not used) sees of m's vertices (m->nv == c->nv; normals
 * nx ny nz used when present) through image (any channels and type, see
 * fct_image_to_rgb8; its field of view is the camera's).  *seen (may be
 * NULL) gets the number of vertices it saw.  0 or -1 (out of memory, an
 * orthographic range image: such views have no image). */
int fct_viewcolor_add(struct fct_viewcolor *c, const struct fct_mesh *m,
                      const struct fct_range_image *r, const struct fct_image *image,
                      const struct fct_viewcolor_params *p, size_t *seen, struct fct_err *err);

/* Write uchar red green blue into m's vertices (replacing any there): the
 * weighted average rounded to the nearest integer, or fallback for vertices
 * no view saw.  stats may be NULL.  0 or -1. */
int fct_viewcolor_write(const struct fct_viewcolor *c, struct fct_mesh *m, const uint8_t fallback[3],
                        struct fct_viewcolor_stats *stats, struct fct_err *err);

/* The noise of a fused surface, vertex by vertex, from the noise models of
 * the views that see it (the same visibility as the colour).
 *
 * Fusion averages views: a vertex seen by views whose sensor noise at its
 * depth is s_i, each weighing w_i = c_i / (1 + (2 s_i / voxel)^2) as fuse.h
 * weighs them (c_i the confidence of the view), has the noise of their
 * weighted mean.  Were the views' errors independent that would be
 * sqrt(sum w_i^2 s_i^2) / sum w_i, were they one and the same the weighted
 * rms sqrt(sum w_i s_i^2 / sum w_i); neither is (neighbouring viewpoints
 * see the same lumps of a surface), and the geometric mean of the two is
 * taken.  In proportion only: the smoothing of the depth images and the
 * planes of the fusion take a like share of every view's noise, which the
 * sensor's model does not know.  So the views give each vertex's noise
 * relative to the others', and the fused surface's own residuals (noise.h's
 * estimate) give the level: the vertices' median sigma is the estimate.
 * The volume adds an error of its own, which no view's noise accounts for:
 * on exact data (mkscene's room, 24 views) the fused surface lies vox/30
 * from the truth rms at 1 and 2 cm voxels, most of it where marching cubes
 * rounds creases (p99 vox/6).  A near surface's noise would have a plane
 * give up the strip along each of its creases to free-form faces, so the
 * figure has a floor, added in quadrature (fct_fuse_depth_sigma: vox/20,
 * the best of vox/30, vox/20 and vox/13 on three sequences,
 * bench/NOTES.md).
 * Measured against the true surface of mkscene's room under Kinect noise
 * at 2 cm voxels, in each fifth of the vertices by the figure: make demo's
 * 18 views of 320x240, 0.07-0.10 times the figure (median absolute
 * distance 0.5 mm to 3.1 mm, near to far); roommodel.sh's 6 views of
 * 160x120, 0.22 in every fifth (1.7 to 9.0 mm).  The independent figure
 * alone gave 0.13-0.11 and 0.31-0.23 (too little noise where many views
 * overlap), the weighted rms 0.04-0.07 and 0.16-0.20 (too much far away). */
struct fct_viewnoise {
	size_t nv;
	double *sum;                /* 2 per vertex: sum w, sum w^2 s^2 */
};

/* An empty accumulator for nv vertices.  0 or -1 (out of memory). */
int fct_viewnoise_init(struct fct_viewnoise *c, size_t nv, struct fct_err *err);
void fct_viewnoise_free(struct fct_viewnoise *c);

/* Add what view r sees of m's vertices (as fct_viewcolor_add: band, the
 * weight's confidence; edge_px unused) under the noise model nz of its
 * sensor, for voxels of vox metres, on threads threads (0: one per
 * processor; the same sums on any number).  *seen (may be NULL) as there.
 * 0 or -1 (an orthographic range image, a mesh of another size). */
int fct_viewnoise_add(struct fct_viewnoise *c, const struct fct_mesh *m, const struct fct_range_image *r,
                      const struct fct_noise *nz, double vox, const struct fct_viewcolor_params *p,
                      int threads, size_t *seen, struct fct_err *err);

/* Write the float vertex property sigma into m (replacing any there): each
 * seen vertex's figure x, scaled, with the floor, sqrt((k x)^2 + floor^2),
 * k such that the median is level (metres, > 0); level for vertices no view
 * saw, and for all when level is not above the floor.  *seen (may be NULL)
 * gets the number seen.  0 or -1 (none seen: nothing written; out of
 * memory). */
int fct_viewnoise_write(const struct fct_viewnoise *c, struct fct_mesh *m, double level, double floor_,
                        size_t *seen, struct fct_err *err);

/* Chamfer distance (1, sqrt 2) in pixels from each pixel of a W x H range
 * image R (0: no data) to the nearest depth edge: a pixel without data, or
 * one with a 4-neighbour without data or not continuous with it (ranges a
 * and b differ by more than band + slope min(a, b)).  Capped at cap;
 * malloc'd W*H floats, NULL when out of memory. */
float *fct_depth_edge_distance(const float *R, int W, int H, double band, double slope,
                              double cap, struct fct_err *err);

#endif
