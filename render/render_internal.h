/* Internal helpers shared by the renderer sources (not installed). The camera helpers
 * (pnpr_frame_camera and its functions) are pure CPU and live in the core library with the
 * cameras: view/view_internal.h. */
#ifndef PNPR_RENDER_INTERNAL_H
#define PNPR_RENDER_INTERNAL_H

#include <pointnpr/render.h>

#include "../view/view_internal.h"

#endif
