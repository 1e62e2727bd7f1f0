/* test_output.c - atomic outputs: the hidden temporary file removed when
 * the program is killed while writing (each fatal signal, in a child
 * process), signals the parent ignores left ignored, SIGPIPE fatal even
 * when ignored or blocked, the message of a write to a closed pipe, and
 * names up to 255 bytes. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "cli/cli.h"
#include "io/output.h"

static char dir[] = "/tmp/facet-test-output.XXXXXX";

/* Number of entries in dir (hidden ones included). */
static int entries(void)
{
	DIR *d = opendir(dir);
	if (!d)
		return -1;
	int n = 0;
	struct dirent *e;
	while ((e = readdir(d)))
		n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	closedir(d);
	return n;
}

static void empty_dir(void)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	char path[600];
	while (d && (e = readdir(d)))
		if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
			snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
			unlink(path);
		}
	if (d)
		closedir(d);
}

/* In a child: set up as a program does (with the parent's disposition of
 * ignored first when it is not 0), open two outputs in dir, write, raise
 * sig, and commit if still alive.  Returns the wait status. */
static int run_child(int sig, int ignored)
{
	fflush(NULL);
	pid_t pid = fork();
	if (pid == 0) {
		if (ignored)
			signal(ignored, SIG_IGN);
		fct_cli_init("test_output");
		struct fct_out a, b;
		struct fct_err err;
		char pa[600], pb[600];
		snprintf(pa, sizeof pa, "%s/model.obj", dir);
		snprintf(pb, sizeof pb, "%s/model.mtl", dir);
		if (fct_out_open(&a, pa, &err) || fct_out_open(&b, pb, &err))
			_exit(3);
		fputs("v 0 0 0\n", a.f);
		fputs("newmtl m\n", b.f);
		fflush(a.f);
		if (entries() != 2)
			_exit(4);   /* both temporaries exist while writing */
		raise(sig);
		if (fct_out_commit(&b, &err) || fct_out_commit(&a, &err))
			_exit(5);
		_exit(0);
	}
	int st = -1;
	waitpid(pid, &st, 0);
	return st;
}

static void test_killed_while_writing(void)
{
	static const int sigs[] = { SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ };
	static const char *const names[] = { "SIGINT", "SIGTERM", "SIGHUP", "SIGPIPE", "SIGXFSZ" };
	for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
		int st = run_child(sigs[i], 0);
		CHECK_MSG(WIFSIGNALED(st) && WTERMSIG(st) == sigs[i], "%s: the child dies of it (status %#x)",
		          names[i], st);
		CHECK_MSG(entries() == 0, "%s: no temporary file left (%d entries)", names[i], entries());
		empty_dir();
	}
	/* Ignored by the parent (nohup): stays ignored, the outputs complete. */
	int st = run_child(SIGHUP, SIGHUP);
	CHECK_MSG(WIFEXITED(st) && WEXITSTATUS(st) == 0, "ignored SIGHUP: status %#x", st);
	CHECK_INT(entries(), 2);
	empty_dir();
	/* SIGPIPE ignored by the parent is fatal all the same. */
	st = run_child(SIGPIPE, SIGPIPE);
	CHECK_MSG(WIFSIGNALED(st) && WTERMSIG(st) == SIGPIPE, "ignored SIGPIPE: status %#x", st);
	CHECK_INT(entries(), 0);
	empty_dir();
}

/* A child writing to a pipe whose reader is gone: with SIGPIPE ignored
 * and no fct_cli_init (a library caller), fct_out_commit says why; after
 * fct_cli_init, even with SIGPIPE blocked and ignored, it dies of SIGPIPE
 * and says nothing. */
static void test_closed_pipe(void)
{
	for (int init = 0; init < 2; init++) {
		int out[2], msg[2];
		if (pipe(out) || pipe(msg)) {
			CHECK_MSG(0, "pipe: %s", strerror(errno));
			return;
		}
		close(out[0]);   /* the reader went away */
		fflush(NULL);
		pid_t pid = fork();
		if (pid == 0) {
			close(msg[0]);
			dup2(out[1], STDOUT_FILENO);
			dup2(msg[1], STDERR_FILENO);
			signal(SIGPIPE, SIG_IGN);
			sigset_t set;
			sigemptyset(&set);
			sigaddset(&set, SIGPIPE);
			sigprocmask(SIG_BLOCK, &set, NULL);
			if (init)
				fct_cli_init("test_output");
			struct fct_out o;
			struct fct_err err;
			memset(err.msg, 'x', sizeof err.msg);   /* nothing left over */
			err.msg[sizeof err.msg - 1] = 0;
			if (fct_out_open(&o, NULL, &err))
				_exit(3);
			for (int i = 0; i < 100000; i++)
				fputs("0123456789\n", o.f);
			int rc = fct_out_commit(&o, &err);
			fprintf(stderr, "%d %s", rc, err.msg);
			_exit(0);
		}
		close(out[1]);
		close(msg[1]);
		char buf[256] = "";
		ssize_t n = read(msg[0], buf, sizeof buf - 1);
		buf[n > 0 ? n : 0] = 0;
		close(msg[0]);
		int st = -1;
		waitpid(pid, &st, 0);
		if (init) {
			CHECK_MSG(WIFSIGNALED(st) && WTERMSIG(st) == SIGPIPE,
			          "closed pipe after fct_cli_init: dies of SIGPIPE (status %#x)", st);
			CHECK_STR(buf, "");
		} else {
			CHECK_MSG(WIFEXITED(st), "closed pipe, SIGPIPE ignored: status %#x", st);
			CHECK_STR(buf, "-1 <stdout>: write error: Broken pipe");
		}
	}
}

/* Names of 252 and 255 bytes (the temporary one is cut to fit), and one of
 * 256 refused with the system's message when it is moved into place. */
static void test_long_names(void)
{
	static const int lens[] = { 252, 255, 256 };
	for (int k = 0; k < 3; k++) {
		char path[600];
		int at = snprintf(path, sizeof path, "%s/", dir);
		memset(path + at, 'n', (size_t)lens[k] - 4);
		strcpy(path + at + lens[k] - 4, ".ply");
		struct fct_out o;
		struct fct_err err;
		int rc = fct_out_open(&o, path, &err);
		CHECK_MSG(rc == 0, "%d bytes: %s", lens[k], rc ? err.msg : "");
		if (rc)
			continue;
		fputs("ply\n", o.f);
		rc = fct_out_commit(&o, &err);
		if (lens[k] > 255) {   /* refused at the rename, nothing left */
			CHECK(rc == -1 && strstr(err.msg, "File name too long") != NULL);
			CHECK_INT(entries(), 0);
			continue;
		}
		CHECK(rc == 0);
		struct stat sb;
		CHECK_MSG(stat(path, &sb) == 0 && sb.st_size == 4, "%d-byte name written", lens[k]);
		CHECK_INT(entries(), 1);
		empty_dir();
	}
}

int main(void)
{
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	test_killed_while_writing();
	test_closed_pipe();
	test_long_names();
	empty_dir();
	rmdir(dir);
	CHECK_DONE();
}
