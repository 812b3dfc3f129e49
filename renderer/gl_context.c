// The headless EGL context, the renderer's feature check, and GL error reporting.
#include "renderer/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <dlfcn.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct gl_headless {
    EGLDisplay display;
    EGLContext context;
};

// Whole-word search in a space-separated extension list (a plain strstr would
// take EGL_KHR_foo for EGL_KHR_foo_bar).
static bool has_word(const char *list, const char *word) {
    size_t n = strlen(word);
    for (const char *p = list; p && (p = strstr(p, word)); p += n) {
        bool starts = p == list || p[-1] == ' ';
        bool ends = p[n] == '\0' || p[n] == ' ';
        if (starts && ends) return true;
    }
    return false;
}

static const char *egl_error_name(EGLint code) {
    switch (code) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
        return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
        return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
        return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
        return "EGL_CONTEXT_LOST";
    default:
        return "unknown EGL error";
    }
}

static int egl_fail(og_error *err, const char *what) {
    EGLint code = eglGetError();
    return og_error_set(err, "headless GL: %s (%s, 0x%x)", what, egl_error_name(code),
                        (unsigned)code);
}

// Initialises the surfaceless display and checks what a configless, surfaceless
// 4.5 core context needs. Returns the display or EGL_NO_DISPLAY with err set.
static EGLDisplay open_surfaceless_display(og_error *err) {
    // libepoxy aborts the process when it cannot load libEGL: look first.
    void *egl_lib = dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    if (!egl_lib) {
        og_error_set(err, "headless GL: no EGL (cannot load libEGL.so.1: %s)", dlerror());
        return EGL_NO_DISPLAY;
    }
    dlclose(egl_lib);

    // Client extensions (EGL 1.5 / EGL_EXT_client_extensions); NULL where unsupported.
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !has_word(client, "EGL_EXT_platform_base")) {
        og_error_set(err, "headless GL: EGL lacks EGL_EXT_platform_base (client extensions: %s)",
                     client ? client : "none");
        return EGL_NO_DISPLAY;
    }
    if (!has_word(client, "EGL_MESA_platform_surfaceless")) {
        og_error_set(err,
                     "headless GL: no surfaceless EGL platform (EGL_MESA_platform_surfaceless "
                     "missing; client extensions: %s)",
                     client);
        return EGL_NO_DISPLAY;
    }
    EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (display == EGL_NO_DISPLAY) {
        egl_fail(err, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) failed");
        return EGL_NO_DISPLAY;
    }
    EGLint major = 0, minor = 0;
    // Never terminated: eglTerminate unloads Mesa's driver, whose remaining
    // allocations then show up as leaks from an unknown module (LeakSanitizer fails
    // every GL test). Initialising an initialised display again is a no-op.
    bool ok = eglInitialize(display, &major, &minor);
    if (!ok) {
        egl_fail(err, "eglInitialize on the surfaceless platform failed");
        return EGL_NO_DISPLAY;
    }
    const char *exts = eglQueryString(display, EGL_EXTENSIONS);
    const char *missing = NULL;
    if (!has_word(exts, "EGL_KHR_surfaceless_context"))
        missing = "EGL_KHR_surfaceless_context";
    else if ((major < 1 || (major == 1 && minor < 5)) && !has_word(exts, "EGL_KHR_create_context"))
        missing = "EGL 1.5 or EGL_KHR_create_context";
    if (missing) {
        og_error_set(err, "headless GL: EGL %d.%d lacks %s", major, minor, missing);
        return EGL_NO_DISPLAY;
    }
    return display;
}

gl_headless *gl_headless_create(og_error *err) {
    EGLDisplay display = open_surfaceless_display(err);
    if (display == EGL_NO_DISPLAY) return NULL;
    if (!eglBindAPI(EGL_OPENGL_API)) {
        egl_fail(err, "no desktop OpenGL through EGL (eglBindAPI(EGL_OPENGL_API) failed)");
        return NULL;
    }
    // No surface is ever made, so a config is only needed where
    // EGL_KHR_no_config_context is missing.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_word(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1) {
            egl_fail(err, "no EGL config renders desktop OpenGL");
            return NULL;
        }
    }
    // clang-format off
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4,
        EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE,
    };
    // clang-format on
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT) {
        egl_fail(err, "no OpenGL 4.5 core context (eglCreateContext failed)");
        return NULL;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        egl_fail(err, "cannot make the surfaceless OpenGL 4.5 context current");
        eglDestroyContext(display, context);
        return NULL;
    }
    gl_headless *ctx = malloc(sizeof *ctx);
    if (!ctx) {
        og_error_set(err, "headless GL: out of memory");
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        return NULL;
    }
    ctx->display = display;
    ctx->context = context;
    return ctx;
}

void gl_headless_destroy(gl_headless *ctx) {
    if (!ctx) return;
    if (eglGetCurrentContext() == ctx->context)
        eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(ctx->display, ctx->context);
    free(ctx);
}

static const char *renderer_name(void) {
    const char *name = (const char *)glGetString(GL_RENDERER);
    return name ? name : "unknown renderer";
}

