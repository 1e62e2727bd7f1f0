/* meshconv - convert a mesh between PLY encodings and OBJ, keeping every
 * property and element the target format can hold; optionally mesh a
 * range-grid scan and place it in the world with its .conf pose; join
 * several meshes and weld them (tsdfuse --bbox tiles). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/camera.h"
#include "geom/adj.h"
#include "cli/cli.h"
#include "io/header.h"
#include "io/meshio.h"
#include "core/path.h"
#include "depth/rangegrid.h"

static const char usage[] =
	"usage: meshconv [-aqv] [-f format] [-o file] [--conf file] [--grid] [--weld]\n"
	"                [input ...]\n"
	"Convert a mesh (PLY or OBJ, detected from the content) to binary PLY,\n"
	"keeping every property, element and comment.\n"
	"  -a            write ascii PLY\n"
	"  -f format     ascii, binary_little_endian, binary_big_endian or obj\n"
	"  -o file       output file (default stdout); a name ending in .obj writes OBJ\n"
	"                and, for a textured mesh, a .mtl beside it\n"
	"  -q            quiet\n"
	"      --conf file  place the scan in the world with its pose from this\n"
	"                Stanford .conf file (the bmesh line naming input); a\n"
	"                range-grid scan is meshed as with --grid\n"
	"      --grid    mesh a range-grid scan (range_grid element, no faces) as\n"
	"                tsdfuse does; the range_grid element is dropped\n"
	"  -v            report counts and time on stderr\n"
	"      --weld    merge vertices at identical positions (the first of each\n"
	"                position is kept) and drop the faces that then repeat a\n"
	"                vertex; with several inputs, after joining them\n"
	"  Several inputs are joined: vertices and faces concatenated in order\n"
	"  (the same vertex and face properties in each), the first input's\n"
	"  comments kept, other elements dropped with a warning.\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

/* The pose of the .conf scan named like in (by file name; the full path
 * decides between equal names). */
static void conf_pose(const char *conf, const char *in, double pose[12])
{
	struct fct_err err;
	struct fct_conf c;
	if (fct_conf_read(&c, conf, &err))
		fct_die_err(&err);
	const char *base = strrchr(in, '/') ? strrchr(in, '/') + 1 : in;
	size_t found = c.n, same = 0;
	for (size_t i = 0; i < c.n; i++) {
		const char *p = c.scans[i].path;
		if (strcmp(strrchr(p, '/') ? strrchr(p, '/') + 1 : p, base))
			continue;
		if (same++ == 0 || !strcmp(p, in))
			found = i;
	}
	if (found == c.n || (same > 1 && strcmp(c.scans[found].path, in))) {
		fct_conf_free(&c);
		fct_die(1, "%s: %s %s", conf, same ? "several bmesh lines name" : "no bmesh line names", base);
	}
	memcpy(pose, c.scans[found].pose, 12 * sizeof *pose);
	fct_conf_free(&c);
}

/* --grid and --conf: mesh the range grid of m, then move it by the pose. */
static void range_scan(struct fct_mesh *m, const char *in, int grid, const char *conf)
{
	struct fct_err err;
	const char *name = fct_path_is_std(in) ? "<stdin>" : in;
	if (grid || (fct_mesh_find_elem(m, "range_grid") && m->nf == 0)) {
		struct fct_mesh meshed;
		if (fct_range_grid_mesh(&meshed, m, NULL, NULL, &err))
			fct_die_err_at(&err, "%s", name);
		fct_mesh_free(m);
		*m = meshed;
	}
	if (!conf)
		return;
	double pose[12];
	conf_pose(conf, in, pose);
	double had[12];
	int hp = fct_header_pose(m, had, &err);
	fct_err_prefix(&err, "%s", name);
	if (hp) {
		fct_mesh_free(m);
		if (hp < 0)
			fct_die_err(&err);
		fct_die(1, "%s: already has a pose comment: its vertices are in a world frame", name);
	}
	for (size_t v = 0; v < m->nv; v++)
		fct_pose_apply(pose, &m->xyz[3 * v], &m->xyz[3 * v]);
	struct fct_prop *n[3] = { fct_elem_find(&m->vertex, "nx"), fct_elem_find(&m->vertex, "ny"),
	                          fct_elem_find(&m->vertex, "nz") };
	if (n[0] && n[1] && n[2])
		for (size_t v = 0; v < m->nv; v++) {
			double a[3], b[3];
			for (int k = 0; k < 3; k++)
				a[k] = fct_prop_get(n[k], v);
			for (int k = 0; k < 3; k++)
				b[k] = pose[4 * k] * a[0] + pose[4 * k + 1] * a[1] + pose[4 * k + 2] * a[2];
			for (int k = 0; k < 3; k++)
				fct_prop_set(n[k], v, b[k]);
		}
	if (fct_header_set_pose(m, pose, &err)) {
		fct_mesh_free(m);
		fct_die_err(&err);
	}
}

