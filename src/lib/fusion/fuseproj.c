/* fuseproj.c - projective fusion: each candidate voxel gets the depth
 * difference along its pixel's ray (Curless and Levoy), the baseline Sun,
 * Paik, Koschan and Abidi compare true distance with (sec. 3), and the
 * way KinectFusion and Open3D fuse depth images. */
#include "fusion/fusepriv.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Voxel l of vb at camera depth `depth`, against the depth r its sample
 * holds: the depth difference, truncated in front at the band, unless r is
 * no data (INFINITY in a raster, not above 0 in a depth image; orthographic
 * depths may be) or the voxel is farther behind than the band.  1 when
 * put. */
static inline int put_depth(struct fct_voxblock *vb, int fresh, int l, float r, int ortho, double depth,
                            double band, int depth2)
{
	if (!(r < INFINITY) || !(r > 0 || ortho))
		return 0;
	double Rd = r, d = Rd - depth;
	if (d < -band)
		return 0;
	put_value(vb, fresh, l, (float)(d < band ? d : band), (float)(depth2 ? 1 / (Rd * Rd) : 1));
	return 1;
}

#if defined(__SSE2__)

/* A row of voxels seen by a pinhole, two at a time (SSE2: the division
 * and the projection were half of fuse_projective_blocks's time): the
 * operations of the scalar code below, in its order, so the same numbers
 * and samples.  Camera coordinates c0 + n step for n = first .. first +
 * cnt - 1; for each voxel its sample (sample_index; -1 outside the raster
 * or behind the camera) and its depth. */
struct pin_step {
	double step[3];          /* camera coordinates from one voxel to the next */
	double ax, bx, ay, by;   /* sample x = ax c0 / c2 + bx, likewise y */
	double wlim, hlim;       /* sample_index's bounds */
	int w;
};

static inline void pin_row(const struct pin_step *P, const double c0[3], int first, int cnt,
                           long *si, double *depth)
{
	const __m128d X0 = _mm_set1_pd(c0[0]), Y0 = _mm_set1_pd(c0[1]), Z0 = _mm_set1_pd(c0[2]);
	const __m128d SX = _mm_set1_pd(P->step[0]), SY = _mm_set1_pd(P->step[1]), SZ = _mm_set1_pd(P->step[2]);
	const __m128d half = _mm_set1_pd(0.5), mhalf = _mm_set1_pd(-0.5), one = _mm_set1_pd(1);
	const __m128d AX = _mm_set1_pd(P->ax), BX = _mm_set1_pd(P->bx), AY = _mm_set1_pd(P->ay),
	              BY = _mm_set1_pd(P->by), WL = _mm_set1_pd(P->wlim), HL = _mm_set1_pd(P->hlim);
	double dd[2];
	for (int m = 0; m < cnt; m += 2) {
		__m128d n = _mm_set_pd((double)(first + m + 1), (double)(first + m));
		__m128d cx = _mm_add_pd(X0, _mm_mul_pd(n, SX)), cy = _mm_add_pd(Y0, _mm_mul_pd(n, SY)),
		        cz = _mm_add_pd(Z0, _mm_mul_pd(n, SZ));
		__m128d iz = _mm_div_pd(one, cz);
		__m128d sx = _mm_add_pd(_mm_mul_pd(_mm_mul_pd(AX, cx), iz), BX);
		__m128d sy = _mm_add_pd(_mm_mul_pd(_mm_mul_pd(AY, cy), iz), BY);
		__m128d in = _mm_and_pd(_mm_and_pd(_mm_cmpgt_pd(cz, _mm_setzero_pd()), _mm_cmpgt_pd(sx, mhalf)),
		                        _mm_and_pd(_mm_and_pd(_mm_cmpgt_pd(sy, mhalf), _mm_cmplt_pd(sx, WL)),
		                                   _mm_cmplt_pd(sy, HL)));
		/* outside: 0 before the conversion */
		__m128i ix = _mm_cvttpd_epi32(_mm_and_pd(_mm_add_pd(sx, half), in));
		__m128i iy = _mm_cvttpd_epi32(_mm_and_pd(_mm_add_pd(sy, half), in));
		int bits = _mm_movemask_pd(in);
		_mm_storeu_pd(dd, cz);
		si[m] = bits & 1 ? (long)_mm_cvtsi128_si32(iy) * P->w + _mm_cvtsi128_si32(ix) : -1;
		depth[m] = dd[0];
		if (m + 1 < cnt) {
			si[m + 1] = bits & 2 ? (long)_mm_cvtsi128_si32(_mm_shuffle_epi32(iy, 1)) * P->w +
			                       _mm_cvtsi128_si32(_mm_shuffle_epi32(ix, 1)) : -1;
			depth[m + 1] = dd[1];
		}
	}
}
#endif

