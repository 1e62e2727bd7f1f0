/* test_freedecim - the free-form faces decimated piece by piece, with the
 * pieces of the round before taken from the cache, against the decimation
 * of all of them at once (fct_qem_decimate of the mesh's copy with only
 * those faces, as the planar model did it): the same survivors, positions
 * and properties bit for bit, the same triangles in the same order, the
 * same figures, round after round as pieces grow, join and change their
 * corners; a piece decimated alone with the whole's centre gives the
 * whole's result. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "geom/qem.h"
#include "planar/freedecim.h"

static struct fct_err err;

#define N 40

/* An N x N grid of cells over [0,1]^2, a gently bumpy height field with
 * noise of 2 mm, each cell cut along an alternating diagonal; a float
 * property s (interpolated) and a uchar red (carried). */
static void make_field(struct fct_mesh *m)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	fct_mesh_init(m);
	for (int j = 0; j <= N; j++)
		for (int i = 0; i <= N; i++) {
			double x = (double)i / N, y = (double)j / N;
			double z = 0.05 * sin(6 * x) * cos(5 * y) + 0.002 * (fct_rng_uniform(&r) - 0.5);
			if (fct_mesh_add_vertex(m, x, y, z, &err) < 0)
				abort();
		}
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++) {
			uint32_t a = (uint32_t)(j * (N + 1) + i), b = a + 1, c = a + N + 1, d = c + 1;
			uint32_t t1[3] = {a, b, d}, t2[3] = {a, d, c}, t3[3] = {a, b, c}, t4[3] = {b, d, c};
			int alt = (i + j) % 2;
			if (fct_mesh_add_face(m, alt ? t1 : t3, 3, &err) < 0 ||
			    fct_mesh_add_face(m, alt ? t2 : t4, 3, &err) < 0)
				abort();
		}
	struct fct_prop *s = fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, &err);
	if (!s || !fct_elem_add_scalar(&m->vertex, "red", FCT_UINT8, &err))
		abort();
	s = fct_elem_find(&m->vertex, "s");
	struct fct_prop *red = fct_elem_find(&m->vertex, "red");
	for (size_t v = 0; v < m->nv; v++) {
		fct_prop_set(s, v, m->xyz[3 * v] * 0.7 + m->xyz[3 * v + 1] * 0.3);
		fct_prop_set(red, v, (double)(v % 251));
	}
}

/* Mark the faces of the cells [i0, i1) x [j0, j1) free. */
static void free_cells(unsigned char *is_free, int i0, int i1, int j0, int j1)
{
	for (int j = j0; j < j1; j++)
		for (int i = i0; i < i1; i++)
			is_free[2 * (j * N + i)] = is_free[2 * (j * N + i) + 1] = 1;
}

/* The decimation of all the free faces at once, as one mesh of m's
 * vertices: F's faces renumbered to m's vertices, vmap its survivors. */
static void whole(struct fct_mesh *F, uint32_t **vmap, size_t *nmap, const struct fct_mesh *m,
                  const unsigned char *is_free, const struct fct_qem_params *qp,
                  struct fct_qem_stats *st)
{
	size_t *keep = malloc(m->nf * sizeof *keep), k = 0;
	if (!keep || fct_mesh_copy(F, m, &err))
		abort();
	for (size_t f = 0; f < m->nf; f++)
		if (is_free[f])
			keep[k++] = f;
	struct fct_prop *idx = fct_elem_add_scalar(&F->vertex, "fct_vertex", FCT_UINT32, &err);
	if (!idx || fct_mesh_gather_faces(F, keep, k, &err))
		abort();
	for (size_t v = 0; v < F->nv; v++)
		fct_prop_set(idx, v, (double)v);
	if (fct_qem_decimate(F, qp, st, &err))
		abort();
	idx = fct_elem_find(&F->vertex, "fct_vertex");
	*vmap = malloc((F->nv ? F->nv : 1) * sizeof **vmap);
	if (!*vmap)
		abort();
	*nmap = F->nv;
	for (size_t v = 0; v < F->nv; v++)
		(*vmap)[v] = (uint32_t)fct_prop_get(idx, v);
	for (size_t c = 0; c < F->fstart[F->nf]; c++)
		F->fvert[c] = (*vmap)[F->fvert[c]];
	free(keep);
}

