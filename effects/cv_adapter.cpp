// OpenCV building blocks for the image-space effects (effects_internal.h): a thin C++ adapter.
extern "C" {
#include "effects_internal.h"
}

extern "C" int pnpr_cv_available(void)
{
#ifdef PNPR_HAVE_OPENCV
    return 1;
#else
    return 0;
#endif
}
