/* test_mcubes.c - marching cubes on analytic fields with known answers:
 * every sign pattern of one cube closed by a positive shell, random and
 * checkerboard fields (all faces ambiguous), a sphere, a torus, planes,
 * block borders, colour, min_weight, and tiles joined by exact welding;
 * and the fast extraction (fct_mcubes_stats, mcubesfast.c) against the
 * plain one (fct_mcubes_reference, mcubes.c), bit for bit, on those fields
 * and on gen_mcubes' room and dense ball, noisy volumes with weights below
 * min_weight, clip boxes, thin and empty volumes. */
#include <stdlib.h>

#include "geom/adj.h"
#include "check.h"
#include "fusion/mcubes.h"
#include "core/rng.h"

static struct fct_err err;

typedef double (*field_fn)(const double p[3], const void *arg);

/* Fill voxels lo..hi (inclusive) with f, weight 1 where |f| <= trunc (world
 * units); blocks are created only where some voxel is written. */
static struct fct_voxgrid *fill(double voxel, const int lo[3], const int hi[3], field_fn f,
                                const void *arg, double trunc, int colour)
{
	struct fct_voxgrid *g = fct_voxgrid_new(voxel, colour, &err);
	if (!g)
		abort();
	for (int k = lo[2]; k <= hi[2]; k++)
		for (int j = lo[1]; j <= hi[1]; j++)
			for (int i = lo[0]; i <= hi[0]; i++) {
				double p[3] = { i * voxel, j * voxel, k * voxel };
				double d = f(p, arg);
				if (!(fabs(d) <= trunc))
					continue;
				int v;
				struct fct_voxblock *b = fct_voxgrid_voxel_at(g, i, j, k, 1, &v, &err);
				if (!b)
					abort();
				b->sdf[v] = (float)d;
				b->weight[v] = 1;
				if (colour) {
					b->rgb[3 * v] = (float)(10 * i);
					b->rgb[3 * v + 1] = 100;
					b->rgb[3 * v + 2] = (float)(200 - 3 * k);
				}
			}
	return g;
}

/* Topology of a triangle mesh. */
struct topo {
	size_t border, nonmanifold, ne;
	long euler;
	int oriented;           /* every two-face edge walked once each way */
	long components;
	long duplicates;        /* vertices at the same position as another */
};

static struct topo topology(const struct fct_mesh *m)
{
	struct topo t;
	memset(&t, 0, sizeof t);
	struct fct_adj a;
	if (fct_adj_build(&a, m, &err))
		abort();
	t.border = a.nborder;
	t.nonmanifold = a.nnonmanifold;
	t.ne = a.ne;
	t.euler = (long)m->nv - (long)a.ne + (long)m->nf;
	int *dir = calloc(a.ne + 1, sizeof *dir);
	uint32_t *label = malloc((m->nf + 1) * sizeof *label);
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t k = 0; k < 3; k++) {
			uint32_t u = m->fvert[3 * f + k], v = m->fvert[3 * f + (k + 1) % 3];
			uint32_t e = a.face_e[3 * f + k];
			if (e != FCT_ADJ_NONE)
				dir[e] += u < v ? 1 : -1;
		}
	t.oriented = 1;
	for (size_t e = 0; e < a.ne; e++)
		if (fct_adj_edge_nfaces(&a, e) == 2 && dir[e] != 0)
			t.oriented = 0;
	t.components = fct_adj_components(&a, label, &err);
	free(dir);
	free(label);
	fct_adj_free(&a);
	struct fct_mesh c;
	if (fct_mesh_copy(&c, m, &err))
		abort();
	t.duplicates = fct_mesh_weld_exact(&c, &err);
	fct_mesh_free(&c);
	return t;
}

/* Signed volume enclosed (positive when the normals point outwards). */
static double volume(const struct fct_mesh *m)
{
	double v = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const double *a = m->xyz + 3 * m->fvert[3 * f], *b = m->xyz + 3 * m->fvert[3 * f + 1],
		             *c = m->xyz + 3 * m->fvert[3 * f + 2];
		v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
		      a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
	}
	return v;
}

static double area(const struct fct_mesh *m)
{
	double s = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const double *a = m->xyz + 3 * m->fvert[3 * f], *b = m->xyz + 3 * m->fvert[3 * f + 1],
		             *c = m->xyz + 3 * m->fvert[3 * f + 2];
		double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
		double w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
		double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
		s += 0.5 * sqrt(x * x + y * y + z * z);
	}
	return s;
}

static const float *prop(const struct fct_mesh *m, const char *name)
{
	struct fct_prop *p = fct_elem_find(&m->vertex, name);
	return p && p->type == FCT_FLOAT32 ? p->data : NULL;
}

/* The fast extraction against the reference ------------------------------ */

/* a and b are the same bytes: counts, positions, faces, every vertex
 * property (name, type, values) in order. */
