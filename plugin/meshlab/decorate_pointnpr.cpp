/* pointnpr — MeshLab 2020.09 decorate plugin "NPR render" (docs/meshlab.md).
 *
 * decorateDoc runs once per frame after MeshLab drew the layers, with the modelview holding the
 * view and the trackball (not the layers' Tr). It
 *   1. finds the pnpr_renderer of the current GL context (created on first use; one per context,
 *      owned by this plugin instance, dropped when the context goes away),
 *   2. merges the visible point layers (vertices, no faces, no edges) into one pnpr_cloud in
 *      scene coordinates (each layer's Tr applied in double; origin = bounding-box centre) when
 *      the layers changed (a signature of ids, counts, Tr and sampled vertices), with the layers'
 *      colours, meaningful normals, segment labels and the features filter's classes/directions,
 *   3. follows the library's stage planner (pnpr_plan_make, plan.h) for the chosen style and
 *      outline: pnpr_compute_features with plan.want, 3D JSEG into cloud->label when
 *      plan.segments says so, profile lines when plan.lines — each once per cloud (the results
 *      stay in the cloud, so the next frame's plan wants nothing), then uploads the cloud,
 *   4. passes MeshLab's GL_MODELVIEW/GL_PROJECTION as they are (pnpr_camera_matrices: perspective,
 *      orthographic and the off-centre tiles of MeshLab's "Save snapshot"),
 *   5. draws into MeshLab's bound framebuffer and viewport (composite REPLACE) and restores state.
 * The plugin holds no rendering decisions of its own: styles, their outline defaults, the plan
 * and the tone defaults come from the library. No C++ exception leaves the plugin: every entry
 * point catches everything. */
#include "decorate_pointnpr.h"
#include "decorate_glcontext.h"
#include "decorate_stages.h"
#include "decorate_stream.h"
#include "vcg_attributes.h"

#include <pointnpr/effects.h>
#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/look.h>
#include <pointnpr/options.h>
#include <pointnpr/plan.h>
#include <pointnpr/render.h>
#include <pointnpr/segment.h>
#include <pointnpr/style.h>
#include <pointnpr/tone.h>
#include <pointnpr/view.h>

#include <QApplication>
#include <QColor>
#include <QElapsedTimer>
#include <QDateTime>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QKeyEvent>
#include <QMainWindow>
#include <QProgressBar>
#include <QStatusBar>
#include <QLineEdit>
#include <QMouseEvent>
#include <QWheelEvent>
#include <QPushButton>
#include <QSpinBox>
#include <QPointer>
#include <QTimer>
#include <QWidget>


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <new>
#include <vector>

namespace {
using pnpr_meshlab::findAttribute;

/* Settings names. The style list grew (painterly): MeshLab keeps a saved RichEnum with its old
 * entries, so the style is stored under a new name (the old "PointNPR::Style" is ignored). */
const char *const kStyle = "PointNPR::DrawStyle";
const char *const kLook = "PointNPR::Look";
const char *const kVariant = "PointNPR::SketchVariant";
const char *const kBudget = "PointNPR::PointBudget";
const char *const kMotionBudget = "PointNPR::MotionBudget";
const char *const kDensity = "PointNPR::ScreenDensity";
const char *const kPaper = "PointNPR::PaperColor";
const char *const kLineWidth = "PointNPR::LineWidth";
const char *const kBrush = "PointNPR::Brush";
const char *const kBrushScale = "PointNPR::BrushScale";
const char *const kTam = "PointNPR::TonalArtMap";
const char *const kAbstraction = "PointNPR::Abstraction";
const char *const kStrokePx = "PointNPR::StrokeSize";
const char *const kOutline = "PointNPR::Outline";
const char *const kOutlineWidth = "PointNPR::OutlineWidth";
const char *const kToneSource = "PointNPR::ToneSource";
const char *const kToneGamma = "PointNPR::ToneGamma";
const char *const kEffects = "PointNPR::Effects";
const char *const kEffectsFile = "PointNPR::EffectsFile";
const char *const kStyleMapFile = "PointNPR::StyleMapFile";
const char *const kEffectsPreview = "PointNPR::EffectsPreview";
const char *const kStream = "PointNPR::StreamSamples";

/* enum index -> renderer style (the order shown in the dialog; new styles go at the end so that
 * saved indices keep their meaning). The labels are the library's names (pnpr_style_name). */
const pnpr_style kStyles[] = {PNPR_STYLE_POINTS, PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE,
                              PNPR_STYLE_CARTOON, PNPR_STYLE_LINES, PNPR_STYLE_PAINTERLY, PNPR_STYLE_BRUSH,
                              PNPR_STYLE_HIERARCHY};
const int kStyleCount = (int)(sizeof kStyles / sizeof kStyles[0]);
static_assert(sizeof kStyles / sizeof kStyles[0] == PNPR_STYLE_COUNT_, "every library style is offered");

/* enum index -> pnpr_draw_options.outline */
const int kOutlines[] = {0, 1, -1};
/* enum index = pnpr_tone_source (auto, colour, light, both) */
static_assert(PNPR_TONE_AUTO == 0 && PNPR_TONE_COLOR == 1 && PNPR_TONE_LIGHT == 2 && PNPR_TONE_BOTH == 3 &&
                  PNPR_TONE_SOURCE_COUNT_ == 4,
              "the tone source list of the dialog follows pnpr_tone_source");

using pnpr_meshlab::kWantNames;

/* While the camera moves: our draw's share of a frame. On this project's 2-core llvmpipe machine
 * MeshLab's own redraw of a 486k-point layer under ours takes about 60 ms: 40 ms of ours makes
 * about 10 frames/s (docs/meshlab.md, "Frame rates"). Never fewer points than kMotionMinPoints. */
const double kMotionDrawMs = 40;
const size_t kMotionMinPoints = 10000;
/* ... and the resolution of a moving frame of a style whose cost is in the pixels */
const float kMotionPreviewScale = 0.5f;

/* The layers the decorator draws: visible, with vertices, not a polyline layer (edges: the profile
 * lines the filter makes, drawn by the lines style from the features). A mesh layer (an RGB-D
 * PLY with a range grid opens as one) is drawn as its vertices. */
bool isDrawnLayer(const MeshModel *mm)
{
    return mm && mm->isVisible() && mm->cm.vn > 0 && mm->cm.en == 0;
}

struct Hash {
    uint64_t h = 1469598103934665603ull;
    void bytes(const void *p, size_t n)
    {
        const unsigned char *c = static_cast<const unsigned char *>(p);
        for (size_t i = 0; i < n; i++) { h ^= c[i]; h *= 1099511628211ull; }
    }
    template <class T> void add(const T &v) { bytes(&v, sizeof v); }
};

/* Which layers are drawn and what they hold: ids, counts, array address, Tr, colour/attribute
 * presence and up to 1024 sampled vertices (positions, normals, colours, feature classes). A change
 * inside a large layer that touches none of the samples is not seen (docs/meshlab.md). */
uint64_t layerSignature(MeshDocument &md)
{
    Hash h;
    for (MeshModel *mm : md.meshList) {
        if (!isDrawnLayer(mm)) continue;
        CMeshO &m = mm->cm;
        h.add(mm->id());
        h.add(m.vn);
        h.add(m.vert.size());
        const void *data = m.vert.empty() ? nullptr : (const void *)&m.vert[0];
        h.add(data);
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) h.add(m.Tr[r][c]);
        bool colour = mm->hasDataMask(MeshModel::MM_VERTCOLOR);
        h.add(colour);
        CMeshO::PerVertexAttributeHandle<float> hc;
        bool hasClass = findAttribute<float>(m, PNPR_PROP_FEATURE_CLASS, hc);
        CMeshO::PerVertexAttributeHandle<float> hs;
        bool hasSeg = findAttribute<float>(m, PNPR_PROP_SEGMENT, hs);
        h.add(hasClass);
        h.add(hasSeg);
        size_t n = m.vert.size(), step = std::max<size_t>(1, n / 1024);
        for (size_t i = 0; i < n; i += step) {
            const CVertexO &v = m.vert[i];
            h.add(v.IsD());
            h.add(v.cP()[0]); h.add(v.cP()[1]); h.add(v.cP()[2]);
            h.add(v.cN()[0]); h.add(v.cN()[1]); h.add(v.cN()[2]);
            if (colour) h.add(v.cC());
            if (hasClass) h.add(hc[i]);
            if (hasSeg) h.add(hs[i]);
        }
    }
    return h.h;
}

QString status(pnpr_status st, const pnpr_error &err)
{
    return err.message[0] ? QString::fromUtf8(err.message) : QString::fromUtf8(pnpr_status_string(st));
}

/* Feature classes of some layers, when not every layer has them: the plan computes classes for
 * the merged cloud, then these replace the computed ones at the points of those layers. */
struct OwnClasses {
    std::vector<uint8_t> has, cls; /* per point: from a layer with classes; its class */
    std::vector<float> dir;        /* its direction (3 per point), in scene coordinates */
    QString layers;                /* "'a.ply', 'b.ply'" */
};

} // namespace

/* Everything the plugin keeps for one GL context. */
struct DecorateContextState {
    pnpr_renderer *renderer = nullptr;
    bool failed = false;          /* renderer could not be created: logged once, nothing drawn */
    pnpr_cloud cloud;             /* the merged layers plus what the plans computed on them: the
                                   * cache of features, normals and segments (the next plan sees
                                   * them and wants nothing more) */
    pnpr_polylines lines;         /* profile lines for the lines style */
    bool linesReady = false;
    bool linesPending = false;    /* lines computed, not yet handed to the renderer */
    uint64_t signature = 0;
    bool built = false;           /* cloud holds the layers of `signature` */
    bool needUpload = false;      /* the renderer does not have the cloud as it is now */
    bool skippedPainterly = false; /* uploaded without painterly's data (no frame painted) */
    bool keyedUpload = false;     /* uploaded with the layer index as the style maps' key */
    QString lastLayerStyles;      /* the styles per layer logged last */
    bool testStylesSet = false;   /* test hook PNPR_MESHLAB_TEST_LAYER_STYLES applied */
    bool testClassSet = false;    /* test hook PNPR_MESHLAB_TEST_LAYER_CLASS applied */
    bool testSampleSet = false;   /* test hook PNPR_MESHLAB_TEST_SAMPLE_OF applied */
    bool testWheelDone = false;   /* test hook PNPR_MESHLAB_TEST_WHEEL applied */
    int infoStage = 0, infoFrames = 0; /* test hook PNPR_MESHLAB_TEST_INFOBOX: 0 undrawn frame next, 1 drawn, 2 done */
    int dragPhase = 0;            /* test hook PNPR_MESHLAB_TEST_DRAG: 1 dragging, 2 released, 3 done */
    int dragFrames = 0;
    size_t dragPoints = 0;
    QElapsedTimer dragClock;
    qint64 dragReleaseMs = 0, dragDrawMs = 0;
    double motionMsPerPoint = 0;  /* our draw's time per point in the last moving frames (running mean) */
    int slowFrames = 0;           /* moving frames in a row over 1.25 kMotionDrawMs at the timed budget (2: preview) */
    uint32_t slowBits = 0;        /*   ... for these styles */
    uint64_t slowSignature = 0;   /*   ... and these layers */
    int dragPreviews = 0;         /* test hook PNPR_MESHLAB_TEST_DRAG: frames drawn as previews */
    bool uploadFailed = false;    /* not retried until the layers change */
    QString layersNote;           /* what buildCloud found, for the upload message */
    qint64 layersMs = 0;          /* how long reading the layers took */
    bool layerFeatures = false;   /* classes/directions came from the layers' attributes */
    OwnClasses ownClasses;        /* some layers' own classes (not every layer has them) */
    bool ownFeatures = false;     /* feature properties computed here (not from the layers) */
    bool ownDither = false;       /*   ... with dithering points, */
    int ditherToneSource = 0;     /*   ... for this tone */
    float ditherToneGamma = 0;
    uint32_t failedWant = 0;      /* a feature computation that failed (not retried every frame, */
    int failedToneSource = 0;     /*   only when the tone changes: a bad gamma fails it) */
    float failedToneGamma = 0;
    bool jsegFailed = false;
    bool brushFailed = false;     /* the brush stage failed on these layers: not retried every frame */
    pnpr_sphere_tree tree;        /* the hierarchy style's sphere tree of these layers (treeReady) */
    bool treeReady = false, treeFailed = false;
    double up[3] = {0, 0, 1};     /* the scene's up (pnpr_scene_frame): where the tone's key light is */
    QString lastPlan;             /* the request whose plan was logged last */
    QString lastError;            /* the last message logged (not repeated every frame) */
    double lastMV[16] = {0}, lastP[16] = {0};
    bool haveLast = false;
    pnpr_camera_matrices restCam = {}; /* the last on-screen frame at rest: the view the tiles' queue is planned for */
    int restW = 0, restH = 0;     /* ... and its viewport (0: none yet) */
    double screenScale = 0;       /* |P[0]| of the last on-screen frame: a tile's over it is the multiplier */
    double snapK = 0;             /* > 0 while MeshLab draws snapshot tiles: their multiplier */
    int uploads = 0;              /* clouds uploaded in this state (the log says so after a restart) */
    bool restarted = false;       /* MeshLab restarted the decoration: kept (startDecorate) */
    int framesDrawn = 0;          /* frames drawn in this state (test hook PNPR_MESHLAB_TEST_RESTART) */
    QPointer<QWidget> widget;     /* the GL widget, for the repaint after camera motion */
    QTimer *settle = nullptr;     /* full-budget repaint after motion stops */
    int frames = 0;
    bool snapshotDone = false;
    std::unique_ptr<pnpr_meshlab::StageJob> job; /* the plan's stages running on a worker thread */
    bool cancelled = false;       /* the last computation was cancelled: plain points until the
                                   * layers change or the decoration is turned off and on */
    bool cancelRequested = false; /* Esc pressed while computing */
    QTimer *poll = nullptr;       /* while computing: progress bar, status line, repaint when done */
    QPointer<QObject> keys;       /* while computing: Esc on the application cancels */
    int pollTicks = 0, barUpdates = 0; /* event-loop ticks and progress shown during the computation */
    QElapsedTimer synthetic;      /* test hook PNPR_MESHLAB_TEST_EVENTS: when its event was posted */
    pnpr_effect_pipeline fx;      /* the effects pipeline of fxKey (count 0: none or it failed) */
    QString fxKey;                /* the preset or file (with its modification time) fx holds */
    pnpr_style_map smap;          /* the style map file of smapKey (count 0 and no default: none) */
    QString smapKey;
    std::vector<unsigned char> fxPixels, fxRows; /* the effects frame, top row first / bottom first */
    std::vector<std::unique_ptr<pnpr_meshlab::LayerStream>> streams; /* the sample layers streamed by the view */
    std::unique_ptr<pnpr_meshlab::StreamJob> streamJob; /* the view's read running (one at a time) */
    uint64_t streamGen = 0;       /* a stream taken over or dropped: the layers are merged again */
    uint64_t layersSig = 0;       /* layerSignature of the layers merged (the stream's part left out) */
    float toneRadius = 0;         /* the streams' estimate of their files' mean spacing (buildCloud; 0: none) */
    bool uploaded = false;        /* the renderer holds an upload of the layers of uploadedLayersSig */
    uint64_t uploadedLayersSig = 0; /* (the streams' part left out) for the styles of uploadedStyles */
    uint32_t uploadedStyles = 0;
    bool drawPrevious = false;    /* merged again for a stream alone: while the stages run on the new
                                   * sample, the renderer's previous one is drawn (not MeshLab's points) */
    bool streamBusy = false;      /* a stream runs or a layer's view is not read yet (the snapshot hook waits) */
    QTimer *streamPoll = nullptr; /* while a stream runs: the status line, a repaint when done */
    DecorateContextState()
    {
        std::memset(&cloud, 0, sizeof cloud);
        std::memset(&lines, 0, sizeof lines);
        std::memset(&fx, 0, sizeof fx);
        std::memset(&tree, 0, sizeof tree);
        std::memset(&smap, 0, sizeof smap);
    }
};

