/* pointnpr — Qt OpenGL-context helpers of the decorator (see decorate_glcontext.h). */
#include "decorate_glcontext.h"

#include <QGLContext>
#include <QGLWidget>
#include <QOpenGLContext>
#include <QWidget>

namespace pnpr_meshlab {

void *currentGLContext() { return QOpenGLContext::currentContext(); }

QWidget *currentGLWidget()
{
    const QGLContext *qgl = QGLContext::currentContext();
    return qgl ? dynamic_cast<QWidget *>(qgl->device()) : nullptr;
}

bool makeWidgetCurrent(QWidget *widget)
{
    QGLWidget *gl = qobject_cast<QGLWidget *>(widget);
    if (!gl) return false;
    gl->makeCurrent();
    return true;
}

void onGLContextDestroyed(void *ctx, QObject *receiver, std::function<void()> fn)
{
    if (!ctx) return;
    QObject::connect(static_cast<QOpenGLContext *>(ctx), &QOpenGLContext::aboutToBeDestroyed, receiver,
                     [fn] { fn(); });
}

} // namespace pnpr_meshlab
