/* meshdist - the distance from one mesh to another: the error measure of
 * Kang, Johnson and Szeliski, "Extraction of Concise and Realistic 3-D Models
 * from Real Data" (DEC CRL 95/7), section 5 and Table 1: "the distribution of
 * distances of the points in the original mesh to the simplified meshes ...
 * the distance from the point to the face closest to the point in the mesh",
 * summarised by its average, standard deviation and maximum.  With -H, also
 * the other direction and the symmetric Hausdorff distance. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "cli/cli.h"
#include "geom/geom.h"
#include "geom/pointdist.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "core/rng.h"

static const char usage[] =
	"usage: meshdist [-aHpqv] [-o file] [-s samples] [--seed n] A B\n"
	"Distances from mesh A to the nearest point on the faces of mesh B (PLY or\n"
	"OBJ; polygons are fanned into triangles): count, mean, stdev, rms and max\n"
	"in the units of the coordinates, one \"key value\" line each.\n"
	"  -a            write -o as ascii PLY\n"
	"  -H            also from B to A (ba_ lines) and the symmetric Hausdorff\n"
	"                distance, the larger of the two maxima\n"
	"  -o file       write A with a float vertex property \"distance\" (the\n"
	"                distance of each vertex to B); .obj names lose it\n"
	"  -p            also the 50th, 90th, 95th and 99th percentiles (p50 ...)\n"
	"  -q            quiet\n"
	"  -s samples    measure from this many random points spread uniformly by\n"
	"                area over the faces of A (and of B with -H), not from the\n"
	"                vertices (default 0: vertices)\n"
	"      --seed n  seed of the random points (default 1)\n"
	"  -v            report sizes, times and queries/s on stderr\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

/* Running figures of one direction. */
struct stats {
	struct fct_dist_run run;
	float *all;          /* -p: every distance, for the percentiles */
	size_t cap;
};

/* -p: keep every distance. */
static int keep_all;

static void stats_add(struct stats *s, double d)
{
	if (keep_all) {
		if (s->run.count == s->cap) {
			struct fct_err err;
			if (fct_grow((void **)&s->all, &s->cap, s->run.count + 1, sizeof *s->all, &err))
				fct_die_err(&err);
		}
		s->all[s->run.count] = (float)d;
	}
	fct_dist_run_add(&s->run, d);
}

static int cmp_float(const void *x, const void *y)
{
	float a = *(const float *)x, b = *(const float *)y;
	return a < b ? -1 : a > b;
}

/* Population standard deviation and RMS (rms^2 = mean^2 + stdev^2), and
 * with -p the 50th, 90th, 95th and 99th percentiles (nearest rank, to float
 * precision). */
static void stats_print(const struct stats *s, const char *prefix)
{
	struct fct_dist_stats f;
	fct_dist_run_stats(&f, &s->run);
	printf("%scount %zu\n", prefix, f.count);
	printf("%smean %.17g\n", prefix, f.mean);
	printf("%sstdev %.17g\n", prefix, f.stdev);
	printf("%srms %.17g\n", prefix, f.rms);
	printf("%smax %.17g\n", prefix, f.max);
	if (!keep_all || f.count == 0)
		return;
	qsort(s->all, f.count, sizeof *s->all, cmp_float);
	static const int pct[] = {50, 90, 95, 99};
	for (size_t i = 0; i < sizeof pct / sizeof *pct; i++) {
		/* The nearest rank: the smallest distance with pct% of them at or below it. */
		size_t rank = (size_t)ceil(pct[i] / 100.0 * (double)f.count);
		printf("%sp%d %.9g\n", prefix, pct[i], (double)s->all[rank ? rank - 1 : 0]);
	}
}

/* Area-uniform random points on the faces of a mesh: a triangle chosen with
 * probability proportional to its area, then a uniform point in it
 * (Turk, "Generating random points in triangles", Graphics Gems, 1990). */
struct sampler {
	const double *xyz;
	uint32_t *tri;
	size_t ntri;
	double *cum;     /* cum[i]: area of triangles 0..i */
	double total;
};