DecoratePointnprPlugin::DecoratePointnprPlugin()
{
    typeList << DP_NPR_RENDER;
    for (FilterIDType tt : types()) actionList << new QAction(decorationName(tt), this);
    for (QAction *ap : actionList) ap->setCheckable(true);
    /* Test-only: turn the decoration on once MeshLab shows a document (tests/meshlab/run.sh). */
    if (std::getenv("PNPR_MESHLAB_DECORATE_AT_START")) {
        startupTimer_ = new QTimer(this);
        startupTimer_->setInterval(250);
        connect(startupTimer_, &QTimer::timeout, this, [this] { testStartupPoll(); });
        startupTimer_->start();
    }
}

/* Frees one context's state: the renderer properly when its context is current (else its GL
 * objects went, or go, with the context; only the CPU side is freed). */
static void freeState(DecorateContextState *s, void *ctx)
{
    s->job.reset(); /* cancels the computation and waits for it */
    s->streamJob.reset(); /* cancels the stream's read and waits for it */
    delete s->streamPoll;
    delete s->poll;
    delete s->keys.data();
    if (s->renderer && pnpr_meshlab::currentGLContext() == ctx) pnpr_renderer_destroy(s->renderer);
    pnpr_cloud_free(&s->cloud);
    pnpr_sphere_tree_free(&s->tree);
    pnpr_lines_free(&s->lines);
    pnpr_effect_pipeline_free(&s->fx);
    pnpr_style_map_free(&s->smap);
    delete s->settle;
    delete s;
}

DecoratePointnprPlugin::~DecoratePointnprPlugin()
{
    /* Renderers whose context is current are destroyed properly; the others' GL objects went
     * (or go) with their context, only the CPU side is freed. */
    for (auto it = states_.begin(); it != states_.end(); ++it) freeState(it.value(), it.key());
    states_.clear();
}

void DecoratePointnprPlugin::testStartupPoll()
{
    try {
        if (++startupTicks_ > 240) { startupTimer_->stop(); return; } /* give up after 60 s */
        bool area = false;
        for (QWidget *w : QApplication::allWidgets())
            if (std::strcmp(w->metaObject()->className(), "GLArea") == 0 && w->isVisible()) area = true;
        const int kSettleTicks = 6; /* 1.5 s with a visible GLArea: the command-line mesh is loaded */
        if (!area) { seenTicks_ = 0; return; }
        if (++seenTicks_ < kSettleTicks) return;
        QAction *a = actionList.isEmpty() ? nullptr : actionList.first();
        if (!a || !a->isEnabled()) return;
        startupTimer_->stop();
        std::fprintf(stderr, "pointnpr decorator: enabling 'NPR render' (PNPR_MESHLAB_DECORATE_AT_START)\n");
        a->trigger();
    } catch (...) {
        if (startupTimer_) startupTimer_->stop();
    }
}

QString DecoratePointnprPlugin::pluginName() const { return "DecoratePointNPR"; }

QString DecoratePointnprPlugin::decorationName(FilterIDType id) const
{
    return id == DP_NPR_RENDER ? QString("NPR render") : QString();
}

QString DecoratePointnprPlugin::decorationInfo(FilterIDType id) const
{
    if (id != DP_NPR_RENDER) return QString();
    QStringList names;
    for (pnpr_style st : kStyles) names << QString::fromUtf8(pnpr_style_name(st));
    return tr("Draws the visible point layers (no faces, no edges) as a non-photorealistic rendering "
              "(pointnpr: %1) over the viewport. What a style needs (features, normals for outlines and "
              "shading, JSEG segments for the cartoon, profile lines) is computed once per layer change, "
              "as the library's stage planner says; feature classes from 'NPR: Compute feature degree and "
              "classify points' and segments from the segmentation filters are used when every layer has "
              "them.").arg(names.join(", "));
}

int DecoratePointnprPlugin::getDecorationClass(QAction *) const
{
    return MeshDecorateInterface::PerDocument; /* GLArea::updateDecorator compares with ==: no other bits */
}

namespace {

/* "lines 2.5 px, cartoon 2.5 px": the styles with an outline by default and its
 * width, as the library says (pnpr_style_outline_default). */
QString outlineDefaults()
{
    QStringList on;
    for (pnpr_style st : kStyles) {
        float w = 0;
        if (pnpr_style_outline_default(st, &w)) on << QString("%1 %2 px").arg(pnpr_style_name(st)).arg(w);
    }
    return on.join(", ");
}

} // namespace

namespace {
/* The entry `name` of one of the library's option tables (options.h): the dialog's defaults and
 * ranges, no numeric default of these options is written in this file. */
const pnpr_option_desc *tableOption(const pnpr_option_desc *(*table)(size_t *), const char *name)
{
    size_t n = 0;
    const pnpr_option_desc *t = table(&n);
    return pnpr_option_find(t, n, name);
}

const pnpr_option_desc *drawOption(const char *name) { return tableOption(pnpr_draw_option_table, name); }
const pnpr_option_desc *hierOption(const char *name) { return tableOption(pnpr_hier_option_table, name); }

QString rangeText(const pnpr_option_desc *d)
{
    char buf[64];
    pnpr_option_range_text(d, buf, sizeof buf);
    return QString::fromUtf8(buf);
}

QString drawRange(const char *name) { return rangeText(drawOption(name)); }

/* A hierarchy option's tooltip: the table's help and range. */
QString hierTip(const char *name)
{
    const pnpr_option_desc *d = hierOption(name);
    return QString("%1, %2").arg(QString::fromUtf8(d->help)).arg(rangeText(d));
}
} // namespace

void DecoratePointnprPlugin::initGlobalParameterSet(QAction *, RichParameterList &par)
{
    try {
        /* The panel's order (MeshLab shows the parameters as added; the settings names are what is
         * saved): the Look, the look's own parameters (style, paper, outline, line width), then the
         * groups (budget, tone, each style's own, effects; the tooltips say which style). Labels of at
         * most 15 characters: MeshLab sizes the label column by the longest, and a longer one pushed
         * the paper colour's swatch out of the panel. */
        if (!par.hasParameter(kLook)) {
            size_t n = 0;
            const pnpr_look *looks = pnpr_looks(&n);
            QStringList names("custom (the parameters below)");
            QString tip = "a finished look from the library (pointnpr render --look): it sets the style and, where "
                          "the parameters below are at their defaults, the outline, widths, ink and paper";
            for (size_t i = 0; i < n; i++) {
                names << QString::fromUtf8(looks[i].name);
                tip += QString("; %1: %2").arg(looks[i].name).arg(looks[i].description);
            }
            par.addParam(RichEnum(kLook, 0, names, "Look", tip));
        }
        if (!par.hasParameter(kStyle)) {
            QStringList names;
            for (pnpr_style st : kStyles) names << QString::fromUtf8(pnpr_style_name(st));
            par.addParam(RichEnum(kStyle, 1, names, "Style",
                                  "points: plain splats; sketchy: strokes along feature directions and hatches; "
                                  "stipple: ink dots; cartoon: flat colours (segments) and outlines; lines: profile "
                                  "lines and outlines; painterly: brush dabs in the points' colours; brush: stroke-based "
                                  "splatting, brush strokes on surface-aligned splats (colour clusters are computed "
                                  "the first time); hierarchy: Chi & Lee's painterly strokes over a sphere hierarchy "
                                  "of colour regions (built the first time)"));
        }
        if (!par.hasParameter(kStyleMapFile))
            par.addParam(RichOpenFile(kStyleMapFile, QString(), QStringList() << "*.txt" << "*",
                                      "Style map", "a style per segment (as pointnpr render --style-map): lines "
                                      "'LABEL STYLE' for the layers' segment labels and '* STYLE' for the others; "
                                      "empty: none. It takes precedence over the layers' own styles"));
        if (!par.hasParameter(kPaper))
            par.addParam(RichColor(kPaper, QColor(255, 255, 255), "Paper colour", "background of the drawing"));
        if (!par.hasParameter(kOutline))
            par.addParam(RichEnum(kOutline, 0, QStringList() << "style default" << "on" << "off", "Outline",
                                  QString("silhouettes and occluding contours, drawn in image space (normals are "
                                          "computed for them when the layers have none). Style default: on for %1; "
                                          "off for the others (points and painterly draw none)")
                                      .arg(outlineDefaults())));
        if (!par.hasParameter(kOutlineWidth))
            par.addParam(RichFloat(kOutlineWidth, 0.0f, "Outline width",
                                   QString("outline width in pixels, %1; 0 = the style's default (%2)")
                                       .arg(drawRange("outline-width"))
                                       .arg(outlineDefaults())));
        if (!par.hasParameter(kLineWidth))
            par.addParam(RichFloat(kLineWidth, static_cast<float>(drawOption("line-width")->def), "Line width",
                                   QString("profile lines and sketch strokes, pixels, %1").arg(drawRange("line-width"))));
        if (!par.hasParameter(kDensity))
            par.addParam(RichFloat(kDensity, static_cast<float>(drawOption("density")->def), "Screen density",
                                   QString("%1, %2; negative = every point, however dense the view")
                                       .arg(drawOption("density")->help)
                                       .arg(drawRange("density"))));
        if (!par.hasParameter(kBudget))
            par.addParam(RichInt(kBudget, 0, "Point budget", "at most this many points per frame (continuous "
                                 "resolution queue prefix); 0 = no count (the screen density still limits them)"));
        if (!par.hasParameter(kMotionBudget))
            par.addParam(RichInt(kMotionBudget, 200000, "Moving budget",
                                 "budget of frames drawn while the camera changes (a full frame follows 0.3 s "
                                 "after the motion stops); 0 = same as the point budget"));
        if (!par.hasParameter(kToneSource))
            par.addParam(RichEnum(kToneSource, 0, QStringList() << "auto" << "colour" << "light" << "both", "Tone source",
                                  "what makes a point dark (density of the dithering points: sketchy hatches, stipple "
                                  "dots): its colour, a key light from above on its normals, or both; auto = both "
                                  "with colours and normals, light without colours"));
        if (!par.hasParameter(kToneGamma))
            par.addParam(RichFloat(kToneGamma, 0.0f, "Tone gamma",
                                   "tone curve exponent (> 1 keeps large mid-tone areas light, the darkest parts "
                                   "dark); 0 = library default"));
        if (!par.hasParameter(kVariant))
            par.addParam(RichEnum(kVariant, 0, QStringList() << "all (strokes + hatches)" << "directional strokes only"
                                                             << "strokes + non-directional hatches",
                                  "Sketch variant", "sketchy style: which primitives are drawn"));
        if (!par.hasParameter(kBrush)) {
            size_t np = 0;
            const pnpr_brush_preset *bp = pnpr_brush_presets(&np);
            QStringList names;
            QString tip = "brush style: the brush";
            for (size_t i = 0; i < np; i++) {
                names << QString::fromUtf8(bp[i].name);
                tip += QString("; %1: %2").arg(bp[i].name).arg(bp[i].description);
            }
            par.addParam(RichEnum(kBrush, 0, names, "Brush", tip));
        }
        if (!par.hasParameter(kBrushScale))
            par.addParam(RichFloat(kBrushScale, static_cast<float>(drawOption("brush-scale")->def), "Brush scale",
                                   QString("brush style: %1, %2").arg(drawOption("brush-scale")->help).arg(drawRange("brush-scale"))));
        if (!par.hasParameter(kTam)) {
            QStringList names;
            for (int k = 0; k < PNPR_TAM_COUNT_; k++) names << QString::fromUtf8(pnpr_tam_name((pnpr_tam_kind)k));
            par.addParam(RichEnum(kTam, 0, names, "Tonal art map",
                                  "hierarchy style: paint (coloured dabs), hatch (pencil hatching in ink), dots (halftone)"));
        }
        if (!par.hasParameter(kAbstraction))
            par.addParam(RichFloat(kAbstraction, static_cast<float>(hierOption("hier-abstraction")->def), "Abstraction",
                                   hierTip("hier-abstraction")));
        if (!par.hasParameter(kStrokePx))
            par.addParam(RichFloat(kStrokePx, static_cast<float>(hierOption("stroke-px")->def), "Stroke size",
                                   hierTip("stroke-px")));
        if (!par.hasParameter(kEffects)) {
            QStringList names;
            names << "none";
            int np = 0;
            const pnpr_effect_preset *pr = pnpr_effect_presets(&np);
            QString docs;
            for (int i = 0; i < np; i++) {
                names << QString::fromUtf8(pr[i].name);
                docs += QString("; %1: %2").arg(QString::fromUtf8(pr[i].name)).arg(QString::fromUtf8(pr[i].doc));
            }
            names << "pipeline file";
            par.addParam(RichEnum(kEffects, 0, names, "Effects",
                                  "segment-specific image-space effects (Wegen et al., docs/effects.md) over the "
                                  "style: a preset for every point, or a pipeline file (effect chains per segment "
                                  "label, as `pointnpr render --effects`)" + docs));
        }
        if (!par.hasParameter(kEffectsFile))
            par.addParam(RichOpenFile(kEffectsFile, QString(), QStringList() << "*.fx" << "*.txt" << "*",
                                      "Effects file", "the pipeline file read when the effects are 'pipeline "
                                      "file' (read again when it changes)"));
        if (!par.hasParameter(kStream))
            par.addParam(RichBool(kStream, true, "Stream samples",
                                  "a layer opened by 'NPR: Open a sample of a large PLY' from a file ordered for drawing "
                                  "(pointnpr convert --lod) is read again for each view the camera rests at, as many "
                                  "points as the layer holds: near points kept, far and unseen ones thinned (the layer "
                                  "itself is not changed); off: the layer's own points"));
        if (!par.hasParameter(kEffectsPreview))
            par.addParam(RichFloat(kEffectsPreview, 0.5f, "Effects preview",
                                   QString("effects layers at this fraction of the viewport while the camera moves "
                                           "(%1..1; the full frame follows when it rests)").arg((double)PNPR_EFFECTS_SCALE_MIN)));
    } catch (...) {
    }
}

/* MeshLab ends and restarts every decoration when a parameter of the dialog is applied and after
 * every filter (GLArea::updateAllDecorators: endDecorate, then startDecorate at once). The state
 * of a context (the merged layers, their features and segments, the uploaded cloud) survives
 * such a restart: endDecorate only marks it, and it is dropped on the next turn of the event loop
 * unless startDecorate came first (the decoration was turned off). What changed is found as on
 * any frame: the layers' signature, the plan, the parameters. */
bool DecoratePointnprPlugin::startDecorate(QAction *, MeshDocument &, const RichParameterList *, GLArea *)
{
    try {
        for (void *ctx : ending_) {
            DecorateContextState *s = states_.value(ctx, nullptr);
            if (s) s->restarted = true;
        }
        ending_.clear();
    } catch (...) {
    }
    return true; /* the renderer is made on the first frame, in the context that draws it */
}

void DecoratePointnprPlugin::endDecorate(QAction *, MeshDocument &, const RichParameterList *, GLArea *)
{
    try {
        void *ctx = pnpr_meshlab::currentGLContext();
        if (!ctx || !states_.contains(ctx)) return;
        ending_.insert(ctx);
        QPointer<QWidget> w = pnpr_meshlab::currentGLWidget();
        QTimer::singleShot(0, this, [this, ctx, w] {
            try {
                if (!ending_.remove(ctx)) return; /* restarted: kept */
                if (w) pnpr_meshlab::makeWidgetCurrent(w); /* so that the renderer's GL objects go too */
                dropState(ctx);
            } catch (...) {
            }
        });
    } catch (...) {
    }
}

void DecoratePointnprPlugin::dropState(void *ctx)
{
    ending_.remove(ctx);
    DecorateContextState *s = states_.take(ctx);
    if (s) freeState(s, ctx);
}

void DecoratePointnprPlugin::decorateDoc(QAction *, MeshDocument &md, const RichParameterList *par,
                                         GLArea *, QPainter *, GLLogStream &lg)
{
    try {
        draw(md, par, lg);
    } catch (const std::bad_alloc &) {
        lg.Logf(GLLogStream::WARNING, "NPR render: out of memory");
    } catch (...) {
        lg.Logf(GLLogStream::WARNING, "NPR render: unexpected error");
    }
}

