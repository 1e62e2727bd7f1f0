/* soup.h - a triangle soup for the BVH tests: flat position and corner
 * arrays, the form fct_bvh_build takes. */
#ifndef FCT_TEST_SOUP_H
#define FCT_TEST_SOUP_H

#include <stdint.h>
#include <stdlib.h>

struct soup {
	double *xyz;
	uint32_t *tri;
	size_t nv, ntri;
};

static void soup_alloc(struct soup *s, size_t nv, size_t ntri)
{
	s->nv = nv;
	s->ntri = ntri;
	s->xyz = malloc(sizeof *s->xyz * 3 * nv);
	s->tri = malloc(sizeof *s->tri * 3 * ntri);
	if (!s->xyz || !s->tri)
		abort();
}

static void soup_free(struct soup *s)
{
	free(s->xyz);
	free(s->tri);
}

#endif
