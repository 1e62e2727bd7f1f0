/* gen_grid - a bench input: an N x N vertex height-field grid with
 * 2(N-1)^2 triangles, written as binary PLY to stdout.
 *   gen_grid [N]     (default 1001: 1,002,001 vertices, 2,000,000 faces) */
#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "io/meshio.h"

int main(int argc, char **argv)
{
	fct_cli_init("gen_grid");
	long n = argc > 1 ? fct_opt_long("N", argv[1], 2, 20000) : 1001;
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	for (long y = 0; y < n; y++)
		for (long x = 0; x < n; x++) {
			/* a gently curved surface with 7-digit coordinates, like a scan */
			double u = (double)x / (double)(n - 1), v = (double)y / (double)(n - 1);
			if (fct_mesh_add_vertex(&m, u * 4.0 - 2.0, v * 3.0 - 1.5, 2.0 + 0.1 * u * u - 0.05 * v, &err) < 0)
				fct_die_err(&err);
		}
	for (long y = 0; y + 1 < n; y++)
		for (long x = 0; x + 1 < n; x++) {
			uint32_t a = (uint32_t)(y * n + x), b = a + 1, c = a + (uint32_t)n, d = c + 1;
			uint32_t t0[3] = {a, b, d}, t1[3] = {a, d, c};
			if (fct_mesh_add_face(&m, t0, 3, &err) < 0 || fct_mesh_add_face(&m, t1, 3, &err) < 0)
				fct_die_err(&err);
		}
	if (fct_mesh_write_file(&m, NULL, 0, &err))
		fct_die_err(&err);
	fct_mesh_free(&m);
	return 0;
}