namespace {

/* Parameters with fallbacks (a missing parameter never throws into MeshLab). */
struct Params {
    pnpr_style style = PNPR_STYLE_SKETCHY;
    const pnpr_look *look = nullptr; /* a library look chosen: it sets the style (and fills defaults) */
    pnpr_sketch_variant variant = PNPR_SKETCH_ALL;
    int budget = 0, motionBudget = 200000;
    float density = 0;        /* 0 = the library's default (pnpr_draw_option_table), < 0 = none */
    QColor paper = QColor(255, 255, 255);
    float lineWidth = 0;      /* 0 = the library's default (pnpr_draw_option_table) */
    int brush = 0;            /* pnpr_brush_presets index */
    float brushScale = 0;     /* 0 = the library's default */
    int tam = 0;              /* pnpr_tam_kind */
    float abstraction = 0;    /* 0 = the library's default (pnpr_hier_option_table) */
    float strokePx = 0;       /* 0 = the library's default */
    int outline = 0;          /* pnpr_draw_options.outline */
    float outlineWidth = 0;   /* 0 = the style's default */
    pnpr_tone_source toneSource = PNPR_TONE_AUTO;
    float toneGamma = 0;      /* 0 = the library's default */
    QString effects;          /* "" none, a preset's name, or "file:PATH" */
    QString styleMap;         /* "" none, or the style map file's path */
    float effectsPreview = 0.5f;
    bool stream = true;       /* sample layers streamed by the view (decorate_stream.h) */
};

Params readParams(const RichParameterList *par)
{
    Params p;
    if (par) {
        if (par->hasParameter(kStyle)) {
            int i = par->getEnum(kStyle);
            if (i >= 0 && i < kStyleCount) p.style = kStyles[i];
        }
        if (par->hasParameter(kVariant)) {
            int v = par->getEnum(kVariant);
            if (v >= 0 && v < (int)PNPR_SKETCH_COUNT_) p.variant = (pnpr_sketch_variant)v;
        }
        if (par->hasParameter(kBudget)) p.budget = std::max(0, par->getInt(kBudget));
        if (par->hasParameter(kMotionBudget)) p.motionBudget = std::max(0, par->getInt(kMotionBudget));
        if (par->hasParameter(kDensity)) p.density = par->getFloat(kDensity);
        if (par->hasParameter(kPaper)) p.paper = par->getColor(kPaper);
        if (par->hasParameter(kLineWidth)) p.lineWidth = par->getFloat(kLineWidth);
        if (par->hasParameter(kBrush)) p.brush = std::max(0, std::min(PNPR_BRUSH_PRESET_COUNT - 1, par->getEnum(kBrush)));
        if (par->hasParameter(kBrushScale)) p.brushScale = par->getFloat(kBrushScale);
        if (par->hasParameter(kTam)) p.tam = std::max(0, std::min((int)PNPR_TAM_COUNT_ - 1, par->getEnum(kTam)));
        if (par->hasParameter(kAbstraction)) p.abstraction = par->getFloat(kAbstraction);
        if (par->hasParameter(kStrokePx)) p.strokePx = par->getFloat(kStrokePx);
        if (par->hasParameter(kOutline)) {
            int i = par->getEnum(kOutline);
            if (i >= 0 && i < 3) p.outline = kOutlines[i];
        }
        /* out-of-range values go to the library, which refuses them with its own message */
        if (par->hasParameter(kOutlineWidth)) p.outlineWidth = par->getFloat(kOutlineWidth);
        if (par->hasParameter(kToneSource)) {
            int i = par->getEnum(kToneSource);
            if (i >= 0 && i < (int)PNPR_TONE_SOURCE_COUNT_) p.toneSource = (pnpr_tone_source)i;
        }
        if (par->hasParameter(kToneGamma)) p.toneGamma = par->getFloat(kToneGamma);
        if (par->hasParameter(kEffects)) {
            int i = par->getEnum(kEffects), np = 0;
            const pnpr_effect_preset *pr = pnpr_effect_presets(&np);
            if (i >= 1 && i <= np) p.effects = QString::fromUtf8(pr[i - 1].name);
            else if (i == np + 1 && par->hasParameter(kEffectsFile)) p.effects = "file:" + par->getOpenFileName(kEffectsFile);
        }
        if (par->hasParameter(kEffectsPreview)) p.effectsPreview = par->getFloat(kEffectsPreview);
        if (par->hasParameter(kStyleMapFile)) p.styleMap = par->getOpenFileName(kStyleMapFile);
        if (par->hasParameter(kStream)) p.stream = par->getBool(kStream);
    }
    if (!(p.effectsPreview >= PNPR_EFFECTS_SCALE_MIN && p.effectsPreview <= 1)) p.effectsPreview = 0.5f;
    if (!pnpr_option_in_range(drawOption("line-width"), p.lineWidth)) p.lineWidth = 0; /* the default */
    if (!(p.density < 0) && !pnpr_option_in_range(drawOption("density"), p.density)) p.density = 0; /* NaN too */
    if (!pnpr_option_in_range(drawOption("brush-scale"), p.brushScale)) p.brushScale = 0;
    /* abstraction: a negative value is "none" (NEGATIVE_OFF); out of range otherwise: the default */
    if (p.abstraction > 0 && !pnpr_option_in_range(hierOption("hier-abstraction"), p.abstraction)) p.abstraction = 0;
    if (!pnpr_option_in_range(hierOption("stroke-px"), p.strokePx)) p.strokePx = 0;
    if (par && par->hasParameter(kLook)) {
        size_t n = 0;
        const pnpr_look *looks = pnpr_looks(&n);
        int i = par->getEnum(kLook);
        if (i >= 1 && (size_t)i <= n) p.look = &looks[i - 1];
    }
    if (p.look) { /* the look's style; its variant and outline where the dialog's are at their defaults
                   * (the library's rule, pnpr_look_apply: the plan needs them before the frame) */
        pnpr_draw_options lo;
        std::memset(&lo, 0, sizeof lo);
        lo.sketch_variant = p.variant;
        lo.outline = p.outline;
        pnpr_look_apply(p.look, &lo);
        p.style = lo.style;
        p.variant = lo.sketch_variant;
        p.outline = lo.outline;
    }
    /* test-only override (tests/meshlab/run.sh): the style by name */
    if (const char *s = std::getenv("PNPR_MESHLAB_TEST_STYLE")) {
        pnpr_style st;
        if (pnpr_style_from_name(s, &st) == PNPR_OK) p.style = st;
    }
    if (const char *m = std::getenv("PNPR_MESHLAB_TEST_STYLE_MAP")) p.styleMap = QString::fromLocal8Bit(m);
    if (const char *e = std::getenv("PNPR_MESHLAB_TEST_EFFECTS")) /* a preset's name or file:PATH */
        p.effects = QString::fromLocal8Bit(e);
    return p;
}

/* Whether a layer's normals mean something: at least 99% of its finite vertices carry a finite,
 * non-zero normal (the features filter's rule; a point cloud read without normals holds zeros). */
bool meaningfulNormals(MeshModel *mm)
{
    if (!mm->hasDataMask(MeshModel::MM_VERTNORMAL)) return false;
    size_t finite = 0, good = 0;
    for (const CVertexO &v : mm->cm.vert) {
        if (v.IsD()) continue;
        if (!(std::isfinite(v.cP()[0]) && std::isfinite(v.cP()[1]) && std::isfinite(v.cP()[2]))) continue;
        finite++;
        const Point3m &n = v.cN();
        double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        good += (std::isfinite(len) && len > 1e-12);
    }
    return good > 0 && good >= finite - finite / 100;
}

/* What buildCloud reads from one layer's attributes. Attributes the filter stamped for an older
 * version of the layer (File > Reload, a filter that moved the vertices) are left out. */
struct LayerAttributes {
    CMeshO::PerVertexAttributeHandle<float> cls, seg;
    CMeshO::PerVertexAttributeHandle<Point3m> dir;
    bool hasClass = false, hasSeg = false, stale = false;
    LayerAttributes() = default;
    explicit LayerAttributes(CMeshO &m)
    {
        stale = pnpr_meshlab::checkStamp(m) == pnpr_meshlab::StampState::Stale;
        if (stale) return;
        hasClass = findAttribute<float>(m, PNPR_PROP_FEATURE_CLASS, cls) && findAttribute<Point3m>(m, PNPR_PROP_FEATURE_DIR, dir);
        hasSeg = findAttribute<float>(m, PNPR_PROP_SEGMENT, seg);
    }
};

/* One point as buildCloud merges it, in the layer's coordinates (before its Tr). */
struct PointIn {
    double p[3], n[3], dir[3];
    uint8_t rgb[3];
    float cls, seg, spacing;
};

/* One drawn layer's points: MeshLab's vertices, or its stream (a view's sample of the file the
 * layer samples, decorate_stream.h), whose positions are the file's less the layer's origin, in
 * double. */
struct LayerPoints {
    MeshModel *mm = nullptr;
    const pnpr_meshlab::LayerStream *stream = nullptr;
    mutable LayerAttributes attrs; /* vcglib's handles read through non-const operator[] */
    size_t count = 0;
    bool colour = false, normals = false; /* normals: a stream's (a layer's are judged by meaningfulNormals) */
    const pnpr_property *cls = nullptr, *dir[3] = {nullptr, nullptr, nullptr};
    const pnpr_property *spacing = nullptr; /* a stream's stored spacing (float), grown by its share */

    LayerPoints(MeshModel *m, const pnpr_meshlab::LayerStream *st) : mm(m), stream(st && st->cloud.count ? st : nullptr)
    {
        if (stream) {
            const pnpr_cloud &c = stream->cloud;
            count = c.count;
            colour = c.rgb != nullptr;
            normals = c.normal != nullptr;
            cls = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_CLASS);
            dir[0] = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_DIR_X);
            dir[1] = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_DIR_Y);
            dir[2] = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_DIR_Z);
            attrs.hasClass = cls && dir[0] && dir[1] && dir[2];
            attrs.hasSeg = c.label != nullptr;
            spacing = pnpr_cloud_find_property(&c, PNPR_PROP_POINT_SPACING);
            if (spacing && spacing->type != PNPR_TYPE_FLOAT32) spacing = nullptr;
            return;
        }
        count = (size_t)mm->cm.vn;
        colour = mm->hasDataMask(MeshModel::MM_VERTCOLOR);
        attrs = LayerAttributes(mm->cm);
    }
    size_t entries() const { return stream ? stream->cloud.count : mm->cm.vert.size(); }
    /* Point i (of entries()), false for a deleted vertex. */
    bool read(size_t i, PointIn &r) const
    {
        if (stream) {
            const pnpr_cloud &c = stream->cloud;
            double w[3];
            pnpr_cloud_world(&c, i, w);
            for (int a = 0; a < 3; a++) {
                r.p[a] = w[a] - stream->origin[a];
                r.n[a] = normals ? c.normal[3 * i + a] : 0;
                r.dir[a] = attrs.hasClass ? pnpr_type_get(dir[a]->type, dir[a]->data, i) : 0;
                r.rgb[a] = colour ? c.rgb[3 * i + a] : 180;
            }
            r.cls = attrs.hasClass ? (float)pnpr_type_get(cls->type, cls->data, i) : 0;
            r.seg = attrs.hasSeg && c.label[i] < 16777216u ? (float)c.label[i] : 0;
            r.spacing = spacing ? ((const float *)spacing->data)[i] : 0;
            return true;
        }
        const CVertexO &v = mm->cm.vert[i];
        if (v.IsD()) return false;
        for (int a = 0; a < 3; a++) {
            r.p[a] = v.cP()[a];
            r.n[a] = v.cN()[a];
            r.dir[a] = attrs.hasClass ? attrs.dir[i][a] : 0;
            r.rgb[a] = colour ? v.cC()[a] : 180;
        }
        r.cls = attrs.hasClass ? attrs.cls[i] : 0;
        r.seg = attrs.hasSeg ? attrs.seg[i] : 0;
        r.spacing = 0;
        return true;
    }
};

/* Writes the layers' own classes and directions over the computed ones (finishJob). */
static void applyOwnClasses(pnpr_cloud &cloud, const OwnClasses &own)
{
    if (own.has.size() != cloud.count) return;
    pnpr_property *pc = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_CLASS);
    pnpr_property *pd[3] = {pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_X),
                            pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Y),
                            pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Z)};
    if (!pc || pc->type != PNPR_TYPE_UINT8 || !pd[0] || !pd[1] || !pd[2]) return;
    for (int a = 0; a < 3; a++)
        if (pd[a]->type != PNPR_TYPE_FLOAT32) return;
    for (size_t i = 0; i < cloud.count; i++) {
        if (!own.has[i]) continue;
        ((uint8_t *)pc->data)[i] = own.cls[i];
        for (int a = 0; a < 3; a++) ((float *)pd[a]->data)[i] = own.dir[3 * i + a];
    }
}

/* The per-point layer index of a merged cloud of several layers (uint32): the key of the style
 * map that gives layers their own styles (pnpr_upload_options.style_key). */
const char *const kLayerKey = "meshlab_layer";

/* The visible point layers merged into `cloud` in scene coordinates (Tr applied), with the layers'
 * colours, meaningful normals and (when every layer has them) feature classes. Segment labels:
 * when any layer has them, each layer's are kept, offset past the previous layer's, and a layer
 * without them is one segment (said in the note). Several layers: kLayerKey. */
