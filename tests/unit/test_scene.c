/* test_scene - the synthetic scenes against their analytic truth: planes
 * hold their faces' vertices, faces are wound to their normals, depths equal
 * ray-plane intersections computed here from the plane equations and from
 * the room's dimensions alone, every depth pixel's point lies on the mesh,
 * cameras see planes from their positive side, colours follow the
 * documented checker, rendering is deterministic, and the noise models
 * have the statistics they promise. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/geom.h"
#include "scene/scene.h"

static struct fct_camera pinhole(int w, int h, double f)
{
	struct fct_camera c;
	memset(&c, 0, sizeof c);
	c.kind = FCT_CAMERA_PINHOLE;
	c.width = w, c.height = h;
	c.fx = c.fy = f;
	c.cx = 0.5 * (w - 1), c.cy = 0.5 * (h - 1);
	return c;
}

static struct fct_camera cylinder(int w, int h)
{
	struct fct_camera c;
	memset(&c, 0, sizeof c);
	c.kind = FCT_CAMERA_CYLINDRICAL;
	c.width = w, c.height = h;
	c.f = w / (2 * M_PI);
	c.cy = 0.5 * (h - 1);
	return c;
}

/* The world ray of pixel (x, y). */
static void world_ray(const struct fct_camera *cam, const double pose[12], int x, int y,
                      double org[3], double dir[3])
{
	double ray[3];
	fct_camera_ray(cam, x, y, ray);
	for (int k = 0; k < 3; k++) {
		dir[k] = pose[4 * k] * ray[0] + pose[4 * k + 1] * ray[1] + pose[4 * k + 2] * ray[2];
		org[k] = pose[4 * k + 3];
	}
}

static const struct fct_prop *prop(const struct fct_elem *e, const char *name)
{
	const struct fct_prop *p = fct_elem_find(e, name);
	if (!p)
		abort();
	return p;
}

/* The mesh: faces on their planes, wound to their normals; the plane
 * element equals the surfaces; counts add up. */
static void check_mesh(const struct fct_scene *s)
{
	const struct fct_mesh *m = &s->mesh;
	const struct fct_prop *patch = prop(&m->face, "patch");
	const struct fct_elem *pl = fct_mesh_find_elem(m, "plane");
	CHECK(pl != NULL);
	if (!pl)
		return;
	CHECK_INT(pl->count, s->nplanes);
	CHECK(m->xyz_type == FCT_FLOAT64);
	const struct fct_prop *nx = prop(pl, "nx"), *ny = prop(pl, "ny"), *nz = prop(pl, "nz");
	const struct fct_prop *d = prop(pl, "d"), *count = prop(pl, "count"), *rms = prop(pl, "rms");
	size_t *faces = calloc(pl->count + 1, sizeof *faces);
	double worst = 0, worst_wind = 0;
	int curved_ok = 1;
	for (size_t f = 0; f < m->nf; f++) {
		int p = (int)fct_prop_get(patch, f);
		const struct fct_scene_surface *su = &s->surf[s->face_surface[f]];
		if (p != su->patch || (p < 0 && su->kind == FCT_SURF_PLANE) ||
		    (p >= 0 && su->kind != FCT_SURF_PLANE)) {
			curved_ok = 0;
			continue;
		}
		if (p < 0)
			continue;
		faces[p]++;
		double n[3] = {fct_prop_get(nx, (size_t)p), fct_prop_get(ny, (size_t)p),
		               fct_prop_get(nz, (size_t)p)};
		double dd = fct_prop_get(d, (size_t)p);
		uint32_t k = fct_face_size(m, f);
		const uint32_t *v = m->fvert + m->fstart[f];
		double newell[3] = {0, 0, 0};
		for (uint32_t i = 0; i < k; i++) {
			const double *a = m->xyz + 3 * (size_t)v[i], *b = m->xyz + 3 * (size_t)v[(i + 1) % k];
			worst = fmax(worst, fabs(fct_v3_dot(n, a) + dd));
			newell[0] += (a[1] - b[1]) * (a[2] + b[2]);
			newell[1] += (a[2] - b[2]) * (a[0] + b[0]);
			newell[2] += (a[0] - b[0]) * (a[1] + b[1]);
		}
		double len = sqrt(fct_v3_dot(newell, newell));
		worst_wind = fmax(worst_wind, 1 - fct_v3_dot(newell, n) / len);
	}
	CHECK(curved_ok);
	CHECK_MSG(worst <= 1e-12, "%s: a vertex is %g off its plane", s->name, worst);
	CHECK_MSG(worst_wind <= 1e-12, "%s: a face is wound against its plane (%g)", s->name, worst_wind);
	for (size_t p = 0; p < pl->count; p++) {
		double n[3] = {fct_prop_get(nx, p), fct_prop_get(ny, p), fct_prop_get(nz, p)};
		CHECK_NEAR(fct_v3_dot(n, n), 1, 1e-15);
		CHECK_INT(fct_prop_get(count, p), faces[p]);
		CHECK(faces[p] > 0);
		CHECK(fct_prop_get(rms, p) == 0);
	}
	free(faces);
}

