/* scene.c - synthetic scenes, their rendering and sensor noise (see
 * scene.h).
 *
 * The room is the kind of scene Kang, Johnson and Szeliski model (DEC CRL
 * 95/7, sections 1 and 6: indoor scenes "mostly made up of planar
 * surfaces", taken as depth maps and cylindrical panoramas): floor, ceiling
 * and walls, boxes, a ramp, and two curved objects that no plane fits.  The
 * noise models are those of depth sensors: Gaussian, the quadratic growth
 * with depth of structured light (Khoshelham and Elberink, "Accuracy and
 * Resolution of Kinect Depth Data for Indoor Mapping Applications",
 * Sensors 12(2), 2012: sigma_z ~ 1.4e-3 z^2 per metre), the structured
 * noise of ICL-NUIM's simulation (jittered sampling, disparity noise and
 * 1/8-pixel disparity steps), outliers and dropouts. */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"
#include "core/rng.h"

const char *fct_scene_names(void)
{
	return "room plane steps cube sphere";
}

/* Building ------------------------------------------------------------------ */

static int add_vertex(struct fct_scene *s, const double p[3], uint32_t *idx, struct fct_err *err)
{
	long v = fct_mesh_add_vertex(&s->mesh, p[0], p[1], p[2], err);
	if (v < 0)
		return -1;
	*idx = (uint32_t)v;
	return 0;
}

static int add_face(struct fct_scene *s, const uint32_t *v, size_t k, int surf, struct fct_err *err)
{
	long f = fct_mesh_add_face(&s->mesh, v, k, err);
	if (f < 0 || fct_grow((void **)&s->face_surface, &s->face_cap, (size_t)f + 1,
	                      sizeof *s->face_surface, err))
		return -1;
	s->face_surface[f] = surf;
	return 0;
}

static int new_surface(struct fct_scene *s, enum fct_surface_kind kind, const char *name,
                       struct fct_err *err)
{
	if (fct_grow((void **)&s->surf, &s->surf_cap, s->nsurf + 1, sizeof *s->surf, err))
		return -1;
	struct fct_scene_surface *su = &s->surf[s->nsurf];
	memset(su, 0, sizeof *su);
	su->kind = kind;
	snprintf(su->name, sizeof su->name, "%s", name);
	su->patch = -1;
	su->cell = 0.25;
	/* Distinct base colours: hues a golden angle apart, alternating
	 * saturation and value so neighbours in the list differ twice over. */
	size_t k = s->nsurf;
	double hue = fmod(0.08 + 0.6180339887498949 * (double)k, 1.0) * 6;
	double sat = k % 2 ? 0.45 : 0.7, val = (k / 2) % 2 ? 0.78 : 0.95;
	int sector = (int)hue;
	double f = hue - sector, p = val * (1 - sat), q = val * (1 - sat * f);
	double t = val * (1 - sat * (1 - f)), rgb[3];
	switch (sector) {
	case 0: rgb[0] = val, rgb[1] = t, rgb[2] = p; break;
	case 1: rgb[0] = q, rgb[1] = val, rgb[2] = p; break;
	case 2: rgb[0] = p, rgb[1] = val, rgb[2] = t; break;
	case 3: rgb[0] = p, rgb[1] = q, rgb[2] = val; break;
	case 4: rgb[0] = t, rgb[1] = p, rgb[2] = val; break;
	default: rgb[0] = val, rgb[1] = p, rgb[2] = q; break;
	}
	for (int c = 0; c < 3; c++)
		su->rgb[c] = (uint8_t)floor(255 * rgb[c] + 0.5);
	return (int)s->nsurf++;
}

static void normalize(double v[3])
{
	double r = sqrt(fct_v3_dot(v, v));
	v[0] /= r, v[1] /= r, v[2] /= r;
}

/* A planar surface over the polygon of vertices v[0..k) (already added),
 * wound counter-clockwise seen from the free side: its plane from Newell's
 * normal and the centroid, its texture frame horizontal where it can be. */