static int sampler_init(struct sampler *s, const struct fct_mesh *m, struct fct_err *err)
{
	uint32_t *face;
	memset(s, 0, sizeof *s);
	s->xyz = m->xyz;
	if (fct_mesh_fan(m, &s->tri, &face, &s->ntri, err))
		return -1;
	free(face);
	s->cum = malloc(sizeof *s->cum * (s->ntri ? s->ntri : 1));
	if (!s->cum)
		return fct_fail(err, "out of memory for %zu triangles", s->ntri);
	double acc = 0;
	for (size_t i = 0; i < s->ntri; i++) {
		const uint32_t *t = s->tri + 3 * i;
		acc += 0.5 * fct_triangle_area2(m->xyz + 3 * (size_t)t[0], m->xyz + 3 * (size_t)t[1],
		                                m->xyz + 3 * (size_t)t[2]);
		s->cum[i] = acc;
	}
	s->total = acc;
	return 0;
}

static void sampler_free(struct sampler *s)
{
	free(s->tri);
	free(s->cum);
}

/* The point for the area fraction u in [0, 1) (which picks the triangle)
 * and two more uniforms from r (which place it inside). */
static void sampler_point(const struct sampler *s, double u, struct fct_rng *r, double p[3])
{
	u *= s->total;
	size_t lo = 0, hi = s->ntri - 1;
	while (lo < hi) {         /* the first triangle whose cumulative area exceeds u */
		size_t mid = lo + (hi - lo) / 2;
		if (s->cum[mid] > u)
			hi = mid;
		else
			lo = mid + 1;
	}
	const uint32_t *t = s->tri + 3 * lo;
	const double *a = s->xyz + 3 * (size_t)t[0], *b = s->xyz + 3 * (size_t)t[1];
	const double *c = s->xyz + 3 * (size_t)t[2];
	double r1 = sqrt(fct_rng_uniform(r)), r2 = fct_rng_uniform(r);
	double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
	for (int k = 0; k < 3; k++)
		p[k] = wa * a[k] + wb * b[k] + wc * c[k];
}

static int cmp_double(const void *pa, const void *pb)
{
	double a = *(const double *)pa, b = *(const double *)pb;
	return (a > b) - (a < b);
}

enum { BLOCK = 4096 };

/* Distances from the points pts[0..n) to the tree, into d.  Each query is
 * independent, so threads (when built with OpenMP) cannot change a result. */
static void query_block(const struct fct_bvh *tree, const double *pts, size_t n, double *d)
{
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
	for (size_t i = 0; i < n; i++) {
		struct fct_bvh_hit hit;
		if (!fct_bvh_closest(tree, pts + 3 * i, INFINITY, &hit))
			abort();    /* a non-empty tree and a finite point always have a nearest point */
		d[i] = sqrt(hit.d2);
	}
}

/* One direction: from the vertices of `from` (per_vertex receives each
 * distance when not NULL), or from nsamples random points on its faces. */
struct direction {
	struct stats st;
	double seconds;
	size_t queries;
};

static void measure_vertices(const struct fct_mesh *from, const char *from_name,
                             const struct fct_bvh *tree, double *per_vertex, struct direction *dir)
{
	double buf[BLOCK];
	struct fct_progress pr;
	fct_progress_start(&pr, "measuring");
	double t0 = fct_now();
	for (size_t i = 0; i < from->nv; i += BLOCK) {
		size_t n = from->nv - i < BLOCK ? from->nv - i : BLOCK;
		double *d = per_vertex ? per_vertex + i : buf;
		query_block(tree, from->xyz + 3 * i, n, d);
		for (size_t k = 0; k < n; k++) {
			if (isinf(d[k]))
				fct_die(1, "%s: vertex %zu: the distance overflows a double", from_name, i + k);
			stats_add(&dir->st, d[k]);
		}
		fct_progress_update(&pr, (double)(i + n), (double)from->nv);
	}
	fct_progress_end(&pr);
	dir->seconds += fct_now() - t0;
	dir->queries += from->nv;
}

