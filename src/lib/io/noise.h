/* noise.h - how a depth sensor's samples are noisy and quantised, and the
 * standard deviation of a sample's depth that follows: the noise model that
 * travels on the pipes (the "noise" header comment, DESIGN.md) and that later
 * stages weigh and bound their work by.
 *
 * Models, as text (the command line's --noise and the header comment):
 *
 *   none                  exact data (synthetic scenes): sigma = 1e-6 z, a
 *                         floor that keeps tests in units of sigma finite
 *   kinect F B SD STEP    structured light (Kinect v1, PrimeSense, Xtion):
 *                         the sensor measures the disparity d = F B / z
 *                         (pixels; F the focal length of its infrared camera,
 *                         B the projector's baseline in metres) with Gaussian
 *                         noise of SD pixels and reports it in steps of STEP
 *                         pixels, so that depth comes in levels F B / (k STEP)
 *                         about z^2 STEP / (F B) apart and
 *                         sigma_z = z^2 SD / (F B)  (+ quantisation)
 *   tof A B               time of flight (Kinect v2 / Azure Kinect class):
 *                         sigma = A + B z
 *   poly A B C            sigma = A + B z + C z^2 (metres)
 *   stereo FB SD DOFFS    disparity stereo, z = FB / (d + DOFFS) (Middlebury's
 *                         doffs): sigma_z = z^2 SD / FB
 *
 * Every model may end with "unit U": the step of the depth's own encoding in
 * metres (1/depth-scale for integer PNG depth; 0, the default, for floats).
 *
 * sigma(z) is the Gaussian part combined in quadrature with the rounding of
 * each quantisation (a uniform error of one step q has deviation
 * q / sqrt(12)): sigma^2 = g(z)^2 + q(z)^2 / 12 + U^2 / 12.
 *
 * The text is the model's name and its numbers, separated by blanks, ':' or
 * ',' ("kinect:585,0.075" on a command line, where the numbers left out take
 * the defaults below; "kinect 585 0.075 0.051 0.125 unit 0.001" in a
 * header, every number in the shortest form that reads back exactly). */
#ifndef FCT_NOISE_H
#define FCT_NOISE_H

#include <stddef.h>

#include "core/err.h"
#include "core/mesh.h"

enum fct_noise_model {
	FCT_NOISE_UNKNOWN = 0,   /* no model: estimate from the data */
	FCT_NOISE_NONE,
	FCT_NOISE_KINECT,
	FCT_NOISE_TOF,
	FCT_NOISE_POLY,
	FCT_NOISE_STEREO
};

struct fct_noise {
	enum fct_noise_model model;
	double focal, baseline;  /* kinect: F (pixels), B (metres) */
	double fb;               /* kinect F B; stereo FB (pixels times metres) */
	double sd;               /* kinect, stereo: disparity noise (pixels) */
	double step;             /* kinect: disparity step (pixels) */
	double doffs;            /* stereo: disparity offset (pixels) */
	double coef[3];          /* tof A B (0), poly A B C: sigma in metres */
	double unit;             /* step of the depth encoding (metres), 0: none */
};

/* The kinect model's defaults.  F and B: the Kinect v1's infrared camera and
 * baseline (Khoshelham and Oude Elberink 2012, "Accuracy and resolution of
 * Kinect depth data for indoor mapping applications", Sensors 12:1437, sec.
 * 2-3: f about 580-585 px, b 7.5 cm); 8 F B = 351 px m is the constant of
 * ICL-NUIM's simulation (Handa et al. 2014: d = 35130 / z with z in
 * centimetres, rounded to integers, i.e. 1/8 px) and of the raw-disparity
 * conversion z = 351.3 / (1092.5 - raw) (Open3D, NYU v2) within 0.1%.
 * STEP: the sensor's 1/8-pixel disparity units.  SD: Khoshelham and Oude
 * Elberink take the measured disparity's deviation as half a raw disparity
 * unit (1/16 px), which gives sigma_z = 1.425e-3 z^2 for 8 F B = 351 (their
 * eq. 9); that deviation includes the rounding ((1/8)^2 / 12 px^2), so the
 * Gaussian part is sqrt(1/256 - 1/768) = 0.051 px and the model's total is
 * their 1.425e-3 z^2: 5.7 mm at 2 m, beside Nguyen, Izadi and Lovell
 * 2012's measured 0.0012 + 0.0019 (z - 0.4)^2 (6.1 mm).  The 7-Scenes
 * frames agree: planes fitted to 48x48-pixel windows leave an rms whose
 * lower quartile is 5.9 mm at 2 m and 12.0 at 3 m (the model with their B,
 * 5.8 and 13.0). */
