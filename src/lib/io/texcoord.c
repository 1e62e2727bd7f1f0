/* texcoord.c - texture coordinates under other programs' names (see texcoord.h). */
#include "io/texcoord.h"

#include <stddef.h>

int fct_texcoord_vertex(const struct fct_mesh *m, const struct fct_prop **s,
                        const struct fct_prop **t)
{
	static const char *const names[][2] = {
		{ "s", "t" }, { "texture_u", "texture_v" }, { "texture_s", "texture_t" }, { "u", "v" },
	};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
		const struct fct_prop *a = fct_elem_find(&m->vertex, names[i][0]);
		const struct fct_prop *b = fct_elem_find(&m->vertex, names[i][1]);
		if (a && b && a->count_type == FCT_NONE && b->count_type == FCT_NONE) {
			*s = a, *t = b;
			return 1;
		}
	}
	*s = *t = NULL;
	return 0;
}

const struct fct_prop *fct_corner_list(const struct fct_mesh *m, const char *name, unsigned dim)
{
	const struct fct_prop *p = fct_elem_find(&m->face, name);
	if (!p || p->count_type == FCT_NONE)
		return NULL;
	for (size_t f = 0; f < m->nf; f++) {
		size_t n = p->off[f + 1] - p->off[f];
		if (n && n != dim * (size_t)fct_face_size(m, f))
			return NULL;
	}
	return p;
}

const struct fct_prop *fct_texcoord_face(const struct fct_mesh *m)
{
	return fct_corner_list(m, "texcoord", 2);
}
