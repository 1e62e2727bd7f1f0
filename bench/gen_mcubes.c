/* gen_mcubes - marching-cubes throughput on synthetic grids, beside a plain
 * pass over the same voxels, one core.
 *   gen_mcubes [-r RUNS] [-t THREADS] room|dense
 *                                       extract RUNS times, print the medians:
 *                                       key=value lines (seconds, voxels, ...):
 *                                       CPU seconds of the process (all its
 *                                       threads) and wall seconds, and the
 *                                       page faults of one extraction, and
 *                                       each phase's wall ms (fct_mcubes_stats)
 *   gen_mcubes [-r RUNS] [-t THREADS] [-s VOXEL] fused VIEW.ply...
 *                                       the same on the volume tsdfuse fuses from
 *                                       the views (dm2mesh meshes with camera and
 *                                       pose comments; true distance, band 3
 *                                       voxels, constant weight; VOXEL 0.01), so
 *                                       that marching cubes is timed alone on a
 *                                       real volume
 *   gen_mcubes -w ...                   (first option) warm output: each run's mesh
 *                                       is freed before the next run extracts, and
 *                                       glibc keeps freed memory (mmap threshold
 *                                       256 MB, trim threshold 1 GB), so that the
 *                                       output comes back already faulted in: the
 *                                       extraction's compute alone, as tsdfuse
 *                                       sees it when it reuses the views' memory
 *                                       (the headline rows without -w: fresh
 *                                       output, page faults included)
 *   gen_mcubes estimate                 blocks and bytes of a 10 x 10 x 3 m room
 *                                       band at 1 cm, counted without allocating
 * room: a 4 x 4 x 2.5 m room at 1 cm voxels, a 0.5 m ball and a 1 x 0.6 x 0.75 m
 * table in it, blocks only where the truncation band (4 voxels) reaches, as a
 * fusion leaves them.  dense: a 256^3 volume, every voxel observed, a ball of
 * radius 100 voxels (the volume scikit-image is usually timed on). */
#include <malloc.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/resource.h>
#include <time.h>

#include "cli/cli.h"
#include "fusion/fuse.h"
#include "io/header.h"
#include "fusion/mcubes.h"
#include "io/meshio.h"

struct scene {
	double room[3];         /* interior from 0 to room */
	double ball[4];         /* centre, radius */
	double table[6];        /* box lo, hi */
};

static double box_out(const double p[3], const double lo[3], const double hi[3])
{
	/* distance from p to the box, negative inside */
	double q[3], out = 0, in = -1e300;
	for (int k = 0; k < 3; k++) {
		double c = 0.5 * (lo[k] + hi[k]), h = 0.5 * (hi[k] - lo[k]);
		q[k] = fabs(p[k] - c) - h;
		out += q[k] > 0 ? q[k] * q[k] : 0;
		in = q[k] > in ? q[k] : in;
	}
	return out > 0 ? sqrt(out) : in;
}

/* Signed distance of the room scene, positive in free space. */
static double room_sdf(const struct scene *s, const double p[3])
{
	double d = 1e300;
	for (int k = 0; k < 3; k++) {
		d = fmin(d, p[k]);
		d = fmin(d, s->room[k] - p[k]);
	}
	double b[3] = { p[0] - s->ball[0], p[1] - s->ball[1], p[2] - s->ball[2] };
	d = fmin(d, sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]) - s->ball[3]);
	return fmin(d, box_out(p, s->table, s->table + 3));
}

/* Blocks of the room band: those whose centre is within trunc + half a block
 * diagonal of the surface.  fill != 0 allocates and fills them. */
static size_t room_blocks(const struct scene *s, double vox, double trunc, struct fct_voxgrid *g,
                          struct fct_err *err)
{
	double bs = 8 * vox, reach = trunc + bs * sqrt(3) / 2;
	int32_t n[3];
	for (int k = 0; k < 3; k++)
		n[k] = (int32_t)ceil((s->room[k] + trunc) / bs) + 1;
	size_t count = 0;
	for (int32_t bz = -1; bz < n[2]; bz++)
		for (int32_t by = -1; by < n[1]; by++)
			for (int32_t bx = -1; bx < n[0]; bx++) {
				double c[3] = { (8 * bx + 3.5) * vox, (8 * by + 3.5) * vox, (8 * bz + 3.5) * vox };
				if (fabs(room_sdf(s, c)) > reach)
					continue;
				count++;
				if (!g)
					continue;
				struct fct_voxblock *b = fct_voxgrid_block(g, bx, by, bz, 1, err);
				if (!b)
					fct_die_err(err);
				for (int v = 0; v < 512; v++) {
					double p[3] = { (8 * bx + (v & 7)) * vox, (8 * by + (v >> 3 & 7)) * vox,
					                (8 * bz + (v >> 6)) * vox };
					double d = room_sdf(s, p);
					if (fabs(d) <= trunc) {
						b->sdf[v] = (float)d;
						b->weight[v] = 1;
					}
				}
			}
	return count;
}

/* Fuse the dm2mesh views at paths[0..n-1] into g as tsdfuse does by
 * default (true distance, band 3 voxels, constant weight). */
