/* viewtex.h - texture a mesh from registered colour photographs: one photo
 * per face, chosen by a graph cut, the faces' texture packed into atlas
 * images, the colour levelled across the seams.  Waechter, Moehrle and
 * Goesele, "Let There Be Color! Large-Scale Texturing of 3D
 * Reconstructions" (ECCV 2014) is the method; Kang, Johnson and Szeliski
 * (DEC CRL 95/7) sec. 9 name it as the step after their planar models, and
 * sec. 6-7 texture each face from the one image in which it lies whole.
 *
 * 1. Candidates (fct_viewtex_add_view, one photo at a time).  The mesh is
 *    rasterised into the photo's camera (raster.h): the visibility buffer
 *    tells, per pixel, the face the photo sees there.  A photo is a
 *    candidate for a face in front of it that it sees some of: its
 *    visible fraction is the face's visible pixels over its projected area
 *    (a face under 8 pixels: whether nothing of the mesh lies in front of
 *    its centre, by more than depth_tol of its depth).  Its quality is the
 *    sum over those pixels of (gradient magnitude + 4 levels) x (distance
 *    weight), times the cosine of the viewing angle and the visible
 *    fraction squared: the gradient magnitude integral of Waechter et al.
 *    (large, close, sharp views win), pixels within edge_px of a depth edge
 *    of the mesh or of the picture's border weighing (1 + d) / (1 +
 *    edge_px).  A view more oblique than acos(min_cos) or seeing under 60%
 *    of the face is a last resort (quality x 1e-3).  Each face keeps its
 *    best `candidates` photos, with the mean colour of its visible pixels.
 * 2. Photometry (fct_viewtex_label, level >= 1): a gain per photo and
 *    channel (exposure, white balance) that makes the faces' mean colours
 *    agree across photos, alternating between each face's consensus colour
 *    (Huber-weighted) and each photo's least-squares gain, the gains then
 *    scaled so that the texture keeps the photos' mean level.  Only photos
 *    that see a face whole (90%, 16 pixels or more) speak for its colour.
 *    Choosing one photo per face, a photo whose corrected colour of such a
 *    face lies more than 40 levels from the consensus of three or more is
 *    dropped (the photo-consistency check of Waechter et al.: something the
 *    mesh does not hold stood in front of the face, or it is misregistered).
 * 3. Labels: E = sum_f A_f (1 - q_f(l) / max q_f) + smooth * sum_{f~g}
 *    L_fg [l_f != l_g], with A_f the face's largest projected area and L_fg
 *    the shared edge's length, both in pixels of the faces' best photos: a
 *    seam costs `smooth` per pixel of its length, a worse photo its loss of
 *    quality over the face's area.  Minimised by alpha-expansion
 *    (graphcut.h), started from each face's best photo.
 * 4. Charts (fct_viewtex_layout): connected faces with the same photo
 *    (and, with rectify, the same planar patch) form a chart.  A chart is
 *    parametrised by its photo's projection at texel_scale texels per
 *    pixel; a chart on a planar patch (face property patch, element plane)
 *    whose faces lie within 25 degrees of the plane is parametrised in the
 *    plane's own frame instead, metric and undistorted, at the photo's
 *    finest resolution over the chart (focal length over the depth of the
 *    nearest face, times texel_scale).  Each chart is turned so that its
 *    principal axis runs along the rows, gets `padding` texels on every
 *    side, and the charts are packed on shelves (tallest first) into square
 *    power-of-two pages no larger than atlas_max (the last page shortened
 *    to the power of two that holds it), at most max_pages of them: the
 *    texel scale shrinks until they fit; a chart larger than a page is
 *    drawn smaller.  Faces no photo sees share one block of the fill colour.
 * 5. Texels (fct_viewtex_sample_view, one photo at a time): each chart's
 *    faces are rasterised into its place in the atlas (raster.h again, at
 *    flat depth), every texel's barycentrics give its 3-D point, the point
 *    is projected into the chart's photo and sampled bilinearly, so the
 *    texture is right under any parametrisation.  A texel the chart's photo
 *    does not see (outside it, or hidden by the mesh) takes the mean of the
 *    face's other candidate photos that see it, each weighed by its
 *    resolution there (the square root of its projected area over the
 *    largest of the face's candidates'); with blend, every texel does (all
 *    its face's candidates that see it, each after its gain).
 *    Seam edges are sampled in both photos along their length.
 * 6. Levelling and padding (fct_viewtex_finish): the gains; with level 2
 *    (one photo per face) Waechter et al.'s global seam levelling: an
 *    offset per vertex and chart, interpolated over the faces, that makes
 *    the two sides of each seam sample agree, varies smoothly inside charts
 *    and is held towards 0 (least squares by conjugate gradients), from the
 *    seam samples where both photos are flat (texture edges that the two
 *    photos place apart on imperfect geometry are not exposure), iteratively
 *    reweighted (Huber, cut at three times).  Then the padding: texels
 *    beside a chart take the mean of their filled neighbours, `padding`
 *    rings deep, each ring reading only the rings before it.
 *
 * Baking (fct_viewtex_layout_bake, fct_viewtex_bake) textures a mesh
 * whose colour is known at every point, without photos, through the same
 * charts, pages, padding and mapping (steps 4 and 6; colbake.h).
 *
 * Memory is bounded by the mesh (candidates per face, charts, seams) and
 * the atlas pages (4 bytes a texel, and 17 more while sampling; at most
 * 2^29 texels in all); one photo is held at a time.  The same inputs give the same texture, bit for bit. */
