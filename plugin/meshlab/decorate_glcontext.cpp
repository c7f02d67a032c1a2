/* pointnpr — Qt OpenGL-context helpers of the decorator (see decorate_glcontext.h). */
#include "decorate_glcontext.h"

#include <QGLContext>
#include <QGLWidget>
#include <QImage>
#include <QOpenGLContext>
#include <QWidget>

#include <algorithm>

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

bool grabWidgetFrame(QWidget *widget, std::vector<unsigned char> &r_rgba, int &r_width, int &r_height)
{
    QGLWidget *gl = qobject_cast<QGLWidget *>(widget);
    if (!gl) return false;
    QImage img = gl->grabFrameBuffer().convertToFormat(QImage::Format_RGBA8888);
    r_width = img.width();
    r_height = img.height();
    r_rgba.resize((size_t)r_width * r_height * 4);
    for (int y = 0; y < r_height; y++)
        std::copy(img.constScanLine(r_height - 1 - y), img.constScanLine(r_height - 1 - y) + 4 * r_width,
                  r_rgba.begin() + (size_t)y * r_width * 4);
    return r_width > 0 && r_height > 0;
}

void onGLContextDestroyed(void *ctx, QObject *receiver, std::function<void()> fn)
{
    if (!ctx) return;
    QObject::connect(static_cast<QOpenGLContext *>(ctx), &QOpenGLContext::aboutToBeDestroyed, receiver,
                     [fn] { fn(); });
}

} // namespace pnpr_meshlab
