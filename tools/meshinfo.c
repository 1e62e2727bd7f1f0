/* meshinfo - what is in a mesh file: format, elements, comments, counts,
 * bounding box and topology, one "key: value" a line in a fixed order, so
 * that tests and scripts can read it (see meshinfo(1) for every line). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"

static const char usage[] =
	"usage: meshinfo [file ...]\n"
	"Describe each mesh (PLY or OBJ; stdin when no file is given or for \"-\"):\n"
	"format, elements and properties, comments, counts, bounding box, edges,\n"
	"components, isolated vertices, degenerate and duplicate faces, the\n"
	"noise model, the noise estimated from the data and the vertices' sigma,\n"
	"as \"key: value\" lines.\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

/* A face whose area is at most this times the squared bounding-box diagonal
 * is degenerate: relative, so that the answer does not depend on units. */
#define ZERO_AREA_REL 1e-12

static void print_props(const char *elem, const struct fct_elem *e)
{
	for (size_t j = 0; j < e->nprops; j++) {
		const struct fct_prop *p = &e->props[j];
		if (p->count_type != FCT_NONE)
			printf("property: %s list %s %s %s\n", elem, fct_type_name(p->count_type),
			       fct_type_name(p->type), p->name);
		else
			printf("property: %s %s %s\n", elem, fct_type_name(p->type), p->name);
	}
}

/* Elements and properties in the order facet writes them. */
static void print_elements(const struct fct_mesh *m)
{
	const char *xt = fct_type_name(m->xyz_type == FCT_FLOAT64 ? FCT_FLOAT64 : FCT_FLOAT32);
	printf("element: vertex %zu\n", m->nv);
	printf("property: vertex %s x\nproperty: vertex %s y\nproperty: vertex %s z\n", xt, xt, xt);
	print_props("vertex", &m->vertex);
	if (m->has_faces || m->nf) {
		printf("element: face %zu\n", m->nf);
		printf("property: face list %s %s vertex_indices\n", fct_type_name(m->fcount_type),
		       fct_type_name(m->findex_type));
		print_props("face", &m->face);
	}
	for (size_t i = 0; i < m->nelems; i++) {
		printf("element: %s %zu\n", m->elems[i].name, m->elems[i].count);
		print_props(m->elems[i].name, &m->elems[i]);
	}
}

/* The comments as written, then what facet understands of them. */
static void print_comments(const struct fct_mesh *m)
{
	for (size_t i = 0; i < m->ncomments; i++)
		printf("%s: %s\n", m->comments[i].obj_info ? "obj_info" : "comment", m->comments[i].text);

	struct fct_err err;
	struct fct_camera cam;
	int rc = fct_header_camera(m, &cam, &err);
	if (rc < 0)
		printf("camera: invalid: %s\n", err.msg);
	else if (rc == 0)
		printf("camera: none\n");
	else if (cam.kind == FCT_CAMERA_PINHOLE)
		printf("camera: pinhole width %d height %d fx %.17g fy %.17g cx %.17g cy %.17g\n",
		       cam.width, cam.height, cam.fx, cam.fy, cam.cx, cam.cy);
	else
		printf("camera: cylindrical width %d height %d f %.17g cy %.17g theta0 %.17g\n",
		       cam.width, cam.height, cam.f, cam.cy, cam.theta0);

	double pose[12];
	rc = fct_header_pose(m, pose, &err);
	if (rc < 0) {
		printf("pose: invalid: %s\n", err.msg);
	} else if (rc == 0) {
		printf("pose: none\n");
	} else {
		printf("pose: rotation");
		for (int r = 0; r < 3; r++)
			for (int c = 0; c < 3; c++)
				printf(" %.17g", pose[4 * r + c]);
		printf(" translation %.17g %.17g %.17g\n", pose[3], pose[7], pose[11]);
	}

	struct fct_noise nz;
	rc = fct_header_noise(m, &nz, &err);
	if (rc < 0) {
		printf("noise: invalid: %s\n", err.msg);
	} else if (rc == 0) {
		printf("noise: unknown\n");
	} else {
		char text[256];
		fct_noise_format(&nz, text, sizeof text);
		printf("noise: %s\n", text);
	}

	const char *tex;
	for (size_t i = 0; (tex = fct_header_texture(m, i)); i++)
		printf("texture: %s\n", tex);
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *t = m->comments[i].text;
		if (!m->comments[i].obj_info && !strncmp(t, "facet", 5) && (t[5] == ' ' || t[5] == '\t'))
			printf("provenance: %s\n", t + 6);
	}
}