/* A rendered view against the scene: every hit point lies on the mesh
 * (closest-point distance, another code path than the ray cast); a hit on
 * a plane has the depth of the ray-plane intersection computed here, and the
 * camera on the plane's positive side; colours are fct_scene_color's. */
static void check_view(const struct fct_scene *s, const struct fct_camera *cam,
                       const double pose[12], const struct fct_render *r, size_t *hits)
{
	const struct fct_elem *pl = fct_mesh_find_elem(&s->mesh, "plane");
	const struct fct_prop *nx = prop(pl, "nx"), *ny = prop(pl, "ny"), *nz = prop(pl, "nz");
	const struct fct_prop *d = prop(pl, "d");
	double off_mesh = 0, off_plane = 0;
	int back = 0, color = 0, bad_cos = 0, miss_nonzero = 0;
	for (int y = 0; y < cam->height; y++)
		for (int x = 0; x < cam->width; x++) {
			size_t i = (size_t)y * (size_t)cam->width + (size_t)x;
			if (r->face[i] < 0) {
				miss_nonzero += r->depth[i] != 0 || r->rgb[3 * i] != 0;
				continue;
			}
			++*hits;
			double org[3], dir[3], ray[3], p[3], q[3];
			world_ray(cam, pose, x, y, org, dir);
			/* The point as a user gets it: depth * ray, moved by the pose. */
			fct_camera_ray(cam, x, y, ray);
			for (int k = 0; k < 3; k++)
				q[k] = r->depth[i] * ray[k];
			fct_pose_apply(pose, q, p);
			struct fct_bvh_hit h;
			fct_bvh_closest(&s->bvh, p, INFINITY, &h);
			off_mesh = fmax(off_mesh, sqrt(h.d2) / r->depth[i]);
			bad_cos += !(r->cosine[i] >= 0 && r->cosine[i] <= 1);
			/* The colour is the texture at the ray's point (the point
			 * above differs in the last bits: a cell edge may fall
			 * between them). */
			uint8_t rgb[3];
			double pr[3];
			fct_v3_axpy(pr, org, r->depth[i], dir);
			fct_scene_color(s, (size_t)r->face[i], pr, rgb);
			color += memcmp(rgb, r->rgb + 3 * i, 3) != 0;
			int pt = s->surf[s->face_surface[r->face[i]]].patch;
			if (pt < 0)
				continue;
			double n[3] = {fct_prop_get(nx, (size_t)pt), fct_prop_get(ny, (size_t)pt),
			               fct_prop_get(nz, (size_t)pt)};
			double dd = fct_prop_get(d, (size_t)pt);
			double side = fct_v3_dot(n, org) + dd;
			back += !(side > 0);
			double t = -side / fct_v3_dot(n, dir);
			off_plane = fmax(off_plane, fabs(r->depth[i] - t) / t);
		}
	CHECK_MSG(off_mesh <= 1e-12, "%s: a pixel's point is %g (relative) off the mesh", s->name, off_mesh);
	CHECK_MSG(off_plane <= 1e-12, "%s: a depth is %g (relative) off its ray-plane intersection",
	          s->name, off_plane);
	CHECK_MSG(back == 0, "%s: %d pixels see a plane from its negative side", s->name, back);
	CHECK_MSG(color == 0, "%s: %d colours differ from fct_scene_color", s->name, color);
	CHECK_INT(bad_cos, 0);
	CHECK_INT(miss_nonzero, 0);
}