/* One round: the cached decimation against the whole's, bit for bit. */
static void compare(const char *what, const struct fct_mesh *m, const unsigned char *is_free,
                    const struct fct_qem_params *qp, struct fct_free_cache *c)
{
	struct fct_mesh A, B;
	fct_mesh_init(&A);
	fct_mesh_init(&B);
	uint32_t *va = NULL, *vb = NULL;
	size_t na = 0, nb = 0;
	struct fct_qem_stats sa, sb;
	whole(&A, &va, &na, m, is_free, qp, &sa);
	CHECK_MSG(fct_free_decimate(&B, &vb, &nb, m, is_free, qp, c, &sb, &err) == 0, "%s: %s", what, err.msg);
	CHECK_MSG(sa.collapses > 0 && sa.refused_error > 0, "%s: the whole collapses and refuses (%zu, %zu)",
	          what, sa.collapses, sa.refused_error);
	CHECK_MSG(na == nb && !memcmp(va, vb, na * sizeof *va), "%s: survivors (%zu vs %zu)", what, na, nb);
	CHECK_MSG(A.nv == na && B.nv == nb && !memcmp(A.xyz, B.xyz, 3 * na * sizeof *A.xyz),
	          "%s: positions bit for bit", what);
	const char *names[2] = {"s", "red"};
	for (int k = 0; k < 2; k++) {
		const struct fct_prop *pa = fct_elem_find(&A.vertex, names[k]), *pb = fct_elem_find(&B.vertex, names[k]);
		int same = pa && pb && pa->type == pb->type;
		for (size_t i = 0; same && i < na; i++)
			same = fct_prop_get(pa, i) == fct_prop_get(pb, i);
		CHECK_MSG(same, "%s: property %s", what, names[k]);
	}
	CHECK_MSG(A.nf == B.nf && A.nf > 0 && !memcmp(A.fvert, B.fvert, 3 * A.nf * sizeof *A.fvert),
	          "%s: triangles in order (%zu vs %zu)", what, A.nf, B.nf);
	CHECK_MSG(sa.faces_in == sb.faces_in && sa.faces_out == sb.faces_out && sa.vertices_in == sb.vertices_in &&
	          sa.vertices_out == sb.vertices_out && sa.dropped == sb.dropped && sa.locked == sb.locked &&
	          sa.collapses == sb.collapses && sa.refused_topology == sb.refused_topology &&
	          sa.refused_flip == sb.refused_flip && sa.refused_error == sb.refused_error &&
	          sa.passes == sb.passes && sa.holes_closed == sb.holes_closed && sa.corners == sb.corners &&
	          sa.max_error == sb.max_error && sa.max_cost == sb.max_cost,
	          "%s: figures (collapses %zu/%zu, refused %zu/%zu %zu/%zu %zu/%zu, passes %zu/%zu, corners %zu/%zu)",
	          what, sa.collapses, sb.collapses, sa.refused_topology, sb.refused_topology, sa.refused_flip,
	          sb.refused_flip, sa.refused_error, sb.refused_error, sa.passes, sb.passes, sa.corners, sb.corners);
	fct_mesh_free(&A);
	fct_mesh_free(&B);
	free(va), free(vb);
}

