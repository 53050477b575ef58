// aggpack.Packing: a packing (aggpack/pack/packing.h) with numpy views of its particles and
// shapes. The views are read-only and share the C++ memory (no copy); each holds a reference to
// the Packing object, so it stays valid after the Packing goes out of scope in Python.

#include <pybind11/stl.h>

#include <cstddef>
#include <memory>
#include <string>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/pack/container.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

using PackingPtr = std::shared_ptr<PyPacking>;

const Packing& packing_of(const py::object& self) { return self.cast<PyPacking&>().packing; }

// A view of one member of every Particle (`member` gives its address in a particle), `columns`
// values each; the rows are sizeof(Particle) apart.
template <class T, class Member>
py::array particle_view(const py::object& self, Member member, std::size_t columns) {
  const auto& particles = packing_of(self).particles;
  static const Particle sample{};
  const auto offset = static_cast<std::size_t>(reinterpret_cast<const char*>(member(sample)) -
                                               reinterpret_cast<const char*>(&sample));
  const char* base = particles.empty() ? nullptr : reinterpret_cast<const char*>(particles.data());
  return view<T>(base == nullptr ? nullptr : base + offset, particles.size(), columns,
                 sizeof(Particle), self);
}

std::size_t shape_index(const Packing& packing, long long index) {
  const auto count = static_cast<long long>(packing.shapes.size());
  if (index < 0) index += count;
  if (index < 0 || index >= count) {
    throw InvalidInput("shape", std::to_string(index),
                       "[0, " + std::to_string(packing.shapes.size()) + ") (shape_count)");
  }
  return static_cast<std::size_t>(index);
}

}  // namespace

py::dict container_dict(const Container& container) {
  const ContainerKindInfo& kind = container_kind_info(container);
  py::dict result;
  result["kind"] = kind.name;
  for (const ContainerParam& param : kind.params) result[param.name] = param.get(container);
  // A box's periodic axes: "none", "x", ..., "xyz" (container.periodic).
  if (container.get_if<BoxContainer>() != nullptr) {
    result["periodic"] = periodic_word(periodic_axes(container));
  }
  result["wall_gap"] = container.wall_gap;
  result["volume"] = container.volume();
  return result;
}

std::optional<Grading> stored_target_grading(const Packing& packing) {
  if (packing.provenance.config_toml.empty()) return std::nullopt;
  try {
    return parse_pack_config(packing.provenance.config_toml, "/provenance/config_toml")
        .target_grading();
  } catch (const Error&) {
    return std::nullopt;  // written by another version or tool: no target, as `aggpack info`
  }
}

