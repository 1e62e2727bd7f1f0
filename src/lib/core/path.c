/* path.c - folder, join and relative paths (see path.h). */
#include "core/path.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

char *fct_path_dir(const char *path, struct fct_err *err)
{
	const char *slash = strrchr(path, '/');
	if (!slash)
		return fct_strdup(".", err);
	if (slash == path)
		return fct_strdup("/", err);
	size_t n = (size_t)(slash - path);
	char *d = malloc(n + 1);
	if (!d) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	memcpy(d, path, n);
	d[n] = 0;
	return d;
}

/* Collapse "." and "seg/.." in place, lexically: a relative path keeps its
 * leading "..", an absolute one stops at the root. */
static void normalise(char *p)
{
	int abs_path = p[0] == '/';
	size_t o = 0, depth = 0;   /* depth: segments written that ".." may remove */
	for (char *s = p; *s;) {
		while (*s == '/')
			s++;
		char *e = s;
		while (*e && *e != '/')
			e++;
		size_t len = (size_t)(e - s);
		if (len == 0 || (len == 1 && s[0] == '.')) {
		} else if (len == 2 && s[0] == '.' && s[1] == '.' && (depth > 0 || abs_path)) {
			if (depth > 0) {
				while (o > 0 && p[o - 1] != '/')
					o--;
				if (o > 0)
					o--;
				depth--;
			}
		} else {
			if (o > 0 || abs_path)
				p[o++] = '/';
			memmove(p + o, s, len);
			o += len;
			if (!(len == 2 && s[0] == '.' && s[1] == '.'))
				depth++;
		}
		s = e;
	}
	if (o == 0) {
		if (abs_path)
			p[o++] = '/';
		else
			p[o++] = '.';
	}
	p[o] = 0;
}

char *fct_path_join(const char *dir, const char *rel, struct fct_err *err)
{
	if (rel[0] == '/' || !dir || !strcmp(dir, "."))
		return fct_strdup(rel, err);
	size_t n = strlen(dir) + strlen(rel) + 2;
	char *p = malloc(n);
	if (!p) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	size_t dl = strlen(dir);
	snprintf(p, n, "%s%s%s", dir, dl && dir[dl - 1] == '/' ? "" : "/", rel);
	/* A folder joined with "../x" names x beside it, also when the folder
	 * is later removed (a temporary stage folder): the path must not pass
	 * through it. */
	normalise(p);
	return p;
}

/* Absolute form of p with the folder resolved through the file system
 * (symbolic links, then "..") where it exists, lexically where it does not:
 * the ".." of a relative path climb the real folders, not the names that
 * led there.  p names a folder when is_dir is set, else a file in one. */
static char *physical(const char *p, int is_dir, struct fct_err *err)
{
	char *cwd = NULL;
	if (p[0] != '/' && !(cwd = getcwd(NULL, 0))) {
		fct_fail(err, "cannot get the current folder");
		return NULL;
	}
	size_t n = (cwd ? strlen(cwd) : 0) + strlen(p) + 3;
	char *raw = malloc(n);
	if (!raw) {
		free(cwd);
		fct_fail(err, "out of memory");
		return NULL;
	}
	snprintf(raw, n, "%s/%s", cwd ? cwd : "", p);
	free(cwd);
	char *slash = is_dir ? NULL : strrchr(raw, '/');
	if (slash)
		*slash = 0;
	char *real = realpath(slash && slash == raw ? "/" : raw, NULL);
	if (slash)
		*slash = '/';
	if (real) {
		const char *base = slash ? slash + 1 : "";
		size_t m = strlen(real) + strlen(base) + 2;
		char *out = malloc(m);
		if (out)
			snprintf(out, m, "%s/%s", real, base);
		free(real);
		free(raw);
		if (!out)
			fct_fail(err, "out of memory");
		else
			normalise(out);
		return out;
	}
	normalise(raw);
	return raw;
}

char *fct_path_relative(const char *target, const char *from, struct fct_err *err)
{
	char *t = physical(target, 0, err), *f = t ? physical(from, 1, err) : NULL;
	if (!t || !f) {
		free(t);
		return NULL;
	}
	/* Longest common prefix ending at a folder boundary. */
	size_t common = 0;
	for (size_t i = 0;; i++) {
		char a = t[i], b = f[i];
		if ((a == '/' || !a) && (b == '/' || !b))
			common = i;
		if (!a || !b || a != b)
			break;
	}
	size_t ups = 0;
	if (f[common])
		for (const char *s = f + common; *s; s++)
			ups += *s == '/';
	if (!strcmp(f, "/"))
		ups = 0, common = 0;
	const char *rest = t + common + (t[common] == '/');
	size_t n = 3 * ups + strlen(rest) + 2;
	char *r = malloc(n);
	if (r) {
		r[0] = 0;
		for (size_t i = 0; i < ups; i++)
			strcat(r, "../");
		strcat(r, rest);
		if (!r[0])
			strcpy(r, ".");
	} else {
		fct_fail(err, "out of memory");
	}
	free(t);
	free(f);
	return r;
}

int fct_path_has_suffix(const char *path, const char *suffix)
{
	size_t n = strlen(path), k = strlen(suffix);
	return n >= k && !strcasecmp(path + n - k, suffix);
}

size_t fct_path_stem_length(const char *path)
{
	const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
	return dot && (!slash || dot > slash) ? (size_t)(dot - path) : strlen(path);
}

int fct_path_is_std(const char *path)
{
	return !path || !strcmp(path, "-");
}

const char *fct_path_display(const char *path)
{
	return fct_path_is_std(path) ? "<stdin>" : path;
}
