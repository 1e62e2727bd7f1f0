/* creaseangle - how well a mesh keeps the creases of a known polyhedral
 * surface: for each crease of the truth (an edge where two planar patches
 * meet) the angle between the two planes fitted to the mesh's vertices in a
 * band on either side of it, against the true angle between the patches.
 * The measure of issue 6 (a smoother that rounds a crease tilts the planes
 * near it toward each other), for areaflow against Laplacian and Taubin.
 *
 * Each vertex is placed on the truth by the ray from the viewpoint through
 * it (the header's pose, or the camera's origin), the way a range sensor saw
 * it, or by the closest point when the mesh has no camera.  The true point
 * decides the patch and the distance to the crease; the vertex's own
 * position gives the height: a least-squares fit h = a + b u + c v of its
 * signed distance h from the true plane over the true point's in-plane
 * coordinates (u, v), so noise along the rays adds variance, not bias (an
 * orthogonal fit of a narrow noisy strip would tilt). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "geom/bvh.h"
#include "cli/cli.h"
#include "geom/geom.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "geom/planes.h"

static const char usage[] =
	"usage: creaseangle [-qv] [-b band] [-m count] A TRUTH\n"
	"Angles at the creases of TRUTH (a mesh with the face property patch and\n"
	"the plane element, as mkscene writes) as the vertices of A show them: for\n"
	"each pair of planar patches sharing an edge at more than 20 degrees, the\n"
	"angle between the planes fitted to A's vertices within band of the crease\n"
	"on either side; one \"crease P Q TRUE MEASURED NP NQ\" line each (degrees\n"
	"between the normals, vertices fitted), then count, mean_error and\n"
	"max_error (degrees).\n"
	"  -b band     the band's width in the units of the coordinates\n"
	"              (default 0.03)\n"
	"  -m count    the fewest vertices on each side for a crease to count\n"
	"              (default 50)\n"
	"  -q          quiet\n"
	"  -v          report sizes on stderr\n"
	"  -h, --help  this help\n"
	"      --version print the version\n";

/* Least-squares moments of h = a + b u + c v. */
struct fit {
	double m[6];   /* sums of 1 u v uu uv vv */
	double r[3];   /* sums of h, hu, hv */
};

static void fit_add(struct fit *f, double u, double v, double h)
{
	f->m[0] += 1, f->m[1] += u, f->m[2] += v;
	f->m[3] += u * u, f->m[4] += u * v, f->m[5] += v * v;
	f->r[0] += h, f->r[1] += h * u, f->r[2] += h * v;
}

/* The slopes (b, c); 0 when the system is singular. */
static int fit_solve(const struct fit *f, double *b, double *c)
{
	double a[3][3] = { { f->m[0], f->m[1], f->m[2] }, { f->m[1], f->m[3], f->m[4] },
	                   { f->m[2], f->m[4], f->m[5] } };
	double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
	             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
	             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
	double scale = a[0][0] * a[1][1] * a[2][2];
	if (!(fabs(det) > 1e-12 * fabs(scale)) || !isfinite(det))
		return 0;
	/* Cramer's rule for the second and third unknowns */
	double db = a[0][0] * (f->r[1] * a[2][2] - a[1][2] * f->r[2]) -
	            f->r[0] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
	            a[0][2] * (a[1][0] * f->r[2] - f->r[1] * a[2][0]);
	double dc = a[0][0] * (a[1][1] * f->r[2] - f->r[1] * a[2][1]) -
	            a[0][1] * (a[1][0] * f->r[2] - f->r[1] * a[2][0]) +
	            f->r[0] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
	*b = db / det;
	*c = dc / det;
	return isfinite(*b) && isfinite(*c);
}

/* One crease: patches p < q, its segments in seg (pairs of TRUTH vertices). */
struct crease {
	int p, q;
	size_t nseg, cap;
	uint32_t *seg;
	struct fit side[2];
	size_t count[2];
};

static struct crease *find_crease(struct crease **cr, size_t *ncr, size_t *cap, int p, int q)
{
	for (size_t i = 0; i < *ncr; i++)
		if ((*cr)[i].p == p && (*cr)[i].q == q)
			return &(*cr)[i];
	if (*ncr == *cap) {
		*cap = *cap ? 2 * *cap : 16;
		*cr = realloc(*cr, sizeof **cr * *cap);
		if (!*cr)
			fct_die(1, "out of memory for the creases");
	}
	struct crease *c = &(*cr)[(*ncr)++];
	memset(c, 0, sizeof *c);
	c->p = p, c->q = q;
	return c;
}