static void print_counts(const struct fct_mesh *m)
{
	/* 3, 4, 5 or more corners; the readers refuse faces of fewer. */
	size_t n[3] = {0, 0, 0};
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t k = fct_face_size(m, f);
		if (k >= 3)
			n[k > 5 ? 2 : k - 3]++;
	}
	printf("vertices: %zu\nfaces: %zu\n", m->nv, m->nf);
	printf("triangles: %zu\nquads: %zu\npolygons: %zu\n", n[0], n[1], n[2]);
}

/* Bounding box of the finite vertices (the readers refuse others; skipping
 * them anyway keeps one bad vertex from hiding the box); returns the squared
 * diagonal (0 when there is none). */
static double print_bbox(const struct fct_mesh *m)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	size_t nfinite = 0;
	for (size_t v = 0; v < m->nv; v++) {
		const double *p = m->xyz + 3 * v;
		if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
			continue;
		nfinite++;
		for (int k = 0; k < 3; k++) {
			lo[k] = p[k] < lo[k] ? p[k] : lo[k];
			hi[k] = p[k] > hi[k] ? p[k] : hi[k];
		}
	}
	if (!nfinite) {
		printf("bbox_min: none\nbbox_max: none\nbbox_size: none\nbbox_diagonal: none\n");
		return 0;
	}
	double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
	double diag2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
	printf("bbox_min: %.9g %.9g %.9g\n", lo[0], lo[1], lo[2]);
	printf("bbox_max: %.9g %.9g %.9g\n", hi[0], hi[1], hi[2]);
	printf("bbox_size: %.9g %.9g %.9g\n", d[0], d[1], d[2]);
	printf("bbox_diagonal: %.9g\n", sqrt(diag2));
	return diag2;
}

/* Mean length of the unique edges whose ends are both finite. */
static void print_edges(const struct fct_mesh *m, const struct fct_adj *a)
{
	double sum = 0;
	size_t n = 0;
	for (size_t e = 0; e < a->ne; e++) {
		const double *p = m->xyz + 3 * (size_t)a->edge_v[2 * e];
		const double *q = m->xyz + 3 * (size_t)a->edge_v[2 * e + 1];
		double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
		                (p[2] - q[2]) * (p[2] - q[2]));
		if (isfinite(d))
			sum += d, n++;
	}
	printf("edges: %zu\n", a->ne);
	if (n)
		printf("mean_edge_length: %.9g\n", sum / (double)n);
	else
		printf("mean_edge_length: none\n");
	printf("border_edges: %zu\nmanifold_edges: %zu\nnon_manifold_edges: %zu\n",
	       a->nborder, a->nmanifold, a->nnonmanifold);
}

static int compare_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* The vertex property sigma's finite values: min, median (the lower middle
 * for an even count), max; nothing when there is no such property.  -1
 * with err set when out of memory. */
