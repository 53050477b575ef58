#pragma once
// aggpack-gui's fonts: ImGui's own (English) and a Chinese one from a Debian font package
// (fonts-noto-cjk, fonts-wqy-microhei or fonts-wqy-zenhei), found at run time, holding only the
// glyphs the Chinese catalogue uses (a small atlas; measured in README, aggpack-gui).

#include <optional>
#include <string>

#include "i18n.h"

namespace aggpack::gui {

/// A font file and the face in it (a .ttc holds several: Noto Sans CJK's Simplified Chinese
/// face is number 2).
struct FontFace {
  std::string path;
  int index = 0;
};

/// The Chinese font: $AGGPACK_GUI_FONT when set ("" or "none": none, else FILE or FILE:INDEX),
/// else the first of the Debian packages' files that exists, else what fontconfig's fc-match
/// finds for 'sans:lang=zh-cn' when it covers zh-cn.
std::optional<FontFace> find_chinese_font();

/// Fills ImGui's font atlas (the current context's): ImGui's default font with the language
/// menu's Chinese glyphs merged in (so English shows "中文"), then `chinese` at 16 px with
/// Latin and every glyph of the Chinese catalogue. Builds the atlas and frees the font files'
/// data; false (and English only) when `chinese` cannot be read.
bool load_fonts(const std::optional<FontFace>& chinese);

/// Whether load_fonts() loaded a Chinese font.
bool has_chinese_font();

/// Makes `language`'s font the default (from the next frame); English without a Chinese font.
void use_font_of(Language language);

}  // namespace aggpack::gui
