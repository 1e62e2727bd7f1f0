/* project.c - vertex projection onto segmentation planes, texture
 * coordinates, orthogonal snapping and the depth scale: Kang, Johnson and
 * Szeliski, DEC CRL 95/7, sections 5 (eq. 2), 6 and 8 (see project.h and
 * projverts(1) for the mathematics). */
#include "planar/project.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "core/arena.h"
#include "planar/chain.h"
#include "geom/geom.h"
#include "io/header.h"

/* LAPACK (Fortran calling convention; character lengths of 1 need no
 * hidden argument for these routines). */
extern void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a,
                    const int *lda, double *s, double *u, const int *ldu, double *vt,
                    const int *ldvt, double *work, const int *lwork, int *info);
extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

#define DEG (M_PI / 180)

void fct_project_params_default(struct fct_project_params *p)
{
	memset(p, 0, sizeof *p);
	p->max_move = -1;
	p->max_move_edges = FCT_PROJECT_MAX_MOVE_EDGES;
	p->rank_tol = FCT_PROJECT_RANK_TOL;
	p->scale_angle = FCT_PROJECT_SCALE_ANGLE;
	p->texcoords = 1;
	p->tear = 1;
	p->straighten = 1;
}

static double norm3(const double v[3])
{
	return sqrt(fct_v3_dot(v, v));
}

/* Section 5 ------------------------------------------------------------- */

/* Rows on the stack up to this many planes; more come from the heap. */
enum { STACK_ROWS = 16 };

/* The plane rule: the foot of the perpendicular from p onto the plane
 * n.x + d = 0, exactly as the SVD would give it. */
static void foot_on_plane(const double n[3], double d, const double p[3], double delta[3])
{
	double r = -(fct_v3_dot(n, p) + d);
	for (int c = 0; c < 3; c++)
		delta[c] = r * n[c];
}

/* The rules of the line of two planes and of the point of k >= 3 (eq. 2):
 * the minimum-norm least-squares moves delta[r - 1] = sum over j < r of
 * v_j (u_j . r) / s_j for r up to the numerical rank, into *rank -- of
 * rank 2 from two planes the nearest point of their line, of rank 3 the
 * least-squares point.  0, or -1 when out of memory or LAPACK fails. */
static int pseudoinverse_moves(const double *normals, const double *offsets, size_t k, const double p[3],
                               double rank_tol, double delta[3][3], int *rank_out, struct fct_err *err)
{
	if (k > (size_t)1 << 26)
		return fct_fail(err, "vertex on %zu planes: too many", k);
	int m = (int)k, n = 3, mn = m < 3 ? m : 3, lwork = 64 + 8 * m, info = 0;
	double stack[STACK_ROWS * 3 * 2 + STACK_ROWS + 64 + 8 * STACK_ROWS];
	double *buf = stack;
	size_t need = k * 3 * 2 + k + (size_t)lwork;
	if (k > STACK_ROWS) {
		buf = fct_alloc_array(need, sizeof *buf, err);
		if (!buf)
			return -1;
	}
	double *a = buf, *u = a + 3 * k, *r = u + 3 * k, *work = r + k;
	double s[3], vt[9];
	for (size_t i = 0; i < k; i++) {
		for (int c = 0; c < 3; c++)
			a[i + k * (size_t)c] = normals[3 * i + (size_t)c];   /* column-major */
		r[i] = -(fct_v3_dot(normals + 3 * i, p) + offsets[i]);
	}
	dgesvd_("S", "S", &m, &n, a, &m, s, u, &m, vt, &mn, work, &lwork, &info);
	if (info != 0) {
		if (buf != stack)
			free(buf);
		return fct_fail(err, "LAPACK dgesvd failed (info %d)", info);
	}
	int rank = 0;
	while (rank < mn && s[rank] > rank_tol * s[0] && s[rank] > 0)
		rank++;
	double acc[3] = { 0, 0, 0 };
	for (int j = 0; j < rank; j++) {
		double ur = 0;
		for (size_t i = 0; i < k; i++)
			ur += u[i + k * (size_t)j] * r[i];
		double c = ur / s[j];
		for (int q = 0; q < 3; q++) {
			acc[q] += vt[j + mn * q] * c;
			delta[j][q] = acc[q];
		}
	}
	*rank_out = rank;
	if (buf != stack)
		free(buf);
	return 0;
}

/* The bound, the paper's refusal of a "drastic shape change": the rank of
 * the move to apply among delta[0..rank), 0 for none.  The full move when
 * within bound, else with fallback the longest truncation within it
 * (|delta_r| grows with r, the terms being orthogonal). */
static int rank_within_bound(const double delta[3][3], int rank, double bound, int fallback)
{
	if (norm3(delta[rank - 1]) <= bound)
		return rank;
	if (fallback)
		for (int j = rank - 1; j >= 1; j--)
			if (norm3(delta[j - 1]) <= bound)
				return j;
	return 0;
}

int fct_project_point(const double *normals, const double *offsets, size_t k, const double p0[3],
                      double bound, double rank_tol, int fallback, double out[3],
                      struct fct_point_fit *fit, struct fct_err *err)
{
	struct fct_point_fit f = { 0, 0, 0, 0 };
	double p[3] = { p0[0], p0[1], p0[2] };
	double delta[3][3] = { { 0 } };   /* delta[r-1]: the solution of rank r */
	if (k == 1) {
		foot_on_plane(normals, offsets[0], p, delta[0]);
		f.rank = 1;
	} else if (k > 1 && pseudoinverse_moves(normals, offsets, k, p, rank_tol, delta, &f.rank, err)) {
		return -1;
	}
	if (f.rank > 0) {
		f.want = norm3(delta[f.rank - 1]);
		int use = rank_within_bound(delta, f.rank, bound, fallback);
		if (use > 0) {
			f.used = use;
			f.move = norm3(delta[use - 1]);
			for (int c = 0; c < 3; c++)
				p[c] += delta[use - 1][c];
		}
	}
	out[0] = p[0], out[1] = p[1], out[2] = p[2];
	if (fit)
		*fit = f;
	return 0;
}

/* Section 6 ------------------------------------------------------------- */

int fct_project_texcoord(const struct fct_camera *cam, const double *inv_pose, const double p[3],
                         double *s, double *t)
{
	double q[3], u, v, depth;
	if (inv_pose)
		fct_pose_apply(inv_pose, p, q);
	else
		q[0] = p[0], q[1] = p[1], q[2] = p[2];
	if (cam->width <= 0 || cam->height <= 0 || !fct_camera_project(cam, q, &u, &v, &depth))
		return 0;
	*s = (u + 0.5) / cam->width;
	*t = 1 - (v + 0.5) / cam->height;
	return isfinite(*s) && isfinite(*t);
}

/* Section 8: snapping --------------------------------------------------- */

/* Principal eigenvector of the symmetric 3x3 matrix m (row-major). */
static int principal_vector(const double m[9], double v[3], struct fct_err *err)
{
	double a[9], w[3], work[64];
	int n = 3, lwork = 64, info = 0;
	memcpy(a, m, sizeof a);
	dsyev_("V", "U", &n, a, &n, w, work, &lwork, &info);
	if (info != 0)
		return fct_fail(err, "LAPACK dsyev failed (info %d)", info);
	/* Eigenvalues ascending; column 2 (column-major) is the largest. */
	v[0] = a[6], v[1] = a[7], v[2] = a[8];
	return 0;
}

/* Sort idx[0..n) by key[idx[.]], largest first, ties by index (reentrant:
 * the keys travel with the indices).  0 or -1 (out of memory). */
struct keyed {
	double k;
	size_t i;
};

static int keyed_desc(const void *x, const void *y)
{
	const struct keyed *a = x, *b = y;
	if (a->k != b->k)
		return a->k > b->k ? -1 : 1;
	return (a->i > b->i) - (a->i < b->i);
}

static int sort_by_key(size_t *idx, size_t n, const double *key, struct fct_err *err)
{
	struct keyed *t = fct_alloc_array(n, sizeof *t, err);
	if (!t)
		return -1;
	for (size_t j = 0; j < n; j++)
		t[j].k = key[idx[j]], t[j].i = idx[j];
	qsort(t, n, sizeof *t, keyed_desc);
	for (size_t j = 0; j < n; j++)
		idx[j] = t[j].i;
	free(t);
	return 0;
}

enum { MAX_CANDIDATES = 1000, MAX_FRAMES = 256 };

/* Refine axis a to the principal direction of the normals within cos_a of
 * it (as lines), twice; the sign follows ref. */
static int refine_axis(const struct fct_plane *pl, size_t n, const double *w, double cos_a,
                       double a[3], const double ref[3], struct fct_err *err)
{
	for (int it = 0; it < 2; it++) {
		double m[9] = { 0 };
		int any = 0;
		for (size_t j = 0; j < n; j++)
			if (fabs(fct_v3_dot(pl[j].n, a)) >= cos_a) {
				for (int r = 0; r < 3; r++)
					for (int c = 0; c < 3; c++)
						m[3 * r + c] += w[j] * pl[j].n[r] * pl[j].n[c];
				any = 1;
			}
		if (!any)
			break;
		double v[3] = { 0, 0, 0 };
		if (principal_vector(m, v, err))
			return -1;
		double len = norm3(v);
		if (!(len > 0))
			break;
		double sg = fct_v3_dot(v, ref) < 0 ? -1 : 1;
		for (int c = 0; c < 3; c++)
			a[c] = sg * v[c] / len;
	}
	return 0;
}

/* Circular distance of azimuths x and y modulo 90 degrees. */
static double dist90(double x, double y)
{
	return fabs(remainder(x - y, M_PI / 2));
}

/* Sorted azimuths (mod 90 degrees) with prefix sums of weights, for the
 * weight within a window of half-width h about x. */
struct azimuths {
	double *x, *cum;   /* x ascending in [0, pi/2); cum[i] = sum of weights of x[0..i) */
	size_t n;
};

