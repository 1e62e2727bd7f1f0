/* tripatch.c - patch boundary polygons ordered, mapped to 2-D and
 * triangulated (Kang, Johnson, Szeliski, DEC CRL 95/7, section 4); see
 * tripatch.h. */
#include "planar/tripatch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"
#include "io/header.h"
#include "geom/planes.h"
#include "planar/chain.h"

static void mark_unclean(const struct fct_tripatch_params *p, int32_t patch, size_t nplanes)
{
	if (p->unclean && patch >= 0 && (size_t)patch < nplanes)
		p->unclean[patch] = 1;
}

void fct_tripatch_params_default(struct fct_tripatch_params *p)
{
	memset(p, 0, sizeof *p);
	p->method = FCT_POLYTRI_GREEDY;
}

/* One directed boundary edge of a patch: a -> b with the patch on the left. */
struct hedge {
	int32_t patch;
	uint32_t a, b;
};

static int hedge_cmp(const void *pa, const void *pb)
{
	const struct hedge *x = pa, *y = pb;
	if (x->patch != y->patch)
		return x->patch < y->patch ? -1 : 1;
	if (x->a != y->a)
		return x->a < y->a ? -1 : 1;
	if (x->b != y->b)
		return x->b < y->b ? -1 : 1;
	return 0;
}

/* Growable arrays of the per-patch work and the output. */
struct work {
	struct fct_err *err;
	size_t nplanes;          /* of the plane element, for the unclean flags */
	/* the patch: local vertices gl[0..nl) (global ids), loc[global] = local */
	int32_t *loc;
	uint32_t *gl, *hf, *ht;
	size_t nl, nh, gl_cap, hf_cap, ht_cap;
	double *xy[2];           /* the two frames: s t and plane */
	size_t xy_cap[2];
	unsigned char *cross[2]; /* ends of crossing loop edges in each frame (local) */
	size_t cross_cap[2];
	int have[2];             /* frame usable */
	int wraps;               /* s is an azimuth that wraps round (cylindrical camera) */
	/* chaining */
	uint32_t *ostart, *oedge, *path;
	int32_t *pos;
	uint8_t *used;
	size_t ostart_cap, oedge_cap, path_cap, pos_cap, used_cap;
	uint32_t *lstart, *lvert;
	size_t nloops, lstart_cap, lvert_cap, nlv;
	/* a piece during repair */
	uint32_t *pstart, *pvert;
	size_t pstart_cap, pvert_cap;
	long *owner;
	size_t owner_cap;
	/* the patch's triangles (local), and the output (global) */
	uint32_t *ptri;
	size_t nptri, ptri_cap;
	uint32_t *tri;
	int32_t *tpatch;
	size_t ntri, tri_cap, tpatch_cap;
};

static void work_free(struct work *w)
{
	free(w->loc), free(w->gl), free(w->hf), free(w->ht), free(w->xy[0]), free(w->xy[1]);
	free(w->ostart), free(w->oedge), free(w->path), free(w->pos), free(w->used);
	free(w->lstart), free(w->lvert), free(w->pstart), free(w->pvert), free(w->owner);
	free(w->ptri), free(w->tri), free(w->tpatch), free(w->cross[0]), free(w->cross[1]);
}

#define GROW(w, arr, cap, need) \
	((need) > (cap) && fct_grow((void **)&(arr), &(cap), (need), sizeof *(arr), (w)->err))

/* Chain the patch's half-edges into loops in frame xy: at each vertex the
 * next edge is the unused one first clockwise from the way back (the face
 * to the left is traced), and a walk that comes back to a vertex on it
 * closes a loop there.  Loops go to w->lstart / w->lvert (local ids); edges
 * of walks that end nowhere are counted in *open.  0 or -1. */
