// aggpack-gui: the interactive program (GLFW + OpenGL 3.3 core + Dear ImGui). See README.md.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <imgui.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/mesh/mesomodel.h"
#include "gui_app.h"
#include "gui_fonts.h"

namespace {

aggpack::gui::GuiApp* g_app = nullptr;  // for the GLFW callbacks, which carry no context

// Installed before ImGui's backend, which then chains to them (install_callbacks = true).
void on_mouse_button(GLFWwindow*, int button, int action, int) {
  if (g_app != nullptr) g_app->on_mouse_button(button, action);
}
void on_cursor(GLFWwindow*, double x, double y) {
  if (g_app != nullptr) g_app->on_cursor(x, y);
}
void on_scroll(GLFWwindow*, double, double dy) {
  if (g_app != nullptr) g_app->on_scroll(dy);
}
void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (g_app != nullptr) g_app->on_key(key, action, mods);
}
void on_glfw_error(int code, const char* text) {
  std::fprintf(stderr, "aggpack-gui: GLFW error %d: %s\n", code, text);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"aggpack-gui " AGGPACK_VERSION
               ": pack irregular convex particles interactively and look at them in 3D.\n"
               "Left drag rotates, right drag pans, the wheel zooms, R resets the view, Enter "
               "packs."};
  aggpack::gui::GuiOptions options;
  std::string config_path, open_path, screenshot_path, view = "iso", color = "id";
  std::string size = "1400x900";
  cli.add_option("config", config_path,
                 "TOML configuration to start from (as for `aggpack pack`; default: the paper's "
                 "case)");
  cli.add_option("--set", options.overrides, "override a configuration key, key=value (repeat)");
  cli.add_option("--open", open_path, "open a saved packing (.h5) at start");
  cli.add_flag("--pack", options.is_pack_at_start, "press Pack once at start");
  cli.add_option("--screenshot", screenshot_path,
                 "save the window as PNG once the first pack/open has finished and been drawn");
  cli.add_flag("--quit", options.is_quit_when_done,
               "exit after the first pack/open (and --screenshot / --benchmark-frames)");
  cli.add_option("--benchmark-frames", options.benchmark_frames,
                 "after the first pack/open, redraw the turning scene this many frames as while "
                 "dragging (light frames, adaptive detail), then 5 full-detail frames; print the "
                 "frame rates and where the time goes")
      ->check(CLI::Range(0, 100000));
  cli.add_option("--size", size, "window size WxH in pixels")->capture_default_str();
  cli.add_option("--view", view, "start view: iso, front, side, top")->capture_default_str();
  cli.add_option("--color", color, "particle colours: id, size, alpha")->capture_default_str();
  cli.add_flag("--wireframe", options.style.is_wireframe, "start in wireframe");
  options.style.triangle_budget = 250000;
  options.style.point_below_pixels = 3.0;
  cli.add_option("--triangle-budget", options.style.triangle_budget,
                 "most triangles per frame; beyond it the smallest particles are drawn as "
                 "points (0 = no limit)")
      ->capture_default_str();
  cli.add_option("--points-below", options.style.point_below_pixels,
                 "draw particles smaller than this many pixels as points (0 = never)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  cli.add_option("--export-name", options.export_base,
                 "file name (without extension) the Export buttons write")
      ->capture_default_str();
  std::string mesomodel_export;
  cli.add_option("--mesomodel-export", mesomodel_export,
                 "after the first pack/open, export the concrete mesomodel as NAME-mesomodel.EXT "
                 "(EXT inp, msh or vtu), as the Mesomodel buttons do");
  cli.add_option("--mesomodel-itz", options.mesomodel_itz_mm,
                 "start value of the mesomodel's ITZ thickness field (mm)")
      ->capture_default_str();
  std::string itz_kind = "solid";
  cli.add_option("--mesomodel-itz-kind", itz_kind,
                 "start value of the mesomodel's ITZ model: solid (a layer of tetrahedra) or "
                 "cohesive (COH3D6 elements, .inp for Abaqus)")
      ->check(CLI::IsMember({"solid", "cohesive"}))
      ->capture_default_str();
  cli.add_option("--edit", options.edits,
                 "after the first pack/open, type VALUE into the panel's KEY field, as a user "
                 "would (KEY=VALUE, repeat); the run prints the fields' errors and whether the "
                 "shown result is out of date");
  cli.add_flag("--frame-log", options.is_frame_log,
               "print the time of every frame from the first job to the end of the script");
  std::string export_format;
  cli.add_option("--export", export_format,
                 "after the first pack/open (and --edit), open the Export dialog for FORMAT (stl, "
                 "dat, ...) and press Export; its questions are printed and answered by --answer");
  std::string export_deck;
  cli.add_option("--export-deck", export_deck,
                 "as --export, for the complete solver deck NAME (abaqus, calculix, lsdyna, "
                 "yade), as File > Export solver deck does");
  cli.add_option("--answer", options.answer,
                 "the answer to the Export dialog's questions (out-of-date result, existing file)")
      ->check(CLI::IsMember({"yes", "no"}))
      ->capture_default_str();
  cli.add_option("--library-dialog", options.library_folder,
                 "after the first pack/open (and --edit), open the shape library dialog in FOLDER "
                 "and answer it with --answer (yes: use the --library-pick files, else the "
                 "folder)");
  cli.add_option("--library-pick", options.library_picks,
                 "--library-dialog: click these files of the folder (repeat or comma list)")
      ->delimiter(',');
  cli.add_option("--settings-dir", options.settings_dir,
                 "folder of the kept settings (default $XDG_CONFIG_HOME/aggpack or "
                 "~/.config/aggpack)");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return cli.exit(error);
  }

  int width = 1400, height = 900;
  try {
    if (!config_path.empty()) options.config_path = config_path;
    if (!open_path.empty()) options.open_path = open_path;
    if (!export_format.empty()) {
      options.export_format = aggpack::format_name(aggpack::parse_export_format(export_format));
    }
    if (!export_deck.empty()) {
      if (!export_format.empty()) {
        throw aggpack::InvalidInput("--export-deck", export_deck, "not with --export");
      }
      options.export_deck = aggpack::parse_deck_kind(export_deck);
      for (const aggpack::DeckInfo& deck : aggpack::deck_kinds()) {
        if (deck.kind == options.export_deck) {
          options.export_format = aggpack::format_name(deck.format);
        }
      }
    }
    options.mesomodel_itz_kind =
        itz_kind == "cohesive" ? aggpack::ItzKind::kCohesive : aggpack::ItzKind::kSolid;
    if (!mesomodel_export.empty()) {
      if (mesomodel_export != "inp" && mesomodel_export != "msh" && mesomodel_export != "vtu") {
        throw aggpack::InvalidInput("--mesomodel-export", mesomodel_export, "inp, msh or vtu");
      }
      options.mesomodel_export = "." + mesomodel_export;
    }
    if (!screenshot_path.empty()) {
      aggpack::check_writable(screenshot_path, aggpack::Overwrite::kAllow);
      options.screenshot_path = screenshot_path;
    }
    options.view = aggpack::parse_view_preset(view, "--view");
    options.style.color = aggpack::parse_color_mode(color, "--color");
    if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width < 320 || height < 240 ||
        width > 8192 || height > 8192) {
      throw aggpack::InvalidInput("--size", size, "WxH with W in [320, 8192], H in [240, 8192]");
    }
  } catch (const aggpack::Error& error) {
    std::fprintf(stderr, "aggpack-gui: error: %s\n", error.what());
    return 2;
  }

  glfwSetErrorCallback(on_glfw_error);
  if (glfwInit() == GLFW_FALSE) {
    std::fprintf(stderr,
                 "aggpack-gui: error: cannot open a display (is DISPLAY set? For no "
                 "display use `aggpack render` or run under xvfb-run)\n");
    return 3;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "aggpack", nullptr, nullptr);
  if (window == nullptr) {
    std::fprintf(stderr, "aggpack-gui: error: cannot create an OpenGL 3.3 core window\n");
    glfwTerminate();
    return 3;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.benchmark_frames > 0 ? 0 : 1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  // ImGui's window state is kept beside the program's settings, never in the working folder.
  const std::string settings_folder = aggpack::gui::GuiSettings::folder_of(options.settings_dir);
  static std::string ini_path;
  ini_path = settings_folder.empty() ? std::string() : settings_folder + "/imgui.ini";
  if (!ini_path.empty()) {
    std::error_code ignored;
    std::filesystem::create_directories(settings_folder, ignored);
  }
  ImGui::GetIO().IniFilename = ini_path.empty() ? nullptr : ini_path.c_str();
  ImGui::StyleColorsDark();
  // An opaque panel: the window's back buffer is not cleared under it (the scene is blitted
  // beside it), so a see-through one shows older frames' text as ghosts.
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  // ImGui's font and, when a Debian font package provides one, a Chinese font (its glyphs of the
  // Chinese catalogue only); GuiApp picks the language.
  const double font_start = glfwGetTime();
  const auto chinese_font = aggpack::gui::find_chinese_font();
  aggpack::gui::load_fonts(chinese_font);
  if (options.is_frame_log) {  // the fonts' cost
    const ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
    std::printf("fonts: %s, atlas %dx%d, %d Chinese-font glyphs, %.0f ms\n",
                chinese_font ? chinese_font->path.c_str() : "no Chinese font", atlas.TexWidth,
                atlas.TexHeight, atlas.Fonts.Size > 1 ? atlas.Fonts[1]->Glyphs.Size : 0,
                1e3 * (glfwGetTime() - font_start));
  }
  glfwSetMouseButtonCallback(window, on_mouse_button);
  glfwSetCursorPosCallback(window, on_cursor);
  glfwSetScrollCallback(window, on_scroll);
  glfwSetKeyCallback(window, on_key);
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  int exit_code = 0;
  {
    std::unique_ptr<aggpack::gui::GuiApp> app;
    try {
      app = std::make_unique<aggpack::gui::GuiApp>(window, options);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "aggpack-gui: error: %s\n", error.what());
      exit_code = 2;
    }
    g_app = app.get();
    while (app && !glfwWindowShouldClose(window) && !app->should_quit()) {
      // Sleep until input when nothing moves by itself; keep polling while a job runs.
      if (app->is_busy()) {
        glfwPollEvents();
      } else {
        glfwWaitEventsTimeout(0.25);
      }
      app->note_frame_start();
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      app->frame();
      ImGui::Render();
      const double ui_start = glfwGetTime();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      const bool is_timing = app->is_timing_frames();
      if (is_timing) glFinish();  // so the swap's time below is the swap's alone
      const double ui_seconds = glfwGetTime() - ui_start;
      app->after_render();
      const double swap_start = glfwGetTime();
      glfwSwapBuffers(window);
      if (is_timing) app->note_present_times(ui_seconds, glfwGetTime() - swap_start);
      app->note_frame_end();
    }
    if (app) exit_code = app->exit_code();
    g_app = nullptr;
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}
