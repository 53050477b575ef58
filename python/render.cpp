// Packing.render(): headless OpenGL rendering (aggpack/render/headless.h), as `aggpack render`,
// to a numpy image and optionally a PNG file. aggpack.has_render says whether it exists.

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.h"

#ifdef AGGPACK_HAS_RENDER
#include "aggpack/core/atomic_file.h"
#include "aggpack/render/headless.h"
#endif

namespace aggpack::python {

void register_render(py::module_& m) {
#ifdef AGGPACK_HAS_RENDER
  m.attr("has_render") = true;
  auto packing = m.attr("Packing").cast<py::class_<PyPacking, std::shared_ptr<PyPacking>>>();
  packing.def(
      "render",
      [](const PyPacking& p, const std::optional<std::string>& path, int width, int height,
         const std::string& view, const std::string& color, bool wireframe, bool ortho,
         bool container, int samples, double coarse_below, bool force) {
        RenderImageOptions options;
        options.width = width;
        options.height = height;
        options.view = parse_view_preset(view, "view");
        options.style.color = parse_color_mode(color, "color");
        options.style.is_wireframe = wireframe;
        options.style.show_container = container;
        options.style.coarse_below_pixels = coarse_below;
        options.is_orthographic = ortho;
        options.samples = samples;
        validate(options);
        Image image;
        {
          const py::gil_scoped_release release;
          if (path) check_writable(*path, force ? Overwrite::kAllow : Overwrite::kForbid);
          image = render_image(p.packing, options);
          if (path) write_png(image, *path, force ? Overwrite::kAllow : Overwrite::kForbid);
        }
        const int rows = image.height;
        const int columns = image.width;
        py::array_t<std::uint8_t> pixels = to_numpy(std::move(image.rgba));
        return pixels.reshape({rows, columns, 4});
      },
      py::arg("path") = py::none(), py::kw_only(), py::arg("width") = 1600,
      py::arg("height") = 1000, py::arg("view") = "iso", py::arg("color") = "id",
      py::arg("wireframe") = false, py::arg("ortho") = false, py::arg("container") = true,
      py::arg("samples") = 4, py::arg("coarse_below") = 0.0, py::arg("force") = false,
      R"doc(Renders the packing headless (EGL, no display; Mesa's llvmpipe without a GPU), as
`aggpack render`. Returns the image as uint8 (height, width, 4) RGBA, rows top to bottom; with
path, also writes it as PNG (an existing file raises IoError unless force=True, as the CLI without -f).

Keywords (defaults): width 1600, height 1000 (pixels, [16, 8192]); view 'iso' | 'front' | 'side'
| 'top'; color 'id' (one hue per particle) | 'size' | 'alpha'; wireframe False; ortho False;
container True (draw its outline); samples 4 (anti-aliasing, [0, 16]); coarse_below 0.0 (pixels).
Raises InvalidInput naming the keyword, IoError (no headless OpenGL, unwritable path).)doc");
#else
  m.attr("has_render") = false;
#endif
}

}  // namespace aggpack::python
