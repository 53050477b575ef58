// Packing.statistics(): the packing statistics of `aggpack info` (aggpack/pack/statistics.h) as
// a dict of numbers and numpy arrays.

#include <pybind11/stl.h>

#include <optional>
#include <vector>

#include "aggpack/pack/statistics.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

py::dict statistics_dict(const PackingStatistics& statistics) {
  py::dict result;
  result["particle_count"] = statistics.particle_count;
  result["shape_count"] = statistics.shape_count;
  result["solid_volume"] = statistics.solid_volume;
  result["container_volume"] = statistics.container_volume;
  result["solid_fraction"] = statistics.solid_fraction;
  py::list profiles;
  for (const AxisProfile& profile : statistics.profiles) {
    py::dict entry;
    entry["axis"] = "xyz"[profile.axis];
    entry["lower"] = profile.lower;
    entry["bin_width"] = profile.bin_width;
    entry["solid_fraction"] = to_numpy(std::vector<double>(profile.solid_fraction));
    profiles.append(entry);
  }
  result["profiles"] = profiles;
  if (!statistics.grading.empty()) {
    std::vector<double> size;
    std::vector<double> target;
    std::vector<double> achieved;
    for (const GradingPoint& point : statistics.grading) {
      size.push_back(point.size);
      target.push_back(point.target_percent);
      achieved.push_back(point.achieved_percent);
    }
    py::dict grading;
    grading["size"] = to_numpy(std::move(size));
    grading["target_percent"] = to_numpy(std::move(target));
    grading["achieved_percent"] = to_numpy(std::move(achieved));
    result["grading"] = grading;
  } else {
    result["grading"] = py::none();
  }
  py::dict descriptors;
  for (const DescriptorSummary& d : statistics.descriptors) {
    py::dict entry;
    entry["unit"] = d.unit;
    entry["mean"] = d.stats.mean;
    entry["std"] = d.stats.standard_deviation;
    entry["min"] = d.stats.minimum;
    entry["max"] = d.stats.maximum;
    entry["count"] = d.stats.count;
    descriptors[py::str(d.name)] = entry;
  }
  result["descriptors"] = descriptors;
  result["text"] = format_statistics(statistics);
  return result;
}

}  // namespace

void register_statistics(py::module_& m) {
  auto packing = m.attr("Packing").cast<py::class_<PyPacking, std::shared_ptr<PyPacking>>>();
  packing.def(
      "statistics",
      [](const PyPacking& p, int bins, bool descriptors, std::vector<double> sieve_sizes) {
        StatisticsOptions options{.bins = bins,
                                  .target = p.target,
                                  .sieve_sizes = std::move(sieve_sizes),
                                  .has_descriptors = descriptors};
        PackingStatistics statistics;
        {
          const py::gil_scoped_release release;
          statistics = compute_statistics(p.packing, options);
        }
        return statistics_dict(statistics);
      },
      py::kw_only(), py::arg("bins") = 10, py::arg("descriptors") = true,
      py::arg("sieve_sizes") = std::vector<double>{},
      R"doc(The statistics `aggpack info` prints: particle_count, shape_count, solid_volume
(m^3), container_volume (m^3), solid_fraction; profiles, one dict per axis x, y, z (lower m,
bin_width m, solid_fraction float64 (bins,), exact slicing); grading (None without a target
grading): the achieved sieve curve next to the configuration's target, a dict of float64 arrays
size (sieve size = control diameter, m), target_percent and achieved_percent (volume % passing);
descriptors: name -> {unit, mean, std, min, max, count} over the particles; text: the readable
summary.

bins: profile bins per axis, [1, 10000] (default 10); descriptors: measure shape descriptors
(default True; False is faster); sieve_sizes: sizes (m) for the grading table (default: the
target's own report sizes).)doc");
}

}  // namespace aggpack::python
