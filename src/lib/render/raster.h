/* raster.h - a small software rasteriser for pictures of meshes (meshshot,
 * pngsheet): pinhole views, a visibility buffer of triangles with a
 * z-buffer, perspective-correct barycentrics, anti-aliased lines tested
 * against the z-buffer, colour maps, a patch palette, bilinear texture
 * lookups and a built-in 5x7 bitmap font for captions and legends.
 *
 * Rendering is deferred: fct_raster_triangle only records, per pixel, the
 * nearest triangle's id and the perspective-correct barycentric coordinates
 * of the pixel centre in it; the caller then colours each pixel once from
 * those (flat or smooth light, texture, per-vertex values), so shading costs
 * one evaluation per pixel whatever the overdraw.
 *
 * Conventions are OpenCV's, as the cameras of DESIGN.md: camera x right, y
 * down, z forward; pixel centres at integer (u, v).  Triangle coverage is
 * decided exactly on a 1/256-pixel grid with a tie rule, so two triangles
 * sharing an edge cover each pixel centre on it exactly once (no gaps, no
 * double hits), and the same input gives the same pixels on every run. */
#ifndef FCT_RASTER_H
#define FCT_RASTER_H

#include <stdint.h>

#include "io/camera.h"
#include "core/err.h"
#include "io/image.h"

/* A pinhole view: world point p is at camera point q = R p + t (R row-major),
 * and at pixel (fx qx / qz + cx, fy qy / qz + cy).  Points closer than near
 * (in camera z) are clipped away. */
struct fct_view {
	double R[9], t[3];
	double fx, fy, cx, cy;
	double near;
	int width, height;
};

/* q = R p + t. */
void fct_view_to_camera(const struct fct_view *v, const double p[3], double q[3]);

/* The view of pinhole camera cam (its width and height set) at pose
 * (camera-to-world, NULL: the camera's own frame), drawn at width x height
 * pixels with the same field of view (0 x 0: the camera's size), near
 * plane near.  Fails when cam is not a pinhole with a size and positive
 * focal lengths, the size is out of range, or the pose is not finite. */
int fct_view_from_camera(struct fct_view *v, const struct fct_camera *cam, const double *pose,
                         int width, int height, double near, struct fct_err *err);

/* The view from eye looking at target, with up the direction that appears
 * upwards in the picture, a vertical field of view of fov_deg degrees, the
 * principal point in the middle of a width x height image and square
 * pixels.  Fails when eye == target, up is parallel to the line of sight,
 * or a number is not finite. */
int fct_view_look_at(struct fct_view *v, const double eye[3], const double target[3],
                     const double up[3], double fov_deg, int width, int height,
                     struct fct_err *err);

/* Move the eye of v along its line of sight through centre, keeping its
 * orientation and focal lengths, to the nearest distance at which every
 * finite point of pts[0..n) is in the picture with margin (0 to 0.5) of
 * each half-width to spare, and shift the principal point so that the
 * points' picture is centred (an off-axis pinhole view); v->near becomes
 * half the nearest point's depth.  For --view front|side|top|oblique. */
void fct_view_fit(struct fct_view *v, const double centre[3], const double *pts, size_t n,
                  double margin);

/* The visibility buffer.  w is 1/depth of the nearest surface (0: none),
 * id its triangle (FCT_RASTER_EMPTY: none), b1 b2 the barycentric weights
 * of corners 1 and 2 of that triangle at the pixel centre, corrected for
 * perspective (corner 0 has 1 - b1 - b2). */
#define FCT_RASTER_EMPTY UINT32_MAX
struct fct_raster {
	int width, height;
	float *w;
	uint32_t *id;
	float *b;       /* 2 per pixel */
	size_t cap;     /* pixels allocated */
};

/* Allocate an empty buffer (sides 1 .. FCT_IMAGE_MAX_SIDE, at most
 * FCT_IMAGE_MAX_PIXELS / 4 pixels).  0 or -1. */
int fct_raster_init(struct fct_raster *r, int width, int height, struct fct_err *err);
/* Free what r owns; r may be NULL. */
void fct_raster_free(struct fct_raster *r);
/* Empty r again as a buffer of width x height pixels, within the pixels
 * it was allocated with (a buffer reused for pictures of several sizes).
 * 0, or -1 when they do not fit. */