static size_t lower(const double *x, size_t n, double v)
{
	size_t lo = 0, hi = n;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (x[mid] < v)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

static size_t upper(const double *x, size_t n, double v)
{
	size_t lo = 0, hi = n;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (x[mid] <= v)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

/* Weight of the azimuths in [lo, hi] on the circle of length pi/2 (the
 * window is narrower than the circle: at most 80 of its 90 degrees). */
static double window_weight(const struct azimuths *az, double lo, double hi)
{
	const double q = M_PI / 2;
	double seg[2][2] = { { lo, hi }, { 1, 0 } };   /* the second segment empty unless wrapped */
	if (lo < 0)
		seg[0][0] = 0, seg[1][0] = lo + q, seg[1][1] = q;
	else if (hi >= q)
		seg[0][1] = q, seg[1][0] = 0, seg[1][1] = hi - q;
	double sum = 0;
	for (int k = 0; k < 2; k++) {
		if (seg[k][0] > seg[k][1])
			continue;
		size_t a = lower(az->x, az->n, seg[k][0]), b = upper(az->x, az->n, seg[k][1]);
		if (b > a)
			sum += az->cum[b] - az->cum[a];
	}
	return sum;
}

static double mod90(double x)
{
	double q = M_PI / 2, r = fmod(x, q);
	if (r < 0)
		r += q;
	if (r >= q)
		r = 0;
	return r;
}

/* Weights: a plane of no weight still counts a little, so that a mesh
 * without area is snapped all the same. */
static void snap_weights(const double *weight, size_t n, double *w)
{
	double wmax = 0;
	for (size_t i = 0; i < n; i++) {
		w[i] = weight && isfinite(weight[i]) && weight[i] > 0 ? weight[i] : 0;
		if (w[i] > wmax)
			wmax = w[i];
	}
	for (size_t i = 0; i < n; i++)
		w[i] = wmax > 0 ? w[i] + 1e-9 * wmax : 1;
}

/* Step 1: up, the candidate normal (of the MAX_CANDIDATES heaviest, order
 * listing the planes heaviest first; those near up_prior when there are
 * any) with the largest weight of normals within cos_a of it, refined. */
static int find_up(const struct fct_plane *pl, size_t n, const double *w, const size_t *order,
                   const double *up_prior, double cos_a, double up[3], struct fct_err *err)
{
	size_t ncand = n < MAX_CANDIDATES ? n : MAX_CANDIDATES;
	long best = -1;
	double best_score = -1;
	for (int pass = up_prior ? 0 : 1; pass < 2 && best < 0; pass++)
		for (size_t c = 0; c < ncand; c++) {
			size_t i = order[c];
			if (pass == 0 && fabs(fct_v3_dot(pl[i].n, up_prior)) < cos(45 * DEG))
				continue;
			double sc = 0;
			for (size_t j = 0; j < n; j++)
				if (fabs(fct_v3_dot(pl[j].n, pl[i].n)) >= cos_a)
					sc += w[j];
			if (sc > best_score || (sc == best_score && (long)i < best))
				best_score = sc, best = (long)i;
		}
	double ref[3];
	memcpy(up, pl[best].n, 3 * sizeof *up);
	memcpy(ref, up_prior ? up_prior : pl[best].n, sizeof ref);
	if (fct_v3_dot(up, ref) < 0)
		for (int c = 0; c < 3; c++)
			up[c] = -up[c];
	return refine_axis(pl, n, w, cos_a, up, ref, err);
}

/* Two horizontal unit axes ea, eb with ea x eb = up: ea from the axis
 * along which up is smallest. */
static void horizontal_basis(const double up[3], double ea[3], double eb[3])
{
	int k = 0;
	for (int c = 1; c < 3; c++)
		if (fabs(up[c]) < fabs(up[k]))
			k = c;
	ea[0] = ea[1] = ea[2] = 0;
	ea[k] = 1;
	fct_v3_axpy(ea, ea, -fct_v3_dot(ea, up), up);
	double len = norm3(ea);
	for (int c = 0; c < 3; c++)
		ea[c] /= len;
	fct_v3_cross(eb, up, ea);
}

/* Step 2's groups of vertical planes. */
struct frames {
	int *of;                 /* per plane: its frame, -1 vertical without one, -2 not vertical */
	double *phi;             /* per vertical plane: its azimuth modulo 90 degrees */
	double (*axes)[2][3];    /* per frame: its two horizontal axes */
	size_t n;
};

/* The seed of the next frame: among the MAX_CANDIDATES heaviest vertical
 * planes without a frame, the one with the largest weight of azimuths
 * within h of its own. */
static size_t frame_seed(const struct frames *fr, const size_t *order, size_t n, const struct azimuths *az,
                         double h)
{
	long pick = -1;
	double pick_score = -1;
	size_t seen = 0;
	for (size_t c = 0; c < n && seen < MAX_CANDIDATES; c++) {
		size_t i = order[c];
		if (fr->of[i] != -1)
			continue;
		seen++;
		double sc = window_weight(az, fr->phi[i] - h, fr->phi[i] + h);
		if (sc > pick_score || (sc == pick_score && (long)i < pick))
			pick_score = sc, pick = (long)i;
	}
	return (size_t)pick;
}

/* Step 2: frames of the vertical planes (normal within sin_a of
 * perpendicular to up), grouped greedily by azimuth, the heaviest group
 * first; idx (n entries) and az are scratch. */
static int vertical_frames(const struct fct_plane *pl, size_t n, const double *w, const size_t *order,
                           const double up[3], double angle, size_t *idx, struct azimuths *az,
                           struct frames *fr, struct fct_err *err)
{
	const double h = angle * DEG;
	double ea[3], eb[3];
	horizontal_basis(up, ea, eb);
	for (size_t i = 0; i < n; i++) {
		fr->of[i] = -2;
		if (fabs(fct_v3_dot(pl[i].n, up)) <= sin(h)) {
			fr->of[i] = -1;
			fr->phi[i] = mod90(atan2(fct_v3_dot(pl[i].n, eb), fct_v3_dot(pl[i].n, ea)));
		}
	}
	const double *phi = fr->phi;
	for (fr->n = 0; fr->n < MAX_FRAMES; fr->n++) {
		/* The unassigned vertical planes, by azimuth. */
		size_t m = 0;
		for (size_t i = 0; i < n; i++)
			if (fr->of[i] == -1)
				idx[m++] = i;
		if (m == 0)
			break;
		if (sort_by_key(idx, m, phi, err))   /* descending azimuth; reversed below */
			return -1;
		az->n = m;
		az->cum[0] = 0;
		for (size_t k = 0; k < m; k++) {
			size_t i = idx[m - 1 - k];
			az->x[k] = phi[i];
			az->cum[k + 1] = az->cum[k] + w[i];
		}
		size_t pick = frame_seed(fr, order, n, az, h);
		/* Its azimuth: the weighted circular mean of 4 x azimuth over the
		 * planes within h, divided by 4, twice. */
		double psi = phi[pick];
		for (int it = 0; it < 2; it++) {
			double sx = 0, sy = 0;
			for (size_t k = 0; k < m; k++) {
				size_t i = idx[k];
				if (dist90(phi[i], psi) <= h) {
					sx += w[i] * cos(4 * phi[i]);
					sy += w[i] * sin(4 * phi[i]);
				}
			}
			if (sx != 0 || sy != 0)
				psi = mod90(atan2(sy, sx) / 4);
		}
		int members = 0;
		for (size_t k = 0; k < m; k++) {
			size_t i = idx[k];
			if (dist90(phi[i], psi) <= h)
				fr->of[i] = (int)fr->n, members++;
		}
		if (!members)
			fr->of[pick] = (int)fr->n, psi = phi[pick];
		double cs = cos(psi), sn = sin(psi);
		for (int c = 0; c < 3; c++) {
			fr->axes[fr->n][0][c] = cs * ea[c] + sn * eb[c];
			fr->axes[fr->n][1][c] = -sn * ea[c] + cs * eb[c];
		}
	}
	return 0;
}

/* Step 3 for one normal nv (of frame f in fr->of's terms), counted in r. */
static void snap_normal(double nv[3], int f, const struct frames *fr, const double up[3], double cos_a,
                        double sin_a, struct fct_ortho_result *r)
{
	double nu = fct_v3_dot(nv, up);
	if (fabs(nu) >= cos_a) {
		double sg = nu < 0 ? -1 : 1;
		for (int c = 0; c < 3; c++)
			nv[c] = sg * up[c];
		r->horizontal++;
	} else if (f >= 0) {
		const double (*ax)[3] = fr->axes[f];
		double d0 = fct_v3_dot(nv, ax[0]), d1 = fct_v3_dot(nv, ax[1]);
		int k = fabs(d1) > fabs(d0);
		double sg = (k ? d1 : d0) < 0 ? -1 : 1;
		for (int c = 0; c < 3; c++)
			nv[c] = sg * ax[k][c];
		r->vertical++;
	} else if (f == -1) {
		/* A vertical plane beyond the frames: only made vertical. */
		fct_v3_axpy(nv, nv, -nu, up);
		double len = norm3(nv);
		for (int c = 0; c < 3; c++)
			nv[c] /= len;
	} else {
		double bestd = HUGE_VAL;
		const double *bax = NULL;
		for (size_t g = 0; g < (fr->n ? 1 : 0); g++)   /* the main frame only */
			for (int k = 0; k < 2; k++) {
				double dd = fabs(fct_v3_dot(nv, fr->axes[g][k]));
				if (dd < bestd)
					bestd = dd, bax = fr->axes[g][k];
			}
		if (bax && bestd <= sin_a) {
			fct_v3_axpy(nv, nv, -fct_v3_dot(nv, bax), bax);
			double len = norm3(nv);
			for (int c = 0; c < 3; c++)
				nv[c] /= len;
			r->oblique++;
		}
	}
}

/* Step 4: plane p, whose normal was snapped from old's, turns about the
 * point of old nearest pivot (NULL or not finite: nearest the origin);
 * the angle turned, in degrees. */
static double turn_about_pivot(struct fct_plane *p, const struct fct_plane *old, const double *pivot)
{
	double q[3];
	if (pivot && isfinite(pivot[0]) && isfinite(pivot[1]) && isfinite(pivot[2]))
		fct_v3_axpy(q, pivot, -fct_plane_distance(old, pivot), old->n);
	else
		for (int c = 0; c < 3; c++)
			q[c] = -old->d * old->n[c];
	p->d = -fct_v3_dot(p->n, q);
	double cosang = fct_v3_dot(p->n, old->n);
	return acos(cosang > 1 ? 1 : cosang < -1 ? -1 : cosang) / DEG;
}

int fct_planes_orthogonalize(struct fct_plane *pl, size_t n, const double *weight,
                             const double *pivot, const double *up_prior, double angle,
                             struct fct_ortho_result *res, struct fct_err *err)
{
	struct fct_ortho_result r;
	memset(&r, 0, sizeof r);
	r.up[2] = 1;
	if (up_prior)
		memcpy(r.up, up_prior, sizeof r.up);
	if (!(angle > 0 && angle <= 40))
		return fct_fail(err, "snapping angle %g: must be in (0, 40] degrees", angle);
	if (n == 0) {
		if (res)
			*res = r;
		return 0;
	}
	const double cos_a = cos(angle * DEG), sin_a = sin(angle * DEG);
	int rc = -1;
	struct fct_arena a = { 0 };
	double *w = fct_arena_array(&a, n, sizeof *w, err);
	size_t *order = fct_arena_array(&a, n, sizeof *order, err);
	size_t *idx = fct_arena_array(&a, n, sizeof *idx, err);
	struct fct_plane *old = fct_arena_array(&a, n, sizeof *old, err);
	struct azimuths az = { fct_arena_array(&a, n, sizeof(double), err),
	                       fct_arena_array(&a, n + 1, sizeof(double), err), 0 };
	struct frames fr = { fct_arena_array(&a, n, sizeof(int), err), fct_arena_array(&a, n, sizeof(double), err),
	                     fct_arena_array(&a, MAX_FRAMES, sizeof *fr.axes, err), 0 };
	if (!w || !order || !idx || !old || !az.x || !az.cum || !fr.of || !fr.phi || !fr.axes)
		goto out;
	memcpy(old, pl, n * sizeof *pl);
	snap_weights(weight, n, w);
	for (size_t i = 0; i < n; i++)
		order[i] = i;
	if (sort_by_key(order, n, w, err) || find_up(pl, n, w, order, up_prior, cos_a, r.up, err) ||
	    vertical_frames(pl, n, w, order, r.up, angle, idx, &az, &fr, err))
		goto out;
	r.frames = fr.n;
	for (size_t i = 0; i < n; i++)
		snap_normal(pl[i].n, fr.of[i], &fr, r.up, cos_a, sin_a, &r);
	for (size_t i = 0; i < n; i++) {
		double ang = turn_about_pivot(&pl[i], &old[i], pivot ? pivot + 3 * i : NULL);
		if (ang > r.max_change)
			r.max_change = ang;
	}
	if (res)
		*res = r;
	rc = 0;
out:
	fct_arena_free(&a);
	return rc;
}

/* Section 8: depth scale ------------------------------------------------ */

/* Per plane: its camera-frame normal split into the unscaled and scaled
 * axes, for the cosine of a pair at any scale. */
struct split {
	double n[3];
};

static const int scaled_pinhole[3] = { 0, 0, 1 }, scaled_cyl[3] = { 1, 0, 1 };

/* Cosine of the angle between planes i and j once depth is scaled by lambda. */
static double pair_cos(const struct split *a, const struct split *b, const int *sc, double lambda)
{
	double num = 0, la = 0, lb = 0;
	for (int c = 0; c < 3; c++) {
		double f = sc[c] ? 1 / lambda : 1;
		double x = a->n[c] * f, y = b->n[c] * f;
		num += x * y, la += x * x, lb += y * y;
	}
	if (!(la > 0 && lb > 0))
		return 1;
	return num / sqrt(la * lb);
}

static double inlier_cost(const struct split *s, const struct fct_plane_pair *pairs,
                          const unsigned char *in, size_t np, const int *sc, double lambda)
{
	double f = 0;
	for (size_t k = 0; k < np; k++)
		if (in[k]) {
			double c = pair_cos(&s[pairs[k].a], &s[pairs[k].b], sc, lambda);
			f += pairs[k].w * c * c;
		}
	return f;
}

int fct_depth_scale_solve(const struct fct_plane *pl, size_t n, const struct fct_plane_pair *pairs,
                          size_t npairs, const double *to_cam, int cylindrical, double angle,
                          struct fct_scale_result *res, struct fct_err *err)
{
	struct fct_scale_result r = { 1, 0, 0, 0 };
	const int *sc = cylindrical ? scaled_cyl : scaled_pinhole;
	if (!(angle > 0 && angle < 90))
		return fct_fail(err, "depth-scale angle %g: must be in (0, 90) degrees", angle);
	int rc = -1;
	struct split *s = fct_alloc_array(n, sizeof *s, err);
	double *lam = fct_alloc_array(npairs, sizeof *lam, err);
	double *wt = fct_alloc_array(npairs, sizeof *wt, err);
	size_t *order = fct_alloc_array(npairs, sizeof *order, err);
	unsigned char *in = fct_alloc_array(npairs, 1, err);
	if (!s || !lam || !wt || !order || !in)
		goto out;
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++)
			s[i].n[c] = to_cam ? to_cam[4 * c] * pl[i].n[0] + to_cam[4 * c + 1] * pl[i].n[1] +
			                     to_cam[4 * c + 2] * pl[i].n[2]
			                   : pl[i].n[c];
	/* Proposals. */
	size_t nprop = 0;
	for (size_t k = 0; k < npairs; k++) {
		lam[k] = 0, wt[k] = -1;
		if (pairs[k].a >= n || pairs[k].b >= n || !(pairs[k].w > 0))
			continue;
		double a = 0, b = 0;
		for (int c = 0; c < 3; c++) {
			double x = s[pairs[k].a].n[c] * s[pairs[k].b].n[c];
			if (sc[c])
				b += x;
			else
				a += x;
		}
		if (!(a * b < 0) || fabs(a) < 1e-12 || fabs(b) < 1e-12)
			continue;
		/* Planes within 20 degrees of parallel as they are (fragments of
		 * one surface) would need a wild scale to meet at right angles. */
		if (fabs(a + b) > cos(FCT_PROJECT_SCALE_PARALLEL * DEG))
			continue;
		double l = sqrt(-b / a);
		if (!(l >= 1 / FCT_PROJECT_SCALE_RANGE && l <= FCT_PROJECT_SCALE_RANGE))
			continue;
		lam[k] = l, wt[k] = pairs[k].w;
		order[nprop++] = k;
	}
	r.pairs = nprop;
	if (nprop == 0) {
		rc = 0;
		goto out;
	}
	if (sort_by_key(order, nprop, wt, err))
		goto out;
	const double sin_t = sin(angle * DEG);
	double best = lam[order[0]], best_score = -1;
	size_t ncand = nprop < MAX_CANDIDATES ? nprop : MAX_CANDIDATES;
	for (size_t c = 0; c < ncand; c++) {
		double l = lam[order[c]], score = 0;
		for (size_t q = 0; q < nprop; q++) {
			size_t k = order[q];
			if (fabs(pair_cos(&s[pairs[k].a], &s[pairs[k].b], sc, l)) <= sin_t)
				score += pairs[k].w;
		}
		if (score > best_score ||
		    (score == best_score && fabs(log(l)) < fabs(log(best))))
			best_score = score, best = l;
	}
	/* Refine: golden section on log lambda over the inliers, twice. */
	double lambda = best;
	for (int it = 0; it < 3; it++) {
		memset(in, 0, npairs);
		for (size_t q = 0; q < nprop; q++) {
			size_t k = order[q];
			in[k] = fabs(pair_cos(&s[pairs[k].a], &s[pairs[k].b], sc, lambda)) <= sin_t;
		}
		if (it == 2)
			break;
		const double g = (sqrt(5) - 1) / 2;
		double lo = log(lambda) - 0.5, hi = log(lambda) + 0.5;
		double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
		double f1 = inlier_cost(s, pairs, in, npairs, sc, exp(x1));
		double f2 = inlier_cost(s, pairs, in, npairs, sc, exp(x2));
		for (int step = 0; step < 200 && hi - lo > 1e-14; step++) {
			if (f1 <= f2) {
				hi = x2, x2 = x1, f2 = f1;
				x1 = hi - g * (hi - lo);
				f1 = inlier_cost(s, pairs, in, npairs, sc, exp(x1));
			} else {
				lo = x1, x1 = x2, f1 = f2;
				x2 = lo + g * (hi - lo);
				f2 = inlier_cost(s, pairs, in, npairs, sc, exp(x2));
			}
		}
		lambda = exp((lo + hi) / 2);
	}
	double sw = 0, sc2 = 0;
	for (size_t k = 0; k < npairs; k++)
		if (in[k]) {
			double c = pair_cos(&s[pairs[k].a], &s[pairs[k].b], sc, lambda);
			sw += pairs[k].w, sc2 += pairs[k].w * c * c;
			r.inliers++;
		}
	r.rms_cos = sw > 0 ? sqrt(sc2 / sw) : 0;
	r.scale = lambda;
	rc = 0;
out:
	if (res)
		*res = r;
	free(s);
	free(lam);
	free(wt);
	free(order);
	free(in);
	return rc;
}

void fct_depth_scale_apply(double lambda, const double *pose, int cylindrical, double *xyz,
                           size_t nv, struct fct_plane *pl, size_t npl, struct fct_camera *cam)
{
	static const double identity[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
	const int *sc = cylindrical ? scaled_cyl : scaled_pinhole;
	double inv[12];
	if (!pose)
		pose = identity;
	fct_pose_invert(pose, inv);
	for (size_t i = 0; i < nv; i++) {
		double q[3];
		fct_pose_apply(inv, xyz + 3 * i, q);
		for (int c = 0; c < 3; c++)
			if (sc[c])
				q[c] *= lambda;
		fct_pose_apply(pose, q, xyz + 3 * i);
	}
	const double t[3] = { pose[3], pose[7], pose[11] };
	for (size_t i = 0; i < npl; i++) {
		/* Camera frame: n_c = R^T n, d_c = n.t + d; scaled: n_c / S, d_c;
		 * normalised; back: n = R n_c, d = d_c - n.t. */
		double nc[3], dc = fct_v3_dot(pl[i].n, t) + pl[i].d;
		for (int c = 0; c < 3; c++) {
			nc[c] = pose[c] * pl[i].n[0] + pose[4 + c] * pl[i].n[1] + pose[8 + c] * pl[i].n[2];
			if (sc[c])
				nc[c] /= lambda;
		}
		double len = norm3(nc);
		for (int c = 0; c < 3; c++)
			nc[c] /= len;
		dc /= len;
		for (int c = 0; c < 3; c++)
			pl[i].n[c] = pose[4 * c] * nc[0] + pose[4 * c + 1] * nc[1] + pose[4 * c + 2] * nc[2];
		pl[i].d = dc - fct_v3_dot(pl[i].n, t);
	}
	if (cam) {
		if (cam->kind == FCT_CAMERA_PINHOLE)
			cam->fx *= lambda, cam->fy *= lambda;
		else if (cam->kind == FCT_CAMERA_CYLINDRICAL)
			cam->f *= lambda;
	}
}

/* The whole stage -------------------------------------------------------- */

static int cmp_u32(const void *x, const void *y)
{
	uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
	return (a > b) - (a < b);
}

static int cmp_pair(const void *x, const void *y)
{
	const struct fct_plane_pair *a = x, *b = y;
	if (a->a != b->a)
		return a->a < b->a ? -1 : 1;
	return (a->b > b->b) - (a->b < b->b);
}

/* Sort pairs and sum the weights of equal ones; the count left. */
static size_t merge_pairs(struct fct_plane_pair *pp, size_t n)
{
	if (n)
		qsort(pp, n, sizeof *pp, cmp_pair);
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		if (k && pp[k - 1].a == pp[i].a && pp[k - 1].b == pp[i].b)
			pp[k - 1].w += pp[i].w;
		else
			pp[k++] = pp[i];
	}
	return k;
}

/* Pairs of patches that share mesh edges, weighted by the edges' length
 * (edges among more than four patches, non-manifold clutter, are skipped);
 * the caller weighs them again. */
static int adjacent_pairs(const struct fct_mesh *m, const struct fct_adj *adj,
                          const int32_t *patch, struct fct_arena *arena, struct fct_plane_pair **out,
                          size_t *nout, struct fct_err *err)
{
	struct fct_plane_pair *pp = NULL;
	size_t n = 0, cap = 0;
	for (size_t e = 0; e < adj->ne; e++) {
		uint32_t lab[4];
		int nl = 0, skip = 0;
		for (uint32_t k = adj->edge_fstart[e]; k < adj->edge_fstart[e + 1] && !skip; k++) {
			int32_t p = patch[adj->edge_f[k]];
			if (p < 0)
				continue;
			int dup = 0;
			for (int q = 0; q < nl; q++)
				dup |= lab[q] == (uint32_t)p;
			if (dup)
				continue;
			if (nl == 4)
				skip = 1;
			else
				lab[nl++] = (uint32_t)p;
		}
		if (skip || nl < 2)
			continue;
		double len = sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)adj->edge_v[2 * e],
		                               m->xyz + 3 * (size_t)adj->edge_v[2 * e + 1]));
		for (int a = 0; a < nl; a++)
			for (int b = a + 1; b < nl; b++) {
				if (fct_arena_grow(arena, (void **)&pp, &cap, n + 1, sizeof *pp, err))
					return -1;
				pp[n].a = lab[a] < lab[b] ? lab[a] : lab[b];
				pp[n].b = lab[a] < lab[b] ? lab[b] : lab[a];
				pp[n].w = len;
				n++;
			}
	}
	*out = pp, *nout = merge_pairs(pp, n);
	return 0;
}