static int print_sigma(const struct fct_mesh *m, struct fct_err *err)
{
	const struct fct_prop *p = fct_elem_find(&m->vertex, "sigma");
	if (!p || p->count_type != FCT_NONE)
		return 0;
	double *v = fct_alloc_array(m->nv, sizeof *v, err);
	if (!v)
		return -1;
	size_t n = 0;
	for (size_t i = 0; i < m->nv; i++) {
		double s = fct_prop_get(p, i);
		if (isfinite(s))
			v[n++] = s;
	}
	if (n) {
		qsort(v, n, sizeof *v, compare_double);
		printf("sigma_min: %.9g\nsigma_median: %.9g\nsigma_max: %.9g\n", v[0], v[(n - 1) / 2], v[n - 1]);
	} else {
		printf("sigma_min: none\nsigma_median: none\nsigma_max: none\n");
	}
	free(v);
	return 0;
}

/* The noise estimated from the data (noise.h), or none when the mesh gives
 * too little to estimate it. */
static void print_estimate(const struct fct_mesh *m)
{
	struct fct_noise_fit fit;
	struct fct_err err;
	if (fct_noise_fit(&fit, m, &err)) {
		printf("sigma_estimate: none\nsigma_estimate_law: none\n");
		return;
	}
	printf("sigma_estimate: %.9g\n", fit.sigma);
	printf("sigma_estimate_law: %.9g z^%d %s\n", fit.c, fit.p, fit.camera ? "along rays" : "along normals");
}

/* Topology and face checks; -1 with err set when out of memory. */
static int print_topology(const struct fct_mesh *m, double diag2, struct fct_err *err)
{
	struct fct_adj a;
	if (fct_adj_build(&a, m, err))
		return -1;
	print_edges(m, &a);
	uint32_t *label = malloc((m->nf ? m->nf : 1) * sizeof *label);
	long ncomp = label ? fct_adj_components(&a, label, err) : fct_fail(err, "out of memory");
	free(label);
	size_t isolated = fct_adj_isolated_vertices(&a);
	fct_adj_free(&a);
	if (ncomp < 0)
		return -1;
	long degenerate = fct_mesh_degenerate_faces(m, ZERO_AREA_REL * diag2, NULL, err);
	long duplicate = degenerate < 0 ? -1 : fct_mesh_duplicate_faces(m, NULL, err);
	long same_place = duplicate < 0 ? -1 : fct_mesh_duplicate_vertices(m, NULL, err);
	if (same_place < 0)
		return -1;
	printf("components: %ld\nisolated_vertices: %zu\nduplicate_vertices: %ld\n", ncomp, isolated,
	       same_place);
	printf("degenerate_faces: %ld\nduplicate_faces: %ld\n", degenerate, duplicate);
	return 0;
}

/* Describe one file, after a blank line when *printed says another came
 * before; 0, or -1 with err set. */
static int describe(const char *path, int *printed, struct fct_err *err)
{
	struct fct_mesh m;
	enum fct_format fmt;
	if (fct_mesh_read_file(&m, path, &fmt, err))
		return -1;
	if (*printed)
		putchar('\n');
	*printed = 1;
	printf("file: %s\n", fct_path_display(path));
	printf("format: %s\n", fct_format_name(fmt));
	print_elements(&m);
	print_comments(&m);
	print_counts(&m);
	double diag2 = print_bbox(&m);
	int rc = print_topology(&m, diag2, err);
	if (!rc)
		print_estimate(&m);
	if (!rc)
		rc = print_sigma(&m, err);
	if (rc)
		fct_err_prefix(err, "%s", fct_path_display(path));
	fct_mesh_free(&m);
	return rc;
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("meshinfo");
	static const char optstring[] = "h";
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'h': fputs(usage, stdout); return 0;
		case 'V': puts("meshinfo (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	int status = 0, printed = 0, nfiles = argc - optind;
	for (int i = 0; i < (nfiles ? nfiles : 1); i++) {
		struct fct_err err;
		if (describe(nfiles ? argv[optind + i] : NULL, &printed, &err)) {
			fflush(stdout);
			fct_error("%s", err.msg);
			status = 1;
		}
	}
	if (fflush(stdout) || ferror(stdout))
		fct_die(1, "<stdout>: write error");
	return status;
}
