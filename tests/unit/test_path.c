/* test_path.c - the path arithmetic of TextureFile: joining a folder and a
 * relative name (collapsing "..", so that a path never passes through a
 * folder that may be gone), and paths relative to an output folder. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "core/path.h"

static struct fct_err err;

static void join_is(const char *dir, const char *rel, const char *want)
{
	char *p = fct_path_join(dir, rel, &err);
	CHECK_MSG(p && !strcmp(p, want), "join(%s, %s) = %s, want %s", dir ? dir : "NULL", rel, p ? p : "NULL",
	          want);
	free(p);
}

static void relative_is(const char *target, const char *from, const char *want)
{
	char *p = fct_path_relative(target, from, &err);
	CHECK_MSG(p && !strcmp(p, want), "relative(%s, %s) = %s, want %s", target, from, p ? p : "NULL", want);
	free(p);
}

/* Absolute targets become relative, and ".." climbs the real folders: an
 * output folder reached through a symbolic link. */
static void test_real_folders(void)
{
	char top[] = "/tmp/facet-path.XXXXXX";
	if (!mkdtemp(top)) {
		CHECK_MSG(0, "mkdtemp failed");
		return;
	}
	char real[512], a[600], b[600], ab[600], deep[600], link[600], t[700];
	if (!realpath(top, real)) {
		CHECK_MSG(0, "realpath failed");
		rmdir(top);
		return;
	}
	snprintf(a, sizeof a, "%s/a", real);
	snprintf(b, sizeof b, "%s/b", real);
	snprintf(ab, sizeof ab, "%s/a/b", real);
	snprintf(deep, sizeof deep, "%s/a/deep", real);
	snprintf(link, sizeof link, "%s/link", real);
	CHECK(mkdir(a, 0700) == 0 && mkdir(b, 0700) == 0 && mkdir(ab, 0700) == 0 &&
	      mkdir(deep, 0700) == 0 && symlink(deep, link) == 0);
	snprintf(t, sizeof t, "%s/tex.png", a);
	relative_is(t, b, "../a/tex.png");
	snprintf(t, sizeof t, "%s/tex.png", b);
	relative_is(t, link, "../../b/tex.png");       /* link is a/deep */
	relative_is(t, deep, "../../b/tex.png");
	snprintf(t, sizeof t, "%s/../b/tex.png", link);   /* link/.. is a, not top */
	relative_is(t, b, "../a/b/tex.png");
	snprintf(t, sizeof t, "%s/tex.png", real);
	relative_is(t, "/", t + 1);
	snprintf(t, sizeof t, "%s/none/tex.png", real);   /* missing: lexical */
	relative_is(t, b, "../none/tex.png");
	unlink(link);
	rmdir(deep);
	rmdir(ab);
	rmdir(a);
	rmdir(b);
	rmdir(top);
}

int main(void)
{
	join_is("a/b", "c.png", "a/b/c.png");
	join_is("a/b/", "c.png", "a/b/c.png");
	join_is(".", "../c.png", "../c.png");
	join_is(NULL, "c.png", "c.png");
	join_is("a", "/abs/c.png", "/abs/c.png");
	/* A stage folder joined with the way back out of it. */
	join_is("/tmp/planarize.X", "../../work/main/rgb.png", "/work/main/rgb.png");
	join_is("a/b", "../c.png", "a/c.png");
	join_is("a", "../../c.png", "../c.png");
	join_is("../x", "y/./z.png", "../x/y/z.png");
	join_is("/a", "../../../c.png", "/c.png");
	join_is("a", "..", ".");
	relative_is("out/tex.png", "out", "tex.png");
	relative_is("img/tex.png", "out/deep", "../../img/tex.png");
	relative_is("out", "out", ".");
	/* the stem that files written beside a model share */
	CHECK_INT(fct_path_stem_length("out/m.obj"), 5);
	CHECK_INT(fct_path_stem_length("m"), 1);
	CHECK_INT(fct_path_stem_length("a.d/m"), 5);
	CHECK_INT(fct_path_stem_length("a.d/m.tar.ply"), 9);
	test_real_folders();
	CHECK_DONE();
}