// True when the internal format reports full support for pname on 2D textures
// (ARB_internalformat_query2, core since 4.3).
static bool format_supports(GLenum target, GLenum format, GLenum pname) {
    GLint support = GL_NONE;
    glGetInternalformativ(target, format, pname, 1, &support);
    return support == GL_FULL_SUPPORT;
}

int gl_require_features(og_error *err) {
    const char *version = (const char *)glGetString(GL_VERSION);
    if (!version)
        return og_error_set(err, "GL: no current context (glGetString(GL_VERSION) is NULL)");
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 5) || strncmp(version, "OpenGL ES", 9) == 0)
        return og_error_set(err, "GL: OpenGL 4.5 core needed, have \"%s\" on %s", version,
                            renderer_name());
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    if (!(profile & GL_CONTEXT_CORE_PROFILE_BIT))
        return og_error_set(
            err, "GL: a core profile context is needed, have \"%s\" (profile mask 0x%x) on %s",
            version, (unsigned)profile, renderer_name());

    // Limits the clipmap and detail textures rely on (array layers per cache, tile sizes).
    GLint layers = 0, tex_size = 0, rb_size = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &layers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &tex_size);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb_size);
    const char *missing = NULL;
    if (layers < 256)
        missing = "texture arrays of 256 layers (GL_MAX_ARRAY_TEXTURE_LAYERS)";
    else if (tex_size < 4096)
        missing = "4096x4096 textures (GL_MAX_TEXTURE_SIZE)";
    else if (rb_size < 4096)
        missing = "4096x4096 renderbuffers (GL_MAX_RENDERBUFFER_SIZE)";
    // Heights are R32F sampled with linear filtering (core 4.5 allows it to be partial).
    else if (!format_supports(GL_TEXTURE_2D_ARRAY, GL_R32F, GL_FILTER))
        missing = "linear filtering of GL_R32F texture arrays";
    else if (!format_supports(GL_TEXTURE_2D, GL_R32F, GL_FRAMEBUFFER_RENDERABLE))
        missing = "rendering to GL_R32F textures";
    // Reversed-Z wants a float depth buffer and glClipControl (core in 4.5).
    else if (!format_supports(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, GL_FRAMEBUFFER_RENDERABLE))
        missing = "GL_DEPTH_COMPONENT32F depth buffers";
    else if (!format_supports(GL_RENDERBUFFER, GL_RGBA8, GL_FRAMEBUFFER_RENDERABLE))
        missing = "GL_RGBA8 colour buffers";
    while (glGetError() != GL_NO_ERROR) {
    } // a failed query must not leak into the caller's checks
    if (missing)
        return og_error_set(err, "GL: %s needed, not available in \"%s\" on %s", missing, version,
                            renderer_name());
    return 0;
}

// Mesa numbers its messages per call site, so a small set of seen ids keeps a
// per-frame error from flooding stderr. Past its size every error prints.
enum { SEEN_IDS_MAX = 256 };
static GLuint seen_ids[SEEN_IDS_MAX];
static int seen_count;
static pthread_mutex_t seen_lock = PTHREAD_MUTEX_INITIALIZER;

static bool first_sighting(GLuint id) {
    bool first = true;
    pthread_mutex_lock(&seen_lock);
    for (int i = 0; i < seen_count && first; i++)
        first = seen_ids[i] != id;
    if (first && seen_count < SEEN_IDS_MAX) seen_ids[seen_count++] = id;
    pthread_mutex_unlock(&seen_lock);
    return first;
}

static void GLAPIENTRY print_gl_error(GLenum source, GLenum type, GLuint id, GLenum severity,
                                      GLsizei length, const GLchar *message, const void *user) {
    (void)severity, (void)user;
    // Compile errors are shader_program_load's to report, at the original file:line.
    if (type != GL_DEBUG_TYPE_ERROR || source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    if (!first_sighting(id)) return;
    int len = length < 0 ? (int)strlen(message) : (int)length;
    fprintf(stderr, "GL error (id %u): %.*s\n", id, len, message);
}

void gl_debug_enable(void) {
    if (epoxy_gl_version() < 43 && !epoxy_has_gl_extension("GL_KHR_debug")) return;
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous, so the message comes from inside the failing call (a debugger
    // breakpoint in print_gl_error shows who made it).
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_FALSE);
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, NULL, GL_TRUE);
    glDebugMessageControl(GL_DEBUG_SOURCE_SHADER_COMPILER, GL_DONT_CARE, GL_DONT_CARE, 0, NULL,
                          GL_FALSE);
    glDebugMessageCallback(print_gl_error, NULL);
}

static const char *gl_error_name(GLenum code) {
    switch (code) {
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW:
        return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
        return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST:
        return "GL_CONTEXT_LOST";
    default:
        return "unknown GL error";
    }
}

int gl_check_error(const char *where, og_error *err) {
    GLenum first = glGetError();
    if (first == GL_NO_ERROR) return 0;
    // Bounded: a lost context may report GL_CONTEXT_LOST on every call.
    int more = 0;
    for (int i = 0; i < 64 && glGetError() != GL_NO_ERROR; i++)
        more++;
    if (more)
        return og_error_set(err, "%s: %s (0x%x) and %d more", where, gl_error_name(first),
                            (unsigned)first, more);
    return og_error_set(err, "%s: %s (0x%x)", where, gl_error_name(first), (unsigned)first);
}