static int chain(struct work *w, const double *xy, size_t *open)
{
	size_t nl = w->nl, nh = w->nh;
	if (GROW(w, w->ostart, w->ostart_cap, nl + 1) || GROW(w, w->oedge, w->oedge_cap, nh) ||
	    GROW(w, w->path, w->path_cap, nh) || GROW(w, w->pos, w->pos_cap, nl) ||
	    GROW(w, w->used, w->used_cap, nh) || GROW(w, w->lstart, w->lstart_cap, nh + 1) ||
	    GROW(w, w->lvert, w->lvert_cap, nh))
		return -1;
	memset(w->ostart, 0, (nl + 1) * sizeof *w->ostart);
	for (size_t h = 0; h < nh; h++)
		w->ostart[w->hf[h] + 1]++;
	for (size_t v = 0; v < nl; v++)
		w->ostart[v + 1] += w->ostart[v];
	/* outgoing edges of each vertex, in edge order (pos as the cursor) */
	for (size_t v = 0; v < nl; v++)
		w->pos[v] = (int32_t)w->ostart[v];
	for (size_t h = 0; h < nh; h++)
		w->oedge[w->pos[w->hf[h]]++] = (uint32_t)h;
	for (size_t v = 0; v < nl; v++)
		w->pos[v] = -1;
	memset(w->used, 0, nh);
	w->nloops = 0, w->nlv = 0;
	w->lstart[0] = 0;
	*open = 0;
	for (size_t h0 = 0; h0 < nh; h0++) {
		if (w->used[h0])
			continue;
		size_t np = 0;
		w->path[np++] = (uint32_t)h0;
		w->used[h0] = 1;
		w->pos[w->hf[h0]] = 0;
		uint32_t cur = w->ht[h0];
		for (;;) {
			if (w->pos[cur] >= 0) {
				size_t k = (size_t)w->pos[cur];
				for (size_t i = k; i < np; i++) {
					w->lvert[w->nlv++] = w->hf[w->path[i]];
					w->pos[w->hf[w->path[i]]] = -1;
				}
				w->lstart[++w->nloops] = (uint32_t)w->nlv;
				np = k;
				if (np == 0)
					break;
			}
			uint32_t u = w->hf[w->path[np - 1]];
			const double *pc = &xy[2 * (size_t)cur], *pu = &xy[2 * (size_t)u];
			double rx = pu[0] - pc[0], ry = pu[1] - pc[1];
			long best = -1;
			double bangle = 0;
			for (uint32_t k = w->ostart[cur]; k < w->ostart[cur + 1]; k++) {
				uint32_t h = w->oedge[k];
				if (w->used[h])
					continue;
				const double *pw = &xy[2 * (size_t)w->ht[h]];
				double dx = pw[0] - pc[0], dy = pw[1] - pc[1];
				double cw = -atan2(rx * dy - ry * dx, rx * dx + ry * dy);
				if (!(cw > 0))
					cw += 2 * M_PI;
				if (best < 0 || cw < bangle)
					best = h, bangle = cw;
			}
			if (best < 0) {
				*open += np;
				for (size_t i = 0; i < np; i++)
					w->pos[w->hf[w->path[i]]] = -1;
				break;
			}
			w->pos[cur] = (int32_t)np;
			w->path[np++] = (uint32_t)best;
			w->used[best] = 1;
			cur = w->ht[best];
		}
	}
	return 0;
}

/* Drop loops of fewer than three vertices or no area in frame xy. */
static size_t drop_degenerate(struct work *w, const double *xy)
{
	size_t out = 0, nv = 0, dropped = 0;
	for (size_t l = 0; l < w->nloops; l++) {
		uint32_t s = w->lstart[l], n = w->lstart[l + 1] - s;
		if (n < 3 || fct_polytri_loop_area2(xy, w->lvert + s, n) == 0) {
			dropped++;
			continue;
		}
		memmove(w->lvert + nv, w->lvert + s, n * sizeof *w->lvert);
		nv += n;
		w->lstart[++out] = (uint32_t)nv;
	}
	w->nloops = out, w->nlv = nv;
	return dropped;
}

static int add_triangles(struct work *w, const uint32_t *t, size_t n)
{
	if (GROW(w, w->ptri, w->ptri_cap, 3 * (w->nptri + n)))
		return -1;
	memcpy(w->ptri + 3 * w->nptri, t, 3 * n * sizeof *t);
	w->nptri += n;
	return 0;
}

