/* levelset.c - a level-set mean-curvature flow on a fused volume, the
 * last step of Sun, Paik, Koschan and Abidi's fusion (sec. 3): small
 * outlier blobs shrink and vanish while large surfaces barely move (see
 * fct_curvature_flow in fuse.h). */
#include "fusion/fuse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int fct_curvature_flow(struct fct_voxgrid *g, int iters, double band, struct fct_err *err)
{
	size_t nb = fct_voxgrid_count(g);
	double h = fct_voxgrid_voxel(g), dt = h * h / 8;
	float *out = fct_alloc_array(nb, FCT_VOXBLOCK_N * sizeof *out, err);
	float *halo = fct_alloc_array(1000, sizeof *halo, err);
	if (!out || !halo) {
		free(out);
		free(halo);
		return -1;
	}
	for (int it = 0; it < iters; it++) {
		for (size_t bi = 0; bi < nb; bi++) {
			const struct fct_voxblock *b = fct_voxgrid_at(g, bi);
			/* The block with a one-voxel halo; unobserved = NaN. */
			for (int z = -1; z <= 8; z++)
				for (int y = -1; y <= 8; y++)
					for (int x = -1; x <= 8; x++) {
						int ox = x < 0 ? -1 : x > 7, oy = y < 0 ? -1 : y > 7, oz = z < 0 ? -1 : z > 7;
						const struct fct_voxblock *nbk = b;
						if (ox || oy || oz)
							nbk = fct_voxgrid_block(g, b->bx + ox, b->by + oy, b->bz + oz, 0, NULL);
						int l = (x - 8 * ox) + 8 * ((y - 8 * oy) + 8 * (z - 8 * oz));
						halo[(x + 1) + 10 * ((y + 1) + 10 * (z + 1))] =
						        nbk && nbk->weight[l] > 0 ? nbk->sdf[l] : NAN;
					}
			for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
				int x = l % 8 + 1, y = l / 8 % 8 + 1, z = l / 64 + 1;
				const float *h0 = &halo[x + 10 * (y + 10 * z)];
				out[bi * FCT_VOXBLOCK_N + (size_t)l] = b->sdf[l];
				if (!(b->weight[l] > 0))
					continue;
				/* Unobserved neighbours mirror the voxel (no flux across
				 * the edge of the data), so open borders stay put. */
				float cc[27];
				for (int dz = -1; dz <= 1; dz++)
					for (int dy = -1; dy <= 1; dy++)
						for (int dx = -1; dx <= 1; dx++) {
							float w = h0[dx + 10 * dy + 100 * dz];
							cc[13 + dx + 3 * dy + 9 * dz] = isnan(w) ? h0[0] : w;
						}
				const float *c = &cc[13];
				const int X = 1, Y = 3, Z = 9;
				double fx = (c[X] - c[-X]) / (2 * h), fy = (c[Y] - c[-Y]) / (2 * h),
				       fz = (c[Z] - c[-Z]) / (2 * h);
				double fxx = (c[X] - 2 * c[0] + c[-X]) / (h * h), fyy = (c[Y] - 2 * c[0] + c[-Y]) / (h * h),
				       fzz = (c[Z] - 2 * c[0] + c[-Z]) / (h * h);
				double fxy = (c[X + Y] - c[X - Y] - c[Y - X] + c[-X - Y]) / (4 * h * h);
				double fxz = (c[X + Z] - c[X - Z] - c[Z - X] + c[-X - Z]) / (4 * h * h);
				double fyz = (c[Y + Z] - c[Y - Z] - c[Z - Y] + c[-Y - Z]) / (4 * h * h);
				double g2 = fx * fx + fy * fy + fz * fz;
				double num = fxx * (fy * fy + fz * fz) + fyy * (fx * fx + fz * fz) +
				             fzz * (fx * fx + fy * fy) - 2 * (fx * fy * fxy + fx * fz * fxz + fy * fz * fyz);
				/* Where the gradient vanishes (the centre of a blob
				 * shrunk to a voxel, flat truncated regions) the
				 * flow is undefined: fall back on diffusion, which
				 * lifts an isolated minimum and leaves flat regions. */
				double nv = c[0] + dt * (g2 > 1e-6 ? num / g2 : (fxx + fyy + fzz) / 2);
				out[bi * FCT_VOXBLOCK_N + (size_t)l] = (float)(nv > band ? band : nv < -band ? -band : nv);
			}
		}
		for (size_t bi = 0; bi < nb; bi++)
			memcpy(fct_voxgrid_at(g, bi)->sdf, &out[bi * FCT_VOXBLOCK_N], sizeof(float) * FCT_VOXBLOCK_N);
	}
	free(out);
	free(halo);
	return 0;
}