/* The same from a wireframe: each edge between two patches, by its length. */
static int wire_pairs(const struct fct_mesh *m, const struct fct_wire *w, size_t nw,
                      struct fct_arena *arena, struct fct_plane_pair **out, size_t *nout,
                      struct fct_err *err)
{
	struct fct_plane_pair *pp = fct_arena_array(arena, nw, sizeof *pp, err);
	if (!pp)
		return -1;
	size_t n = 0;
	for (size_t i = 0; i < nw; i++) {
		if (w[i].p1 < 0 || w[i].p2 < 0 || w[i].p1 == w[i].p2)
			continue;
		uint32_t a = (uint32_t)w[i].p1, b = (uint32_t)w[i].p2;
		pp[n].a = a < b ? a : b;
		pp[n].b = a < b ? b : a;
		pp[n].w = sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)w[i].v1, m->xyz + 3 * (size_t)w[i].v2));
		n++;
	}
	*out = pp, *nout = merge_pairs(pp, n);
	return 0;
}

/* Area and area-weighted centroid of each patch (polygons fanned). */
static void patch_moments(const struct fct_mesh *m, const int32_t *patch, size_t np,
                          double *area, double *cen)
{
	for (size_t i = 0; i < np; i++)
		area[i] = 0, cen[3 * i] = cen[3 * i + 1] = cen[3 * i + 2] = 0;
	for (size_t f = 0; f < m->nf; f++) {
		if (patch[f] < 0)
			continue;
		size_t p = (size_t)patch[f];
		const uint32_t *fv = m->fvert + m->fstart[f];
		uint32_t ns = fct_face_size(m, f);
		for (uint32_t k = 1; k + 1 < ns; k++) {
			const double *a = m->xyz + 3 * (size_t)fv[0], *b = m->xyz + 3 * (size_t)fv[k],
			             *c = m->xyz + 3 * (size_t)fv[k + 1];
			double ar = fct_triangle_area2(a, b, c) / 2;
			area[p] += ar;
			for (int q = 0; q < 3; q++)
				cen[3 * p + q] += ar * (a[q] + b[q] + c[q]) / 3;
		}
	}
	for (size_t i = 0; i < np; i++)
		for (int q = 0; q < 3; q++)
			cen[3 * i + q] = area[i] > 0 ? cen[3 * i + q] / area[i] : NAN;
}

