/* depthcode.h - depth images whose integer samples are not plain depth:
 * the encodings of datasets that store their frames otherwise.
 *
 * A depth image is decoded once, right after it is read and before
 * anything looks at its samples; what comes out is a plain depth image
 * that the depth parameters (units per metre, disparity) then read as any
 * other.  Codes combine, applied in this order:
 *   swap        16-bit samples in the other byte order: NYU Depth v2's raw
 *               PGMs are written little-endian, against the format;
 *   rotate      SUN RGB-D's PNGs, whose millimetres are stored with their
 *               16 bits rotated left by 3: depth = (s >> 3 | s << 13) & 0xffff;
 *   kinect-raw  a Kinect v1's raw disparity codes (0-2047, 2047 no data), as
 *               NYU Depth v2 stores them: depth = 351.3 / (1092.5 - s) metres
 *               (NYU's toolbox), codes at or beyond 1092 no data; the image
 *               becomes float metres.
 * The dataset names: nyu = swap,kinect-raw; sun = rotate. */
#ifndef FCT_DEPTHCODE_H
#define FCT_DEPTHCODE_H

#include "core/err.h"
#include "io/image.h"

enum {
	FCT_DEPTH_SWAP = 1,
	FCT_DEPTH_ROTATE = 2,
	FCT_DEPTH_KINECT_RAW = 4,
};

/* The codes of a comma-separated list of the names above (and "none"):
 * 0 and *code set, or -1 with the name not known in err. */
int fct_depth_code_parse(const char *list, unsigned *code, struct fct_err *err);

/* The names fct_depth_code_parse takes, blank-separated, for messages. */
const char *fct_depth_code_names(void);

/* The code a dataset's camera name (-K) implies: nyu's; 0 for the others. */
unsigned fct_depth_code_named(const char *camera_name);

/* Decode img in place by code: a code needs a one-channel 16-bit image
 * (-1 and why in err otherwise); kinect-raw replaces img's samples by float
 * metres.  0 does nothing. */
int fct_depth_decode(struct fct_image *img, unsigned code, struct fct_err *err);

#endif
