/* square.h - the square [-1,1]^2 at depth z, facing -z (towards a camera at
 * the origin looking along +z), split into n x n cells of two triangles: the
 * one flat view the fusion and colouring tests share, and that camera. */
#ifndef FCT_TEST_SQUARE_H
#define FCT_TEST_SQUARE_H

#include <stdint.h>

#include "fusion/fuse.h"
#include "core/mesh.h"

static void square(struct fct_mesh *m, int n, double z)
{
	struct fct_err err;
	fct_mesh_init(m);
	for (int j = 0; j <= n; j++)
		for (int i = 0; i <= n; i++)
			fct_mesh_add_vertex(m, -1 + 2.0 * i / n, -1 + 2.0 * j / n, z, &err);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
			uint32_t t1[3] = { a, c, b }, t2[3] = { b, c, d };
			fct_mesh_add_face(m, t1, 3, &err);
			fct_mesh_add_face(m, t2, 3, &err);
		}
}

/* v: mesh m seen by a 64 x 64 pinhole (focal 32, centre 31.5) at the
 * origin looking along +z. */
static inline void view_of(struct fct_fuse_view *v, const struct fct_mesh *m)
{
	*v = (struct fct_fuse_view){ 0 };
	v->mesh = m;
	v->cam = (struct fct_camera){ FCT_CAMERA_PINHOLE, 64, 64, 32, 32, 31.5, 31.5, 0, 0 };
	v->pose[0] = v->pose[5] = v->pose[10] = 1;
}

#endif