pnpr_status buildCloud(MeshDocument &md, const std::vector<std::unique_ptr<pnpr_meshlab::LayerStream>> &streams,
                       pnpr_cloud &cloud, bool &layerFeatures, OwnClasses &own, float &toneRadius, QString &note)
{
    toneRadius = 0;
    pnpr_cloud_free(&cloud);
    own = OwnClasses();
    std::vector<LayerPoints> layers;
    size_t total = 0;
    bool anyColour = false, allClass = true, anyClass = false, anySeg = false, allNormals = true, allSpacing = true;
    QStringList withClass;
    size_t meshes = 0;
    QStringList stale, oneSegment, streamed;
    double toneSum = 0; /* the streams' tone radii (in scene units), weighted by their points */
    int measured = 0, fromFile = 0; /* streams whose spacing was measured on the sample / grown from the file */
    bool allTone = true;   /* every stream carries its file's mean spacing */
    for (MeshModel *mm : md.meshList) {
        if (!isDrawnLayer(mm)) continue;
        const pnpr_meshlab::LayerStream *st = nullptr;
        for (const auto &ls : streams)
            if (ls->meshId == mm->id()) st = ls.get();
        layers.emplace_back(mm, st);
        const LayerPoints &lp = layers.back();
        if (lp.stream) streamed << QString("'%1'").arg(mm->label());
        if (lp.stream) (lp.stream->spacingMeasured ? measured : fromFile)++;
        meshes += mm->cm.fn > 0;
        total += lp.count;
        anyColour |= lp.colour;
        allNormals = allNormals && (lp.stream ? lp.normals : meaningfulNormals(mm)); /* a pass over the layer: once needed */
        allSpacing &= lp.spacing != nullptr;
        const LayerAttributes &la = lp.attrs;
        if (la.stale) stale << QString("'%1'").arg(mm->label());
        allClass &= la.hasClass;
        anyClass |= la.hasClass;
        if (la.hasClass) withClass << QString("'%1'").arg(mm->label());
        anySeg |= la.hasSeg;
    }
    layerFeatures = false;
    if (layers.empty() || total == 0) { note = "no visible layer with vertices"; return PNPR_OK; }
    std::vector<double> world(3 * total);
    std::vector<uint8_t> rgb(anyColour ? 3 * total : 0);
    std::vector<uint8_t> cls(anyClass ? total : 0);
    std::vector<float> dir(anyClass ? 3 * total : 0);
    if (anyClass && !allClass) own.has.assign(total, 0);
    std::vector<uint32_t> label(anySeg ? total : 0);
    std::vector<uint32_t> layerIndex(layers.size() > 1 ? total : 0);
    std::vector<float> normal(allNormals ? 3 * total : 0);
    std::vector<float> spacing(allSpacing ? total : 0);
    size_t j = 0;
    uint32_t labelBase = 0;
    for (size_t li = 0; li < layers.size(); li++) {
        const LayerPoints &lp = layers[li];
        MeshModel *mm = lp.mm;
        CMeshO &m = mm->cm;
        double T[4][4];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) T[r][c] = m.Tr[r][c];
        /* normals turn with the cofactor matrix of Tr's upper 3x3 (= det * inverse transpose) */
        double C[3][3];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                C[r][c] = T[(r + 1) % 3][(c + 1) % 3] * T[(r + 2) % 3][(c + 2) % 3] -
                          T[(r + 1) % 3][(c + 2) % 3] * T[(r + 2) % 3][(c + 1) % 3];
        /* lengths grow with Tr's scale (the cube root of its upper 3x3's determinant) */
        const double scale = std::cbrt(std::fabs(T[0][0] * C[0][0] + T[0][1] * C[0][1] + T[0][2] * C[0][2]));
        if (allSpacing) toneSum += (double)lp.stream->toneRadius * scale * (double)lp.count;
        allTone = allTone && allSpacing && lp.stream->toneRadius > 0;
        const LayerAttributes &la = lp.attrs;
        if (anySeg && !la.hasSeg) oneSegment << QString("'%1'").arg(mm->label());
        uint32_t maxLabel = 0;
        PointIn v;
        for (size_t i = 0; i < lp.entries() && j < total; i++) {
            if (!lp.read(i, v)) continue;
            const double *p = v.p;
            double w = T[3][0] * p[0] + T[3][1] * p[1] + T[3][2] * p[2] + T[3][3];
            if (!(w != 0)) w = 1;
            for (int r = 0; r < 3; r++) world[3 * j + r] = (T[r][0] * p[0] + T[r][1] * p[1] + T[r][2] * p[2] + T[r][3]) / w;
            if (anyColour) std::memcpy(&rgb[3 * j], v.rgb, 3);
            if (la.hasClass) {
                if (!own.has.empty()) own.has[j] = 1;
                float c = v.cls;
                cls[j] = (c >= 0 && c <= 3) ? (uint8_t)std::lround(c) : 0;
                const double *d = v.dir;
                double t[3], n = 0;
                for (int r = 0; r < 3; r++) { t[r] = T[r][0] * d[0] + T[r][1] * d[1] + T[r][2] * d[2]; n += t[r] * t[r]; }
                n = std::sqrt(n);
                for (int r = 0; r < 3; r++) dir[3 * j + r] = n > 0 && std::isfinite(n) ? (float)(t[r] / n) : 0.0f;
            }
            if (allNormals) {
                const double *n = v.n;
                double t[3], len = 0;
                for (int r = 0; r < 3; r++) { t[r] = C[r][0] * n[0] + C[r][1] * n[1] + C[r][2] * n[2]; len += t[r] * t[r]; }
                len = std::sqrt(len);
                for (int r = 0; r < 3; r++) normal[3 * j + r] = len > 0 && std::isfinite(len) ? (float)(t[r] / len) : 0.0f;
            }
            if (anySeg) {
                float sv = la.hasSeg ? v.seg : 0.0f;
                uint32_t l = (sv >= 0 && sv < 16777216.0f) ? (uint32_t)sv : 0;
                label[j] = labelBase + l;
                maxLabel = std::max(maxLabel, l);
            }
            if (allSpacing) spacing[j] = (float)(v.spacing * scale);
            if (!layerIndex.empty()) layerIndex[j] = (uint32_t)li;
            j++;
        }
        labelBase += maxLabel + 1;
    }
    if (!own.has.empty()) { /* some layers have classes: theirs replace the computed ones */
        own.has.resize(j);
        cls.resize(j);
        dir.resize(3 * j);
        own.cls = std::move(cls);
        own.dir = std::move(dir);
        own.layers = withClass.join(", ");
    }
    pnpr_status st = pnpr_cloud_alloc(&cloud, j);
    if (st == PNPR_OK) st = pnpr_cloud_set_world(&cloud, world.data());
    if (st == PNPR_OK && anyColour && (st = pnpr_cloud_alloc_rgb(&cloud)) == PNPR_OK)
        std::memcpy(cloud.rgb, rgb.data(), 3 * j);
    if (st == PNPR_OK && anySeg && (st = pnpr_cloud_alloc_labels(&cloud)) == PNPR_OK)
        std::memcpy(cloud.label, label.data(), j * sizeof(uint32_t));
    if (st == PNPR_OK && allNormals && (st = pnpr_cloud_alloc_normals(&cloud)) == PNPR_OK)
        std::memcpy(cloud.normal, normal.data(), 3 * j * sizeof(float));
    pnpr_property *pk = nullptr;
    if (st == PNPR_OK && allSpacing && (st = pnpr_cloud_add_property(&cloud, PNPR_PROP_POINT_SPACING, PNPR_TYPE_FLOAT32, &pk)) == PNPR_OK) {
        std::memcpy(pk->data, spacing.data(), j * sizeof(float));
        /* the files' mean spacing when every stream has one; else 0: the renderer's mean radius */
        toneRadius = allTone && j && toneSum > 0 && std::isfinite(toneSum) ? (float)(toneSum / (double)j) : 0;
    }
    if (st == PNPR_OK && !layerIndex.empty() && (st = pnpr_cloud_add_property(&cloud, kLayerKey, PNPR_TYPE_UINT32, &pk)) == PNPR_OK)
        std::memcpy(pk->data, layerIndex.data(), j * sizeof(uint32_t));
    if (st == PNPR_OK && allClass) {
        pnpr_property *pc = nullptr, *px = nullptr, *py = nullptr, *pz = nullptr;
        st = pnpr_cloud_add_property(&cloud, PNPR_PROP_FEATURE_CLASS, PNPR_TYPE_UINT8, &pc);
        if (st == PNPR_OK) st = pnpr_cloud_add_property(&cloud, PNPR_PROP_FEATURE_DIR_X, PNPR_TYPE_FLOAT32, &px);
        if (st == PNPR_OK) st = pnpr_cloud_add_property(&cloud, PNPR_PROP_FEATURE_DIR_Y, PNPR_TYPE_FLOAT32, &py);
        if (st == PNPR_OK) st = pnpr_cloud_add_property(&cloud, PNPR_PROP_FEATURE_DIR_Z, PNPR_TYPE_FLOAT32, &pz);
        if (st == PNPR_OK) {
            /* pnpr_cloud_add_property may move the property array: look them up again */
            pc = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_CLASS);
            px = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_X);
            py = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Y);
            pz = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Z);
            std::memcpy(pc->data, cls.data(), j);
            for (size_t i = 0; i < j; i++) {
                ((float *)px->data)[i] = dir[3 * i];
                ((float *)py->data)[i] = dir[3 * i + 1];
                ((float *)pz->data)[i] = dir[3 * i + 2];
            }
            layerFeatures = true;
        }
    }
    note = QString("%1 points from %2 layer(s)%3%4%5%6%7%8%9")
               .arg(j).arg(layers.size())
               .arg(meshes ? QString(" (%1 mesh layer(s): their vertices)").arg(meshes) : QString())
               .arg(anyColour ? ", colours" : "")
               .arg(allNormals ? ", normals" : "")
               .arg(allClass ? ", feature classes from the layers' attributes"
                             : anyClass ? QString(", feature classes from %1's attributes (computed for the others)").arg(own.layers)
                                        : QString())
               .arg(anySeg ? ", segment labels" : "")
               .arg(oneSegment.isEmpty() ? QString() : QString(" (%1 without: one segment each)").arg(oneSegment.join(", ")))
               .arg(stale.isEmpty() ? QString()
                                    : QString("; the attributes of %1 belong to an older version of the layer (reloaded or "
                                              "edited): left out").arg(stale.join(", ")));
    if (!streamed.isEmpty())
        note += QString("; %1 streamed for the view%2").arg(streamed.join(", "))
                    .arg(!allSpacing            ? ""
                         : measured && fromFile ? ", point spacing from the files grown by the view's share or measured on the stream's thread"
                         : measured             ? ", the sample's point spacing measured on the stream's thread"
                                                : ", point spacing from the file grown by the view's share");
    return st;
}

/* test-only: PNPR_MESHLAB_SNAPSHOT=PREFIX writes PREFIX-plain.{png,pgm} (MeshLab's own frame,
 * read before drawing), PREFIX-npr.{png,pgm} (after) and PREFIX-camera.txt (MV, P, viewport). */
bool readViewport(const GLint vp[4], std::vector<unsigned char> &rgba)
{
    if (vp[2] <= 0 || vp[3] <= 0) return false;
    rgba.assign((size_t)vp[2] * vp[3] * 4, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(vp[0], vp[1], vp[2], vp[3], GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    return true;
}

/* test-only (tests/meshlab/run.sh, case snapshot): PNPR_MESHLAB_TEST_SAVE_SNAPSHOT=FOLDER drives
 * MeshLab's own File > Save snapshot: its QAction ("Save snapsho&t") is triggered and its modal
 * dialog (SaveSnapshotDialog, object name SSDialog) gets output folder FOLDER, base name
 * meshlab_snapshot and screen multiplier PNPR_MESHLAB_TEST_SNAPSHOT_FACTOR (default 2), then its
 * Save button is clicked. MeshLab then renders the tiles (off-centre frusta) and writes
 * FOLDER/meshlab_snapshot00.png itself. */
void testSaveSnapshot()
{
    const char *dir = std::getenv("PNPR_MESHLAB_TEST_SAVE_SNAPSHOT");
    if (!dir) return;
    int factor = 2;
    if (const char *f = std::getenv("PNPR_MESHLAB_TEST_SNAPSHOT_FACTOR")) factor = std::max(1, std::atoi(f));
    QAction *act = nullptr;
    for (QWidget *w : QApplication::topLevelWidgets())
        for (QAction *a : w->findChildren<QAction *>())
            if (!act && a->text() == "Save snapsho&t") act = a;
    if (!act) { std::fprintf(stderr, "pointnpr decorator: test: no 'Save snapshot' action\n"); return; }
    QTimer *poll = new QTimer(qApp);
    int *ticks = new int(0);
    QString folder = QString::fromLocal8Bit(dir);
    QObject::connect(poll, &QTimer::timeout, poll, [poll, ticks, folder, factor] {
        QWidget *dlg = nullptr;
        for (QWidget *w : QApplication::topLevelWidgets())
            if (w->objectName() == "SSDialog" && w->isVisible()) dlg = w;
        if (!dlg) {
            if (++*ticks > 200) { poll->stop(); poll->deleteLater(); delete ticks; }
            return;
        }
        poll->stop();
        poll->deleteLater();
        delete ticks;
        QLineEdit *out = dlg->findChild<QLineEdit *>("outDirLineEdit");
        QLineEdit *base = dlg->findChild<QLineEdit *>("baseNameLineEdit");
        QSpinBox *res = dlg->findChild<QSpinBox *>("resolutionSpinBox");
        QPushButton *save = dlg->findChild<QPushButton *>("saveButton");
        if (!out || !base || !res || !save) {
            std::fprintf(stderr, "pointnpr decorator: test: Save snapshot dialog has unexpected widgets\n");
            return;
        }
        out->setText(folder);
        base->setText("meshlab_snapshot");
        res->setValue(factor);
        std::fprintf(stderr, "pointnpr decorator: test: Save snapshot dialog accepted (folder %s, multiplier %d)\n",
                     folder.toLocal8Bit().constData(), res->value());
        save->click();
    });
    poll->start(100);
    std::fprintf(stderr, "pointnpr decorator: test: triggering File > Save snapshot\n");
    act->trigger(); /* MainWindow::saveSnapshot: dialog.exec() runs the poll above */
}

/* "PATH@MTIME:SIZE": what a file is kept by, so that it is read again after it was saved. */
QString fileKey(const QString &path)
{
    QFileInfo fi(path);
    return QString("%1@%2:%3").arg(path).arg(fi.lastModified().toMSecsSinceEpoch()).arg(fi.size());
}

/* Reads the text file `path` (at most max bytes) and hands it to parse(text, size, path). */
template <class Parse> pnpr_status parseFile(const QString &path, size_t max, pnpr_error &err, Parse parse)
{
    QByteArray p = path.toLocal8Bit();
    char *text = nullptr;
    size_t size = 0;
    pnpr_status st = pnpr_text_file_load(p.constData(), max, &text, &size, &err);
    if (st == PNPR_OK) st = parse(text, size, p.constData());
    std::free(text);
    return st;
}

/* The effects pipeline of `what` ("" none, a preset's name, "file:PATH") in s->fx, kept while the
 * preset, or the file with its modification time and size, stays the same (a file is read again
 * after it was saved). False when there are no effects; msg then says why (empty for none), else
 * what was loaded. */
bool loadEffects(DecorateContextState *s, const QString &what, QString &msg)
{
    msg.clear();
    if (what.isEmpty()) {
        pnpr_effect_pipeline_free(&s->fx);
        s->fxKey.clear();
        return false;
    }
    bool file = what.startsWith("file:");
    QString key = file ? "file:" + fileKey(what.mid(5)) : what;
    if (key == s->fxKey) return s->fx.count > 0;
    s->fxKey = key;
    pnpr_effect_pipeline_free(&s->fx);
    pnpr_error err{};
    pnpr_status st;
    if (file) {
        st = parseFile(what.mid(5), PNPR_EFFECT_PIPELINE_FILE_MAX, err, [&](const char *text, size_t size, const char *name) {
            return pnpr_effect_pipeline_parse(text, size, name, &s->fx, &err);
        });
    } else {
        QByteArray text = ("preset " + what + "\n").toUtf8();
        st = pnpr_effect_pipeline_parse(text.constData(), (size_t)text.size(), "preset", &s->fx, &err);
    }
    if (st != PNPR_OK) {
        msg = QString("effects %1: %2; drawn without").arg(file ? "file" : "preset").arg(status(st, err));
        return false;
    }
    msg = QString("effects: %1, %2 node(s), layering %3")
              .arg(file ? what.mid(5) : "preset " + what).arg(s->fx.count).arg(pnpr_layering_name(s->fx.layering));
    return true;
}

/* The style map file `path` into s->smap, read again when its modification time or size changes;
 * true when a map is in use. msg: what to log when it was (re)read. */
bool loadStyleMap(DecorateContextState *s, const QString &path, QString &msg)
{
    msg.clear();
    if (path.isEmpty()) {
        pnpr_style_map_free(&s->smap);
        s->smapKey.clear();
        return false;
    }
    QString key = fileKey(path);
    if (key == s->smapKey) return s->smap.count > 0 || s->smap.have_default;
    s->smapKey = key;
    pnpr_style_map_free(&s->smap);
    pnpr_error err{};
    pnpr_status st = parseFile(path, PNPR_STYLE_MAP_FILE_MAX, err, [&](const char *text, size_t size, const char *name) {
        return pnpr_style_map_parse(text, size, name, &s->smap, &err);
    });
    if (st != PNPR_OK) {
        msg = QString("style map file: %1; drawn without").arg(status(st, err));
        return false;
    }
    msg = QString("style map: %1, %2 entries%3").arg(path).arg(s->smap.count)
              .arg(s->smap.have_default ? QString(", others %1").arg(pnpr_style_name(s->smap.default_style)) : QString());
    return true;
}

/* Every width in pixels at k times the view's: a tile of "Save snapshot" at screen multiplier k (its
 * P[0] is k times the view's), or a moving frame drawn at k < 1 of the viewport. Every width in
 * pixels (strokes, lines, dots, outlines, the hierarchy's strokes, the shortest line kept) k times the view's, resolved
 * from the library's defaults, so that the snapshot is the view at k times the resolution instead
 * of the same pixel widths over k times the area. */
static void scaleWidths(pnpr_draw_options &o, double k)
{
    if (!(k > 0.01 && k <= 64) || std::fabs(k - 1) < 0.001) return;
    auto widen = [k](float v, const pnpr_option_desc *d) { /* within the option's range */
        double w = (v > 0 ? v : (d ? d->def : 1)) * k;
        return (float)(d ? std::min(d->max, std::max(d->min, w)) : w);
    };
    o.line_width = widen(o.line_width, drawOption("line-width"));
    o.stroke_width = widen(o.stroke_width, drawOption("stroke-width"));
    if (!(o.stroke_max < 0)) o.stroke_max = widen(o.stroke_max, drawOption("stroke-max"));
    o.dot_size = widen(o.dot_size, drawOption("dot-size"));
    o.line_min_px = widen(o.line_min_px, drawOption("line-min")); /* the same profile lines kept */
    o.hierarchy.stroke_px = widen(o.hierarchy.stroke_px, hierOption("stroke-px"));
    float ow = o.outline_width;
    if (!(ow > 0)) pnpr_style_outline_default(o.style, &ow);
    const pnpr_option_desc *od = drawOption("outline-width");
    o.outline_width = (float)std::min(ow * k, od ? od->max : 64.0);
}

/* Copies a frame of w x h pixels (RGBA8, top row first, in s->fxPixels) into MeshLab's framebuffer
 * `fb`, stretched over the viewport: the renderer's own frame held it, so the host's framebuffer
 * and viewport are bound again first. The fixed-function state that glDrawPixels goes through is
 * in the caller's glPushAttrib; the program is restored here. */
static void copyToHost(DecorateContextState *s, int w, int h, const GLint vp[4], GLint fb, GLint readFb, GLint program)
{
    size_t row = (size_t)w * 4;
    s->fxRows.resize(row * (size_t)h);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)readFb);
    glViewport(vp[0], vp[1], vp[2], vp[3]);
    for (int y = 0; y < h; y++) /* GL rows go bottom-up */
        std::memcpy(&s->fxRows[(size_t)(h - 1 - y) * row], &s->fxPixels[(size_t)y * row], row);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_FOG);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelZoom((float)vp[2] / (float)w, (float)vp[3] / (float)h);
    glWindowPos2i(vp[0], vp[1]);
    glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, s->fxRows.data());
    glPixelZoom(1, 1);
    glUseProgram((GLuint)program);
}

