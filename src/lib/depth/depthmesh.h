/* depthmesh.h - a depth (or disparity) image and its camera to a mesh in the
 * camera frame, with texture coordinates of the co-registered image.
 *
 * Depth images follow DESIGN.md: integer PNG samples are depth_scale units
 * per metre; PFM samples are metres (divided by depth_scale only when
 * scale_float is set).  Zero, non-finite and, in 16-bit images, 65535 (the
 * 7-Scenes and Kinect "no reading" mark) mean no data, as does a depth
 * outside [min_depth, max_depth].  With a baseline the samples are
 * disparities d in pixels and depth = baseline * focal / (d + doffs), doffs
 * the difference of the two cameras' principal points (Middlebury's
 * calib.txt; 0 for rectified pairs that share them).
 *
 * Every step-th pixel of every step-th row (from pixel 0) is a grid cell of
 * gridmesh.h; s = (u + 0.5) / W and t = 1 - (v + 0.5) / H place the vertex
 * of pixel (u, v) on any image of the same field of view, whatever its
 * resolution.
 *
 * With a noise model (noise.h) each vertex gets the float property sigma:
 * the expected standard deviation (metres) of its position along its ray,
 * fct_noise_sigma of its depth times the ray's length per unit depth.  The
 * model also widens the depth-jump test (gridmesh.h) by what the noise of
 * two samples may make of one surface: noise_jump times the deviation of
 * their difference, sqrt(2) sigma(z) at the farther depth z, so that a far
 * wall under Kinect noise stays one surface while occlusions are cut. */
#ifndef FCT_DEPTHMESH_H
#define FCT_DEPTHMESH_H

#include "io/camera.h"
#include "depth/gridmesh.h"
#include "io/image.h"
#include "core/mesh.h"
#include "io/noise.h"

struct fct_depth_params {
	unsigned code;            /* depthcode.h's codes, for the reader to decode the image by */
	double depth_scale;       /* units per metre; default 1000 */
	int scale_float;          /* apply depth_scale to PFM samples as well */
	double baseline, focal;   /* baseline > 0: disparity image */
	double doffs;             /* disparity offset (Middlebury): depth = b f / (d + doffs) */
	double min_depth, max_depth;
	int step;                 /* sample every step-th pixel (>= 1) */
	struct fct_grid_params grid;
	int texcoords;            /* add float vertex properties s, t */
	struct fct_noise noise;   /* FCT_NOISE_UNKNOWN: no sigma property */
	double noise_jump;        /* deviations of noise allowed in a jump */
};

/* The defaults: scale 1000, no disparity, depths in (0, inf), step 1,
 * max_jump FCT_DEFAULT_MAX_JUMP, min_faces FCT_DEFAULT_MIN_FACES, s t on,
 * no noise model, noise_jump FCT_DEFAULT_NOISE_JUMP. */
void fct_depth_params_default(struct fct_depth_params *p);

/* Largest depth change per lateral step that is still one surface: 10 is
 * the tangent of 84 degrees, the most grazing view a structured-light sensor
 * measures usefully; on Kinect frames (7-Scenes, TUM) at step 1 lower
 * values start to shred surfaces along the sensor's noise (see dm2mesh(1)). */
#define FCT_DEFAULT_MAX_JUMP 10.0
#define FCT_DEFAULT_MIN_FACES 8
#define FCT_DEFAULT_NOISE_JUMP 2.0

/* Depth in metres of sample (x, y) of a one-channel depth image, 0 for no
 * data. */
double fct_depth_at(const struct fct_image *img, int x, int y, const struct fct_depth_params *p);

/* The step of img's depth encoding in metres: 1 / depth_scale for integer
 * (PNG) depth, 0 for floats and for disparities (whose depth steps vary). */
double fct_depth_unit(const struct fct_image *img, const struct fct_depth_params *p);

/* A noise model without a unit of its own takes img's encoding's
 * (fct_depth_unit): the quantisation of the depth as stored is part of
 * its noise.  No model: nothing. */
void fct_depth_noise_unit(struct fct_depth_params *p, const struct fct_image *img);

/* Give each vertex of m the float property sigma (replacing any) under
 * noise model nz, as a view's mesh has it: fct_noise_sigma of its depth in
 * camera cam times the ray's length per unit depth, m's coordinates taken
 * into the camera's frame by inv (the inverse of its pose; NULL: they are
 * in it already); a vertex the camera cannot project takes its distance
 * from the camera as its depth.  Without a camera (cam NULL or
 * FCT_CAMERA_NONE) every vertex gets the model's one figure, and a model
 * that grows with depth (fct_noise_grows_with_depth) is refused: 0 or -1. */
int fct_mesh_noise_sigma(struct fct_mesh *m, const struct fct_noise *nz, const struct fct_camera *cam,
                         const double *inv, struct fct_err *err);

/* Depths a known RGB-D sensor measures (metres): a median outside is a
 * wrong depth scale, not a scene. */
#define FCT_SENSOR_MIN_DEPTH 0.3
#define FCT_SENSOR_MAX_DEPTH 8.0

/* The median of a one-channel depth image's depths in metres, over every
 * 4th pixel of every 4th row; 0 when none has data. */
double fct_depth_median(const struct fct_image *img, const struct fct_depth_params *p);

/* Is the depth image implausible for its camera?  When cam is a dataset's
 * RGB-D camera (fct_camera_known) and the median of the image's depths
 * (fct_depth_median) lies outside [FCT_SENSOR_MIN_DEPTH,
 * FCT_SENSOR_MAX_DEPTH], returns 1 with why in msg (the median, the
 * camera, and its dataset's depth scale when p's differs: TUM's frames in
 * units of 1/5000 m read as millimetres give 7-45 m); 0 otherwise. */
int fct_depth_implausible(char *msg, size_t size, const struct fct_image *img,
                          const struct fct_camera *cam, const struct fct_depth_params *p);

/* Mesh the depth image seen by cam (whose size must be the image's) into m,
 * which is initialised here.  stats may be NULL.  0 or -1. */
int fct_depth_mesh(struct fct_mesh *m, const struct fct_image *img, const struct fct_camera *cam,
                   const struct fct_depth_params *p, struct fct_grid_stats *stats,
                   struct fct_err *err);

/* fct_depth_mesh, and when kept is not NULL a malloc'd width x height
 * image of the depths (metres) the mesh keeps: those of its vertices'
 * pixels, 0 elsewhere (a pixel a depth jump or a speck left out is in no
 * triangle). */
int fct_depth_mesh_kept(struct fct_mesh *m, const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *p, struct fct_grid_stats *stats, float **kept,
                        struct fct_err *err);

#endif