/* The voxels of blocks lo..hi, each the depth difference along its ray
 * (Curless and Levoy), truncated in front at the band; those farther
 * behind than the band are left alone.  Pinholes step along a row of
 * voxels in camera coordinates (pin_row where there is SSE2).  A block's
 * constants are in locals: its int8_t box would be loaded again after
 * every store of a float. */
void fuse_projective_blocks(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	const struct fctx *F = ctx;
	const struct raster *R = F->R;
	const struct fct_fuse_params *p = F->p;
	const float *Rz = R->depth;
	double vox = F->vox, band = p->band;
	int depth2 = p->weight == FCT_FUSE_DEPTH2 && F->v->cam.kind != FCT_CAMERA_NONE;
	const struct fct_camera *cam = &F->v->cam;
	int pin = cam->kind == FCT_CAMERA_PINHOLE, ortho = cam->kind == FCT_CAMERA_NONE;
	const double *M = R->inv;
	/* Pinholes: sensor coordinates along a row of voxels by adding a step;
	 * sample x = ax * c0 / c2 + bx (likewise y). */
	double dx[3] = { M[0] * vox, M[4] * vox, M[8] * vox };
	double ax = cam->fx * R->S, bx = (cam->cx - R->u0) * R->S;
	double ay = cam->fy * R->S, by = (cam->cy - R->v0) * R->S;
#if defined(__SSE2__)
	struct pin_step P = { { dx[0], dx[1], dx[2] }, ax, bx, ay, by, R->w - 0.5, R->h - 0.5, R->w };
#endif
	for (size_t bi = lo; bi < hi; bi++) {
		struct sblock *b = F->s->blk[bi];
		struct fct_voxblock *vb = b->vb;
		int fresh = b->fresh;
		int32_t o[3] = { b->bx * FCT_VOXBLOCK, b->by * FCT_VOXBLOCK, b->bz * FCT_VOXBLOCK };
		int lx = b->lo[0], x0 = b->lo[0], x1 = b->hi[0];
		if (p->has_clip) {   /* the clip box along x, once for the block */
			x0 = p->clip_lo[0] - o[0] > x0 ? p->clip_lo[0] - o[0] : x0;
			x1 = p->clip_hi[0] - o[0] < x1 ? p->clip_hi[0] - o[0] : x1;
		}
		size_t nvox = 0;
		for (int z = b->lo[2]; z <= b->hi[2]; z++)
			for (int y = b->lo[1]; y <= b->hi[1]; y++) {
				int32_t i0 = o[0] + lx, j = o[1] + y, k = o[2] + z;
				if (!in_clip(p, o[0] + x0, j, k))
					continue;
				double X = i0 * vox, Y = j * vox, Z = k * vox, c0[3];
				for (int a = 0; a < 3; a++)
					c0[a] = M[4 * a] * X + M[4 * a + 1] * Y + M[4 * a + 2] * Z + M[4 * a + 3];
#if defined(__SSE2__)
				if (pin && x0 <= x1) {
					long si[FCT_VOXBLOCK];
					double dep[FCT_VOXBLOCK];
					pin_row(&P, c0, x0 - lx, x1 - x0 + 1, si, dep);
					for (int xx = x0; xx <= x1; xx++) {
						long s = si[xx - x0];
						if (s >= 0)
							nvox += put_depth(vb, fresh, xx + 8 * (y + 8 * z), Rz[s], 0,
							                  dep[xx - x0], band, depth2);
					}
					continue;
				}
#endif
				for (int xx = x0; xx <= x1; xx++) {
					double sx, sy, depth;
					if (pin) {
						double n = xx - lx;
						double c[3] = { c0[0] + n * dx[0], c0[1] + n * dx[1], c0[2] + n * dx[2] };
						if (!(c[2] > 0))
							continue;
						double iz = 1 / c[2];
						sx = ax * c[0] * iz + bx;
						sy = ay * c[1] * iz + by;
						depth = c[2];
					} else {
						double x[3] = { (o[0] + xx) * vox, Y, Z };
						if (!sample_of(R, x, &sx, &sy, &depth))
							continue;
					}
					long si = sample_index(R, sx, sy);
					if (si >= 0)
						nvox += put_depth(vb, fresh, xx + 8 * (y + 8 * z), Rz[si], ortho, depth,
						                  band, depth2);
				}
			}
		b->nvox += nvox;
	}
}
