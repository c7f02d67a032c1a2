/* The point cloud model: float offsets from a double origin, optional arrays, extra properties. */
#include <pointnpr/cloud.h>

#include "internal.h"
#include <pointnpr/outliers.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t pnpr_type_size(pnpr_type t)
{
    switch (t) {
    case PNPR_TYPE_INT8: case PNPR_TYPE_UINT8: return 1;
    case PNPR_TYPE_INT16: case PNPR_TYPE_UINT16: return 2;
    case PNPR_TYPE_INT32: case PNPR_TYPE_UINT32: case PNPR_TYPE_FLOAT32: return 4;
    case PNPR_TYPE_FLOAT64: return 8;
    default: return 0;
    }
}

const char *pnpr_type_ply_name(pnpr_type t)
{
    switch (t) {
    case PNPR_TYPE_INT8: return "char";
    case PNPR_TYPE_UINT8: return "uchar";
    case PNPR_TYPE_INT16: return "short";
    case PNPR_TYPE_UINT16: return "ushort";
    case PNPR_TYPE_INT32: return "int";
    case PNPR_TYPE_UINT32: return "uint";
    case PNPR_TYPE_FLOAT32: return "float";
    case PNPR_TYPE_FLOAT64: return "double";
    default: return "";
    }
}

double pnpr_type_get(pnpr_type t, const void *data, size_t i)
{
    switch (t) {
    case PNPR_TYPE_INT8: return ((const int8_t *)data)[i];
    case PNPR_TYPE_UINT8: return ((const uint8_t *)data)[i];
    case PNPR_TYPE_INT16: return ((const int16_t *)data)[i];
    case PNPR_TYPE_UINT16: return ((const uint16_t *)data)[i];
    case PNPR_TYPE_INT32: return ((const int32_t *)data)[i];
    case PNPR_TYPE_UINT32: return ((const uint32_t *)data)[i];
    case PNPR_TYPE_FLOAT32: return ((const float *)data)[i];
    case PNPR_TYPE_FLOAT64: return ((const double *)data)[i];
    default: return 0.0;
    }
}

static double clamp_round(double v, double lo, double hi)
{
    if (v != v) return 0.0;
    v = floor(v + 0.5);
    return v < lo ? lo : (v > hi ? hi : v);
}

void pnpr_type_set(pnpr_type t, void *data, size_t i, double v)
{
    switch (t) {
    case PNPR_TYPE_INT8: ((int8_t *)data)[i] = (int8_t)clamp_round(v, -128, 127); break;
    case PNPR_TYPE_UINT8: ((uint8_t *)data)[i] = (uint8_t)clamp_round(v, 0, 255); break;
    case PNPR_TYPE_INT16: ((int16_t *)data)[i] = (int16_t)clamp_round(v, -32768, 32767); break;
    case PNPR_TYPE_UINT16: ((uint16_t *)data)[i] = (uint16_t)clamp_round(v, 0, 65535); break;
    case PNPR_TYPE_INT32: ((int32_t *)data)[i] = (int32_t)clamp_round(v, -2147483648.0, 2147483647.0); break;
    case PNPR_TYPE_UINT32: ((uint32_t *)data)[i] = (uint32_t)clamp_round(v, 0, 4294967295.0); break;
    case PNPR_TYPE_FLOAT32: ((float *)data)[i] = (float)v; break;
    case PNPR_TYPE_FLOAT64: ((double *)data)[i] = v; break;
    default: break;
    }
}

void pnpr_cloud_free(pnpr_cloud *cloud)
{
    if (!cloud) return;
    free(cloud->xyz);
    free(cloud->src_xyz);
    free(cloud->rgb);
    free(cloud->normal);
    free(cloud->label);
    for (size_t i = 0; i < cloud->prop_count; i++)
        free(cloud->props[i].data);
    free(cloud->props);
    free(cloud->faces.offset);
    free(cloud->faces.index);
    memset(cloud, 0, sizeof *cloud);
}

/* calloc(n, size) with overflow check; n == 0 gives a valid 1-byte block so that NULL always
 * means failure. */
static void *alloc_zero(size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size) return NULL;
    return calloc(n ? n : 1, size ? size : 1);
}

