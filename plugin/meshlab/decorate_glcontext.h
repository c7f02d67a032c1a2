/* pointnpr — the few Qt OpenGL-context calls of the decorator, in their own translation unit:
 * MeshLab's interfaces.h pulls in GLEW, and Qt's QOpenGLContext/QGLContext headers refuse to be
 * included after GLEW (#warning, an error under -Werror). */
#ifndef POINTNPR_DECORATE_GLCONTEXT_H
#define POINTNPR_DECORATE_GLCONTEXT_H

#include <functional>
#include <vector>

class QObject;
class QWidget;

namespace pnpr_meshlab {
/* The current QOpenGLContext (as an opaque key), or nullptr. */
void *currentGLContext();
/* The widget of the current QGLContext (MeshLab's GLArea), or nullptr. */
QWidget *currentGLWidget();
/* Makes the GL context of `widget` (MeshLab's GLArea, a QGLWidget) current; false if it has none. */
bool makeWidgetCurrent(QWidget *widget);
/* The frame MeshLab last showed in `widget` (QGLWidget::grabFrameBuffer) as RGBA rows bottom-up, as
 * glReadPixels gives them; false if it is not a QGLWidget. Test hooks only. */
bool grabWidgetFrame(QWidget *widget, std::vector<unsigned char> &r_rgba, int &r_width, int &r_height);
/* Calls fn when the context `ctx` is about to be destroyed (while `receiver` lives). */
void onGLContextDestroyed(void *ctx, QObject *receiver, std::function<void()> fn);
} // namespace pnpr_meshlab

#endif