static int plane_face(struct fct_scene *s, const char *name, const uint32_t *v, size_t k,
                      struct fct_err *err)
{
	int id = new_surface(s, FCT_SURF_PLANE, name, err);
	if (id < 0)
		return -1;
	struct fct_scene_surface *su = &s->surf[id];
	double n[3] = {0, 0, 0}, c[3] = {0, 0, 0};
	for (size_t i = 0; i < k; i++)
		fct_v3_add(c, c, s->mesh.xyz + 3 * (size_t)v[i]);
	for (int j = 0; j < 3; j++)
		c[j] /= (double)k;
	/* Newell's sums about the centroid: a coordinate all corners share
	 * is 0 there, so horizontal and axis-aligned faces get exact normals. */
	for (size_t i = 0; i < k; i++) {
		double a[3], b[3];
		fct_v3_sub(a, s->mesh.xyz + 3 * (size_t)v[i], c);
		fct_v3_sub(b, s->mesh.xyz + 3 * (size_t)v[(i + 1) % k], c);
		n[0] += (a[1] - b[1]) * (a[2] + b[2]);
		n[1] += (a[2] - b[2]) * (a[0] + b[0]);
		n[2] += (a[0] - b[0]) * (a[1] + b[1]);
	}
	normalize(n);
	memcpy(su->n, n, sizeof n);
	su->d = -fct_v3_dot(n, c) + 0.0;
	su->patch = (int)s->nplanes++;
	/* e1 horizontal for walls, along x for floors; e2 = n x e1 (up on walls). */
	double e1[3];
	if (fabs(n[2]) < 0.9) {
		double z[3] = {0, 0, 1};
		fct_v3_cross(e1, z, n);
	} else {
		double x[3] = {1, 0, 0};
		fct_v3_axpy(e1, x, -n[0], n);
	}
	normalize(e1);
	memcpy(su->e1, e1, sizeof e1);
	fct_v3_cross(su->e2, n, e1);
	memcpy(su->o, s->mesh.xyz + 3 * (size_t)v[0], sizeof su->o);
	return add_face(s, v, k, id, err);
}

/* The faces of a box: corner i has x from bit 0, y from bit 1, z from bit
 * 2 (0 low, 1 high); each face wound outward. */
static const uint32_t box_quads[6][4] = {
	{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}
};
static const char *const box_side[6] = {"bottom", "top", "-y", "+y", "-x", "+x"};

/* A box of half sizes hx, hy about (cx, cy), turned by yaw radians about
 * the vertical, from z0 to z1.  inward: faces wound and facing inwards (a
 * room).  Without a bottom, it stands on the floor. */
static int add_box(struct fct_scene *s, const char *name, double cx, double cy, double hx,
                   double hy, double yaw, double z0, double z1, int inward, int bottom,
                   struct fct_err *err)
{
	uint32_t corner[8];
	double cs = cos(yaw), sn = sin(yaw);
	if (yaw == 0)
		cs = 1, sn = 0;
	for (int i = 0; i < 8; i++) {
		double lx = i & 1 ? hx : -hx, ly = i & 2 ? hy : -hy;
		double p[3] = {cx + cs * lx - sn * ly, cy + sn * lx + cs * ly, i & 4 ? z1 : z0};
		if (add_vertex(s, p, &corner[i], err))
			return -1;
	}
	for (int f = 0; f < 6; f++) {
		if (f == 0 && !bottom)
			continue;
		uint32_t q[4];
		for (int j = 0; j < 4; j++)
			q[j] = corner[box_quads[f][inward ? 3 - j : j]];
		char label[24];
		if (inward)
			snprintf(label, sizeof label, "%s", f == 0 ? "floor" : f == 1 ? "ceiling" :
			         f == 2 ? "wall -y" : f == 3 ? "wall +y" : f == 4 ? "wall -x" : "wall +x");
		else
			snprintf(label, sizeof label, "%s %s", name, box_side[f]);
		if (plane_face(s, label, q, 4, err))
			return -1;
	}
	return 0;
}

/* A square of side 2a centred at c in the plane through c with normal n
 * (unit), facing n. */
static int add_square(struct fct_scene *s, const char *name, const double c[3], const double n[3],
                      double a, struct fct_err *err)
{
	double e1[3], e2[3], z[3] = {0, 0, 1}, x[3] = {1, 0, 0};
	if (fabs(n[2]) < 0.9)
		fct_v3_cross(e1, z, n);
	else
		fct_v3_axpy(e1, x, -n[0], n);
	normalize(e1);
	fct_v3_cross(e2, n, e1);
	uint32_t v[4];
	static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
	for (int i = 0; i < 4; i++) {
		double p[3];
		for (int k = 0; k < 3; k++)
			p[k] = c[k] + a * (sx[i] * e1[k] + sy[i] * e2[k]);
		if (add_vertex(s, p, &v[i], err))
			return -1;
	}
	return plane_face(s, name, v, 4, err);
}

/* A rectangle from its four corners, counter-clockwise seen from its front. */
static int add_rect(struct fct_scene *s, const char *name, const double p[4][3], struct fct_err *err)
{
	uint32_t v[4];
	for (int i = 0; i < 4; i++)
		if (add_vertex(s, p[i], &v[i], err))
			return -1;
	return plane_face(s, name, v, 4, err);
}