static int same_mesh(const struct fct_mesh *a, const struct fct_mesh *b)
{
	if (a->nv != b->nv || a->nf != b->nf || a->vertex.nprops != b->vertex.nprops ||
	    (a->nv && memcmp(a->xyz, b->xyz, 3 * a->nv * sizeof *a->xyz)))
		return 0;
	if (a->nf && (memcmp(a->fstart, b->fstart, (a->nf + 1) * sizeof *a->fstart) ||
	              memcmp(a->fvert, b->fvert, a->fstart[a->nf] * sizeof *a->fvert)))
		return 0;
	for (size_t k = 0; k < a->vertex.nprops; k++) {
		const struct fct_prop *p = &a->vertex.props[k], *q = &b->vertex.props[k];
		if (strcmp(p->name, q->name) || p->type != q->type ||
		    (a->nv && memcmp(p->data, q->data, a->nv * fct_type_size(p->type))))
			return 0;
	}
	return 1;
}

/* fct_mcubes_stats on 1 and 2 threads gives the reference's bytes on g
 * (the clip box lo, hi may be NULL); *nv, *nf (may be NULL): the mesh's
 * counts, so that the caller can check that something was compared. */
static void check_reference(const struct fct_voxgrid *g, float min_weight, const int32_t *lo,
                            const int32_t *hi, const char *what, size_t *nv, size_t *nf)
{
	struct fct_mesh ref, fast;
	CHECK_MSG(fct_mcubes_reference(&ref, g, min_weight, lo, hi, &err) == 0, "%s: reference", what);
	for (int threads = 1; threads <= 2; threads++) {
		CHECK_MSG(fct_mcubes_stats(&fast, g, min_weight, lo, hi, threads, NULL, &err) == 0,
		          "%s: fast", what);
		CHECK_MSG(same_mesh(&ref, &fast), "%s, %d thread(s): %zu/%zu vertices, %zu/%zu faces",
		          what, threads, ref.nv, fast.nv, ref.nf, fast.nf);
		fct_mesh_free(&fast);
	}
	if (nv)
		*nv = ref.nv;
	if (nf)
		*nf = ref.nf;
	fct_mesh_free(&ref);
}

/* Fields ------------------------------------------------------------------ */

struct sphere {
	double c[3], r;
};

static double sphere_f(const double p[3], const void *arg)
{
	const struct sphere *s = arg;
	double d[3] = { p[0] - s->c[0], p[1] - s->c[1], p[2] - s->c[2] };
	return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - s->r;
}

struct torus {
	double R, r;
};

static double torus_f(const double p[3], const void *arg)
{
	const struct torus *t = arg;
	double q = sqrt(p[0] * p[0] + p[1] * p[1]) - t->R;
	return sqrt(q * q + p[2] * p[2]) - t->r;
}

struct plane {
	double n[3], d;
};

static double plane_f(const double p[3], const void *arg)
{
	const struct plane *pl = arg;
	return pl->n[0] * p[0] + pl->n[1] * p[1] + pl->n[2] * p[2] + pl->d;
}

/* gen_mcubes' room (bench/gen_mcubes.c): the inside of a 4 x 4 x 2.5 m
 * box, a ball of 0.5 m at (2.6, 1.4, 1.2) and a 1 x 0.6 x 0.75 m table on
 * the floor; positive in free space. */
static double room_f(const double p[3], const void *arg)
{
	static const double room[3] = { 4, 4, 2.5 }, lo[3] = { 0.8, 2.2, 0 }, hi[3] = { 1.8, 2.8, 0.75 };
	static const struct sphere ball = { { 2.6, 1.4, 1.2 }, 0.5 };
	(void)arg;
	double d = sphere_f(p, &ball), out = 0, in = -1e300;
	for (int k = 0; k < 3; k++) {
		d = fmin(d, fmin(p[k], room[k] - p[k]));
		double q = fabs(p[k] - 0.5 * (lo[k] + hi[k])) - 0.5 * (hi[k] - lo[k]);
		out += q > 0 ? q * q : 0;
		in = fmax(in, q);
	}
	return fmin(d, out > 0 ? sqrt(out) : in);
}

/* Tests ------------------------------------------------------------------- */

static int closed_ok(const struct topo *t)
{
	return t->border == 0 && t->nonmanifold == 0 && t->oriented && t->duplicates == 0;
}

/* Every sign pattern of the cube (1..2)^3, random magnitudes, inside a
 * positive shell: a closed, oriented, manifold surface whose volume is
 * positive; the single-corner pattern has its exact answer. */
