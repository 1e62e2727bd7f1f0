/* header.c - camera, pose, TextureFile and provenance comments (see header.h). */
#include "io/header.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "core/numparse.h"

/* Does text start with the word key? */
static int starts_with_word(const char *t, const char *key)
{
	size_t n = strlen(key);
	return !strncmp(t, key, n) && (t[n] == ' ' || t[n] == '\t' || !t[n]);
}

/* Index of the first comment whose text starts with the word key, or -1. */
static long find_comment(const struct fct_mesh *m, const char *key, size_t from)
{
	for (size_t i = from; i < m->ncomments; i++)
		if (!m->comments[i].obj_info && starts_with_word(m->comments[i].text, key))
			return (long)i;
	return -1;
}

/* Parse up to max numbers after the key word; returns how many, -1 on junk. */
static int parse_numbers(const char *s, double *v, int max)
{
	int n = 0;
	for (;;) {
		while (*s == ' ' || *s == '\t')
			s++;
		if (!*s)
			return n;
		if (n == max)
			return -1;
		const char *end = fct_parse_double(s, &v[n]);
		if (!end || (*end && *end != ' ' && *end != '\t') || !isfinite(v[n]))
			return -1;
		n++;
		s = end;
	}
}

static void remove_comment(struct fct_mesh *m, size_t i)
{
	free(m->comments[i].text);
	memmove(&m->comments[i], &m->comments[i + 1], (m->ncomments - i - 1) * sizeof *m->comments);
	m->ncomments--;
}

/* Replace comment `at` (or append when at < 0) with text. */
static int put_comment(struct fct_mesh *m, long at, const char *text, struct fct_err *err)
{
	if (at < 0)
		return fct_mesh_add_comment(m, text, 0, err);
	char *t = fct_strdup(text, err);
	if (!t)
		return -1;
	free(m->comments[at].text);
	m->comments[at].text = t;
	return 0;
}

int fct_header_camera(const struct fct_mesh *m, struct fct_camera *cam, struct fct_err *err)
{
	memset(cam, 0, sizeof *cam);
	long i = find_comment(m, "camera", 0);
	if (i < 0)
		return 0;
	if (fct_camera_parse(m->comments[i].text + 6, cam, err)) {
		fct_err_prefix(err, "comment");
		return -1;
	}
	return 1;
}

int fct_header_set_camera(struct fct_mesh *m, const struct fct_camera *cam, struct fct_err *err)
{
	long i = find_comment(m, "camera", 0);
	if (cam->kind == FCT_CAMERA_NONE) {
		if (i >= 0)
			remove_comment(m, (size_t)i);
		return 0;
	}
	char buf[300] = "camera ";
	fct_camera_format(cam, buf + 7, sizeof buf - 7);
	return put_comment(m, i, buf, err);
}

int fct_header_pose(const struct fct_mesh *m, double pose[12], struct fct_err *err)
{
	long i = find_comment(m, "pose", 0);
	if (i < 0)
		return 0;
	if (parse_numbers(m->comments[i].text + 4, pose, 12) != 12)
		return fct_fail(err, "comment pose: expected 12 numbers (3x4 camera-to-world matrix, row by row)");
	return 1;
}

/* "pose" and the 12 numbers, each the shortest text that reads back to the
 * same double (a rotation's entries in %.17g made the line 260 bytes). */
static void format_pose(char *buf, size_t size, const double pose[12])
{
	size_t n = (size_t)snprintf(buf, size, "pose");
	for (int k = 0; k < 12 && n + 34 < size; k++) {
		buf[n++] = ' ';
		n += (size_t)fct_format_double(buf + n, size - n, pose[k]);
	}
}

int fct_header_set_pose(struct fct_mesh *m, const double pose[12], struct fct_err *err)
{
	long i = find_comment(m, "pose", 0);
	if (!pose) {
		if (i >= 0)
			remove_comment(m, (size_t)i);
		return 0;
	}
	char buf[512];
	format_pose(buf, sizeof buf, pose);
	return put_comment(m, i, buf, err);
}

