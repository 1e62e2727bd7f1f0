/* test_path.c - the path arithmetic of TextureFile: joining a folder and a
 * relative name (collapsing "..", so that a path never passes through a
 * folder that may be gone), and paths relative to an output folder. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "path.h"

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
	relative_is("/abs/tex.png", "out", "/abs/tex.png");
	relative_is("out", "out", ".");
	CHECK_DONE();
}