static void test_all_patterns(void)
{
	struct fct_rng rng;
	fct_rng_seed(&rng, 7);
	int ok = 1, vol_ok = 1, euler_ok = 1, amb_seen = 0;
	for (int trial = 0; trial < 40; trial++)
		for (int cfg = 0; cfg < 256; cfg++) {
			struct fct_voxgrid *g = fct_voxgrid_new(1, 0, &err);
			for (int k = 0; k < 4; k++)
				for (int j = 0; j < 4; j++)
					for (int i = 0; i < 4; i++) {
						/* put the cube across the block corner at voxel 8 */
						int v;
						struct fct_voxblock *b = fct_voxgrid_voxel_at(g, i + 6, j + 6, k + 6, 1, &v, &err);
						int in = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
						int c = (i - 1) + 2 * (j - 1) + 4 * (k - 1);
						double mag = trial ? 0.05 + fct_rng_uniform(&rng) : 1;
						b->sdf[v] = (float)(in && (cfg >> c & 1) ? -mag : mag);
						b->weight[v] = 1;
					}
			struct fct_mesh m;
			struct fct_mcubes_stats st;
			if (fct_mcubes_stats(&m, g, 0, NULL, NULL, 1, &st, &err))
				abort();
			amb_seen += st.ambiguous > 0;
			if (trial < 4)
				check_reference(g, 0, NULL, NULL, "sign pattern", NULL, NULL);
			struct topo t = topology(&m);
			ok &= closed_ok(&t) && (cfg == 0) == (m.nf == 0);
			vol_ok &= cfg == 0 || volume(&m) > 0;
			euler_ok &= t.euler == 2 * t.components;
			if (trial == 0 && cfg == 1) {
				/* one corner at -1, its six neighbours at +1: the three
				 * edges cross at mid-edge, other cubes add the rest of an
				 * octahedron: 6 vertices, 8 faces */
				CHECK_INT(m.nv, 6);
				CHECK_INT(m.nf, 8);
				CHECK_NEAR(volume(&m), 4.0 / 3 * 0.125, 1e-12);
			}
			fct_mesh_free(&m);
			fct_voxgrid_free(g);
		}
	CHECK(ok);
	CHECK(vol_ok);
	CHECK(euler_ok);
	CHECK(amb_seen > 0);
}

/* Random and checkerboard fields in a 12^3 region (across block borders)
 * closed by a positive shell. */
static void test_random_fields(void)
{
	struct fct_rng rng;
	fct_rng_seed(&rng, 11);
	int ok = 1, euler_ok = 1;
	size_t amb = 0, centres = 0;
	for (int trial = 0; trial < 30; trial++) {
		struct fct_voxgrid *g = fct_voxgrid_new(0.5, 0, &err);
		for (int k = -6; k < 8; k++)
			for (int j = -6; j < 8; j++)
				for (int i = -6; i < 8; i++) {
					int v;
					struct fct_voxblock *b = fct_voxgrid_voxel_at(g, i, j, k, 1, &v, &err);
					int shell = i == -6 || i == 7 || j == -6 || j == 7 || k == -6 || k == 7;
					double s;
					if (shell)
						s = 1;
					else if (trial == 0)
						s = (i + j + k) & 1 ? 1 : -1;   /* checkerboard, all ties */
					else if (trial == 1)
						s = ((i + j + k) & 1 ? 1 : -1) * (1 + 0.01 * fct_rng_uniform(&rng));
					else
						s = fct_rng_uniform(&rng) - 0.5;
					b->sdf[v] = (float)s;
					b->weight[v] = 1;
				}
		struct fct_mesh m, m2;
		struct fct_mcubes_stats st;
		if (fct_mcubes_stats(&m, g, 0.5f, NULL, NULL, 1, &st, &err) ||
		    fct_mcubes_stats(&m2, g, 0.5f, NULL, NULL, 3, NULL, &err))
			abort();
		amb += st.ambiguous;
		centres += st.centres;
		check_reference(g, 0.5f, NULL, NULL, trial ? "random field" : "checkerboard", NULL, NULL);
		struct topo t = topology(&m);
		ok &= closed_ok(&t) && t.nonmanifold == 0 && m.nf > 0 && volume(&m) > 0;
		euler_ok &= t.euler % 2 == 0;
		/* deterministic: the same bytes on 1 and 3 threads */
		ok &= m.nv == m2.nv && m.nf == m2.nf &&
		      !memcmp(m.xyz, m2.xyz, 3 * m.nv * sizeof *m.xyz) &&
		      !memcmp(m.fvert, m2.fvert, 3 * m.nf * sizeof *m.fvert);
		for (int k = 0; k < 3 && ok; k++) {
			static const char *nn[3] = { "nx", "ny", "nz" };
			ok &= !memcmp(fct_elem_find(&m.vertex, nn[k])->data,
			              fct_elem_find(&m2.vertex, nn[k])->data, m.nv * sizeof(float));
		}
		if (!ok) {
			fprintf(stderr, "trial %d: border %zu nonmanifold %zu oriented %d dup %ld\n", trial,
			        t.border, t.nonmanifold, t.oriented, t.duplicates);
			break;
		}
		fct_mesh_free(&m);
		fct_mesh_free(&m2);
		fct_voxgrid_free(g);
	}
	CHECK(ok);
	CHECK(euler_ok);
	CHECK(amb > 1000);
	CHECK(centres > 0);
}

/* A sphere of radius 1 m at 0.05 m voxels (20 voxels), off the lattice, in
 * a band of 3 voxels: closed, genus 0, every vertex within 1% of the radius,
 * normals radial, no duplicates; the band crosses many block borders. */
