// The exporters' entry point: format choice, validation, the per-particle meshing view, and the
// per-particle folder mode.

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"
#include "deck_common.h"
#include "export_detail.h"

namespace aggpack {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

constexpr const char* kFormatNames =
    "stl, dat (rock.dat), inp (abaqus), vtu, msh (gmsh), k (key, lsdyna), mac (apdl, ansys), "
    "obj, py (yade)";

detail::ElementMode element_mode(ExportFormat format, const ExportOptions& options) {
  switch (format) {
    case ExportFormat::kStl:
    case ExportFormat::kObj:
    case ExportFormat::kYade:
      return detail::ElementMode::kSurface;
    case ExportFormat::kVtu:
      return options.cells == MeshCells::kTetrahedra ? detail::ElementMode::kTetrahedra
                                                     : detail::ElementMode::kSurface;
    case ExportFormat::kGmsh:
      return options.cells == MeshCells::kSurface ? detail::ElementMode::kSurface
                                                  : detail::ElementMode::kTetrahedra;
    case ExportFormat::kAbaqus:
      return options.is_quadratic ? detail::ElementMode::kQuadraticTetrahedra
                                  : detail::ElementMode::kTetrahedra;
    default:
      return detail::ElementMode::kTetrahedra;
  }
}

void write_format(const detail::ExportModel& model, ExportFormat format, std::ostream& out);

void write_one(const Packing& packing, const std::string& path, const ExportOptions& options,
               ExportFormat format, std::size_t first, std::size_t last, Overwrite overwrite,
               ExportSummary& summary) {
  const detail::ExportModel model(packing, options, element_mode(format, options), first, last);
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  try {
    write_format(model, format, out);
  } catch (const IoError&) {
    // A failed write (disk full, file size limit): name the file and the reason.
    if (!out.good()) throw IoError(file.write_error_message());
    throw;
  }
  file.commit();
  summary.nodes += model.node_count();
  summary.elements += model.element_count();
  summary.files += 1;
  summary.tetgen_shapes += model.tetgen_shape_count();
  summary.tetgen_fallbacks.insert(summary.tetgen_fallbacks.end(), model.tetgen_fallbacks().begin(),
                                  model.tetgen_fallbacks().end());
  summary.quality.add(model.quality());
}

void write_format(const detail::ExportModel& model, ExportFormat format, std::ostream& out) {
  switch (model.options().deck.kind) {
    case DeckKind::kAbaqus:
      detail::write_deck_abaqus(model, out);
      break;
    case DeckKind::kCalculix:
      detail::write_deck_calculix(model, out);
      break;
    case DeckKind::kLsDyna:
      detail::write_deck_lsdyna(model, out);
      break;
    case DeckKind::kYade:
      detail::write_deck_yade(model, out);
      break;
    case DeckKind::kNone:
      break;
  }
  switch (model.options().deck.kind == DeckKind::kNone ? format : ExportFormat::kAuto) {
    case ExportFormat::kStl:
      detail::write_stl(model, out);
      break;
    case ExportFormat::kRockDat:
      detail::write_rock_dat(model, out);
      break;
    case ExportFormat::kAbaqus:
      detail::write_abaqus(model, out);
      break;
    case ExportFormat::kVtu:
      detail::write_vtu(model, out);
      break;
    case ExportFormat::kGmsh:
      detail::write_gmsh(model, out);
      break;
    case ExportFormat::kLsDyna:
      detail::write_lsdyna(model, out);
      break;
    case ExportFormat::kAnsysApdl:
      detail::write_ansys(model, out);
      break;
    case ExportFormat::kObj:
      detail::write_obj(model, out);
      break;
    case ExportFormat::kYade:
      detail::write_yade(model, out);
      break;
    case ExportFormat::kAuto:
      break;
  }
}

// Removes a folder this process created, on every exit path that did not hand it over (and on
// SIGINT/SIGTERM through temp_paths.h).
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const fs::path& beside) {
    std::string folder = beside.parent_path().string();
    const std::string pattern = temporary_pattern(folder);
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const CleanupSignalBlock block;
    if (::mkdtemp(buffer.data()) == nullptr) {
      throw IoError("cannot create a temporary folder beside " + beside.string() + ": " +
                    std::strerror(errno));
    }
    path_ = buffer.data();
    slot_ = register_temporary(path_.string(), /*is_folder=*/true);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  ~TemporaryFolder() {
    if (!path_.empty()) {
      std::error_code error;
      fs::remove_all(path_, error);
    }
    unregister_temporary(slot_);
  }
  [[nodiscard]] const fs::path& path() const { return path_; }
  void forget_on_signal() {
    unregister_temporary(slot_);
    slot_ = -1;
  }
  void release() {
    path_.clear();
    unregister_temporary(slot_);
    slot_ = -1;
  }

 private:
  fs::path path_;
  int slot_ = -1;
};

