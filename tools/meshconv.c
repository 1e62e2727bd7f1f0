/* meshconv - convert a mesh between PLY encodings and OBJ, keeping every
 * property and element the target format can hold. */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "meshio.h"
#include "path.h"

static const char usage[] =
	"usage: meshconv [-aqv] [-f format] [-o file] [input]\n"
	"Convert a mesh (PLY or OBJ, detected from the content) to binary PLY,\n"
	"keeping every property, element and comment.\n"
	"  -a            write ascii PLY\n"
	"  -f format     ascii, binary_little_endian, binary_big_endian or obj\n"
	"  -o file       output file (default stdout); a name ending in .obj writes OBJ\n"
	"                and, for a textured mesh, a .mtl beside it\n"
	"  -q            quiet\n"
	"  -v            report counts and time on stderr\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("meshconv");
	const char *out = NULL;
	int fmt = -1, c;
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
		default: fct_bad_option(optstring, argv);
		}
	}
	if (argc - optind > 1)
		fct_usage_error("too many operands");
	const char *in = optind < argc ? argv[optind] : NULL;

	struct fct_err err;
	struct fct_mesh m;
	enum fct_format infmt;
	double t0 = fct_now();
	if (fct_mesh_read_file(&m, in, &infmt, &err))
		fct_die_err(&err);
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
	fct_report("vertices", "%zu", m.nv);
	fct_report("faces", "%zu", m.nf);
	fct_report("read_s", "%.3f", t1 - t0);
	fct_report("write_s", "%.3f", fct_now() - t1);
	fct_mesh_free(&m);
	return 0;
}
