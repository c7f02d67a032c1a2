/* pointnpr — the decorator's background stages (docs/meshlab.md, "Long computations"): the work a
 * style's plan asks for (features, JSEG segments, brush preparation, the sphere hierarchy,
 * profile lines) runs on a worker thread over a copy of the merged layers, so that MeshLab's
 * event loop keeps answering (the viewport draws plain points meanwhile, the progress bar moves,
 * Esc cancels). The results are taken over on the GUI thread once done(). No Qt here: plain
 * library calls, std::thread and atomics. */
#ifndef POINTNPR_DECORATE_STAGES_H
#define POINTNPR_DECORATE_STAGES_H

#include <pointnpr/cloud.h>
#include <pointnpr/hierarchy.h>
#include <pointnpr/lines.h>
#include <pointnpr/tone.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace pnpr_meshlab {

/* What the PNPR_WANT_* bits of a plan are, for the log (index = bit number). */
extern const char *const kWantNames[5];

/* What to compute; zero = nothing. */
struct StageRequest {
    uint32_t want = 0;         /* PNPR_WANT_* bits for pnpr_compute_features */
    pnpr_tone_options tone{};  /* the tone the dithering points follow */
    bool jseg = false, brush = false, tree = false, lines = false;
    std::string style;         /* the style's name, for the messages */
    bool any() const { return want || jseg || brush || tree || lines; }
};

/* One stage's outcome. */
enum class StageOutcome { NotRun, Done, Failed, Cancelled };

struct StageMessage {
    bool warning;
    std::string text;
};

class StageJob
{
public:
    /* Copies `cloud` and starts the worker; false (and r_error) when the copy cannot be made. */
    bool start(const pnpr_cloud &cloud, const StageRequest &req, std::string &r_error);
    bool running() const { return thread_.joinable(); }
    bool done() const { return finished_.load(); }
    void cancel() { cancel_.store(true); }
    /* Waits for the worker (after cancel() it stops at the stage's next progress report). */
    void join();
    /* The running stage and its fraction (0..1), for the progress bar. */
    std::string stage() const;
    double fraction() const { return permille_.load() / 1000.0; }
    int reports() const { return reports_.load(); }
    long elapsedMs() const { return elapsedMs_; }
    ~StageJob();

    /* Valid after done() and join(): */
    StageRequest request;
    pnpr_cloud cloud{};        /* the copy, with the results in it */
    pnpr_sphere_tree tree{};
    pnpr_polylines lines{};
    StageOutcome features = StageOutcome::NotRun, jseg = StageOutcome::NotRun, brush = StageOutcome::NotRun,
                 hierarchy = StageOutcome::NotRun, profile = StageOutcome::NotRun;
    std::vector<StageMessage> messages;

private:
    void run();
    void begin(const char *part);
    void note(StageOutcome o, const std::string &ok, const std::string &what, const std::string &why);
    StageOutcome runFeatures(const pnpr_progress &pr, std::chrono::steady_clock::time_point t);
    StageOutcome runJseg(const pnpr_progress &pr, std::chrono::steady_clock::time_point t);
    StageOutcome runBrush(const pnpr_progress &pr, std::chrono::steady_clock::time_point t);
    StageOutcome runTree(const pnpr_progress &pr, std::chrono::steady_clock::time_point t);
    StageOutcome runLines(const pnpr_progress &pr, std::chrono::steady_clock::time_point t);
    static int progress(void *user, const char *stage, double fraction);
    std::thread thread_;
    std::atomic<bool> cancel_{false}, finished_{false};
    std::atomic<int> permille_{0}, reports_{0};
    mutable std::mutex stageMutex_;
    std::string stage_; /* "features: knn" */
    const char *part_ = ""; /* our stage running (a literal) */
    long elapsedMs_ = 0;
};

} // namespace pnpr_meshlab

#endif