/* One loop edge for flag_crossings: its box and its ends (local ids). */
struct loop_edge {
	double x0, x1, y0, y1;
	uint32_t a, b;
};

static int loop_edge_cmp(const void *pa, const void *pb)
{
	const struct loop_edge *x = pa, *y = pb;
	if (x->x0 != y->x0)
		return x->x0 < y->x0 ? -1 : 1;
	if (x->a != y->a)
		return x->a < y->a ? -1 : 1;
	return x->b < y->b ? -1 : x->b > y->b;
}

/* Flag in flag[] (local ids, w->nl) both ends of every loop edge that
 * crosses, overlaps or runs through a vertex of another edge of the
 * patch's loops in frame xy (fct_segments_conflict): where polytri refused
 * them.  A sweep along x over the edges' boxes.  *pairs gets the count of
 * such pairs of edges.  0 or -1. */
static int flag_crossings(struct work *w, const double *xy, unsigned char *flag, size_t *pairs)
{
	size_t n = w->nlv;
	struct loop_edge *e = fct_alloc_array(n ? n : 1, sizeof *e, w->err);
	if (!e)
		return -1;
	for (size_t l = 0; l < w->nloops; l++)
		for (uint32_t k = w->lstart[l]; k < w->lstart[l + 1]; k++) {
			uint32_t a = w->lvert[k], b = w->lvert[k + 1 < w->lstart[l + 1] ? k + 1 : w->lstart[l]];
			const double *pa = &xy[2 * (size_t)a], *pb = &xy[2 * (size_t)b];
			e[k] = (struct loop_edge){ fmin(pa[0], pb[0]), fmax(pa[0], pb[0]),
			                           fmin(pa[1], pb[1]), fmax(pa[1], pb[1]), a, b };
		}
	qsort(e, n, sizeof *e, loop_edge_cmp);
	memset(flag, 0, w->nl);
	*pairs = 0;
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n && e[j].x0 <= e[i].x1; j++) {
			if (e[j].y0 > e[i].y1 || e[j].y1 < e[i].y0 ||
			    !fct_segments_conflict(&xy[2 * (size_t)e[i].a], &xy[2 * (size_t)e[i].b],
			                           &xy[2 * (size_t)e[j].a], &xy[2 * (size_t)e[j].b], e[i].a,
			                           e[i].b, e[j].a, e[j].b))
				continue;
			flag[e[i].a] = flag[e[i].b] = flag[e[j].a] = flag[e[j].b] = 1;
			(*pairs)++;
		}
	free(e);
	return 0;
}

/* Count outer loops and holes of the loops in frame xy. */
static void count_loops(const double *xy, const uint32_t *lstart, size_t nloops,
                        const uint32_t *lvert, struct fct_tripatch_stats *st)
{
	for (size_t l = 0; l < nloops; l++) {
		double a = fct_polytri_loop_area2(xy, lvert + lstart[l], lstart[l + 1] - lstart[l]);
		if (a > 0)
			st->polygons++;
		else
			st->holes++;
	}
}

/* Step 3: each outer loop with its holes alone, in s t then the plane, and
 * cut into ears when both refuse it.  Frame 1 (the plane) is always there. */
