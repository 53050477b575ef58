#pragma once
// Rendering a Packing to an image with no display: an OpenGL 3.3 core context from EGL on Mesa's
// surfaceless platform (software rasteriser llvmpipe when there is no GPU), an off-screen
// framebuffer, and PNG output (stb_image_write).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/pack/packing.h"
#include "aggpack/render/camera.h"
#include "aggpack/render/colors.h"
#include "aggpack/render/renderer.h"

namespace aggpack {

/// An 8-bit RGBA image, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes

  /// Colour of pixel (x, y), (0, 0) = top left. Precondition: inside the image.
  [[nodiscard]] Rgb pixel(int x, int y) const {
    const std::size_t at = 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                static_cast<std::size_t>(x));
    return {rgba[at], rgba[at + 1], rgba[at + 2]};
  }
};

/// An OpenGL 3.3 core context with no window (EGL, Mesa surfaceless platform), current on the
/// creating thread for the object's lifetime. Not copyable.
class HeadlessContext {
 public:
  /// \throw IoError if EGL, the surfaceless platform or a 3.3 core context is not available.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Renderer string of the context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  [[nodiscard]] std::string renderer_name() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// An off-screen colour + depth framebuffer (optionally multisampled). Needs a current context.
class OffscreenTarget {
 public:
  /// width, height in pixels, [1, 16384]; samples: 0 or 1 = no multisampling, else up to the
  /// driver's maximum (clamped). \throw InvalidInput (size), IoError (incomplete framebuffer).
  OffscreenTarget(int width, int height, int samples = 0);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// Binds the framebuffer for drawing.
  void bind() const;
  /// Resolves multisampling and reads the pixels back (rows top to bottom).
  [[nodiscard]] Image read() const;
  /// Copies the picture into framebuffer `framebuffer` (0 = the window) with its lower-left
  /// corner at pixel (x, y) there. Leaves `framebuffer` bound for drawing.
  void blit(unsigned framebuffer, int x, int y) const;
  /// Stretches the picture over the rectangle (x, y, width, height) of framebuffer
  /// `framebuffer` with linear filtering (a target made without multisampling only). Leaves
  /// `framebuffer` bound for drawing.
  void blit_stretched(unsigned framebuffer, int x, int y, int width, int height) const;
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

 private:
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
  unsigned draw_framebuffer_ = 0;
  unsigned resolve_framebuffer_ = 0;
  unsigned renderbuffers_[3] = {0, 0, 0};  // colour, depth, resolved colour
};

/// Reads the currently bound read framebuffer's region (x, y, width, height) (lower-left origin,
/// pixels) into an image with rows top to bottom, e.g. a window's back buffer for a screenshot.
Image read_framebuffer(int x, int y, int width, int height);

/// Options of render_image. Sizes in pixels.
struct RenderImageOptions {
  int width = 1600;                    ///< image width, [16, 8192]
  int height = 1000;                   ///< image height, [16, 8192]
  ViewPreset view = ViewPreset::kIso;  ///< camera direction (the camera frames the scene)
  bool is_orthographic = false;        ///< orthographic instead of perspective projection
  int samples = 4;                     ///< multisample anti-aliasing samples, [0, 16] (0 = off)
  RenderStyle style;                   ///< colours, wireframe, container outline, detail
};

/// Throws InvalidInput naming the field ("width", "height", "samples",
/// "style.coarse_below_pixels") unless the options are usable.
void validate(const RenderImageOptions& options);

/// Renders `packing` headless with the camera framing the container and particles from
/// options.view. Creates and destroys its own context.
/// \throw InvalidInput (options), IoError (no headless OpenGL).
Image render_image(const Packing& packing, const RenderImageOptions& options = {});

/// Encodes `image` as PNG (8-bit RGB) and writes it atomically to `path`.
/// \throw InvalidInput (empty image), IoError (folder missing or not writable, file exists with
///        Overwrite::kForbid, write failure).
void write_png(const Image& image, const std::string& path,
               Overwrite overwrite = Overwrite::kAllow);

}  // namespace aggpack