static void test_sphere(void)
{
	struct sphere s = { { 0.013, -0.021, 0.037 }, 1.0 };
	int lo[3] = { -24, -24, -24 }, hi[3] = { 24, 24, 24 };
	double vox = 0.05;
	struct fct_voxgrid *g = fill(vox, lo, hi, sphere_f, &s, 3 * vox, 0);
	struct fct_mesh m;
	struct fct_mcubes_stats st;
	CHECK_INT(fct_mcubes_stats(&m, g, 0, NULL, NULL, 1, &st, &err), 0);
	struct topo t = topology(&m);
	CHECK_INT(t.border, 0);
	CHECK_INT(t.nonmanifold, 0);
	CHECK(t.oriented);
	CHECK_INT(t.euler, 2);
	CHECK_INT(t.components, 1);
	CHECK_INT(t.duplicates, 0);
	double maxe = 0, sume = 0, mindot = 1;
	const float *nx = prop(&m, "nx"), *ny = prop(&m, "ny"), *nz = prop(&m, "nz");
	CHECK(nx && ny && nz);
	for (size_t v = 0; v < m.nv; v++) {
		double d[3] = { m.xyz[3 * v] - s.c[0], m.xyz[3 * v + 1] - s.c[1], m.xyz[3 * v + 2] - s.c[2] };
		double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
		double e = fabs(r - s.r);
		maxe = e > maxe ? e : maxe;
		sume += e;
		double dot = (nx[v] * d[0] + ny[v] * d[1] + nz[v] * d[2]) / r;
		mindot = dot < mindot ? dot : mindot;
	}
	/* chords of a 20-voxel sphere sag by at most r(1 - cos(asin(1/2r)))
	 * between lattice points: the vertex error is a fraction of that */
	CHECK(maxe < 0.01 * s.r);
	CHECK(sume / (double)m.nv < 0.001 * s.r);
	CHECK(mindot > 0.995);
	double V = 4.0 / 3 * M_PI;
	CHECK_NEAR(volume(&m) / V, 1, 0.01);
	CHECK_NEAR(area(&m) / (4 * M_PI), 1, 0.01);
	/* the grid is 48^3 voxels' worth of band only */
	CHECK(fct_voxgrid_count(g) < 7 * 7 * 7);
	CHECK_INT(st.voxels, fct_voxgrid_count(g) * 512);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);
}

/* A grid whose blocks' bounding box is too sparse for mcubes' block map
 * (one far block) is looked up through the grid's hash instead: the same
 * mesh, byte for byte. */
static void test_sparse_lookup(void)
{
	struct sphere s = { { 0.013, -0.021, 0.037 }, 1.0 };
	int lo[3] = { -24, -24, -24 }, hi[3] = { 24, 24, 24 };
	double vox = 0.05;
	struct fct_voxgrid *g = fill(vox, lo, hi, sphere_f, &s, 3 * vox, 0);
	struct fct_mesh a, b;
	CHECK_INT(fct_mcubes_stats(&a, g, 0, NULL, NULL, 1, NULL, &err), 0);
	struct fct_voxblock *far = fct_voxgrid_block(g, 100000, -3, 2, 1, &err);
	CHECK(far != NULL);
	for (int v = 0; far && v < 512; v++)
		far->sdf[v] = 0.1f, far->weight[v] = 1;
	CHECK_INT(fct_mcubes_stats(&b, g, 0, NULL, NULL, 2, NULL, &err), 0);
	CHECK(a.nv > 1000);
	CHECK_INT(b.nv, a.nv);
	CHECK_INT(b.nf, a.nf);
	if (a.nv == b.nv && a.nf == b.nf) {
		CHECK(!memcmp(a.xyz, b.xyz, 3 * a.nv * sizeof *a.xyz));
		CHECK(!memcmp(a.fvert, b.fvert, 3 * a.nf * sizeof *a.fvert));
		CHECK(!memcmp(prop(&a, "nx"), prop(&b, "nx"), a.nv * sizeof(float)));
	}
	fct_mesh_free(&a);
	fct_mesh_free(&b);
	fct_voxgrid_free(g);
}

/* Where the gradients at the two ends of an edge nearly cancel, a vertex's
 * normal is still the normalised interpolated gradient to float precision
 * (the vertex pass takes such normals from its double path; worked in
 * float, the one at y = 1 turns by 1.2e-3): one block, sdf f(x) + c y, f
 * chosen so that on the edges x = 1..2 the x gradients 2.30 and -2.14
 * interpolate to about 0 against the y gradient c = 1e-4. */
static void test_cancelling_normal(void)
{
	static const double f[8] = { -2.0577114545715984, -2.7324386878903, 2.5419109339268267,
		                     -7.011338153439137, -5, -5, -5, -5 };
	const double c = 1e-4;
	struct fct_voxgrid *g = fct_voxgrid_new(1.0, 0, &err);
	struct fct_voxblock *b = g ? fct_voxgrid_block(g, 0, 0, 0, 1, &err) : NULL;
	CHECK(b != NULL);
	if (!b)
		return;
	for (int v = 0; v < 512; v++) {
		b->sdf[v] = (float)(f[v & 7] + c * (v >> 3 & 7));
		b->weight[v] = 1;
	}
	struct fct_mesh m;
	CHECK_INT(fct_mcubes_stats(&m, g, 0, NULL, NULL, 1, NULL, &err), 0);
	check_reference(g, 0, NULL, NULL, "cancelling normals", NULL, NULL);
	const float *nx = prop(&m, "nx"), *ny = prop(&m, "ny"), *nz = prop(&m, "nz");
	int seen = 0;
#define S(x, y, z) ((double)b->sdf[(x) + 8 * ((y) + 8 * (z))])
	for (size_t v = 0; nx && v < m.nv; v++) {
		const double *p = m.xyz + 3 * v;
		int y = (int)p[1], z = (int)p[2];
		if (!(p[0] > 1 && p[0] < 2) || p[1] != y || p[2] != z || y < 1 || y > 6 || z < 1 || z > 6)
			continue;
		/* the zero crossing on (1, y, z)-(2, y, z) and the central
		 * differences at its ends, in double */
		double t = S(1, y, z) / (S(1, y, z) - S(2, y, z));
		double g0[3] = { 0.5 * (S(2, y, z) - S(0, y, z)), 0.5 * (S(1, y + 1, z) - S(1, y - 1, z)), 0 };
		double g1[3] = { 0.5 * (S(3, y, z) - S(1, y, z)), 0.5 * (S(2, y + 1, z) - S(2, y - 1, z)), 0 };
		double n[3], len = 0;
		for (int k = 0; k < 3; k++) {
			n[k] = (1 - t) * g0[k] + t * g1[k];
			len += n[k] * n[k];
		}
		len = sqrt(len);
		CHECK_NEAR(nx[v], n[0] / len, 1e-6);
		CHECK_NEAR(ny[v], n[1] / len, 1e-6);
		CHECK_NEAR(nz[v], n[2] / len, 1e-6);
		seen++;
	}
#undef S
	CHECK_INT(seen, 36);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);
}