/* Draws the effects frame (pnpr_renderer_effects, layers at `scale` of the viewport) and copies it
 * into MeshLab's framebuffer. */
pnpr_status drawEffects(DecorateContextState *s, const pnpr_draw_options &o, const GLint vp[4], GLint fb, float scale,
                        pnpr_effects_stats &es, pnpr_error *err)
{
    s->fxPixels.resize((size_t)vp[2] * 4 * (size_t)vp[3]);
    pnpr_effects_options eo;
    std::memset(&eo, 0, sizeof eo);
    eo.scale = scale;
    GLint program = 0, readFb = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFb);
    pnpr_status st = pnpr_renderer_effects(s->renderer, nullptr, &o, &s->fx, vp[2], vp[3], &eo, s->fxPixels.data(), &es, err);
    if (st != PNPR_OK) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)fb);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)readFb);
        glViewport(vp[0], vp[1], vp[2], vp[3]);
        glUseProgram((GLuint)program);
        return st;
    }
    copyToHost(s, vp[2], vp[3], vp, fb, readFb, program);
    return PNPR_OK;
}

/* A moving frame at `scale` of the viewport (the renderer's own framebuffer, widths in pixels
 * scaled alike), stretched into MeshLab's: for styles whose cost is in the pixels (cartoon's fills
 * and outlines, the brush's splats), where fewer points do not make the frame cheaper. */
pnpr_status drawPreview(DecorateContextState *s, pnpr_draw_options o, const GLint vp[4], GLint fb, float scale,
                        pnpr_render_stats *stats, pnpr_error *err)
{
    int w = std::max(1, (int)std::lround(vp[2] * scale)), h = std::max(1, (int)std::lround(vp[3] * scale));
    scaleWidths(o, (double)w / vp[2]);
    GLint program = 0, readFb = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFb);
    pnpr_target tg;
    std::memset(&tg, 0, sizeof tg);
    tg.width = w;
    tg.height = h;
    tg.offscreen = 1;
    s->fxPixels.resize((size_t)w * 4 * (size_t)h);
    pnpr_status st = pnpr_renderer_draw(s->renderer, nullptr, &o, &tg, stats, err);
    if (st == PNPR_OK) st = pnpr_renderer_read_frame(s->renderer, s->fxPixels.data(), 1);
    if (st != PNPR_OK) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)fb);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)readFb);
        glViewport(vp[0], vp[1], vp[2], vp[3]);
        glUseProgram((GLuint)program);
        return st;
    }
    copyToHost(s, w, h, vp, fb, readFb, program);
    return PNPR_OK;
}

bool writeImages(const QString &prefix, const std::vector<unsigned char> &rgba, int w, int h)
{
    QImage img(w, h, QImage::Format_RGB888);
    QFile pgm(prefix + ".pgm.tmp");
    if (!pgm.open(QIODevice::WriteOnly)) return false;
    QByteArray text = QString("P2\n%1 %2\n255\n").arg(w).arg(h).toUtf8();
    for (int y = 0; y < h; y++) {
        const unsigned char *row = &rgba[(size_t)(h - 1 - y) * w * 4]; /* GL rows go bottom-up */
        for (int x = 0; x < w; x++) {
            const unsigned char *p = row + 4 * x;
            img.setPixel(x, y, qRgb(p[0], p[1], p[2]));
            int g = (299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000;
            text += QByteArray::number(g);
            text += (x + 1 == w) ? '\n' : ' ';
        }
    }
    bool ok = pgm.write(text) == text.size();
    pgm.close();
    ok = ok && img.save(prefix + ".png", "PNG");
    QFile::remove(prefix + ".pgm");
    return ok && QFile::rename(prefix + ".pgm.tmp", prefix + ".pgm");
}

} // namespace


/* Reports a message in MeshLab's log and on stderr, not repeating the last one every frame. */
using Reporter = std::function<void(const QString &, bool)>;

/* The styles drawn: the decorator's Style, or a layer's own (per-mesh attribute written by the
 * filter "NPR: Set layer style"), or with an effects pipeline its nodes' styles (the layers' own
 * styles are then not used: the pipeline chooses by segment). */
struct LayerStyles {
    pnpr_style main = PNPR_STYLE_SKETCHY;   /* the frame's style (of layers without their own) */
    uint32_t bits = 0;                      /* every style drawn (the plan's request) */
    std::vector<pnpr_style_map_entry> map;  /* layer index (kLayerKey) -> own style, or with bySegment
                                             * the style map file's entries; empty: one style */
    bool bySegment = false;                 /* map keyed by segment labels (a style map file) */
    QString text;                           /* "'a.ply' cartoon, 'b.ply' sketchy (Style)" for the log */
};

static LayerStyles layerStyles(MeshDocument &md, const DecorateContextState *s, pnpr_style def, bool fxOn, bool mapOn)
{
    LayerStyles ls;
    ls.main = def;
    if (fxOn) {
        for (size_t k = 0; k < s->fx.count; k++) ls.bits |= 1u << s->fx.nodes[k].style;
        return ls;
    }
    if (mapOn) { /* a style per segment label; the others in the map's default, else the Style */
        if (s->smap.have_default) ls.main = s->smap.default_style;
        ls.bits = 1u << ls.main;
        ls.map.assign(s->smap.entries, s->smap.entries + s->smap.count);
        for (const pnpr_style_map_entry &e : ls.map) ls.bits |= 1u << e.style;
        ls.bySegment = !ls.map.empty();
        return ls;
    }
    std::vector<int> own;
    QStringList parts;
    bool anyOwn = false;
    for (MeshModel *mm : md.meshList) {
        if (!isDrawnLayer(mm)) continue;
        int st = -1;
        if (!pnpr_meshlab::layerStyle(mm->cm, st) || st >= (int)PNPR_STYLE_COUNT_) st = -1;
        own.push_back(st);
        anyOwn |= st >= 0;
        parts << QString("'%1' %2").arg(mm->label()).arg(st >= 0 ? pnpr_style_name((pnpr_style)st)
                                                                  : qUtf8Printable(QString("%1 (Style)").arg(pnpr_style_name(def))));
    }
    if (own.size() == 1 && own[0] >= 0) ls.main = (pnpr_style)own[0]; /* one layer: its style is the frame's */
    ls.bits = 1u << ls.main;
    if (own.size() > 1 && anyOwn && pnpr_cloud_find_property(&s->cloud, kLayerKey)) {
        ls.bits = 0;
        bool defUsed = false;
        for (size_t i = 0; i < own.size(); i++) {
            pnpr_style st = own[i] >= 0 ? (pnpr_style)own[i] : def;
            defUsed |= own[i] < 0;
            ls.bits |= 1u << st;
            if (own[i] >= 0) ls.map.push_back({(uint32_t)i, st});
        }
        if (!defUsed) ls.main = ls.map[0].style; /* the renderer needs what the frame's style needs */
    }
    if (anyOwn) ls.text = parts.join(", ");
    return ls;
}

/* "cartoon and points" */
static QString styleNames(uint32_t bits)
{
    QStringList names;
    for (int st = 0; st < (int)PNPR_STYLE_COUNT_; st++)
        if (bits & (1u << st)) names << pnpr_style_name((pnpr_style)st);
    if (names.size() <= 1) return names.join("");
    QString last = names.takeLast();
    return names.join(", ") + " and " + last;
}

/* 1. The merged cloud, rebuilt from the layers when they changed (a running computation on the
 * old layers is cancelled first). Returns false when there is nothing to draw. */
static bool refreshLayers(MeshDocument &md, DecorateContextState *s, const Reporter &report)
{
    const uint64_t lsig = layerSignature(md), sig = lsig ^ (s->streamGen * 0x9E3779B97F4A7C15ull);
    if (s->built && sig == s->signature) return !s->uploadFailed && s->cloud.count > 0;
    s->drawPrevious = s->uploaded && !s->uploadFailed && lsig == s->uploadedLayersSig;
    s->layersSig = lsig;
    s->job.reset(); /* cancels and waits: its results would be those of the old layers */
    QElapsedTimer t;
    t.start();
    pnpr_status st = buildCloud(md, s->streams, s->cloud, s->layerFeatures, s->ownClasses, s->toneRadius, s->layersNote);
    s->built = true;
    s->signature = sig;
    s->needUpload = true;
    s->uploadFailed = false;
    s->ownFeatures = s->ownDither = false;
    s->failedWant = 0;
    s->jsegFailed = s->brushFailed = s->cancelled = false;
    if (s->renderer) pnpr_renderer_set_hierarchy(s->renderer, nullptr);
    pnpr_sphere_tree_free(&s->tree);
    s->treeReady = s->treeFailed = false;
    s->lastPlan.clear();
    pnpr_lines_free(&s->lines);
    s->linesReady = s->linesPending = false;
    /* the scene's up, as the CLI's default view finds it: the tone's key light comes from there */
    s->up[0] = 0; s->up[1] = 0; s->up[2] = 1;
    pnpr_view_info vi;
    if (st == PNPR_OK && s->cloud.count > 0 && pnpr_scene_frame(&s->cloud, nullptr, &vi) == PNPR_OK)
        std::memcpy(s->up, vi.up, sizeof s->up);
    if (st != PNPR_OK) {
        s->uploadFailed = true;
        pnpr_error err{};
        report("cannot read the layers: " + status(st, err), true);
        return false;
    }
    s->layersMs = t.elapsed();
    return s->cloud.count > 0;
}

/* 2. The library's plan for the style (or the effects' styles) on the cloud as it is; logged once
 * per request and cloud. Features this plugin computed without dithering points, or for another
 * tone, are dropped when dithering is needed (the plan cannot tell them from the classes): the plan
 * then computes them anew. */
static bool makePlan(DecorateContextState *s, const Params &prm, uint32_t styles, const pnpr_tone_options &tone,
                     pnpr_plan &plan, const Reporter &report)
{
    pnpr_plan_request req;
    std::memset(&req, 0, sizeof req);
    req.styles = styles;
    req.sketch_variant = prm.variant;
    req.outline = prm.outline;
    pnpr_status pst = pnpr_plan_make(&req, &s->cloud, &plan);
    if (pst == PNPR_OK && s->ownFeatures && (plan.needed & PNPR_WANT_DITHER) &&
        (!s->ownDither || s->ditherToneSource != (int)tone.source || s->ditherToneGamma != tone.gamma)) {
        static const char *const props[] = {PNPR_PROP_FEATURE_DEGREE, PNPR_PROP_FEATURE_CLASS, PNPR_PROP_FEATURE_CONFIDENCE,
                                            PNPR_PROP_FEATURE_DIR_X, PNPR_PROP_FEATURE_DIR_Y, PNPR_PROP_FEATURE_DIR_Z};
        for (const char *name : props) {
            pnpr_status rs = pnpr_cloud_remove_property(&s->cloud, name); /* NOT_FOUND: nothing to drop */
            (void)rs;
        }
        s->ownFeatures = s->ownDither = false;
        s->failedWant = 0;
        pst = pnpr_plan_make(&req, &s->cloud, &plan);
    }
    if (pst != PNPR_OK) {
        report(QString("no plan for the %1 style: %2").arg(styleNames(styles)).arg(pnpr_status_string(pst)), true);
        return false;
    }
    QStringList parts;
    for (int b = 0; b < 5; b++)
        if (plan.want & (1u << b)) parts << QString("compute %1 (%2)").arg(kWantNames[b]).arg(plan.why[b] ? plan.why[b] : "");
    if (plan.reused_features) parts << QString("features from the %1").arg(s->ownFeatures ? "earlier computation" : "layers");
    if (plan.reused_normals && (plan.needed & (PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY))) parts << "normals reused";
    if (plan.segments == PNPR_PLAN_SEGMENTS_JSEG) parts << QString("segments by JSEG (%1)").arg(plan.segments_why);
    else if (plan.segments == PNPR_PLAN_SEGMENTS_INPUT) parts << QString("segment labels reused (%1)").arg(plan.segments_why);
    else if (plan.segments == PNPR_PLAN_SEGMENTS_SHADE) parts << QString("shading bands (%1)").arg(plan.segments_why);
    if (plan.lines) parts << QString("profile lines (%1)").arg(plan.lines_why ? plan.lines_why : "");
    if (plan.brush) parts << QString("brush sizes and clusters (%1)").arg(plan.brush_why);
    if (plan.hierarchy) parts << QString("sphere hierarchy (%1)").arg(plan.hierarchy_why);
    /* logged once per request and cloud (not again when its own results arrive) */
    QString key = QString("%1 %2 %3 %4").arg(s->signature).arg(styles).arg((int)prm.variant).arg(prm.outline);
    if (key != s->lastPlan) {
        s->lastPlan = key;
        report(QString("plan for the %1 style: %2").arg(styleNames(styles))
                   .arg(parts.isEmpty() ? QString("nothing to compute") : parts.join("; ")), false);
    }
    return true;
}

/* What the plan still asks for, less what failed or was cancelled before (not retried every
 * frame: features only when the tone changes, the other stages when the layers change). */
static pnpr_meshlab::StageRequest stageRequest(const DecorateContextState *s, const pnpr_plan &plan,
                                               const pnpr_tone_options &tone, const QString &styles)
{
    pnpr_meshlab::StageRequest rq;
    bool failedBefore = plan.want == s->failedWant && s->failedToneSource == (int)tone.source &&
                        s->failedToneGamma == tone.gamma;
    if (plan.want != 0 && !failedBefore) rq.want = plan.want;
    rq.tone = tone;
    rq.jseg = plan.segments == PNPR_PLAN_SEGMENTS_JSEG && !s->jsegFailed && s->cloud.rgb;
    rq.brush = plan.brush && !s->brushFailed;
    rq.tree = plan.hierarchy && !s->treeReady && !s->treeFailed;
    rq.lines = plan.lines && (!s->linesReady || rq.want); /* new features: new lines */
    rq.style = styles.toStdString();
    return rq;
}

