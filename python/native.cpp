// The native packing file (aggpack/io/native.h): aggpack.read(path) and Packing.write(path).

#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/io/native.h"
#include "bindings.h"

namespace aggpack::python {

void register_native(py::module_& m) {
  m.def(
      "read",
      [](const std::string& path) {
        auto packing = std::make_shared<PyPacking>();
        {
          const py::gil_scoped_release release;
          packing->packing = read_packing(path);
          packing->target = stored_target_grading(packing->packing);
        }
        return packing;
      },
      py::arg("path"),
      R"doc(Reads a native packing file (.h5, written by `aggpack pack` or Packing.write) and
validates it, as every aggpack command does. Returns a Packing (report None; the target grading
for statistics() comes from the stored configuration). Raises IoError (missing, unreadable),
FormatError ("<path>: <dataset>: <reason>" for a file that is not a valid packing).)doc");

  auto packing = m.attr("Packing").cast<py::class_<PyPacking, std::shared_ptr<PyPacking>>>();
  packing.def(
      "write",
      [](const PyPacking& p, const std::string& path, bool force, int compression, bool xdmf) {
        const py::gil_scoped_release release;
        write_packing(p.packing, path,
                      {.overwrite = force ? Overwrite::kAllow : Overwrite::kForbid,
                       .compression = compression,
                       .write_xdmf = xdmf});
      },
      py::arg("path"), py::kw_only(), py::arg("force") = false, py::arg("compression") = 0,
      py::arg("xdmf") = false,
      R"doc(Writes the native packing file (.h5) atomically: the same bytes `aggpack pack -o
PATH` writes for the same configuration and seed. force (default False): replace an existing
file (without it an existing file raises IoError, as the CLI without -f); compression: deflate level 0 (none,
default) .. 9; xdmf: also store world-coordinate surfaces and write PATH with extension .xdmf for
ParaView. Raises InvalidInput, IoError.)doc");
}

}  // namespace aggpack::python