static void measure_samples(const struct sampler *s, const char *from_name, struct fct_rng *r,
                            size_t nsamples, const struct fct_bvh *tree, struct direction *dir)
{
	static double pts[3 * BLOCK], d[BLOCK], u[BLOCK];
	struct fct_progress pr;
	fct_progress_start(&pr, "measuring");
	double t0 = fct_now();
	for (size_t i = 0; i < nsamples; i += BLOCK) {
		size_t n = nsamples - i < BLOCK ? nsamples - i : BLOCK;
		/* Sorted area fractions visit the faces in file order, which is
		 * usually spatially coherent and so kind to the caches; the set of
		 * samples, and so every figure but the last bits of the mean, is
		 * that of the unsorted draws. */
		for (size_t k = 0; k < n; k++)
			u[k] = fct_rng_uniform(r);
		qsort(u, n, sizeof *u, cmp_double);
		for (size_t k = 0; k < n; k++)
			sampler_point(s, u[k], r, pts + 3 * k);
		query_block(tree, pts, n, d);
		for (size_t k = 0; k < n; k++) {
			if (isinf(d[k]))
				fct_die(1, "%s: -s: the distance of a sample overflows a double", from_name);
			stats_add(&dir->st, d[k]);
		}
		fct_progress_update(&pr, (double)(i + n), (double)nsamples);
	}
	fct_progress_end(&pr);
	dir->seconds += fct_now() - t0;
	dir->queries += nsamples;
}

/* Every vertex of m is a query point (or carries -o figures): all must be finite. */
static void check_finite(const struct fct_mesh *m, const char *path)
{
	for (size_t i = 0; i < 3 * m->nv; i++)
		if (!isfinite(m->xyz[i]))
			fct_die(1, "%s: vertex %zu: coordinate is not finite", fct_path_display(path), i / 3);
}

static void build_tree(struct fct_bvh *tree, const struct fct_mesh *m, const char *path,
                       double *seconds)
{
	struct fct_err err;
	double t0 = fct_now();
	if (fct_bvh_build_mesh(tree, m, &err))
		fct_die_err_at(&err, "%s", fct_path_display(path));
	if (tree->ntri == 0)
		fct_die(1, "%s: no faces to measure the distance to", fct_path_display(path));
	*seconds += fct_now() - t0;
}

/* One direction from `from` to the tree of `to`; samples > 0 draws points on
 * the faces of `from` from the generator r. */
