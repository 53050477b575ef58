#pragma once
// Internal to the renderer: occlusion test against a read-back depth buffer.

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace aggpack::render_detail {

// Occlusion test against the depth buffer: the drawn depth read back and reduced to a pyramid
// of maxima (each level halves the resolution), so a screen rectangle is tested with a few
// texels of the level where it spans at most four.
class DepthPyramid {
 public:
  // Reads the depth of the bound framebuffer's pixels (0, 0) to (width, height) (window depth in
  // [0, 1]) and builds the levels.
  void build(int width, int height) {
    widths_.assign(1, width);
    heights_.assign(1, height);
    levels_.resize(1);
    levels_[0].resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, levels_[0].data());
    int w = width, h = height;
    for (std::size_t level = 1; w > 1 || h > 1; ++level) {
      const int nw = (w + 1) / 2, nh = (h + 1) / 2;
      if (levels_.size() <= level) levels_.emplace_back();
      const std::vector<float>& fine = levels_[level - 1];
      std::vector<float>& coarse = levels_[level];
      coarse.resize(static_cast<std::size_t>(nw) * static_cast<std::size_t>(nh));
      for (int y = 0; y < nh; ++y) {
        const float* row0 = fine.data() + static_cast<std::size_t>(2 * y) * w;
        const float* row1 = fine.data() + static_cast<std::size_t>(std::min(2 * y + 1, h - 1)) * w;
        float* out = coarse.data() + static_cast<std::size_t>(y) * nw;
        for (int x = 0; x < nw; ++x) {
          const int x1 = std::min(2 * x + 1, w - 1);
          out[x] = std::max(std::max(row0[2 * x], row0[x1]), std::max(row1[2 * x], row1[x1]));
        }
      }
      widths_.push_back(nw);
      heights_.push_back(nh);
      w = nw;
      h = nh;
    }
    levels_.resize(widths_.size());
  }

  // True if every pixel of the square of half-width `radius` about (x, y) (pixels, lower-left
  // origin; the part outside the image is ignored) holds a depth nearer than `depth`.
  [[nodiscard]] bool is_hidden(float x, float y, float radius, float depth) const {
    const int ix0 = std::max(0, static_cast<int>(std::floor(x - radius)));
    const int iy0 = std::max(0, static_cast<int>(std::floor(y - radius)));
    const int ix1 = std::min(widths_[0] - 1, static_cast<int>(std::floor(x + radius)));
    const int iy1 = std::min(heights_[0] - 1, static_cast<int>(std::floor(y + radius)));
    if (ix0 > ix1 || iy0 > iy1) return false;
    // A well hidden particle is hidden at a coarse level already (a small, cache-friendly
    // array); otherwise test the level where the square spans <= 8 texels.
    if (is_hidden_at(level_spanning(ix0, iy0, ix1, iy1, 2), ix0, iy0, ix1, iy1, depth)) return true;
    // Texels of the fine level that meet the disc of `radius` (the square's corners hold
    // neighbours' gaps more often than not).
    const std::size_t level = level_spanning(ix0, iy0, ix1, iy1, 8);
    const int w = widths_[level];
    const float size = static_cast<float>(1 << level);
    const float radius2 = radius * radius;
    const std::vector<float>& texels = levels_[level];
    for (int ty = iy0 >> level; ty <= iy1 >> level; ++ty) {
      const float dy = std::max({0.0f, ty * size - y, y - (ty + 1) * size});
      if (!(dy * dy < radius2)) continue;
      // The texels of this row within `half` of x across: tx * size - x < half and
      // x - (tx + 1) * size < half. Widened by a hundredth of a texel against rounding, so it
      // never tests fewer texels than the disc meets (more only makes the test more cautious).
      const float half = std::sqrt(radius2 - dy * dy) + 0.01f * size;
      const int tx0 = std::max(ix0 >> level, static_cast<int>(std::floor((x - half) / size)));
      const int tx1 = std::min(ix1 >> level, static_cast<int>(std::ceil((x + half) / size)) - 1);
      const float* row = texels.data() + static_cast<std::size_t>(ty) * w;
      for (int tx = tx0; tx <= tx1; ++tx) {
        if (!(row[tx] < depth)) return false;
      }
    }
    return true;
  }

 private:
  // The finest level where pixels [x0, x1] x [y0, y1] span at most `span` texels each way.
  [[nodiscard]] std::size_t level_spanning(int x0, int y0, int x1, int y1, int span) const {
    std::size_t level = 0;
    while (level + 1 < levels_.size() &&
           ((x1 >> level) - (x0 >> level) >= span || (y1 >> level) - (y0 >> level) >= span)) {
      ++level;
    }
    return level;
  }

  [[nodiscard]] bool is_hidden_at(std::size_t level, int x0, int y0, int x1, int y1,
                                  float depth) const {
    const int w = widths_[level];
    const std::vector<float>& texels = levels_[level];
    for (int y = y0 >> level; y <= y1 >> level; ++y) {
      const float* row = texels.data() + static_cast<std::size_t>(y) * w;
      for (int x = x0 >> level; x <= x1 >> level; ++x) {
        if (!(row[x] < depth)) return false;
      }
    }
    return true;
  }

 private:
  std::vector<std::vector<float>> levels_;
  std::vector<int> widths_, heights_;
};

}  // namespace aggpack::render_detail
