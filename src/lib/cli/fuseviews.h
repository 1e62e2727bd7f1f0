/* fuseviews.h - tsdfuse's views, read one at a time: meshes carrying their
 * camera and pose comments, depth images with the camera and poses of the
 * options (fuseopts.h, poses.h), and the range-grid scans of a .conf file.
 * Each is loaded, used and freed before the next, so that memory is bounded
 * by the volume, not by the number of views, in as many passes as the
 * program needs.
 *
 * Like cli.h this is command-line layer, for mains only: a view that cannot
 * be read or fused prints "prog: VIEW: what" and exits 1, a mismatch of
 * operands and options (depth images without --poses) is a usage error. */
#ifndef FCT_FUSEVIEWS_H
#define FCT_FUSEVIEWS_H

#include "fusion/fuse.h"
#include "cli/fuseopts.h"
#include "core/mesh.h"
#include "depth/rangegrid.h"

/* The depth image at path into img, decoded by dp->code, and cam the depth
 * camera dcam sized to it (exit 1 when it cannot be read or decoded, or is
 * not the camera's size); with may_warn, a warning when its depths are
 * implausible for the camera (a wrong depth scale): 1 when it warned. */
int fct_fuse_read_depth(struct fct_image *img, struct fct_camera *cam, const char *path,
                        const struct fct_camera *dcam, const struct fct_depth_params *dp, int may_warn);

/* One view in memory: its mesh, camera and pose; its colour image when
 * asked for (malloc'd path, NULL for none); for a depth image fused with
 * --projective the depths of its mesh's pixels (view.depth). */
struct fct_fuse_input {
	struct fct_mesh mesh;
	struct fct_fuse_view view;
	char name[512];
	int depth_image;
	char *image;
	float *depth;
};

struct fct_fuse_views {
	const struct fct_fuse_opts *o;
	char **paths;             /* the operands: meshes and depth images */
	size_t npaths;
	const struct fct_conf *conf;   /* and the .conf's scans after them */
	int color;                /* find each view's colour image */
	const struct fct_camera *dcam;          /* the depth images' camera */
	const struct fct_depth_params *dp;      /* and depth parameters */
	size_t n;                 /* views: the operands, then the .conf's scans */
	size_t *image;            /* per view: 1 + its --image, 0 for none */
	size_t *depth;            /* per view: 1 + its place among the depth images, 0 for none */
	size_t ndepth;
	double *dposes;           /* 12 per depth image */
	double read_s;            /* time spent reading the views */
};

/* The views of the operands paths[0..npaths) and conf's scans: the depth
 * images among the operands (told by content) get the --image files in
 * order and their poses from --poses (fct_frame_poses; -v reports how they
 * matched).  Exit 2 when they do not fit the options. */
void fct_fuse_views_init(struct fct_fuse_views *vs, const struct fct_fuse_opts *o, char **paths,
                         size_t npaths, const struct fct_conf *conf, int color,
                         const struct fct_camera *dcam, const struct fct_depth_params *dp);
void fct_fuse_views_free(struct fct_fuse_views *vs);

/* View i read into in (every field set here): a scan meshed and moved by
 * its .conf pose, a depth image smoothed and meshed with its noise model, a
 * mesh with its camera and pose checked.  Exit 1 on a view that cannot be
 * read, or that has no faces or a vertex that is not finite. */
void fct_fuse_input_open(struct fct_fuse_views *vs, size_t i, struct fct_fuse_input *in);
void fct_fuse_input_close(struct fct_fuse_input *in);

/* A view that changed no voxel: a warning that says why where it can. */
void fct_fuse_input_warn_unused(const struct fct_fuse_input *in, int has_bbox);

/* The noise of the fused surface out as its vertex property sigma
 * (viewcolor.h's fct_viewnoise): the n depth images depth[0..n) at poses
 * (12 numbers each), read with dcam and dp, under dp's sensor noise model,
 * seen as they are (fct_range_image_depth) with o's band, weight and voxel;
 * the level from out's own residuals (noise.h's fct_noise_estimate), a
 * floor of a twentieth of a voxel (the volume's own error).  0, or
 * -1 with nothing written (segplanes then estimates one figure) when the
 * noise is unknown or none (exact data, whose fused error is the volume's)
 * or out has too few neighbourhoods to estimate the level.  *seen gets the
 * vertices some view saw (the others have the median), *level the level
 * (0 when nothing was written). */
int fct_fuse_depth_sigma(struct fct_mesh *out, const char *const *depth, const double *pose, size_t n,
                         const struct fct_camera *dcam, const struct fct_depth_params *dp,
                         const struct fct_fuse_opts *o, size_t *seen, double *level);

/* The views' extent: the box of their vertices and their area. */
struct fct_fuse_extent {
	double lo[3], hi[3], area;
	size_t n;
};

void fct_fuse_extent_init(struct fct_fuse_extent *e);
void fct_fuse_extent_add(struct fct_fuse_extent *e, const struct fct_mesh *m);

/* Voxel indices from the origin each way (fuse.c's 21-bit block keys). */
#define FCT_FUSE_VOXEL_RANGE (1 << 23)

/* The machine's memory in bytes (4e9 when the system does not say). */
double fct_fuse_machine_bytes(void);

/* The voxels of size vox that views of extent e reach with a band of half
 * width band (within the box bbox, x0,y0,z0,x1,y1,z1, when not NULL),
 * clo..chi, and the bytes the volume needs for them: the band around their
 * surface in blocks (at most their box's), and with carve the carving
 * bitsets.  Exit 1 when that is more than the machine has, or when the
 * voxels overflow the volume's indices (saying whether the views' span or
 * their offset is beyond). */
double fct_fuse_extent_volume(const struct fct_fuse_extent *e, double vox, double band,
                              const double *bbox, int carve, int32_t clo[3], int32_t chi[3]);

/* --color: each vertex of out gets the weighted average colour of the
 * views that see it (viewcolor.h), grey 128 when none does, *ncolor the
 * views that had a colour image.  The views are read again, one with its
 * range image and colour image at a time; -v reports per view and the
 * figures. */
void fct_fuse_views_color(struct fct_fuse_views *vs, struct fct_mesh *out, size_t *ncolor);

#endif