static void read_mesh(struct fct_mesh *m, const char *path)
{
	struct fct_err err;
	fct_mesh_init(m);
	if (fct_mesh_read_file(m, path, NULL, &err))
		fct_die_err(&err);
	for (size_t i = 0; i < 3 * m->nv; i++)
		if (!isfinite(m->xyz[i]))
			fct_die(1, "%s: vertex %zu: coordinate is not finite", fct_path_display(path), i / 3);
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 256},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "b:hm:qv";
	fct_cli_init("creaseangle");
	double band = 0.03;
	long minc = 50;
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'b': band = fct_opt_double("-b", optarg, 1e-300, 1e300); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'm': minc = fct_opt_long("-m", optarg, 3, 1000000000); break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case 256: printf("creaseangle %s\n", FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (argc - optind != 2)
		fct_usage_error("%s", argc - optind < 2 ? "two meshes needed: A TRUTH" : "too many operands");
	if (!strcmp(argv[optind], "-") && !strcmp(argv[optind + 1], "-"))
		fct_usage_error("only one of A and TRUTH may be standard input");
	struct fct_mesh a, t;
	read_mesh(&a, argv[optind]);
	read_mesh(&t, argv[optind + 1]);
	const char *tname = fct_path_display(argv[optind + 1]);
	struct fct_err err;
	struct fct_plane *pl = NULL;
	size_t npl = 0;
	int32_t *patch = NULL;
	int present = 0;
	if (fct_planes_get(&t, &pl, &npl, &err) ||
	    fct_patches_get(&t, &patch, &present, (long)npl, &err))
		fct_die_err_at(&err, "%s", tname);
	if (!present || !npl)
		fct_die(1, "%s: no face property patch and plane element", tname);

	/* The viewpoint: the pose's origin, or the camera's. */
	double org[3] = { 0, 0, 0 }, pose[12];
	struct fct_camera cam;
	int has_cam = fct_header_camera(&a, &cam, &err) == 1;
	int has_pose = fct_header_pose(&a, pose, &err) == 1;
	if (has_pose)
		org[0] = pose[3], org[1] = pose[7], org[2] = pose[11];
	int rays = has_cam || has_pose;

	/* The creases: edges of TRUTH between faces of two patches whose
	 * normals differ by more than 20 degrees.  Corners (TRUTH vertices on
	 * three or more patches) are kept out of every band, so each band sees
	 * two planes only. */
	struct fct_adj adj;
	if (fct_adj_build(&adj, &t, &err))
		fct_die_err(&err);
	struct crease *cr = NULL;
	size_t ncr = 0, ccap = 0;
	for (size_t e = 0; e < adj.ne; e++) {
		if (fct_adj_edge_nfaces(&adj, e) != 2)
			continue;
		int p = patch[adj.edge_f[adj.edge_fstart[e]]], q = patch[adj.edge_f[adj.edge_fstart[e] + 1]];
		if (p < 0 || q < 0 || p == q)
			continue;
		if (p > q) { int s = p; p = q; q = s; }
		if (fct_v3_dot(pl[p].n, pl[q].n) > cos(20 * M_PI / 180))
			continue;
		struct crease *k = find_crease(&cr, &ncr, &ccap, p, q);
		if (k->nseg == k->cap) {
			k->cap = k->cap ? 2 * k->cap : 8;
			k->seg = realloc(k->seg, sizeof *k->seg * 2 * k->cap);
			if (!k->seg)
				fct_die(1, "out of memory for the creases");
		}
		k->seg[2 * k->nseg] = adj.edge_v[2 * e];
		k->seg[2 * k->nseg + 1] = adj.edge_v[2 * e + 1];
		k->nseg++;
	}
	unsigned char *corner = calloc(t.nv ? t.nv : 1, 1);
	if (!corner)
		fct_die(1, "out of memory");
	for (size_t v = 0; v < t.nv; v++) {
		int seen[3] = { -2, -2, -2 }, ns = 0;
		for (uint32_t i = adj.vert_fstart[v]; i < adj.vert_fstart[v + 1] && ns < 3; i++) {
			int pp = patch[adj.vert_f[i]];
			if (pp != seen[0] && pp != seen[1])
				seen[ns++] = pp;
		}
		corner[v] = ns >= 3;
	}

	struct fct_bvh tree;
	if (fct_bvh_build_mesh(&tree, &t, &err))
		fct_die_err_at(&err, "%s", tname);
	for (size_t v = 0; v < a.nv; v++) {
		const double *x = a.xyz + 3 * v;
		double tp[3];
		uint32_t f;
		if (rays) {
			double dir[3];
			struct fct_bvh_ray_hit rh;
			fct_v3_sub(dir, x, org);
			if (!fct_bvh_raycast(&tree, org, dir, 0, INFINITY, &rh))
				continue;
			fct_v3_axpy(tp, org, rh.t, dir);
			f = rh.id;
		} else {
			struct fct_bvh_hit h;
			if (!fct_bvh_closest(&tree, x, INFINITY, &h))
				continue;
			memcpy(tp, h.q, sizeof tp);
			f = h.id;
		}
		int p = patch[f];
		if (p < 0)
			continue;
		/* the nearest crease of p within the band, away from corners */
		struct crease *best = NULL;
		double bd = band;
		int near_corner = 0;
		for (size_t i = 0; i < ncr && !near_corner; i++) {
			if (cr[i].p != p && cr[i].q != p)
				continue;
			for (size_t s = 0; s < cr[i].nseg; s++) {
				const double *s0 = t.xyz + 3 * (size_t)cr[i].seg[2 * s];
				const double *s1 = t.xyz + 3 * (size_t)cr[i].seg[2 * s + 1];
				for (int e = 0; e < 2; e++)
					if (corner[cr[i].seg[2 * s + e]] &&
					    fct_v3_dist2(tp, e ? s1 : s0) < 4 * band * band)
						near_corner = 1;
				double cq[3];
				fct_closest_on_segment(tp, s0, s1, cq);
				double d = sqrt(fct_v3_dist2(tp, cq));
				if (d < bd)
					bd = d, best = &cr[i];
			}
		}
		if (!best || near_corner)
			continue;
		int side = best->q == p;
		double e1[3], e2[3], h = fct_v3_dot(pl[p].n, x) + pl[p].d;
		fct_plane_frame(pl[p].n, e1, e2);
		fit_add(&best->side[side], fct_v3_dot(tp, e1), fct_v3_dot(tp, e2), h);
		best->count[side]++;
	}

	size_t used = 0;
	double sum = 0, mx = 0;
	for (size_t i = 0; i < ncr; i++) {
		struct crease *k = &cr[i];
		if (k->count[0] < (size_t)minc || k->count[1] < (size_t)minc)
			continue;
		double n[2][3];
		int ok = 1;
		for (int s = 0; s < 2; s++) {
			const struct fct_plane *P = &pl[s ? k->q : k->p];
			double e1[3], e2[3], b, cc;
			fct_plane_frame(P->n, e1, e2);
			if (!fit_solve(&k->side[s], &b, &cc)) {
				ok = 0;
				break;
			}
			/* h = a + b u + c v: the fitted normal is n - b e1 - c e2 */
			for (int j = 0; j < 3; j++)
				n[s][j] = P->n[j] - b * e1[j] - cc * e2[j];
			double len = sqrt(fct_v3_dot(n[s], n[s]));
			for (int j = 0; j < 3; j++)
				n[s][j] /= len;
		}
		if (!ok)
			continue;
		double dt = fct_v3_dot(pl[k->p].n, pl[k->q].n), dm = fct_v3_dot(n[0], n[1]);
		double at = acos(dt < -1 ? -1 : dt > 1 ? 1 : dt) * 180 / M_PI;
		double am = acos(dm < -1 ? -1 : dm > 1 ? 1 : dm) * 180 / M_PI;
		printf("crease %d %d %.9g %.9g %zu %zu\n", k->p, k->q, at, am, k->count[0], k->count[1]);
		used++;
		sum += fabs(am - at);
		if (fabs(am - at) > mx)
			mx = fabs(am - at);
	}
	printf("count %zu\n", used);
	printf("mean_error %.9g\n", used ? sum / (double)used : 0);
	printf("max_error %.9g\n", mx);
	fct_report("creases", "%zu", ncr);
	fct_report("measured", "%zu", used);
	fct_report("placed_by", "%s", rays ? "rays" : "closest points");
	for (size_t i = 0; i < ncr; i++)
		free(cr[i].seg);
	free(cr);
	free(corner);
	free(pl);
	free(patch);
	fct_bvh_free(&tree);
	fct_adj_free(&adj);
	fct_mesh_free(&a);
	fct_mesh_free(&t);
	if (fflush(stdout) || ferror(stdout))
		fct_die(1, "standard output: write error");
	return 0;
}