/* While a computation runs, Esc anywhere in MeshLab cancels it (the key still reaches MeshLab);
 * the test hook's synthetic event (PNPR_MESHLAB_TEST_EVENTS) is answered here, which proves the
 * event loop runs meanwhile. Installed on the application once per state. */
class JobKeys : public QObject
{
public:
    static const QEvent::Type kSynthetic = QEvent::Type(QEvent::User + 817);
    explicit JobKeys(DecorateContextState *s) : s_(s) {}

protected:
    bool eventFilter(QObject *o, QEvent *e) override
    {
        try {
            if (e->type() == kSynthetic) {
                bool computing = s_->job && !s_->job->done();
                std::fprintf(stderr, "pointnpr decorator: synthetic event answered after %lld ms %s\n",
                             (long long)s_->synthetic.elapsed(),
                             computing ? qUtf8Printable("while computing (" + QString::fromStdString(s_->job->stage()) + ")")
                                       : "after the computation");
                return true;
            }
            if (e->type() == QEvent::KeyPress && static_cast<QKeyEvent *>(e)->key() == Qt::Key_Escape && s_->job &&
                !s_->job->done() && !s_->cancelRequested) {
                s_->cancelRequested = true;
                s_->job->cancel();
                std::fprintf(stderr, "pointnpr decorator: Esc: cancelling the computation\n");
            }
        } catch (...) {
        }
        return QObject::eventFilter(o, e);
    }

private:
    DecorateContextState *s_;
};

/* MeshLab's own progress bar (MainWindow::qb, the status bar's progress bar without a style
 * sheet; the other one shows GPU memory), or null. */
static QProgressBar *meshlabProgressBar(QWidget *w)
{
    QMainWindow *mw = w ? qobject_cast<QMainWindow *>(w->window()) : nullptr;
    if (!mw || !mw->statusBar()) return nullptr;
    for (QProgressBar *b : mw->statusBar()->findChildren<QProgressBar *>())
        if (b->styleSheet().isEmpty()) return b;
    return nullptr;
}

/* Every 50 ms while computing: the progress bar and the status line; a repaint once done (the
 * next frame takes the results over). Test hook PNPR_MESHLAB_TEST_CANCEL: Esc once the
 * computation reported progress. */
static void pollJob(DecorateContextState *s)
{
    QProgressBar *bar = meshlabProgressBar(s->widget);
    QMainWindow *mw = s->widget ? qobject_cast<QMainWindow *>(s->widget->window()) : nullptr;
    QStatusBar *sb = mw ? mw->statusBar() : nullptr;
    if (!s->job || s->job->done()) {
        s->poll->stop();
        if (bar) bar->reset();
        if (sb && sb->currentMessage().startsWith("NPR render:")) sb->clearMessage();
        if (s->widget) s->widget->update();
        return;
    }
    s->pollTicks++;
    int pct = (int)std::lround(100 * s->job->fraction());
    if (bar) {
        bar->show();
        bar->setValue(pct);
        s->barUpdates++;
    }
    if (sb) sb->showMessage(QString("NPR render: %1 %2% (Esc cancels)").arg(QString::fromStdString(s->job->stage())).arg(pct));
    if (std::getenv("PNPR_MESHLAB_TEST_CANCEL") && s->job->reports() > 0 && !s->cancelRequested && s->widget)
        QCoreApplication::postEvent(s->widget.data(), new QKeyEvent(QEvent::KeyPress, Qt::Key_Escape, Qt::NoModifier));
}

/* Starts the plan's stages on a worker thread over a copy of the cloud. */
static void startJob(DecorateContextState *s, const pnpr_meshlab::StageRequest &rq, bool previous, const Reporter &report)
{
    std::unique_ptr<pnpr_meshlab::StageJob> job(new pnpr_meshlab::StageJob);
    std::string why;
    if (!job->start(s->cloud, rq, why)) { /* remembered as failed: not retried every frame */
        report(QString::fromStdString(why), true);
        s->failedWant = rq.want;
        s->failedToneSource = (int)rq.tone.source;
        s->failedToneGamma = rq.tone.gamma;
        s->jsegFailed |= rq.jseg;
        s->brushFailed |= rq.brush;
        s->treeFailed |= rq.tree;
        s->linesReady |= rq.lines;
        return;
    }
    s->job = std::move(job);
    s->cancelled = s->cancelRequested = false;
    s->pollTicks = s->barUpdates = 0;
    if (!s->poll) {
        s->poll = new QTimer;
        s->poll->setInterval(50);
        QObject::connect(s->poll, &QTimer::timeout, [s] { try { pollJob(s); } catch (...) {} });
    }
    s->poll->start();
    if (!s->keys) {
        s->keys = new JobKeys(s);
        qApp->installEventFilter(s->keys.data());
    }
    QStringList what;
    if (rq.want) what << "features";
    if (rq.jseg) what << "segments";
    if (rq.brush) what << "brush";
    if (rq.tree) what << "hierarchy";
    if (rq.lines) what << "profile lines";
    report(QString("computing %1 for the %2 style in the background (%3 points): %4 meanwhile, Esc cancels")
               .arg(what.join(", ")).arg(QString::fromStdString(rq.style)).arg(s->cloud.count)
               .arg(previous ? "the previous sample" : "MeshLab's own points"), false);
    if (std::getenv("PNPR_MESHLAB_TEST_EVENTS") && s->widget) {
        s->synthetic.start();
        QCoreApplication::postEvent(s->widget.data(), new QEvent(JobKeys::kSynthetic));
    }
}

/* Takes over a finished computation's results (GUI thread): the cloud with its new properties,
 * the tree, the lines; what failed or was cancelled is remembered so that it is not restarted
 * every frame. */
static void finishJob(DecorateContextState *s, const Reporter &report)
{
    using pnpr_meshlab::StageOutcome;
    pnpr_meshlab::StageJob &j = *s->job;
    j.join();
    for (const pnpr_meshlab::StageMessage &m : j.messages) report(QString::fromStdString(m.text), m.warning);
    const pnpr_meshlab::StageRequest &rq = j.request;
    auto undone = [](bool asked, StageOutcome o) { return asked && o != StageOutcome::Done; };
    bool cancelled = j.features == StageOutcome::Cancelled || j.jseg == StageOutcome::Cancelled ||
                     j.brush == StageOutcome::Cancelled || j.hierarchy == StageOutcome::Cancelled ||
                     j.profile == StageOutcome::Cancelled || s->cancelRequested;
    if (undone(rq.want != 0, j.features)) {
        s->failedWant = rq.want;
        s->failedToneSource = (int)rq.tone.source;
        s->failedToneGamma = rq.tone.gamma;
    }
    s->jsegFailed |= undone(rq.jseg, j.jseg);
    s->brushFailed |= undone(rq.brush, j.brush);
    s->treeFailed |= undone(rq.tree, j.hierarchy);
    bool changed = j.features == StageOutcome::Done || j.jseg == StageOutcome::Done || j.brush == StageOutcome::Done;
    if (changed) { /* the copy holds everything the old cloud had, and the new results */
        std::swap(s->cloud, j.cloud);
        s->needUpload = true;
    }
    if (j.features == StageOutcome::Done) {
        applyOwnClasses(s->cloud, s->ownClasses);
        if (rq.want & ~(uint32_t)(PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY)) s->ownFeatures = true;
        if (rq.want & PNPR_WANT_DITHER) {
            s->ownDither = true;
            s->ditherToneSource = (int)rq.tone.source;
            s->ditherToneGamma = rq.tone.gamma;
        }
        pnpr_lines_free(&s->lines); /* lines of the old features */
        s->linesReady = s->linesPending = false;
    }
    if (j.hierarchy == StageOutcome::Done) {
        pnpr_renderer_set_hierarchy(s->renderer, nullptr);
        pnpr_sphere_tree_free(&s->tree);
        std::swap(s->tree, j.tree);
        s->treeReady = true;
    }
    if (rq.lines) {
        s->linesReady = true; /* also on failure: no retry every frame */
        if (j.profile == StageOutcome::Done) {
            pnpr_lines_free(&s->lines);
            std::swap(s->lines, j.lines);
            s->linesPending = true; /* handed to the renderer after the upload */
        }
    }
    s->cancelled = cancelled;
    report(QString("background computation %1 after %2 ms: %3 progress reports, %4 progress bar updates, %5 event-loop "
                   "timer ticks meanwhile")
               .arg(cancelled ? "cancelled" : "done").arg(j.elapsedMs()).arg(j.reports()).arg(s->barUpdates)
               .arg(s->pollTicks), false);
    s->job.reset();
    s->cancelRequested = false;
}

/* ---- a sample layer streamed by the view (decorate_stream.h) ------------------------------- */

/* test-only: PNPR_MESHLAB_TEST_STREAM_OUT=PATH writes each sample taken over to PATH (ascii PLY)
 * (tests/meshlab/run.sh 'stream') */
static void testWriteStream(const pnpr_cloud &c)
{
    const char *out = std::getenv("PNPR_MESHLAB_TEST_STREAM_OUT");
    if (!out) return;
    pnpr_write_options wo;
    std::memset(&wo, 0, sizeof wo);
    wo.encoding = PNPR_PLY_ASCII;
    pnpr_error err{};
    if (pnpr_write_file(out, &c, &wo, &err) != PNPR_OK) std::fprintf(stderr, "pointnpr decorator: %s\n", err.message);
}

/* The layer's own vertices drawn again (its sample was of another view). */
static void dropSample(DecorateContextState *s, pnpr_meshlab::LayerStream &ls)
{
    if (ls.cloud.count) s->streamGen++;
    pnpr_cloud_free(&ls.cloud);
    ls.toneRadius = 0;
}

/* A finished read taken over (GUI thread): its layer draws the new sample from this frame on
 * (streamGen: the layers are merged again). A cancelled read is dropped; a failed one is logged
 * and not retried for that view. */
static void takeStream(DecorateContextState *s, const Reporter &report)
{
    if (!s->streamJob || !s->streamJob->done()) return;
    pnpr_meshlab::StreamJob &j = *s->streamJob;
    j.join();
    for (auto &ls : s->streams) {
        if (ls->meshId != j.meshId || ls->path != j.path) continue;
        if (j.status == PNPR_OK) {
            std::swap(ls->cloud, j.cloud);
            ls->toneRadius = j.toneRadius;
            ls->spacingMeasured = j.spacingMeasured;
            ls->view = j.view;
            s->streamGen++;
            const pnpr_lod_read_info &in = j.info;
            report(QString("streamed %1 of the %2 points of %3 for the view (%4 asked, about %5 in view; %6% of the "
                           "file read; %7 ms)")
                       .arg(ls->cloud.count).arg(in.total).arg(QString::fromLocal8Bit(j.path.c_str())).arg(j.points)
                       .arg(in.in_view).arg(in.total ? 100.0 * (double)in.visited / (double)in.total : 0.0, 0, 'f', 1)
                       .arg(j.elapsedMs), false);
            testWriteStream(ls->cloud);
        } else if (j.status != PNPR_ERR_CANCELLED) {
            ls->view = j.view; /* not retried for this view */
            dropSample(s, *ls);
            report(QString("cannot stream %1 for the view: %2 (the layer is drawn as it is)")
                       .arg(QString::fromLocal8Bit(j.path.c_str())).arg(QString::fromStdString(j.message)), true);
        }
    }
    s->streamJob.reset();
}

/* Every 100 ms while a stream runs: the status line; a repaint once done (the next frame takes
 * the sample over, or starts the read of the view now on screen). */
static void pollStream(DecorateContextState *s)
{
    QMainWindow *mw = s->widget ? qobject_cast<QMainWindow *>(s->widget->window()) : nullptr;
    QStatusBar *sb = mw ? mw->statusBar() : nullptr;
    if (!s->streamJob || s->streamJob->done()) {
        s->streamPoll->stop();
        if (sb && sb->currentMessage().startsWith("NPR render: reading")) sb->clearMessage();
        if (s->widget) s->widget->update();
        return;
    }
    if (sb && !(s->job && !s->job->done()))
        sb->showMessage(QString("NPR render: reading the view's points %1%").arg((int)std::lround(100 * s->streamJob->fraction())));
}

/* The layer's stream, kept when it samples the same file from the same origin, else new. */
static std::unique_ptr<pnpr_meshlab::LayerStream> streamOf(DecorateContextState *s, int id, const std::string &path,
                                                           const double origin[3])
{
    for (auto &ls : s->streams)
        if (ls && ls->meshId == id && ls->path == path && std::memcmp(ls->origin, origin, sizeof ls->origin) == 0)
            return std::move(ls);
    std::unique_ptr<pnpr_meshlab::LayerStream> ls(new pnpr_meshlab::LayerStream);
    ls->meshId = id;
    ls->path = path;
    std::memcpy(ls->origin, origin, sizeof ls->origin);
    return ls;
}

/* Whether the file of ls is ordered for drawing, found once (logged when it is not). */
static bool streamable(pnpr_meshlab::LayerStream &ls, const QString &label, const Reporter &report)
{
    if (ls.ordered < 0) {
        pnpr_lod l;
        std::memset(&l, 0, sizeof l);
        pnpr_error err{};
        pnpr_status st = pnpr_lod_open(ls.path.c_str(), &l, &err);
        pnpr_lod_free(&l);
        ls.ordered = st == PNPR_OK;
        const QString file = QString::fromLocal8Bit(ls.path.c_str());
        const QString why = !QFileInfo(file).isFile()   ? QString("missing or not a regular file")
                            : st == PNPR_ERR_UNSUPPORTED ? QString("not ordered for drawing")
                                                         : status(st, err);
        if (st != PNPR_OK)
            report(QString("layer '%1' is a sample of %2, which is %3: the layer is drawn as it is, not streamed by the "
                           "view (pointnpr convert --lod orders a file for drawing; docs/meshlab.md)")
                       .arg(label).arg(file).arg(why), false);
    }
    return ls.ordered == 1;
}

/* After a frame: the sample layers whose file is ordered for drawing get the view now on screen
 * read for them when the camera rests (one read at a time, none while the stages run on the last
 * sample; a read of an older view is cancelled, and so is any read while the camera moves).
 * Layers no longer drawn, edited (stale stamp) or with the stream off go back to their own
 * vertices, and so does a layer whose view cannot be streamed (orthographic, a transformation
 * that is not a similarity): a sample of another view would lack what this one sees. */
static void planStream(MeshDocument &md, DecorateContextState *s, bool on, const double mv[16], const double P[16],
                       const GLint vp[4], bool moving, const Reporter &report)
{
    std::vector<std::unique_ptr<pnpr_meshlab::LayerStream>> kept;
    for (MeshModel *mm : md.meshList) {
        std::string path;
        double origin[3];
        if (on && isDrawnLayer(mm) && pnpr_meshlab::sampleSource(mm->cm, path, origin))
            kept.push_back(streamOf(s, mm->id(), path, origin));
    }
    for (auto &ls : s->streams)
        if (ls && ls->cloud.count) s->streamGen++; /* a sample drawn no more */
    s->streams = std::move(kept);
    bool jobKept = false; /* the running read is for a layer still streamed */
    for (auto &ls : s->streams) jobKept |= s->streamJob && s->streamJob->meshId == ls->meshId && s->streamJob->path == ls->path;
    if (s->streamJob && (moving || !jobKept)) s->streamJob->cancel();
    s->streamBusy = s->streamJob != nullptr;
    if (moving) return;
    for (auto &ls : s->streams) {
        MeshModel *mm = md.getMesh(ls->meshId);
        if (!mm || !streamable(*ls, mm->label(), report)) continue;
        double T[4][4];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) T[r][c] = mm->cm.Tr[r][c];
        pnpr_meshlab::StreamView v;
        if (!pnpr_meshlab::streamViewOf(mv, P, vp[2], vp[3], T, ls->origin, v)) {
            if (!ls->unstreamable)
                report(QString("the view of layer '%1' cannot be streamed (an orthographic view, or a transformation "
                               "that is not a similarity): the layer is drawn as it is").arg(mm->label()), false);
            ls->unstreamable = true;
            if (s->streamJob && s->streamJob->meshId == ls->meshId) s->streamJob->cancel();
            dropSample(s, *ls);
            ls->view = pnpr_meshlab::StreamView();
            continue;
        }
        ls->unstreamable = false;
        if (v == ls->view) continue;
        s->streamBusy = true;
        if (s->streamJob) { /* one at a time: this layer's read of an older view stops, and this one
                             * starts when it has (another layer's read is waited for) */
            if (s->streamJob->meshId == ls->meshId && s->streamJob->view != v) s->streamJob->cancel();
            continue;
        }
        if (s->job) continue; /* the stages on the last sample first: its frame, then the next read */
        std::unique_ptr<pnpr_meshlab::StreamJob> job(new pnpr_meshlab::StreamJob);
        std::string why;
        if (!job->start(ls->meshId, ls->path, v, (uint64_t)mm->cm.vn, why)) {
            ls->view = v;
            report(QString::fromStdString(why), true);
            continue;
        }
        s->streamJob = std::move(job);
        if (!s->streamPoll) {
            s->streamPoll = new QTimer;
            s->streamPoll->setInterval(100);
            QObject::connect(s->streamPoll, &QTimer::timeout, [s] { try { pollStream(s); } catch (...) {} });
        }
        s->streamPoll->start();
    }
}

