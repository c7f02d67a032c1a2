// OpenCV building blocks for the image-space effects (effects_internal.h): a thin C++ adapter.
// Every function wraps caller-owned float buffers (interleaved, 1 or 3 channels, top row first)
// in cv::Mat headers without copying, calls one OpenCV function and maps exceptions to
// pnpr_status (std::bad_alloc and OpenCV's StsNoMem -> PNPR_ERR_OUT_OF_MEMORY, any other
// cv::Exception -> PNPR_ERR_UNSUPPORTED). Borders replicate the edge pixels. No global state is
// touched: OpenCV's own threading splits the work by rows, which gives the same bytes whatever the
// thread count, so cv::setNumThreads is left alone.
extern "C" {
#include "effects_internal.h"
}

#ifdef PNPR_HAVE_OPENCV
#include <new>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace {

pnpr_status check_args(const void *a, const void *b, int w, int h, int ch, const char *what, pnpr_error *err)
{
    if (!a || !b || w <= 0 || h <= 0 || (ch != 1 && ch != 3))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: %s: bad buffer (%dx%d, %d channels)", what, w,
                              h, ch);
    return PNPR_OK;
}

cv::Mat wrap(const float *p, int w, int h, int ch)
{
    return cv::Mat(h, w, CV_32FC(ch), const_cast<float *>(p));
}

// Runs f, mapping exceptions to a status with a message naming the building block.
template <typename F> pnpr_status guarded(const char *what, pnpr_error *err, F f)
{
    try {
        f();
        return PNPR_OK;
    } catch (const cv::Exception &e) {
        if (e.code == cv::Error::StsNoMem)
            return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "effects: %s: out of memory", what);
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "effects: %s: OpenCV: %s", what, e.err.c_str());
    } catch (const std::bad_alloc &) {
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "effects: %s: out of memory", what);
    } catch (...) {
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "effects: %s: unexpected exception", what);
    }
}

} // namespace

extern "C" int pnpr_cv_available(void)
{
    return 1;
}

extern "C" pnpr_status pnpr_cv_bilateral(const float *src, float *dst, int w, int h, int ch, int radius,
                                         float sigma_color, float sigma_space, pnpr_error *err)
{
    pnpr_status st = check_args(src, dst, w, h, ch, "bilateral filter", err);
    if (st != PNPR_OK) return st;
    if (src == dst || radius < 1 || !(sigma_color > 0) || !(sigma_space > 0))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: bilateral filter: bad arguments");
    return guarded("bilateral filter", err, [&] {
        cv::Mat out = wrap(dst, w, h, ch);
        cv::bilateralFilter(wrap(src, w, h, ch), out, 2 * radius + 1, sigma_color, sigma_space,
                            cv::BORDER_REPLICATE);
    });
}

extern "C" pnpr_status pnpr_cv_gaussian(const float *src, float *dst, int w, int h, int ch, float sigma,
                                        pnpr_error *err)
{
    pnpr_status st = check_args(src, dst, w, h, ch, "Gaussian blur", err);
    if (st != PNPR_OK) return st;
    if (!(sigma > 0) || sigma > 1000)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: Gaussian blur: bad sigma %g", (double)sigma);
    return guarded("Gaussian blur", err, [&] {
        cv::Mat out = wrap(dst, w, h, ch);
        int k = 2 * (int)(3 * sigma + 0.999f) + 1; // +-3 sigma
        cv::GaussianBlur(wrap(src, w, h, ch), out, cv::Size(k, k), sigma, sigma, cv::BORDER_REPLICATE);
    });
}

extern "C" pnpr_status pnpr_cv_close_open(const float *src, float *dst, int w, int h, int ch, int radius,
                                          pnpr_error *err)
{
    pnpr_status st = check_args(src, dst, w, h, ch, "morphology", err);
    if (st != PNPR_OK) return st;
    if (radius < 0 || radius > 256)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: morphology: bad radius %d", radius);
    return guarded("morphology", err, [&] {
        cv::Mat out = wrap(dst, w, h, ch);
        if (radius == 0) { wrap(src, w, h, ch).copyTo(out); return; }
        cv::Mat k = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
        cv::morphologyEx(wrap(src, w, h, ch), out, cv::MORPH_CLOSE, k, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
        cv::morphologyEx(out, out, cv::MORPH_OPEN, k, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
    });
}

extern "C" pnpr_status pnpr_cv_sobel(const float *src, float *dx, float *dy, int w, int h, int ch, pnpr_error *err)
{
    pnpr_status st = check_args(src, dx, w, h, ch, "Sobel", err);
    if (st != PNPR_OK) return st;
    if (!dy) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: Sobel: bad arguments");
    return guarded("Sobel", err, [&] {
        cv::Mat in = wrap(src, w, h, ch), ox = wrap(dx, w, h, ch), oy = wrap(dy, w, h, ch);
        cv::Sobel(in, ox, CV_32F, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
        cv::Sobel(in, oy, CV_32F, 0, 1, 3, 1, 0, cv::BORDER_REPLICATE);
    });
}

/* One cv::cvtColor conversion `code` of 3-channel float images, named `what` in messages. */
static pnpr_status convert_colour(const float *src, float *dst, int w, int h, int code, const char *what, pnpr_error *err)
{
    pnpr_status st = check_args(src, dst, w, h, 3, what, err);
    if (st != PNPR_OK) return st;
    return guarded(what, err, [&] {
        cv::Mat out = wrap(dst, w, h, 3);
        cv::cvtColor(wrap(src, w, h, 3), out, code);
    });
}

extern "C" pnpr_status pnpr_cv_rgb_to_lab(const float *rgb, float *lab, int w, int h, pnpr_error *err)
{
    return convert_colour(rgb, lab, w, h, cv::COLOR_RGB2Lab, "RGB to Lab", err);
}

extern "C" pnpr_status pnpr_cv_lab_to_rgb(const float *lab, float *rgb, int w, int h, pnpr_error *err)
{
    return convert_colour(lab, rgb, w, h, cv::COLOR_Lab2RGB, "Lab to RGB", err);
}

extern "C" pnpr_status pnpr_cv_resize_rgba8(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh,
                                            pnpr_error *err)
{
    if (!src || !dst || sw <= 0 || sh <= 0 || dw <= 0 || dh <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: resize: bad image (%dx%d to %dx%d)", sw, sh, dw,
                              dh);
    return guarded("resize", err, [&] {
        cv::Mat s(sh, sw, CV_8UC4, const_cast<uint8_t *>(src)), d(dh, dw, CV_8UC4, dst);
        cv::resize(s, d, d.size(), 0, 0, cv::INTER_LINEAR);
        if (d.data != dst) throw cv::Exception(cv::Error::StsInternal, "resize reallocated", "", "", 0);
    });
}

#else // no OpenCV: every building block is unsupported

#define PNPR_NO_CV return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "effects: this build has no OpenCV")

extern "C" int pnpr_cv_available(void)
{
    return 0;
}

extern "C" pnpr_status pnpr_cv_bilateral(const float *, float *, int, int, int, int, float, float, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_gaussian(const float *, float *, int, int, int, float, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_sobel(const float *, float *, float *, int, int, int, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_close_open(const float *, float *, int, int, int, int, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_rgb_to_lab(const float *, float *, int, int, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_lab_to_rgb(const float *, float *, int, int, pnpr_error *err)
{
    PNPR_NO_CV;
}

extern "C" pnpr_status pnpr_cv_resize_rgba8(const uint8_t *, int, int, uint8_t *, int, int, pnpr_error *err)
{
    PNPR_NO_CV;
}

#endif