/* A wedge leaning on the wall y = wall: its slope rises from the floor at
 * y = y0 to height h on the wall, between x0 and x1; the slope and the two
 * triangular ends are seen, the back and the bottom lie on wall and floor. */
static int add_ramp(struct fct_scene *s, double x0, double x1, double y0, double wall, double h,
                    struct fct_err *err)
{
	double pts[6][3] = {
		{x0, y0, 0}, {x1, y0, 0}, {x1, wall, h}, {x0, wall, h}, {x0, wall, 0}, {x1, wall, 0}
	};
	uint32_t v[6];
	for (int i = 0; i < 6; i++)
		if (add_vertex(s, pts[i], &v[i], err))
			return -1;
	uint32_t slope[4] = {v[0], v[1], v[2], v[3]};
	uint32_t left[3] = {v[0], v[3], v[4]}, right[3] = {v[1], v[5], v[2]};
	if (plane_face(s, "ramp slope", slope, 4, err) || plane_face(s, "ramp -x", left, 3, err) ||
	    plane_face(s, "ramp +x", right, 3, err))
		return -1;
	return 0;
}

/* A latitude-longitude sphere: nlon sectors, nlat bands, poles on the z
 * axis through c; triangles wound outward. */
static int add_sphere(struct fct_scene *s, const char *name, const double c[3], double r,
                      int nlon, int nlat, struct fct_err *err)
{
	int id = new_surface(s, FCT_SURF_SPHERE, name, err);
	if (id < 0)
		return -1;
	memcpy(s->surf[id].c, c, sizeof s->surf[id].c);
	s->surf[id].r = r;
	uint32_t north, south, first = 0;
	double pn[3] = {c[0], c[1], c[2] + r}, ps[3] = {c[0], c[1], c[2] - r};
	if (add_vertex(s, pn, &north, err))
		return -1;
	for (int i = 1; i < nlat; i++) {
		double th = M_PI * i / nlat;
		for (int j = 0; j < nlon; j++) {
			double ph = 2 * M_PI * j / nlon;
			double p[3] = {c[0] + r * sin(th) * cos(ph), c[1] + r * sin(th) * sin(ph),
			               c[2] + r * cos(th)};
			uint32_t v;
			if (add_vertex(s, p, &v, err))
				return -1;
			if (i == 1 && j == 0)
				first = v;
		}
	}
	if (add_vertex(s, ps, &south, err))
		return -1;
#define RING(i, j) (first + (uint32_t)(((i) - 1) * nlon + ((j) % nlon)))
	for (int j = 0; j < nlon; j++) {
		uint32_t t[3] = {north, RING(1, j), RING(1, j + 1)};
		if (add_face(s, t, 3, id, err))
			return -1;
	}
	for (int i = 1; i + 1 < nlat; i++)
		for (int j = 0; j < nlon; j++) {
			uint32_t a = RING(i, j), b = RING(i + 1, j), cc = RING(i + 1, j + 1), d = RING(i, j + 1);
			uint32_t t1[3] = {a, b, cc}, t2[3] = {a, cc, d};
			if (add_face(s, t1, 3, id, err) || add_face(s, t2, 3, id, err))
				return -1;
		}
	for (int j = 0; j < nlon; j++) {
		uint32_t t[3] = {RING(nlat - 1, j), south, RING(nlat - 1, j + 1)};
		if (add_face(s, t, 3, id, err))
			return -1;
	}
#undef RING
	return 0;
}

/* A vertical cylinder of radius r from the floor point c up to height h,
 * nseg sectors: its side in triangles (curved), its top a planar polygon. */
static int add_cylinder(struct fct_scene *s, const char *name, const double c[3], double r, double h,
                        int nseg, struct fct_err *err)
{
	int id = new_surface(s, FCT_SURF_CYLINDER, name, err);
	if (id < 0)
		return -1;
	struct fct_scene_surface *su = &s->surf[id];
	memcpy(su->c, c, sizeof su->c);
	su->r = r;
	su->h = h;
	su->cell = 0.2;
	uint32_t *ring = malloc(sizeof *ring * 2 * (size_t)nseg);
	if (!ring)
		return fct_fail(err, "scene: out of memory");
	int rc = -1;
	for (int j = 0; j < nseg; j++) {
		double ph = 2 * M_PI * j / nseg;
		double pb[3] = {c[0] + r * cos(ph), c[1] + r * sin(ph), c[2]};
		double pt[3] = {pb[0], pb[1], c[2] + h};
		if (add_vertex(s, pb, &ring[j], err) || add_vertex(s, pt, &ring[nseg + j], err))
			goto out;
	}
	for (int j = 0; j < nseg; j++) {
		uint32_t b0 = ring[j], b1 = ring[(j + 1) % nseg], t0 = ring[nseg + j];
		uint32_t t1 = ring[nseg + (j + 1) % nseg];
		uint32_t f1[3] = {b0, b1, t1}, f2[3] = {b0, t1, t0};
		if (add_face(s, f1, 3, id, err) || add_face(s, f2, 3, id, err))
			goto out;
	}
	char label[24];
	snprintf(label, sizeof label, "%s top", name);
	rc = plane_face(s, label, ring + nseg, (size_t)nseg, err);
out:
	free(ring);
	return rc;
}

