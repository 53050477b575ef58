// aggpack.pack: the pipeline's pack() (aggpack/pipeline/pipeline.h), as `aggpack pack` runs it,
// with the GIL released, a progress callback and cancelling (callback returning False, or any
// exception in it, Ctrl-C included).

#include <Python.h>
#include <pybind11/stl.h>

#include <atomic>
#include <exception>
#include <memory>
#include <optional>

#include "aggpack/config/config.h"
#include "aggpack/core/parallel.h"
#include "aggpack/pipeline/pipeline.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

const char* stage_name(PackStage stage) {
  switch (stage) {
    case PackStage::kShapes:
      return "shapes";
    case PackStage::kPlacement:
      return "placement";
    case PackStage::kDensify:
      return "densify";
  }
  return "placement";
}

py::dict progress_dict(const PackProgress& progress) {
  py::dict result;
  result["stage"] = stage_name(progress.stage);
  result["fraction"] = progress.fraction;
  result["placed"] = progress.placed;
  result["attempted"] = progress.attempted;
  result["total"] = progress.total;
  result["solid_fraction"] = progress.solid_fraction;
  return result;
}

py::dict densify_dict(const DensifyReport& report) {
  py::dict result;
  result["summary"] = report.summary();
  result["sweeps"] = report.sweeps;
  result["moves_tried"] = report.moves_tried;
  result["moves_accepted"] = report.moves_accepted;
  result["compressions"] = report.compressions;
  result["start_fraction"] = report.start_fraction;
  result["solid_fraction"] = report.solid_fraction;
  result["bulk_fraction"] = report.bulk_fraction;
  result["surface_height"] = report.surface_height;
  result["min_distance"] = report.min_distance;
  result["seconds"] = report.seconds;
  return result;
}

// Calls the Python callback (if any) and checks for Ctrl-C, holding the GIL only for that. The
// first exception (or a False return) sets `cancel`; the exception is kept for the caller.
struct CallbackBridge {
  py::object callback;
  std::atomic<bool> cancel{false};
  std::exception_ptr error;

  void operator()(const PackProgress& progress) {
    if (cancel.load()) return;
    const py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback.is_none()) {
        const py::object answer = callback(progress_dict(progress));
        if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) cancel.store(true);
      }
    } catch (...) {
      error = std::current_exception();
      cancel.store(true);
    }
  }
};

}  // namespace

py::dict report_dict(const PackReport& report) {
  py::dict result;
  result["stop_reason"] = to_string(report.stop_reason);
  result["is_target_reached"] = report.is_target_reached;
  result["placed"] = report.placed;
  result["requested"] = report.requested;
  result["rejected"] = report.rejected;
  result["shrunk"] = report.shrunk;
  result["attempts"] = report.attempts;
  result["solid_volume"] = report.solid_volume;
  result["container_volume"] = report.container_volume;
  result["solid_fraction"] = report.solid_fraction;
  result["target_solid_fraction"] = report.target_solid_fraction;
  result["shape_seconds"] = report.shape_seconds;
  result["placement_seconds"] = report.placement_seconds;
  result["summary"] = report.summary();
  return result;
}

void register_pack(py::module_& m) {
  m.def(
      "pack",
      [](const py::object& source, const py::object& progress, double progress_interval) {
        const PackConfig config = to_pack_config(source);
        require_in_range("progress_interval", progress_interval, 0.0, 3600.0);
        CallbackBridge bridge;
        bridge.callback = progress;
        PackControl control;
        control.on_progress = [&bridge](const PackProgress& p) { bridge(p); };
        control.progress_interval = progress_interval;
        control.cancel = &bridge.cancel;
        std::optional<PipelineResult> result;
        {
          const py::gil_scoped_release release;
          // packer.threads caps the worker threads for this call only (results do not depend
          // on it).
          std::optional<ThreadLimit> limit;
          if (config.threads > 0) limit.emplace(config.threads);
          result = pack(config, control);
        }
        if (bridge.error) std::rethrow_exception(bridge.error);
        auto packing = std::make_shared<PyPacking>();
        packing->packing = std::move(result->packing);
        packing->report = result->report;
        packing->target = config.target_grading();
        if (result->densify) packing->extra["densify"] = densify_dict(*result->densify);
        if (result->fill) {
          py::dict fill = report_dict(result->fill->report);
          fill["container"] = container_dict(result->fill->container);
          fill["scale"] = result->fill->scale;
          fill["asked_fraction"] = result->fill->asked_fraction;
          packing->extra["fill"] = fill;
          packing->extra["shortfalls"] = py::cast(dense_shortfalls(*result));
        }
        return packing;
      },
      py::arg("config"), py::kw_only(), py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.1,
      R"doc(Packs particles as `aggpack pack` does with the same configuration: the same packing,
byte for byte once written. config: a PackConfig (pack_config()), a dict of keys (nested tables
or dotted keys, as PackConfig.from_dict) or the path of a TOML file (str or pathlib.Path, as
`aggpack pack FILE`). Releases the GIL while it runs.

progress: None or a callable progress(dict) called at most every progress_interval seconds
(default 0.1, [0, 3600]) and once at the end (holding the GIL only then), with stage ('shapes',
'placement', 'densify'), fraction (of this stage, [0, 1]), placed, attempted, total,
solid_fraction. Returning False cancels: the packer stops and pack() returns what it placed
(report['stop_reason'] == 'cancelled'). An exception raised by the callback also cancels, and
pack() re-raises it. Ctrl-C (KeyboardInterrupt) is checked at the same moments and cancels the same
way.

Returns a Packing; its report holds the counts, volumes, stop_reason and times. A run that stops
short of its target (budget, size list) is not an error: see report['is_target_reached'].
Raises ConfigError / InvalidInput / LimitExceeded for options the packer refuses.)doc");
}

}  // namespace aggpack::python