static void test_torus(void)
{
	struct torus tr = { 6.0, 2.5 };
	int lo[3] = { -20, -20, -7 }, hi[3] = { 20, 20, 7 };
	struct fct_voxgrid *g = fill(0.5, lo, hi, torus_f, &tr, 1.0, 0);
	struct fct_mesh m;
	CHECK_INT(fct_mcubes(&m, g, 0, NULL, NULL, &err), 0);
	struct topo t = topology(&m);
	CHECK_INT(t.border, 0);
	CHECK_INT(t.nonmanifold, 0);
	CHECK(t.oriented);
	CHECK_INT(t.euler, 0);
	CHECK_INT(t.components, 1);
	CHECK_NEAR(volume(&m) / (2 * M_PI * M_PI * tr.R * tr.r * tr.r), 1, 0.02);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);
}

/* A horizontal plane z = 2.3 over observed voxels x, y in 0..16: a disk of
 * area 16 x 16 voxels at exactly z = 2.3, normals +z; a tilted plane: every
 * vertex on it (the field is linear, so interpolation is exact). */
static void test_planes(void)
{
	struct plane p = { { 0, 0, 1 }, -2.3 };
	int lo[3] = { 0, 0, -3 }, hi[3] = { 16, 16, 9 };
	struct fct_voxgrid *g = fill(1, lo, hi, plane_f, &p, 100, 0);
	struct fct_mesh m;
	CHECK_INT(fct_mcubes(&m, g, 0, NULL, NULL, &err), 0);
	struct topo t = topology(&m);
	CHECK_INT(t.euler, 1);
	CHECK_INT(t.nonmanifold, 0);
	CHECK_INT(t.border, 64);
	CHECK(t.oriented);
	CHECK_INT(m.nv, 17 * 17);
	CHECK_INT(m.nf, 2 * 16 * 16);
	CHECK_NEAR(area(&m), 256, 1e-9);
	double maxz = 0, minnz = 1;
	const float *nz = prop(&m, "nz");
	for (size_t v = 0; v < m.nv; v++) {
		maxz = fmax(maxz, fabs(m.xyz[3 * v + 2] - 2.3));
		minnz = fmin(minnz, nz[v]);
	}
	CHECK(maxz < 1e-6);
	CHECK_NEAR(minnz, 1, 1e-6);
	/* orientation: triangle normals +z (to the positive side) */
	int up = 1;
	for (size_t f = 0; f < m.nf; f++) {
		const double *a = m.xyz + 3 * m.fvert[3 * f], *b = m.xyz + 3 * m.fvert[3 * f + 1],
		             *c = m.xyz + 3 * m.fvert[3 * f + 2];
		up &= (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0;
	}
	CHECK(up);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);

	struct plane q = { { 0.36, -0.48, 0.8 }, 0.123 };
	int lo2[3] = { -10, -10, -10 }, hi2[3] = { 10, 10, 10 };
	g = fill(0.1, lo2, hi2, plane_f, &q, 0.25, 0);
	CHECK_INT(fct_mcubes(&m, g, 0, NULL, NULL, &err), 0);
	t = topology(&m);
	CHECK_INT(t.euler, 1);
	CHECK_INT(t.nonmanifold, 0);
	CHECK(t.oriented);
	double maxd = 0, mindot = 1;
	const float *nx = prop(&m, "nx"), *ny = prop(&m, "ny");
	nz = prop(&m, "nz");
	for (size_t v = 0; v < m.nv; v++) {
		maxd = fmax(maxd, fabs(plane_f(m.xyz + 3 * v, &q)));
		mindot = fmin(mindot, nx[v] * q.n[0] + ny[v] * q.n[1] + nz[v] * q.n[2]);
	}
	CHECK(maxd < 1e-6);
	CHECK(mindot > 0.99999);
	CHECK(m.nf > 500);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);
}

