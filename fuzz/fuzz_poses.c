/* fuzz_poses - libFuzzer target: any bytes, as a file, read as a
 * trajectory (poses.h), an intrinsics file (camera.h) and a Stanford .conf
 * (rangegrid.h), the text readers tsdfuse and dm2mesh take options from;
 * then freed.  A crash, leak, sanitizer report or huge allocation is a bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "camera.h"
#include "poses.h"
#include "rangegrid.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* the readers take paths: one file, rewritten for every input */
static char path[] = "/tmp/fuzz_poses.XXXXXX";

static void remove_file(void)
{
	unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int fd = -1;
	if (fd < 0) {
		if ((fd = mkstemp(path)) < 0)
			return 0;
		close(fd);
		atexit(remove_file);
	}
	FILE *f = fopen(path, "wb");
	if (!f)
		return 0;
	fwrite(data, 1, size, f);
	fclose(f);
	struct fct_err err;
	struct fct_trajectory tr;
	if (fct_trajectory_read(&tr, path, &err) == 0) {
		const char *frames[2] = { "1305031102.2.png", "frame-000001.png" };
		double poses[24];
		const char *files[1] = { path };
		fct_frame_poses(poses, NULL, files, 1, frames, 1 + (size & 1), 0.02, &err);
		fct_trajectory_free(&tr);
	}
	struct fct_camera cam;
	struct fct_stereo st;
	fct_camera_read_stereo(&cam, &st, path, &err);
	struct fct_conf c;
	if (fct_conf_read(&c, path, &err) == 0)
		fct_conf_free(&c);
	return 0;
}