/* The room: 6 x 4 x 2.8 m, x in [-3, 3], y in [-2, 2], z in [0, 2.8]. */
static int build_room(struct fct_scene *s, struct fct_err *err)
{
	double sphere_c[3] = {0.95, 0.85, 0.35}, cyl_c[3] = {2.2, 1.25, 0};
	if (add_box(s, "room", 0, 0, 3, 2, 0, 0, 2.8, 1, 1, err) ||
	    add_box(s, "box1", 1.9, -1.2, 0.45, 0.35, 0, 0, 0.7, 0, 0, err) ||
	    add_box(s, "box2", -2.25, 1.3, 0.35, 0.4, 0, 0, 0.45, 0, 0, err) ||
	    add_box(s, "box3", -0.95, -0.95, 0.5, 0.3, M_PI / 6, 0, 0.9, 0, 0, err) ||
	    add_ramp(s, -0.9, 0.3, 1.3, 2, 1.0, err) ||
	    add_sphere(s, "sphere", sphere_c, 0.35, 64, 32, err) ||
	    add_cylinder(s, "cylinder", cyl_c, 0.25, 1.0, 96, err))
		return -1;
	s->orbit = 0;
	double pano[3] = {0, 0, 1.4};
	memcpy(s->pano, pano, sizeof pano);
	return 0;
}

/* Small scenes: the camera at eye looks at target, along +x. */
static void small_view(struct fct_scene *s, double ex, double ey, double ez, double tx, double ty,
                       double tz)
{
	s->orbit = 1;
	s->eye[0] = ex, s->eye[1] = ey, s->eye[2] = ez;
	s->target[0] = tx, s->target[1] = ty, s->target[2] = tz;
	memcpy(s->pano, s->eye, sizeof s->pano);
}

static int build_small(struct fct_scene *s, const char *name, struct fct_err *err)
{
	if (!strcmp(name, "plane")) {
		/* One plane 2.5 m ahead, turned 35 degrees about the vertical and
		 * tilted 20 degrees back: no axis lies in it. */
		double n[3] = {-cos(0.35) * cos(0.61), -cos(0.35) * sin(0.61), sin(0.35)};
		double c[3] = {2.5, 0, 1.5};
		small_view(s, 0, 0, 1.5, 2.5, 0, 1.5);
		return add_square(s, "plane", c, n, 30, err);
	}
	if (!strcmp(name, "steps")) {
		/* A wall 3.5 m ahead and, 1 m before it, a panel covering the
		 * left half of the view (y > 0): a depth step along the image's
		 * middle column. */
		double wall[4][3] = {{3.5, 20, -20}, {3.5, -20, -20}, {3.5, -20, 20}, {3.5, 20, 20}};
		double panel[4][3] = {{2.5, 20, -20}, {2.5, 0, -20}, {2.5, 0, 20}, {2.5, 20, 20}};
		small_view(s, 0, 0, 1.5, 2.5, 0, 1.5);
		return add_rect(s, "wall", wall, err) || add_rect(s, "panel", panel, err) ? -1 : 0;
	}
	if (!strcmp(name, "cube")) {
		/* A 1 m cube turned 30 degrees on a floor, seen from above at an
		 * angle: top and two sides, with creases between them. */
		double up[3] = {0, 0, 1}, c[3] = {3, 0, 0};
		small_view(s, 1.2, 0, 2, 3, 0, 0.4);
		return add_square(s, "floor", c, up, 30, err) ||
		       add_box(s, "cube", 3, 0, 0.5, 0.5, M_PI / 6, 0, 1, 0, 0, err) ? -1 : 0;
	}
	if (!strcmp(name, "sphere")) {
		/* A sphere of radius 0.6, 2.2 m ahead, before a wall at 4 m. */
		double wn[3] = {-1, 0, 0}, wc[3] = {4, 0, 1.5}, c[3] = {2.2, 0, 1.5};
		small_view(s, 0, 0, 1.5, 2.2, 0, 1.5);
		return add_square(s, "wall", wc, wn, 30, err) ||
		       add_sphere(s, "sphere", c, 0.6, 128, 64, err) ? -1 : 0;
	}
	return fct_fail(err, "scene: unknown scene \"%s\" (known: %s)", name, fct_scene_names());
}