static void test_scenes(void)
{
	static const char *const names[] = {"room", "plane", "steps", "cube", "sphere"};
	for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
		struct fct_scene s;
		struct fct_err err;
		CHECK(fct_scene_build(&s, names[k], &err) == 0);
		check_mesh(&s);
		struct fct_camera cam = pinhole(160, 120, 131.25);
		size_t hits = 0, pixels = 0;
		for (int i = 0; i < 4; i++) {
			double pose[12];
			fct_scene_view_pose(&s, i, 4, pose);
			CHECK(fct_pose_check(pose, 1e-12, &err) == 0);
			struct fct_render r;
			CHECK(fct_scene_render(&s, &cam, pose, &r, &err) == 0);
			check_view(&s, &cam, pose, &r, &hits);
			pixels += 160 * 120;
			fct_render_free(&r);
		}
		/* Every pinhole pixel sees something in every scene. */
		CHECK_MSG(hits == pixels, "%s: %zu of %zu pixels hit", names[k], hits, pixels);
		struct fct_camera pc = cylinder(256, 64);
		double pose[12];
		fct_scene_panorama_pose(&s, pose);
		struct fct_render r;
		CHECK(fct_scene_render(&s, &pc, pose, &r, &err) == 0);
		hits = 0;
		check_view(&s, &pc, pose, &r, &hits);
		if (!strcmp(names[k], "room"))
			CHECK_INT(hits, 256 * 64);   /* a closed room */
		fct_render_free(&r);
		fct_scene_free(&s);
	}
	struct fct_scene s;
	struct fct_err err;
	CHECK(fct_scene_build(&s, "attic", &err) == -1);
	CHECK_STR(err.msg, "scene: unknown scene \"attic\" (known: room plane steps cube sphere)");
	CHECK(s.mesh.nv == 0 && s.surf == NULL);
	fct_scene_free(&s);
	fct_scene_free(NULL);
}

/* The room's panorama against the room's size alone: from (0, 0, 1.4), the
 * rows by the equator see the walls over every object, at the distance
 * rho = min(3 / |cos theta|, 2 / |sin theta|) from the axis, theta measured
 * from +x clockwise seen from above. */
static void test_room_panorama(void)
{
	struct fct_scene s;
	struct fct_err err;
	CHECK(fct_scene_build(&s, "room", &err) == 0);
	struct fct_camera pc = cylinder(2048, 512);
	double pose[12];
	fct_scene_panorama_pose(&s, pose);
	CHECK_NEAR(pose[3], 0, 0);
	CHECK_NEAR(pose[7], 0, 0);
	CHECK_NEAR(pose[11], 1.4, 0);
	struct fct_render r;
	CHECK(fct_scene_render(&s, &pc, pose, &r, &err) == 0);
	double worst = 0;
	int walls = 0, n = 0;
	for (int y = 150; y < 362; y += 7)
		for (int x = 0; x < 2048; x++) {
			size_t i = (size_t)y * 2048 + (size_t)x;
			double th = 2 * M_PI * x / 2048;
			double c = fabs(cos(th)), sn = fabs(sin(th));
			double rho = fmin(c > 0 ? 3 / c : INFINITY, sn > 0 ? 2 / sn : INFINITY);
			/* Rows going up clear every object; rows going down clear
			 * them (at most 1.1 m high) while they are above 1.1 m at
			 * the wall.  Neither may reach the floor or ceiling. */
			double h = (y - pc.cy) / pc.f;
			if (h > 0 ? rho * h >= 0.3 : -rho * h >= 1.3)
				continue;
			int p = r.face[i] >= 0 ? s.surf[s.face_surface[r.face[i]]].patch : -1;
			walls += p >= 2 && p <= 5;
			worst = fmax(worst, fabs(r.depth[i] - rho) / rho);
			n++;
		}
	CHECK(n > 20000);
	CHECK_INT(walls, n);
	CHECK_MSG(worst <= 1e-13, "panorama depth off the walls by %g (relative)", worst);
	/* The corner directions: atan(2/3) from +x towards -y is the corner
	 * (3, -2), at sqrt(13) from the axis. */
	fct_render_free(&r);
	fct_scene_free(&s);
}

