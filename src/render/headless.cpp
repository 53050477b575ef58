// Headless OpenGL through EGL on Mesa's surfaceless platform. EGL was chosen over OSMesa because
// it gives a real 3.3 core context through the same vendor-neutral libOpenGL the GUI uses, so the
// renderer is one code path compiled once; OSMesa would need its own GL entry points.

#include "aggpack/render/headless.h"

#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/raster.h"

// LeakSanitizer (the sanitizer CI run): Mesa's EGL/GLX/llvmpipe and the X11 libraries keep
// driver singletons and the LLVM JIT until process exit; they are not aggpack's. Every program
// that renders links this file, so the suppressions live here; aggpack's own code is still
// checked. Ignored in builds without LeakSanitizer.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libEGL_mesa\nleak:libGLX_mesa\nleak:libgallium\nleak:libLLVM\nleak:libglapi\n"
         "leak:libGLdispatch\nleak:swrast_dri\nleak:libdrm\nleak:libexpat\nleak:libX11\n"
         "leak:libxcb\nleak:libglfw\nleak:libdbus\nleak:libfontconfig\n";
}

namespace aggpack {

namespace {

std::string egl_error_text() {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "EGL error 0x%04x", static_cast<unsigned>(eglGetError()));
  return buffer;
}

}  // namespace

struct HeadlessContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

HeadlessContext::HeadlessContext() : state_(std::make_unique<State>()) {
  const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (extensions == nullptr ||
      std::string(extensions).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
    throw IoError(
        "headless OpenGL: EGL has no EGL_MESA_platform_surfaceless (install Mesa's libegl-mesa0)");
  }
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) {
    throw IoError("headless OpenGL: eglGetPlatformDisplayEXT is missing");
  }
  State& s = *state_;
  s.display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (s.display == EGL_NO_DISPLAY || eglInitialize(s.display, &major, &minor) == EGL_FALSE) {
    throw IoError("headless OpenGL: cannot initialise the EGL surfaceless display (" +
                  egl_error_text() + ")");
  }
  if (eglBindAPI(EGL_OPENGL_API) == EGL_FALSE) {
    eglTerminate(s.display);
    throw IoError("headless OpenGL: EGL cannot bind desktop OpenGL (" + egl_error_text() + ")");
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               3,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  // No config and no surface: we draw only into our own framebuffer objects
  // (EGL_KHR_no_config_context and EGL_KHR_surfaceless_context, both in Mesa).
  s.context = eglCreateContext(s.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (s.context == EGL_NO_CONTEXT) {
    const std::string error = egl_error_text();
    eglTerminate(s.display);
    throw IoError("headless OpenGL: cannot create a 3.3 core context (" + error + ")");
  }
  if (eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context) == EGL_FALSE) {
    const std::string error = egl_error_text();
    eglDestroyContext(s.display, s.context);
    eglTerminate(s.display);
    throw IoError("headless OpenGL: cannot make the context current (" + error + ")");
  }
}

HeadlessContext::~HeadlessContext() {
  State& s = *state_;
  eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(s.display, s.context);
  eglTerminate(s.display);
  eglReleaseThread();
}

std::string HeadlessContext::renderer_name() const {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return name != nullptr ? name : "";
}

OffscreenTarget::OffscreenTarget(int width, int height, int samples)
    : width_(width), height_(height) {
  require_in_range("width", width, 1, 16384);
  require_in_range("height", height, 1, 16384);
  require_in_range("samples", samples, 0, 64);
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples_ = samples > 1 ? std::min(samples, static_cast<int>(max_samples)) : 0;

  glGenRenderbuffers(3, renderbuffers_);
  glGenFramebuffers(1, &draw_framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, draw_framebuffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[0]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            renderbuffers_[0]);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[1]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            renderbuffers_[1]);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (samples_ > 0) {
    // Multisampled pixels cannot be read directly: resolve into a plain colour buffer first.
    glGenFramebuffers(1, &resolve_framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_framebuffer_);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[2]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              renderbuffers_[2]);
  }
  const GLenum resolve_status =
      samples_ > 0 ? glCheckFramebufferStatus(GL_FRAMEBUFFER) : GL_FRAMEBUFFER_COMPLETE;
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE || resolve_status != GL_FRAMEBUFFER_COMPLETE) {
    throw IoError("OpenGL: off-screen framebuffer " + std::to_string(width) + "x" +
                  std::to_string(height) + " is incomplete");
  }
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteFramebuffers(1, &draw_framebuffer_);
  if (resolve_framebuffer_ != 0) glDeleteFramebuffers(1, &resolve_framebuffer_);
  glDeleteRenderbuffers(3, renderbuffers_);
}

void OffscreenTarget::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, draw_framebuffer_); }

Image OffscreenTarget::read() const {
  if (samples_ > 0) {
    // Multisampled pixels cannot be read directly: resolve into the plain colour buffer first.
    glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_framebuffer_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_framebuffer_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, samples_ > 0 ? resolve_framebuffer_ : draw_framebuffer_);
  Image image = read_framebuffer(0, 0, width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

void OffscreenTarget::blit(unsigned framebuffer, int x, int y) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width_, y + height_, GL_COLOR_BUFFER_BIT,
                    GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

void OffscreenTarget::blit_stretched(unsigned framebuffer, int x, int y, int width,
                                     int height) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT,
                    GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

Image read_framebuffer(int x, int y, int width, int height) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  // OpenGL's rows run bottom to top; images run top to bottom.
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 4;
  for (int row = 0; row < height / 2; ++row) {
    auto top =
        image.rgba.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(row) * row_bytes);
    auto bottom = image.rgba.begin() + static_cast<std::ptrdiff_t>(
                                           static_cast<std::size_t>(height - 1 - row) * row_bytes);
    std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(row_bytes), bottom);
  }
  // Window back buffers may carry alpha < 255; the picture is opaque.
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  return image;
}

void validate(const RenderImageOptions& options) {
  require_in_range("width", options.width, 16, 8192);
  require_in_range("height", options.height, 16, 8192);
  require_in_range("samples", options.samples, 0, 16);
  require_in_range("style.coarse_below_pixels", options.style.coarse_below_pixels, 0.0, 1e6);
}

Image render_image(const Packing& packing, const RenderImageOptions& options) {
  validate(options);
  HeadlessContext context;
  Image image;
  {
    // Renderer and framebuffer must go before the context does.
    PackingRenderer renderer;
    renderer.set_packing(packing);
    const Camera camera = Camera::framing(renderer.scene_bounds(), options.view,
                                          static_cast<double>(options.width) / options.height,
                                          options.is_orthographic);
    OffscreenTarget target(options.width, options.height, options.samples);
    target.bind();
    renderer.draw(camera, options.width, options.height, options.style);
    image = target.read();
  }
  return image;
}

void write_png(const Image& image, const std::string& path, Overwrite overwrite) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4) {
    throw InvalidInput("image", std::to_string(image.width) + "x" + std::to_string(image.height),
                       "a non-empty RGBA image");
  }
  check_writable(path, overwrite);
  // RGB, not RGBA: the picture is opaque and a third smaller without the alpha channel.
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) *
                                static_cast<std::size_t>(image.height) * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    rgb[3 * i] = image.rgba[4 * i];
    rgb[3 * i + 1] = image.rgba[4 * i + 1];
    rgb[3 * i + 2] = image.rgba[4 * i + 2];
  }
  write_png_rgb(path, image.width, image.height, rgb, overwrite);
}

}  // namespace aggpack