int fct_header_noise(const struct fct_mesh *m, struct fct_noise *nz, struct fct_err *err)
{
	memset(nz, 0, sizeof *nz);
	long i = find_comment(m, "noise", 0);
	if (i < 0)
		return 0;
	if (fct_noise_parse(nz, m->comments[i].text + 5, err)) {
		fct_err_prefix(err, "comment");
		return -1;
	}
	return 1;
}

int fct_header_set_noise(struct fct_mesh *m, const struct fct_noise *nz, struct fct_err *err)
{
	long i = find_comment(m, "noise", 0);
	if (nz->model == FCT_NOISE_UNKNOWN) {
		if (i >= 0)
			remove_comment(m, (size_t)i);
		return 0;
	}
	char buf[300] = "noise ";
	fct_noise_format(nz, buf + 6, sizeof buf - 6);
	return put_comment(m, i, buf, err);
}

/* Index of the i-th TextureFile comment, or -1. */
static long texture_comment(const struct fct_mesh *m, size_t i)
{
	long at = -1;
	for (size_t k = 0; k <= i; k++)
		if ((at = find_comment(m, "TextureFile", (size_t)(at + 1))) < 0)
			return -1;
	return at;
}

const char *fct_comment_texture(const struct fct_comment *c)
{
	const char *t = c->text;
	if (c->obj_info || strncmp(t, "TextureFile", 11) || (t[11] != ' ' && t[11] != '\t' && t[11]))
		return NULL;
	t += 11;
	while (*t == ' ' || *t == '\t')
		t++;
	return t;
}

size_t fct_header_texture_count(const struct fct_mesh *m)
{
	size_t n = 0;
	for (size_t i = 0; i < m->ncomments; i++)
		n += fct_comment_texture(&m->comments[i]) != NULL;
	return n;
}

const char *fct_header_texture(const struct fct_mesh *m, size_t i)
{
	long at = texture_comment(m, i);
	return at < 0 ? NULL : fct_comment_texture(&m->comments[at]);
}

/* "TextureFile PATH", malloc'd; NULL (message set) on a newline or no memory. */
static char *texture_text(const char *path, struct fct_err *err)
{
	if (strchr(path, '\n')) {
		fct_fail(err, "TextureFile: newline in path");
		return NULL;
	}
	size_t n = strlen(path) + 16;
	char *buf = malloc(n);
	if (!buf)
		fct_fail(err, "out of memory");
	else
		snprintf(buf, n, "TextureFile %s", path);
	return buf;
}

int fct_comment_set_texture(struct fct_comment *c, const char *path, struct fct_err *err)
{
	char *t = texture_text(path, err);
	if (!t)
		return -1;
	free(c->text);
	c->text = t;
	c->obj_info = 0;
	return 0;
}

int fct_header_set_texture(struct fct_mesh *m, size_t i, const char *path, struct fct_err *err)
{
	long at = texture_comment(m, i);
	if (at >= 0)
		return fct_comment_set_texture(&m->comments[at], path, err);
	char *t = texture_text(path, err);
	if (!t)
		return -1;
	int rc = fct_mesh_add_comment(m, t, 0, err);
	free(t);
	return rc;
}

int fct_header_add_provenance(struct fct_mesh *m, const char *prog, int argc, char **argv,
                              struct fct_err *err)
{
	size_t n = strlen(prog) + 8;
	for (int i = 0; i < argc; i++)
		n += strlen(argv[i]) + 1;
	char *buf = malloc(n);
	if (!buf)
		return fct_fail(err, "out of memory");
	char *p = buf + sprintf(buf, "facet %s", prog);
	for (int i = 0; i < argc; i++) {
		*p++ = ' ';
		for (const char *a = argv[i]; *a; a++)
			*p++ = (*a == ' ' || *a == '\t' || *a == '\n' || *a == '\r') ? '_' : *a;
	}
	*p = 0;
	int rc = fct_mesh_add_comment(m, buf, 0, err);
	free(buf);
	return rc;
}