#define FCT_KINECT_FOCAL 585.0
#define FCT_KINECT_BASELINE 0.075
#define FCT_KINECT_SD 0.051
#define FCT_KINECT_STEP 0.125

/* The tof model's defaults: a line through the axial noise of the Kinect v2
 * that Fankhauser et al. 2015 ("Kinect v2 for mobile robot navigation:
 * evaluation and modeling", ICAR, eq. 5 at normal incidence) fit as
 * 1.5 - 0.5 z + 0.3 z^2 mm: A + B z meets it within 0.3 mm from 1 to
 * 3.5 m (1.3, 1.7, 2.7 mm at 1, 2, 3 m; the line 1.2, 2.0, 2.8).  Phone
 * LiDAR and other sensors need their own tof:A,B. */
#define FCT_TOF_A 0.0004
#define FCT_TOF_B 0.0008

/* Relative floor of the none model: sigma = FCT_NOISE_FLOOR z. */
#define FCT_NOISE_FLOOR 1e-6

/* Parse a model from text (see above) into nz; numbers left out take their
 * defaults (kinect: F B SD STEP; tof: A B; stereo: DOFFS 0); poly needs its
 * three, stereo FB and SD.  0, or -1 with a message naming what is wrong. */
int fct_noise_parse(struct fct_noise *nz, const char *text, struct fct_err *err);

/* The header text of nz: the model's name and all its numbers (each the
 * shortest text that reads back to the same double),
 * "unit U" when U > 0; "" for FCT_NOISE_UNKNOWN.  At most 256 bytes with
 * the terminator suffice. */
void fct_noise_format(const struct fct_noise *nz, char *buf, size_t size);

/* The names of the models, blank-separated. */
const char *fct_noise_models(void);

/* Does text start with the name of a model (as --noise's argument, which
 * may also name a file holding one)?  1 or 0. */
int fct_noise_names_model(const char *text);

/* The kinect model with the defaults above (unit 0). */
void fct_noise_kinect(struct fct_noise *nz);

/* The model a dataset's camera name (camera.h's fct_camera_named) implies:
 * every one is a Kinect v1 / PrimeSense sensor, so kinect with F = 585 and
 * the defaults, except B where the data tell it.  Depth levels are
 * 8 F B / k apart in 1/z, and the spacing of the distinct depths of the
 * shared frames gives 8 F B = 345.5 px m for 7-Scenes (the 20 redkitchen
 * frames) and 342.2 for TUM (the fr3 frame of samples/), so B = 0.0738 and
 * 0.0731 there; ICL-NUIM's simulation constant 35130 gives B = 0.07506;
 * the others keep 0.075.  0, or -1 for a name it does not know. */
int fct_noise_named(const char *camera_name, struct fct_noise *nz);

/* Read a model from a small text file: one line "noise MODEL ..." (with or
 * without "comment" before it), as mkscene writes beside its views.  0 or
 * -1 (message naming path). */
int fct_noise_read_file(const char *path, struct fct_noise *nz, struct fct_err *err);

