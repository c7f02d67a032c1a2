// OBJ/OFF vertices through OpenMesh (placeholder: the adapter lands with the I/O work).
#include <pointnpr/io.h>

extern "C" pnpr_status pnpr_read_mesh_file(const char *path, const pnpr_read_options *opts,
                                           pnpr_cloud *cloud, pnpr_error *err)
{
    (void)opts; (void)cloud;
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: OBJ/OFF reading not implemented yet", path ? path : "");
}