/* --weld: merge equal positions, drop faces that repeat a vertex. */
static void weld(struct fct_mesh *m)
{
	struct fct_err err;
	size_t ndeg;
	long merged = fct_mesh_weld(m, &ndeg, &err);
	if (merged < 0) {
		fct_mesh_free(m);
		fct_die_err(&err);
	}
	fct_report("welded_vertices", "%ld", merged);
	fct_report("degenerate_faces", "%zu", ndeg);
}

/* Join next (freed) onto m; next's other elements are dropped. */
static void join(struct fct_mesh *m, struct fct_mesh *next, const char *in)
{
	struct fct_err err;
	for (size_t i = 0; i < next->nelems; i++)
		fct_warn("%s: element %s dropped (several inputs are joined)", in, next->elems[i].name);
	if (fct_mesh_append(m, next, &err))
		fct_die_err_at(&err, "%s", in);
	fct_mesh_free(next);
}

int main(int argc, char **argv)
{
	enum { OPT_CONF = 256, OPT_GRID, OPT_WELD };
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{"conf", required_argument, NULL, OPT_CONF},
		{"grid", no_argument, NULL, OPT_GRID},
		{"weld", no_argument, NULL, OPT_WELD},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("meshconv");
	const char *out = NULL, *conf = NULL;
	int fmt = -1, c, grid = 0, welding = 0;
	static const char optstring[] = "af:ho:qv";
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': fmt = FCT_FORMAT_PLY_ASCII; break;
		case 'f':
			if (!strcmp(optarg, "ascii")) fmt = FCT_FORMAT_PLY_ASCII;
			else if (!strcmp(optarg, "binary_little_endian")) fmt = FCT_FORMAT_PLY_LE;
			else if (!strcmp(optarg, "binary_big_endian")) fmt = FCT_FORMAT_PLY_BE;
			else if (!strcmp(optarg, "obj")) fmt = FCT_FORMAT_OBJ;
			else fct_usage_error("-f: unknown format \"%s\"", optarg);
			break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case 'V': puts("meshconv (facet) " FCT_VERSION); return 0;
		case OPT_CONF: conf = optarg; break;
		case OPT_GRID: grid = 1; break;
		case OPT_WELD: welding = 1; break;
		default: fct_bad_option(optstring, argv);
		}
	}
	int nin = argc > optind ? argc - optind : 1, nstd = 0;
	for (int i = optind; i < argc; i++)
		nstd += fct_path_is_std(argv[i]);
	if (nstd > 1)
		fct_usage_error("standard input given %d times", nstd);
	const char *in = optind < argc ? argv[optind] : NULL;
	if (conf && (fct_path_is_std(in) || nstd))
		fct_usage_error("--conf: the scan is found by its file name: give it, not standard input");

	struct fct_err err;
	struct fct_mesh m;
	enum fct_format infmt;
	double t0 = fct_now();
	if (fct_mesh_read_file(&m, in, &infmt, &err))
		fct_die_err(&err);
	if (grid || conf)
		range_scan(&m, in, grid, conf);
	if (nin > 1)
		for (size_t i = 0; i < m.nelems; i++)
			fct_warn("%s: element %s dropped (several inputs are joined)", in, m.elems[i].name);
	while (nin > 1 && m.nelems)
		fct_mesh_remove_elem(&m, m.elems[0].name);
	for (int i = optind + 1; i < argc; i++) {
		struct fct_mesh next;
		enum fct_format f;
		if (fct_mesh_read_file(&next, argv[i], &f, &err)) {
			fct_mesh_free(&m);
			fct_die_err(&err);
		}
		if (grid || conf)
			range_scan(&next, argv[i], grid, conf);
		join(&m, &next, fct_path_is_std(argv[i]) ? "<stdin>" : argv[i]);
	}
	if (welding)
		weld(&m);
	double t1 = fct_now();
	if (fmt == -1)
		fmt = fct_format_for_path(out, 0);
	else if (out && strcmp(out, "-") && fct_path_has_suffix(out, ".obj") && fmt != FCT_FORMAT_OBJ)
		fct_usage_error("-o %s: the name says OBJ but the format asked for is PLY", out);
	int rc = fct_mesh_write_file_as(&m, out, (enum fct_format)fmt, &err);
	if (rc) {
		fct_mesh_free(&m);
		if (err.msg[0])
			fct_die_err(&err);
		return 1;
	}
	fct_report("input", "%s", fct_format_name(infmt));
	fct_report("inputs", "%d", nin);
	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("read_s", "%.3f", t1 - t0);
	fct_report("write_s", "%.3f", fct_now() - t1);
	fct_mesh_free(&m);
	return 0;
}