/* Colour interpolated along the edge: red = 10 i at voxel i. */
static void test_colour(void)
{
	struct plane p = { { 1, 0, 0 }, -3.25 };   /* x = 3.25 */
	int lo[3] = { 0, 0, 0 }, hi[3] = { 6, 4, 4 };
	struct fct_voxgrid *g = fill(1, lo, hi, plane_f, &p, 100, 1);
	struct fct_mesh m;
	CHECK_INT(fct_mcubes(&m, g, 0, NULL, NULL, &err), 0);
	check_reference(g, 0, NULL, NULL, "colour", NULL, NULL);
	struct fct_prop *r = fct_elem_find(&m.vertex, "red"), *gr = fct_elem_find(&m.vertex, "green"),
	                *bl = fct_elem_find(&m.vertex, "blue");
	CHECK(r && gr && bl && r->type == FCT_UINT8);
	CHECK_INT(m.nv, 25);
	int ok = 1;
	for (size_t v = 0; r && gr && bl && v < m.nv; v++) {
		int k = (int)lrint(m.xyz[3 * v + 2]);
		ok &= fct_prop_get(r, v) == 33 && fct_prop_get(gr, v) == 100 &&
		      fct_prop_get(bl, v) == 200 - 3 * k;
	}
	CHECK(ok);
	fct_mesh_free(&m);
	fct_voxgrid_free(g);
}

/* Voxels under min_weight are unobserved; a missing block too. */
static void test_min_weight(void)
{
	struct sphere s = { { 0.2, 0.1, 0.3 }, 5 };
	int lo[3] = { -8, -8, -8 }, hi[3] = { 8, 8, 8 };
	struct fct_voxgrid *g = fill(1, lo, hi, sphere_f, &s, 2, 0);
	/* lower the weight of every voxel with x >= 1 */
	for (size_t b = 0; b < fct_voxgrid_count(g); b++) {
		struct fct_voxblock *B = fct_voxgrid_at(g, b);
		for (int v = 0; v < 512; v++)
			if (8 * B->bx + (v & 7) >= 1 && B->weight[v] > 0)
				B->weight[v] = 0.5f;
	}
	struct fct_mesh all, half;
	CHECK_INT(fct_mcubes(&all, g, 0.5f, NULL, NULL, &err), 0);
	CHECK_INT(fct_mcubes(&half, g, 0.75f, NULL, NULL, &err), 0);
	check_reference(g, 0.75f, NULL, NULL, "min_weight", NULL, NULL);
	struct topo t = topology(&all), h = topology(&half);
	CHECK_INT(t.border, 0);
	CHECK(h.border > 0);
	CHECK_INT(h.nonmanifold, 0);
	double maxx = -1e9;
	for (size_t v = 0; v < half.nv; v++)
		maxx = fmax(maxx, half.xyz[3 * v]);
	CHECK(maxx <= 0 && maxx > -0.5);
	fct_mesh_free(&all);
	fct_mesh_free(&half);
	fct_voxgrid_free(g);
}

/* Append b to a (positions and faces only). */
static void concat(struct fct_mesh *a, const struct fct_mesh *b)
{
	size_t off = a->nv;
	for (size_t v = 0; v < b->nv; v++)
		if (fct_mesh_add_vertex(a, b->xyz[3 * v], b->xyz[3 * v + 1], b->xyz[3 * v + 2], &err) < 0)
			abort();
	for (size_t f = 0; f < b->nf; f++) {
		uint32_t t[3];
		for (int k = 0; k < 3; k++)
			t[k] = (uint32_t)(b->fvert[3 * f + k] + off);
		if (fct_mesh_add_face(a, t, 3, &err) < 0)
			abort();
	}
}

/* Triangles as position triples, rotated to start at the smallest. */
struct ptri {
	double p[9];
};

static int cmp_ptri(const void *a, const void *b)
{
	return memcmp(a, b, sizeof(struct ptri));
}

static struct ptri *ptris(const struct fct_mesh *m)
{
	struct ptri *t = malloc((m->nf + 1) * sizeof *t);
	for (size_t f = 0; f < m->nf; f++) {
		int s = 0;
		for (int k = 1; k < 3; k++)
			if (memcmp(m->xyz + 3 * m->fvert[3 * f + k], m->xyz + 3 * m->fvert[3 * f + s],
			           3 * sizeof(double)) < 0)
				s = k;
		for (int k = 0; k < 3; k++)
			memcpy(t[f].p + 3 * k, m->xyz + 3 * m->fvert[3 * f + (s + k) % 3], 3 * sizeof(double));
	}
	qsort(t, m->nf, sizeof *t, cmp_ptri);
	return t;
}

/* Tiles: a sphere extracted whole and as 2 x 2 x 1 tiles whose borders cut
 * blocks (x at 3, y at -5): each tile is open, the welded union is closed
 * and has exactly the whole extraction's vertices and triangles.  The tiles
 * are extracted from grids fused separately over their box plus a margin. */