/* The same from a wireframe: each patch's boundary (its edges with the
 * patch on the left, holes running the other way) fanned from its first
 * vertex, the signed areas taken along the plane normal. */
static int wire_moments(const struct fct_mesh *m, const struct fct_wire *w, size_t nw,
                        const struct fct_plane *pl, size_t np, double *area, double *cen,
                        struct fct_err *err)
{
	double *apex = fct_alloc_array(3 * np, sizeof *apex, err);
	unsigned char *seen = calloc(np ? np : 1, 1);
	if (!apex || !seen) {
		free(apex), free(seen);
		return apex ? fct_fail(err, "out of memory") : -1;
	}
	for (size_t i = 0; i < np; i++)
		area[i] = 0, cen[3 * i] = cen[3 * i + 1] = cen[3 * i + 2] = 0;
	for (size_t i = 0; i < nw; i++)
		for (int side = 0; side < 2; side++) {
			int32_t p = side ? w[i].p2 : w[i].p1;
			if (p < 0)
				continue;
			const double *a = m->xyz + 3 * (size_t)(side ? w[i].v2 : w[i].v1),
			             *b = m->xyz + 3 * (size_t)(side ? w[i].v1 : w[i].v2);
			double *o = apex + 3 * (size_t)p;
			if (!seen[p]) {
				memcpy(o, a, 3 * sizeof *o);
				seen[p] = 1;
			}
			double u[3], v[3], x[3];
			fct_v3_sub(u, a, o);
			fct_v3_sub(v, b, o);
			fct_v3_cross(x, u, v);
			double ar = fct_v3_dot(x, pl[p].n) / 2;
			area[p] += ar;
			for (int q = 0; q < 3; q++)
				cen[3 * (size_t)p + q] += ar * (o[q] + a[q] + b[q]) / 3;
		}
	for (size_t i = 0; i < np; i++) {
		for (int q = 0; q < 3; q++)
			cen[3 * i + q] = area[i] > 0 ? cen[3 * i + q] / area[i] : NAN;
		if (!(area[i] > 0))
			area[i] = 0;
	}
	free(apex), free(seen);
	return 0;
}

/* Each plane's area and centroid, from the wireframe when wired (else
 * from the patches), into *area and *cen, taken from arena when NULL.
 * 0 or -1. */
static int plane_moments(const struct fct_mesh *m, int wired, const struct fct_wire *wire,
                         size_t nwire, const int32_t *patch, const struct fct_plane *pl, size_t npl,
                         struct fct_arena *arena, double **area, double **cen, struct fct_err *err)
{
	if (!*area)
		*area = fct_arena_array(arena, npl, sizeof **area, err);
	if (!*cen)
		*cen = fct_arena_array(arena, 3 * npl, sizeof **cen, err);
	if (!*area || !*cen)
		return -1;
	if (wired)
		return wire_moments(m, wire, nwire, pl, npl, *area, *cen, err);
	patch_moments(m, patch, npl, *area, *cen);
	return 0;
}

/* Make sure m has a scalar vertex column name (float when added). */
static int texcoord_column(struct fct_mesh *m, const char *name, struct fct_err *err)
{
	const struct fct_prop *c = fct_elem_find(&m->vertex, name);
	enum fct_type t = c && c->count_type == FCT_NONE ? c->type : FCT_FLOAT32;
	return fct_elem_add_scalar(&m->vertex, name, t, err) ? 0 : -1;
}

int fct_camera_texcoords(struct fct_mesh *m, const struct fct_camera *cam, const double *inv_pose,
                         size_t *no_pixel, struct fct_err *err)
{
	if (texcoord_column(m, "s", err) || texcoord_column(m, "t", err))
		return -1;
	struct fct_prop *ps = fct_elem_find(&m->vertex, "s"), *pt = fct_elem_find(&m->vertex, "t");
	for (size_t v = 0; v < m->nv; v++) {
		double s, t;
		if (fct_project_texcoord(cam, inv_pose, m->xyz + 3 * v, &s, &t)) {
			fct_prop_set(ps, v, s);
			fct_prop_set(pt, v, t);
		} else {
			++*no_pixel;
		}
	}
	return 0;
}

/* The point where the ray from the camera centre c through x meets the
 * plane (k = 1), or the point of the planes' line nearest that ray (k = 2),
 * into out; 0 when the ray runs (nearly) along the plane or the line. */
static int along_ray(const double *n, const double *d, size_t k, const double c[3],
                     const double x[3], double out[3])
{
	double r[3];
	fct_v3_sub(r, x, c);
	double rl = sqrt(fct_v3_dot(r, r));
	if (!(rl > 0))
		return 0;
	if (k == 1) {
		double nr = fct_v3_dot(n, r);
		if (!(fabs(nr) > 1e-3 * rl))
			return 0;
		double lambda = -(fct_v3_dot(n, c) + d[0]) / nr;
		fct_v3_axpy(out, c, lambda, r);
		return 1;
	}
	/* The line: direction u = n1 x n2 through the point p0 of both planes
	 * nearest the origin; then the closest points of two lines. */
	double u[3], p0[3], a[3], b[3];
	fct_v3_cross(u, n, n + 3);
	double uu = fct_v3_dot(u, u);
	if (!(uu > 1e-6))
		return 0;
	fct_v3_cross(a, u, n + 3);
	fct_v3_cross(b, n, u);
	for (int i = 0; i < 3; i++)
		p0[i] = (-d[0] * a[i] - d[1] * b[i]) / uu;
	double w0[3];
	fct_v3_sub(w0, p0, c);
	double A = uu, B = fct_v3_dot(u, r), C = fct_v3_dot(r, r), D = fct_v3_dot(u, w0), E = fct_v3_dot(r, w0);
	double den = A * C - B * B;
	if (!(den > 1e-6 * A * C))
		return 0;
	double s = (B * E - C * D) / den;
	fct_v3_axpy(out, p0, s, u);
	return 1;
}

/* The distinct planes of each vertex, ascending, as lists lab[lstart[v] ..
 * lstart[v + 1]): the patches of its faces, or of its wires' two sides;
 * the lists are taken from arena. */