/* Text of at most max bytes: the start of text, then "...". */
static const char *cut_end(const char *text, size_t max, char *buf)
{
	snprintf(buf, max + 1, "%.*s...", (int)(max - 3), text);
	return buf;
}

/* A provenance line "facet PROG ARGS..." in at most max bytes: the program,
 * the leading arguments that fit (options, then the first operands), the
 * count of those left out, and the last argument (its end, when it alone
 * is too long): "facet tsdfuse -o room.ply v00.ply v01.ply ... (19 more)
 * ... v21.ply". */
static const char *abbreviate_provenance(const char *text, size_t max, char *buf)
{
	const char *p = text;        /* past "facet PROG", the head */
	for (int k = 0; k < 2; k++) {
		while (*p == ' ')
			p++;
		while (*p && *p != ' ')
			p++;
	}
	size_t head = (size_t)(p - text);
	const char *last = text + strlen(text);
	while (last > p && last[-1] == ' ')
		last--;
	const char *end = last;
	while (last > p && last[-1] != ' ')
		last--;
	size_t nargs = 0;            /* words between the head and the last one */
	for (const char *q = p; q < last;) {
		while (q < last && *q == ' ')
			q++;
		if (q < last)
			nargs++;
		while (q < last && *q != ' ')
			q++;
	}
	if (last == p || head + 40 > max)
		return cut_end(text, max, buf);
	/* The last word, cut to its end when it takes over a third. */
	char tail[96];
	size_t lastlen = (size_t)(end - last);
	if (lastlen > max / 3)
		snprintf(tail, sizeof tail, "...%.*s", (int)(max / 3 - 3), end - (max / 3 - 3));
	else
		snprintf(tail, sizeof tail, "%.*s", (int)lastlen, last);
	size_t n = head, kept = 0;
	memcpy(buf, text, head);
	for (const char *q = p; q < last;) {
		while (q < last && *q == ' ')
			q++;
		const char *e = q;
		while (e < last && *e != ' ')
			e++;
		if (e == q)
			break;
		char more[48];
		int ml = snprintf(more, sizeof more, " ... (%zu more) ", nargs - kept - 1);
		if (n + 1 + (size_t)(e - q) + (size_t)ml + strlen(tail) > max)
			break;
		buf[n++] = ' ';
		memcpy(buf + n, q, (size_t)(e - q));
		n += (size_t)(e - q);
		kept++;
		q = e;
	}
	snprintf(buf + n, max + 1 - n, " ... (%zu more) %s", nargs - kept, tail);
	return buf;
}

const char *fct_comment_line(const struct fct_comment *c, size_t max, char *buf)
{
	const char *t = c->text;
	if (strlen(t) <= max || max < 48)
		return t;
	double pose[12];
	if (!c->obj_info && starts_with_word(t, "pose") && parse_numbers(t + 4, pose, 12) == 12) {
		format_pose(buf, FCT_HEADER_LINE_MAX + 64, pose);   /* the same numbers, shorter */
		return buf;
	}
	/* Data that cannot be shortened: kept whole. */
	if (!c->obj_info && (fct_comment_texture(c) || starts_with_word(t, "camera")))
		return t;
	if (!c->obj_info && starts_with_word(t, "facet"))
		return abbreviate_provenance(t, max, buf);
	return cut_end(t, max, buf);
}

void fct_header_remove_textures(struct fct_mesh *m)
{
	size_t j = 0;
	for (size_t i = 0; i < m->ncomments; i++) {
		if (fct_comment_texture(&m->comments[i])) {
			free(m->comments[i].text);
			continue;
		}
		m->comments[j++] = m->comments[i];
	}
	m->ncomments = j;
}
