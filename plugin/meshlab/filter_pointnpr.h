/* pointnpr — MeshLab 2020.09 filter plugin: a thin adapter over the C API (include/pointnpr/).
 * C++ only because MeshLab's plugin interface is a Qt class; all the work is pnpr_* calls.
 * See docs/meshlab.md for the filters, their parameters and where the results are stored. */
#ifndef POINTNPR_FILTER_POINTNPR_H
#define POINTNPR_FILTER_POINTNPR_H

#include <common/interfaces.h>

class FilterPointnprPlugin : public QObject, public MeshFilterInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
    Q_INTERFACES(MeshFilterInterface)

public:
    enum { FP_FEATURES, FP_SELECT_FEATURES };

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
    bool fail(const QString &message);
};

#endif
