/* pointnpr — the decorator's stream of a sample layer (docs/meshlab.md, "A sample layer streamed
 * by the view"). "NPR: Open a sample of a large PLY" opens a uniform sample of a file as a layer
 * and names the file on it (vcg_attributes.h, sampleSource). When that file is ordered for drawing
 * (pointnpr convert --lod), each view the camera rests at reads the file again for that view, as
 * many points as the layer holds (pnpr_lod_read_view: near points kept, far and unseen ones
 * thinned), on a worker thread; the decorator then draws that sample instead of the layer's
 * vertices (MeshLab's layer itself is not changed). No Qt here: plain library calls, std::thread
 * and atomics. */
#ifndef POINTNPR_DECORATE_STREAM_H
#define POINTNPR_DECORATE_STREAM_H

#include <pointnpr/cloud.h>
#include <pointnpr/lod.h>

#include <atomic>
#include <string>
#include <thread>

namespace pnpr_meshlab {

/* A view in the file's coordinates (pnpr_view_sample_init's look-at view). */
struct StreamView {
    double eye[3] = {0, 0, 0}, target[3] = {0, 0, 0};
    double fov = 0; /* vertical, degrees; 0: none */
    int width = 0, height = 0;
    bool operator==(const StreamView &o) const;
    bool operator!=(const StreamView &o) const { return !(*this == o); }
};

/* The view of MeshLab's matrices (GL order, column-major) and viewport in the coordinates of the
 * file of a layer whose vertices are the file's points less `origin`, placed by its Tr (row-major,
 * as vcg's Matrix44): the eye and a point ahead of it mapped back through Tr, the vertical field
 * of view from the projection. False for an orthographic or off-centre projection, a singular
 * modelview, a Tr that is not a similarity (rotation, mirror, uniform scale and translation: the
 * cone would not carry over), or a view that is not finite (the layer is then drawn as it is). */
bool streamViewOf(const double mv[16], const double P[16], int width, int height, const double Tr[4][4],
                  const double origin[3], StreamView &r);

/* One layer's stream: its file, and the sample of the last view read. */
struct LayerStream {
    int meshId = -1;
    std::string path;          /* the file (local 8-bit) */
    double origin[3] = {0, 0, 0};
    int ordered = -1;          /* the file is ordered for drawing: -1 not checked yet */
    pnpr_cloud cloud{};        /* the sample of `view` (count 0: none yet: the layer's vertices),
                                * its stored point spacing grown by the view's share */
    float toneRadius = 0;      /* the file's mean spacing as the sample estimates it (0: none) */
    bool spacingMeasured = false; /* the file had no point_spacing: the sample's own was measured */
    StreamView view;           /* the view of cloud */
    bool unstreamable = false; /* the view on screen cannot be streamed (said once until it can) */
    LayerStream() = default;
    LayerStream(const LayerStream &) = delete;
    LayerStream &operator=(const LayerStream &) = delete;
    ~LayerStream() { pnpr_cloud_free(&cloud); }
};

/* A read of one view's sample on a worker thread. */
class StreamJob
{
public:
    /* Starts the worker; false (and r_error) when it cannot. */
    bool start(int meshId, const std::string &path, const StreamView &view, uint64_t points, std::string &r_error);
    bool done() const { return finished_.load(); }
    void cancel() { cancel_.store(true); }
    void join();
    double fraction() const { return permille_.load() / 1000.0; }
    ~StreamJob();

    /* Valid after done() and join(): */
    int meshId = -1;
    std::string path;
    StreamView view;
    uint64_t points = 0;
    pnpr_status status = PNPR_OK;
    std::string message;        /* the library's, when status is not PNPR_OK */
    pnpr_cloud cloud{};
    pnpr_lod_read_info info{};
    float toneRadius = 0;       /* pnpr_lod_grow_spacing's estimate (0: no stored spacing) */
    bool spacingMeasured = false; /* no stored spacing: the sample's own measured here */
    long elapsedMs = 0;

private:
    void run();
    pnpr_status sampleSpacing();
    static int progress(void *user, const char *stage, double fraction);
    std::thread thread_;
    std::atomic<bool> cancel_{false}, finished_{false};
    std::atomic<int> permille_{0};
};

} // namespace pnpr_meshlab

#endif
