/* pointnpr — MeshLab 2020.09 filter plugin: a thin adapter over the C API (include/pointnpr/).
 * C++ only because MeshLab's plugin interface is a Qt class; all the work is pnpr_* calls.
 * See docs/meshlab.md for the filters, their parameters and where the results are stored. */
#ifndef POINTNPR_FILTER_POINTNPR_H
#define POINTNPR_FILTER_POINTNPR_H

#include <common/interfaces.h>

#include <pointnpr/features.h>

#include <QString>

struct LayerCloud;
struct ProgressBridge;

class FilterPointnprPlugin : public QObject, public MeshFilterInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
    Q_INTERFACES(MeshFilterInterface)

public:
    enum { FP_FEATURES, FP_SELECT_FEATURES, FP_PROFILE_LINES, FP_SEGMENT_JSEG, FP_SEGMENT_GROW, FP_LAYER_STYLE,
           FP_OPEN_SAMPLE };

    FilterPointnprPlugin();

    QString pluginName() const override;
    QString filterName(FilterIDType filter) const override;
    QString filterInfo(FilterIDType filter) const override;
    FilterClass getClass(QAction *a) override;
    FILTER_ARITY filterArity(QAction *a) const override;
    int getPreConditions(QAction *a) const override;
    int postCondition(QAction *a) const override;
    void initParameterSet(QAction *a, MeshModel &m, RichParameterList &par) override;
    bool applyFilter(QAction *a, MeshDocument &md, const RichParameterList &par,
                     vcg::CallBackPos *cb) override;

private:
    bool computeFeatures(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb);
    bool selectFeatures(MeshDocument &md, const RichParameterList &par);
    bool profileLines(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb);
    bool segment(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb, bool jseg);
    bool layerStyle(MeshDocument &md, const RichParameterList &par);
    bool openSample(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb);
    bool fail(const QString &message);

    /* shared by the filters: the current layer -> pnpr_cloud, the feature analysis */
    bool loadLayerCloud(MeshModel &mm, bool withColor, bool withLayerNormals, const char *what,
                        const char *leftOutNote, LayerCloud &lc);
    bool checkFeatureParams(const RichParameterList &par, bool all, pnpr_features_options &fo);
    bool runFeatures(LayerCloud &lc, pnpr_features_options &fo, ProgressBridge &pb, pnpr_features_stats &stats,
                     double &seconds);
};

#endif
