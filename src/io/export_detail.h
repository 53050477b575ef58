#pragma once
// Internals shared by the exporters (src/io/export_*.cpp); not a public header.

#include <charconv>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/io/export.h"
#include "aggpack/io/text_number.h"

namespace aggpack::detail {

/// What a writer's elements are.
enum class ElementMode { kSurface, kTetrahedra, kQuadraticTetrahedra };

/// Per-shape measures, computed once (unscaled, local frame).
struct ShapeInfo {
  double volume = 0;
  double sphericity = 0;
  double alpha = 0;
  Vec3 centroid = Vec3::Zero();
  std::uint32_t nodes = 0;     ///< per particle of this shape, in the model's element mode
  std::uint32_t elements = 0;  ///< triangles or tetrahedra
  TetQuality quality = {};     ///< tetrahedral modes: of the shape's mesh
};

/// A read-only view of particles [first, last) of a packing, meshed on demand in world
/// coordinates times the export scale. Holds per-shape data only: each shape is tetrahedralised
/// once, here (TetGen), or is its own fan (its triangles and centroid). A particle's mesh is its
/// shape's, so writers ask for the part each pass writes: a node pass places the particle's nodes
/// (linear_nodes) and an element pass reads the shape's connectivity (tetrahedra), which needs no
/// coordinates; nothing per particle is kept.
class ExportModel {
 public:
  ExportModel(const Packing& packing, const ExportOptions& options, ElementMode mode,
              std::size_t first, std::size_t last);

  [[nodiscard]] std::size_t size() const { return last_ - first_; }
  /// Index into packing.particles of the k-th particle of the view.
  [[nodiscard]] std::size_t particle_index(std::size_t k) const { return first_ + k; }
  /// 1-based particle number used in names ("P<number>").
  [[nodiscard]] std::size_t particle_number(std::size_t k) const { return first_ + k + 1; }
  /// "P<number>", the particle's name in set, part and group names.
  [[nodiscard]] std::string particle_name(std::size_t k) const;
  [[nodiscard]] const Packing& packing() const { return packing_; }
  [[nodiscard]] const ExportOptions& options() const { return options_; }
  [[nodiscard]] ElementMode mode() const { return mode_; }
  /// True when the tetrahedra are centroid fans (every tetrahedron's face S1 on the surface). With
  /// TetGen false, also for shapes that fell back to fans (boundary_faces tells their surface).
  [[nodiscard]] bool is_fan() const { return shape_meshes_.empty(); }

  /// 0-based offset of particle k's first node / element; k = size() gives the totals.
  [[nodiscard]] std::uint64_t node_offset(std::size_t k) const { return node_offsets_[k]; }
  [[nodiscard]] std::uint64_t element_offset(std::size_t k) const { return element_offsets_[k]; }
  [[nodiscard]] std::uint64_t node_count() const { return node_offsets_.back(); }
  [[nodiscard]] std::uint64_t element_count() const { return element_offsets_.back(); }
  [[nodiscard]] std::uint32_t nodes_of(std::size_t k) const {
    return static_cast<std::uint32_t>(node_offsets_[k + 1] - node_offsets_[k]);
  }
  [[nodiscard]] std::uint32_t elements_of(std::size_t k) const {
    return static_cast<std::uint32_t>(element_offsets_[k + 1] - element_offsets_[k]);
  }

  /// Particle k's surface vertices in output coordinates (same order as the shape's vertices).
  void surface_nodes(std::size_t k, std::vector<Vec3>& nodes) const;
  /// Particle k's surface triangles (0-based, local to the particle, outward CCW).
  [[nodiscard]] const std::vector<Triangle>& triangles(std::size_t k) const;
  /// Particle k's nodes of the linear mesh in output coordinates: the surface vertices, then for
  /// tetrahedra the centroid (fan) or TetGen's added nodes. A quadratic writer appends the
  /// mid-side nodes (append_midside_nodes).
  void linear_nodes(std::size_t k, std::vector<Vec3>& nodes) const;
  /// Particle k's linear tetrahedra (0-based, local to the particle): the shape's TetGen mesh, or
  /// its centroid fan built into `scratch` (fan_tetrahedron of every surface triangle, the
  /// centroid being node vertex_count). No coordinates are computed.
  [[nodiscard]] const std::vector<Tetrahedron>& tetrahedra(std::size_t k,
                                                           std::vector<Tetrahedron>& scratch) const;
  /// Particle k's 10-node elements (quadratic mode; empty otherwise): a function of its shape's
  /// tetrahedra only, so it costs an edge map per call and no coordinates.
  [[nodiscard]] QuadraticTopology quadratic_topology(std::size_t k) const;
  /// Particle k's surface faces per tetrahedron (TetMesh::boundary_faces). TetGen meshes only:
  /// a fan's surface is face S1 of every tetrahedron (is_fan()).
  [[nodiscard]] const std::vector<std::uint8_t>& boundary_faces(std::size_t k) const;

  /// Shapes of the view TetGen was asked to mesh, and those it failed on (cut as fans).
  [[nodiscard]] std::uint64_t tetgen_shape_count() const { return tetgen_shape_count_; }
  [[nodiscard]] const std::vector<TetGenFallback>& tetgen_fallbacks() const {
    return tetgen_fallbacks_;
  }

