/* segmesh.c - a mesh on the pipe segmented into planar patches (see
 * segmesh.h). */
#include "planar/segmesh.h"

#include <stdlib.h>

#include "geom/adj.h"
#include "geom/planes.h"
#include "io/header.h"

int fct_segment_mesh(struct fct_mesh *m, const struct fct_segment_params *p, int tls,
                     struct fct_segment_stats *stats, struct fct_err *err)
{
	if (m->nf == 0)
		return fct_fail(err, "no faces to segment (%s)",
		                m->nv ? "a point cloud: mesh it first, e.g. with dm2mesh --points"
		                      : "an empty mesh");
	struct fct_segment_params sp = *p;
	/* Noise along the rays of the camera the mesh was measured with. */
	struct fct_camera cam;
	int hc = fct_header_camera(m, &cam, err);
	if (hc < 0)
		return -1;
	/* A mesh of no camera may be a triangle soup (every face its own
	 * corners: an STL file converted, an exporter that splits vertices),
	 * where no two faces share an edge and none would merge: the copies of
	 * a position become one vertex.  The faces stay as they are, in their
	 * order (one that now repeats a vertex is a degenerate face, which the
	 * segmentation takes).  A view's mesh is its pixel grid, one vertex a
	 * pixel. */
	size_t welded = 0;
	if (hc == 0) {
		long n = fct_mesh_weld_exact(m, err);
		if (n < 0)
			return -1;
		welded = (size_t)n;
	}
	if (hc > 0 && !tls) {
		double pose[12];
		int hp = fct_header_pose(m, pose, err);
		if (hp < 0)
			return -1;
		sp.use_viewpoint = 1;
		if (hp > 0)
			sp.viewpoint[0] = pose[3], sp.viewpoint[1] = pose[7], sp.viewpoint[2] = pose[11];
	}
	/* The noise of each vertex from the sensor's model (dm2mesh's sigma). */
	double *sigma = NULL;
	const struct fct_prop *prop = fct_elem_find(&m->vertex, "sigma");
	if (prop && prop->count_type == FCT_NONE) {
		if (!(sigma = fct_alloc_array(m->nv ? m->nv : 1, sizeof *sigma, err)))
			return -1;
		for (size_t v = 0; v < m->nv; v++)
			sigma[v] = fct_prop_get(prop, v);
		sp.sigma = sigma;
	}
	int32_t *patch = fct_alloc_array(m->nf, sizeof *patch, err);
	struct fct_plane *planes = NULL;
	size_t np = 0;
	int rc = -1;
	if (patch && !fct_segment(patch, &planes, &np, m, &sp, stats, err) &&
	    !fct_patches_set(m, patch, err) && !fct_planes_set(m, planes, np, err))
		rc = 0;
	if (stats)
		stats->welded = welded;
	free(patch);
	free(planes);
	free(sigma);
	return rc;
}