void write_per_particle(const Packing& packing, const std::string& path,
                        const ExportOptions& options, ExportFormat format, ExportSummary& summary) {
  fs::path target(path);
  while (!target.empty() && !target.has_filename()) target = target.parent_path();  // "dir/"
  // The folder itself is checked like a file: its parent must exist and be writable, and an
  // existing folder (a real one: not a link, file or device) is only replaced with
  // Overwrite::kAllow.
  check_folder_writable(target.parent_path().string(), target.string());
  std::error_code error;
  const fs::file_status status = fs::symlink_status(target, error);
  const bool exists = fs::exists(status);
  if (exists && status.type() != fs::file_type::directory) {
    throw IoError("refusing to replace " + target.string() + " by a folder: it is not a folder" +
                  (status.type() == fs::file_type::symlink ? " (symbolic link)" : ""));
  }
  if (exists && options.overwrite != Overwrite::kAllow) {
    throw IoError("cannot write " + target.string() + ": it exists (use --force to replace it)");
  }
  TemporaryFolder staging(target);
  fs::permissions(staging.path(),
                  fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                      fs::perms::others_read | fs::perms::others_exec,
                  error);
  const std::size_t count = packing.particles.size();
  const int width = std::max<int>(6, static_cast<int>(std::to_string(count).size()));
  std::string extension = ".";
  extension += format_name(format);
  for (std::size_t i = 0; i < count; ++i) {
    const std::string number = std::to_string(i + 1);
    std::string name = "P";
    name.append(static_cast<std::size_t>(width) - std::min<std::size_t>(width, number.size()), '0');
    name += number;
    name += extension;
    write_one(packing, (staging.path() / name).string(), options, format, i, i + 1,
              Overwrite::kForbid, summary);
  }
  // Swap in the new folder; an old one is moved aside first and removed only afterwards, so at
  // every moment `target` is either the complete old or the complete new folder.
  if (exists) {
    TemporaryFolder old_parking(target);
    fs::remove(old_parking.path());
    // From here it holds the user's old folder: a signal must not empty it (at worst it stays
    // behind under its temporary name).
    old_parking.forget_on_signal();
    fs::rename(target, old_parking.path(), error);
    if (error) throw IoError("cannot replace " + target.string() + ": " + error.message());
    fs::rename(staging.path(), target, error);
    if (error) {
      fs::rename(old_parking.path(), target);
      throw IoError("cannot rename into " + target.string() + ": " + error.message());
    }
  } else {
    fs::rename(staging.path(), target, error);
    if (error) throw IoError("cannot rename into " + target.string() + ": " + error.message());
  }
  staging.release();
}

// The format a deck is written in.
ExportFormat deck_format(DeckKind kind) {
  switch (kind) {
    case DeckKind::kAbaqus:
    case DeckKind::kCalculix:
      return ExportFormat::kAbaqus;
    case DeckKind::kLsDyna:
      return ExportFormat::kLsDyna;
    case DeckKind::kYade:
      return ExportFormat::kYade;
    case DeckKind::kNone:
      break;
  }
  return ExportFormat::kAuto;
}