static void measure(const struct fct_mesh *from, const char *from_path, const struct fct_bvh *tree,
                    long samples, struct fct_rng *r, double *per_vertex, struct direction *dir)
{
	if (samples == 0 || from->nv == 0) {
		measure_vertices(from, fct_path_display(from_path), tree, per_vertex, dir);
		return;
	}
	struct fct_err err;
	struct sampler s;
	if (sampler_init(&s, from, &err))
		fct_die_err_at(&err, "%s", fct_path_display(from_path));
	if (!(s.total > 0)) {
		sampler_free(&s);
		fct_die(1, "%s: -s: the faces have no area to sample", fct_path_display(from_path));
	}
	measure_samples(&s, fct_path_display(from_path), r, (size_t)samples, tree, dir);
	sampler_free(&s);
	if (per_vertex) {
		struct direction tmp = {0};
		measure_vertices(from, fct_path_display(from_path), tree, per_vertex, &tmp);
		free(tmp.st.all);
	}
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{"seed", required_argument, NULL, 'S'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("meshdist");
	const char *out = NULL;
	int ascii = 0, sym = 0, c;
	long samples = 0;
	uint64_t seed = 1;
	static const char optstring[] = "aHho:pqs:v";
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': ascii = 1; break;
		case 'H': sym = 1; break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'p': keep_all = 1; break;
		case 'q': fct_quiet = 1; break;
		case 's': samples = fct_opt_long("-s", optarg, 0, 1000000000000L); break;
		case 'S': seed = (uint64_t)fct_opt_long("--seed", optarg, 0, 0x7fffffffffffffffL); break;
		case 'v': fct_verbose = 1; break;
		case 'V': puts("meshdist (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (argc - optind != 2)
		fct_usage_error(argc - optind < 2 ? "two meshes A and B are needed" : "too many operands");
	const char *pa = argv[optind], *pb = argv[optind + 1];
	if (!strcmp(pa, "-") && !strcmp(pb, "-"))
		fct_usage_error("A and B cannot both be standard input");
	if (out && !strcmp(out, "-"))
		fct_usage_error("-o: the figures go to standard output; name a file");

	struct fct_err err;
	struct fct_mesh a, b;
	double t0 = fct_now();
	if (fct_mesh_read_file(&a, pa, NULL, &err))
		fct_die_err(&err);
	if (fct_mesh_read_file(&b, pb, NULL, &err)) {
		fct_mesh_free(&a);
		fct_die_err(&err);
	}
	double read_s = fct_now() - t0, build_s = 0;
	check_finite(&a, pa);
	if (sym)
		check_finite(&b, pb);

	struct fct_bvh tree_b, tree_a;
	memset(&tree_a, 0, sizeof tree_a);
	build_tree(&tree_b, &b, pb, &build_s);
	if (sym)
		build_tree(&tree_a, &a, pa, &build_s);

	double *per_vertex = NULL;
	if (out && !(per_vertex = malloc(sizeof *per_vertex * (a.nv ? a.nv : 1))))
		fct_die(1, "out of memory for %zu vertices", a.nv);

	/* B to A draws from its own stream, so adding -H leaves A to B unchanged. */
	struct fct_rng rng_ab, rng_ba;
	fct_rng_seed(&rng_ab, seed);
	rng_ba = rng_ab;
	fct_rng_jump(&rng_ba);
	struct direction ab = {0}, ba = {0};
	measure(&a, pa, &tree_b, samples, &rng_ab, per_vertex, &ab);
	if (sym)
		measure(&b, pb, &tree_a, samples, &rng_ba, NULL, &ba);

	stats_print(&ab.st, "");
	if (sym) {
		stats_print(&ba.st, "ba_");
		printf("hausdorff %.17g\n", ab.st.run.max > ba.st.run.max ? ab.st.run.max : ba.st.run.max);
	}
	if (fflush(stdout) || ferror(stdout))
		fct_die(1, "standard output: write error");

	if (out) {
		struct fct_prop *p = fct_elem_add_scalar(&a.vertex, "distance", FCT_FLOAT32, &err);
		if (!p)
			fct_die_err(&err);
		for (size_t i = 0; i < a.nv; i++)
			fct_prop_set(p, i, per_vertex[i]);
		if (fct_header_add_provenance(&a, "meshdist", argc - 1, argv + 1, &err) ||
		    fct_mesh_write_file(&a, out, ascii, &err))
			fct_die_err(&err);
	}

	size_t nq = ab.queries + ba.queries;
	double qs = ab.seconds + ba.seconds;
	fct_report("vertices_a", "%zu", a.nv);
	fct_report("faces_a", "%zu", a.nf);
	fct_report("vertices_b", "%zu", b.nv);
	fct_report("faces_b", "%zu", b.nf);
	fct_report("triangles_b", "%zu", tree_b.ntri);
	fct_report("bvh_nodes_b", "%zu", tree_b.nnodes);
	fct_report("bvh_depth_b", "%d", tree_b.depth);
	fct_report("read_s", "%.3f", read_s);
	fct_report("build_s", "%.3f", build_s);
	fct_report("queries", "%zu", nq);
	fct_report("query_s", "%.3f", qs);
	fct_report("queries_per_s", "%.0f", qs > 0 ? (double)nq / qs : 0);
	struct fct_dist_stats f;
	fct_dist_run_stats(&f, &ab.st.run);
	fct_report("max", "%.9g", f.max);
	fct_report("rms", "%.9g", f.rms);

	free(per_vertex);
	fct_bvh_free(&tree_a);
	fct_bvh_free(&tree_b);
	free(ab.st.all);
	free(ba.st.all);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
	return 0;
}