static int vertex_labels(const struct fct_mesh *m, const struct fct_adj *adj, const int32_t *patch,
                         const struct fct_wire *wire, size_t nwire, struct fct_arena *arena,
                         size_t **lstart_out, uint32_t **lab_out, struct fct_err *err)
{
	size_t *lstart = fct_arena_zeroed(arena, m->nv + 1, sizeof *lstart, err);
	if (!lstart)
		return -1;
	/* Count an upper bound per vertex, fill, then sort and squeeze. */
	if (wire) {
		for (size_t i = 0; i < nwire; i++) {
			lstart[wire[i].v1 + 1] += 2;
			lstart[wire[i].v2 + 1] += 2;
		}
	} else {
		for (size_t v = 0; v < m->nv; v++)
			lstart[v + 1] = adj->vert_fstart[v + 1] - adj->vert_fstart[v];
	}
	for (size_t v = 0; v < m->nv; v++)
		lstart[v + 1] += lstart[v];
	uint32_t *lab = fct_arena_array(arena, lstart[m->nv], sizeof *lab, err);
	size_t *fill = fct_arena_array(arena, m->nv, sizeof *fill, err);
	if (!lab || !fill)
		return -1;
	memcpy(fill, lstart, m->nv * sizeof *fill);
	if (wire) {
		for (size_t i = 0; i < nwire; i++) {
			int32_t p[2] = { wire[i].p1, wire[i].p2 };
			uint32_t ends[2] = { wire[i].v1, wire[i].v2 };
			for (int e = 0; e < 2; e++)
				for (int s = 0; s < 2; s++)
					if (p[s] >= 0)
						lab[fill[ends[e]]++] = (uint32_t)p[s];
		}
	} else {
		for (size_t v = 0; v < m->nv; v++)
			for (uint32_t q = adj->vert_fstart[v]; q < adj->vert_fstart[v + 1]; q++)
				if (patch[adj->vert_f[q]] >= 0)
					lab[fill[v]++] = (uint32_t)patch[adj->vert_f[q]];
	}
	size_t out = 0;
	for (size_t v = 0; v < m->nv; v++) {
		uint32_t *l = lab + lstart[v];
		size_t k = fill[v] - lstart[v];
		qsort(l, k, sizeof *l, cmp_u32);
		lstart[v] = out;
		for (size_t q = 0; q < k; q++)
			if (q == 0 || l[q] != l[q - 1])
				lab[out++] = l[q];
	}
	lstart[m->nv] = out;
	*lstart_out = lstart, *lab_out = lab;
	return 0;
}

static uint32_t copy_of(const size_t *lstart, const uint32_t *lab, const long *first, size_t v,
                        int32_t p)
{
	for (size_t q = 1; q < lstart[v + 1] - lstart[v]; q++)
		if (lab[lstart[v] + q] == (uint32_t)p)
			return (uint32_t)(first[v] + (long)q - 1);
	return (uint32_t)v;
}

/* The copies of a torn vertex x0 seen from centre, one per plane
 * (normals n, offsets d), along its ray into out[3k]; 0 when one of the
 * rays meets its plane too obliquely, behind the camera or farther than
 * reach. */
static int tear_copies(const double *n, const double *d, size_t k, const double centre[3],
                       const double x0[3], double reach, double *out)
{
	double r[3];
	fct_v3_sub(r, x0, centre);
	double len = sqrt(fct_v3_dot(r, r));
	if (!(len > 0))
		return 0;
	for (size_t q = 0; q < k; q++) {
		double nr = fct_v3_dot(n + 3 * q, r);
		if (fabs(nr) < FCT_PROJECT_TEAR_COS * len)
			return 0;
		/* x0 + s r on the plane: n.(x0 + s r) + d = 0 */
		double s = -(fct_v3_dot(n + 3 * q, x0) + d[q]) / nr;
		if (!(1 + s > 0) || !(fabs(s) * len <= reach))
			return 0;
		fct_v3_axpy(out + 3 * q, x0, s, r);
	}
	return 1;
}

/* Tear the vertices tv[0..nt) (ascending; vertex tv[i] has the planes
 * lab[lstart[tv[i]]..] and copies txyz[3 * (tstart[i] + q)] for them) out
 * of m's wireframe *wirep[0..*nwp) as fct_project_mesh describes; the new
 * wires (malloc'd, as fct_wires_get's) replace the old; the scratch
 * comes from arena. */
static int tear_apply(struct fct_mesh *m, const size_t *lstart, const uint32_t *lab, const size_t *tv,
                      const size_t *tstart, size_t nt, const double *txyz, struct fct_arena *arena,
                      struct fct_wire **wirep, size_t *nwp, size_t *added, struct fct_err *err)
{
	const struct fct_wire *wire = *wirep;
	size_t nw = *nwp;
	size_t nv = m->nv, extra = tstart[nt] - nt;
	size_t *src = fct_arena_array(arena, nv + extra, sizeof *src, err);
	long *first = fct_arena_array(arena, nv, sizeof *first, err);   /* copy index of plane 2.. */
	if (!src || !first)
		return -1;
	for (size_t v = 0; v < nv; v++)
		src[v] = v, first[v] = -1;
	size_t at = nv;
	for (size_t i = 0; i < nt; i++) {
		first[tv[i]] = (long)at;
		for (size_t q = 1; q < tstart[i + 1] - tstart[i]; q++)
			src[at++] = tv[i];
	}
	if (fct_mesh_gather_vertices(m, src, nv + extra, err))
		return -1;
	for (size_t i = 0; i < nt; i++) {
		size_t k = tstart[i + 1] - tstart[i];
		for (size_t q = 0; q < k; q++) {
			size_t v = q == 0 ? tv[i] : (size_t)first[tv[i]] + q - 1;
			memcpy(m->xyz + 3 * v, txyz + 3 * (tstart[i] + q), 3 * sizeof *m->xyz);
		}
	}
	struct fct_wire *out = fct_alloc_array(2 * nw, sizeof *out, err);
	if (!out)
		return -1;
	/* The vertex standing for v on plane p. */
#define COPY(v, p) (first[v] < 0 ? (v) : copy_of(lstart, lab, first, (v), (p)))
	size_t no = 0;
	for (size_t e = 0; e < nw; e++) {
		struct fct_wire w = wire[e];
		uint32_t a1 = w.v1, b1 = w.v2, a2 = w.v1, b2 = w.v2;
		if (w.p1 >= 0)
			a1 = COPY(w.v1, w.p1), b1 = COPY(w.v2, w.p1);
		if (w.p2 >= 0)
			a2 = COPY(w.v1, w.p2), b2 = COPY(w.v2, w.p2);
		if (w.p1 < 0 || w.p2 < 0 || (a1 == a2 && b1 == b2)) {
			out[no++] = (struct fct_wire){ w.p1 >= 0 ? a1 : a2, w.p1 >= 0 ? b1 : b2, w.p1, w.p2 };
		} else {
			out[no++] = (struct fct_wire){ a1, b1, w.p1, -1 };
			out[no++] = (struct fct_wire){ a2, b2, -1, w.p2 };
		}
	}
#undef COPY
	free(*wirep);
	*wirep = out, *nwp = no;
	*added = extra;
	return 0;
}

/* The wireframe's edges in the image, to refuse a change that would make
 * two boundary edges of one patch cross there (tripatch triangulates each
 * patch in the image, which needs simple polygons): a uniform grid of
 * cells, each listing the edges whose box meets it.  An edge whose end
 * moves is listed again (stale entries cost a test, nothing more); edges
 * without a pixel at both ends are never listed. */
struct guard_node {
	uint32_t edge, next;
};
struct wire_guard {
	struct fct_arena *arena;       /* holds the arrays below */
	const struct fct_wire *w;
	const unsigned char *dead;     /* edges to ignore (may be NULL) */
	double *px;                    /* the pixel of each vertex (NaN: none) */
	double lo[2], h;
	size_t nx, ny;
	uint32_t *head, *stamp, query;
	size_t nw;
	struct guard_node *pool;
	size_t npool, pool_cap;
};

static void guard_pixel(const struct fct_camera *cam, const double *inv, const double x[3], double out[2])
{
	double s, t;
	if (fct_project_texcoord(cam, inv, x, &s, &t))
		out[0] = s * cam->width, out[1] = t * cam->height;
	else
		out[0] = out[1] = NAN;
}

static void guard_cells(const struct wire_guard *g, const double a[2], const double b[2], size_t c[4])
{
	for (int q = 0; q < 2; q++) {
		double lo = (fmin(a[q], b[q]) - g->lo[q]) / g->h, hi = (fmax(a[q], b[q]) - g->lo[q]) / g->h;
		size_t n = q ? g->ny : g->nx;
		c[q] = lo < 0 ? 0 : lo >= (double)n ? n - 1 : (size_t)lo;
		c[2 + q] = hi < 0 ? 0 : hi >= (double)n ? n - 1 : (size_t)hi;
	}
}

static int guard_add(struct wire_guard *g, size_t e, struct fct_err *err)
{
	const double *a = g->px + 2 * (size_t)g->w[e].v1, *b = g->px + 2 * (size_t)g->w[e].v2;
	if (!isfinite(a[0]) || !isfinite(b[0]))
		return 0;
	size_t c[4];
	guard_cells(g, a, b, c);
	for (size_t y = c[1]; y <= c[3]; y++)
		for (size_t x = c[0]; x <= c[2]; x++) {
			if (fct_arena_grow(g->arena, (void **)&g->pool, &g->pool_cap, g->npool + 1, sizeof *g->pool,
			                   err))
				return -1;
			if (g->npool >= UINT32_MAX)
				return fct_fail(err, "too many wireframe edges");
			size_t cell = y * g->nx + x;
			g->pool[g->npool] = (struct guard_node){ (uint32_t)e, g->head[cell] };
			g->head[cell] = (uint32_t)g->npool++;
		}
	return 0;
}

/* The guard of wireframe w[0..nw) of m seen by cam, its arrays taken from
 * arena. */
