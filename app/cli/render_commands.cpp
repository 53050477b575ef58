// `aggpack render`: a saved packing to a PNG picture with no display (issue 5). Compiles to
// nothing when aggpack is built without rendering (AGGPACK_BUILD_RENDER=OFF or no OpenGL/EGL).
// `--mesomodel-cut z=V` draws a section of the concrete mesomodel instead (issue 16): software
// drawing on core/raster.h (mesomodel_cut_render.cpp), no OpenGL context is made.

#ifdef AGGPACK_HAS_RENDER

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>

#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/io/native.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/pack/resources.h"
#include "aggpack/render/headless.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"

namespace aggpack::cli {

namespace {

struct RenderFlags {
  std::string input;
  std::string output;
  std::string size = "1600x1000";
  std::string view = "iso";
  std::string color = "id";
  bool is_wireframe = false;
  bool is_orthographic = false;
  bool has_no_container = false;
  int samples = 4;
  double coarse_below_pixels = 0.0;
  bool is_forced = false;
  std::string mesomodel_cut;  ///< "z=0.05": draw the mesomodel's section instead ("" = no)
  MesoOptions meso;
  bool is_untinted = false;
};

// "WxH" -> (W, H), each in [16, 8192].
void parse_size(const std::string& text, RenderImageOptions& options) {
  const auto x = text.find('x');
  const std::string allowed = "WxH with W and H whole numbers in [16, 8192], e.g. 1600x1000";
  if (x == std::string::npos || x == 0 || x + 1 >= text.size() ||
      text.find_first_not_of("0123456789x") != std::string::npos ||
      text.find('x', x + 1) != std::string::npos || x > 5 || text.size() - x - 1 > 5) {
    throw InvalidInput("--size", text, allowed);
  }
  options.width = std::stoi(text.substr(0, x));
  options.height = std::stoi(text.substr(x + 1));
  if (options.width < 16 || options.width > 8192 || options.height < 16 || options.height > 8192) {
    throw InvalidInput("--size", text, allowed);
  }
}

void run_render(const RenderFlags& flags, bool has_output) {
  // -o "" is refused like in every command (not taken as "no -o").
  if (has_output) check_output_file_flag("-o/--output", flags.output);
  RenderImageOptions options;
  parse_size(flags.size, options);
  if (!flags.mesomodel_cut.empty()) {
    render_mesomodel_cut({.input = flags.input,
                          .output = flags.output,
                          .plane = flags.mesomodel_cut,
                          .meso = flags.meso,
                          .width = options.width,
                          .size_text = flags.size,
                          .is_tinted = !flags.is_untinted,
                          .is_forced = flags.is_forced});
    return;
  }
  options.view = parse_view_preset(flags.view, "--view");
  options.style.color = parse_color_mode(flags.color, "--color");
  options.style.is_wireframe = flags.is_wireframe;
  options.style.show_container = !flags.has_no_container;
  options.style.coarse_below_pixels = flags.coarse_below_pixels;
  options.is_orthographic = flags.is_orthographic;
  options.samples = flags.samples;
  with_key_names({}, {{"samples", "--samples"}, {"style.coarse_below_pixels", "--coarse-below"}},
                 [&] { validate(options); });
  const std::string output =
      flags.output.empty() ? std::filesystem::path(flags.input).replace_extension(".png").string()
                           : flags.output;
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  check_writable(output, overwrite);  // fail before the (slower) load and render
  const Packing packing = read_packing(flags.input);
  double shape_bytes = 0.0;
  for (const ConvexPolyhedron& shape : packing.shapes) shape_bytes += heap_bytes(shape);
  announce_heavy_run(estimate_render(static_cast<double>(packing.particles.size()), shape_bytes,
                                     static_cast<double>(options.width) * options.height,
                                     options.samples));
  const Image image = render_image(packing, options);
  write_png(image, output, overwrite);
  fmt::print("wrote {} ({}x{}, {} particles, view {}, colour {}{})\n", output, image.width,
             image.height, packing.particles.size(), flags.view,
             color_mode_name(options.style.color), flags.is_wireframe ? ", wireframe" : "");
}

}  // namespace

void register_render(CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  CLI::App* command = app.add_subcommand(
      "render",
      "Render a saved packing to a PNG picture, headless (EGL, no display needed); --mesomodel-cut "
      "z=V draws a section of its concrete mesomodel instead (phases coloured, software)");
  command->add_option("packing", flags->input, "native packing file (.h5) from `aggpack pack`")
      ->required();
  command->add_option("-o,--output", flags->output,
                      "PNG file to write (default: the packing's name with extension .png)");
  command->add_option("--size", flags->size, "image size WxH in pixels, each in [16, 8192]")
      ->capture_default_str();
  command
      ->add_option("--view", flags->view,
                   "camera direction: iso (front-right-top corner), front (along +y), side "
                   "(along -x), top (down -z)")
      ->capture_default_str();
  command
      ->add_option("--color", flags->color,
                   "particle colours: id (one hue per particle), size (equivalent diameter), "
                   "alpha (measured shape parameter, Eq. 2)")
      ->capture_default_str();
  command->add_flag("--wireframe", flags->is_wireframe, "draw triangle edges only");
  command->add_flag("--ortho", flags->is_orthographic,
                    "orthographic projection (parallel lines stay parallel; for measuring)");
  command->add_flag("--no-container", flags->has_no_container, "leave out the container outline");
  command
      ->add_option("--samples", flags->samples,
                   "anti-aliasing samples per pixel, [0, 16] (0 = off)")
      ->capture_default_str();
  command
      ->add_option("--coarse-below", flags->coarse_below_pixels,
                   "draw particles smaller than this many pixels with a 24-triangle coarse "
                   "shape (0 = full detail always)")
      ->capture_default_str();
  command->add_option(
      "--mesomodel-cut", flags->mesomodel_cut,
      "instead of the 3D view: mesh the concrete mesomodel (as `aggpack mesomodel`) "
      "and draw its section by the plane AXIS=VALUE (m), e.g. z=0.05: phases coloured, "
      "element edges, legend, scale bar. Software drawing, no OpenGL; --size gives "
      "the width (>= 200), the height follows the section");
  command
      ->add_option("--itz", flags->meso.itz_thickness,
                   "with --mesomodel-cut: ITZ thickness (m), >= 0; 0 = no ITZ")
      ->capture_default_str();
  command
      ->add_option("--aggregate-size", flags->meso.aggregate_size,
                   "with --mesomodel-cut: target element edge in the aggregates (m), 0 = no bound")
      ->capture_default_str();
  command
      ->add_option("--mortar-size", flags->meso.mortar_size,
                   "with --mesomodel-cut: target element edge in the mortar (m), 0 = no bound")
      ->capture_default_str();
  command->add_flag("--no-tint", flags->is_untinted,
                    "with --mesomodel-cut: one grey for every aggregate");
  command->add_flag("-f,--force", flags->is_forced, "replace an existing output file");
  command->callback([flags, command] { run_render(*flags, command->count("--output") > 0); });
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_RENDER