/* Small scenes whose depths are known in closed form. */
static void test_small(void)
{
	struct fct_err err;
	struct fct_scene s;
	struct fct_render r;
	double pose[12];
	struct fct_camera cam = pinhole(641, 481, 525);
	/* steps, view 0 of 1: looking along +x from (0, 0, 1.5); columns left
	 * of the middle see the panel at 2.5, right of it the wall at 3.5, the
	 * middle column (exactly on the panel's edge) the panel. */
	CHECK(fct_scene_build(&s, "steps", &err) == 0);
	fct_scene_view_pose(&s, 0, 1, pose);
	CHECK(fct_scene_render(&s, &cam, pose, &r, &err) == 0);
	int bad = 0;
	for (int y = 0; y < 481; y++)
		for (int x = 0; x < 641; x++) {
			double want = x <= 320 ? 2.5 : 3.5;
			bad += fabs(r.depth[(size_t)y * 641 + (size_t)x] - want) > 1e-15 * want;
		}
	CHECK_INT(bad, 0);
	fct_render_free(&r);
	fct_scene_free(&s);

	/* sphere: the middle pixel sees the sphere's vertex nearest the camera,
	 * 2.2 - 0.6 away; elsewhere on the sphere the mesh lies within its
	 * sagitta inside the true sphere. */
	CHECK(fct_scene_build(&s, "sphere", &err) == 0);
	fct_scene_view_pose(&s, 0, 1, pose);
	CHECK(fct_scene_render(&s, &cam, pose, &r, &err) == 0);
	CHECK_NEAR(r.depth[240 * 641 + 320], 1.6, 1e-15);
	double worst = 0;
	int on_sphere = 0, outside = 0;
	for (int y = 0; y < 481; y++)
		for (int x = 0; x < 641; x++) {
			size_t i = (size_t)y * 641 + (size_t)x;
			if (s.surf[s.face_surface[r.face[i]]].kind != FCT_SURF_SPHERE)
				continue;
			on_sphere++;
			double org[3], dir[3], p[3], q[3];
			world_ray(&cam, pose, x, y, org, dir);
			fct_v3_axpy(p, org, r.depth[i], dir);
			fct_v3_sub(q, p, s.surf[s.face_surface[r.face[i]]].c);
			double dist = 0.6 - sqrt(fct_v3_dot(q, q));
			worst = fmax(worst, dist);
			outside += dist < -1e-12;
		}
	CHECK_INT(outside, 0);
	/* Radius 0.6, 128 sectors by 64 bands of pi / 64: an edge's sagitta
	 * is 0.6 (1 - cos(pi / 128)) = 0.18 mm, a triangle's middle lies at
	 * most as deep as a chord of pi / 32 across a quad's diagonal. */
	double sag = 0.6 * (1 - cos(M_PI / 128));
	CHECK_MSG(worst > sag && worst < 4 * sag, "deepest %g, edge sagitta %g", worst, sag);
	/* The sphere covers a disc of angular radius asin(0.6 / 2.2). */
	double a = asin(0.6 / 2.2), disc = M_PI * pow(525 * tan(a), 2);
	CHECK_MSG(fabs(on_sphere - disc) < 0.02 * disc, "%d pixels on the sphere, about %.0f expected",
	          on_sphere, disc);
	fct_render_free(&r);
	fct_scene_free(&s);

	/* plane: all 641 x 481 pixels hit the one plane. */
	CHECK(fct_scene_build(&s, "plane", &err) == 0);
	CHECK_INT(s.nplanes, 1);
	for (int i = 0; i < 3; i++) {
		fct_scene_view_pose(&s, i, 3, pose);
		CHECK(fct_scene_render(&s, &cam, pose, &r, &err) == 0);
		size_t hits = 0;
		check_view(&s, &cam, pose, &r, &hits);
		CHECK_INT(hits, 641 * 481);
		fct_render_free(&r);
	}
	/* The middle view of an odd count is the scene's own eye. */
	double p1[12], p3[12];
	fct_scene_view_pose(&s, 0, 1, p1);
	fct_scene_view_pose(&s, 1, 3, p3);
	CHECK(!memcmp(p1, p3, sizeof p1));
	CHECK_NEAR(p1[3], 0, 0);
	CHECK_NEAR(p1[11], 1.5, 0);
	fct_scene_free(&s);
}