static int guard_init(struct wire_guard *g, struct fct_arena *arena, const struct fct_mesh *m,
                      const struct fct_camera *cam, const double *inv, const struct fct_wire *w,
                      size_t nw, struct fct_err *err)
{
	memset(g, 0, sizeof *g);
	g->arena = arena, g->w = w, g->nw = nw;
	g->px = fct_arena_array(arena, 2 * (m->nv ? m->nv : 1), sizeof *g->px, err);
	g->stamp = fct_arena_zeroed(arena, nw, sizeof *g->stamp, err);
	if (!g->px || !g->stamp)
		return -1;
	double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
	for (size_t v = 0; v < m->nv; v++) {
		guard_pixel(cam, inv, m->xyz + 3 * v, g->px + 2 * v);
		for (int q = 0; q < 2 && isfinite(g->px[2 * v]); q++)
			lo[q] = fmin(lo[q], g->px[2 * v + q]), hi[q] = fmax(hi[q], g->px[2 * v + q]);
	}
	if (!(lo[0] <= hi[0]))
		lo[0] = lo[1] = 0, hi[0] = hi[1] = 1;
	/* About one cell per edge. */
	double wx = fmax(hi[0] - lo[0], 1e-9), wy = fmax(hi[1] - lo[1], 1e-9);
	double cells = nw < 16 ? 16 : nw > (1u << 20) ? (double)(1u << 20) : (double)nw;
	g->h = fmax(sqrt(wx * wy / cells), fmax(wx, wy) / 4096);
	g->lo[0] = lo[0], g->lo[1] = lo[1];
	g->nx = (size_t)(wx / g->h) + 1, g->ny = (size_t)(wy / g->h) + 1;
	g->head = fct_arena_array(arena, g->nx * g->ny, sizeof *g->head, err);
	if (!g->head)
		return -1;
	memset(g->head, 0xff, g->nx * g->ny * sizeof *g->head);
	for (size_t e = 0; e < nw; e++)
		if (guard_add(g, e, err))
			return -1;
	return 0;
}

/* Would the segment from vertex a at pa to vertex b at pb, a boundary of
 * patches p1 and p2 (-1: none), meet another edge of those patches?  Edge
 * skip_edge and the edges touching vertex skip are ignored; vertex moved is
 * taken at pmoved. */
static int guard_crosses(struct wire_guard *g, uint32_t a, const double pa[2], uint32_t b,
                         const double pb[2], int32_t p1, int32_t p2, uint32_t skip, size_t skip_edge,
                         uint32_t moved, const double pmoved[2])
{
	if (!isfinite(pa[0]) || !isfinite(pb[0]))
		return 1;
	if (++g->query == 0) {
		memset(g->stamp, 0, (g->nw ? g->nw : 1) * sizeof *g->stamp);
		g->query = 1;
	}
	size_t c[4];
	guard_cells(g, pa, pb, c);
	for (size_t y = c[1]; y <= c[3]; y++)
		for (size_t x = c[0]; x <= c[2]; x++)
			for (uint32_t n = g->head[y * g->nx + x]; n != UINT32_MAX; n = g->pool[n].next) {
				uint32_t e = g->pool[n].edge;
				if (g->stamp[e] == g->query)
					continue;
				g->stamp[e] = g->query;
				const struct fct_wire *f = g->w + e;
				if ((g->dead && g->dead[e]) || e == skip_edge || f->v1 == skip || f->v2 == skip)
					continue;
				int mine = (p1 >= 0 && (f->p1 == p1 || f->p2 == p1)) ||
				           (p2 >= 0 && (f->p1 == p2 || f->p2 == p2));
				if (!mine)
					continue;
				const double *c1 = f->v1 == moved ? pmoved : g->px + 2 * (size_t)f->v1;
				const double *c2 = f->v2 == moved ? pmoved : g->px + 2 * (size_t)f->v2;
				if (!isfinite(c1[0]) || !isfinite(c2[0]))
					continue;
				if (fct_segments_conflict(pa, pb, c1, c2, a, b, f->v1, f->v2))
					return 1;
			}
	return 0;
}

/* Drop the vertices of crease chains that projection put on the line of
 * their two planes (see fct_project_mesh), renumbering the rest; the
 * scratch comes from arena. */
static int straighten(struct fct_mesh *m, const struct fct_plane *pl, double bound,
                      const struct fct_camera *cam, const double *inv, struct fct_arena *arena,
                      struct fct_wire **wirep, size_t *nwp, size_t *dropped, size_t *kept,
                      struct fct_err *err)
{
	struct fct_wire *w = *wirep;
	size_t nw = *nwp, nv = m->nv;
	struct wire_guard g;
	memset(&g, 0, sizeof g);
	/* Each vertex's first two edges, and its edge count. */
	size_t *inc = fct_arena_array(arena, 2 * nv, sizeof *inc, err);
	uint32_t *deg = fct_arena_zeroed(arena, nv, sizeof *deg, err);
	unsigned char *dead = fct_arena_zeroed(arena, nw, 1, err), *gone = fct_arena_zeroed(arena, nv, 1, err);
	if (!inc || !deg || !dead || !gone)
		return -1;
	if (cam) {
		if (guard_init(&g, arena, m, cam, inv, w, nw, err))
			return -1;
		g.dead = dead;
	}
	for (size_t e = 0; e < nw; e++) {
		uint32_t ends[2] = { w[e].v1, w[e].v2 };
		for (int q = 0; q < 2; q++) {
			if (deg[ends[q]] < 2)
				inc[2 * (size_t)ends[q] + deg[ends[q]]] = e;
			deg[ends[q]]++;
		}
	}
	size_t ndrop = 0;
	for (size_t v = 0; v < nv; v++) {
		if (deg[v] != 2)
			continue;
		size_t e1 = inc[2 * v], e2 = inc[2 * v + 1];
		if (e1 == e2)
			continue;
		/* e1 as x -> v and e2 as v -> y, each with its (left, right). */
		struct fct_wire a = w[e1], b = w[e2];
		if (a.v2 != v)
			a = (struct fct_wire){ a.v2, a.v1, a.p2, a.p1 };
		if (b.v1 != v)
			b = (struct fct_wire){ b.v2, b.v1, b.p2, b.p1 };
		if (a.p1 != b.p1 || a.p2 != b.p2 || a.p1 < 0 || a.p2 < 0 || a.p1 == a.p2 || a.v1 == b.v2)
			continue;
		const double *x = m->xyz + 3 * v;
		double tol = 1e-9 * (bound + fabs(x[0]) + fabs(x[1]) + fabs(x[2]));
		if (fabs(fct_plane_distance(&pl[a.p1], x)) > tol || fabs(fct_plane_distance(&pl[a.p2], x)) > tol)
			continue;
		if (cam && guard_crosses(&g, a.v1, g.px + 2 * (size_t)a.v1, b.v2, g.px + 2 * (size_t)b.v2, a.p1,
		                         a.p2, (uint32_t)v, (size_t)-1, UINT32_MAX, NULL)) {
			(*kept)++;
			continue;
		}
		/* x -> y replaces both; y's record of e2 becomes e1. */
		w[e1] = (struct fct_wire){ a.v1, b.v2, a.p1, a.p2 };
		dead[e2] = 1, gone[v] = 1, ndrop++;
		if (cam && guard_add(&g, e1, err))
			return -1;
		uint32_t y = b.v2;
		for (int q = 0; q < 2 && q < (int)deg[y]; q++)
			if (inc[2 * (size_t)y + q] == e2)
				inc[2 * (size_t)y + q] = e1;
	}
	if (ndrop) {
		size_t *keep = fct_arena_array(arena, nv - ndrop, sizeof *keep, err);
		uint32_t *map = fct_arena_array(arena, nv, sizeof *map, err);
		if (!keep || !map)
			return -1;
		size_t nk = 0;
		for (size_t v = 0; v < nv; v++)
			if (!gone[v])
				map[v] = (uint32_t)nk, keep[nk++] = v;
		size_t ne = 0;
		for (size_t e = 0; e < nw; e++)
			if (!dead[e])
				w[ne++] = (struct fct_wire){ map[w[e].v1], map[w[e].v2], w[e].p1, w[e].p2 };
		if (fct_mesh_gather_vertices(m, keep, nk, err))
			return -1;
		*nwp = ne;
	}
	*dropped = ndrop;
	return 0;
}

/* How many faces around vertex v (all its faces, fanned from their first
 * corner) face against their patch's plane normal. */
static size_t faces_against(const struct fct_mesh *m, const struct fct_adj *adj, const int32_t *patch,
                            const struct fct_plane *pl, size_t v)
{
	size_t bad = 0;
	for (uint32_t q = adj->vert_fstart[v]; q < adj->vert_fstart[v + 1]; q++) {
		uint32_t f = adj->vert_f[q];
		if (patch[f] < 0)
			continue;
		const uint32_t *fv = m->fvert + m->fstart[f];
		uint32_t n = fct_face_size(m, f);
		double area[3] = { 0, 0, 0 };
		for (uint32_t i = 1; i + 1 < n; i++) {
			double e1[3], e2[3], c[3];
			fct_v3_sub(e1, m->xyz + 3 * (size_t)fv[i], m->xyz + 3 * (size_t)fv[0]);
			fct_v3_sub(e2, m->xyz + 3 * (size_t)fv[i + 1], m->xyz + 3 * (size_t)fv[0]);
			fct_v3_cross(c, e1, e2);
			fct_v3_add(area, area, c);
		}
		bad += fct_v3_dot(area, pl[patch[f]].n) <= 0;
	}
	return bad;
}

/* fct_project_mesh's state: what it read from the mesh, the camera, the
 * figures, and the scratch of section 5. */
struct stage {
	struct fct_mesh *m;
	const struct fct_project_params *p;
	struct fct_project_stats st;
	struct fct_arena arena;          /* every scratch array, freed by stage_free */
	/* Read from the mesh; malloc'd by the readers. */
	struct fct_plane *pl;
	size_t npl;
	int32_t *patch;                  /* per face; NULL for a wireframe */
	int wired;                       /* the vertices take their planes from the wires */
	struct fct_wire *wire;
	size_t nwire;
	struct fct_adj adj;
	/* Each vertex's planes (vertex_labels), from the arena. */
	size_t *lstart;
	uint32_t *lab;
	/* The camera and pose comments. */
	struct fct_camera cam;
	int have_cam, have_pose, cyl;
	double pose[12], inv[12];
	const double *to_cam;            /* inv, or NULL without a pose */
	double centre[3];                /* the camera centre in the mesh's frame */
	/* Section 8. */
	double *area, *cen;              /* plane_moments, once taken */
	int planes_changed;
	/* Section 5: the planes of the vertex at hand, the image guard, the
	 * torn vertices (vertex tv[i] has copies txyz[3 * (tstart[i] ..
	 * tstart[i + 1])), one per plane) and the running sums of the figures. */
	double *nbuf, *dbuf;
	int guarded;
	struct wire_guard guard;
	size_t *wstart, *wlist;          /* each vertex's wires: wlist[wstart[v] .. wstart[v + 1]) */
	size_t *tv, *tstart, ncopies, tv_cap, tstart_cap, txyz_cap;
	double *txyz;
	double move_sum, r2_before, r2_after;
	size_t nres;
};

