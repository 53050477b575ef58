#include "upload_scheduler.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <utility>

namespace aggpack::gui {

void UploadScheduler::begin(PackingRenderer& renderer, std::shared_ptr<const Packing> packing,
                            std::shared_ptr<SceneData> scene, std::vector<std::string> entries) {
  renderer.begin_upload(std::move(scene));
  packing_ = std::move(packing);
  entries_ = std::move(entries);
}

bool UploadScheduler::step(PackingRenderer& renderer) {
  if (!packing_) return false;
  constexpr std::size_t kUploadPieceBytes = std::size_t{4} << 20;
  constexpr double kUploadSecondsPerFrame = 0.025;
  const double start = glfwGetTime();
  bool is_uploaded = false;
  for (bool is_first = true;; is_first = false) {
    const std::size_t bytes = renderer.next_upload_bytes(kUploadPieceBytes);
    const double now = glfwGetTime();
    if (!is_first &&
        now - start + static_cast<double>(bytes) * seconds_per_byte_ > kUploadSecondsPerFrame) {
      break;
    }
    is_uploaded = renderer.upload_step(kUploadPieceBytes);
    if (bytes >= (std::size_t{1} << 20)) {  // large enough to time
      const double rate = (glfwGetTime() - now) / static_cast<double>(bytes);
      seconds_per_byte_ = 0.5 * (seconds_per_byte_ + rate);
    }
    if (is_uploaded) break;
  }
  return is_uploaded;
}

UploadScheduler::Uploaded UploadScheduler::take() {
  Uploaded uploaded{.packing = std::move(packing_), .entries = std::move(entries_)};
  packing_.reset();
  entries_.clear();
  return uploaded;
}

}  // namespace aggpack::gui
