/* scene.h - synthetic scenes with exact ground truth, rendered by ray
 * casting: the test data under every quality test of facet (mkscene).
 *
 * A scene is a polygon mesh in world coordinates (metres, z up) made of
 * surfaces: planar ones (each a patch with an exact plane) and curved ones
 * (a sphere, a vertical cylinder), each finely tessellated.  Rendering casts
 * one ray per pixel centre through exactly this mesh, so the mesh is the
 * ground truth of every depth pixel.  Colours are procedural textures in
 * each surface's own coordinates times a fixed Lambert shading, the same
 * from every viewpoint.  Noise is applied afterwards to the depth along each
 * pixel's ray (and, for structured light, to where each pixel samples), from
 * seeded streams (rng.h), so the same options give the same bytes.
 *
 * Plane normals point to the free side of their surface: into the room for
 * its floor, ceiling and walls, out of boxes and objects; every camera that
 * sees a plane is on its positive side (n.c + d > 0), and every face is
 * wound counter-clockwise seen from that side. */
#ifndef FCT_SCENE_H
#define FCT_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "geom/bvh.h"
#include "io/camera.h"
#include "core/err.h"
#include "core/mesh.h"
#include "io/noise.h"

enum fct_surface_kind { FCT_SURF_PLANE, FCT_SURF_SPHERE, FCT_SURF_CYLINDER };

/* One surface of a scene.  Texture: a checker of light (rgb) and dark
 * (0.6 rgb) cells.  Planes: cells of `cell` metres along e1 and e2 from o.
 * Spheres: 16 sectors of longitude about the z axis times 8 bands of
 * latitude.  Cylinders: 16 sectors times bands of `cell` metres from the
 * base. */
struct fct_scene_surface {
	enum fct_surface_kind kind;
	char name[24];
	int patch;                  /* the plane's index (patch label), -1 if curved */
	double n[3], d;             /* plane: unit normal to the free side, n.p + d = 0 */
	double o[3], e1[3], e2[3];  /* plane: texture origin and in-plane axes, e1 x e2 = n */
	double c[3], r, h;          /* sphere: centre, radius; cylinder: base centre, radius, height */
	double cell;                /* texture cell in metres (planes, cylinders) */
	uint8_t rgb[3];             /* base colour */
};

struct fct_scene {
	char name[16];
	/* The exact mesh: double x y z, faces with "int patch" (-1 on curved
	 * surfaces) and a "plane" element nx ny nz d (double), int count (the
	 * faces of the patch), rms (0): what scene.ply holds. */
	struct fct_mesh mesh;
	int32_t *face_surface;      /* surface of each face */
	struct fct_scene_surface *surf;
	size_t nsurf, nplanes;
	size_t face_cap, surf_cap;  /* capacities of face_surface and surf */
	struct fct_bvh bvh;         /* over the faces of mesh; ids are face indices */
	double light[3];            /* unit direction towards the light */
	/* Default viewpoints: pinhole views placed by fct_scene_view_pose,
	 * the panorama at pano[]. */
	int orbit;                  /* 1: views orbit target from eye; 0: room views */
	int grain;                  /* 1: the albedo also has a fine grain (fct_scene_color) */
	double eye[3], target[3];
	double pano[3];
};

/* The scene names fct_scene_build knows, blank-separated:
 * "room plane steps cube sphere". */
const char *fct_scene_names(void);

/* Build the named scene into s (initialised here; free with
 * fct_scene_free).  -1 with a message for an unknown name or out of memory. */
int fct_scene_build(struct fct_scene *s, const char *name, struct fct_err *err);
void fct_scene_free(struct fct_scene *s);

/* The camera-to-world pose of pinhole view i of n (0 <= i < n): in the
 * room, views spread round the room looking at its walls and corners from
 * inside, tilted down; in the small scenes, views orbit the object about a
 * vertical axis, 8 degrees apart, view 0 in the middle for odd n. */
void fct_scene_view_pose(const struct fct_scene *s, int i, int n, double pose[12]);
/* The pose of the panorama: at s->pano, its axis vertical, theta = 0 along +x. */
void fct_scene_panorama_pose(const struct fct_scene *s, double pose[12]);

/* A rendered view: per pixel, row-major from the top left. */
struct fct_render {
	int width, height;
	double *depth;    /* depth (pinhole z, cylindrical rho), 0 where nothing is hit */
	int32_t *face;    /* face of s->mesh hit, -1 for none */
	double *cosine;   /* |cos| of the angle between the ray and the face's normal */
	uint8_t *rgb;     /* 3 per pixel, 0 where nothing is hit */
};