/* The expected standard deviation (metres) of a sample's depth at depth z
 * (> 0) under nz, quantisation included; 0 for FCT_NOISE_UNKNOWN.  A
 * point's deviation along its ray is this times |ray| / ray_z for a pinhole
 * (the ray's length when its z is 1). */
double fct_noise_sigma(const struct fct_noise *nz, double depth);

/* fct_noise_sigma of depth[0..n) into sigma[0..n), 0 where the depth is not
 * positive: the loop over the pixels of a depth image. */
void fct_noise_sigmas(const struct fct_noise *nz, const double *depth, float *sigma, size_t n);

/* 1 when nz's sigma changes with depth (every model but poly and tof with
 * only A, and unknown), else 0: whether a mesh without a camera can be
 * given its noise. */
int fct_noise_grows_with_depth(const struct fct_noise *nz);

/* The Gaussian part alone (what a simulation draws before rounding). */
double fct_noise_sigma_gaussian(const struct fct_noise *nz, double depth);

/* The largest quantisation step of the depth at z (metres): the distance
 * between neighbouring depth levels of the kinect model there
 * (z^2 STEP / (F B), to first order), or the encoding's unit; 0 when the
 * data are not quantised. */
double fct_noise_step(const struct fct_noise *nz, double depth);

/* Estimating the noise of a mesh that carries no sigma (a fused scan,
 * another tool's mesh, a depth mesh of an unknown sensor).
 *
 * One-ring residuals cannot tell noise: quantised depth comes in plateaus,
 * exact planes along the optical axis whose one-ring residual is 0.  The
 * estimate works at a scale above any plateau: about FCT_NOISE_SEEDS seed
 * vertices spread evenly by index; at each, the plane of the vertices
 * within FCT_NOISE_RADIUS times the seed's mean edge length (reached
 * through faces, at least 12) and the rms of their distances from it
 * (n - 3 degrees of freedom): the noise along the normal there.  With a
 * camera comment (the mesh of one view), each rms is moved onto the seed's
 * ray (divided by |cos| of the angle between the ray and the normal, at
 * least 0.3) and the noise may grow with depth z: the rms are divided by
 * z^p |ray| for p = 0, 1, 2 (constant, time of flight, disparity sensors)
 * and the p whose quotients spread least (median absolute deviation of
 * their logarithms) is taken.  Curvature inflates some fits and plateaus
 * deflate others; the median quotient c is the estimate:
 * sigma = c z^p |ray| along the ray (c alone without a camera, along the
 * normal).  On mkscene's room it comes within 2% of the kinect model's
 * median sigma and 13% of a Gaussian sigma, and on the 20 7-Scenes frames
 * (as meshes without sigma) within 8% of their kinect model's median.
 */
#define FCT_NOISE_SEEDS 4000
#define FCT_NOISE_RADIUS 7.0

struct fct_noise_fit {
	double c;        /* sigma = c z^p |ray|: metres per metre^p */
	int p;           /* 0, 1 or 2; 0 without a camera */
	int camera;      /* 1: along the rays of the mesh's camera, 0: along normals */
	size_t seeds;    /* neighbourhoods that had a plane and a positive rms */
	double sigma;    /* the median of the seeds' sigma: one figure for the mesh */
};

/* Fit the noise of m as above into fit.  0, or -1 (message set) when m
 * gives fewer than 20 neighbourhoods with a fit (few vertices, no faces, a
 * malformed camera or pose comment) or memory runs out. */
int fct_noise_fit(struct fct_noise_fit *fit, const struct fct_mesh *m, struct fct_err *err);

/* fit.sigma alone: the mesh's noise as one figure (metres). */
int fct_noise_estimate(double *sigma, const struct fct_mesh *m, struct fct_err *err);

/* Each vertex's sigma under the fitted law, into sigma[0 .. m->nv) (a vertex
 * behind a pinhole camera gets the fit's sigma). */
int fct_noise_estimate_vertices(float *sigma, const struct fct_mesh *m, struct fct_err *err);

#endif