/* Colours: the floor's checker flips every 0.25 m and is lit by
 * 0.5 + 0.5 light_z; identical renders give identical bytes. */
static void test_color(void)
{
	struct fct_scene s;
	struct fct_err err;
	CHECK(fct_scene_build(&s, "room", &err) == 0);
	const struct fct_scene_surface *fl = &s.surf[s.face_surface[0]];
	CHECK_STR(fl->name, "floor");
	size_t f = 0;
	double shade = 0.5 + 0.5 * s.light[2];
	uint8_t rgb[3], rgb2[3];
	/* the floor's texture origin is its corner (3, -2): (0.1, 0.1) is
	 * cells (-12, 8) along e1 = x, e2 = y: light; 0.25 further, dark */
	double p[3] = {fl->o[0] - 11.5 * 0.25, fl->o[1] + 8.5 * 0.25, 0};
	fct_scene_color(&s, f, p, rgb);
	p[0] += 0.25;
	fct_scene_color(&s, f, p, rgb2);
	for (int k = 0; k < 3; k++) {
		CHECK_INT(rgb[k], (int)floor(fl->rgb[k] * shade + 0.5));
		CHECK_INT(rgb2[k], (int)floor(fl->rgb[k] * 0.6 * shade + 0.5));
	}
	/* Distinct base colours on all 25 planes. */
	int same = 0;
	for (size_t i = 0; i < s.nsurf; i++)
		for (size_t j = 0; j < i; j++)
			same += !memcmp(s.surf[i].rgb, s.surf[j].rgb, 3);
	CHECK_INT(same, 0);
	CHECK_INT(s.nplanes, 25);
	struct fct_camera cam = pinhole(200, 150, 160);
	double pose[12];
	fct_scene_view_pose(&s, 2, 3, pose);
	struct fct_render r1, r2;
	CHECK(fct_scene_render(&s, &cam, pose, &r1, &err) == 0);
	CHECK(fct_scene_render(&s, &cam, pose, &r2, &err) == 0);
	CHECK(!memcmp(r1.depth, r2.depth, sizeof *r1.depth * 200 * 150));
	CHECK(!memcmp(r1.rgb, r2.rgb, 3 * 200 * 150));
	fct_render_free(&r1);
	fct_render_free(&r2);
	struct fct_camera none = pinhole(0, 0, 1);
	CHECK(fct_scene_render(&s, &none, pose, &r1, &err) == -1);
	fct_scene_free(&s);
}

