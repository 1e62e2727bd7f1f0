/* timeit - median wall-clock seconds of a shell command over N runs.
 *   timeit N 'command'      prints the median, in seconds, %.4f */
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/cli.h"

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
	fct_cli_init("timeit");
	if (argc != 3)
		fct_usage_error("usage: timeit N command");
	long n = fct_opt_long("N", argv[1], 1, 1000);
	double *t = malloc((size_t)n * sizeof *t);
	if (!t)
		fct_die(1, "out of memory");
	for (long i = 0; i < n; i++) {
		double t0 = fct_now();
		pid_t pid = fork();
		if (pid == 0) {
			execl("/bin/sh", "sh", "-c", argv[2], (char *)NULL);
			_exit(127);
		}
		int st;
		if (pid < 0 || waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st))
			fct_die(1, "%s: failed", argv[2]);
		t[i] = fct_now() - t0;
	}
	qsort(t, (size_t)n, sizeof *t, cmp);
	printf("%.4f\n", n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]));
	free(t);
	return 0;
}
