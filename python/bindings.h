#pragma once
// What the binding files of the Python module share (issue 17): the Packing object Python holds,
// the registration function of each file, and small conversions. One file per concept:
// errors.cpp, particles.cpp, config.cpp, packing.cpp, pack.cpp, native.cpp, export.cpp,
// statistics.cpp, sim.cpp, study.cpp, render.cpp; module.cpp calls the register_* functions in
// order.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/pack/grading.h"
#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"
#include "aggpack/shape/descriptors.h"

namespace aggpack {
struct PackConfig;
}  // namespace aggpack

namespace aggpack::python {

namespace py = pybind11;

/// The Python `aggpack.Packing`: a packing and, when pack() made it, its report and the target
/// grading of its configuration (for the statistics). Held by std::shared_ptr; the numpy views
/// keep the Python object (and so this) alive.
struct PyPacking {
  Packing packing;
  std::optional<PackReport> report;  ///< set by pack(), not by read()
  py::dict extra;                    ///< dense kind: "densify" and "fill" dicts
  std::optional<Grading> target;     ///< the configuration's target grading, when it has one
};

/// The target grading of a stored configuration text (provenance.config_toml), as `aggpack info`
/// reads it: nullopt when there is none or it does not parse.
std::optional<Grading> stored_target_grading(const Packing& packing);

/// A read-only numpy view of `count` rows of `columns` values of type T, `row_stride` bytes apart,
/// starting at `data`, owned by `owner` (kept alive by the array). columns == 0: a 1-D array.
template <class T>
py::array view(const void* data, std::size_t count, std::size_t columns, std::size_t row_stride,
               const py::handle& owner) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(count)};
  std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(row_stride)};
  if (columns > 0) {
    shape.push_back(static_cast<py::ssize_t>(columns));
    strides.push_back(static_cast<py::ssize_t>(sizeof(T)));
  }
  py::array array(py::dtype::of<T>(), shape, strides, static_cast<const T*>(data), owner);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

/// A numpy array that takes over `values` (no copy): the vector moves into a capsule.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

/// The report of a packer as a dict (counts, volumes, fractions, stop_reason as its sentence).
py::dict report_dict(const PackReport& report);

/// The descriptors of many bodies as a dict name -> float64 array (descriptor_columns() order).
py::dict descriptor_dict(const std::vector<ShapeDescriptors>& descriptors);

/// The container as a dict: kind, its sizes (m), wall_gap (m), volume (m^3).
py::dict container_dict(const Container& container);

// A PackConfig from what pack() takes: a PackConfig, a dict of keys (PackConfig.from_dict) or the
// path of a TOML file (str or os.PathLike); anything else is InvalidInput naming `config`.
PackConfig to_pack_config(const py::object& source);

void register_errors(py::module_& m);
void register_particles(py::module_& m);
void register_config(py::module_& m);
void register_packing(py::module_& m);
void register_pack(py::module_& m);
void register_native(py::module_& m);
void register_export(py::module_& m);
void register_statistics(py::module_& m);
void register_sim(py::module_& m);
void register_study(py::module_& m);
void register_render(py::module_& m);

}  // namespace aggpack::python