void register_packing(py::module_& m) {
  py::class_<PyPacking, PackingPtr>(m, "Packing", R"doc(A packing: container, particle shapes (each
in a local frame, centroid at the origin), particles (shape index + pose + scale) and provenance.
Made by pack(), read(), settle(). Arrays are read-only numpy views of the C++ data (no copy);
copy them (np.array(p.positions)) to change them. Lengths in metres.

Particle i's world vertices: rotation_i @ (scale_i * shape_vertices(shape_index_i)) + position_i
(world_vertices(i) computes them).)doc")
      .def_property_readonly(
          "positions",
          [](const py::object& self) {
            return particle_view<double>(
                self, [](const Particle& q) { return q.pose.position.data(); }, 3);
          },
          "float64 (N, 3): world position of each particle's shape origin (m). View.")
      .def_property_readonly(
          "rotations",
          [](const py::object& self) {
            return particle_view<double>(
                self, [](const Particle& q) { return q.pose.rotation.coeffs().data(); }, 4);
          },
          "float64 (N, 4): unit quaternions, SCALAR LAST (x, y, z, w), the order of "
          "scipy.spatial.transform.Rotation.from_quat (the native file stores w, x, y, z). View.")
      .def_property_readonly(
          "scales",
          [](const py::object& self) {
            return particle_view<double>(
                self, [](const Particle& q) { return &q.scale; }, 0);
          },
          "float64 (N,): uniform scale of the stored shape (1 unless a shape library). View.")
      .def_property_readonly(
          "size_classes",
          [](const py::object& self) {
            return particle_view<std::uint32_t>(
                self, [](const Particle& q) { return &q.size_class; }, 0);
          },
          "uint32 (N,): grading class index (0 without a grading). View.")
      .def_property_readonly(
          "control_radii",
          [](const py::object& self) {
            return particle_view<double>(
                self, [](const Particle& q) { return &q.control_radius; }, 0);
          },
          "float64 (N,): control radius r each particle was grown with, after scaling (m). View.")
      .def_property_readonly(
          "shape_indices",
          [](const py::object& self) {
            return particle_view<std::uint32_t>(
                self, [](const Particle& q) { return &q.shape; }, 0);
          },
          "uint32 (N,): index of each particle's shape (shape_vertices / shape_triangles). View.")
      .def_property_readonly(
          "particle_count", [](const PyPacking& p) { return p.packing.particles.size(); },
          "Number of particles N.")
      .def("__len__", [](const PyPacking& p) { return p.packing.particles.size(); })
      .def_property_readonly(
          "shape_count", [](const PyPacking& p) { return p.packing.shapes.size(); },
          "Number of stored shapes (a lattice pack has one per particle; a shape library fewer).")
      .def(
          "shape_vertices",
          [](const py::object& self, long long index) {
            const Packing& packing = packing_of(self);
            const auto& vertices = packing.shapes[shape_index(packing, index)].vertices();
            return view<double>(vertices.data(), vertices.size(), 3, sizeof(Vec3), self);
          },
          py::arg("shape"),
          "float64 (V, 3): shape `shape`'s vertices in its local frame (m, centroid at the "
          "origin, before the particle's scale). View.")
      .def(
          "shape_triangles",
          [](const py::object& self, long long index) {
            const Packing& packing = packing_of(self);
            const auto& triangles = packing.shapes[shape_index(packing, index)].triangles();
            return view<std::uint32_t>(triangles.data(), triangles.size(), 3, sizeof(Triangle),
                                       self);
          },
          py::arg("shape"),
          "uint32 (T, 3): shape `shape`'s triangles, indices into shape_vertices(shape), "
          "counter-clockwise seen from outside. View.")
      .def(
          "world_vertices",
          [](const PyPacking& p, long long index) {
            const auto count = static_cast<long long>(p.packing.particles.size());
            if (index < 0) index += count;
            if (index < 0 || index >= count) {
              throw InvalidInput("particle", std::to_string(index),
                                 "[0, " + std::to_string(count) + ") (particle_count)");
            }
            const ConvexPolyhedron body = p.packing.placed(static_cast<std::size_t>(index));
            py::array_t<double> out(
                {static_cast<py::ssize_t>(body.vertex_count()), py::ssize_t{3}});
            std::copy(body.vertices().front().data(),
                      body.vertices().front().data() + 3 * body.vertex_count(), out.mutable_data());
            return out;
          },
          py::arg("particle"),
          "float64 (V, 3): particle `particle`'s vertices in world coordinates (m), a new array; "
          "its triangles are shape_triangles(shape_indices[particle]).")
      .def(
          "descriptors",
          [](const PyPacking& p) {
            std::vector<ShapeDescriptors> descriptors(p.packing.particles.size());
            {
              const py::gil_scoped_release release;
              parallel_for_index(0, descriptors.size(), [&](std::size_t i) {
                descriptors[i] = describe(p.packing.local_body(i));
              });
            }
            return descriptor_dict(descriptors);
          },
          "Shape descriptors of every particle at its true size: a dict name -> float64 (N,) "
          "(volume m^3, surface_area m^2, sphericity, measured_alpha, ..., as "
          "generate_particles). Computed on call (in parallel).")
      .def_property_readonly(
          "container", [](const PyPacking& p) { return container_dict(p.packing.container); },
          "The container: dict with kind ('box' or 'cylinder'), its sizes (m), a box's periodic "
          "axes ('none', 'x', ..., 'xyz'), wall_gap (m), volume (m^3).")
      .def_property_readonly(
          "provenance",
          [](const PyPacking& p) {
            const Provenance& v = p.packing.provenance;
            py::dict result;
            result["aggpack_version"] = v.aggpack_version;
            result["config_toml"] = v.config_toml;
            result["seed"] = v.seed;
            result["packer"] = v.packer;
            result["shape_library"] = v.shape_library;
            return result;
          },
          "Where the packing came from: aggpack_version, config_toml (the resolved "
          "configuration), seed, packer, shape_library (particle.library: a header line, then "
          "'name<TAB>hash' per library shape, shape k on line k + 1; '' without a library).")
      .def_property_readonly(
          "report",
          [](const PyPacking& p) -> py::object {
            if (!p.report) return py::none();
            py::dict result = report_dict(*p.report);
            for (const auto& [key, value] : p.extra) result[key] = value;
            return result;
          },
          "The packer's report when pack() made this packing (None after read()): placed, "
          "requested, rejected, attempts, solid_volume m^3, container_volume m^3, "
          "solid_fraction, is_target_reached, stop_reason ('target reached', 'cancelled', ...), "
          "shape_seconds, placement_seconds; the dense kind adds densify and fill.")
      .def("__repr__", [](const PyPacking& p) {
        return "<aggpack.Packing " + std::to_string(p.packing.particles.size()) + " particles, " +
               std::to_string(p.packing.shapes.size()) + " shapes, " +
               container_kind_info(p.packing.container).name + ">";
      });
}

}  // namespace aggpack::python
