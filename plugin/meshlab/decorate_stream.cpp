/* pointnpr — the decorator's stream of a sample layer (decorate_stream.h). */
#include "decorate_stream.h"

#include <pointnpr/crq.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>
#include <pointnpr/props.h>
#include <pointnpr/render.h>

#include <chrono>
#include <cmath>
#include <cstring>

namespace pnpr_meshlab {

bool StreamView::operator==(const StreamView &o) const
{
    for (int a = 0; a < 3; a++)
        if (eye[a] != o.eye[a] || target[a] != o.target[a]) return false;
    return fov == o.fov && width == o.width && height == o.height;
}

namespace {

/* The inverse of the 3x3 matrix a (row-major), false when singular or not finite. */
bool invert3(const double a[3][3], double r[3][3])
{
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!std::isfinite(det) || std::fabs(det) < 1e-300) return false;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[j][i] = (a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3] -
                       a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3]) / det;
    return true;
}

/* x with A x + t = y (A, t: an affine map's linear part and translation). */
void solveAffine(const double Ai[3][3], const double t[3], const double y[3], double x[3])
{
    for (int r = 0; r < 3; r++) x[r] = Ai[r][0] * (y[0] - t[0]) + Ai[r][1] * (y[1] - t[1]) + Ai[r][2] * (y[2] - t[2]);
}

} // namespace

bool streamViewOf(const double mv[16], const double P[16], int width, int height, const double Tr[4][4],
                  const double origin[3], StreamView &r)
{
    /* a symmetric perspective projection: P[11] = -1, P[15] = 0, P[8] = P[9] = 0 */
    if (!(P[11] == -1 && P[15] == 0 && P[8] == 0 && P[9] == 0 && P[5] > 0) || width <= 0 || height <= 0) return false;
    if (Tr[3][0] != 0 || Tr[3][1] != 0 || Tr[3][2] != 0 || Tr[3][3] != 1) return false;
    double A[3][3], Ai[3][3], t[3], T[3][3], Ti[3][3], tt[3];
    for (int r0 = 0; r0 < 3; r0++) {
        for (int c = 0; c < 3; c++) {
            A[r0][c] = mv[c * 4 + r0];
            T[r0][c] = Tr[r0][c];
        }
        t[r0] = mv[12 + r0];
        tt[r0] = Tr[r0][3];
    }
    if (!invert3(A, Ai) || !invert3(T, Ti)) return false;
    /* a similarity (rotation, mirror, uniform scale): the field of view carries over; another
     * transformation would widen or narrow it unevenly */
    double n0 = T[0][0] * T[0][0] + T[1][0] * T[1][0] + T[2][0] * T[2][0];
    for (int a = 0; a < 3; a++)
        for (int b = a; b < 3; b++) {
            double dot = T[0][a] * T[0][b] + T[1][a] * T[1][b] + T[2][a] * T[2][b];
            if (std::fabs(dot - (a == b ? n0 : 0.0)) > 1e-6 * n0) return false;
        }
    /* in MeshLab's world: the eye (eye space origin) and a point ahead (eye space (0, 0, -1)) */
    const double zero[3] = {0, 0, 0}, ahead[3] = {0, 0, -1};
    double eyeW[3], aheadW[3];
    solveAffine(Ai, t, zero, eyeW);
    solveAffine(Ai, t, ahead, aheadW);
    /* in the layer's coordinates (Tr^-1), then the file's (+ origin) */
    double e[3], g[3];
    solveAffine(Ti, tt, eyeW, e);
    solveAffine(Ti, tt, aheadW, g);
    StreamView v;
    double d = 0;
    for (int a = 0; a < 3; a++) {
        v.eye[a] = e[a] + origin[a];
        v.target[a] = g[a] + origin[a];
        d += (v.target[a] - v.eye[a]) * (v.target[a] - v.eye[a]);
    }
    v.fov = 2.0 * std::atan(1.0 / P[5]) * 180.0 / M_PI;
    v.width = width;
    v.height = height;
    for (int a = 0; a < 3; a++)
        if (!std::isfinite(v.eye[a]) || !std::isfinite(v.target[a])) return false;
    if (!(d > 0) || !(v.fov > 0 && v.fov < 180)) return false;
    r = v;
    return true;
}

int StreamJob::progress(void *user, const char *, double fraction)
{
    StreamJob *j = static_cast<StreamJob *>(user);
    j->permille_.store(fraction >= 0 && fraction <= 1 ? (int)(fraction * 1000) : 0);
    return j->cancel_.load() ? 1 : 0;
}

bool StreamJob::start(int id, const std::string &file, const StreamView &v, uint64_t n, std::string &r_error)
{
    meshId = id;
    path = file;
    view = v;
    points = n;
    try {
        thread_ = std::thread([this] { run(); });
    } catch (...) {
        r_error = "cannot start the stream's thread";
        return false;
    }
    return true;
}

void StreamJob::run()
{
    auto t0 = std::chrono::steady_clock::now();
    pnpr_error err{};
    pnpr_view_sample vs;
    status = pnpr_view_sample_init(&vs, view.eye, view.target, view.fov, view.width, view.height);
    if (status == PNPR_OK) {
        pnpr_read_options ro;
        std::memset(&ro, 0, sizeof ro);
        ro.progress.fn = progress;
        ro.progress.user = this;
        status = pnpr_lod_read_view(path.c_str(), &vs, points, &ro, &cloud, &info, &err);
    }
    if (status == PNPR_OK) toneRadius = pnpr_lod_grow_spacing(&cloud, &vs, 1); /* the disk radii of a thinned surface */
    if (status == PNPR_OK && cancel_.load()) status = PNPR_ERR_CANCELLED; /* an older view's: not taken over */
    if (status == PNPR_OK) status = sampleSpacing();
    if (status == PNPR_OK && cancel_.load()) status = PNPR_ERR_CANCELLED; /* cancelled during the spacing */
    if (status != PNPR_OK) {
        if (message.empty()) message = err.message[0] ? err.message : pnpr_status_string(status);
        pnpr_cloud_free(&cloud);
    }
    elapsedMs = (long)std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count();
    finished_.store(true);
}

/* A file without point_spacing: the sample's own, here rather than in the upload on MeshLab's
 * thread (the upload takes a stored spacing of its own neighbour count as its disk radii). */
pnpr_status StreamJob::sampleSpacing()
{
    if (cloud.count < 2 || pnpr_cloud_find_property(&cloud, PNPR_PROP_POINT_SPACING)) return PNPR_OK;
    pnpr_property *p = nullptr;
    pnpr_status st = pnpr_cloud_add_property(&cloud, PNPR_PROP_POINT_SPACING, PNPR_TYPE_FLOAT32, &p);
    if (st == PNPR_OK) st = pnpr_point_spacing(cloud.xyz, cloud.count, pnpr_upload_defaults().spacing_k, 0, (float *)p->data, nullptr);
    spacingMeasured = st == PNPR_OK;
    if (st != PNPR_OK) message = std::string("the sample's point spacing: ") + pnpr_status_string(st);
    return st;
}

void StreamJob::join()
{
    if (thread_.joinable()) thread_.join();
}

StreamJob::~StreamJob()
{
    cancel();
    join();
    pnpr_cloud_free(&cloud);
}

} // namespace pnpr_meshlab
