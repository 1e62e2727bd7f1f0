/* noisy_view.h - a view of an mkscene scene as its depth image with a
 * sensor's noise (scene.h's simulation), the depth images the noise tests
 * of depthmesh and of the noise estimator mesh. */
#ifndef FCT_TEST_NOISY_VIEW_H
#define FCT_TEST_NOISY_VIEW_H

#include <stdlib.h>
#include <string.h>

#include "io/image.h"
#include "scene/scene.h"

/* The depth image of a view of s with the noise of `sensor` after `jitter`
 * pixels of lateral noise, as mkscene writes it (float), and the depths
 * sampled before the noise; both allocated here; aborts on failure. */
static void noisy_view(const struct fct_scene *s, const struct fct_camera *cam, const double pose[12],
                       const struct fct_noise *sensor, double jitter, double **sampled,
                       struct fct_image *img)
{
	struct fct_err err;
	struct fct_render r;
	if (fct_scene_render(s, cam, pose, &r, &err))
		abort();
	size_t n = (size_t)cam->width * (size_t)cam->height;
	double *jit = malloc(n * sizeof *jit), *noisy = malloc(n * sizeof *noisy);
	if (!jit || !noisy || fct_scene_render_jitter(s, cam, pose, jitter, 1, 0, jit, &err))
		abort();
	struct fct_scene_noise nz;
	memset(&nz, 0, sizeof nz);
	nz.grazing = 90;
	nz.sensor = *sensor;
	fct_depth_noise(&nz, 1, 0, r.depth, jit, r.cosine, noisy, n, NULL);
	if (fct_image_alloc(img, cam->width, cam->height, 1, FCT_PIX_F32, &err))
		abort();
	for (size_t i = 0; i < n; i++)
		((float *)img->data)[i] = (float)noisy[i];
	*sampled = jit;
	fct_render_free(&r);
	free(noisy);
}

#endif