/* The patch property and the plane element. */
static int finish_mesh(struct fct_scene *s, struct fct_err *err)
{
	struct fct_mesh *m = &s->mesh;
	m->xyz_type = FCT_FLOAT64;
	m->has_faces = 1;
	struct fct_prop *patch = fct_elem_add_scalar(&m->face, "patch", FCT_INT32, err);
	if (!patch)
		return -1;
	size_t np = s->nplanes;
	int32_t *count = calloc(np ? np : 1, sizeof *count);
	if (!count)
		return fct_fail(err, "scene: out of memory");
	for (size_t f = 0; f < m->nf; f++) {
		int p = s->surf[s->face_surface[f]].patch;
		fct_prop_set(patch, f, p);
		if (p >= 0)
			count[p]++;
	}
	struct fct_elem *e = fct_mesh_add_elem(m, "plane", np, err);
	static const char *const names[6] = {"nx", "ny", "nz", "d", "count", "rms"};
	for (int k = 0; e && k < 6; k++)
		if (!fct_elem_add_scalar(e, names[k], k == 4 ? FCT_INT32 : FCT_FLOAT64, err))
			e = NULL;
	if (!e) {
		free(count);
		return -1;
	}
	struct fct_prop *col[6];
	for (int k = 0; k < 6; k++)
		col[k] = fct_elem_find(e, names[k]);
	for (size_t i = 0; i < s->nsurf; i++) {
		const struct fct_scene_surface *su = &s->surf[i];
		if (su->patch < 0)
			continue;
		size_t p = (size_t)su->patch;
		for (int k = 0; k < 3; k++)
			fct_prop_set(col[k], p, su->n[k] + 0.0);
		fct_prop_set(col[3], p, su->d);
		fct_prop_set(col[4], p, count[p]);
		fct_prop_set(col[5], p, 0);
	}
	free(count);
	return 0;
}

int fct_scene_build(struct fct_scene *s, const char *name, struct fct_err *err)
{
	memset(s, 0, sizeof *s);
	fct_mesh_init(&s->mesh);
	snprintf(s->name, sizeof s->name, "%s", name);
	double light[3] = {0.35, 0.5, 0.8};
	normalize(light);
	memcpy(s->light, light, sizeof light);
	int rc = !strcmp(name, "room") ? build_room(s, err) : build_small(s, name, err);
	if (rc == 0)
		rc = finish_mesh(s, err);
	if (rc == 0)
		rc = fct_bvh_build_mesh(&s->bvh, &s->mesh, err);
	if (rc)
		fct_scene_free(s);
	return rc;
}

void fct_scene_free(struct fct_scene *s)
{
	if (!s)
		return;
	fct_mesh_free(&s->mesh);
	fct_bvh_free(&s->bvh);
	free(s->face_surface);
	free(s->surf);
	memset(s, 0, sizeof *s);
}

/* Views --------------------------------------------------------------------- */

/* The pose of a camera at c looking along unit f, turned by roll radians
 * about f: x right (horizontal before the roll), y down, z = f. */
static void look_pose(const double c[3], const double f[3], double roll, double pose[12])
{
	double right[3], down[3], z[3] = {0, 0, 1};
	fct_v3_cross(right, f, z);
	normalize(right);
	fct_v3_cross(down, f, right);
	double cr = cos(roll), sr = sin(roll);
	double x[3], y[3];
	for (int k = 0; k < 3; k++) {
		x[k] = cr * right[k] + sr * down[k];
		y[k] = -sr * right[k] + cr * down[k];
	}
	for (int k = 0; k < 3; k++) {
		pose[4 * k] = x[k] + 0.0;
		pose[4 * k + 1] = y[k] + 0.0;
		pose[4 * k + 2] = f[k] + 0.0;
		pose[4 * k + 3] = c[k] + 0.0;
	}
}