/* test-only (PNPR_MESHLAB_TEST_INFOBOX): once MeshLab has finished the frame (its info box drawn
 * over ours), writes PREFIX-under-NAME (the viewport as the overlay found it) and PREFIX-host-NAME
 * (the frame shown), NAME plain (stage 0, undrawn) or npr (stage 1), and asks for the next frame. */
void DecoratePointnprPlugin::testGrabAfterPaint(void *ctx, int stage, const QString &prefix,
                                                std::vector<unsigned char> under, int w, int h)
{
    DecorateContextState *s = states_.value(ctx, nullptr);
    if (!s || !s->widget) return;
    QPointer<QWidget> widget = s->widget;
    auto shared = std::make_shared<std::vector<unsigned char>>(std::move(under));
    QTimer::singleShot(0, this, [this, ctx, stage, prefix, shared, w, h, widget] {
        try {
            DecorateContextState *st = states_.value(ctx, nullptr);
            std::vector<unsigned char> host;
            int hw = 0, hh = 0;
            if (!st || !widget || !pnpr_meshlab::grabWidgetFrame(widget, host, hw, hh)) return;
            QString name = stage == 0 ? "plain" : "npr";
            bool ok = writeImages(prefix + "-under-" + name, *shared, w, h) && writeImages(prefix + "-host-" + name, host, hw, hh);
            std::fprintf(stderr, "pointnpr decorator: info box frame '%s' %s (%dx%d, viewport %dx%d)\n", qUtf8Printable(name),
                         ok ? "written" : "FAILED", hw, hh, w, h);
            st->infoStage = stage + 1;
            widget->update();
        } catch (...) {
        }
    });
}

/* test-only: PNPR_MESHLAB_TEST_DRAG=SECONDS (docs/meshlab.md's frame rates): once a frame at rest is
 * drawn, drags the trackball with synthetic mouse events (a move every 10 ms, 3 px each, for
 * SECONDS), counts the frames drawn meanwhile and times the full-budget frame after the release. */
static void testDragFrame(DecorateContextState *s, bool moving, size_t drawn)
{
    QPointer<QWidget> w = s->widget;
    if (!w || s->dragPhase == 3) return;
    if (s->dragPhase == 0) {
        if (moving) return;
        double seconds = std::atof(std::getenv("PNPR_MESHLAB_TEST_DRAG"));
        if (!(seconds > 0 && seconds <= 60)) seconds = 2;
        s->dragPhase = 1;
        s->dragClock.start();
        QPoint c(w->width() / 2, w->height() / 2);
        QCoreApplication::postEvent(w.data(), new QMouseEvent(QEvent::MouseButtonPress, c, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier));
        auto step = std::make_shared<int>(0);
        QTimer *mover = new QTimer(w.data());
        QObject::connect(mover, &QTimer::timeout, [s, w, c, step, mover, seconds] {
            if (!w) return;
            QPoint p = c + QPoint((++*step * 3) % 200 - 100, 0);
            if (s->dragClock.elapsed() < (qint64)(seconds * 1000)) {
                QCoreApplication::postEvent(w.data(), new QMouseEvent(QEvent::MouseMove, p, Qt::NoButton, Qt::LeftButton, Qt::NoModifier));
                return;
            }
            mover->stop();
            mover->deleteLater();
            QCoreApplication::postEvent(w.data(), new QMouseEvent(QEvent::MouseButtonRelease, p, Qt::LeftButton, Qt::NoButton, Qt::NoModifier));
            s->dragPhase = 2;
            s->dragReleaseMs = s->dragClock.elapsed();
        });
        mover->start(10);
        return;
    }
    if (s->dragPhase == 1 && moving) {
        s->dragFrames++;
        s->dragPoints += drawn;
    }
    if (s->dragPhase == 2 && !moving) {
        s->dragPhase = 3;
        double secs = s->dragReleaseMs / 1000.0;
        QString line = QString("drag: %1 frames in %2 s (%3 frames/s, %4 points per frame, our draw %7 ms of each, %8 "
                               "at half resolution); full budget %5 ms after the release (%6 points)")
                           .arg(s->dragFrames).arg(secs, 0, 'f', 2).arg(secs > 0 ? s->dragFrames / secs : 0.0, 0, 'f', 1)
                           .arg(s->dragFrames ? s->dragPoints / s->dragFrames : 0)
                           .arg(s->dragClock.elapsed() - s->dragReleaseMs).arg(drawn)
                           .arg(s->dragFrames ? s->dragDrawMs / s->dragFrames : 0).arg(s->dragPreviews);
        std::fprintf(stderr, "pointnpr decorator: %s\n", qUtf8Printable(line));
        if (const char *snap = std::getenv("PNPR_MESHLAB_SNAPSHOT")) { /* PREFIX-drag.txt for the script */
            QFile f(QString::fromLocal8Bit(snap) + "-drag.txt");
            if (f.open(QIODevice::WriteOnly)) f.write((line + "\n").toUtf8());
        }
    }
}

/* The state of context ctx, made on its first frame (the renderer created there: one per context). */
DecorateContextState *DecoratePointnprPlugin::stateFor(void *ctx, GLLogStream &lg)
{
    DecorateContextState *s = states_.value(ctx, nullptr);
    if (!s) {
        s = new DecorateContextState;
        states_.insert(ctx, s);
        pnpr_meshlab::onGLContextDestroyed(ctx, this, [this, ctx] {
            try { dropState(ctx); } catch (...) {}
        });
        s->widget = pnpr_meshlab::currentGLWidget();
        s->settle = new QTimer;
        s->settle->setSingleShot(true);
        QPointer<QWidget> w = s->widget;
        QObject::connect(s->settle, &QTimer::timeout, [w] { if (w) w->update(); });
        pnpr_error err{};
        pnpr_status st = pnpr_renderer_create(nullptr, &s->renderer, &err);
        if (st != PNPR_OK) {
            s->failed = true;
            lg.Logf(GLLogStream::WARNING, "NPR render: cannot create the renderer: %s", qUtf8Printable(status(st, err)));
            std::fprintf(stderr, "pointnpr decorator: cannot create the renderer: %s\n", qUtf8Printable(status(st, err)));
        } else {
            lg.Logf(GLLogStream::FILTER, "NPR render: renderer created (OpenGL %s)",
                     (const char *)glGetString(GL_VERSION));
        }
    }
    return s;
}

/* test-only hooks that write what the filters would on the drawn layers, once per state (before
 * the layers are read) */
static void applyTestLayerHooks(MeshDocument &md, DecorateContextState *s)
{
    /* test-only: PNPR_MESHLAB_TEST_LAYER_CLASS=C gives the first drawn layer feature classes C and
     * directions (1,0,0), as the features filter's attributes (tests/meshlab/run.sh 'ownclass') */
    if (const char *tc = std::getenv("PNPR_MESHLAB_TEST_LAYER_CLASS")) {
        if (!s->testClassSet) {
            s->testClassSet = true;
            for (MeshModel *mm : md.meshList) {
                if (!isDrawnLayer(mm)) continue;
                auto hc = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<float>(mm->cm, PNPR_PROP_FEATURE_CLASS);
                auto hd = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Point3m>(mm->cm, PNPR_PROP_FEATURE_DIR);
                for (size_t i = 0; i < mm->cm.vert.size(); i++) {
                    hc[i] = (float)std::atof(tc);
                    hd[i] = Point3m(1, 0, 0);
                }
                break;
            }
        }
    }
    /* test-only: PNPR_MESHLAB_TEST_SAMPLE_OF=PATH[;PATH...] makes the drawn layers, in order, samples
     * of those files, their vertices offsets from PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="X Y Z" (default
     * 0 0 0; the layers' Tr from a project file places them there), as "NPR: Open a sample of a
     * large PLY" makes its layer (tests/meshlab/run.sh 'stream') */
    if (const char *so = std::getenv("PNPR_MESHLAB_TEST_SAMPLE_OF")) {
        if (!s->testSampleSet) {
            s->testSampleSet = true;
            double origin[3] = {0, 0, 0};
            if (const char *o = std::getenv("PNPR_MESHLAB_TEST_SAMPLE_ORIGIN"))
                std::sscanf(o, "%lf %lf %lf", &origin[0], &origin[1], &origin[2]);
            const QStringList files = QString::fromLocal8Bit(so).split(';');
            int i = 0;
            for (MeshModel *mm : md.meshList) {
                if (!isDrawnLayer(mm) || i >= files.size()) continue;
                pnpr_meshlab::setSampleSource(mm->cm, files[i++].toLocal8Bit().toStdString(), origin);
                pnpr_meshlab::writeStamp(mm->cm);
            }
        }
    }
    /* test-only: PNPR_MESHLAB_TEST_LAYER_STYLES=cartoon,points gives the drawn layers, in order, their
     * own styles as the filter "NPR: Set layer style" does (tests/meshlab/run.sh 'layers') */
    if (const char *tls = std::getenv("PNPR_MESHLAB_TEST_LAYER_STYLES")) {
        if (!s->testStylesSet) {
            s->testStylesSet = true;
            QStringList names = QString::fromLocal8Bit(tls).split(',');
            int i = 0;
            for (MeshModel *mm : md.meshList) {
                pnpr_style st;
                if (isDrawnLayer(mm) && i < names.size() &&
                    pnpr_style_from_name(qUtf8Printable(names[i++]), &st) == PNPR_OK)
                    pnpr_meshlab::setLayerStyle(mm->cm, (int)st);
            }
        }
    }
}

/* Uploads the cloud when it changed (with painterly's data when a frame paints, keyed by the
 * layer index for styles per layer); false when the upload failed (logged). */
static bool uploadIfNeeded(DecorateContextState *s, const pnpr_tone_options &tone, bool paints, bool keyed,
                           uint32_t styles, const Reporter &report)
{
    if (s->needUpload) {
        QElapsedTimer t;
        t.start();
        pnpr_upload_options uo;
        std::memset(&uo, 0, sizeof uo);
        uo.tone = tone; /* colourless clouds: greys lit from the scene's up */
        uo.tone_radius = s->toneRadius; /* a stream's spacing grows by its share: the hatches keep the file's */
        uo.skip_painterly = !paints;
        s->skippedPainterly = !paints;
        uo.style_key = keyed ? kLayerKey : nullptr;
        s->keyedUpload = keyed;
        pnpr_error err{};
        pnpr_status st = pnpr_renderer_set_cloud(s->renderer, &s->cloud, &uo, &err);
        s->needUpload = false;
        s->uploads++;
        if (st != PNPR_OK) {
            s->uploadFailed = true;
            report("cannot upload the layers: " + status(st, err), true);
            return false;
        }
        report(QString("uploaded %1 (layers read in %2 ms, upload %3 ms)").arg(s->layersNote).arg(s->layersMs).arg(t.elapsed()),
               false);
        s->uploaded = true;
        s->uploadedLayersSig = s->layersSig;
        s->uploadedStyles = styles;
    }
    return true;
}

/* The frame's draw options from the panel, the styles of the layers, the motion and the tiles.
 * r_budgetTimed: the time, not the parameters, set this frame's budget. */
static pnpr_draw_options frameOptions(DecorateContextState *s, const Params &prm, const LayerStyles &ls, bool plainPoints,
                                      bool keyed, bool moving, bool tile, bool &r_budgetTimed)
{
    r_budgetTimed = false;
    pnpr_draw_options o;
    std::memset(&o, 0, sizeof o);
    o.style = plainPoints ? PNPR_STYLE_POINTS : ls.main;
    if ((keyed && s->keyedUpload) || (ls.bySegment && !plainPoints && !s->keyedUpload)) {
        o.style_map = ls.map.data();
        o.style_map_count = ls.map.size();
    }
    o.sketch_variant = prm.variant;
    o.background[0] = (float)prm.paper.redF();
    o.background[1] = (float)prm.paper.greenF();
    o.background[2] = (float)prm.paper.blueF();
    o.background[3] = 1;
    o.budget = (size_t)prm.budget;
    o.density = prm.density;
    if (moving && prm.motionBudget > 0 && (prm.budget == 0 || prm.motionBudget < prm.budget))
        o.budget = (size_t)prm.motionBudget;
    /* while moving, the budget also follows the time our draw took in the last moving frames: about
     * kMotionDrawMs for our part of a frame (MeshLab redraws its own layers under ours too) */
    if (moving && s->motionMsPerPoint > 0) {
        size_t timed = (size_t)std::max((double)kMotionMinPoints, kMotionDrawMs / s->motionMsPerPoint);
        r_budgetTimed = o.budget == 0 || timed < o.budget;
        o.budget = o.budget > 0 ? std::min(o.budget, timed) : timed;
    }
    if (ls.bits != s->slowBits || s->signature != s->slowSignature) { /* learnt per style and layers */
        s->slowFrames = 0;
        s->slowBits = ls.bits;
        s->slowSignature = s->signature;
    }
    if (tile && s->restW > 0) { /* the tile draws the points the view on screen draws (the per-cell queues' plan) */
        o.plan_matrices = &s->restCam;
        o.plan_width = s->restW;
        o.plan_height = s->restH;
    }
    o.line_width = prm.lineWidth;
    o.brush_preset = prm.brush;
    o.brush_scale = prm.brushScale;
    o.hierarchy.tam = prm.tam;
    o.hierarchy.abstraction = prm.abstraction;
    o.hierarchy.stroke_px = prm.strokePx;
    o.stroke_width = prm.lineWidth;
    o.outline = plainPoints ? -1 : prm.outline;
    o.outline_width = prm.outlineWidth;
    if (prm.look && !plainPoints) { /* the look fills what the dialog leaves at its defaults */
        const pnpr_option_desc *lw = drawOption("line-width");
        if (lw && o.line_width == (float)lw->def) o.line_width = o.stroke_width = 0;
        if (prm.paper == QColor(255, 255, 255)) std::memset(o.background, 0, sizeof o.background);
        pnpr_look_apply(prm.look, &o);
        o.style = ls.main; /* the look's style, or a layer's own */
    }
    return o;
}

/* Whether the renderer's previous upload is drawn while the stages run on a new stream: the same
 * layers (the streams' part aside), uploaded for these styles and this key, not the hierarchy. */
static bool drawsPrevious(const DecorateContextState *s, uint32_t styles, bool keyed)
{
    return s->drawPrevious && styles == s->uploadedStyles && keyed == s->keyedUpload &&
           !(styles & (1u << PNPR_STYLE_HIERARCHY));
}