static int repair(struct work *w, const struct fct_tripatch_params *p, struct fct_tripatch_stats *st)
{
	struct fct_err perr;
	if (GROW(w, w->owner, w->owner_cap, w->nloops) || GROW(w, w->pstart, w->pstart_cap, w->nloops + 1) ||
	    GROW(w, w->pvert, w->pvert_cap, w->nlv))
		return -1;
	if (fct_polytri_nest(w->owner, w->xy[1], w->lstart, w->nloops, w->lvert))
		return 0;
	for (size_t o = 0; o < w->nloops; o++) {
		if (w->owner[o] != (long)o)
			continue;
		size_t np = 0, nv = 0;
		w->pstart[0] = 0;
		for (size_t l = 0; l < w->nloops; l++) {
			if (w->owner[l] != (long)o)
				continue;
			uint32_t s = w->lstart[l], n = w->lstart[l + 1] - s;
			memcpy(w->pvert + nv, w->lvert + s, n * sizeof *w->pvert);
			nv += n;
			w->pstart[++np] = (uint32_t)nv;
		}
		uint32_t *t = NULL;
		size_t nt = 0;
		int done = 0;
		for (int f = p->plane_only ? 1 : 0; f < 2 && !done; f++) {
			if (!w->have[f])
				continue;
			int rc = fct_polytri(&t, &nt, w->xy[f], w->nl, w->pstart, np, w->pvert, p->method, &st->tri, &perr);
			if (rc < 0) {
				*w->err = perr;
				return -1;
			}
			if (rc == 0)
				done = 1;
		}
		if (!done) {
			int rc = fct_polytri_earclip(&t, &nt, w->xy[1], w->nl, w->pstart, np, w->pvert, &st->tri, &perr);
			if (rc < 0) {
				*w->err = perr;
				return -1;
			}
			st->earclipped++;
		}
		count_loops(w->xy[1], w->pstart, np, w->pvert, st);
		int rc = add_triangles(w, t, nt);
		free(t);
		if (rc)
			return -1;
	}
	return 0;
}

/* Frame f of the patch's vertices: 0 image coordinates, 1 the plane.  Sets
 * w->have[f]: usable (finite, with area); mirrors it when seen from
 * behind. */
static int make_frame(struct work *w, const struct fct_mesh *m, int f, const struct fct_prop *ps,
                      const struct fct_prop *pt, double W, double H, const double n[3])
{
	if (GROW(w, w->xy[f], w->xy_cap[f], 2 * w->nl))
		return -1;
	double *xy = w->xy[f];
	w->have[f] = 0;
	if (f == 0) {
		if (!ps || !pt)
			return 0;
		for (size_t i = 0; i < w->nl; i++) {
			xy[2 * i] = W == 1 ? fct_prop_get(ps, w->gl[i]) : fct_snap_pixel_centre(fct_prop_get(ps, w->gl[i]) * W);
			xy[2 * i + 1] = H == 1 ? fct_prop_get(pt, w->gl[i]) : fct_snap_pixel_centre(fct_prop_get(pt, w->gl[i]) * H);
		}
		/* On a cylindrical panorama an edge that crosses the 0/360 seam
		 * goes the long way round in s: the loops of a patch round the
		 * camera (a ceiling, a floor) or across the seam are no polygons
		 * in s t.  Dropped there, a ceiling's hole (the unseen disc
		 * overhead) once left two triangles over the zenith, which no
		 * planar view of cyl2planar can hold. */
		if (w->wraps)
			for (size_t h = 0; h < w->nh; h++)
				if (fabs(xy[2 * (size_t)w->hf[h]] - xy[2 * (size_t)w->ht[h]]) > W / 2)
					return 0;
	} else {
		double e1[3], e2[3];
		fct_plane_frame(n, e1, e2);
		/* relative to the first vertex, for precision far from the origin */
		const double *o = &m->xyz[3 * (size_t)w->gl[0]];
		for (size_t i = 0; i < w->nl; i++) {
			double d[3];
			fct_v3_sub(d, &m->xyz[3 * (size_t)w->gl[i]], o);
			xy[2 * i] = fct_v3_dot(d, e1);
			xy[2 * i + 1] = fct_v3_dot(d, e2);
		}
	}
	double area = 0;
	const double *o = &xy[0];
	for (size_t h = 0; h < w->nh; h++) {
		const double *a = &xy[2 * (size_t)w->hf[h]], *b = &xy[2 * (size_t)w->ht[h]];
		area += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
	}
	if (!isfinite(area) || area == 0)
		return 0;
	if (area < 0)
		for (size_t i = 0; i < w->nl; i++)
			xy[2 * i + 1] = -xy[2 * i + 1];
	w->have[f] = 1;
	return 0;
}

/* Twice the area of local triangle (a, b, c) along n (signed), and the
 * square of its longest edge. */