void fct_scene_view_pose(const struct fct_scene *s, int i, int n, double pose[12])
{
	if (s->orbit) {
		/* Orbit the target about the vertical through it. */
		double a = (i - 0.5 * (n - 1)) * (8 * M_PI / 180);
		double v[3], c[3], f[3];
		fct_v3_sub(v, s->eye, s->target);
		c[0] = s->target[0] + cos(a) * v[0] - sin(a) * v[1];
		c[1] = s->target[1] + sin(a) * v[0] + cos(a) * v[1];
		c[2] = s->eye[2];
		if (i * 2 == n - 1)
			memcpy(c, s->eye, sizeof c);
		fct_v3_sub(f, s->target, c);
		normalize(f);
		look_pose(c, f, 0, pose);
		return;
	}
	/* Room: headings spread evenly from one looking at the +y wall's
	 * middle left; each camera backs away from the room's middle towards
	 * the wall behind it, 1.6 m up, looking 22 degrees down (view 0; the
	 * others vary the tilt and roll a little, like a hand-held camera). */
	double psi = 2.55 + 2 * M_PI * i / n;
	double pitch = -(22 + (i ? 6 * sin(1.7 * i) : 0)) * M_PI / 180;
	double roll = (i ? 4 * sin(2.9 * i) : 0) * M_PI / 180;
	double bx = -cos(psi), by = -sin(psi);
	double dist = fmin(fabs(bx) > 0 ? 3 / fabs(bx) : INFINITY, fabs(by) > 0 ? 2 / fabs(by) : INFINITY);
	double c[3] = {0.85 * dist * bx, 0.85 * dist * by, 1.6};
	double f[3] = {cos(pitch) * cos(psi), cos(pitch) * sin(psi), sin(pitch)};
	look_pose(c, f, roll, pose);
}

void fct_scene_panorama_pose(const struct fct_scene *s, double pose[12])
{
	/* Camera x = -y, y = -z (down), z = +x: theta = 0 along +x and theta
	 * growing clockwise seen from above, to the right as in an image. */
	static const double r[9] = {0, 0, 1, -1, 0, 0, 0, -1, 0};
	for (int k = 0; k < 3; k++) {
		for (int j = 0; j < 3; j++)
			pose[4 * k + j] = r[3 * k + j];
		pose[4 * k + 3] = s->pano[k];
	}
}

/* Rendering ----------------------------------------------------------------- */

/* A value in [0, 1) for lattice point (i, j) of surface k (a 64-bit mix
 * of the three, SplitMix64's finaliser). */
static double lattice(long long i, long long j, size_t k)
{
	uint64_t x = (uint64_t)i * 0x9E3779B97F4A7C15u ^ (uint64_t)j * 0xC2B2AE3D27D4EB4Fu ^
	             (uint64_t)k * 0x165667B19E3779F9u;
	x ^= x >> 30;
	x *= 0xBF58476D1CE4E5B9u;
	x ^= x >> 27;
	x *= 0x94D049BB133111EBu;
	x ^= x >> 31;
	return (double)(x >> 11) / 9007199254740992.0;
}

/* Value noise at (x, y) metres on surface k: bilinear between lattice
 * values cell metres apart. */
static double value_noise(double x, double y, double cell, size_t k)
{
	double fx = floor(x / cell), fy = floor(y / cell), tx = x / cell - fx, ty = y / cell - fy;
	long long i = (long long)fx, j = (long long)fy;
	double a = lattice(i, j, k), b = lattice(i + 1, j, k), c = lattice(i, j + 1, k);
	double d = lattice(i + 1, j + 1, k);
	return (a + tx * (b - a)) * (1 - ty) + (c + tx * (d - c)) * ty;
}