pnpr_status pnpr_cloud_alloc(pnpr_cloud *cloud, size_t count)
{
    if (!cloud) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_cloud_free(cloud);
    if (count > SIZE_MAX / (3 * sizeof(double))) return PNPR_ERR_OUT_OF_MEMORY;
    cloud->xyz = alloc_zero(3 * count, sizeof(float));
    if (!cloud->xyz) return PNPR_ERR_OUT_OF_MEMORY;
    cloud->count = count;
    return PNPR_OK;
}

static pnpr_status alloc_optional(void **arr, size_t n, size_t size)
{
    if (*arr) return PNPR_OK;
    *arr = alloc_zero(n, size);
    return *arr ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
}

pnpr_status pnpr_cloud_alloc_rgb(pnpr_cloud *c)
{
    return c ? alloc_optional((void **)&c->rgb, 3 * c->count, 1) : PNPR_ERR_INVALID_ARGUMENT;
}
pnpr_status pnpr_cloud_alloc_normals(pnpr_cloud *c)
{
    return c ? alloc_optional((void **)&c->normal, 3 * c->count, sizeof(float)) : PNPR_ERR_INVALID_ARGUMENT;
}
pnpr_status pnpr_cloud_alloc_labels(pnpr_cloud *c)
{
    return c ? alloc_optional((void **)&c->label, c->count, sizeof(uint32_t)) : PNPR_ERR_INVALID_ARGUMENT;
}
pnpr_status pnpr_cloud_alloc_src_xyz(pnpr_cloud *c)
{
    return c ? alloc_optional((void **)&c->src_xyz, 3 * c->count, sizeof(double)) : PNPR_ERR_INVALID_ARGUMENT;
}

pnpr_property *pnpr_cloud_find_property(const pnpr_cloud *cloud, const char *name)
{
    if (!cloud || !name) return NULL;
    for (size_t i = 0; i < cloud->prop_count; i++)
        if (strcmp(cloud->props[i].name, name) == 0)
            return &cloud->props[i];
    return NULL;
}

pnpr_status pnpr_cloud_add_property(pnpr_cloud *cloud, const char *name, pnpr_type type,
                                    pnpr_property **r_prop)
{
    if (r_prop) *r_prop = NULL;
    if (!cloud || !name || !name[0] || strlen(name) >= sizeof(((pnpr_property *)0)->name) ||
        pnpr_type_size(type) == 0)
        return PNPR_ERR_INVALID_ARGUMENT;
    void *data = alloc_zero(cloud->count, pnpr_type_size(type));
    if (!data) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_property *p = pnpr_cloud_find_property(cloud, name);
    if (!p) {
        pnpr_property *grown = realloc(cloud->props, (cloud->prop_count + 1) * sizeof *grown);
        if (!grown) { free(data); return PNPR_ERR_OUT_OF_MEMORY; }
        cloud->props = grown;
        p = &cloud->props[cloud->prop_count++];
        memset(p, 0, sizeof *p);
        strcpy(p->name, name);
    }
    free(p->data);
    p->type = type;
    p->data = data;
    if (r_prop) *r_prop = p;
    return PNPR_OK;
}

pnpr_status pnpr_cloud_remove_property(pnpr_cloud *cloud, const char *name)
{
    pnpr_property *p = pnpr_cloud_find_property(cloud, name);
    if (!p) return PNPR_ERR_NOT_FOUND;
    size_t i = (size_t)(p - cloud->props);
    free(p->data);
    memmove(p, p + 1, (cloud->prop_count - i - 1) * sizeof *p);
    cloud->prop_count--;
    return PNPR_OK;
}

void pnpr_cloud_world(const pnpr_cloud *cloud, size_t i, double r_world[3])
{
    for (int a = 0; a < 3; a++)
        r_world[a] = cloud->src_xyz ? cloud->src_xyz[3 * i + a]
                                    : cloud->origin[a] + (double)cloud->xyz[3 * i + a];
}

/* Centre of the finite bounding box of the world coordinates that are not far outliers
 * (pnpr_world_outliers, default factor; 0 when there is no finite point). Without far outliers
 * this is the centre of the whole finite bounding box. */
