/* cylview.h - planar (pinhole) views of a cylindrical panorama, and the
 * texturing of a model through them: Kang, Johnson and Szeliski,
 * "Extraction of Concise and Realistic 3-D Models from Real Data" (DEC CRL
 * 95/7), section 7.
 *
 * A cylindrical image bends straight lines, so it is covered by overlapping
 * pinhole views at regular yaw angles with one field of view; a view pixel
 * takes the colour where its ray meets the cylinder, interpolated bilinearly
 * from the four nearest panorama pixels (wrapping round the 0/360 seam).
 *
 * Frames: everything is in the panorama's camera frame (DESIGN.md: x right,
 * y down, z forward at theta = 0; azimuth theta = atan2(x, z)).  View k looks
 * along azimuth yaw_k: its axes are x_k = (cos yaw, 0, -sin yaw), y_k =
 * (0, 1, 0), z_k = (sin yaw, 0, cos yaw), so a point p of the panorama frame
 * is (x_k.p, y_k.p, z_k.p) in the view's frame, and the view's camera-to-
 * panorama rotation has columns x_k, y_k, z_k.
 *
 * The pinhole pixel (u, v) of view k with x = (u - cx) / F, y = (v - cy) / F
 * sees azimuth yaw + atan(x) at distance rho = sqrt(1 + x^2) from the axis
 * (per unit depth), so height h = y / rho: panorama column
 * (theta - theta0) W / (2 pi) (mod W) and row cy_p + f h. */
#ifndef FCT_CYLVIEW_H
#define FCT_CYLVIEW_H

#include <stddef.h>
#include <stdint.h>

#include "io/camera.h"
#include "core/err.h"
#include "io/image.h"
#include "core/mesh.h"

#define FCT_CYLVIEW_MAX_COUNT 3600
/* A view holds at most this many times the panorama's pixels (or 2^20). */
#define FCT_CYLVIEW_MAX_ZOOM 16

struct fct_cylview_params {
	int count;          /* views (default 8) */
	double step;        /* degrees between views; 0: 360 / count */
	double fov;         /* horizontal field of view in degrees, (0, 180) (default 90) */
	double yaw0;        /* azimuth of view 0 in degrees (default 0: the camera's z) */
	int width, height;  /* view size; 0: automatic (see fct_cylview_plan) */
};

void fct_cylview_params_default(struct fct_cylview_params *p);

/* One planar view. */
struct fct_cylview {
	double yaw;               /* radians */
	struct fct_camera cam;    /* pinhole, fx = fy */
	double rot[9];            /* view-to-panorama rotation, row-major */
};

/* The views of panorama camera pano (cylindrical, width and height set) into
 * views[0..p->count).  Focal length F = W_v / (2 tan(fov / 2)) with
 * cx = (W_v - 1) / 2.  Automatic width: F = the panorama's pixels per radian
 * (W / 2 pi), so the centre of a view has the panorama's resolution.
 * Automatic height: tall enough that the panorama's whole height is inside
 * the view out to halfway between the edge of the view's own sector
 * (step / 2) and the edge of its field of view, so a point near a border
 * between sectors lies inside one view; the horizon row at the panorama's
 * relative place.  A given height keeps that relative place at the same
 * F.  Fails (message set) on a count outside [1, FCT_CYLVIEW_MAX_COUNT], a
 * fov outside (0, 180), a non-cylindrical camera, sizes out of range, and
 * views of more than FCT_CYLVIEW_MAX_ZOOM times the panorama's pixels (and
 * over 2^20): what the panorama cannot justify. */
int fct_cylview_plan(const struct fct_camera *pano, const struct fct_cylview_params *p,
                     struct fct_cylview *views, struct fct_err *err);

/* Render view of panorama img (U8, U16 or F32, any channels) seen by
 * camera pano into out (allocated here, same type and channels): bilinear
 * interpolation, columns wrapping round the seam, rows clamped within half
 * a pixel of the panorama's edge; pixels whose ray misses the panorama's
 * rows are 0.  img must be pano's size. */
int fct_cylview_render(const struct fct_image *img, const struct fct_camera *pano,
                       const struct fct_cylview *view, struct fct_image *out,
                       struct fct_err *err);

/* Project panorama-frame point p into view: 1 with (u, v) and the view-frame
 * depth when p is in front of it, 0 otherwise. */
int fct_cylview_project(const struct fct_cylview *view, const double p[3], double *u, double *v,
                        double *depth);