static void test_tiles(void)
{
	struct sphere s = { { 0.31, -0.17, 0.05 }, 9.2 };
	int lo[3] = { -12, -12, -12 }, hi[3] = { 12, 12, 12 };
	struct fct_voxgrid *g = fill(1, lo, hi, sphere_f, &s, 2.5, 0);
	struct fct_mesh whole;
	CHECK_INT(fct_mcubes(&whole, g, 0, NULL, NULL, &err), 0);
	fct_voxgrid_free(g);
	int cut[3][3] = { { -12, 3, 12 }, { -12, -5, 12 }, { -12, 12, 12 } };
	struct fct_mesh all;
	fct_mesh_init(&all);
	int open_ok = 1;
	for (int ty = 0; ty < 2; ty++)
		for (int tx = 0; tx < 2; tx++) {
			int32_t clo[3] = { cut[0][tx], cut[1][ty], -12 }, chi[3] = { cut[0][tx + 1], cut[1][ty + 1], 12 };
			int flo[3], fhi[3];
			for (int k = 0; k < 3; k++)
				flo[k] = clo[k] - 1, fhi[k] = chi[k] + 1;
			struct fct_voxgrid *tg = fill(1, flo, fhi, sphere_f, &s, 2.5, 0);
			struct fct_mesh m;
			CHECK_INT(fct_mcubes(&m, tg, 0, clo, chi, &err), 0);
			check_reference(tg, 0, clo, chi, "tile", NULL, NULL);
			struct topo t = topology(&m);
			open_ok &= t.border > 0 && t.nonmanifold == 0 && m.nf > 0;
			concat(&all, &m);
			fct_mesh_free(&m);
			fct_voxgrid_free(tg);
		}
	CHECK(open_ok);
	long removed = fct_mesh_weld_exact(&all, &err);
	CHECK(removed > 0);
	struct topo t = topology(&all);
	CHECK_INT(t.border, 0);
	CHECK_INT(t.nonmanifold, 0);
	CHECK(t.oriented);
	CHECK_INT(t.euler, 2);
	CHECK_INT(all.nv, whole.nv);
	CHECK_INT(all.nf, whole.nf);
	if (all.nf == whole.nf) {
		struct ptri *a = ptris(&all), *b = ptris(&whole);
		CHECK(!memcmp(a, b, whole.nf * sizeof *a));
		free(a);
		free(b);
	}
	fct_mesh_free(&all);
	fct_mesh_free(&whole);

	/* an empty box, a box with no surface */
	g = fill(1, lo, hi, sphere_f, &s, 2.5, 0);
	int32_t e0[3] = { 0, 0, 0 }, e1[3] = { 0, 5, 5 }, n1[3] = { 2, 2, 2 };
	struct fct_mesh m;
	CHECK_INT(fct_mcubes(&m, g, 0, e0, e1, &err), 0);
	CHECK_INT(m.nv, 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);
	CHECK_INT(fct_mcubes(&m, g, 0, e0, n1, &err), 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);
	CHECK_INT(fct_mcubes(&m, g, 0, e0, NULL, &err), -1);
	CHECK_INT(fct_mcubes_reference(&m, g, 0, NULL, e1, &err), -1);
	fct_voxgrid_free(g);
}

/* gen_mcubes' scenes, smaller: the room band at 5 cm (4 voxels of
 * truncation, as the bench's at 1 cm), with colour, and the dense ball (a
 * 32^3 volume, every voxel observed).  Both cross many block borders. */
static void test_reference_scenes(void)
{
	size_t nv, nf;
	int lo[3] = { -3, -3, -3 }, hi[3] = { 83, 83, 53 };
	struct fct_voxgrid *g = fill(0.05, lo, hi, room_f, NULL, 0.2, 1);
	check_reference(g, 0, NULL, NULL, "room", &nv, &nf);
	CHECK(nv > 30000 && nf > 60000);
	int32_t clo[3] = { 10, -3, -3 }, chi[3] = { 45, 50, 27 };
	check_reference(g, 0, clo, chi, "room, clipped", &nv, NULL);
	CHECK(nv > 3000);
	fct_voxgrid_free(g);
	struct sphere s = { { 15.6, 16.3, 15.9 }, 12.5 };
	int dlo[3] = { 0, 0, 0 }, dhi[3] = { 31, 31, 31 };
	g = fill(1, dlo, dhi, sphere_f, &s, 1e9, 0);
	CHECK_INT(fct_voxgrid_count(g), 64);
	check_reference(g, 0, NULL, NULL, "dense ball", &nv, NULL);
	CHECK(nv > 1000);
	fct_voxgrid_free(g);
}

/* Noisy volumes: random values (some NaN, infinite, +-0) and weights,
 * a quarter of the voxels below min_weight, some never written, one block
 * absent in the middle; with and without colour, min_weight 0.5 and 0;
 * clip boxes across blocks, of one cube, empty, inverted, outside, and
 * larger than the grid. */