static void fuse_views(struct fct_voxgrid *g, char **paths, int n, int threads)
{
	struct fct_err err;
	struct fct_fuse_params fp = { 0 };
	fp.band = 3 * fct_voxgrid_voxel(g);
	fp.weight = FCT_FUSE_CONSTANT;
	fp.threads = threads;
	for (int i = 0; i < n; i++) {
		struct fct_mesh m;
		struct fct_fuse_view v = { 0 };
		if (fct_mesh_read_file(&m, paths[i], NULL, &err))
			fct_die_err(&err);
		if (fct_header_camera(&m, &v.cam, &err) != 1 || fct_header_pose(&m, v.pose, &err) != 1)
			fct_die(1, "%s: needs the camera and pose comments dm2mesh writes", paths[i]);
		v.mesh = &m;
		if (fct_fuse_view(g, &v, &fp, NULL, &err))
			fct_die_err(&err);
		fct_mesh_free(&m);
	}
}

/* CPU seconds of this process: the machines are shared, wall time is not
 * ours alone. */
static double cpu_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double wall_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* FNV-1a of the mesh's bytes (positions, normals, faces): equal output
 * across builds and thread counts shows as equal figures. */
static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *c = p;
	for (size_t i = 0; i < n; i++)
		h = (h ^ c[i]) * 1099511628211u;
	return h;
}

static uint64_t mesh_hash(const struct fct_mesh *m)
{
	static const char *nn[3] = { "nx", "ny", "nz" };
	uint64_t h = fnv(14695981039346656037u, m->xyz, 3 * m->nv * sizeof *m->xyz);
	for (int k = 0; k < 3; k++) {
		const struct fct_prop *p = fct_elem_find(&m->vertex, nn[k]);
		h = fnv(h, p->data, m->nv * sizeof(float));
	}
	return m->nf ? fnv(h, m->fvert, m->fstart[m->nf] * sizeof *m->fvert) : h;
}

/* Minor page faults of this process so far. */
static double faults_now(void)
{
	struct rusage u;
	return getrusage(RUSAGE_SELF, &u) ? 0 : (double)u.ru_minflt;
}

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

