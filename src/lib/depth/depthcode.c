/* depthcode.c - dataset depth encodings decoded (see depthcode.h). */
#include "depth/depthcode.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const struct {
	const char *name;
	unsigned code;
} code_names[] = {
	{ "none", 0 },
	{ "swap", FCT_DEPTH_SWAP },
	{ "rotate", FCT_DEPTH_ROTATE },
	{ "kinect-raw", FCT_DEPTH_KINECT_RAW },
	{ "nyu", FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW },
	{ "sun", FCT_DEPTH_ROTATE },
};

const char *fct_depth_code_names(void)
{
	return "none swap rotate kinect-raw nyu sun";
}

int fct_depth_code_parse(const char *list, unsigned *code, struct fct_err *err)
{
	*code = 0;
	const char *p = list;
	for (;;) {
		size_t n = strcspn(p, ",");
		size_t i = 0, count = sizeof code_names / sizeof *code_names;
		while (i < count && !(strlen(code_names[i].name) == n && !strncmp(code_names[i].name, p, n)))
			i++;
		if (i == count)
			return fct_fail(err, "\"%.*s\" is not a depth code (%s)", (int)n, p,
			                fct_depth_code_names());
		*code |= code_names[i].code;
		if (!p[n])
			return 0;
		p += n + 1;
	}
}

unsigned fct_depth_code_named(const char *camera_name)
{
	return camera_name && !strcmp(camera_name, "nyu") ? FCT_DEPTH_SWAP | FCT_DEPTH_KINECT_RAW : 0;
}

/* NYU Depth v2's toolbox (depth_rel2depth_abs): metres from a Kinect v1's
 * raw disparity code. */
#define KINECT_RAW_NUMERATOR 351.3
#define KINECT_RAW_OFFSET 1092.5
/* Codes from here on (2047 among them) would put the surface beyond 350 m. */
#define KINECT_RAW_NO_DATA 1092

int fct_depth_decode(struct fct_image *img, unsigned code, struct fct_err *err)
{
	if (!code)
		return 0;
	if (img->channels != 1 || img->type != FCT_PIX_U16)
		return fct_fail(err, "a depth code needs a one-channel 16-bit image, not %d channel%s of %s",
		                img->channels, img->channels > 1 ? "s" : "", fct_pix_name(img->type));
	size_t n = fct_image_samples(img);
	uint16_t *s = img->data;
	if (code & FCT_DEPTH_SWAP)
		for (size_t i = 0; i < n; i++)
			s[i] = (uint16_t)(s[i] >> 8 | s[i] << 8);
	if (code & FCT_DEPTH_ROTATE)
		for (size_t i = 0; i < n; i++)
			s[i] = (uint16_t)(s[i] >> 3 | s[i] << 13);
	if (code & FCT_DEPTH_KINECT_RAW) {
		float *m = malloc(n * sizeof *m);
		if (!m)
			return fct_fail(err, "out of memory (%zu bytes for the depths)", n * sizeof *m);
		for (size_t i = 0; i < n; i++)
			m[i] = s[i] < KINECT_RAW_NO_DATA ? (float)(KINECT_RAW_NUMERATOR / (KINECT_RAW_OFFSET - s[i])) : 0;
		free(img->data);
		img->data = m;
		img->type = FCT_PIX_F32;
	}
	return 0;
}