static void stage_free(struct stage *s)
{
	fct_arena_free(&s->arena);
	free(s->pl), free(s->patch), free(s->wire);
	fct_adj_free(&s->adj);
}

/* The mean edge length: of the wireframe's edges when wired, else of the
 * mesh's. */
static double mean_edge(const struct stage *s)
{
	const struct fct_mesh *m = s->m;
	double sum = 0;
	size_t nedges = s->wired ? s->nwire : s->adj.ne;
	for (size_t e = 0; e < nedges; e++)
		sum += s->wired ? sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)s->wire[e].v1,
		                                    m->xyz + 3 * (size_t)s->wire[e].v2))
		                : sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)s->adj.edge_v[2 * e],
		                                    m->xyz + 3 * (size_t)s->adj.edge_v[2 * e + 1]));
	return nedges ? sum / (double)nedges : 0;
}

/* Read the planes, the patches or the wireframe, each vertex's planes, the
 * camera and the pose from s->m. */
static int stage_read(struct stage *s, struct fct_err *err)
{
	struct fct_mesh *m = s->m;
	if (fct_planes_get(m, &s->pl, &s->npl, err))
		return -1;
	if (!fct_mesh_find_elem(m, "plane"))
		return fct_fail(err, "no plane element (the planes of segplanes)");
	int present = 0;
	if (fct_patches_get(m, &s->patch, &present, (long)s->npl, err))
		return -1;
	/* A mesh without faces may be a wireframe (simpchain's output): its
	 * vertices then take their planes from the edges' two sides. */
	if (!present || (m->nf == 0 && fct_mesh_find_elem(m, "edge"))) {
		if (fct_wires_get(m, (long)s->npl, &s->wire, &s->nwire, &s->wired, err))
			return -1;
		if (!s->wired)
			return fct_fail(err, "no face property patch (the labels of segplanes) nor edge element "
			                     "(simpchain's wireframe)");
	}
	s->st.nvert = m->nv, s->st.nplanes = s->npl;
	if (fct_adj_build(&s->adj, m, err) ||
	    vertex_labels(m, &s->adj, s->patch, s->wire, s->nwire, &s->arena, &s->lstart, &s->lab, err))
		return -1;
	s->st.mean_edge = mean_edge(s);

	s->have_cam = fct_header_camera(m, &s->cam, err);
	if (s->have_cam < 0)
		return -1;
	s->have_pose = fct_header_pose(m, s->pose, err);
	if (s->have_pose < 0)
		return -1;
	if (s->have_pose) {
		if (fct_pose_check(s->pose, 1e-3, err)) {
			fct_err_prefix(err, "comment pose");
			return -1;
		}
		fct_pose_invert(s->pose, s->inv);
		s->to_cam = s->inv;
		/* Both camera models see from their origin. */
		s->centre[0] = s->pose[3], s->centre[1] = s->pose[7], s->centre[2] = s->pose[11];
	}
	s->cyl = s->have_cam && s->cam.kind == FCT_CAMERA_CYLINDRICAL;
	return 0;
}

/* Section 8, Figure 8: scale camera-frame depth so that adjacent planes
 * become orthogonal (points, planes and the camera's focal length). */
static int fix_depth_scale(struct stage *s, struct fct_err *err)
{
	struct fct_mesh *m = s->m;
	const struct fct_project_params *p = s->p;
	struct fct_plane_pair *pairs = NULL;
	size_t npairs = 0;
	if (s->wired ? wire_pairs(m, s->wire, s->nwire, &s->arena, &pairs, &npairs, err)
	             : adjacent_pairs(m, &s->adj, s->patch, &s->arena, &pairs, &npairs, err))
		return -1;
	/* Weigh each adjacent pair by its smaller patch's area, and leave
	 * out patches under 1% of the labelled area: the planes of large
	 * patches are the reliable ones, while small patches of a noisy,
	 * curved or cluttered surface meet at every angle (and more of
	 * them look orthogonal the more depth is stretched). */
	if (plane_moments(m, s->wired, s->wire, s->nwire, s->patch, s->pl, s->npl, &s->arena, &s->area,
	                  &s->cen, err))
		return -1;
	double total = 0;
	for (size_t i = 0; i < s->npl; i++)
		total += s->area[i];
	size_t kept = 0;
	for (size_t k = 0; k < npairs; k++) {
		double a = s->area[pairs[k].a], b = s->area[pairs[k].b], w = a < b ? a : b;
		if (w >= FCT_PROJECT_SCALE_MIN_AREA * total && w > 0) {
			pairs[kept] = pairs[k];
			pairs[kept++].w = w;
		}
	}
	npairs = kept;
	double angle = p->scale_angle > 0 ? p->scale_angle
	             : p->ortho_angle > 0 ? p->ortho_angle : FCT_PROJECT_SCALE_ANGLE;
	struct fct_scale_result *res = &s->st.scale_res;
	if (fct_depth_scale_solve(s->pl, s->npl, pairs, npairs, s->to_cam, s->cyl, angle, res, err))
		return -1;
	s->st.scaled = 1;
	if (res->scale != 1) {
		fct_depth_scale_apply(res->scale, s->have_pose ? s->pose : NULL, s->cyl, m->xyz, m->nv, s->pl,
		                      s->npl, s->have_cam ? &s->cam : NULL);
		if (s->have_cam && fct_header_set_camera(m, &s->cam, err))
			return -1;
		s->planes_changed = 1;
	}
	return 0;
}

/* Section 8: snap the planes to a frame; with a camera or a pose, up is
 * sought near the camera's -y (image rows run down). */
static int snap_planes(struct stage *s, struct fct_err *err)
{
	/* The scale fix's moments serve unless it moved the points. */
	if ((!s->area || s->planes_changed) &&
	    plane_moments(s->m, s->wired, s->wire, s->nwire, s->patch, s->pl, s->npl, &s->arena, &s->area,
	                  &s->cen, err))
		return -1;
	double prior[3], down[3] = { 0, -1, 0 };
	int use_prior = s->have_cam || s->have_pose;
	if (s->have_pose) {
		double o[3] = { 0, 0, 0 }, a[3], b[3];
		fct_pose_apply(s->pose, down, a);
		fct_pose_apply(s->pose, o, b);
		fct_v3_sub(prior, a, b);
	} else {
		memcpy(prior, down, sizeof prior);
	}
	if (fct_planes_orthogonalize(s->pl, s->npl, s->area, s->cen, use_prior ? prior : NULL,
	                             s->p->ortho_angle, &s->st.ortho_res, err))
		return -1;
	s->st.ortho = 1;
	s->planes_changed = 1;
	return 0;
}

/* The image guard of a wireframe seen by the camera, and each vertex's
 * wires for it. */
static int guard_setup(struct stage *s, struct fct_err *err)
{
	const struct fct_mesh *m = s->m;
	const struct fct_wire *wire = s->wire;
	size_t nwire = s->nwire;
	if (guard_init(&s->guard, &s->arena, m, &s->cam, s->to_cam, wire, nwire, err))
		return -1;
	size_t *wstart = s->wstart = fct_arena_zeroed(&s->arena, m->nv + 1, sizeof *wstart, err);
	size_t *wlist = s->wlist = fct_arena_array(&s->arena, 2 * nwire, sizeof *wlist, err);
	if (!wstart || !wlist)
		return -1;
	for (size_t e = 0; e < nwire; e++)
		wstart[wire[e].v1 + 1]++, wstart[wire[e].v2 + 1]++;
	for (size_t v = 0; v < m->nv; v++)
		wstart[v + 1] += wstart[v];
	for (size_t e = 0; e < nwire; e++)
		wlist[wstart[wire[e].v1]++] = e, wlist[wstart[wire[e].v2]++] = e;
	for (size_t v = m->nv; v > 0; v--)
		wstart[v] = wstart[v - 1];
	wstart[0] = 0;
	return 0;
}

/* What section 5's rules made of a vertex: its one verdict, each rule
 * taking it from the one before. */
enum verdict {
	KEPT,         /* on no plane: nothing to do */
	MOVED,        /* projected onto its plane, line or point (perhaps along its ray) */
	OVER_BOUND,   /* the move was longer than the bound: kept, as the paper does */
	FLIPPED,      /* the move would turn a face against its plane: kept */
	APART,        /* a rank-deficient move that left it on none of its planes
	                 (between parallel ones): moved, unless torn or put back */
	CROSSING,     /* the move would make a patch boundary cross itself in the
	                 image: kept */
	RAYED,        /* of one plane, refused: moved along its ray onto the plane */
	TORN,         /* torn: one copy per plane along its ray */
};

/* The vertex at hand: its planes, where it was, where the rules put it. */
struct vertex {
	size_t v, k;             /* its index; its number of planes */
	const uint32_t *vl;      /* its planes, vl[0..k), also in s->nbuf and s->dbuf */
	double x0[3];            /* where it was */
	double *x;               /* where it is (in the mesh) */
	struct fct_point_fit fit;
	enum verdict vd;
};

/* Section 5 proper (eq. 2): to the point of the vertex's planes nearest
 * it -- its foot on one plane, the nearest point of the line of two, the
 * least-squares point of more (fct_project_point) -- or kept when that is
 * farther than the bound. */
static int onto_planes(struct stage *s, struct vertex *c, struct fct_err *err)
{
	if (fct_project_point(s->nbuf, s->dbuf, c->k, c->x, s->st.bound, s->p->rank_tol, s->p->fallback, c->x,
	                      &c->fit, err))
		return -1;
	c->vd = c->fit.used > 0 ? MOVED : c->fit.rank > 0 ? OVER_BOUND : KEPT;
	return 0;
}

/* Range noise lies along the rays: with along_rays, a vertex on one or two
 * planes moves along its own ray (to the plane, or to the point of the
 * line nearest the ray) rather than perpendicularly, which keeps it on its
 * pixel, so its faces keep their orientation in the image. */
static void move_along_ray(struct stage *s, struct vertex *c)
{
	if (!(s->have_cam && s->p->along_rays && c->vd == MOVED && c->fit.used == c->fit.rank &&
	      (c->k == 1 || c->k == 2)))
		return;
	double y[3];
	if (along_ray(s->nbuf, s->dbuf, c->k, s->centre, c->x0, y) && sqrt(fct_v3_dist2(y, c->x0)) <= s->st.bound) {
		memcpy(c->x, y, sizeof y);
		c->fit.move = sqrt(fct_v3_dist2(y, c->x0));
		s->st.along_ray++;
	}
}

