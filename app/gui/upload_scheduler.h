#pragma once
// The upload scheduler of aggpack-gui: a finished job's scene goes to OpenGL a bounded piece per
// frame (about 25 ms of it), so the window stays live while a large packing is uploaded and a
// loaded machine uploads less per frame. It holds the packing (and its panel entries) until the
// upload is done; GuiApp then shows it.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/pack/packing.h"
#include "aggpack/render/renderer.h"

namespace aggpack::gui {

class UploadScheduler {
 public:
  /// Starts uploading `scene` (prepared from `packing`) with renderer.begin_upload; a pending
  /// upload is replaced. \throw Error as begin_upload (then nothing is pending).
  void begin(PackingRenderer& renderer, std::shared_ptr<const Packing> packing,
             std::shared_ptr<SceneData> scene, std::vector<std::string> entries);

  /// Steps while the frame has time: each step allocates one buffer or copies at most 4 MB, and
  /// starts only if it fits the time left at the cost per byte measured so far (llvmpipe clears
  /// new storage; fresh memory costs 1-3 ms per MB on the test VM). The first step of a call
  /// always runs. True when the upload is complete (take() then hands over the packing).
  bool step(PackingRenderer& renderer);

  /// Whether a packing waits for its upload (step() has not yet returned true for it).
  [[nodiscard]] bool is_pending() const { return packing_ != nullptr; }

  /// The packing and its panel entries whose upload step() finished; nothing is pending after.
  struct Uploaded {
    std::shared_ptr<const Packing> packing;
    std::vector<std::string> entries;
  };
  Uploaded take();

 private:
  std::shared_ptr<const Packing> packing_;
  std::vector<std::string> entries_;
  // Seconds per byte of an upload step, measured (a running average; 1 ms per MB at first).
  double seconds_per_byte_ = 1e-3 / (1 << 20);
};

}  // namespace aggpack::gui