/* The view's camera-to-world pose given the panorama's (NULL: identity). */
void fct_cylview_pose(const struct fct_cylview *view, const double *pano_pose, double pose[12]);

/* Is the panorama img what a 360-degree camera expects?  Its size must be
 * the camera's; then the seam: the mean absolute difference between the
 * last and first columns must not stand out from those between neighbouring
 * columns elsewhere (above 3 times their 99th percentile and above 2% of
 * the sample range), or the picture does not close on itself.  0, or -1
 * with the message set.  seam_ratio (may be NULL) gets the seam's
 * difference over that percentile. */
int fct_cylview_check_panorama(const struct fct_image *img, const struct fct_camera *pano,
                               int check_seam, double *seam_ratio, struct fct_err *err);

/* Texturing a mesh in the panorama's frame (triangles or polygons; vertices
 * with the panorama frame coordinates, or world ones with pano_pose). */
struct fct_cylview_assign_params {
	int split;             /* bisect faces that fit in no view (conformingly) */
	size_t max_splits;     /* 0: 64 times the faces plus 1024 */
};

struct fct_cylview_assign_stats {
	size_t faces;          /* after splitting */
	size_t splits;         /* edges bisected */
	size_t uncovered;      /* faces in no view */
	size_t views_used;
	double max_ratio;      /* largest depth ratio of an assigned face */
};

/* For each face of m, the view in which all its corners lie within the
 * pixel centres ([0, W-1] x [0, H-1]) in front of the camera, and seen most
 * frontally: the smallest ratio of its corners' largest to smallest depth
 * in the view (1 for a face parallel to the image plane; the amount by
 * which affine texture interpolation differs from the true perspective),
 * ties to the view whose axis is nearest the face's centre, then the lower
 * index.  With p->split, a triangle in no view has its angularly longest
 * edge bisected, with the other face on that edge (new vertices interpolate
 * every scalar vertex property; new faces copy the scalar face properties),
 * until it fits, its edge subtends under 1e-4 radians, or the split budget
 * is spent.  *view_of (malloc'd, m->nf entries after splitting) gets the
 * view per face or -1.  pano_pose: camera-to-world of the panorama (NULL:
 * the mesh is in its frame). */
int fct_cylview_assign(struct fct_mesh *m, const double *pano_pose,
                       const struct fct_cylview *views, size_t nviews,
                       const struct fct_cylview_assign_params *p, int32_t **view_of,
                       struct fct_cylview_assign_stats *st, struct fct_err *err);

/* Texture m from the views chosen by view_of (m->nf entries, -1: none):
 * a view is used when some face has it, and its texture number is its rank
 * among the used views.  TextureFile comments are replaced by names[k] of
 * the used views k in order (names has nviews entries; unused ones may be
 * NULL); int face property texnumber is set (-1 for no view).
 * per_face = 1 (PLY, as MeshLab reads it): a face list property
 * "float texcoord" (list uchar, 2 per corner), and vertex s t removed.
 * per_face = 0 (OBJ): a vertex used by faces of several views is
 * duplicated, one copy per view after the vertices (the first keeps its
 * index), and vertex s t are set.  Texture coordinates are
 * s = (u + 0.5) / W, t = 1 - (v + 0.5) / H of the corner's pixel. */
int fct_cylview_texture(struct fct_mesh *m, const double *pano_pose,
                        const struct fct_cylview *views, size_t nviews, const int32_t *view_of,
                        char *const *names, int per_face, struct fct_err *err);

struct fct_cylview_model_stats {
	struct fct_cylview_assign_stats assign;
	size_t written;        /* views written */
	size_t pixels;         /* their pixels */
};

/* Texture the model m, to be written to the file out, from the panorama
 * img (U8 or U16: a texture) seen by pano (pano_pose: camera-to-world,
 * NULL when m is in the panorama's frame) through the views planned by p:
 * each face from its view (fct_cylview_assign; with split, faces that fit
 * in none are bisected), the views some face uses written beside out as
 * STEM.viewNN.png (STEM: out without its extension; atomically),
 * then fct_cylview_texture with those names, per-corner texcoord unless
 * out ends in .obj.  st may be NULL.  Fails (message set) when faces lie
 * whole in no view, naming up to ten of them; that message and the
 * assignment's start with name (m's, for messages). */
int fct_cylview_texture_model(struct fct_mesh *m, const struct fct_image *img,
                              const struct fct_camera *pano, const double *pano_pose,
                              const struct fct_cylview_params *p, int split, const char *name,
                              const char *out, struct fct_cylview_model_stats *st,
                              struct fct_err *err);

#endif