void fct_scene_color(const struct fct_scene *s, size_t f, const double p[3], uint8_t rgb[3])
{
	const struct fct_scene_surface *su = &s->surf[s->face_surface[f]];
	double q[3], n[3];
	long long a, b;
	if (su->kind == FCT_SURF_PLANE) {
		fct_v3_sub(q, p, su->o);
		a = (long long)floor(fct_v3_dot(q, su->e1) / su->cell);
		b = (long long)floor(fct_v3_dot(q, su->e2) / su->cell);
		memcpy(n, su->n, sizeof n);
	} else {
		fct_v3_sub(q, p, su->c);
		double phi = atan2(q[1], q[0]) + M_PI;   /* [0, 2 pi] */
		a = (long long)floor(phi / (2 * M_PI) * 16);
		if (su->kind == FCT_SURF_SPHERE) {
			double z = q[2] / su->r;
			b = (long long)floor(acos(z < -1 ? -1 : z > 1 ? 1 : z) / M_PI * 8);
			memcpy(n, q, sizeof n);
		} else {
			b = (long long)floor(q[2] / su->cell);
			n[0] = q[0], n[1] = q[1], n[2] = 0;
		}
		double len = sqrt(fct_v3_dot(n, n));
		if (len > 0)
			n[0] /= len, n[1] /= len, n[2] /= len;
	}
	double tone = (a + b) % 2 ? 0.6 : 1.0;
	if (s->grain) {
		/* The surface's own metric coordinates: in-plane, or arc length
		 * and height (cylinder), or arc lengths (sphere). */
		double x, y;
		if (su->kind == FCT_SURF_PLANE) {
			x = fct_v3_dot(q, su->e1), y = fct_v3_dot(q, su->e2);
		} else {
			x = su->r * atan2(q[1], q[0]);
			y = su->kind == FCT_SURF_SPHERE ? su->r * atan2(q[2], hypot(q[0], q[1])) : q[2];
		}
		size_t k = (size_t)s->face_surface[f];
		double g = (2 * value_noise(x, y, 0.04, k) + value_noise(x, y, 0.02, k + 1000)) / 3;
		tone *= 0.6 + 0.4 * g;
	}
	double lit = fct_v3_dot(n, s->light);
	double shade = 0.5 + 0.5 * (lit > 0 ? lit : 0);
	for (int k = 0; k < 3; k++) {
		double v = floor(su->rgb[k] * tone * shade + 0.5);
		rgb[k] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
	}
}

void fct_render_free(struct fct_render *r)
{
	if (!r)
		return;
	free(r->depth);
	free(r->face);
	free(r->cosine);
	free(r->rgb);
	memset(r, 0, sizeof *r);
}

/* The camera-frame direction ray turned into the world by pose. */
static void world_direction(const double pose[12], const double ray[3], double dir[3])
{
	for (int k = 0; k < 3; k++)
		dir[k] = pose[4 * k] * ray[0] + pose[4 * k + 1] * ray[1] + pose[4 * k + 2] * ray[2];
}

int fct_scene_render(const struct fct_scene *s, const struct fct_camera *cam,
                     const double pose[12], struct fct_render *out, struct fct_err *err)
{
	memset(out, 0, sizeof *out);
	if (cam->width < 1 || cam->height < 1)
		return fct_fail(err, "render: the camera has no image size");
	size_t w = (size_t)cam->width, h = (size_t)cam->height, n;
	if (fct_mul_size(w, h, &n) || n > ((size_t)1 << 31))
		return fct_fail(err, "render: %zu x %zu pixels: too many", w, h);
	out->width = cam->width;
	out->height = cam->height;
	out->depth = fct_alloc_array(n, sizeof *out->depth, err);
	out->face = fct_alloc_array(n, sizeof *out->face, err);
	out->cosine = fct_alloc_array(n, sizeof *out->cosine, err);
	out->rgb = fct_alloc_array(n, 3, err);
	if (!out->depth || !out->face || !out->cosine || !out->rgb) {
		fct_render_free(out);
		return fct_fail(err, "render: out of memory for %zu pixels", n);
	}
	const double org[3] = {pose[3], pose[7], pose[11]};
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4)
#endif
	for (size_t y = 0; y < h; y++) {
		for (size_t x = 0; x < w; x++) {
			size_t i = y * w + x;
			double ray[3], dir[3];
			fct_camera_ray(cam, (double)x, (double)y, ray);
			world_direction(pose, ray, dir);
			struct fct_bvh_ray_hit hit;
			if (!fct_bvh_raycast(&s->bvh, org, dir, 0, INFINITY, &hit)) {
				out->depth[i] = 0;
				out->face[i] = -1;
				out->cosine[i] = 0;
				memset(out->rgb + 3 * i, 0, 3);
				continue;
			}
			const struct fct_bvh_tri *t = &s->bvh.tris[hit.tri];
			double e1[3], e2[3], nrm[3], p[3];
			fct_v3_sub(e1, t->b, t->a);
			fct_v3_sub(e2, t->c, t->a);
			fct_v3_cross(nrm, e1, e2);
			double c = fct_v3_dot(nrm, dir) / sqrt(fct_v3_dot(nrm, nrm) * fct_v3_dot(dir, dir));
			fct_v3_axpy(p, org, hit.t, dir);
			out->depth[i] = hit.t;
			out->face[i] = (int32_t)hit.id;
			out->cosine[i] = fabs(c);
			fct_scene_color(s, hit.id, p, out->rgb + 3 * i);
		}
	}
	return 0;
}

/* Noise --------------------------------------------------------------------- */