/* A move must not turn a face around the vertex against its plane (a
 * sliver whose corner slides across its opposite edge): such a move is
 * refused like one over the bound.  The faces of a wireframe's mesh
 * (without patches) have no plane to turn against. */
static void refuse_flip(struct stage *s, struct vertex *c)
{
	if (c->vd != MOVED || !s->patch)
		return;
	double x1[3];
	memcpy(x1, c->x, sizeof x1);
	memcpy(c->x, c->x0, sizeof c->x0);
	size_t against = faces_against(s->m, &s->adj, s->patch, s->pl, c->v);
	memcpy(c->x, x1, sizeof x1);
	if (faces_against(s->m, &s->adj, s->patch, s->pl, c->v) > against) {
		memcpy(c->x, c->x0, sizeof c->x0);
		c->vd = FLIPPED;
		s->st.flip_refused++;
	}
}

/* The numerical rank of the vertex's normals is below min(k, 3). */
static int rank_deficient(const struct vertex *c)
{
	return c->fit.rank > 0 && c->fit.rank < (c->k < 3 ? (int)c->k : 3);
}

/* A rank-deficient point that lies on none of its planes: parallel planes
 * apart, it went between them. */
static void between_parallels(const struct stage *s, struct vertex *c)
{
	if (c->vd != MOVED || !rank_deficient(c))
		return;
	for (size_t q = 0; q < c->k; q++)
		if (fabs(fct_plane_distance(&s->pl[c->vl[q]], c->x)) > FCT_PROJECT_TEAR_APART * s->st.bound) {
			c->vd = APART;
			return;
		}
}

/* The image guard: a move must not make a patch's boundary cross itself
 * in the image, where tripatch triangulates it.  A move it lets through
 * updates the guard. */
static int image_guard(struct stage *s, struct vertex *c, struct fct_err *err)
{
	if (!s->guarded || c->vd != MOVED)
		return 0;
	struct wire_guard *g = &s->guard;
	uint32_t v = (uint32_t)c->v;
	double q[2];
	guard_pixel(&s->cam, s->to_cam, c->x, q);
	int crossing = !isfinite(q[0]);
	for (size_t i = s->wstart[v]; i < s->wstart[v + 1] && !crossing; i++) {
		const struct fct_wire *f = s->wire + s->wlist[i];
		uint32_t o = f->v1 == v ? f->v2 : f->v1;
		crossing = guard_crosses(g, v, q, o, g->px + 2 * (size_t)o, f->p1, f->p2, UINT32_MAX, s->wlist[i],
		                         v, q);
	}
	if (crossing) {
		memcpy(c->x, c->x0, sizeof c->x0);
		c->vd = CROSSING;
		s->st.cross_refused++;
		return 0;
	}
	memcpy(g->px + 2 * (size_t)v, q, sizeof q);
	for (size_t i = s->wstart[v]; i < s->wstart[v + 1]; i++)
		if (guard_add(g, s->wlist[i], err))
			return -1;
	return 0;
}

/* Tearing along rays, what the image allows instead of a refused move (or
 * one between parallel planes): along the vertex's ray onto each of its
 * planes, which keeps its pixel -- one plane: the vertex moves; more: it
 * is torn, its copies kept for tear_apply. */
static int tear_along_rays(struct stage *s, struct vertex *c, struct fct_err *err)
{
	size_t k = c->k;
	if (!(s->wired && s->p->tear && s->have_cam && k >= 1 &&
	      (c->vd == OVER_BOUND || c->vd == APART || c->vd == CROSSING)))
		return 0;
	if (fct_arena_grow(&s->arena, (void **)&s->txyz, &s->txyz_cap, 3 * (s->ncopies + k), sizeof *s->txyz,
	                   err))
		return -1;
	double *copies = s->txyz + 3 * s->ncopies;
	/* A vertex of one plane refused for its distance is far off that
	 * plane: the ray may take it at most FCT_PROJECT_RAY_EDGES bounds (a
	 * small patch's plane is not to be trusted far out). */
	double reach = k == 1 && c->vd == OVER_BOUND ? FCT_PROJECT_RAY_EDGES : FCT_PROJECT_TEAR_EDGES;
	if (!tear_copies(s->nbuf, s->dbuf, k, s->centre, c->x0, reach * s->st.bound, copies)) {
		if (c->vd == APART) {
			/* between the planes is no better than where it was */
			memcpy(c->x, c->x0, sizeof c->x0);
			c->vd = OVER_BOUND;
		}
		return 0;
	}
	memcpy(c->x, copies, sizeof c->x0);
	if (k == 1) {
		c->vd = RAYED;
		s->st.ray_fallback++;
		return 0;
	}
	size_t n = s->st.torn;
	if (fct_arena_grow(&s->arena, (void **)&s->tv, &s->tv_cap, n + 1, sizeof *s->tv, err) ||
	    fct_arena_grow(&s->arena, (void **)&s->tstart, &s->tstart_cap, n + 2, sizeof *s->tstart, err))
		return -1;
	s->tv[n] = c->v, s->tstart[n] = s->ncopies;
	s->ncopies += k;
	s->tstart[n + 1] = s->ncopies;
	s->st.torn = n + 1;
	c->vd = TORN;
	return 0;
}

/* The figures of the vertex's verdict. */
static void account(struct stage *s, const struct vertex *c)
{
	struct fct_project_stats *st = &s->st;
	int kk = c->k < 3 ? (int)c->k : 3;
	st->by_k[kk]++;
	if (c->vd == MOVED || c->vd == APART) {
		st->moved[kk]++;
		s->move_sum += c->fit.move;
		if (c->fit.move > st->max_move)
			st->max_move = c->fit.move;
		if (c->fit.used < c->fit.rank)
			st->fallback++;
	} else if (c->vd == OVER_BOUND) {
		st->rejected++;
	}
	if (rank_deficient(c))
		st->rank_deficient++;
	/* A torn vertex's copies are the last k of txyz, one per plane. */
	const double *torn = c->vd == TORN ? s->txyz + 3 * (s->ncopies - c->k) : NULL;
	for (size_t q = 0; q < c->k; q++) {
		double r = fct_plane_distance(&s->pl[c->vl[q]], torn ? torn + 3 * q : c->x);
		s->r2_after += r * r;
		if (fabs(r) > st->max_after)
			st->max_after = fabs(r);
	}
	s->nres += c->k;
}

/* Section 5's rules for vertex v, in order, each taking the verdict of the
 * one before. */
static int project_vertex(struct stage *s, size_t v, struct fct_err *err)
{
	struct vertex c;
	c.v = v, c.k = s->lstart[v + 1] - s->lstart[v], c.vl = s->lab + s->lstart[v];
	c.x = s->m->xyz + 3 * v;
	memcpy(c.x0, c.x, sizeof c.x0);
	for (size_t q = 0; q < c.k; q++) {
		const struct fct_plane *pl = &s->pl[c.vl[q]];
		memcpy(s->nbuf + 3 * q, pl->n, 3 * sizeof *s->nbuf);
		s->dbuf[q] = pl->d;
	}
	for (size_t q = 0; q < c.k; q++) {
		double r = fct_plane_distance(&s->pl[c.vl[q]], c.x);
		s->r2_before += r * r;
	}
	if (onto_planes(s, &c, err))
		return -1;
	move_along_ray(s, &c);
	refuse_flip(s, &c);
	between_parallels(s, &c);
	if (image_guard(s, &c, err) || tear_along_rays(s, &c, err))
		return -1;
	account(s, &c);
	return 0;
}

/* Section 5 on every vertex, then the means of the figures. */
static int project_vertices(struct stage *s, struct fct_err *err)
{
	const struct fct_mesh *m = s->m;
	const struct fct_project_params *p = s->p;
	size_t maxdeg = 1;
	for (size_t v = 0; v < m->nv; v++)
		if (s->lstart[v + 1] - s->lstart[v] > maxdeg)
			maxdeg = s->lstart[v + 1] - s->lstart[v];
	s->nbuf = fct_arena_array(&s->arena, 3 * maxdeg, sizeof *s->nbuf, err);
	s->dbuf = fct_arena_array(&s->arena, maxdeg, sizeof *s->dbuf, err);
	if (!s->nbuf || !s->dbuf)
		return -1;
	s->st.bound = p->max_move >= 0 ? p->max_move : p->max_move_edges * s->st.mean_edge;
	s->guarded = s->wired && s->have_cam;
	if (s->guarded && guard_setup(s, err))
		return -1;
	for (size_t v = 0; v < m->nv; v++)
		if (project_vertex(s, v, err))
			return -1;
	struct fct_project_stats *st = &s->st;
	size_t nmoved = st->moved[1] + st->moved[2] + st->moved[3];
	st->mean_move = nmoved ? s->move_sum / (double)nmoved : 0;
	st->rms_before = s->nres ? sqrt(s->r2_before / (double)s->nres) : 0;
	st->rms_after = s->nres ? sqrt(s->r2_after / (double)s->nres) : 0;
	return 0;
}

int fct_project_mesh(struct fct_mesh *m, const struct fct_project_params *p,
                     struct fct_project_stats *st, struct fct_err *err)
{
	struct stage s;
	memset(&s, 0, sizeof s);
	s.m = m, s.p = p;
	int rc = -1;
	if (stage_read(&s, err))
		goto out;
	/* Section 8: the depth scale first (it changes shape), then snapping. */
	if ((p->depth_scale_fix && fix_depth_scale(&s, err)) || (p->ortho_angle > 0 && snap_planes(&s, err)))
		goto out;
	/* Section 5, then the wireframe's tears and straight creases. */
	if (project_vertices(&s, err))
		goto out;
	if (s.st.torn && tear_apply(m, s.lstart, s.lab, s.tv, s.tstart, s.st.torn, s.txyz, &s.arena, &s.wire,
	                            &s.nwire, &s.st.tear_copies, err))
		goto out;
	if (s.wired && p->straighten &&
	    straighten(m, s.pl, s.st.bound, s.have_cam ? &s.cam : NULL, s.to_cam, &s.arena, &s.wire, &s.nwire,
	               &s.st.straightened, &s.st.straight_refused, err))
		goto out;
	if ((s.st.torn || s.st.straightened) && fct_wires_set(m, s.wire, s.nwire, err))
		goto out;
	/* Section 6. */
	if (p->texcoords && s.have_cam && m->nv > 0) {
		if (fct_camera_texcoords(m, &s.cam, s.to_cam, &s.st.no_pixel, err))
			goto out;
		s.st.texcoords = 1;
	}
	if (s.planes_changed && fct_planes_set(m, s.pl, s.npl, err))
		goto out;
	rc = 0;
out:
	if (st)
		*st = s.st;
	stage_free(&s);
	return rc;
}