void validate_deck(const ExportOptions& options, ExportFormat format) {
  const DeckOptions& deck = options.deck;
  if (deck.kind == DeckKind::kNone) return;
  const std::string name = deck_name(deck.kind);
  if (format != deck_format(deck.kind)) {
    throw InvalidInput("deck", name + " for ." + format_name(format),
                       "the ." + format_name(deck_format(deck.kind)) + " format");
  }
  if (options.is_per_particle) {
    throw InvalidInput("per-particle", "true with --deck " + name, "one file for a deck");
  }
  if (options.abaqus_layout != AbaqusLayout::kElementSets) {
    throw InvalidInput("inp layout", "parts with --deck " + name, "sets");
  }
  if (options.is_quadratic && deck.kind == DeckKind::kAbaqus) {
    throw InvalidInput("quadratic", "true with --deck abaqus",
                       "C3D4 (Abaqus/Explicit has no C3D10; use --deck calculix)");
  }
  require_in_range("friction", deck.friction, 0.0, 10.0);
  require_positive("gravity", deck.gravity);
  require_positive("baffle speed", deck.baffle_speed);
  require_in_range("baffle position", deck.baffle_position, 0.0, 1e9);
  require_in_range("trough length", deck.trough_length, 0.0, 1e9);
  require_in_range("settle time", deck.settle_time, 0.0, 1e9);
  require_in_range("rest time", deck.rest_time, 0.0, 1e9);
  require_in_range("contact distance", deck.contact_distance, 0.0, 1e9);
  require_in_range("time step", deck.time_step, 0.0, 1e9);
}

}  // namespace

ExportFormat parse_export_format(const std::string& name) {
  const std::string key = lower(name);
  if (key == "stl") return ExportFormat::kStl;
  if (key == "dat" || key == "rock.dat" || key == "rockdat") return ExportFormat::kRockDat;
  if (key == "inp" || key == "abaqus" || key == "calculix") return ExportFormat::kAbaqus;
  if (key == "vtu" || key == "vtk") return ExportFormat::kVtu;
  if (key == "msh" || key == "gmsh") return ExportFormat::kGmsh;
  if (key == "k" || key == "key" || key == "lsdyna" || key == "ls-dyna") {
    return ExportFormat::kLsDyna;
  }
  if (key == "mac" || key == "apdl" || key == "ansys") return ExportFormat::kAnsysApdl;
  if (key == "obj") return ExportFormat::kObj;
  if (key == "py" || key == "yade") return ExportFormat::kYade;
  throw InvalidInput("format", "'" + name + "'", kFormatNames);
}

ExportFormat format_from_extension(const std::string& path) {
  fs::path file(path);
  while (!file.empty() && !file.has_filename()) file = file.parent_path();
  const std::string extension = file.extension().string();
  if (extension.size() < 2) {
    throw InvalidInput("output extension", "'" + file.string() + "'",
                       std::string("one of ") + kFormatNames + ", or give --format");
  }
  try {
    return parse_export_format(extension.substr(1));
  } catch (const InvalidInput&) {
    throw InvalidInput("output extension", "'" + extension + "'",
                       std::string("one of ") + kFormatNames + ", or give --format");
  }
}

DeckKind parse_deck_kind(const std::string& name) {
  const std::string key = lower(name);
  if (key == "none") return DeckKind::kNone;
  if (key == "abaqus") return DeckKind::kAbaqus;
  if (key == "calculix" || key == "ccx") return DeckKind::kCalculix;
  if (key == "lsdyna" || key == "ls-dyna") return DeckKind::kLsDyna;
  if (key == "yade") return DeckKind::kYade;
  throw InvalidInput("deck", "'" + name + "'", "none, abaqus, calculix (ccx), lsdyna, yade");
}

std::string deck_name(DeckKind kind) {
  switch (kind) {
    case DeckKind::kAbaqus:
      return "abaqus";
    case DeckKind::kCalculix:
      return "calculix";
    case DeckKind::kLsDyna:
      return "lsdyna";
    case DeckKind::kYade:
      return "yade";
    case DeckKind::kNone:
      break;
  }
  return "none";
}

const std::vector<std::string>& output_format_names() {
  static const std::vector<std::string> names = {"native", "stl", "obj", "vtu",  "dat",
                                                 "inp",    "msh", "k",   "apdl", "yade"};
  return names;
}

std::string format_name(ExportFormat format) {
  switch (format) {
    case ExportFormat::kStl:
      return "stl";
    case ExportFormat::kRockDat:
      return "dat";
    case ExportFormat::kAbaqus:
      return "inp";
    case ExportFormat::kVtu:
      return "vtu";
    case ExportFormat::kGmsh:
      return "msh";
    case ExportFormat::kLsDyna:
      return "k";
    case ExportFormat::kAnsysApdl:
      return "mac";
    case ExportFormat::kObj:
      return "obj";
    case ExportFormat::kYade:
      return "py";
    case ExportFormat::kAuto:
      break;
  }
  return "auto";
}