int fct_raster_reset(struct fct_raster *r, int width, int height, struct fct_err *err);

/* Draw the triangle with camera-frame corners q0 q1 q2 (see
 * fct_view_to_camera) as triangle id: clipped to z >= v->near and to a
 * guard band around the picture, then every pixel centre inside it (top-left
 * tie rule on the edges) whose surface is nearer than what the buffer holds
 * takes it; at equal depth the triangle drawn first stays.  Both sides are
 * drawn.  Corners that are not finite draw nothing.  Returns the number of
 * pixels written. */
long fct_raster_triangle(struct fct_raster *r, const struct fct_view *v, const double q0[3],
                         const double q1[3], const double q2[3], uint32_t id);

/* Lines and text on an RGB image (3 channels, U8). */

/* A line of the given width (pixels) from (x0, y0) to (x1, y1) in pixel
 * coordinates, anti-aliased: each pixel is blended towards rgb by opacity
 * times the part of it the line (a capsule of that width, at least 1 pixel
 * wide in coverage) covers, measured from the pixel centre's distance to
 * the segment.  Returns the number of pixels touched. */
long fct_draw_line2d(struct fct_image *img, double x0, double y0, double x1, double y1,
                     double width, const unsigned char rgb[3], double opacity);

/* The line between camera-frame points q0 and q1, clipped like triangles
 * and drawn as fct_draw_line2d where it is not hidden: a pixel is drawn
 * when the line there is not behind the farthest surface r holds in the
 * 3x3 pixels around it by more than a relative 1e-3 of depth, so lines
 * lying on the surface (and on its silhouette) show and lines behind it do
 * not.  r NULL draws without a depth test. */
long fct_draw_line3d(struct fct_image *img, const struct fct_raster *r, const struct fct_view *v,
                     const double q0[3], const double q1[3], double width,
                     const unsigned char rgb[3], double opacity);

/* Fill the rectangle [x0, x1) x [y0, y1) (clipped to the image). */
void fct_draw_rect(struct fct_image *img, int x0, int y0, int x1, int y1,
                   const unsigned char rgb[3]);

/* Text in the built-in 5x7 font (printable ASCII; anything else draws as
 * '?'), each font pixel a scale x scale square, the top-left corner of the
 * first character at (x, y); '\n' starts a new line.  Each character
 * advances 6 scale pixels, each line 9 scale.  Returns the width drawn. */
int fct_draw_text(struct fct_image *img, int x, int y, int scale, const unsigned char rgb[3],
                  const char *text);
/* The width and height fct_draw_text would cover. */
void fct_text_size(const char *text, int scale, int *width, int *height);

/* Colours. */

enum fct_cmap { FCT_CMAP_VIRIDIS, FCT_CMAP_GRAY, FCT_CMAP_COOLWARM };
/* The map by name ("viridis", "gray", "coolwarm"): 0, or -1 if unknown. */
int fct_cmap_parse(const char *name, enum fct_cmap *map);
/* The colour of t in [0, 1] (clamped; NaN gives mid grey): viridis
 * (linear between matplotlib's colours at t = 0, 1/8, ..., 1), gray (black
 * to white), coolwarm (Moreland's end colours through grey). */
void fct_cmap_color(enum fct_cmap map, double t, unsigned char rgb[3]);

/* A colour for patch label id: hues spread by the golden ratio so that
 * neighbouring labels differ, the same colour for the same id everywhere;
 * id < 0 (no patch) is light grey. */
void fct_patch_color(long id, unsigned char rgb[3]);

/* Convert any image (grey, grey+alpha, RGB, RGBA; 8 or 16 bit; PFM floats
 * taken as 0..1) to RGB U8, alpha composited over bg.  dst is set up here
 * (fct_image_free).  0 or -1. */
int fct_image_to_rgb8(const struct fct_image *src, const unsigned char bg[3],
                      struct fct_image *dst, struct fct_err *err);

/* Bilinear lookup in an RGB U8 image at texture coordinates (s, t), t
 * pointing up (s = 0 the left edge, t = 0 the bottom edge), texel centres
 * at ((i + 0.5) / W, 1 - (j + 0.5) / H), clamped at the borders.  rgb gets
 * 0..255 values. */
void fct_texture_sample(const struct fct_image *tex, double s, double t, double rgb[3]);

#endif