  /// Particle k's volume in output units (m^3 times scale^3), sphericity (Eq. 1), measured alpha
  /// (Eq. 2), control radius in output units, size class.
  [[nodiscard]] double volume(std::size_t k) const;
  [[nodiscard]] double sphericity(std::size_t k) const;
  [[nodiscard]] double alpha(std::size_t k) const;
  [[nodiscard]] double control_radius(std::size_t k) const;
  [[nodiscard]] std::uint32_t size_class(std::size_t k) const;
  /// Quality of every tetrahedron of the view (each shape measured once, counted per particle);
  /// empty in surface mode.
  [[nodiscard]] TetQuality quality() const;

 private:
  [[nodiscard]] const Particle& particle(std::size_t k) const {
    return packing_.particles[first_ + k];
  }
  [[nodiscard]] Vec3 place(std::size_t k, const Vec3& local) const;
  void mesh_with_tetgen(const std::vector<char>& is_used);

  const Packing& packing_;
  const ExportOptions& options_;
  ElementMode mode_;
  std::size_t first_;
  std::size_t last_;
  std::vector<ShapeInfo> shapes_;
  /// TetGen meshes per shape (local frame; a fan where TetGen failed); empty for fans.
  std::vector<TetMesh> shape_meshes_;
  std::uint64_t tetgen_shape_count_ = 0;
  std::vector<TetGenFallback> tetgen_fallbacks_;
  std::vector<std::uint64_t> node_offsets_;
  std::vector<std::uint64_t> element_offsets_;
};

/// Formats `count` items in parallel batches and writes them to `out` in item order, so the
/// output does not depend on the thread count. `format(k, buffer)` appends item k's bytes.
template <class Format>
void stream_items(std::size_t count, std::ostream& out, const Format& format) {
  constexpr std::size_t kBatch = 1024;
  std::vector<std::string> buffers(kBatch);
  for (std::size_t begin = 0; begin < count; begin += kBatch) {
    const std::size_t size = std::min(kBatch, count - begin);
    auto run = [&](std::size_t j) {
      buffers[j].clear();
      format(begin + j, buffers[j]);
    };
    parallel_for_index(0, size, run);
    for (std::size_t j = 0; j < size; ++j) {
      out.write(buffers[j].data(), static_cast<std::streamsize>(buffers[j].size()));
    }
    // Stop at the first failed write (disk full, file size limit) instead of formatting the rest.
    if (!out.good()) throw IoError(Wording{Sentence::kWriteStreamError, {}});
  }
}

/// Appends the shortest decimal form that reads back to exactly `value`.
inline void append_number(std::string& out, double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

/// Appends `value` in scientific notation with `digits` digits after the point.
inline void append_scientific(std::string& out, double value, int digits) {
  char text[40];
  const auto result =
      std::to_chars(text, text + sizeof text, value, std::chars_format::scientific, digits);
  out.append(text, result.ptr);
}

inline void append_number(std::string& out, std::uint64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

/// Appends one text line per node, "<prefix><id><separator>x<separator>y<separator>z", ids
/// counting up from `first_id` (rock.dat and Abaqus: "", ", "; ANSYS: "N,", ","), each coordinate
/// in at most `max_chars` characters (append_number_fitting).
inline void append_node_lines(std::string& out, std::string_view prefix, std::string_view separator,
                              std::uint64_t first_id, const std::vector<Vec3>& nodes,
                              int max_chars) {
  std::uint64_t id = first_id;
  for (const Vec3& node : nodes) {
    out += prefix;
    append_number(out, id++);
    for (int axis = 0; axis < 3; ++axis) {
      out += separator;
      append_number_fitting(out, node[axis], max_chars);
    }
    out += '\n';
  }
}

/// Appends one text line per element, "<prefix><id><separator>n1<separator>n2...", ids counting
/// up from `first_id`, node numbers = `first_node` + the element's 0-based local numbers.
template <class Element>
void append_element_lines(std::string& out, std::string_view prefix, std::string_view separator,
                          std::uint64_t first_id, std::uint64_t first_node,
                          const std::vector<Element>& elements) {
  std::uint64_t id = first_id;
  for (const Element& element : elements) {
    out += prefix;
    append_number(out, id++);
    for (auto index : element) {
      out += separator;
      append_number(out, first_node + index);
    }
    out += '\n';
  }
}

/// Appends `value` right-aligned in a field of `width` characters (LS-DYNA fixed columns).
void append_field(std::string& out, std::uint64_t value, int width);
void append_field(std::string& out, double value, int width);

/// Appends raw little-endian bytes of a trivially copyable value.
template <class T>
void append_bytes(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// Throws LimitExceeded unless every id of the model fits `max_id` (formats with 32-bit or
/// fixed-width ids).
void require_ids_fit(const ExportModel& model, std::uint64_t max_id, const std::string& format);

// One writer per format. Each writes the whole view to `out`.
void write_stl(const ExportModel& model, std::ostream& out);
void write_rock_dat(const ExportModel& model, std::ostream& out);
void write_abaqus(const ExportModel& model, std::ostream& out);
void write_vtu(const ExportModel& model, std::ostream& out);
void write_gmsh(const ExportModel& model, std::ostream& out);
void write_lsdyna(const ExportModel& model, std::ostream& out);
/// The .k file without its closing *END; `comments` ($ lines) follow *KEYWORD. Part i is particle
/// i, section 1 and material 1 are the particles'.
void write_lsdyna_mesh(const ExportModel& model, std::ostream& out, const std::string& comments);
void write_ansys(const ExportModel& model, std::ostream& out);
void write_obj(const ExportModel& model, std::ostream& out);
void write_yade(const ExportModel& model, std::ostream& out);

}  // namespace aggpack::detail