void validate(const ExportOptions& options, ExportFormat format) {
  require_positive("scale", options.scale);
  validate(options.tetrahedra);
  const auto& material = options.material;
  require_positive("density", material.density);
  require_positive("youngs modulus", material.youngs_modulus);
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5)) {
    throw InvalidInput("poisson ratio", format_value(material.poisson_ratio), "(-1, 0.5)");
  }
  const bool is_name_ok = !material.name.empty() && material.name.size() <= 32 &&
                          std::isalpha(static_cast<unsigned char>(material.name[0])) &&
                          std::all_of(material.name.begin(), material.name.end(),
                                      [](unsigned char c) { return std::isalnum(c) || c == '_'; });
  if (!is_name_ok) {
    throw InvalidInput("material name", "'" + material.name + "'",
                       "a letter, then letters, digits or _, at most 32 characters");
  }
  if (options.is_quadratic && format != ExportFormat::kAbaqus) {
    throw InvalidInput("quadratic", "true for ." + format_name(format), "only for .inp (C3D10)");
  }
  if (options.is_per_particle && format != ExportFormat::kStl && format != ExportFormat::kObj) {
    throw InvalidInput("per-particle", "true for ." + format_name(format), "only for .stl, .obj");
  }
  if (options.cells != MeshCells::kDefault && format != ExportFormat::kVtu &&
      format != ExportFormat::kGmsh) {
    throw InvalidInput("cells", "set for ." + format_name(format), "only for .vtu, .msh");
  }
  validate_deck(options, format);
}

ExportFormat resolve_format(const std::string& path, const ExportOptions& options) {
  if (options.format != ExportFormat::kAuto) return options.format;
  if (options.deck.kind != DeckKind::kNone) {
    // The deck picks the format; an extension naming another format is a mistake.
    const ExportFormat format = deck_format(options.deck.kind);
    ExportFormat named = ExportFormat::kAuto;
    try {
      named = format_from_extension(path);
    } catch (const InvalidInput&) {
    }
    if (named != ExportFormat::kAuto && named != format) {
      throw InvalidInput("output extension", "'" + fs::path(path).extension().string() + "'",
                         "." + format_name(format) + " for --deck " + deck_name(options.deck.kind));
    }
    return format;
  }
  fs::path file(path);
  while (!file.empty() && !file.has_filename()) file = file.parent_path();
  if (options.is_per_particle && file.extension().empty()) return ExportFormat::kStl;
  return format_from_extension(path);
}

ExportSummary write(const Packing& packing, const std::string& path, const ExportOptions& options) {
  const ExportFormat format = resolve_format(path, options);
  validate(options, format);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    if (packing.particles[i].shape >= packing.shapes.size()) {
      throw InvalidInput("particle " + std::to_string(i) + " shape",
                         std::to_string(packing.particles[i].shape),
                         "< " + std::to_string(packing.shapes.size()));
    }
  }
  ExportSummary summary;
  summary.format = format;
  summary.particles = packing.particles.size();
  if (options.is_per_particle) {
    write_per_particle(packing, path, options, format, summary);
  } else {
    write_one(packing, path, options, format, 0, packing.particles.size(), options.overwrite,
              summary);
  }
  return summary;
}