static double tri_orient(const struct work *w, const struct fct_mesh *m, const uint32_t t[3],
                         const double n[3], double *longest2)
{
	const double *p[3];
	for (int q = 0; q < 3; q++)
		p[q] = &m->xyz[3 * (size_t)w->gl[t[q]]];
	double b[3], c[3], x[3];
	fct_v3_sub(b, p[1], p[0]);
	fct_v3_sub(c, p[2], p[0]);
	fct_v3_cross(x, b, c);
	*longest2 = 0;
	for (int q = 0; q < 3; q++) {
		double e[3];
		fct_v3_sub(e, p[(q + 1) % 3], p[q]);
		*longest2 = fmax(*longest2, fct_v3_dot(e, e));
	}
	return fct_v3_dot(x, n);
}

/* A triangle thinner than this (twice its area over its longest edge
 * squared) is a sliver. */
#define SLIVER 1e-6
/* Triangle visits the sliver flips of one patch may make. */
#define SLIVER_BUDGET ((size_t)1 << 26)

/* Triangulating in the image can cut an ear from three corners that the
 * projection put on one crease line in space: a triangle of no area whose
 * normal means nothing.  Flip its longest edge (a diagonal, since two
 * collinear boundary edges cannot be its longest) with the triangle across
 * it when both new triangles keep the patch's winding and are not thin.
 * sgn is the sign of the patch's winding along n. */
static size_t flip_slivers(struct work *w, const struct fct_mesh *m, const double n[3], double sgn,
                           size_t *budget)
{
	size_t flips = 0;
	for (size_t k = 0; k < w->nptri; k++) {
		uint32_t *t = &w->ptri[3 * k];
		double l2, o = tri_orient(w, m, t, n, &l2);
		if (!(l2 > 0) || fabs(o) >= SLIVER * l2)
			continue;
		/* each sliver scans the patch's triangles twice: a budget keeps a
		 * patch of thousands of collinear corners from taking quadratic
		 * time (what it leaves stays a sliver) */
		if (*budget < 2 * w->nptri)
			break;
		*budget -= 2 * w->nptri;
		/* rotate t to (p, q, r) with p-q its longest edge */
		int e = 0;
		double best = -1;
		for (int q = 0; q < 3; q++) {
			double d[3];
			fct_v3_sub(d, &m->xyz[3 * (size_t)w->gl[t[(q + 1) % 3]]], &m->xyz[3 * (size_t)w->gl[t[q]]]);
			if (fct_v3_dot(d, d) > best)
				best = fct_v3_dot(d, d), e = q;
		}
		uint32_t P = t[e], Q = t[(e + 1) % 3], R = t[(e + 2) % 3];
		for (size_t j = 0; j < w->nptri; j++) {
			uint32_t *u = &w->ptri[3 * j];
			int at = -1;
			for (int q = 0; q < 3; q++)
				if (u[q] == Q && u[(q + 1) % 3] == P)
					at = q;
			if (j == k || at < 0)
				continue;
			uint32_t O = u[(at + 2) % 3];
			uint32_t t1[3] = { R, P, O }, t2[3] = { O, Q, R };
			double m1, m2, o1 = tri_orient(w, m, t1, n, &m1), o2 = tri_orient(w, m, t2, n, &m2);
			if (!(o1 * sgn >= SLIVER * m1 && o2 * sgn >= SLIVER * m2))
				break;
			/* the new diagonal R-O must not be an edge already */
			int exists = 0;
			for (size_t i = 0; i < w->nptri && !exists; i++)
				for (int q = 0; q < 3; q++) {
					uint32_t a = w->ptri[3 * i + q], b = w->ptri[3 * i + (q + 1) % 3];
					exists |= (a == R && b == O) || (a == O && b == R);
				}
			if (exists)
				break;
			memcpy(t, t1, sizeof t1);
			memcpy(u, t2, sizeof t2);
			flips++;
			break;
		}
	}
	return flips;
}

static int tri_cmp(const void *pa, const void *pb)
{
	const uint32_t *x = pa, *y = pb;
	for (int k = 0; k < 3; k++)
		if (x[k] != y[k])
			return x[k] < y[k] ? -1 : 1;
	return 0;
}

/* Triangulate one patch (its half-edges in w->hf/ht, local ids) and append
 * its triangles to the output. */
