#include "gui_fonts.h"

#include <imgui.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string_view>
#include <vector>

#include "system_words.h"

namespace aggpack::gui {

namespace {

// The Debian packages' files, best first (Noto's .ttc: face 2 is Noto Sans CJK SC).
constexpr std::array<std::pair<std::string_view, int>, 4> kKnownFonts = {{
    {"/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc", 2},
    {"/usr/share/fonts/truetype/wqy/wqy-microhei.ttc", 0},
    {"/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc", 0},
    {"/usr/share/fonts/opentype/noto/NotoSerifCJK-Regular.ttc", 2},
}};

constexpr float kChineseSize = 16.0f;

// "FILE" or "FILE:INDEX".
FontFace parse_face(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon != std::string::npos && colon + 1 < text.size() &&
      text.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
    return {text.substr(0, colon), std::atoi(text.c_str() + colon + 1)};
  }
  return {text, 0};
}

// fontconfig's choice for Simplified Chinese, if it covers the language ("" when not).
std::string ask_fontconfig() {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(
      popen("fc-match -f '%{file}:%{index}\\n%{lang}' 'sans:lang=zh-cn' 2>/dev/null", "r"), pclose);
  if (!pipe) return "";
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe.get()) != nullptr) out += buffer.data();
  const auto newline = out.find('\n');
  if (newline == std::string::npos) return "";
  const std::string langs = "|" + out.substr(newline + 1) + "|";
  if (langs.find("|zh-cn|") == std::string::npos) return "";
  return out.substr(0, newline);
}

// The glyphs of every Chinese catalogue entry (ImFontGlyphRangesBuilder::AddText).
void add_text(const char* text, void* builder) {
  static_cast<ImFontGlyphRangesBuilder*>(builder)->AddText(text);
}

}  // namespace

std::optional<FontFace> find_chinese_font() {
  if (const char* forced = std::getenv("AGGPACK_GUI_FONT"); forced != nullptr) {
    const std::string text = forced;
    if (text.empty() || text == "none") return std::nullopt;
    return parse_face(text);
  }
  std::error_code ignored;
  for (const auto& [path, index] : kKnownFonts) {
    if (std::filesystem::is_regular_file(path, ignored)) return FontFace{std::string(path), index};
  }
  const std::string found = ask_fontconfig();
  if (found.empty()) return std::nullopt;
  return parse_face(found);
}

bool load_fonts(const std::optional<FontFace>& chinese) {
  ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
  atlas.AddFontDefault();  // Fonts[0]: English; Fonts[1]: Chinese, when there is one
  // The glyph ranges must live until the atlas is built (below).
  static ImVector<ImWchar> menu_ranges, chinese_ranges;
  if (chinese) {
    std::ifstream in(chinese->path, std::ios::binary);
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad() || data.size() < 12) {
      std::fprintf(stderr, "aggpack-gui: cannot read the font %s\n", chinese->path.c_str());
    } else {
      // The atlas owns one copy (freed by ClearInputData below); both fonts read from it.
      void* owned = IM_ALLOC(data.size());
      std::copy(data.begin(), data.end(), static_cast<char*>(owned));
      const int size = static_cast<int>(data.size());
      ImFontGlyphRangesBuilder menu;
      menu.AddText(catalogue_text(Language::kEnglish, Text::kMenuLanguage));
      menu.AddText(catalogue_text(Language::kEnglish, Text::kLanguageChinese));
      menu.BuildRanges(&menu_ranges);
      ImFontConfig merge;
      merge.MergeMode = true;
      merge.FontNo = chinese->index;
      merge.FontDataOwnedByAtlas = false;
      merge.GlyphOffset.y = 1.0f;
      atlas.AddFontFromMemoryTTF(owned, size, 13.0f, &merge, menu_ranges.Data);
      ImFontGlyphRangesBuilder builder;
      builder.AddRanges(atlas.GetGlyphRangesDefault());
      for_each_chinese_text(add_text, &builder);
      for (const char* words : system_reasons_chinese()) builder.AddText(words);
      builder.BuildRanges(&chinese_ranges);
      ImFontConfig config;
      config.FontNo = chinese->index;
      config.FontDataOwnedByAtlas = true;
      atlas.AddFontFromMemoryTTF(owned, size, kChineseSize, &config, chinese_ranges.Data);
    }
  }
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  if (!atlas.Build()) {  // a font stb_truetype cannot read: English alone
    std::fprintf(stderr, "aggpack-gui: cannot use the font %s\n",
                 chinese ? chinese->path.c_str() : "");
    atlas.Clear();
    atlas.AddFontDefault();
  }
  atlas.GetTexDataAsRGBA32(&pixels, &width, &height);
  atlas.ClearInputData();
  ImGui::GetIO().FontDefault = atlas.Fonts[0];
  return has_chinese_font();
}

bool has_chinese_font() { return ImGui::GetIO().Fonts->Fonts.Size > 1; }

void use_font_of(Language language) {
  ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
  ImGui::GetIO().FontDefault =
      atlas.Fonts[language == Language::kChinese && has_chinese_font() ? 1 : 0];
}

}  // namespace aggpack::gui