namespace detail {

ExportModel::ExportModel(const Packing& packing, const ExportOptions& options, ElementMode mode,
                         std::size_t first, std::size_t last)
    : packing_(packing), options_(options), mode_(mode), first_(first), last_(last) {
  std::vector<char> is_used(packing.shapes.size(), 0);
  for (std::size_t k = 0; k < size(); ++k) is_used[particle(k).shape] = 1;
  shapes_.resize(packing.shapes.size());
  const bool is_tetgen =
      mode != ElementMode::kSurface && options.tetrahedra.method == TetMethod::kTetGen;
  if (is_tetgen) mesh_with_tetgen(is_used);
  auto measure = [&](std::size_t s) {
    if (!is_used[s]) return;
    const ConvexPolyhedron& body = packing.shapes[s];
    const MassProperties properties = mass_properties(body);
    ShapeInfo& info = shapes_[s];
    info.volume = properties.volume;
    info.centroid = properties.centroid;
    if (properties.volume > 0 && properties.surface_area > 0) {
      info.sphericity = aggpack::sphericity(properties.volume, properties.surface_area);
      info.alpha = aggpack::measured_alpha(properties.volume, properties.surface_area);
    }
    if (mode == ElementMode::kSurface) {
      info.nodes = static_cast<std::uint32_t>(body.vertex_count());
      info.elements = static_cast<std::uint32_t>(body.triangle_count());
      return;
    }
    if (!is_tetgen && !(properties.volume > 0)) {
      throw InvalidInput("shape " + std::to_string(s) + " volume", format_value(properties.volume),
                         "> 0 (a closed outward convex body)");
    }
    const std::size_t linear_nodes =
        is_tetgen ? shape_meshes_[s].nodes.size() : body.vertex_count() + 1;
    info.elements = static_cast<std::uint32_t>(is_tetgen ? shape_meshes_[s].tetrahedra.size()
                                                         : body.triangle_count());
    info.nodes = static_cast<std::uint32_t>(linear_nodes);
    if (is_tetgen) {
      info.quality = measure_quality(shape_meshes_[s].nodes, shape_meshes_[s].tetrahedra);
    } else {
      std::vector<Vec3> nodes = body.vertices();
      nodes.push_back(properties.centroid);
      std::vector<Tetrahedron> fan;
      fan.reserve(body.triangle_count());
      for (const Triangle& t : body.triangles()) {
        fan.push_back(fan_tetrahedron(t, static_cast<std::uint32_t>(body.vertex_count())));
      }
      info.quality = measure_quality(nodes, fan);
    }
    if (mode == ElementMode::kQuadraticTetrahedra) {
      // Fan edges are the surface edges (3F/2) plus one spoke per vertex.
      const std::size_t edges = is_tetgen ? count(shape_meshes_[s]).edges
                                          : body.triangle_count() * 3 / 2 + body.vertex_count();
      info.nodes = static_cast<std::uint32_t>(linear_nodes + edges);
    }
  };
  parallel_for_index(0, packing.shapes.size(), measure);
  node_offsets_.resize(size() + 1, 0);
  element_offsets_.resize(size() + 1, 0);
  for (std::size_t k = 0; k < size(); ++k) {
    const ShapeInfo& info = shapes_[particle(k).shape];
    node_offsets_[k + 1] = node_offsets_[k] + info.nodes;
    element_offsets_[k + 1] = element_offsets_[k] + info.elements;
  }
}

// TetGen runs in worker processes (tetgen_meshes); a shape it fails on, e.g. one where Debian's
// TetGen 1.5 aborts, is cut as the paper's centroid fan and reported instead of failing the export.
void ExportModel::mesh_with_tetgen(const std::vector<char>& is_used) {
  std::vector<std::uint32_t> shapes;
  std::vector<const ConvexPolyhedron*> bodies;
  for (std::size_t s = 0; s < is_used.size(); ++s) {
    if (!is_used[s]) continue;
    shapes.push_back(static_cast<std::uint32_t>(s));
    bodies.push_back(&packing_.shapes[s]);
  }
  std::vector<TetGenOutcome> outcomes = tetgen_meshes(bodies, options_.tetrahedra);
  shape_meshes_.resize(packing_.shapes.size());
  tetgen_shape_count_ = shapes.size();
  std::vector<std::size_t> fallback_of(packing_.shapes.size(), SIZE_MAX);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const std::uint32_t s = shapes[i];
    if (outcomes[i].is_meshed) {
      shape_meshes_[s] = std::move(outcomes[i].mesh);
      continue;
    }
    shape_meshes_[s] = centroid_fan(packing_.shapes[s]);
    fallback_of[s] = tetgen_fallbacks_.size();
    tetgen_fallbacks_.push_back(
        {.shape = s, .failure = std::move(outcomes[i].failure), .particles = {}});
  }
  for (std::size_t k = 0; k < size(); ++k) {
    const std::size_t fallback = fallback_of[particle(k).shape];
    if (fallback != SIZE_MAX) tetgen_fallbacks_[fallback].particles.push_back(particle_number(k));
  }
}

std::string ExportModel::particle_name(std::size_t k) const {
  std::string name = "P";
  name += std::to_string(particle_number(k));
  return name;
}

Vec3 ExportModel::place(std::size_t k, const Vec3& local) const {
  const Particle& p = particle(k);
  return options_.scale * (p.pose.rotation * (p.scale * local) + p.pose.position);
}

