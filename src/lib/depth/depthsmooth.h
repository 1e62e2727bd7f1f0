/* depthsmooth.h - a depth image's noise averaged out before it is meshed,
 * in units of its sensor's noise (noise.h).
 *
 * Under Kinect-class noise a far wall comes as plateaus of quantised depth
 * with noise and jitter between them: a pixel-scale staircase whose steps
 * (26 mm at 3 m) are larger than a fusion's voxels.  Meshed as it is, the
 * staircase's risers turn the normals of the mesh sideways, and the signed
 * distance to it changes sign in single voxels a voxel or two off the wall:
 * thousands of closed specks in a fused room.  Averaging each pixel with
 * its neighbours that lie on the same surface within the noise removes the
 * staircase and keeps the surface's edges: an edge-preserving (bilateral)
 * filter whose range kernel is the noise model's sigma at the pixel.
 *
 * Each pixel with data becomes the weighted mean of the pixels with data in
 * the (2 radius + 1)^2 window around it: a Gaussian weight of their
 * distance in the image, deviation s pixels, times Tukey's biweight
 * (1 - q / 9)^2 of q = (d / (k sigma))^2 for their depth difference d
 * (k = range, sigma = fct_noise_sigma at the centre's depth): a pixel more
 * than 3 k sigma off is another surface and weighs nothing.  Two passes:
 * the second compares with the first's result rather than with the noisy
 * centre, which would otherwise keep the neighbours that share its error
 * (a bilateral filter's pull toward its input: on a slanted plane under
 * the kinect model one pass leaves 0.55 of the noise's rms, two 0.32, the
 * window's ideal mean 0.23).  The mean is taken of inverse depths, so that
 * a plane stays a plane (1/z is affine in the image on a plane, z is not).
 *
 * s is (radius + 0.5) / 2, or less when the data are for a volume of
 * voxel metres (voxel > 0): averaging costs nothing within a quarter voxel
 * (the volume does not resolve it) and is worth its blur of corners and
 * curves only while the noise is above FCT_DEPTH_SMOOTH_LEFT voxels, so s
 * is the wider of a quarter voxel's pixels at the pixel's depth and the
 * deviation whose window leaves that much noise (a Gaussian window of
 * deviation s averages about 4 pi s^2 samples), at most the radius's.
 * Gaussian noise of 3 mm fused at 4 cm from 160x120 views (23 mm pixels
 * at 3 m) is then barely smoothed (the full window cost 7% of the fused
 * room's accuracy, this 2%), while Kinect noise at 3 m (13 mm) gets the
 * whole window.  The result is the same for any order of the work. */
#ifndef FCT_DEPTHSMOOTH_H
#define FCT_DEPTHSMOOTH_H

#include <stddef.h>

#include "io/camera.h"
#include "depth/depthmesh.h"
#include "core/err.h"
#include "io/image.h"
#include "io/noise.h"

struct fct_depth_smooth {
	int radius;              /* window half-width in pixels; 0: no smoothing */
	double range;            /* deviation of the range kernel in sigmas */
	double voxel;            /* the volume's voxel (metres) the data are for; 0: none */
};

/* The defaults: a 5 x 5 window and a range of 2 sigma.  On mkscene's room
 * with ICL-NUIM's structured noise (24 640x480 views fused by tsdfuse at
 * 2 cm, with the model) they bring the fused room from 2576 components
 * (--smooth 0) to 33 and its mean distance to the true surface from 4.7
 * to 1.7 mm (without the model: 3494, 5.0 mm; one pass of a Gaussian
 * range kernel: 151 components, 2.0 mm; a 3 x 3 window: 522); a range of
 * 3 sigma does a little better there (24, 1.6 mm) but blends depth steps
 * up to 9 sigma (11 cm at 3 m) into ramps. */
#define FCT_DEPTH_SMOOTH_RADIUS 2
#define FCT_DEPTH_SMOOTH_RANGE 2.0

/* The noise left, in voxels, below which a window is not widened for the
 * noise (above). */
#define FCT_DEPTH_SMOOTH_LEFT (1.0 / 16)

/* The largest radius taken (a larger one is this). */
#define FCT_DEPTH_SMOOTH_MAX 64

/* The defaults above (voxel 0). */
void fct_depth_smooth_default(struct fct_depth_smooth *p);

/* Smooth depth (w x h metres, row by row; a pixel has data when it is above
 * 0 and finite) under noise model nz into out (w x h; 0 where depth has no
 * data); footprint: the lateral size of a pixel per metre of depth
 * (fct_camera_pixel_angle), for p->voxel.  No model (FCT_NOISE_UNKNOWN), exact data (FCT_NOISE_NONE) or a
 * radius of 0 copies the depths (non-finite ones as 0).  out and depth
 * must not overlap.  0, or -1 when memory runs out or the range is not
 * positive. */
int fct_depth_smooth(float *out, const float *depth, size_t w, size_t h, double footprint,
                     const struct fct_noise *nz, const struct fct_depth_smooth *p, struct fct_err *err);

/* A depth (or disparity) image of camera cam read under p, smoothed under
 * p's noise model: out gets its depths in metres as a one-channel float image
 * (fct_image_free), and p is changed to read them (metres, no disparity,
 * the model's unit set from the image's encoding when it had none), so
 * that fct_depth_mesh of out with p meshes the smoothed depths.  0 or -1. */
int fct_depth_smooth_image(struct fct_image *out, const struct fct_image *img, const struct fct_camera *cam,
                           struct fct_depth_params *p, const struct fct_depth_smooth *sp, struct fct_err *err);

#endif
