#pragma once
// The colours of a value the GUI refuses: the message text and the input's background. One
// home, so every panel marks an error alike.

#include <imgui.h>

namespace aggpack::gui {

/// Text of an error message (a value outside its range, a sieve table error).
inline const ImVec4 kErrorText(0.95f, 0.35f, 0.3f, 1.0f);
/// Background of an input whose value is refused.
inline const ImVec4 kErrorFrame(0.55f, 0.15f, 0.12f, 1.0f);

}  // namespace aggpack::gui