void DecoratePointnprPlugin::draw(MeshDocument &md, const RichParameterList *par, GLLogStream &lg)
{
    void *ctx = pnpr_meshlab::currentGLContext();
    if (!ctx) return;
    DecorateContextState *s = stateFor(ctx, lg);
    if (s->failed || !s->renderer) return;
    Params prm = readParams(par);
    Reporter report = [&lg, s](const QString &msg, bool warning) {
        if (msg == s->lastError) return;
        s->lastError = msg;
        lg.Logf(warning ? GLLogStream::WARNING : GLLogStream::FILTER, "NPR render: %s", qUtf8Printable(msg));
        std::fprintf(stderr, "pointnpr decorator: %s\n", qUtf8Printable(msg));
    };
    QString fxKeyBefore = s->fxKey, fxMsg;
    bool fxOn = loadEffects(s, prm.effects, fxMsg);
    if (s->fxKey != fxKeyBefore && !fxMsg.isEmpty()) report(fxMsg, !fxOn);

    applyTestLayerHooks(md, s);
    takeStream(s, report);
    if (!refreshLayers(md, s, report)) return; /* nothing to draw over MeshLab's own frame */
    QString smapMsg, smapKeyBefore = s->smapKey;
    bool mapOn = !fxOn && loadStyleMap(s, prm.styleMap, smapMsg);
    if (s->smapKey != smapKeyBefore && !smapMsg.isEmpty()) report(smapMsg, !mapOn);
    LayerStyles ls = layerStyles(md, s, prm.style, fxOn, mapOn);
    if (ls.text != s->lastLayerStyles) {
        s->lastLayerStyles = ls.text;
        if (!ls.text.isEmpty()) report("styles per layer: " + ls.text, false);
    }
    pnpr_error err{};
    pnpr_tone_options tone;
    std::memset(&tone, 0, sizeof tone);
    tone.source = prm.toneSource;
    tone.gamma = prm.toneGamma;
    std::memcpy(tone.up, s->up, sizeof tone.up);

    /* 2. the plan; what it asks for runs on a worker thread while plain points are drawn. A running
     * computation finishes first (a style changed meanwhile is planned when its results are in). */
    if (s->job && s->job->done()) finishJob(s, report);
    if (!s->job) {
        pnpr_plan plan;
        if (!makePlan(s, prm, ls.bits, tone, plan, report)) return;
        pnpr_meshlab::StageRequest rq = stageRequest(s, plan, tone, styleNames(ls.bits));
        if (rq.any()) startJob(s, rq, drawsPrevious(s, ls.bits, !s->cancelled && !ls.map.empty() && !ls.bySegment), report);
    }
    /* plain points after a cancel (the style lacks what it needs) */
    bool plainPoints = s->cancelled;
    /* painterly's data (12-neighbour lists, colour passes: 4x the upload time and memory) only
     * for a frame that paints; a later painterly frame uploads again */
    bool paints = !plainPoints && (ls.bits & (1u << PNPR_STYLE_PAINTERLY));
    bool keyed = !plainPoints && !ls.map.empty() && !ls.bySegment; /* styles per layer: the map reads the layer index */
    /* While computing, MeshLab's own frame (its plain points) stays: nothing is uploaded or drawn,
     * so the GUI thread is free (an upload's spacing kNN would hold it as long as the features).
     * After a new stream alone, the renderer's previous sample of the same layers is drawn
     * meanwhile, for the styles it was uploaded for (not uploaded again; not for the hierarchy
     * style, whose tree went with the old sample). */
    const bool previous = s->job && drawsPrevious(s, ls.bits, keyed);
    if (s->job && !previous) return;
    if (paints && s->skippedPainterly) s->needUpload = true;
    if (keyed != s->keyedUpload) s->needUpload = true; /* the key: the layer index, or the segments */
    if (!previous && !uploadIfNeeded(s, tone, paints, keyed, ls.bits, report)) return;
    if (!s->job) s->drawPrevious = false;
    if (s->linesPending && !previous) {
        s->linesPending = false;
        pnpr_status st = pnpr_renderer_set_lines(s->renderer, &s->lines, &err);
        if (st != PNPR_OK) report("profile lines failed: " + status(st, err), true);
    }

    /* 3. camera from MeshLab's matrices; motion = the matrices changed since the last frame */
    double mv[16], P[16];
    GLint vp[4], fb = 0;
    glGetDoublev(GL_MODELVIEW_MATRIX, mv);
    glGetDoublev(GL_PROJECTION_MATRIX, P);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    /* MeshLab's tiled "Save snapshot" draws its tiles with off-centre frusta (a symmetric frustum
     * has P[8] = P[9] = 0, a symmetric orthographic box P[12] = P[13] = 0) k times narrower than
     * the view's (P[0] k times larger); the middle tile of an odd multiplier is symmetric, and is
     * told by its P[0], k times the view's, right after the off-centre ones. A tile is not camera
     * motion; its queue is planned for the view on screen at rest (pnpr_draw_options.plan_matrices:
     * the points the screen draws, cell by cell; a tile's own coverage would differ from tile to
     * tile and leave seams) and every width is k times. */
    bool offCentre = P[15] == 0 ? (P[8] != 0 || P[9] != 0) : (P[12] != 0 || P[13] != 0);
    double zoom = s->screenScale > 0 ? std::fabs(P[0]) / s->screenScale : 1;
    if (offCentre) s->snapK = zoom;
    else if (!(s->snapK > 0 && std::fabs(zoom - s->snapK) <= 1e-6 * s->snapK)) s->snapK = 0;
    bool tile = s->snapK > 0;
    bool moving = !tile && s->haveLast &&
                  (std::memcmp(mv, s->lastMV, sizeof mv) != 0 || std::memcmp(P, s->lastP, sizeof P) != 0);
    std::memcpy(s->lastMV, mv, sizeof mv);
    std::memcpy(s->lastP, P, sizeof P);
    s->haveLast = true;
    /* MeshLab's matrices as they are (the cloud is in scene coordinates, the layers' Tr already
     * applied, and the modelview holds view x trackball): perspective, orthographic and the
     * off-centre frusta of the tiled "Save snapshot" alike. The renderer rebases the view on the
     * cloud's origin in double and refuses matrices it cannot use (PNPR_ERR_NUMERIC). */
    pnpr_camera_matrices cm;
    std::memcpy(cm.view, mv, sizeof mv);
    std::memcpy(cm.projection, P, sizeof P);
    if (vp[2] <= 0 || vp[3] <= 0) return;

    pnpr_renderer_set_hierarchy(s->renderer, s->treeReady ? &s->tree : nullptr);
    bool budgetTimed = false;
    pnpr_draw_options o = frameOptions(s, prm, ls, plainPoints, keyed, moving, tile, budgetTimed);
    if (tile) {
        scaleWidths(o, s->snapK);
        report(QString("snapshot tiles at %1x the view: the points of the view on screen, widths %1x").arg(s->snapK, 0, 'g', 3), false);
    } else {
        s->screenScale = std::fabs(P[0]);
    }
    o.composite = PNPR_COMPOSITE_REPLACE;
    o.matrices = &cm;
    pnpr_target tg;
    std::memset(&tg, 0, sizeof tg);
    tg.framebuffer = (uint32_t)fb;
    tg.x = vp[0];
    tg.y = vp[1];
    tg.width = vp[2];
    tg.height = vp[3];
    /* a tile of "Save snapshot": drawn with the renderer's guard band, so that the sprites, strokes
     * and outlines of the points beyond its border are whole (else GL drops the sprites whose
     * centre lies outside, and strokes and outlines stop at the tile's edge: seams) */
    if (tile) tg.guard = -1;

    const char *snap = std::getenv("PNPR_MESHLAB_SNAPSHOT");
    /* test mode: the snapshot is taken on the 3rd frame with unchanged matrices */
    bool takeSnap = snap && !s->snapshotDone && !moving && !s->streamBusy && !s->job && ++s->frames >= 3 &&
                    !(std::getenv("PNPR_MESHLAB_TEST_INFOBOX") && s->infoStage < 2); /* after the info box frames */
    std::vector<unsigned char> plain, npr;

    /* test-only: PNPR_MESHLAB_TEST_INFOBOX=PREFIX (tests/meshlab/run.sh 'infobox'): a frame at rest
     * left undrawn, then one drawn; of each, the viewport as MeshLab's overlay (the info box) finds
     * it and the whole frame once MeshLab has drawn the overlay */
    const char *infoPrefix = std::getenv("PNPR_MESHLAB_TEST_INFOBOX");
    int infoStage = infoPrefix && !moving && !tile && s->infoStage < 2 && ++s->infoFrames >= 3 ? s->infoStage : -1;
    std::vector<unsigned char> under;

    /* MeshLab calls decorateDoc outside its own glPushAttrib: save the legacy state here too. In a
     * compatibility context gl_PointCoord needs GL_POINT_SPRITE (the core renderer assumes it). */
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
    if (takeSnap) readViewport(vp, plain);
    if (infoStage == 0) {
        readViewport(vp, under);
        glPopClientAttrib();
        glPopAttrib();
        testGrabAfterPaint(ctx, 0, QString::fromLocal8Bit(infoPrefix), std::move(under), vp[2], vp[3]);
        return;
    }
    glEnable(GL_POINT_SPRITE);
    pnpr_render_stats stats;
    std::memset(&stats, 0, sizeof stats);
    pnpr_effects_stats es;
    std::memset(&es, 0, sizeof es);
    bool fxDraw = fxOn && !plainPoints;
    /* moving frames are timed (finished before and after: the swap waits for them anyway) */
    QElapsedTimer drawClock;
    if (moving) {
        glFinish();
        drawClock.start();
    }
    /* while moving, a style whose frames stay slow at the time-following budget (two in a row over
     * 1.25 kMotionDrawMs: its cost is in the pixels, fewer points draw larger disks) is drawn at
     * kMotionPreviewScale of the viewport, for these styles and layers from then on */
    bool preview = moving && !fxDraw && !tile && (s->slowFrames >= 2 || std::getenv("PNPR_MESHLAB_TEST_PREVIEW"));
    pnpr_status st = fxDraw    ? drawEffects(s, o, vp, fb, moving ? prm.effectsPreview : 0.0f, es, &err)
                     : preview ? drawPreview(s, o, vp, fb, kMotionPreviewScale, &stats, &err)
                               : pnpr_renderer_draw(s->renderer, nullptr, &o, &tg, &stats, &err);
    if (moving) {
        glFinish();
        qint64 ms = drawClock.nsecsElapsed() / 1000000;
        if (st == PNPR_OK && stats.points_sent > 0) { /* slower at once, faster over about 4 frames */
            /* per vertex sent: what the budget caps (the shaders drop the far cells' extra ones) */
            double perPoint = (double)drawClock.nsecsElapsed() / 1e6 / (double)stats.points_sent;
            s->motionMsPerPoint = s->motionMsPerPoint > 0 && perPoint < s->motionMsPerPoint
                                      ? 0.75 * s->motionMsPerPoint + 0.25 * perPoint
                                      : perPoint;
        }
        if (s->dragPhase == 1) s->dragDrawMs += ms; /* test hook PNPR_MESHLAB_TEST_DRAG: our share of a frame */
        if (!preview && budgetTimed) s->slowFrames = ms > 1.25 * kMotionDrawMs ? s->slowFrames + 1 : 0; /* in a row */
        if (preview && s->dragPhase == 1) s->dragPreviews++;
    }
    if (takeSnap && st == PNPR_OK) readViewport(vp, npr);
    if (infoStage == 1 && st == PNPR_OK && readViewport(vp, under))
        testGrabAfterPaint(ctx, 1, QString::fromLocal8Bit(infoPrefix), std::move(under), vp[2], vp[3]);
    glPopClientAttrib();
    glPopAttrib();
    if (st != PNPR_OK) {
        if (previous) return; /* the previous upload cannot draw this frame: MeshLab's points until the stages end */
        report(QString("draw (%1) failed: %2").arg(fxDraw ? QString("effects") : styleNames(ls.bits)).arg(status(st, err)), true);
        return;
    }
    if (!tile) planStream(md, s, prm.stream, mv, P, vp, moving, report);
    if (!tile && !moving && !fxDraw) {
        s->restCam = cm;
        s->restW = vp[2];
        s->restH = vp[3];
    }
    if (s->restarted) {
        s->restarted = false;
        report(QString("decoration restarted by MeshLab (a parameter applied or a filter run): layers, features and "
                       "upload kept (%1 upload(s) so far)").arg(s->uploads), false);
    }
    /* test-only: PNPR_MESHLAB_TEST_RESTART=1 has MeshLab restart the decoration after the 2nd frame,
     * as applying a parameter does (tests/meshlab/run.sh decorate, run 'restart') */
    if (++s->framesDrawn == 2 && std::getenv("PNPR_MESHLAB_TEST_RESTART") && s->widget)
        QMetaObject::invokeMethod(s->widget.data(), "updateAllDecorators", Qt::QueuedConnection);
    if (fxDraw) report(QString("effects frame: %1 layers of %2x%3%4").arg(es.layers).arg(es.layer_width).arg(es.layer_height)
                         .arg(moving ? " (preview while moving)" : ""), false);
    if (moving && s->settle) s->settle->start(300); /* a full-budget frame once the camera rests */
    if (std::getenv("PNPR_MESHLAB_TEST_DRAG")) testDragFrame(s, moving, stats.points_drawn);
    /* test-only: PNPR_MESHLAB_TEST_WHEEL=N turns the mouse wheel N notches (zooms in) at the
     * first frame at rest, then with PNPR_MESHLAB_TEST_ORTHO toggles MeshLab's orthographic
     * camera (tests/meshlab/run.sh 'stream') */
    if (const char *wh = std::getenv("PNPR_MESHLAB_TEST_WHEEL")) {
        if (!s->testWheelDone && !moving && s->widget) {
            s->testWheelDone = true;
            QPointF c(s->widget->width() / 2.0, s->widget->height() / 2.0);
            for (int i = 0; i < std::min(50, std::max(0, std::atoi(wh))); i++)
                QCoreApplication::postEvent(s->widget.data(), new QWheelEvent(c, QPointF(s->widget->mapToGlobal(c.toPoint())), QPoint(), QPoint(0, -120),
                                                                              Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false));
            QMainWindow *mw = qobject_cast<QMainWindow *>(s->widget->window());
            if (std::getenv("PNPR_MESHLAB_TEST_ORTHO") && mw) /* MeshLab's View > Toggle Orthographic Camera */
                for (QAction *a : mw->findChildren<QAction *>())
                    if (a->text() == "Toggle Orthographic Camera") {
                        QTimer::singleShot(0, a, &QAction::trigger);
                        break;
                    }
        }
    }

    if (snap && !s->snapshotDone) {
        if (takeSnap && !plain.empty() && !npr.empty()) {
            s->snapshotDone = true;
            QString prefix = QString::fromLocal8Bit(snap);
            bool ok = writeImages(prefix + "-plain", plain, vp[2], vp[3]) && writeImages(prefix + "-npr", npr, vp[2], vp[3]);
            QFile f(prefix + "-camera.txt");
            if (ok && f.open(QIODevice::WriteOnly)) {
                QString txt = "modelview";
                for (double v : mv) txt += QString(" %1").arg(v, 0, 'g', 17);
                txt += "\nprojection";
                for (double v : P) txt += QString(" %1").arg(v, 0, 'g', 17);
                txt += QString("\nviewport %1 %2 %3 %4\nstyle %5\npoints %6 drawn %7 strokes %8\n")
                           .arg(vp[0]).arg(vp[1]).arg(vp[2]).arg(vp[3]).arg(pnpr_style_name(prm.style))
                           .arg(stats.points_total).arg(stats.points_drawn).arg(stats.strokes_drawn);
                if (fxDraw)
                    txt += QString("effects %1 layers %2 of %3x%4\n").arg(prm.effects).arg(es.layers).arg(es.layer_width)
                               .arg(es.layer_height);
                ok = f.write(txt.toUtf8()) > 0;
                f.close();
            }
            std::fprintf(stderr, "pointnpr decorator: snapshot %s %s\n", snap, ok ? "written" : "FAILED");
            if (ok && std::getenv("PNPR_MESHLAB_TEST_SAVE_SNAPSHOT"))
                QTimer::singleShot(300, qApp, [] { try { testSaveSnapshot(); } catch (...) {} });
        } else if (s->widget) {
            QPointer<QWidget> w = s->widget;
            QTimer::singleShot(200, w.data(), [w] { if (w) w->update(); }); /* more frames until it is taken */
        }
    }
}
