/* Headless OpenGL 3.3+ core context, no X server: a GPU through EGL's device platform
 * (EGL_EXT_platform_device: NVIDIA's driver, Mesa's hardware drivers) when EGL lists one, else
 * Mesa's surfaceless platform (llvmpipe: no GPU needed). PNPR_GL_DEVICE=software skips the GPUs;
 * PNPR_GL_DEVICE=device takes the first listed device even when it is a software one (Mesa lists
 * llvmpipe as a device: the device path is then tested on a machine without a GPU). EGL and GL
 * entry points come through libepoxy. */
#include <pointnpr/render.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

struct pnpr_gl_context {
    void *libegl;        /* our own reference to libEGL (checked before epoxy needs it) */
    EGLDisplay display;
    EGLContext context;
    int terminate;       /* the display is reference-counted (EGL_KHR_display_reference) */
    int device;          /* on EGL's device platform (else Mesa's surfaceless one) */
};

static int has_word(const char *list, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = list; p && (p = strstr(p, word)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    return 0;
}

/* Mesa's surfaceless display, initialised (reference-counted when EGL can: *r_terminate). */
static EGLDisplay surfaceless_display(const char *client, int *r_terminate)
{
    EGLint dpy_attr[3] = {EGL_NONE, EGL_NONE, EGL_NONE};
    if (has_word(client, "EGL_KHR_display_reference")) {
        dpy_attr[0] = EGL_TRACK_REFERENCES_KHR;
        dpy_attr[1] = EGL_TRUE;
        *r_terminate = 1;
    }
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, dpy_attr);
    EGLint major = 0, minor = 0;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) { *r_terminate = 0; return EGL_NO_DISPLAY; }
    return d;
}

/* The display of an EGL device: the first listed hardware one (no EGL_MESA_device_software), or
 * with any_device the first of all; EGL_NO_DISPLAY when there is none or it does not initialise. */
static EGLDisplay device_display(const char *client, int any_device)
{
    if (!has_word(client, "EGL_EXT_platform_device") || !has_word(client, "EGL_EXT_device_enumeration") ||
        !has_word(client, "EGL_EXT_device_query"))
        return EGL_NO_DISPLAY;
    EGLDeviceEXT dev[16];
    EGLint n = 0;
    if (!eglQueryDevicesEXT(16, dev, &n)) return EGL_NO_DISPLAY;
    for (EGLint i = 0; i < n; i++) {
        if (!any_device && has_word(eglQueryDeviceStringEXT(dev[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            continue;
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, dev[i], NULL);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
    }
    return EGL_NO_DISPLAY;
}

pnpr_status pnpr_gl_context_create(pnpr_gl_context **r_context, pnpr_error *err)
{
    if (!r_context) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "no context pointer");
    *r_context = NULL;
    /* libepoxy aborts the process when it cannot load libEGL: find out first. */
    void *lib = dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    if (!lib)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "headless OpenGL: libEGL.so.1 not found (install libegl1 and libegl-mesa0)");
    pnpr_gl_context *c = calloc(1, sizeof *c);
    if (!c) { dlclose(lib); return PNPR_ERR_OUT_OF_MEMORY; }
    c->libegl = lib;
    c->display = EGL_NO_DISPLAY;
    c->context = EGL_NO_CONTEXT;
    pnpr_status st = PNPR_ERR_UNSUPPORTED;

    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const char *want = getenv("PNPR_GL_DEVICE");
    int software = want && !strcmp(want, "software"), any_device = want && !strcmp(want, "device");
    if (!has_word(client, "EGL_EXT_platform_base")) {
        pnpr_error_set(err, st, "headless OpenGL: EGL lacks EGL_EXT_platform_base");
        goto fail;
    }
    if (!software) c->display = device_display(client, any_device);
    c->device = c->display != EGL_NO_DISPLAY;
    if (!c->device && any_device) {
        pnpr_error_set(err, st, "headless OpenGL: PNPR_GL_DEVICE=device, but EGL lists no device that initialises");
        goto fail;
    }
    if (!c->device && !has_word(client, "EGL_MESA_platform_surfaceless")) {
        pnpr_error_set(err, st, "headless OpenGL: EGL offers no GPU device and lacks EGL_MESA_platform_surfaceless "
                                "(Mesa's libegl-mesa0 provides it)");
        goto fail;
    }
    if (!c->device) c->display = surfaceless_display(client, &c->terminate);
    if (c->display == EGL_NO_DISPLAY) {
        pnpr_error_set(err, st, "headless OpenGL: cannot initialise the surfaceless EGL display (EGL error 0x%x)",
                       (unsigned)eglGetError());
        goto fail;
    }
    if (!has_word(eglQueryString(c->display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        pnpr_error_set(err, st, "headless OpenGL: EGL lacks EGL_KHR_surfaceless_context");
        goto fail;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        pnpr_error_set(err, st, "headless OpenGL: EGL cannot bind the desktop OpenGL API");
        goto fail;
    }
    static const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint ncfg = 0;
    if (!eglChooseConfig(c->display, cfg_attr, &cfg, 1, &ncfg) || ncfg < 1) {
        pnpr_error_set(err, st, "headless OpenGL: no EGL config for desktop OpenGL");
        goto fail;
    }
    static const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    c->context = eglCreateContext(c->display, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (c->context == EGL_NO_CONTEXT) {
        pnpr_error_set(err, st, "headless OpenGL: cannot create an OpenGL 3.3 core context (EGL error 0x%x)",
                       (unsigned)eglGetError());
        goto fail;
    }
    if (!eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context)) {
        pnpr_error_set(err, st, "headless OpenGL: cannot make the context current (EGL error 0x%x)",
                       (unsigned)eglGetError());
        goto fail;
    }
    if (epoxy_gl_version() < 33) {
        pnpr_error_set(err, st, "headless OpenGL: the context has OpenGL %d.%d, 3.3 is needed",
                       epoxy_gl_version() / 10, epoxy_gl_version() % 10);
        goto fail;
    }
    *r_context = c;
    return PNPR_OK;
fail:
    pnpr_gl_context_destroy(c);
    return st;
}

pnpr_status pnpr_gl_context_make_current(pnpr_gl_context *c)
{
    if (!c) return PNPR_ERR_INVALID_ARGUMENT;
    return eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context)
               ? PNPR_OK : PNPR_ERR_UNSUPPORTED;
}

const char *pnpr_gl_context_platform(const pnpr_gl_context *c)
{
    return c ? (c->device ? "device" : "surfaceless") : NULL;
}

void pnpr_gl_context_destroy(pnpr_gl_context *c)
{
    if (!c) return;
    if (c->display != EGL_NO_DISPLAY) {
        if (c->context != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == c->context)
                eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(c->display, c->context);
        }
        /* Without reference counting the display is shared by every context of the process:
         * terminating it would pull the other contexts down, so it stays initialised. */
        if (c->terminate) eglTerminate(c->display);
    }
    if (c->libegl) dlclose(c->libegl);
    free(c);
}