static double median(double *t, int n)
{
	qsort(t, (size_t)n, sizeof *t, cmp);
	return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

int main(int argc, char **argv)
{
	fct_cli_init("gen_mcubes");
	struct fct_err err;
	int runs = 5, threads = 1, a = 1, warm = 0;
	double voxel = 0.01;
	if (a < argc && !strcmp(argv[a], "-w"))
		warm = 1, a++;
	for (; a + 2 < argc; a += 2) {
		if (!strcmp(argv[a], "-r"))
			runs = (int)fct_opt_long("-r", argv[a + 1], 1, 1000);
		else if (!strcmp(argv[a], "-t"))
			threads = (int)fct_opt_long("-t", argv[a + 1], 1, 64);
		else if (!strcmp(argv[a], "-s"))
			voxel = fct_opt_double("-s", argv[a + 1], 1e-6, 1e6);
		else
			break;
	}
	if (a >= argc || (a + 1 != argc && strcmp(argv[a], "fused")))
		fct_usage_error("usage: gen_mcubes [-w] [-r RUNS] [-t THREADS] [-s VOXEL] room|dense|estimate|fused VIEW.ply...");
	const char *what = argv[a];
	if (!strcmp(what, "estimate")) {
		struct scene s = { { 10, 10, 3 }, { 5, 5, -10, 0 }, { 0, 0, -9, 0, 0, -9 } };
		double trunc = 0.04;
		size_t n = room_blocks(&s, 0.01, trunc, NULL, &err);
		printf("room_blocks=%zu\nblock_bytes=%zu\nblock_bytes_colour=%zu\n", n,
		       fct_voxgrid_block_bytes(0), fct_voxgrid_block_bytes(1));
		printf("room_gb=%.3f\nroom_gb_colour=%.3f\n", n * (double)fct_voxgrid_block_bytes(0) / 1e9,
		       n * (double)fct_voxgrid_block_bytes(1) / 1e9);
		printf("dense_gb=%.1f\n", 1000.0 * 1000 * 300 * 8 / 1e9);
		return 0;
	}
	struct fct_voxgrid *g = fct_voxgrid_new(strcmp(what, "fused") ? 0.01 : voxel, 0, &err);
	if (!g)
		fct_die_err(&err);
	if (!strcmp(what, "room")) {
		struct scene s = { { 4, 4, 2.5 }, { 2.6, 1.4, 1.2, 0.5 }, { 0.8, 2.2, 0, 1.8, 2.8, 0.75 } };
		room_blocks(&s, 0.01, 0.04, g, &err);
	} else if (!strcmp(what, "dense")) {
		for (int32_t bz = 0; bz < 32; bz++)
			for (int32_t by = 0; by < 32; by++)
				for (int32_t bx = 0; bx < 32; bx++) {
					struct fct_voxblock *b = fct_voxgrid_block(g, bx, by, bz, 1, &err);
					if (!b)
						fct_die_err(&err);
					for (int v = 0; v < 512; v++) {
						double x = 8 * bx + (v & 7) - 127.6, y = 8 * by + (v >> 3 & 7) - 128.3,
						       z = 8 * bz + (v >> 6) - 127.9;
						b->sdf[v] = (float)(0.01 * (sqrt(x * x + y * y + z * z) - 100));
						b->weight[v] = 1;
					}
				}
	} else if (!strcmp(what, "fused")) {
		fuse_views(g, argv + a + 1, argc - a - 1, threads);
	} else {
		fct_usage_error("gen_mcubes: unknown scene %s", what);
	}
	size_t nb = fct_voxgrid_count(g);
	double *tm = malloc((size_t)runs * sizeof *tm), *tr = malloc((size_t)runs * sizeof *tr);
	double *tw = malloc((size_t)runs * sizeof *tw), *tf = malloc((size_t)runs * sizeof *tf);
	/* Every run extracts into fresh memory (the meshes of all runs are kept
	 * to the end), as a one-shot extraction does: the time includes the
	 * kernel's page faults on the output arrays alike in every run.  (Freed
	 * between runs, they came back from malloc already faulted in or not,
	 * as glibc's mmap threshold moved, and the median with them.) */
	struct fct_mesh *ms = calloc((size_t)runs, sizeof *ms);
	if (warm) {
		/* with -w the meshes are freed between runs and glibc keeps their
		 * memory for the next */
		mallopt(M_MMAP_THRESHOLD, 256 << 20);
		mallopt(M_TRIM_THRESHOLD, 1 << 30);
	}
	double *tph = malloc((size_t)runs * FCT_MC_PHASES * sizeof *tph);
	if (!tm || !tr || !tw || !tf || !ms || !tph)
		fct_die(1, "out of memory");
	struct fct_mcubes_stats st;
	double sum = 0;
	for (int r = 0; r < runs; r++) {
		/* reference: one pass reading every sdf and weight value */
		double t0 = cpu_now();
		float acc[8] = { 0 };
		for (size_t b = 0; b < nb; b++) {
			const struct fct_voxblock *B = fct_voxgrid_at(g, b);
			for (int v = 0; v < 512; v += 8)
				for (int k = 0; k < 8; k++)
					acc[k] += B->sdf[v + k] * B->weight[v + k];
		}
		for (int k = 0; k < 8; k++)
			sum += acc[k];
		tr[r] = cpu_now() - t0;
		if (warm && r)
			fct_mesh_free(&ms[r - 1]);     /* leaves it empty: freed again at the end harmlessly */
		double f0 = faults_now();
		t0 = cpu_now();
		double w0 = wall_now();
		if (fct_mcubes_stats(&ms[r], g, 0, NULL, NULL, threads, &st, &err))
			fct_die_err(&err);
		tm[r] = cpu_now() - t0;
		tw[r] = wall_now() - w0;
		tf[r] = faults_now() - f0;
		for (int k = 0; k < FCT_MC_PHASES; k++)
			tph[k * runs + r] = st.phase_s[k];
	}
	const struct fct_mesh *m = &ms[runs - 1];
	double vox = (double)nb * 512, band = 0;
	for (size_t b = 0; b < nb; b++) {
		const struct fct_voxblock *B = fct_voxgrid_at(g, b);
		for (int v = 0; v < 512; v++)
			band += B->weight[v] > 0;
	}
	double t = median(tm, runs), t_ref = median(tr, runs), t_wall = median(tw, runs);
	printf("threads=%zu\nband_voxels=%.0f\nmcubes_band_mvox_s=%.1f\n", st.threads, band,
	       band / t / 1e6);
	printf("mcubes_wall_s=%.5f\nmcubes_wall_mvox_s=%.1f\n", t_wall, vox / t_wall / 1e6);
	printf("blocks=%zu\nvoxels=%.0f\nvertices=%zu\nfaces=%zu\ncubes=%zu\nambiguous=%zu\ncentres=%zu\n",
	       nb, vox, m->nv, m->nf, st.cubes, st.ambiguous, st.centres);
	printf("mcubes_faults=%.0f\n", median(tf, runs));
	/* pass 0, pass 1, pass 2, output allocation, vertices, triangles */
	printf("phase_ms=");
	for (int k = 0; k < FCT_MC_PHASES; k++)
		printf("%.2f%c", 1e3 * median(tph + k * runs, runs), k + 1 < FCT_MC_PHASES ? ' ' : '\n');
	printf("mcubes_s=%.5f\nmcubes_mvox_s=%.1f\nref_s=%.5f\nref_mvox_s=%.1f\nchecksum=%.3g\n", t,
	       vox / t / 1e6, t_ref, vox / t_ref / 1e6, sum);
	printf("grid_mb=%.1f\nmesh_fnv=%016llx\n", fct_voxgrid_bytes(g) / 1e6,
	       (unsigned long long)mesh_hash(m));
	for (int r = 0; r < runs; r++)
		fct_mesh_free(&ms[r]);
	free(ms);
	free(tf);
	free(tph);
	fct_voxgrid_free(g);
	free(tm);
	free(tr);
	free(tw);
	return 0;
}