static pnpr_status world_centre(const double *world, size_t count, double r_c[3])
{
    pnpr_outlier_info info;
    pnpr_status st = pnpr_world_outliers(world, count, NULL, NULL, &info);
    if (st != PNPR_OK) return st;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < count; i++) {
        const double *p = world + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || pnpr_outlier_is_far(&info, p)) continue;
        for (int a = 0; a < 3; a++) {
            if (p[a] < lo[a]) lo[a] = p[a];
            if (p[a] > hi[a]) hi[a] = p[a];
        }
    }
    for (int a = 0; a < 3; a++)
        r_c[a] = lo[a] <= hi[a] ? 0.5 * lo[a] + 0.5 * hi[a] : 0.0;
    return PNPR_OK;
}

pnpr_status pnpr_cloud_set_world(pnpr_cloud *cloud, const double *world)
{
    if (!cloud || (!world && cloud->count) || (cloud->count && !cloud->xyz))
        return PNPR_ERR_INVALID_ARGUMENT;
    double origin[3];
    pnpr_status st = world_centre(world, cloud->count, origin);
    return st == PNPR_OK ? pnpr_cloud_set_world_at(cloud, world, origin) : st;
}

pnpr_status pnpr_cloud_set_world_at(pnpr_cloud *cloud, const double *world, const double origin[3])
{
    if (!cloud || !origin || (!world && cloud->count) || (cloud->count && !cloud->xyz) || !isfinite(origin[0]) ||
        !isfinite(origin[1]) || !isfinite(origin[2]))
        return PNPR_ERR_INVALID_ARGUMENT;
    memcpy(cloud->origin, origin, sizeof cloud->origin);
    for (size_t i = 0; i < 3 * cloud->count; i++)
        cloud->xyz[i] = (float)(world[i] - cloud->origin[i % 3]);
    return PNPR_OK;
}

size_t pnpr_cloud_bounds(const pnpr_cloud *cloud, float r_min[3], float r_max[3])
{
    size_t n = 0;
    for (int a = 0; a < 3; a++) { r_min[a] = INFINITY; r_max[a] = -INFINITY; }
    if (!cloud) return 0;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        n++;
        for (int a = 0; a < 3; a++) {
            if (p[a] < r_min[a]) r_min[a] = p[a];
            if (p[a] > r_max[a]) r_max[a] = p[a];
        }
    }
    return n;
}

/* Grows a per-point array from old_n to new_n elements of `size` bytes (new part zeroed). */
static pnpr_status grow(void **arr, size_t old_n, size_t new_n, size_t size)
{
    if (size && new_n > SIZE_MAX / size) return PNPR_ERR_OUT_OF_MEMORY;
    void *p = realloc(*arr, new_n * size > 0 ? new_n * size : 1);
    if (!p) return PNPR_ERR_OUT_OF_MEMORY;
    memset((char *)p + old_n * size, 0, (new_n - old_n) * size);
    *arr = p;
    return PNPR_OK;
}

