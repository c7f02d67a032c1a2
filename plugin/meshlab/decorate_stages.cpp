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

void StageJob::begin(const char *part)
{
    std::lock_guard<std::mutex> lock(stageMutex_);
    part_ = part;
    stage_ = part;
    permille_.store(0);
}

/* The message of a stage: `ok` when done, "WHAT cancelled" / "WHAT failed: WHY" otherwise. */
void StageJob::note(StageOutcome o, const std::string &ok, const std::string &what, const std::string &why)
{
    if (o == StageOutcome::Done) messages.push_back({false, ok});
    else if (o == StageOutcome::Cancelled) messages.push_back({true, what + " cancelled"});
    else messages.push_back({true, what + " failed: " + why});
}

StageOutcome StageJob::runFeatures(const pnpr_progress &pr, std::chrono::steady_clock::time_point t)
{
    pnpr_features_options fo{};
    fo.want = request.want;
    fo.tone = request.tone;
    fo.progress = pr;
    pnpr_status st = pnpr_compute_features(&cloud, &fo, nullptr);
    std::string what = wantList(request.want);
    note(outcome(st), format("features computed for the %s style (%zu points, %ld ms): %s", request.style.c_str(), cloud.count,
                             msSince(t), what.c_str()),
         "feature analysis (" + what + ")", pnpr_status_string(st));
    return outcome(st);
}

StageOutcome StageJob::runJseg(const pnpr_progress &pr, std::chrono::steady_clock::time_point t)
{
    std::vector<uint32_t> labels(cloud.count);
    pnpr_jseg_options jo{};
    jo.progress = pr;
    pnpr_segment_info info{};
    pnpr_status st = pnpr_segment_jseg(cloud.xyz, cloud.rgb, cloud.count, &jo, labels.data(), &info);
    if (st == PNPR_OK && (st = pnpr_cloud_alloc_labels(&cloud)) == PNPR_OK)
        std::memcpy(cloud.label, labels.data(), labels.size() * sizeof(uint32_t));
    note(outcome(st), format("%zu segments (JSEG, %zu points, %ld ms) for the %s style", (size_t)info.segment_count,
                             cloud.count, msSince(t), request.style.c_str()),
         "segmentation (JSEG)", pnpr_status_string(st));
    return outcome(st);
}

StageOutcome StageJob::runBrush(const pnpr_progress &pr, std::chrono::steady_clock::time_point t)
{
    pnpr_brush_options bo{};
    bo.progress = pr;
    pnpr_brush_stats bs{};
    pnpr_error err{};
    pnpr_status st = pnpr_brush_prepare(&cloud, &bo, &bs, &err);
    note(outcome(st), format("brush strokes prepared (%zu colour clusters, %zu points, %ld ms)", (size_t)bs.clusters,
                             cloud.count, msSince(t)),
         "brush preparation", errorText(st, err));
    return outcome(st);
}

StageOutcome StageJob::runTree(const pnpr_progress &pr, std::chrono::steady_clock::time_point t)
{
    pnpr_sphere_tree_options to{};
    to.progress = pr;
    pnpr_sphere_tree_stats ts{};
    pnpr_error err{};
    pnpr_status st = pnpr_sphere_tree_build(&cloud, &to, &tree, &ts, &err);
    note(outcome(st), format("sphere hierarchy built (%zu leaves, %zu regions, %zu points, %ld ms)", (size_t)ts.leaves,
                             (size_t)ts.regions, cloud.count, msSince(t)),
         "sphere hierarchy", errorText(st, err));
    return outcome(st);
}

StageOutcome StageJob::runLines(const pnpr_progress &pr, std::chrono::steady_clock::time_point t)
{
    pnpr_lines_options lo{};
    lo.progress = pr;
    pnpr_status st = pnpr_profile_lines(&cloud, &lo, &lines, nullptr);
    note(outcome(st), format("%zu profile lines (%ld ms)", (size_t)lines.count, msSince(t)), "profile lines",
         pnpr_status_string(st));
    return outcome(st);
}

/* The stages asked for, in the plan's order; a cancel ends the job (the later stages are not run). */
void StageJob::run()
{
    auto t0 = std::chrono::steady_clock::now();
    pnpr_progress pr{&StageJob::progress, this};
    using Runner = StageOutcome (StageJob::*)(const pnpr_progress &, std::chrono::steady_clock::time_point);
    struct Step {
        bool asked;
        const char *part;
        Runner fn;
        StageOutcome *out;
    };
    const Step steps[] = {{request.want != 0, "features", &StageJob::runFeatures, &features},
                          {request.jseg && cloud.rgb, "segments", &StageJob::runJseg, &jseg},
                          {request.brush, "brush", &StageJob::runBrush, &brush},
                          {request.tree, "hierarchy", &StageJob::runTree, &hierarchy},
                          {request.lines, "profile lines", &StageJob::runLines, &profile}};
    for (const Step &step : steps) {
        if (!step.asked) continue;
        begin(step.part);
        *step.out = (this->*step.fn)(pr, std::chrono::steady_clock::now());
        if (*step.out == StageOutcome::Cancelled) break;
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