static void test_rounds(void)
{
	struct fct_mesh m;
	make_field(&m);
	unsigned char *is_free = calloc(m.nf, 1), *corner = calloc(m.nv, 1);
	double *sigma = malloc(m.nv * sizeof *sigma);
	if (!is_free || !corner || !sigma)
		abort();
	for (size_t v = 0; v < m.nv; v++)
		sigma[v] = 0.002;
	struct fct_qem_params qp;
	fct_qem_params_default(&qp);
	qp.max_error = 1.5;
	qp.hold_borders = 1;
	qp.sigma = sigma;
	qp.corner = corner;
	qp.use_viewpoint = 1;
	qp.viewpoint[0] = qp.viewpoint[1] = 0.5, qp.viewpoint[2] = 2;
	/* Pieces of many cells, one of a single cell and one lone triangle
	 * (done in one pass, with refusals that each further pass of the
	 * whole counts again); corners flagged on two. */
	free_cells(is_free, 0, 12, 0, 12);
	free_cells(is_free, 20, 35, 5, 15);
	free_cells(is_free, 5, 15, 25, 38);
	free_cells(is_free, 30, 31, 30, 31);
	is_free[2 * (38 * N + 38)] = 1;
	corner[6 * (N + 1) + 12] = 1;
	corner[30 * (N + 1) + 10] = 1;
	corner[2] = 1;   /* a vertex of no free face is a corner all the same */
	struct fct_free_cache c;
	memset(&c, 0, sizeof c);
	compare("round 1", &m, is_free, &qp, &c);
	CHECK_INT(c.npieces, 5);
	/* A piece grows, another changes a corner, two stay. */
	free_cells(is_free, 12, 16, 0, 12);
	corner[30 * (N + 1) + 10] = 0;
	corner[28 * (N + 1) + 8] = 1;
	compare("round 2", &m, is_free, &qp, &c);
	CHECK_INT(c.npieces, 5);
	/* Nothing changes: every piece from the cache. */
	compare("round 3", &m, is_free, &qp, &c);
	/* Two pieces join. */
	free_cells(is_free, 16, 20, 5, 10);
	compare("round 4", &m, is_free, &qp, &c);
	CHECK_INT(c.npieces, 4);
	/* A vertex of a piece moves, as one put back off a crease line does:
	 * that piece is decimated again. */
	m.xyz[3 * (6 * (N + 1) + 6) + 2] += 0.01;
	compare("round 5", &m, is_free, &qp, &c);
	fct_free_cache_free(&c);
	/* Without sigma, corners or a viewpoint, and with nothing free. */
	qp.sigma = NULL, qp.corner = NULL, qp.use_viewpoint = 0;
	memset(&c, 0, sizeof c);
	compare("plain", &m, is_free, &qp, &c);
	fct_free_cache_free(&c);
	memset(is_free, 0, m.nf);
	struct fct_mesh F;
	fct_mesh_init(&F);
	uint32_t *vmap = NULL;
	size_t nmap = 0;
	struct fct_qem_stats st;
	memset(&c, 0, sizeof c);
	CHECK(fct_free_decimate(&F, &vmap, &nmap, &m, is_free, &qp, &c, &st, &err) == 0);
	CHECK(nmap == m.nv && F.nf == 0 && st.faces_in == 0 && st.corners == 0);
	fct_free_cache_free(&c);
	fct_mesh_free(&F);
	free(vmap);
	free(is_free), free(corner), free(sigma);
	fct_mesh_free(&m);
}

/* A vertex that is not finite fails as the whole decimation fails. */
static void test_not_finite(void)
{
	struct fct_mesh m, F;
	make_field(&m);
	fct_mesh_init(&F);
	m.xyz[3 * 5 + 1] = NAN;
	unsigned char *is_free = calloc(m.nf, 1);
	if (!is_free)
		abort();
	free_cells(is_free, 0, 3, 0, 3);
	struct fct_qem_params qp;
	fct_qem_params_default(&qp);
	struct fct_free_cache c;
	memset(&c, 0, sizeof c);
	uint32_t *vmap = NULL;
	size_t nmap = 0;
	struct fct_qem_stats st;
	CHECK(fct_free_decimate(&F, &vmap, &nmap, &m, is_free, &qp, &c, &st, &err) == -1);
	CHECK_STR(err.msg, "vertex 5: coordinate is not finite");
	fct_free_cache_free(&c);
	fct_mesh_free(&F);
	fct_mesh_free(&m);
	free(vmap), free(is_free);
}

int main(void)
{
	test_rounds();
	test_not_finite();
	CHECK_DONE();
}