pnpr_status pnpr_cloud_append(pnpr_cloud *dst, const pnpr_cloud *src)
{
    if (!dst || !src || (src->count && !src->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    const size_t n0 = dst->count, n1 = src->count, n = n0 + n1;
    if (n < n0 || n > UINT32_MAX) return PNPR_ERR_OUT_OF_MEMORY; /* face indices are uint32 */
    pnpr_status st;
    int keep_src = dst->src_xyz || src->src_xyz ||
                   dst->src_coord_type == PNPR_TYPE_FLOAT64 || src->src_coord_type == PNPR_TYPE_FLOAT64;
    if (n0 == 0 && !dst->xyz) {
        memcpy(dst->origin, src->origin, sizeof dst->origin);
        dst->src_coord_type = src->src_coord_type;
    }
    if (src->src_coord_type == PNPR_TYPE_FLOAT64) dst->src_coord_type = PNPR_TYPE_FLOAT64;
    /* Exact world coordinates for the existing points before offsets change meaning. */
    if (keep_src && !dst->src_xyz) {
        if ((st = pnpr_cloud_alloc_src_xyz(dst)) != PNPR_OK) return st;
        for (size_t i = 0; i < n0; i++) pnpr_cloud_world(dst, i, dst->src_xyz + 3 * i);
    }
    if ((st = grow((void **)&dst->xyz, 3 * n0, 3 * n, sizeof(float))) != PNPR_OK) return st;
    if (keep_src && (st = grow((void **)&dst->src_xyz, 3 * n0, 3 * n, sizeof(double))) != PNPR_OK) return st;
    if ((dst->rgb || src->rgb) && (st = grow((void **)&dst->rgb, dst->rgb ? 3 * n0 : 0, 3 * n, 1)) != PNPR_OK) return st;
    if ((dst->normal || src->normal) &&
        (st = grow((void **)&dst->normal, dst->normal ? 3 * n0 : 0, 3 * n, sizeof(float))) != PNPR_OK) return st;
    if ((dst->label || src->label) &&
        (st = grow((void **)&dst->label, dst->label ? n0 : 0, n, sizeof(uint32_t))) != PNPR_OK) return st;
    for (size_t i = 0; i < n1; i++) {
        double w[3];
        pnpr_cloud_world(src, i, w);
        for (int a = 0; a < 3; a++) {
            /* offset relative to dst origin, computed without subtracting large doubles in float */
            double rel = (src->origin[a] - dst->origin[a]) + (double)src->xyz[3 * i + a];
            dst->xyz[3 * (n0 + i) + a] = (float)rel;
            if (keep_src) dst->src_xyz[3 * (n0 + i) + a] = w[a];
        }
    }
    if (src->rgb) memcpy(dst->rgb + 3 * n0, src->rgb, 3 * n1);
    if (src->normal) memcpy(dst->normal + 3 * n0, src->normal, 3 * n1 * sizeof(float));
    if (src->label) memcpy(dst->label + n0, src->label, n1 * sizeof(uint32_t));
    /* extra properties: union by name; a type clash converts to the destination's type */
    for (size_t k = 0; k < dst->prop_count; k++) {
        pnpr_property *p = &dst->props[k];
        size_t sz = pnpr_type_size(p->type);
        if ((st = grow(&p->data, n0, n, sz)) != PNPR_OK) return st;
    }
    for (size_t k = 0; k < src->prop_count; k++) {
        const pnpr_property *sp = &src->props[k];
        pnpr_property *p = pnpr_cloud_find_property(dst, sp->name);
        if (!p) {
            size_t saved = dst->count;
            dst->count = n;
            st = pnpr_cloud_add_property(dst, sp->name, sp->type, &p);
            dst->count = saved;
            if (st != PNPR_OK) return st;
        }
        if (p->type == sp->type)
            memcpy((char *)p->data + n0 * pnpr_type_size(p->type), sp->data, n1 * pnpr_type_size(p->type));
        else
            for (size_t i = 0; i < n1; i++)
                pnpr_type_set(p->type, p->data, n0 + i, pnpr_type_get(sp->type, sp->data, i));
    }
    if (src->faces.count) {
        size_t f0 = dst->faces.count, f1 = src->faces.count;
        size_t i0 = dst->faces.count ? dst->faces.offset[f0] : 0, i1 = src->faces.offset[f1];
        if ((st = grow((void **)&dst->faces.offset, f0 ? f0 + 1 : 0, f0 + f1 + 1, sizeof(uint32_t))) != PNPR_OK) return st;
        if ((st = grow((void **)&dst->faces.index, i0, i0 + i1, sizeof(uint32_t))) != PNPR_OK) return st;
        for (size_t f = 0; f <= f1; f++) dst->faces.offset[f0 + f] = (uint32_t)(i0 + src->faces.offset[f]);
        for (size_t j = 0; j < i1; j++) dst->faces.index[i0 + j] = (uint32_t)(src->faces.index[j] + n0);
        dst->faces.count = f0 + f1;
    }
    dst->count = n;
    return PNPR_OK;
}

/* Moves the kept elements (keep[i] != 0) of an array of n elements of `size` bytes to its front. */
static void compact(void *data, size_t size, size_t n, const uint8_t *keep)
{
    if (!data) return;
    char *a = data;
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (!keep[i]) continue;
        if (m != i) memcpy(a + m * size, a + i * size, size);
        m++;
    }
}

/* Faces whose corners are all kept, re-indexed to the kept points' new positions. */
static pnpr_status keep_faces(pnpr_faces *f, size_t n, const uint8_t *keep)
{
    if (!f->count) return PNPR_OK;
    uint32_t *map = malloc(n * sizeof *map);
    if (!map) return PNPR_ERR_OUT_OF_MEMORY;
    uint32_t m = 0;
    for (size_t i = 0; i < n; i++) map[i] = keep[i] ? m++ : UINT32_MAX;
    size_t nf = 0, ni = 0;
    for (size_t k = 0; k < f->count; k++) {
        uint32_t b = f->offset[k], e = f->offset[k + 1], ok = 1;
        for (uint32_t j = b; j < e; j++) ok &= f->index[j] < n && map[f->index[j]] != UINT32_MAX;
        if (!ok) continue;
        f->offset[nf++] = (uint32_t)ni;
        for (uint32_t j = b; j < e; j++) f->index[ni++] = map[f->index[j]];
    }
    f->offset[nf] = (uint32_t)ni;
    f->count = nf;
    free(map);
    return PNPR_OK;
}

pnpr_status pnpr_cloud_keep(pnpr_cloud *cloud, const uint8_t *keep, size_t *r_removed)
{
    if (r_removed) *r_removed = 0;
    if (!cloud || (cloud->count && (!keep || !cloud->xyz))) return PNPR_ERR_INVALID_ARGUMENT;
    const size_t n = cloud->count;
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += keep[i] != 0;
    if (m == n) return PNPR_OK;
    pnpr_status st = keep_faces(&cloud->faces, n, keep);
    if (st != PNPR_OK) return st;
    compact(cloud->xyz, 3 * sizeof(float), n, keep);
    compact(cloud->src_xyz, 3 * sizeof(double), n, keep);
    compact(cloud->rgb, 3, n, keep);
    compact(cloud->normal, 3 * sizeof(float), n, keep);
    compact(cloud->label, sizeof(uint32_t), n, keep);
    for (size_t k = 0; k < cloud->prop_count; k++)
        compact(cloud->props[k].data, pnpr_type_size(cloud->props[k].type), n, keep);
    cloud->count = m;
    if (r_removed) *r_removed = n - m;
    return PNPR_OK;
}

/* Permutes n elements of `size` bytes through `scratch` (n * size bytes). forward: the element
 * at position p moves to perm[p] (tree order -> input order); else the element at perm[p] moves
 * to p (input order -> tree order). Out of place on purpose: independent scattered stores keep
 * many cache misses in flight, where following permutation cycles in place would wait for each
 * miss in turn (measured 0.8 s vs 0.1 s for the eight arrays of a 1M-point cloud). */
void pnpr_permute(void *data, size_t size, size_t n, const uint32_t *perm, int forward, char *scratch)
{
    if (!data || n == 0) return;
    const char *a = data;
    if (forward)
        for (size_t p = 0; p < n; p++) memcpy(scratch + (size_t)perm[p] * size, a + p * size, size);
    else
        for (size_t p = 0; p < n; p++) memcpy(scratch + p * size, a + (size_t)perm[p] * size, size);
    memcpy(data, scratch, n * size);
}

pnpr_status pnpr_cloud_permute(pnpr_cloud *cloud, const uint32_t *perm)
{
    if (!cloud || (cloud->count && !perm) || cloud->faces.count) return PNPR_ERR_INVALID_ARGUMENT;
    const size_t n = cloud->count;
    if (n == 0) return PNPR_OK;
    char *scratch = malloc(n * 3 * sizeof(double));
    if (!scratch) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_permute(cloud->xyz, 3 * sizeof(float), n, perm, 0, scratch);
    pnpr_permute(cloud->src_xyz, 3 * sizeof(double), n, perm, 0, scratch);
    pnpr_permute(cloud->rgb, 3, n, perm, 0, scratch);
    pnpr_permute(cloud->normal, 3 * sizeof(float), n, perm, 0, scratch);
    pnpr_permute(cloud->label, sizeof(uint32_t), n, perm, 0, scratch);
    for (size_t k = 0; k < cloud->prop_count; k++)
        pnpr_permute(cloud->props[k].data, pnpr_type_size(cloud->props[k].type), n, perm, 0, scratch);
    free(scratch);
    return PNPR_OK;
}
