/* poses.h - camera trajectories as RGB-D datasets ship them, read into
 * camera-to-world poses and matched to their depth frames.
 *
 * Every pose is camera-to-world, a row-major 3x4 [R | t] (camera.h), the
 * camera frame OpenCV's (x right, y down, z forward), as these formats
 * store them (detected from the content, '#' lines and blank lines aside):
 *
 *   TUM RGB-D trajectory   "timestamp tx ty tz qx qy qz qw" per line (the
 *                          optical centre and a unit quaternion), matched
 *                          to depth frames by the timestamps in their names
 *   Redwood / Open3D .log  per frame a line of 3 integers (ids, ignored),
 *                          then the 4x4 matrix on 4 lines
 *   KITTI odometry poses   12 numbers per line: the 3x4 [R | t] row by row
 *   stacked 4x4 matrices   4 lines of 4 numbers per pose (last row 0 0 0 1),
 *                          or 16 numbers per line
 *   one pose               a 4x4 or 3x4 matrix in any layout, or a pose line
 *                          (fct_pose_read_file): 7-Scenes' and ScanNet's
 *                          frame-NNNNNN.pose.txt, dm2mesh --pose
 *
 * Lines are read with the shared reader (reader.h): NUL bytes are refused
 * as binary data, and an endless stream ends at its 16 MB line limit. */
#ifndef FCT_POSES_H
#define FCT_POSES_H

#include <stddef.h>

#include "core/err.h"

enum fct_traj_format {
	FCT_TRAJ_POSE,          /* one pose */
	FCT_TRAJ_TUM,
	FCT_TRAJ_LOG,
	FCT_TRAJ_KITTI,
	FCT_TRAJ_STACKED,
};

struct fct_trajectory {
	enum fct_traj_format format;
	size_t n;
	double *pose;           /* 12 per pose */
	double *stamp;          /* TUM: n timestamps (seconds); NULL otherwise */
};

/* "a pose", "a TUM trajectory", "a Redwood .log trajectory", "KITTI poses",
 * "stacked 4x4 matrices": for messages. */
const char *fct_traj_format_name(enum fct_traj_format f);

/* Read the poses of path (any format above) into tr (fct_trajectory_free).
 * Every R must be a rotation (to 1e-3; TUM quaternions are normalised when
 * their norm is within 1e-2 of 1).  0, or -1 with "FILE:LINE: what". */
int fct_trajectory_read(struct fct_trajectory *tr, const char *path, struct fct_err *err);
void fct_trajectory_free(struct fct_trajectory *tr);

/* The timestamp in a TUM frame's name ("depth/1305031102.160407.png": a
 * number, then a dot and an extension): 1 and *stamp, or 0. */
int fct_path_stamp(const char *path, double *stamp);
/* The frame number in a name: its last run of digits ("frame-000050.depth.png"
 * 50, "000010.png" 10): 1 and *number, or 0 (none, or over 2^53). */
int fct_path_frame_number(const char *path, size_t *number);

/* For each of the n stamps, the pose of tr (which has stamps) nearest in
 * time, no further than max_diff seconds (TUM's associate.py, default 0.02):
 * index[i], or (size_t)-1 when none is that near.  Ties go to the earlier
 * line.  associate.py pairs one to one, greedily by difference; the
 * nearest is the same whenever the trajectory is denser than the frames,
 * as ground truth is (100 Hz against 30), and needs no n x m pairs.
 * Returns the largest difference matched (0 when none). */
double fct_trajectory_associate(size_t *index, const struct fct_trajectory *tr,
                                const double *stamps, size_t n, double max_diff);

/* How fct_frame_poses matched frames to poses. */
enum fct_pose_match { FCT_MATCH_FILES, FCT_MATCH_ORDER, FCT_MATCH_STAMP, FCT_MATCH_NUMBER };

struct fct_frame_poses_stats {
	enum fct_traj_format format;   /* of the one file (FCT_TRAJ_POSE for a file per frame) */
	size_t poses;                  /* poses the file(s) hold */
	enum fct_pose_match match;
	double max_diff;               /* FCT_MATCH_STAMP: the largest difference matched (s) */
};

/* The camera-to-world pose of each of the nframes depth frames (named by
 * their paths, in order) from the nfiles pose files, into poses (12 per
 * frame):
 *   - one file per frame, each holding one pose (FCT_MATCH_FILES);
 *   - one file holding as many poses as there are frames: in order
 *     (FCT_MATCH_ORDER; for a TUM trajectory only when no frame's name
 *     carries a timestamp);
 *   - one TUM trajectory and frames named by their timestamps: the nearest
 *     pose within max_diff seconds (FCT_MATCH_STAMP);
 *   - one file of more poses than frames, each frame's name carrying its
 *     number (frame-000050.depth.png: pose 50) (FCT_MATCH_NUMBER).
 * A mismatch is refused with what was found ("5 depth frames but traj.log
 * holds 3 poses (a Redwood .log trajectory)").  stats may be NULL.  0 or
 * -1. */
int fct_frame_poses(double *poses, struct fct_frame_poses_stats *stats,
                    const char *const *files, size_t nfiles,
                    const char *const *frames, size_t nframes, double max_diff,
                    struct fct_err *err);

#endif
