/* fuzz_poses - libFuzzer target: any bytes, as a file, read as a
 * trajectory (poses.h), an intrinsics file (camera.h), a Stanford .conf
 * (rangegrid.h), the text readers tsdfuse and dm2mesh take options from,
 * and a TUM folder's lists (dataset.h: depth.txt, rgb.txt and
 * groundtruth.txt all these bytes), which roommodel reads; then freed.  A crash, leak, sanitizer report or huge allocation is a bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "io/camera.h"
#include "io/dataset.h"
#include "io/poses.h"
#include "depth/rangegrid.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* the readers take paths: one file, rewritten for every input, and a
 * folder of the TUM lists */
static char path[] = "/tmp/fuzz_poses.XXXXXX";
static char dir[] = "/tmp/fuzz_poses_tum.XXXXXX";
static const char *const lists[] = { "depth.txt", "rgb.txt", "groundtruth.txt" };

static void remove_file(void)
{
	unlink(path);
	char p[64];
	for (int k = 0; k < 3; k++) {
		snprintf(p, sizeof p, "%s/%s", dir, lists[k]);
		unlink(p);
	}
	rmdir(dir);
}

static void write_file(const char *name, const uint8_t *data, size_t size)
{
	FILE *f = fopen(name, "wb");
	if (!f)
		return;
	fwrite(data, 1, size, f);
	fclose(f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int fd = -1;
	if (fd < 0) {
		if ((fd = mkstemp(path)) < 0 || !mkdtemp(dir))
			return 0;
		close(fd);
		atexit(remove_file);
	}
	write_file(path, data, size);
	char p[64];
	for (int k = 0; k < 3; k++) {
		snprintf(p, sizeof p, "%s/%s", dir, lists[k]);
		write_file(p, data, size);
	}
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
	struct fct_dataset ds;
	if (fct_dataset_read(&ds, dir, 0.02, &err) == 0)
		fct_dataset_free(&ds);
	return 0;
}
