/* pointnpr — MeshLab 2020.09 decorate plugin "NPR render": draws the visible point layers with the
 * pointnpr renderer (include/pointnpr/render.h) in MeshLab's viewport. A thin Qt adapter; the
 * work is pnpr_* calls. One renderer per GL context, kept in the plugin instance (no globals).
 * See docs/meshlab.md (section "NPR render decorator"). */
#ifndef POINTNPR_DECORATE_POINTNPR_H
#define POINTNPR_DECORATE_POINTNPR_H

#include <common/interfaces.h>

#include <QHash>
#include <QSet>
#include <QString>

#include <vector>

class QTimer;
struct DecorateContextState;

class DecoratePointnprPlugin : public QObject, public MeshDecorateInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_DECORATE_INTERFACE_IID)
    Q_INTERFACES(MeshDecorateInterface)

public:
    enum { DP_NPR_RENDER };

    DecoratePointnprPlugin();
    ~DecoratePointnprPlugin() override;

    QString pluginName() const override;
    QString decorationName(FilterIDType id) const override;
    QString decorationInfo(FilterIDType id) const override;
    int getDecorationClass(QAction *a) const override;
    void initGlobalParameterSet(QAction *a, RichParameterList &par) override;
    bool startDecorate(QAction *a, MeshDocument &md, const RichParameterList *par, GLArea *gla) override;
    void endDecorate(QAction *a, MeshDocument &md, const RichParameterList *par, GLArea *gla) override;
    void decorateMesh(QAction *, MeshModel &, const RichParameterList *, GLArea *, QPainter *,
                      GLLogStream &) override {}
    void decorateDoc(QAction *a, MeshDocument &md, const RichParameterList *par, GLArea *gla,
                     QPainter *painter, GLLogStream &log) override;

private:
    void draw(MeshDocument &md, const RichParameterList *par, GLLogStream &lg);
    void dropState(void *ctx);
    DecorateContextState *stateFor(void *ctx, GLLogStream &lg);
    void testStartupPoll();
    void testGrabAfterPaint(void *ctx, int stage, const QString &prefix, std::vector<unsigned char> under, int w, int h);

    QHash<void *, DecorateContextState *> states_; /* one renderer per GL context (QOpenGLContext) */
    QSet<void *> ending_; /* contexts whose decoration ended: dropped unless it restarts at once */
    QTimer *startupTimer_ = nullptr; /* test mode only (PNPR_MESHLAB_DECORATE_AT_START) */
    int startupTicks_ = 0;
    int seenTicks_ = 0; /* ticks since a visible GLArea appeared */
};

#endif