static void test_reference_noisy(void)
{
	struct fct_rng rng;
	fct_rng_seed(&rng, 23);
	size_t total = 0;
	for (int trial = 0; trial < 6; trial++) {
		struct fct_voxgrid *g = fct_voxgrid_new(0.25, trial & 1, &err);
		for (int k = -9; k <= 9; k++)
			for (int j = -9; j <= 9; j++)
				for (int i = -9; i <= 9; i++) {
					int v;
					if (fct_rng_uniform(&rng) < 0.05 || (trial > 1 && i < 0 && j >= 0 && k < 0))
						continue;
					struct fct_voxblock *b = fct_voxgrid_voxel_at(g, i, j, k, 1, &v, &err);
					if (!b)
						abort();
					double u = fct_rng_uniform(&rng);
					float sdf = (float)(fct_rng_uniform(&rng) - 0.45);
					if (u < 0.01)
						sdf = NAN;
					else if (u < 0.02)
						sdf = u < 0.015 ? INFINITY : -INFINITY;
					else if (u < 0.04)
						sdf = u < 0.03 ? 0.0f : -0.0f;
					b->sdf[v] = sdf;
					u = fct_rng_uniform(&rng);
					b->weight[v] = (float)(u < 0.25 ? 2 * u : 0.5 + u);
					for (int c = 0; b->rgb && c < 3; c++)
						b->rgb[3 * v + c] = (float)(256 * fct_rng_uniform(&rng));
				}
		size_t nv, nf;
		check_reference(g, 0.5f, NULL, NULL, "noisy", &nv, &nf);
		total += nf;
		check_reference(g, 0, NULL, NULL, "noisy, min_weight 0", NULL, NULL);
		static const int32_t box[][2][3] = {
			{ { -5, -5, -5 }, { 5, 5, 5 } },     { { -8, 0, -3 }, { 1, 7, 9 } },
			{ { 3, 3, 3 }, { 4, 4, 4 } },        { { 0, 0, 0 }, { 0, 5, 5 } },
			{ { 5, 5, 5 }, { 2, 2, 2 } },        { { 50, 50, 50 }, { 60, 60, 60 } },
			{ { -100, -100, -100 }, { 100, 100, 100 } },
		};
		for (size_t b = 0; b < sizeof box / sizeof box[0]; b++)
			check_reference(g, 0.5f, box[b][0], box[b][1], "noisy, clipped", NULL, NULL);
		fct_voxgrid_free(g);
	}
	CHECK(total > 1000);
}

/* Thin and empty volumes: one voxel thick (observed, no cube: an empty
 * mesh), two voxels thick (one layer of cubes) across a block border, no
 * block, blocks with nothing observed, observed without a sign change, and
 * min_weight NaN (nothing observed). */
static void test_reference_thin_empty(void)
{
	struct plane p = { { 0.1, -0.2, 1 }, -0.3 };
	size_t nv, nf;
	int lo[3] = { -10, -10, 0 }, hi[3] = { 10, 10, 0 };
	struct fct_voxgrid *g = fill(1, lo, hi, plane_f, &p, 100, 1);
	check_reference(g, 0, NULL, NULL, "one voxel thick", &nv, NULL);
	CHECK_INT(nv, 0);
	fct_voxgrid_free(g);
	int lo2[3] = { -10, -10, -1 }, hi2[3] = { 10, 10, 0 };
	struct plane q = { { 0.01, -0.02, 1 }, 0.5 };
	g = fill(1, lo2, hi2, plane_f, &q, 100, 1);
	check_reference(g, 0, NULL, NULL, "two voxels thick", &nv, &nf);
	CHECK_INT(nf, 2 * 20 * 20);
	fct_voxgrid_free(g);

	g = fct_voxgrid_new(1, 0, &err);
	check_reference(g, 0, NULL, NULL, "no block", &nv, NULL);
	CHECK_INT(nv, 0);
	struct fct_voxblock *b = fct_voxgrid_block(g, 0, 0, 0, 1, &err);
	CHECK(b != NULL);
	for (int v = 0; b && v < 512; v++)
		b->sdf[v] = (v & 1) ? 1.0f : -1.0f;     /* weights 0 */
	check_reference(g, 0, NULL, NULL, "nothing observed", &nv, NULL);
	CHECK_INT(nv, 0);
	for (int v = 0; b && v < 512; v++)
		b->weight[v] = 1;
	check_reference(g, NAN, NULL, NULL, "min_weight NaN", &nv, NULL);
	CHECK_INT(nv, 0);
	for (int v = 0; b && v < 512; v++)
		b->sdf[v] = 1;
	check_reference(g, 0, NULL, NULL, "no sign change", &nv, NULL);
	CHECK_INT(nv, 0);
	fct_voxgrid_free(g);
}

static void test_weld(void)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	double p[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 0, 0 }, { 0, 0, 0 } };
	for (int v = 0; v < 5; v++)
		fct_mesh_add_vertex(&m, p[v][0], p[v][1], p[v][2], &err);
	uint32_t f0[3] = { 0, 1, 2 }, f1[3] = { 4, 2, 3 };
	fct_mesh_add_face(&m, f0, 3, &err);
	fct_mesh_add_face(&m, f1, 3, &err);
	CHECK_INT(fct_mesh_weld_exact(&m, &err), 2);
	CHECK_INT(m.nv, 3);
	CHECK_INT(m.nf, 2);
	CHECK_INT(m.fvert[3], 0);
	CHECK_INT(m.fvert[4], 2);
	CHECK_INT(m.fvert[5], 1);
	fct_mesh_free(&m);
}

int main(void)
{
	test_all_patterns();
	test_random_fields();
	test_sphere();
	test_sparse_lookup();
	test_cancelling_normal();
	test_torus();
	test_planes();
	test_colour();
	test_min_weight();
	test_tiles();
	test_reference_scenes();
	test_reference_noisy();
	test_reference_thin_empty();
	test_weld();
	CHECK_DONE();
}