/* Noise statistics on a flat truth of 1e6 pixels at 2 m. */
static void test_noise(void)
{
	size_t n = 1000000;
	double *truth = malloc(sizeof *truth * n), *a = malloc(sizeof *a * n);
	double *b = malloc(sizeof *b * n), *cosine = malloc(sizeof *cosine * n);
	if (!truth || !a || !b || !cosine)
		abort();
	for (size_t i = 0; i < n; i++) {
		truth[i] = i % 100 == 0 ? 0 : 2;   /* 1% without data */
		cosine[i] = (double)(i % 1000) / 1000;
	}
	struct fct_scene_noise nz = {0.01, 0, 0, 0, 90, 0, 0, {0}};
	struct fct_scene_noise_stats st;
	fct_depth_noise(&nz, 1, 0, truth, NULL, cosine, a, n, &st);
	CHECK_INT(st.valid, 990000);
	CHECK_INT(st.noisy, 990000);
	double s1 = 0, s2 = 0;
	int zero_kept = 1;
	for (size_t i = 0; i < n; i++) {
		if (truth[i] == 0) {
			zero_kept &= a[i] == 0;
			continue;
		}
		s1 += a[i] - 2;
		s2 += (a[i] - 2) * (a[i] - 2);
	}
	CHECK(zero_kept);
	double mean = s1 / 990000, sd = sqrt(s2 / 990000 - mean * mean);
	CHECK_NEAR(mean, 0, 1e-4);        /* sd of the mean 1e-5 */
	CHECK_NEAR(sd, 0.01, 0.0002);     /* 2 percent; sd of the estimate 0.07 percent */
	CHECK_NEAR(sqrt(st.sum2 / (double)st.noisy), sd, 1e-6);
	/* Same seed, same stream: same bytes; another seed or stream: others. */
	fct_depth_noise(&nz, 1, 0, truth, NULL, cosine, b, n, NULL);
	CHECK(!memcmp(a, b, sizeof *a * n));
	fct_depth_noise(&nz, 2, 0, truth, NULL, cosine, b, n, NULL);
	CHECK(memcmp(a, b, sizeof *a * n) != 0);
	fct_depth_noise(&nz, 1, 1, truth, NULL, cosine, b, n, NULL);
	CHECK(memcmp(a, b, sizeof *a * n) != 0);

	/* Kinect: sigma = a z^2 = 0.002 * 4 = 0.008; with Gaussian 0.006 too,
	 * sqrt(0.006^2 + 0.008^2) = 0.01. */
	struct fct_scene_noise kn = {0, 0.002, 0, 0, 90, 0, 0, {0}};
	fct_depth_noise(&kn, 1, 0, truth, NULL, cosine, b, n, &st);
	CHECK_NEAR(sqrt(st.sum2 / (double)st.noisy), 0.008, 0.008 * 0.02);
	kn.sigma = 0.006;
	fct_depth_noise(&kn, 1, 0, truth, NULL, cosine, b, n, &st);
	CHECK_NEAR(sqrt(st.sum2 / (double)st.noisy), 0.01, 0.01 * 0.02);
	/* The same normal draws, scaled: noise at a pixel is (sd / 0.01) times
	 * the Gaussian-only noise there. */
	int prop_ok = 1;
	for (size_t i = 0; i < n; i += 997)
		if (truth[i] > 0)
			prop_ok &= fabs((b[i] - 2) - (a[i] - 2)) < 1e-12;
	CHECK(prop_ok);

	/* Missing 10 %, outliers 5 %: fractions within a percent; outliers in
	 * [1, 3]; pixels neither missing nor outliers keep the noise they had
	 * without those options. */
	struct fct_scene_noise mo = {0.01, 0, 0.05, 0.1, 90, 0, 0, {0}};
	fct_depth_noise(&mo, 1, 0, truth, NULL, cosine, b, n, &st);
	CHECK_NEAR((double)st.missing / 990000, 0.1, 0.01);
	CHECK_NEAR((double)st.outliers / (990000 - st.missing), 0.05, 0.01);
	size_t zeros = 0, in_range = 0, same = 0, kept = 0;
	for (size_t i = 0; i < n; i++) {
		zeros += b[i] == 0;
		if (truth[i] == 0 || b[i] == 0)
			continue;
		if (b[i] == a[i])
			same++;
		else
			in_range += b[i] >= 1 && b[i] < 3;
		kept++;
	}
	CHECK_INT(zeros, 10000 + st.missing);
	CHECK_INT(same, st.noisy);
	CHECK_INT(in_range, st.outliers);
	CHECK_INT(kept, st.noisy + st.outliers);

	/* Range [0, 1.9] drops everything at 2 m; grazing 60 degrees drops the
	 * pixels with cosine < 0.5: half of them. */
	struct fct_scene_noise rg = {0, 0, 0, 0, 90, 0, 1.9, {0}};
	fct_depth_noise(&rg, 1, 0, truth, NULL, cosine, b, n, &st);
	CHECK_INT(st.range, 990000);
	struct fct_scene_noise gz = {0, 0, 0, 0, 60, 0, 0, {0}};
	fct_depth_noise(&gz, 1, 0, truth, NULL, cosine, b, n, &st);
	CHECK_INT(st.grazing, 495000);
	CHECK(b[1] == 0 && b[999] == 2);   /* cosine 0.001 dropped, 0.999 kept exactly */
	free(truth);
	free(a);
	free(b);
	free(cosine);
}