/* Render s from the camera cam (pinhole or cylindrical, width and height
 * set) at pose (camera-to-world): one ray per pixel centre, the ray of
 * fct_camera_ray moved to the world, its first hit by fct_bvh_raycast.  The
 * depth is the ray parameter of the hit, so depth * ray is the hit point in
 * the camera frame in both models.  out is allocated here (fct_render_free). */
int fct_scene_render(const struct fct_scene *s, const struct fct_camera *cam,
                     const double pose[12], struct fct_render *out, struct fct_err *err);
void fct_render_free(struct fct_render *r);

/* The colour of world point p on face f: the surface's checker times
 * 0.5 + 0.5 max(0, n.light) with n the surface's exact normal at p,
 * rounded to 8 bits.  With s->grain the checker is also multiplied by
 * 0.6 + 0.4 g, g in [0, 1] a value noise in the surface's own metric
 * coordinates (two octaves, lattices of 4 and 2 cm): detail finer than a
 * 1 cm mesh's vertex colours hold, for judging texture against them. */
void fct_scene_color(const struct fct_scene *s, size_t f, const double p[3], uint8_t rgb[3]);

/* Sensor models applied to a depth image.  Each valid pixel (truth > 0),
 * in this order: dropped (0) when its truth is outside [near, far] (far 0:
 * no limit) or it is seen more than `grazing` degrees from its normal;
 * dropped with probability `missing`; replaced with probability `outliers`
 * by a depth uniform in [0.5, 1.5] times its truth; otherwise measured:
 *
 * - without a sensor model, moved by a normal deviate of standard deviation
 *   sqrt(sigma^2 + (kinect_gauss z^2)^2), z its truth;
 * - with one (noise.h), the depth the sensor samples there (`sampled`, the
 *   truth along a jittered ray, fct_scene_render_jitter; the truth when
 *   NULL) goes through it: kinect and stereo turn it into the disparity
 *   F B / z, add SD times a normal deviate and (kinect) round to a multiple
 *   of STEP, then back to depth -- the structured-light simulation of
 *   ICL-NUIM (Handa et al., "A Benchmark for RGB-D Visual Odometry, 3D
 *   Reconstruction and SLAM", ICRA 2014, after Barron and Malik 2013), with
 *   rounding to the nearest level; tof and poly add their sigma(z) times a
 *   normal deviate; none keeps it.
 *
 * A measured depth <= 0 is dropped.  Each kind of draw has its own stream,
 * one draw per pixel whatever happens, so one option never changes what
 * another does. */
struct fct_scene_noise {
	double sigma;          /* metres */
	double kinect_gauss;   /* per metre: sigma = kinect_gauss z^2 */
	double outliers;       /* fraction in [0, 1] */
	double missing;        /* fraction in [0, 1] */
	double grazing;        /* degrees; >= 90: off */
	double near, far;      /* metres */
	struct fct_noise sensor;   /* FCT_NOISE_UNKNOWN: sigma and kinect_gauss */
};

struct fct_scene_noise_stats {
	size_t valid;              /* truth > 0 */
	size_t range, grazing;     /* dropped by range, by angle */
	size_t missing, outliers;  /* dropped at random, replaced */
	size_t lost;               /* the sampled depth (jittered ray) is 0 */
	size_t noisy;              /* measured with noise */
	double sum, sum2;          /* of (noisy - truth) over the noisy ones */
	double model2;             /* sum of the model's sigma(truth)^2 over them */
};

/* Apply nz to truth[0..n) into out (may equal truth), with streams drawn
 * from seed and stream (one stream number per image); sampled (may be
 * NULL) as above; cosine (may be NULL when grazing >= 90) as from
 * fct_scene_render.  stats may be NULL. */
void fct_depth_noise(const struct fct_scene_noise *nz, uint64_t seed, uint64_t stream,
                     const double *truth, const double *sampled, const double *cosine, double *out,
                     size_t n, struct fct_scene_noise_stats *stats);

/* The depths a sensor records when the point it samples for pixel (u, v)
 * is (u + du, v + dv), du and dv normal deviates of `jitter` pixels (the
 * lateral noise of Handa et al. 2014), drawn from their own stream of seed
 * and stream: the depth of that jittered ray's first hit (0 for none),
 * into depth[0 .. width * height).  The same camera, pose and streams as
 * fct_scene_render and fct_depth_noise.  0 or -1. */
int fct_scene_render_jitter(const struct fct_scene *s, const struct fct_camera *cam,
                            const double pose[12], double jitter, uint64_t seed, uint64_t stream,
                            double *depth, struct fct_err *err);

#endif
