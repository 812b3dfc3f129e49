#include "app/window.h"

#include "renderer/map_image.h"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char glfw_message[512];

static void on_glfw_error(int code, const char *description) {
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description, code);
}

typedef struct window_state {
    cmd_context *ctx;
    world *shown;        // the world the view belongs to (new/load replace it)
    map_view view;
    int dragging;
    double last_x, last_y;
    int dirty;           // the map must be composed again
    char stdin_buf[8192];
    size_t stdin_len;
    int stdin_open;
} window_state;

static const char *vertex_src =
    "#version 450 core\n"
    "out vec2 uv;\n"
    "void main() {\n"
    "    // One triangle that covers the viewport.\n"
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    uv = vec2(p.x, 1.0 - p.y); // image row 0 at the top\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";

static const char *fragment_src =
    "#version 450 core\n"
    "in vec2 uv;\n"
    "out vec4 colour;\n"
    "layout(binding = 0) uniform sampler2D map;\n"
    "void main() { colour = texture(map, uv); }\n";

static GLuint compile(GLenum type, const char *src, const char *name, og_error *err) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        og_error_set(err, "app/window.c: %s shader: %s", name, log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static void reset_view(window_state *st) {
    st->shown = st->ctx->world;
    st->view = map_view_default(st->shown);
    st->dirty = 1;
}

static void on_mouse_button(GLFWwindow *win, int button, int action, int mods) {
    (void)mods;
    window_state *st = glfwGetWindowUserPointer(win);
    // The drag starts where the last motion event left the cursor (not where the
    // pointer is now: events queue up, and querying would skip the moves between).
    if (button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_MIDDLE)
        st->dragging = action == GLFW_PRESS;
}

static void on_cursor(GLFWwindow *win, double x, double y) {
    window_state *st = glfwGetWindowUserPointer(win);
    if (st->dragging) {
        st->view.cx -= (x - st->last_x) * st->view.mpp;
        st->view.cz -= (y - st->last_y) * st->view.mpp;
        st->dirty = 1;
    }
    st->last_x = x, st->last_y = y;
}

static void on_scroll(GLFWwindow *win, double dx, double dy) {
    (void)dx;
    window_state *st = glfwGetWindowUserPointer(win);
    // Zoom about the cursor: the point under it stays put.
    double mx = st->last_x, my = st->last_y;
    int w, h;
    glfwGetWindowSize(win, &w, &h);
    double px = st->view.cx + (mx - w * 0.5) * st->view.mpp;
    double pz = st->view.cz + (my - h * 0.5) * st->view.mpp;
    double mpp = st->view.mpp * pow(0.8, dy);
    double spacing = world_get_params(st->shown)->spacing;
    mpp = fmax(spacing / 16.0, fmin(mpp, spacing * ldexp(1.0, TILE_MAX_LEVEL)));
    st->view.cx = px - (mx - w * 0.5) * mpp;
    st->view.cz = pz - (my - h * 0.5) * mpp;
    st->view.mpp = mpp;
    st->dirty = 1;
}

static void run_commands(window_state *st, const char *text) {
    og_error err = {{0}};
    if (cmd_run(st->ctx, text, strlen(text), "console", &err) != 0) fprintf(stderr, "%s\n", err.msg);
    fflush(stdout);
    st->dirty = 1; // parameters or the world may have changed
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods) {
    (void)scancode;
    window_state *st = glfwGetWindowUserPointer(win);
    if (action != GLFW_PRESS) return;
    if (key == GLFW_KEY_S && (mods & GLFW_MOD_CONTROL)) {
        if (world_path(st->ctx->world)[0])
            run_commands(st, "save");
        else
            fprintf(stderr, "console: this world has no file yet: type save FILE\n");
    } else if (key == GLFW_KEY_HOME) {
        reset_view(st);
    } else if (key >= GLFW_KEY_1 && key <= GLFW_KEY_6 &&
               world_get_params(st->ctx->world)->kind == WORLD_PLANET) {
        st->view.face = key - GLFW_KEY_1;
        st->dirty = 1;
    }
}

// Runs every complete line waiting on standard input, without blocking.
static void poll_stdin(window_state *st) {
    while (st->stdin_open) {
        struct pollfd pfd = {STDIN_FILENO, POLLIN, 0};
        if (poll(&pfd, 1, 0) <= 0 || !(pfd.revents & (POLLIN | POLLHUP))) return;
        size_t room = sizeof st->stdin_buf - 1 - st->stdin_len;
        ssize_t got = read(STDIN_FILENO, st->stdin_buf + st->stdin_len, room);
        if (got <= 0) {
            st->stdin_open = 0; // the window stays; only the console is gone
            return;
        }
        st->stdin_len += (size_t)got;
        st->stdin_buf[st->stdin_len] = 0;
        char *nl;
        while ((nl = memchr(st->stdin_buf, '\n', st->stdin_len))) {
            *nl = 0;
            run_commands(st, st->stdin_buf);
            size_t used = (size_t)(nl - st->stdin_buf) + 1;
            memmove(st->stdin_buf, nl + 1, st->stdin_len - used);
            st->stdin_len -= used;
            if (st->ctx->exit_requested) return;
        }
        if (st->stdin_len == sizeof st->stdin_buf - 1) {
            fprintf(stderr, "console: line longer than %zu bytes ignored\n", sizeof st->stdin_buf);
            st->stdin_len = 0;
        }
    }
}

static void set_title(GLFWwindow *win, window_state *st, int pending) {
    char title[512];
    const char *path = world_path(st->shown);
    snprintf(title, sizeof title,
             "Orogen - %s - centre (%.1f, %.1f) m - %.3f m/px - face %d - level %d - pending %d",
             path[0] ? path : "unsaved world", st->view.cx, st->view.cz, st->view.mpp,
             st->view.face, map_view_level(st->shown, &st->view), pending);
    glfwSetWindowTitle(win, title);
}

int window_run(cmd_context *ctx, og_error *err) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        return og_error_set(err, "cannot start the window system: %s", glfw_message);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    GLFWwindow *win = glfwCreateWindow(1280, 800, "Orogen", NULL, NULL);
    if (!win) {
        glfwTerminate();
        return og_error_set(err, "cannot open a window with an OpenGL 4.5 core context through "
                                 "EGL: %s", glfw_message);
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);

    GLuint vs = compile(GL_VERTEX_SHADER, vertex_src, "map vertex", err);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, fragment_src, "map fragment", err) : 0;
    if (!fs) {
        glfwDestroyWindow(win);
        glfwTerminate();
        return -1;
    }
    GLuint prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glLinkProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLuint vao, tex = 0;
    glCreateVertexArrays(1, &vao);
    int tex_w = 0, tex_h = 0;
    uint8_t *pixels = NULL;

    window_state st = {.ctx = ctx, .stdin_open = 1};
    reset_view(&st);
    glfwSetWindowUserPointer(win, &st);
    glfwSetMouseButtonCallback(win, on_mouse_button);
    glfwSetCursorPosCallback(win, on_cursor);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetKeyCallback(win, on_key);
    printf("Orogen: drag to pan, wheel to zoom, Home to recentre, Ctrl+S to save.\n"
           "Console: type commands here ('help' lists them, 'exit' quits).\n");
    fflush(stdout);

    int pending = 0;
    while (!glfwWindowShouldClose(win) && !ctx->exit_requested) {
        // Sleep until input, but wake often while tiles are still arriving.
        glfwWaitEventsTimeout(pending ? 0.03 : 0.1);
        poll_stdin(&st);
        if (ctx->exit_requested) break;
        if (st.shown != ctx->world) reset_view(&st);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        if (w <= 0 || h <= 0) continue; // minimised
        if (w != tex_w || h != tex_h) {
            if (tex) glDeleteTextures(1, &tex);
            glCreateTextures(GL_TEXTURE_2D, 1, &tex);
            glTextureStorage2D(tex, 1, GL_RGBA8, w, h);
            glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            free(pixels);
            pixels = malloc((size_t)w * h * 4);
            tex_w = w, tex_h = h;
            st.dirty = 1;
        }
        if (st.dirty || pending) {
            pending = map_image_compose(ctx->world, &st.view, w, h, pixels);
            glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
            st.dirty = 0;
            set_title(win, &st, pending);
        }
        glViewport(0, 0, w, h);
        glUseProgram(prog);
        glBindTextureUnit(0, tex);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glfwSwapBuffers(win);
        GLenum gl_err = glGetError();
        if (gl_err != GL_NO_ERROR) fprintf(stderr, "orogen: OpenGL error 0x%x in the map view\n", gl_err);
    }
    free(pixels);
    glDeleteTextures(1, &tex);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    glfwDestroyWindow(win);
    glfwTerminate();
    return 0;
}
