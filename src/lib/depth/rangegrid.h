/* rangegrid.h - the classic range-scan archives: Stanford/VRIP .conf files
 * and PLY scans with a range_grid element.
 *
 * A .conf file lists scans with their poses, one per line:
 *
 *   camera tx ty tz qx qy qz qw        (the viewer's camera; ignored)
 *   bmesh FILE tx ty tz qx qy qz qw    the scan FILE, placed in the world by
 *                                      the rotation of the conjugate of the
 *                                      unit quaternion (qx, qy, qz, qw),
 *                                      then the translation t (what puts
 *                                      the bunny scans together)
 *   mesh FILE ...                      a mesh scanalyze shows (the dragon
 *                                      archive's dragonStandRight_cybcyl,
 *                                      a file it does not hold): vrip fuses
 *                                      bmesh lines only, and so do we; the
 *                                      line is kept in skipped
 *
 * A range-grid scan (Turk's ply tools, the Stanford 3-D Scanning Repository)
 * holds its points in the scan frame as the vertex element and, as element
 * range_grid of num_cols * num_rows rows (obj_info num_cols, num_rows), a
 * list of 0 or 1 vertex index per grid cell, row by row.  The scanner looks
 * along the scan frame's -z.  Sun et al. mesh each range image the way
 * dm2mesh meshes an organised depth map: gridmesh.h in explicit-xyz mode. */
#ifndef FCT_RANGEGRID_H
#define FCT_RANGEGRID_H

#include "depth/gridmesh.h"
#include "core/mesh.h"

struct fct_conf_scan {
	char *path;              /* relative to the .conf file's folder already */
	double pose[12];         /* scan-to-world [R | t] */
	long line;               /* line of the .conf it came from */
};

/* A line read but not fused. */
struct fct_conf_skip {
	long line;
	char *text;              /* its first 80 bytes, escaped (fct_escape) */
};

struct fct_conf {
	size_t n;
	struct fct_conf_scan *scans;
	size_t nskipped;
	struct fct_conf_skip *skipped;
};

/* Read a .conf file (at most 1 MB, lines of at most 4 KB, no NUL bytes):
 * c is set up here (fct_conf_free).  Quaternions must have a norm within
 * 1e-3 of 1 and are normalised.  0 or -1 with "FILE:LINE: what", where
 * any bytes of the file are escaped. */
int fct_conf_read(struct fct_conf *c, const char *path, struct fct_err *err);
void fct_conf_free(struct fct_conf *c);

/* The depth-jump bound of a range-grid scan's mesh (gridmesh.h max_jump):
 * a face whose z changes by more than ten grid steps per step is cut. */
#define FCT_RANGE_GRID_MAX_JUMP 10

/* Mesh the range-grid scan in m (as read, with its range_grid element and
 * no faces) into out (initialised here), in the scan frame, faces oriented
 * towards the scanner (+z).  The vertices are the scan's vertices that some
 * triangle uses, in grid order, with all their properties; every comment
 * and every element but range_grid is kept.  Depth jumps are judged along z
 * with the grid's own step; p as for fct_grid_mesh (NULL: max_jump
 * FCT_RANGE_GRID_MAX_JUMP, min_faces FCT_DEFAULT_MIN_FACES).  *step gets the
 * median grid step (metres, may be NULL).  0 or -1 ("no range_grid element",
 * "range_grid cell N: vertex index out of range", ...).  tsdfuse --conf and
 * meshconv --grid both mesh scans here. */
int fct_range_grid_mesh(struct fct_mesh *out, const struct fct_mesh *m,
                        const struct fct_grid_params *p, double *step, struct fct_err *err);

#endif