static int do_patch(struct work *w, const struct fct_mesh *m, int32_t patch,
                    const struct fct_plane *plane, const struct fct_prop *ps,
                    const struct fct_prop *pt, double W, double H,
                    const struct fct_tripatch_params *p, struct fct_tripatch_stats *st)
{
	/* The Newell normal of the edges: the patch's own orientation. */
	double nn[3] = { 0, 0, 0 };
	const double *o = &m->xyz[3 * (size_t)w->gl[0]];
	for (size_t h = 0; h < w->nh; h++) {
		double a[3], b[3], c[3];
		fct_v3_sub(a, &m->xyz[3 * (size_t)w->gl[w->hf[h]]], o);
		fct_v3_sub(b, &m->xyz[3 * (size_t)w->gl[w->ht[h]]], o);
		fct_v3_cross(c, a, b);
		fct_v3_add(nn, nn, c);
	}
	double n[3];
	if (plane) {
		memcpy(n, plane->n, sizeof n);
	} else {
		double l = sqrt(fct_v3_dot(nn, nn));
		if (l > 0 && isfinite(l))
			n[0] = nn[0] / l, n[1] = nn[1] / l, n[2] = nn[2] / l;
		else
			n[0] = 0, n[1] = 0, n[2] = 1;
	}
	if (make_frame(w, m, 0, p->plane_only ? NULL : ps, pt, W, H, n) || make_frame(w, m, 1, ps, pt, W, H, n))
		return -1;
	w->nptri = 0, w->nloops = 0, w->nlv = 0;
	int done = 0, st_avail = !p->plane_only && ps && pt;
	size_t open = 0, ncross[2] = { 0, 0 };
	struct fct_err perr;
	for (int f = 0; f < 2 && !done; f++) {
		if (!w->have[f])
			continue;
		if (chain(w, w->xy[f], &open))
			return -1;
		st->degenerate += drop_degenerate(w, w->xy[f]);
		if (w->nloops == 0)
			break;
		uint32_t *t = NULL;
		size_t nt = 0;
		int rc = fct_polytri(&t, &nt, w->xy[f], w->nl, w->lstart, w->nloops, w->lvert, p->method,
		                     &st->tri, &perr);
		if (rc < 0) {
			*w->err = perr;
			fct_err_prefix(w->err, "patch %ld", (long)patch);
			return -1;
		}
		if (rc == 1 && p->trouble &&
		    (GROW(w, w->cross[f], w->cross_cap[f], w->nl) ||
		     flag_crossings(w, w->xy[f], w->cross[f], &ncross[f])))
			return -1;
		if (rc == 0) {
			done = 1;
			rc = add_triangles(w, t, nt);
			free(t);
			if (rc)
				return -1;
			count_loops(w->xy[f], w->lstart, w->nloops, w->lvert, st);
			if (f == 0)
				st->in_st++;
			else
				st->in_plane++, st->fallbacks += (size_t)st_avail;
		}
	}
	if (!w->have[0] && !w->have[1]) {
		/* nothing to triangulate: only count what does not close */
		if (chain(w, w->xy[1], &open))
			return -1;
		if (w->nloops > 0) {
			/* Closed, but without area in the image or the plane
			 * (projection put its corners on one line or point):
			 * there is nothing to cover, so it is not a failure. */
			st->degenerate += w->nloops;
			st->open_edges += open;
			return 0;
		}
	}
	if (p->unclean && patch >= 0 && (size_t)patch < w->nplanes && (open || (!done && w->nloops > 0)))
		p->unclean[patch] = 1;
	/* Where to mend: first the crossings of the frame that has fewer (one
	 * clean frame is enough), then the other's. */
	if (!done && p->trouble && (ncross[0] || ncross[1])) {
		int f = !ncross[0] || (ncross[1] && ncross[1] < ncross[0]);
		for (size_t i = 0; i < w->nl; i++)
			p->trouble[w->gl[i]] |= (unsigned char)(w->cross[f][i] | (ncross[!f] ? w->cross[!f][i] << 1 : 0));
	}
	if (!done && w->nloops > 0 && w->have[1]) {
		st->repairs++;
		if (repair(w, p, st))
			return -1;
	}
	st->open_edges += open;
	if (w->nptri == 0) {
		if (p->unclean && patch >= 0 && (size_t)patch < w->nplanes)
			p->unclean[patch] = 1;
		st->failures++;
		if (st->first_failure < 0)
			st->first_failure = patch;
		return 0;
	}
	/* Wind the patch with its plane normal. */
	double s = 0;
	for (size_t k = 0; k < w->nptri; k++) {
		const double *a = &m->xyz[3 * (size_t)w->gl[w->ptri[3 * k]]];
		double b[3], c[3], x[3];
		fct_v3_sub(b, &m->xyz[3 * (size_t)w->gl[w->ptri[3 * k + 1]]], a);
		fct_v3_sub(c, &m->xyz[3 * (size_t)w->gl[w->ptri[3 * k + 2]]], a);
		fct_v3_cross(x, b, c);
		s += fct_v3_dot(x, n);
	}
	/* a run of collinear corners leaves slivers side by side: each pass
	 * frees the next one */
	size_t budget = SLIVER_BUDGET;
	for (int pass = 0; pass < 16; pass++) {
		size_t f = flip_slivers(w, m, n, s < 0 ? -1 : 1, &budget);
		st->slivers_flipped += f;
		if (f == 0)
			break;
	}
	int reverse = s < 0;
	st->reversed += (size_t)reverse;
	if (GROW(w, w->tri, w->tri_cap, 3 * (w->ntri + w->nptri)) ||
	    GROW(w, w->tpatch, w->tpatch_cap, w->ntri + w->nptri))
		return -1;
	uint32_t *out = w->tri + 3 * w->ntri;
	for (size_t k = 0; k < w->nptri; k++) {
		uint32_t v[3];
		for (int q = 0; q < 3; q++)
			v[q] = w->gl[w->ptri[3 * k + (reverse ? 2 - q : q)]];
		int r = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
		for (int q = 0; q < 3; q++)
			out[3 * k + q] = v[(r + q) % 3];
		w->tpatch[w->ntri + k] = patch;
	}
	qsort(out, w->nptri, 3 * sizeof *out, tri_cmp);
	w->ntri += w->nptri;
	st->triangles += w->nptri;
	return 0;
}

