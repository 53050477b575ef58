// generate_particle / generate_particles: the paper's particle generator (aggpack/shape/
// generator.h) as `aggpack particle` and `aggpack shapes` run it, results as numpy arrays.

#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

// The generator options from the keyword arguments: `radius` sets radius_min and radius_max (as
// the CLI's --radius); radius_max defaults to radius_min. Checked by the library's validate(),
// whose messages name these same keywords.
GeneratorOptions generator_options(double alpha, std::optional<double> radius,
                                   std::optional<double> radius_min,
                                   std::optional<double> radius_max, double edge_length,
                                   std::uint64_t seed, std::uint32_t max_vertices,
                                   const std::string& growth, double elongation, double flatness,
                                   double min_edge_ratio) {
  GeneratorOptions options{
      .alpha = alpha, .edge_length = edge_length, .max_vertices = max_vertices, .seed = seed};
  const auto rule = find_growth(growth);
  if (!rule) throw InvalidInput("growth", growth, "hull or midpoint");
  options.form = {.growth = *rule,
                  .elongation = elongation,
                  .flatness = flatness,
                  .min_edge_ratio = min_edge_ratio};
  if (radius) {
    if (radius_min || radius_max) {
      throw InvalidInput("radius", format_value(*radius),
                         "either radius or radius_min/radius_max, not both");
    }
    radius_min = radius;
    radius_max = radius;
  }
  options.radius_min = radius_min.value_or(0.1);
  options.radius_max = radius_max.value_or(options.radius_min);
  validate(options);
  return options;
}

}  // namespace

py::dict descriptor_dict(const std::vector<ShapeDescriptors>& descriptors) {
  py::dict result;
  for (const DescriptorColumn& column : descriptor_columns()) {
    std::vector<double> values(descriptors.size());
    for (std::size_t i = 0; i < descriptors.size(); ++i) values[i] = column.get(descriptors[i]);
    result[column.name] = to_numpy(std::move(values));
  }
  return result;
}

void register_particles(py::module_& m) {
  m.def(
      "generate_particle",
      [](double alpha, std::optional<double> radius, std::optional<double> radius_min,
         std::optional<double> radius_max, double edge_length, std::uint64_t seed,
         std::uint64_t index, std::uint32_t max_vertices, const std::string& growth,
         double elongation, double flatness, double min_edge_ratio) {
        const GeneratorOptions options =
            generator_options(alpha, radius, radius_min, radius_max, edge_length, seed,
                              max_vertices, growth, elongation, flatness, min_edge_ratio);
        GeneratedParticle particle;
        ShapeDescriptors descriptors;
        {
          const py::gil_scoped_release release;
          particle = generate_particle(options, index);
          descriptors = describe(particle.body);
        }
        const auto& vertices = particle.body.vertices();
        const auto& triangles = particle.body.triangles();
        py::array_t<double> v({static_cast<py::ssize_t>(vertices.size()), py::ssize_t{3}});
        py::array_t<std::uint32_t> t({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
        std::copy(vertices.front().data(), vertices.front().data() + 3 * vertices.size(),
                  v.mutable_data());
        std::copy(triangles.front().data(), triangles.front().data() + 3 * triangles.size(),
                  t.mutable_data());
        py::dict measured;
        for (const DescriptorColumn& column : descriptor_columns()) {
          measured[column.name] = column.get(descriptors);
        }
        py::dict result;
        result["vertices"] = v;
        result["triangles"] = t;
        result["control_radius"] = particle.control_radius;
        result["descriptors"] = measured;
        return result;
      },
      py::kw_only(), py::arg("alpha") = 0.5, py::arg("radius") = py::none(),
      py::arg("radius_min") = py::none(), py::arg("radius_max") = py::none(),
      py::arg("edge_length") = 0.1, py::arg("seed") = 1, py::arg("index") = 0,
      py::arg("max_vertices") = 20000, py::arg("growth") = "hull", py::arg("elongation") = 1.0,
      py::arg("flatness") = 1.0, py::arg("min_edge_ratio") = 0.25,
      R"doc(Grows one particle (paper Section 2), as `aggpack particle` does.

Particle `index` of the family `seed` (its own random stream, so any index can be made alone).
Lengths in metres. Keywords (defaults): alpha 0.5 (Eq. 3 shape control, [0, 1]); radius (sets
radius_min and radius_max) or radius_min 0.1 m and radius_max (default radius_min): the control
radius is uniform in [radius_min, radius_max]; edge_length 0.1 m (L: growth stops when every edge
is <= L); seed 1; index 0; max_vertices 20000 (cap, [6, 10^6]); growth "hull" (the paper's
words: a random point of the longest edge, out to its Eq. 3 distance, convex hull kept) or
"midpoint" (aggpack 0.1's rule); elongation 1 and flatness 1 (the control ellipsoid's semi-axis
ratios, [0.1, 1]); min_edge_ratio 0.25 (minimum edge length / L of hull growth, [0, 0.5]).

Returns a dict: vertices float64 (V, 3) in m, centred on the growth centre; triangles uint32
(T, 3), counter-clockwise seen from outside; control_radius (m); descriptors, a dict of floats
(volume m^3, surface_area m^2, sphericity, measured_alpha, ... as `aggpack particle` prints).
Raises InvalidInput / LimitExceeded naming the keyword.)doc");

  m.def(
      "generate_particles",
      [](std::uint64_t count, double alpha, std::optional<double> radius,
         std::optional<double> radius_min, std::optional<double> radius_max, double edge_length,
         std::uint64_t seed, std::uint32_t max_vertices, const std::string& growth,
         double elongation, double flatness, double min_edge_ratio) {
        if (count < 1 || count > 100000000ULL) {
          throw InvalidInput("count", std::to_string(count), "[1, 100000000]");
        }
        const GeneratorOptions options =
            generator_options(alpha, radius, radius_min, radius_max, edge_length, seed,
                              max_vertices, growth, elongation, flatness, min_edge_ratio);
        const auto n = static_cast<std::size_t>(count);
        std::vector<ShapeDescriptors> descriptors(n);
        std::vector<double> radii(n);
        {
          const py::gil_scoped_release release;
          parallel_for_index(0, n, [&](std::size_t i) {
            const GeneratedParticle particle = generate_particle(options, i);
            descriptors[i] = describe(particle.body);
            radii[i] = particle.control_radius;
          });
        }
        py::dict result = descriptor_dict(descriptors);
        result["control_radius"] = to_numpy(std::move(radii));
        return result;
      },
      py::arg("count"), py::kw_only(), py::arg("alpha") = 0.5, py::arg("radius") = py::none(),
      py::arg("radius_min") = py::none(), py::arg("radius_max") = py::none(),
      py::arg("edge_length") = 0.1, py::arg("seed") = 1, py::arg("max_vertices") = 20000,
      py::arg("growth") = "hull", py::arg("elongation") = 1.0, py::arg("flatness") = 1.0,
      py::arg("min_edge_ratio") = 0.25,
      R"doc(Grows particles 0 .. count-1 of the family `seed` in parallel and measures them, as
`aggpack shapes -n COUNT` does (the same numbers as its CSV), without keeping the shapes.

count in [1, 10^8]; the other keywords as generate_particle. Returns a dict of float64 arrays of
length count: control_radius (m) and every descriptor (volume m^3, surface_area m^2, sphericity,
measured_alpha, vertices, edges, faces (counts), long, intermediate, short (principal
dimensions, m), elongation, flatness, circumscribed_radius m, enclosing_radius m,
equivalent_diameter m, longest_edge m: the columns of `aggpack shapes`'s CSV).)doc");
}

}  // namespace aggpack::python