#ifndef FCT_VIEWTEX_H
#define FCT_VIEWTEX_H

#include <stddef.h>
#include <stdint.h>

#include "io/camera.h"
#include "core/err.h"
#include "io/image.h"
#include "core/mesh.h"
#include "render/photo.h"

struct fct_viewtex_params {
	double smooth;        /* seam cost per pixel of seam, in pixels of area (default 10) */
	double min_cos;       /* most oblique view accepted, cosine (default 0.1) */
	double depth_tol;     /* occlusion test, relative depth (default 0.02) */
	double edge_px;       /* falloff near depth edges and borders, pixels (default 8) */
	double texel_scale;   /* texels per photo pixel, at most 4 (default 1) */
	int padding;          /* texels around each chart (default 4) */
	int atlas_max;        /* largest page side, a power of two in [64, 16384] (default 4096) */
	int max_pages;        /* (default 16); pages x atlas_max^2 at most 2^29 texels */
	int level;            /* 0 none, 1 a gain per photo, 2 and seam levelling (default 2) */
	int rectify;          /* planar patches in their plane's frame (default 1) */
	int candidates;       /* photos kept per face, 1 to 32 (default 6) */
	int blend;            /* texels the weighted mean of the face's candidates (default 0: its one photo) */
	int max_cycles;       /* alpha-expansion cycles (default 8) */
	uint8_t fill[3];      /* colour of faces no photo sees (default 128 128 128) */
};

void fct_viewtex_params_default(struct fct_viewtex_params *p);

struct fct_viewtex_stats {
	size_t faces;
	size_t unseen;            /* faces no photo sees (fill colour) */
	size_t candidates;        /* (face, photo) pairs kept */
	size_t outliers;          /* candidates dropped by the photo-consistency check */
	size_t views_used;        /* photos that texture some face */
	size_t charts, rectified; /* charts, and those in their plane's frame */
	size_t seam_edges;        /* edges between charts */
	int cycles;               /* alpha-expansion cycles run */
	double energy_start, energy;
	size_t pages;
	int page_width, page_height;   /* of the first page */
	double fill_ratio;        /* texels of faces over the pages' texels */
	double scale;             /* texel scale used */
	double seam_rms_before;   /* RMS colour difference of the flat seam samples, levels */
	double seam_rms_after;    /* the same after levelling */
};

struct fct_viewtex;

/* A texturer of m (kept by pointer: it must outlive the texturer and keep
 * its faces and vertices until fct_viewtex_apply) from nviews photos.
 * Fails (message set) on a mesh without faces, a non-finite vertex, more
 * than 2^31 faces or photos, bad parameters, out of memory. */
struct fct_viewtex *fct_viewtex_new(const struct fct_mesh *m, size_t nviews,
                                    const struct fct_viewtex_params *p, struct fct_err *err);
void fct_viewtex_free(struct fct_viewtex *T);

/* Step 1 for photo k (each k once, any order): cam a pinhole of rgb's
 * size, pose camera-to-world, rgb RGB U8.  *seen (may be NULL) gets the
 * faces it is a candidate for.  0 or -1. */
int fct_viewtex_add_view(struct fct_viewtex *T, size_t k, const struct fct_camera *cam,
                         const double pose[12], const struct fct_image *rgb, size_t *seen,
                         struct fct_err *err);