void ExportModel::surface_nodes(std::size_t k, std::vector<Vec3>& nodes) const {
  const auto& vertices = packing_.shapes[particle(k).shape].vertices();
  nodes.resize(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) nodes[i] = place(k, vertices[i]);
}

const std::vector<Triangle>& ExportModel::triangles(std::size_t k) const {
  return packing_.shapes[particle(k).shape].triangles();
}

void ExportModel::linear_nodes(std::size_t k, std::vector<Vec3>& nodes) const {
  const std::uint32_t s = particle(k).shape;
  if (!shape_meshes_.empty()) {
    const std::vector<Vec3>& local = shape_meshes_[s].nodes;
    nodes.resize(local.size());
    for (std::size_t i = 0; i < local.size(); ++i) nodes[i] = place(k, local[i]);
    return;
  }
  surface_nodes(k, nodes);
  if (mode_ != ElementMode::kSurface) nodes.push_back(place(k, shapes_[s].centroid));
}

const std::vector<Tetrahedron>& ExportModel::tetrahedra(std::size_t k,
                                                        std::vector<Tetrahedron>& scratch) const {
  const std::uint32_t s = particle(k).shape;
  if (!shape_meshes_.empty()) return shape_meshes_[s].tetrahedra;
  const ConvexPolyhedron& body = packing_.shapes[s];
  const auto centre = static_cast<std::uint32_t>(body.vertex_count());
  scratch.resize(body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    scratch[f] = fan_tetrahedron(body.triangles()[f], centre);
  }
  return scratch;
}

QuadraticTopology ExportModel::quadratic_topology(std::size_t k) const {
  if (mode_ != ElementMode::kQuadraticTetrahedra) return {};
  const std::uint32_t s = particle(k).shape;
  const std::size_t corners =
      shape_meshes_.empty() ? packing_.shapes[s].vertex_count() + 1 : shape_meshes_[s].nodes.size();
  std::vector<Tetrahedron> scratch;
  return aggpack::quadratic_topology(tetrahedra(k, scratch), static_cast<std::uint32_t>(corners));
}

const std::vector<std::uint8_t>& ExportModel::boundary_faces(std::size_t k) const {
  return shape_meshes_[particle(k).shape].boundary_faces;
}

double ExportModel::volume(std::size_t k) const {
  const double factor = particle(k).scale * options_.scale;
  return shapes_[particle(k).shape].volume * factor * factor * factor;
}
double ExportModel::sphericity(std::size_t k) const {
  return shapes_[particle(k).shape].sphericity;
}
double ExportModel::alpha(std::size_t k) const { return shapes_[particle(k).shape].alpha; }
double ExportModel::control_radius(std::size_t k) const {
  return particle(k).control_radius * options_.scale;
}
std::uint32_t ExportModel::size_class(std::size_t k) const { return particle(k).size_class; }

TetQuality ExportModel::quality() const {
  TetQuality total;
  if (mode_ == ElementMode::kSurface) return total;
  std::vector<std::uint64_t> uses(shapes_.size(), 0);
  for (std::size_t k = 0; k < size(); ++k) ++uses[particle(k).shape];
  for (std::size_t s = 0; s < shapes_.size(); ++s) total.add(shapes_[s].quality, uses[s]);
  return total;
}

void append_field(std::string& out, std::uint64_t value, int width) {
  char text[32];
  const int length =
      std::snprintf(text, sizeof text, "%*llu", width, static_cast<unsigned long long>(value));
  out.append(text, static_cast<std::size_t>(length));
}

void append_field(std::string& out, double value, int width) {
  // Width - 7 significant digits after the point leaves room for sign, "d.", and "e+NN".
  char text[48];
  const int length = std::snprintf(text, sizeof text, "%*.*e", width, width - 8, value);
  out.append(text, static_cast<std::size_t>(length));
}

void require_ids_fit(const ExportModel& model, std::uint64_t max_id, const std::string& format) {
  const std::uint64_t largest =
      std::max({model.node_count(), model.element_count(),
                static_cast<std::uint64_t>(model.particle_index(model.size()))});
  if (largest > max_id) {
    throw LimitExceeded(format + " ids", std::to_string(largest), "<= " + std::to_string(max_id));
  }
}

}  // namespace detail

}  // namespace aggpack
