/* pointnpr — the decorator's background stages (decorate_stages.h). */
#include "decorate_stages.h"

#include <pointnpr/brush.h>
#include <pointnpr/features.h>
#include <pointnpr/segment.h>

#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace pnpr_meshlab {

namespace {

long msSince(std::chrono::steady_clock::time_point t0)
{
    return (long)std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count();
}

std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

std::string wantList(uint32_t want)
{
    std::string s;
    for (int b = 0; b < 5; b++)
        if (want & (1u << b)) s += (s.empty() ? "" : ", ") + std::string(kWantNames[b]);
    return s;
}

StageOutcome outcome(pnpr_status st) { return st == PNPR_OK ? StageOutcome::Done : st == PNPR_ERR_CANCELLED ? StageOutcome::Cancelled : StageOutcome::Failed; }

std::string errorText(pnpr_status st, const pnpr_error &err)
{
    return err.message[0] ? std::string(err.message) : std::string(pnpr_status_string(st));
}

} // namespace

const char *const kWantNames[5] = {"oriented normals", "feature degree", "feature classes", "dithering points",
                                   "normals"};

int StageJob::progress(void *user, const char *stage, double fraction)
{
    StageJob *j = static_cast<StageJob *>(user);
    {
        std::lock_guard<std::mutex> lock(j->stageMutex_);
        j->stage_ = std::string(j->part_) + (stage && stage[0] ? ": " + std::string(stage) : std::string());
    }
    j->permille_.store(fraction >= 0 && fraction <= 1 ? (int)(fraction * 1000) : 0);
    j->reports_.fetch_add(1);
    return j->cancel_.load() ? 1 : 0;
}

std::string StageJob::stage() const
{
    std::lock_guard<std::mutex> lock(stageMutex_);
    return stage_;
}

bool StageJob::start(const pnpr_cloud &src, const StageRequest &req, std::string &r_error)
{
    request = req;
    pnpr_status st = pnpr_cloud_append(&cloud, &src); /* into an empty cloud: an exact copy */
    if (st != PNPR_OK) {
        r_error = std::string("cannot copy the layers for the computation: ") + pnpr_status_string(st);
        pnpr_cloud_free(&cloud);
        return false;
    }
    try {
        thread_ = std::thread([this] { run(); });
    } catch (...) {
        r_error = "cannot start the computation's thread";
        return false;
    }
    return true;
}

void StageJob::run()
{
    auto t0 = std::chrono::steady_clock::now();
    pnpr_progress pr{&StageJob::progress, this};
    const char *style = request.style.c_str();
    auto begin = [this](const char *part) {
        std::lock_guard<std::mutex> lock(stageMutex_);
        part_ = part;
        stage_ = part;
        permille_.store(0);
    };
    auto note = [this](StageOutcome o, std::string ok, std::string what, const std::string &why) {
        if (o == StageOutcome::Done) messages.push_back({false, std::move(ok)});
        else if (o == StageOutcome::Cancelled) messages.push_back({true, what + " cancelled"});
        else messages.push_back({true, what + " failed: " + why});
    };
    bool stop = false; /* a cancel ends the job: the later stages are not run */
    if (request.want) {
        begin("features");
        auto t = std::chrono::steady_clock::now();
        pnpr_features_options fo;
        std::memset(&fo, 0, sizeof fo);
        fo.want = request.want;
        fo.tone = request.tone;
        fo.progress = pr;
        pnpr_status st = pnpr_compute_features(&cloud, &fo, nullptr);
        features = outcome(st);
        note(features, format("features computed for the %s style (%zu points, %ld ms): %s", style, cloud.count, msSince(t),
                              wantList(request.want).c_str()),
             "feature analysis (" + wantList(request.want) + ")", pnpr_status_string(st));
        stop = features == StageOutcome::Cancelled;
    }
    if (request.jseg && !stop && cloud.rgb) {
        begin("segments");
        auto t = std::chrono::steady_clock::now();
        std::vector<uint32_t> labels(cloud.count);
        pnpr_jseg_options jo;
        std::memset(&jo, 0, sizeof jo);
        jo.progress = pr;
        pnpr_segment_info info;
        std::memset(&info, 0, sizeof info);
        pnpr_status st = pnpr_segment_jseg(cloud.xyz, cloud.rgb, cloud.count, &jo, labels.data(), &info);
        if (st == PNPR_OK && (st = pnpr_cloud_alloc_labels(&cloud)) == PNPR_OK)
            std::memcpy(cloud.label, labels.data(), labels.size() * sizeof(uint32_t));
        jseg = outcome(st);
        note(jseg, format("%zu segments (JSEG, %zu points, %ld ms) for the %s style", (size_t)info.segment_count, cloud.count,
                          msSince(t), style),
             "segmentation (JSEG)", pnpr_status_string(st));
        stop = jseg == StageOutcome::Cancelled;
    }
    if (request.brush && !stop) {
        begin("brush");
        auto t = std::chrono::steady_clock::now();
        pnpr_brush_options bo;
        std::memset(&bo, 0, sizeof bo);
        bo.progress = pr;
        pnpr_brush_stats bs;
        std::memset(&bs, 0, sizeof bs);
        pnpr_error err;
        std::memset(&err, 0, sizeof err);
        pnpr_status st = pnpr_brush_prepare(&cloud, &bo, &bs, &err);
        brush = outcome(st);
        note(brush, format("brush strokes prepared (%zu colour clusters, %zu points, %ld ms)", (size_t)bs.clusters, cloud.count,
                           msSince(t)),
             "brush preparation", errorText(st, err));
        stop = brush == StageOutcome::Cancelled;
    }
    if (request.tree && !stop) {
        begin("hierarchy");
        auto t = std::chrono::steady_clock::now();
        pnpr_sphere_tree_options to;
        std::memset(&to, 0, sizeof to);
        to.progress = pr;
        pnpr_sphere_tree_stats ts;
        std::memset(&ts, 0, sizeof ts);
        pnpr_error err;
        std::memset(&err, 0, sizeof err);
        pnpr_status st = pnpr_sphere_tree_build(&cloud, &to, &tree, &ts, &err);
        hierarchy = outcome(st);
        note(hierarchy, format("sphere hierarchy built (%zu leaves, %zu regions, %zu points, %ld ms)", (size_t)ts.leaves,
                               (size_t)ts.regions, cloud.count, msSince(t)),
             "sphere hierarchy", errorText(st, err));
        stop = hierarchy == StageOutcome::Cancelled;
    }
    if (request.lines && !stop) {
        begin("profile lines");
        auto t = std::chrono::steady_clock::now();
        pnpr_lines_options lo;
        std::memset(&lo, 0, sizeof lo);
        lo.progress = pr;
        pnpr_status st = pnpr_profile_lines(&cloud, &lo, &lines, nullptr);
        profile = outcome(st);
        note(profile, format("%zu profile lines (%ld ms)", (size_t)lines.count, msSince(t)), "profile lines",
             pnpr_status_string(st));
    }
    elapsedMs_ = msSince(t0);
    finished_.store(true);
}

void StageJob::join()
{
    if (thread_.joinable()) thread_.join();
}

StageJob::~StageJob()
{
    cancel();
    join();
    pnpr_cloud_free(&cloud);
    pnpr_sphere_tree_free(&tree);
    pnpr_lines_free(&lines);
}

} // namespace pnpr_meshlab
