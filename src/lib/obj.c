/* obj.c - placeholder until the OBJ reader and writer land (see obj.h). */
#include "obj.h"

int fct_obj_read(struct fct_mesh *m, struct fct_reader *r, const char *dir, struct fct_err *err)
{
	(void)m, (void)dir;
	return fct_fail(err, "%s: not a PLY file (OBJ support is not built yet)", r->name);
}

int fct_obj_write(const struct fct_mesh *m, FILE *f, const char *mtl_name, FILE *mtl,
                  struct fct_err *err)
{
	(void)m, (void)f, (void)mtl_name, (void)mtl;
	return fct_fail(err, "OBJ output is not built yet");
}

int fct_obj_wants_mtl(const struct fct_mesh *m)
{
	(void)m;
	return 0;
}