/* An integer-valued property value in [lo, hi], or fail. */
int fct_tripatch(struct fct_mesh *m, const struct fct_tripatch_params *p,
                 struct fct_tripatch_stats *st, struct fct_err *err)
{
	struct fct_tripatch_stats dummy;
	if (!st)
		st = &dummy;
	memset(st, 0, sizeof *st);
	st->first_failure = -1;
	struct fct_plane *planes = NULL;
	size_t nplanes = 0;
	if (fct_planes_get(m, &planes, &nplanes, err))
		return -1;
	int has_planes = fct_mesh_find_elem(m, "plane") != NULL;
	struct work w;
	memset(&w, 0, sizeof w);
	w.err = err;
	int rc = -1, present = 0;
	struct hedge *he = NULL;
	struct fct_wire *wire = NULL;
	size_t nwire = 0, nhe = 0;
	if (fct_wires_get(m, has_planes ? (long)nplanes : -1, &wire, &nwire, &present, err))
		goto out;
	if (!present) {
		fct_fail(err, "no edge element (tripatch reads simpchain's wireframe)");
		goto out;
	}
	if (nwire > ((size_t)-1) / 2 / sizeof *he) {
		fct_fail(err, "element edge: too many edges");
		goto out;
	}
	he = fct_alloc_array(2 * nwire, sizeof *he, err);
	if (!he && nwire)
		goto out;
	st->edges = nwire;
	for (size_t i = 0; i < nwire; i++) {
		if (wire[i].p1 >= 0)
			he[nhe++] = (struct hedge){ wire[i].p1, wire[i].v1, wire[i].v2 };
		if (wire[i].p2 >= 0)
			he[nhe++] = (struct hedge){ wire[i].p2, wire[i].v2, wire[i].v1 };
	}
	qsort(he, nhe, sizeof *he, hedge_cmp);
	/* Repeated edges once; opposite edges of one patch cancel. */
	{
		size_t k = 0;
		for (size_t i = 0; i < nhe; i++) {
			if (k && !hedge_cmp(&he[k - 1], &he[i])) {
				st->duplicates++;
				mark_unclean(p, he[i].patch, nplanes);
				continue;
			}
			he[k++] = he[i];
		}
		nhe = k;
		uint8_t *gone = calloc(nhe ? nhe : 1, 1);
		if (!gone) {
			fct_fail(err, "out of memory");
			goto out;
		}
		for (size_t i = 0; i < nhe; i++) {
			if (he[i].a > he[i].b || gone[i])
				continue;
			struct hedge key = { he[i].patch, he[i].b, he[i].a };
			struct hedge *f = bsearch(&key, he, nhe, sizeof *he, hedge_cmp);
			if (f) {
				gone[i] = gone[f - he] = 1;
				st->slits++;
				mark_unclean(p, he[i].patch, nplanes);
			}
		}
		k = 0;
		for (size_t i = 0; i < nhe; i++)
			if (!gone[i])
				he[k++] = he[i];
		nhe = k;
		free(gone);
	}
	const struct fct_prop *ps = fct_elem_find(&m->vertex, "s"), *pt = fct_elem_find(&m->vertex, "t");
	if ((ps && ps->count_type != FCT_NONE) || (pt && pt->count_type != FCT_NONE) || !ps || !pt)
		ps = pt = NULL;
	double W = 1, H = 1;
	struct fct_camera cam;
	struct fct_err cerr;
	if (fct_header_camera(m, &cam, &cerr) == 1 && cam.width > 0 && cam.height > 0)
		W = cam.width, H = cam.height;
	w.nplanes = nplanes;
	w.wraps = cam.kind == FCT_CAMERA_CYLINDRICAL;
	w.loc = fct_alloc_array(m->nv, sizeof *w.loc, err);
	if (!w.loc)
		goto out;
	for (size_t v = 0; v < m->nv; v++)
		w.loc[v] = -1;
	for (size_t g0 = 0, g1; g0 < nhe; g0 = g1) {
		int32_t patch = he[g0].patch;
		for (g1 = g0; g1 < nhe && he[g1].patch == patch; g1++)
			;
		size_t nh = g1 - g0;
		st->patches++;
		w.nl = 0, w.nh = nh;
		if (GROW(&w, w.hf, w.hf_cap, nh) || GROW(&w, w.ht, w.ht_cap, nh) || GROW(&w, w.gl, w.gl_cap, 2 * nh))
			goto out;
		/* local numbers in order of first use (the edges are sorted by a) */
		for (size_t i = g0; i < g1; i++)
			for (int q = 0; q < 2; q++) {
				uint32_t v = q ? he[i].b : he[i].a;
				if (w.loc[v] < 0) {
					w.loc[v] = (int32_t)w.nl;
					w.gl[w.nl++] = v;
				}
			}
		for (size_t i = g0; i < g1; i++)
			w.hf[i - g0] = (uint32_t)w.loc[he[i].a], w.ht[i - g0] = (uint32_t)w.loc[he[i].b];
		int r = do_patch(&w, m, patch, (size_t)patch < nplanes ? &planes[patch] : NULL, ps, pt, W, H, p, st);
		for (size_t i = 0; i < w.nl; i++)
			w.loc[w.gl[i]] = -1;
		if (r)
			goto out;
	}
	/* The new faces: no other face property survives. */
	while (m->face.nprops)
		fct_elem_remove(&m->face, m->face.props[0].name);
	if (fct_mesh_set_triangle_count(m, w.ntri, err))
		goto out;
	if (w.ntri)
		memcpy(m->fvert, w.tri, 3 * w.ntri * sizeof *m->fvert);
	if (fct_patches_set(m, w.tpatch, err))
		goto out;
	fct_mesh_remove_elem(m, "edge");
	rc = 0;
out:
	work_free(&w);
	free(he), free(wire), free(planes);
	return rc;
}