/* The generator of one kind of draw for one image. */
static void stream_seed(struct fct_rng *r, uint64_t seed, uint64_t stream, uint64_t kind)
{
	uint64_t st = seed;
	uint64_t a = fct_splitmix64(&st);
	st = a ^ ((stream * 4 + kind + 1) * UINT64_C(0x9e3779b97f4a7c15));
	fct_rng_seed(r, fct_splitmix64(&st));
}

/* The depth the sensor model nz measures for a sampled depth z, with the
 * normal deviate g; 0 when it measures none. */
static double sensor_measure(const struct fct_noise *nz, double z, double g)
{
	double d;
	switch (nz->model) {
	case FCT_NOISE_KINECT:
	case FCT_NOISE_STEREO:
		d = nz->fb / z + nz->sd * g;
		if (nz->model == FCT_NOISE_KINECT && nz->step > 0)
			d = nz->step * floor(d / nz->step + 0.5);
		return d > 0 ? nz->fb / d : 0;
	case FCT_NOISE_TOF:
	case FCT_NOISE_POLY:
		return z + fct_noise_sigma_gaussian(nz, z) * g;
	default:
		return z;
	}
}

void fct_depth_noise(const struct fct_scene_noise *nz, uint64_t seed, uint64_t stream,
                     const double *truth, const double *sampled, const double *cosine, double *out,
                     size_t n, struct fct_scene_noise_stats *stats)
{
	struct fct_scene_noise_stats st;
	memset(&st, 0, sizeof st);
	struct fct_rng rmiss, rout, rnoise;
	stream_seed(&rmiss, seed, stream, 0);
	stream_seed(&rout, seed, stream, 1);
	stream_seed(&rnoise, seed, stream, 2);
	double cos_max = nz->grazing < 90 ? cos(nz->grazing * M_PI / 180) : -1;
	const struct fct_noise *sensor = &nz->sensor;
	int model = sensor->model != FCT_NOISE_UNKNOWN;
	for (size_t i = 0; i < n; i++) {
		double z = truth[i];
		double u_miss = fct_rng_uniform(&rmiss);
		double u_out = fct_rng_uniform(&rout), u_val = fct_rng_uniform(&rout);
		double g = fct_rng_normal(&rnoise);
		if (!(z > 0)) {
			out[i] = 0;
			continue;
		}
		st.valid++;
		double zs = sampled ? sampled[i] : z;
		if (z < nz->near || (nz->far > 0 && z > nz->far)) {
			st.range++;
			out[i] = 0;
		} else if (cosine && cosine[i] < cos_max) {
			st.grazing++;
			out[i] = 0;
		} else if (u_miss < nz->missing) {
			st.missing++;
			out[i] = 0;
		} else if (u_out < nz->outliers) {
			st.outliers++;
			out[i] = z * (0.5 + u_val);
		} else if (!(zs > 0)) {
			st.lost++;
			out[i] = 0;
		} else {
			double v, sd;
			if (model) {
				v = sensor_measure(sensor, zs, g);
				sd = sensor->model == FCT_NOISE_NONE ? 0 : fct_noise_sigma(sensor, z);
			} else {
				double k = nz->kinect_gauss * z * z;
				sd = sqrt(nz->sigma * nz->sigma + k * k);
				v = z + sd * g;
			}
			if (sd > 0) {
				st.noisy++;
				st.sum += v - z;
				st.sum2 += (v - z) * (v - z);
				st.model2 += sd * sd;
			}
			out[i] = v > 0 ? v : 0;
		}
	}
	if (stats)
		*stats = st;
}

int fct_scene_render_jitter(const struct fct_scene *s, const struct fct_camera *cam,
                            const double pose[12], double jitter, uint64_t seed, uint64_t stream,
                            double *depth, struct fct_err *err)
{
	if (cam->width < 1 || cam->height < 1)
		return fct_fail(err, "render: the camera has no image size");
	size_t w = (size_t)cam->width, h = (size_t)cam->height;
	struct fct_rng r;
	stream_seed(&r, seed, stream, 3);
	const double org[3] = {pose[3], pose[7], pose[11]};
	for (size_t y = 0; y < h; y++)
		for (size_t x = 0; x < w; x++) {
			double du = jitter * fct_rng_normal(&r), dv = jitter * fct_rng_normal(&r);
			double ray[3], dir[3];
			fct_camera_ray(cam, (double)x + du, (double)y + dv, ray);
			world_direction(pose, ray, dir);
			struct fct_bvh_ray_hit hit;
			depth[y * w + x] = fct_bvh_raycast(&s->bvh, org, dir, 0, INFINITY, &hit) ? hit.t : 0;
		}
	return 0;
}