/* The structured-light simulation (kinect, ICL-NUIM's): every measured
 * depth is a level F B / (k STEP) for an integer k, neighbouring levels are
 * fct_noise_step apart (11.4 mm at 2 m), and the rms error against the
 * truth is fct_noise_sigma's within 15% at 1, 2 and 3 m, on truths spread
 * evenly over each step; without rounding or Gaussian part, the parts
 * alone.  Then the plane scene with lateral jitter, through the same calls
 * as mkscene. */
static void test_structured(void)
{
	struct fct_scene_noise nz = {0, 0, 0, 0, 90, 0, 0, {0}};
	fct_noise_kinect(&nz.sensor);
	const struct fct_noise *k = &nz.sensor;
	size_t n = 200000;
	double *truth = malloc(sizeof *truth * n), *out = malloc(sizeof *out * n);
	if (!truth || !out)
		abort();
	for (int z = 1; z <= 3; z++) {
		double step = fct_noise_step(k, z);
		for (size_t i = 0; i < n; i++)
			truth[i] = z + 4 * step * ((double)i / (double)n - 0.5);   /* four steps about z */
		struct fct_scene_noise_stats st;
		fct_depth_noise(&nz, 3, (uint64_t)z, truth, NULL, NULL, out, n, &st);
		CHECK_INT(st.noisy, n);
		int on_levels = 1;
		double gap = HUGE_VAL;   /* the smallest gap between distinct levels near z */
		for (size_t i = 0; i < n; i++) {
			double kk = k->fb / out[i] / k->step;
			on_levels &= fabs(kk - floor(kk + 0.5)) < 1e-6;
			double next = k->fb / (floor(kk + 0.5) - 1) / k->step;   /* the level beyond */
			if (fabs(out[i] - z) < step)
				gap = fmin(gap, next - out[i]);
		}
		CHECK_MSG(on_levels, "z %d: a depth off the disparity levels", z);
		CHECK_MSG(fabs(gap / step - 1) < 0.02, "z %d: levels %g apart, step %g", z, gap, step);
		double rms = sqrt(st.sum2 / (double)st.noisy), model = fct_noise_sigma(k, z);
		CHECK_MSG(fabs(rms / model - 1) < 0.15, "z %d: rms %g, model %g", z, rms, model);
		CHECK_NEAR(sqrt(st.model2 / (double)st.noisy), model, 0.02 * model);
	}
	/* 2 m exactly: steps of z^2 / (8 F B) = 4 / 351 m. */
	CHECK_NEAR(fct_noise_step(k, 2), 4.0 / 351, 1e-5);

	/* The rounding alone: uniform within a step, rms step / sqrt(12); the
	 * Gaussian alone: SD's depth equivalent. */
	struct fct_scene_noise q = nz;
	q.sensor.sd = 0;
	for (size_t i = 0; i < n; i++)
		truth[i] = 2 + 0.2 * ((double)i / (double)n - 0.5);
	struct fct_scene_noise_stats st;
	fct_depth_noise(&q, 3, 9, truth, NULL, NULL, out, n, &st);
	double step2 = fct_noise_step(k, 2);
	CHECK_NEAR(sqrt(st.sum2 / (double)st.noisy), step2 / sqrt(12), 0.05 * step2 / sqrt(12));
	q.sensor.sd = k->sd, q.sensor.step = 0;
	fct_depth_noise(&q, 3, 9, truth, NULL, NULL, out, n, &st);
	double g2 = fct_noise_sigma_gaussian(k, 2);
	CHECK_NEAR(sqrt(st.sum2 / (double)st.noisy), g2, 0.03 * g2);

	/* The plane scene (2.5 m, turned 35 degrees) with half a pixel of
	 * jitter: the sampled depths are the truth's at nearby points, the
	 * error against the truth is the model's within 15% (the jitter on the
	 * slant adds about 2%), and the same calls give the same bytes. */
	struct fct_scene sc;
	struct fct_err err;
	CHECK_INT(fct_scene_build(&sc, "plane", &err), 0);
	struct fct_camera cam = pinhole(320, 240, 262.5);
	double pose[12];
	fct_scene_view_pose(&sc, 0, 1, pose);
	struct fct_render r;
	CHECK_INT(fct_scene_render(&sc, &cam, pose, &r, &err), 0);
	size_t np = (size_t)cam.width * (size_t)cam.height;
	double *jit = malloc(sizeof *jit * np), *noisy = malloc(sizeof *noisy * np);
	double *again = malloc(sizeof *again * np);
	if (!jit || !noisy || !again)
		abort();
	CHECK_INT(fct_scene_render_jitter(&sc, &cam, pose, 0.5, 1, 0, jit, &err), 0);
	/* Each sampled depth is the truth's one pixel or so away: on this slant
	 * the depth changes by at most z tan(incidence) / f per pixel, under
	 * 3.5 * 2.3 / 262.5 = 0.031 m, so the change is within five deviations
	 * of the jitter, and half a pixel's worth in the rms. */
	double jmax = 0, j2 = 0, slope2 = 0;
	size_t moved = 0, m2 = 0;
	for (size_t i = 0; i < np; i++) {
		if (!(r.depth[i] > 0 && jit[i] > 0))
			continue;
		jmax = fmax(jmax, fabs(jit[i] - r.depth[i]));
		j2 += (jit[i] - r.depth[i]) * (jit[i] - r.depth[i]);
		moved += jit[i] != r.depth[i];
		m2++;
		if (i % (size_t)cam.width + 1 < (size_t)cam.width && i + (size_t)cam.width < np &&
		    r.depth[i + 1] > 0 && r.depth[i + (size_t)cam.width] > 0) {
			double gx = r.depth[i + 1] - r.depth[i], gy = r.depth[i + (size_t)cam.width] - r.depth[i];
			slope2 += gx * gx + gy * gy;
		}
	}
	CHECK(m2 > np / 2 && moved > 0.99 * (double)m2);
	CHECK_MSG(jmax < 5 * 0.5 * 0.031, "jitter moved a depth by %g", jmax);
	double jrms = sqrt(j2 / (double)m2), expect = 0.5 * sqrt(slope2 / (double)m2);
	CHECK_MSG(fabs(jrms / expect - 1) < 0.1, "jitter rms %g, half a pixel's slope %g", jrms, expect);
	fct_depth_noise(&nz, 1, 0, r.depth, jit, r.cosine, noisy, np, &st);
	double rms = sqrt(st.sum2 / (double)st.noisy), model = sqrt(st.model2 / (double)st.noisy);
	CHECK_MSG(fabs(rms / model - 1) < 0.15, "plane: rms %g, model %g", rms, model);
	CHECK(rms > model);
	CHECK_INT(fct_scene_render_jitter(&sc, &cam, pose, 0.5, 1, 0, again, &err), 0);
	CHECK(!memcmp(jit, again, sizeof *jit * np));
	fct_depth_noise(&nz, 1, 0, r.depth, again, r.cosine, again, np, NULL);
	CHECK(!memcmp(noisy, again, sizeof *noisy * np));
	fct_render_free(&r);
	fct_scene_free(&sc);
	free(jit);
	free(noisy);
	free(again);
	free(truth);
	free(out);
}

int main(void)
{
	test_scenes();
	test_room_panorama();
	test_small();
	test_color();
	test_noise();
	test_structured();
	CHECK_DONE();
}