/* Steps 2-4, after every photo was added.  0 or -1. */
int fct_viewtex_label(struct fct_viewtex *T, struct fct_err *err);
int fct_viewtex_layout(struct fct_viewtex *T, struct fct_err *err);

/* Faces textured from photo k (after labelling). */
size_t fct_viewtex_view_faces(const struct fct_viewtex *T, size_t k);
/* Must photo k be sampled (step 5)?  It textures faces, or is a candidate
 * of some. */
int fct_viewtex_needs_view(const struct fct_viewtex *T, size_t k);
/* The photo face f is textured from (after labelling), -1 for none. */
int32_t fct_viewtex_face_photo(const struct fct_viewtex *T, size_t f);
/* Photo k's gain per channel (after labelling; 1 without levelling). */
void fct_viewtex_photo_gain(const struct fct_viewtex *T, size_t k, double gain[3]);

/* Step 5 for photo k (the same image as was added), for every photo that
 * fct_viewtex_needs_view.  0 or -1. */
int fct_viewtex_sample_view(struct fct_viewtex *T, size_t k, const struct fct_image *rgb,
                            struct fct_err *err);

/* Step 6.  0 or -1. */
int fct_viewtex_finish(struct fct_viewtex *T, struct fct_err *err);

/* The atlas pages (RGB U8), after finish. */
size_t fct_viewtex_npages(const struct fct_viewtex *T);
const struct fct_image *fct_viewtex_page(const struct fct_viewtex *T, size_t i);

/* Write the mapping into m (the mesh given to new): texture coordinates
 * per corner (texmap.h: face lists with per_face, else vertex s t with
 * vertices copied at chart borders), texnumber the page, and TextureFile
 * comments names[0 .. npages) replacing any there.  0 or -1. */
int fct_viewtex_apply(struct fct_viewtex *T, struct fct_mesh *m, char *const *names, int per_face,
                      struct fct_err *err);

/* Baking: the texture of a surface whose colour is known at every point
 * (a denser coloured mesh's, colbake.h), without photos; T made with
 * nviews 0.  Steps 3-4: a face's chart key is the axis (+-x, +-y, +-z)
 * nearest its normal, or its planar patch plane's when it lies within 25
 * degrees of the plane; connected faces of one key (and patch) form a
 * chart, parametrised in its plane's frame, else projected along its axis
 * (which all its faces' normals lie within 55 degrees of), at
 * texels_per_metre times texel_scale, the scale shrunk until the pages fit
 * as above.  0 or -1. */
int fct_viewtex_layout_bake(struct fct_viewtex *T, double texels_per_metre, struct fct_err *err);

/* The colour (RGB, 0-255) at point x of face `face`, for a bake; called
 * from several threads at once, so it may only read ctx. */
typedef void fct_viewtex_colour_fn(const void *ctx, size_t face, const double x[3], double rgb[3]);

/* Step 5 of a bake: every texel of every chart gets fn's colour at its 3-D
 * point, fn called on nthreads threads (fct_par_threads: 0 one per
 * processor); the pages are the same whatever the thread count.  Then
 * fct_viewtex_finish pads the charts.  0 or -1. */
int fct_viewtex_bake(struct fct_viewtex *T, fct_viewtex_colour_fn *fn, const void *ctx, int nthreads,
                     struct fct_err *err);

void fct_viewtex_get_stats(const struct fct_viewtex *T, struct fct_viewtex_stats *st);

/* Step 1 for the photos ph[0..n) (photo.h; photo k is view k), each read
 * (fct_photo_read, sides to 16384) and added in turn, one held at a time:
 * seen[k] (seen may be NULL) the faces photo k is a candidate for.  0 or
 * -1 ("PATH: ..."). */
int fct_viewtex_add_photos(struct fct_viewtex *T, const struct fct_photo *ph, size_t n, size_t *seen,
                           struct fct_err *err);
/* Step 5 for the photos ph[0..n) that fct_viewtex_needs_view, read again
 * one at a time.  0 or -1 ("PATH: ..."). */
int fct_viewtex_sample_photos(struct fct_viewtex *T, const struct fct_photo *ph, size_t n,
                              struct fct_err *err);

/* The atlas pages' file names beside model: name.obj -> name_atlas0.png,
 * name_atlas1.png, ... (n of them, malloc'd, as is the array), or NULL
 * (out of memory).  Free with fct_viewtex_page_names_free. */
char **fct_viewtex_page_names(const char *model, size_t n, struct fct_err *err);
void fct_viewtex_page_names_free(char **names, size_t n);

#endif
