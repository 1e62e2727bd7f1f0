/* fuzz_mesh.h - shared body of the mesh-reader fuzz targets: read the bytes,
 * and when they are accepted, check that what was read survives a write and
 * a second read with the same counts (so the writer is fuzzed too; it may
 * only refuse a header line too long for MeshLab), and read
 * its noise comment and estimate its noise (so those are fuzzed too). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/header.h"
#include "io/meshio.h"
#include "io/noise.h"

static void fuzz_mesh_bytes(const uint8_t *data, size_t size)
{
	if (!size)
		return;
	FILE *f = fmemopen((void *)data, size, "rb");
	if (!f)
		return;
	struct fct_mesh m, r;
	struct fct_err err;
	int rc = fct_mesh_read_stream(&m, f, "fuzz", NULL, NULL, &err);
	fclose(f);
	if (rc) {
		if (!err.msg[0] || strchr(err.msg, '\n'))
			abort();  /* every failure must say one line */
		return;
	}
	struct fct_noise nz;
	struct fct_noise_fit fit;
	if ((fct_header_noise(&m, &nz, &err) < 0 || fct_noise_fit(&fit, &m, &err)) &&
	    (!err.msg[0] || strchr(err.msg, '\n')))
		abort();
	/* OBJ cannot say "no vertices": an empty mesh is only checked as PLY. */
	int last = m.nv ? FCT_FORMAT_OBJ : FCT_FORMAT_PLY_BE;
	for (int fmt = FCT_FORMAT_PLY_ASCII; fmt <= last; fmt++) {
		char *buf = NULL;
		size_t n = 0;
		FILE *w = open_memstream(&buf, &n);
		if (fct_mesh_write_stream(&m, w, (enum fct_format)fmt, &err)) {
			/* The one refusal allowed: a header line that cannot be
			 * shortened (a texture path padded past 255 bytes) and that
			 * MeshLab and Open3D would not read, said in one line. */
			if (!strstr(err.msg, "header line") || strchr(err.msg, '\n'))
				abort();
			fclose(w);
			free(buf);
			continue;
		}
		fclose(w);
		FILE *in = fmemopen(buf, n, "rb");
		if (fct_mesh_read_stream(&r, in, "again", NULL, NULL, &err))
			abort();  /* what we write we must read */
		fclose(in);
		if (r.nf != m.nf || r.nv != m.nv)  /* OBJ too: a vertex is its v line */
			abort();
		fct_mesh_free(&r);
		free(buf);
	}
	fct_mesh_free(&m);
}
