// What the mesomodel writers share (io/mesomodel_files.h): materials and options checks, the mesh
// check, the element order, the dispatch by extension, atomic writing and the Voigt/Reuss bounds.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"
#include "mesomodel_detail.h"

namespace aggpack {

namespace {

void validate_phase(const std::string& name, const PhaseMaterial& material) {
  const std::string field = "materials." + name + ".";
  // Pa: 1e13 is far above diamond's ~1.1e12; kg/m^3: 1e5 is above any solid (osmium ~22,600).
  if (!(material.youngs_modulus > 0.0 && material.youngs_modulus <= 1e13)) {
    throw InvalidInput(field + "youngs_modulus", format_value(material.youngs_modulus),
                       "(0, 1e13] Pa");
  }
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5)) {
    throw InvalidInput(field + "poisson_ratio", format_value(material.poisson_ratio), "(-1, 0.5)");
  }
  if (!(material.density > 0.0 && material.density <= 1e5)) {
    throw InvalidInput(field + "density", format_value(material.density), "(0, 1e5] kg/m^3");
  }
}

// The cohesive wedges: one particle each, nodes in range, and no ITZ tetrahedra beside them.
void validate_cohesive(const MesoMesh& mesh, std::uint32_t nodes) {
  if (mesh.cohesive_particle.size() != mesh.cohesive.size()) {
    throw InvalidInput("mesh.cohesive_particle size", std::to_string(mesh.cohesive_particle.size()),
                       std::to_string(mesh.cohesive.size()) + " (one per cohesive element)");
  }
  if (mesh.cohesive.empty()) return;
  if (std::find(mesh.phase.begin(), mesh.phase.end(), MesoPhase::kItz) != mesh.phase.end()) {
    throw InvalidInput("mesh.phase", "ITZ tetrahedra beside cohesive elements",
                       "one ITZ model: a solid layer or cohesive elements");
  }
  for (std::size_t i = 0; i < mesh.cohesive.size(); ++i) {
    for (const std::uint32_t node : mesh.cohesive[i]) {
      if (node >= nodes) {
        throw InvalidInput("mesh.cohesive[" + std::to_string(i) + "] node", std::to_string(node),
                           "0.." + std::to_string(nodes == 0 ? 0 : nodes - 1) + " (0-based)");
      }
    }
    const std::uint32_t particle = mesh.cohesive_particle[i];
    if (particle == 0 || particle > mesh.particle_count) {
      throw InvalidInput("mesh.cohesive_particle[" + std::to_string(i) + "]",
                         std::to_string(particle), "1.." + std::to_string(mesh.particle_count));
    }
  }
}

}  // namespace

const PhaseMaterial& MesoMaterials::of(MesoPhase phase) const {
  switch (phase) {
    case MesoPhase::kAggregate:
      return aggregate;
    case MesoPhase::kItz:
      return itz;
    case MesoPhase::kMortar:
      break;
  }
  return mortar;
}

double length_scale(MesoUnits units) { return units == MesoUnits::kMillimetre ? 1000.0 : 1.0; }

void validate(const MesoMaterials& materials) {
  validate_phase("aggregate", materials.aggregate);
  validate_phase("itz", materials.itz);
  validate_phase("mortar", materials.mortar);
}

void validate(const MesoFileOptions& options) {
  validate(options.materials);
  if (options.units != MesoUnits::kMetre && options.units != MesoUnits::kMillimetre) {
    throw InvalidInput("units", std::to_string(static_cast<int>(options.units)), "m or mm");
  }
  if (!(options.step.strain >= 0.0 && options.step.strain <= 0.1)) {
    throw InvalidInput("step.strain", format_value(options.step.strain), "[0, 0.1]; 0 = no step");
  }
  if (options.solver != MesoSolver::kDirect && options.solver != MesoSolver::kIterative) {
    throw InvalidInput("solver", std::to_string(static_cast<int>(options.solver)),
                       "direct or iterative");
  }
}

void validate(const MesoMesh& mesh) {
  const std::size_t count = mesh.tetrahedra.size();
  if (mesh.phase.size() != count) {
    throw InvalidInput("mesh.phase size", std::to_string(mesh.phase.size()),
                       std::to_string(count) + " (one per tetrahedron)");
  }
  if (mesh.particle.size() != count) {
    throw InvalidInput("mesh.particle size", std::to_string(mesh.particle.size()),
                       std::to_string(count) + " (one per tetrahedron)");
  }
  if (count == 0) throw InvalidInput("mesh.tetrahedra", "none", "at least one tetrahedron");
  const std::uint64_t elements = count + mesh.cohesive.size();
  if (mesh.nodes.size() > 0xFFFFFFFFULL || elements > 999999999ULL) {
    throw InvalidInput(
        "mesh size",
        std::to_string(mesh.nodes.size()) + " nodes, " + std::to_string(elements) + " elements",
        "< 2^32 nodes and <= 999999999 elements (Abaqus labels)");
  }
  const Vec3 extent = mesh.bounds.upper - mesh.bounds.lower;
  if (!(extent.x() > 0.0 && extent.y() > 0.0 && extent.z() > 0.0 && extent.allFinite())) {
    throw InvalidInput("mesh.bounds",
                       format_value(extent.x()) + " x " + format_value(extent.y()) + " x " +
                           format_value(extent.z()) + " m",
                       "a box with positive, finite extent");
  }
  // The container's prism is what the writers' face sets are found on: a mesh made by hand must
  // say which container it fills.
  const Aabb prism = prism_bounds(mesh.container, std::max(mesh.prism_sides, 3));
  if (prism.lower != mesh.bounds.lower || prism.upper != mesh.bounds.upper) {
    throw InvalidInput("mesh.container", prism_summary(mesh.container, mesh.prism_sides),
                       "the container whose prism (mesh.prism_sides) has the mesh's bounds");
  }
  const auto nodes = static_cast<std::uint32_t>(mesh.nodes.size());
  validate_cohesive(mesh, nodes);
  for (std::size_t i = 0; i < count; ++i) {
    for (const std::uint32_t node : mesh.tetrahedra[i]) {
      if (node >= nodes) {
        throw InvalidInput("mesh.tetrahedra[" + std::to_string(i) + "] node", std::to_string(node),
                           "0.." + std::to_string(nodes == 0 ? 0 : nodes - 1) + " (0-based)");
      }
    }
    const auto phase = static_cast<std::uint8_t>(mesh.phase[i]);
    if (phase > 2) {
      throw InvalidInput("mesh.phase[" + std::to_string(i) + "]", std::to_string(phase),
                         "0 (mortar), 1 (ITZ), 2 (aggregate)");
    }
    const std::uint32_t particle = mesh.particle[i];
    if (mesh.phase[i] == MesoPhase::kMortar ? particle != 0
                                            : (particle == 0 || particle > mesh.particle_count)) {
      throw InvalidInput("mesh.particle[" + std::to_string(i) + "]", std::to_string(particle),
                         mesh.phase[i] == MesoPhase::kMortar
                             ? "0 for a mortar tetrahedron"
                             : "1.." + std::to_string(mesh.particle_count) +
                                   " for an aggregate or ITZ tetrahedron");
    }
  }
}

ExportFormat mesomodel_format(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::vector<std::string> allowed;
  for (const FormatInfo& info : export_formats()) {
    if (info.write_mesomodel == nullptr) continue;
    if (extension == "." + std::string(info.name)) return info.format;
    allowed.push_back("." + std::string(info.name));
  }
  std::sort(allowed.begin(), allowed.end());
  std::string list;
  for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
  throw InvalidInput("output", "'" + path + "'", list);
}

MesoFileSummary write_mesomodel(const std::string& path, const MesoMesh& mesh,
                                const MesoFileOptions& options) {
  return format_info(mesomodel_format(path)).write_mesomodel(path, mesh, options);
}

MesoModulusBounds voigt_reuss_bounds(const MesoMesh& mesh, const MesoMaterials& materials) {
  validate(mesh);
  validate(materials);
  double volumes[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < mesh.tetrahedra.size(); ++i) {
    const Tetrahedron& t = mesh.tetrahedra[i];
    volumes[static_cast<int>(mesh.phase[i])] +=
        tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
  }
  const double total = volumes[0] + volumes[1] + volumes[2];
  MesoModulusBounds bounds;
  double compliance = 0.0;
  for (int p = 0; p < 3; ++p) {
    bounds.fractions[p] = volumes[p] / total;
    const double modulus = materials.of(static_cast<MesoPhase>(p)).youngs_modulus;
    bounds.voigt += bounds.fractions[p] * modulus;
    compliance += bounds.fractions[p] / modulus;
  }
  bounds.reuss = 1.0 / compliance;
  return bounds;
}

namespace detail {

MesoPhase MesoLayout::group_phase(std::size_t g) const {
  if (g < particle_count) return MesoPhase::kAggregate;
  if (g < 2ULL * particle_count) return MesoPhase::kItz;
  return MesoPhase::kMortar;
}

std::uint32_t MesoLayout::group_particle(std::size_t g) const {
  if (g < particle_count) return static_cast<std::uint32_t>(g + 1);
  if (g < 2ULL * particle_count) return static_cast<std::uint32_t>(g - particle_count + 1);
  return 0;
}

std::uint64_t MesoLayout::phase_begin(MesoPhase phase) const {
  switch (phase) {
    case MesoPhase::kAggregate:
      return group_offsets[0];
    case MesoPhase::kItz:
      return group_offsets[particle_count];
    case MesoPhase::kMortar:
      break;
  }
  return group_offsets[2ULL * particle_count];
}

std::uint64_t MesoLayout::phase_end(MesoPhase phase) const {
  switch (phase) {
    case MesoPhase::kAggregate:
      return group_offsets[particle_count];
    case MesoPhase::kItz:
      return group_offsets[2ULL * particle_count];
    case MesoPhase::kMortar:
      break;
  }
  return group_offsets.back();
}

MesoPhase element_phase(const MesoMesh& mesh, std::uint32_t element) {
  return element < mesh.tetrahedra.size() ? mesh.phase[element] : MesoPhase::kItz;
}

std::uint32_t element_particle(const MesoMesh& mesh, std::uint32_t element) {
  return element < mesh.tetrahedra.size()
             ? mesh.particle[element]
             : mesh.cohesive_particle[element - mesh.tetrahedra.size()];
}

MesoLayout make_layout(const MesoMesh& mesh) {
  MesoLayout layout;
  const std::uint32_t n = mesh.particle_count;
  layout.particle_count = n;
  layout.is_cohesive = !mesh.cohesive.empty();
  const std::size_t groups = 2ULL * n + 1;
  const auto elements = static_cast<std::uint32_t>(element_count(mesh));
  auto group_of = [&](std::uint32_t i) -> std::size_t {
    switch (element_phase(mesh, i)) {
      case MesoPhase::kAggregate:
        return element_particle(mesh, i) - 1;
      case MesoPhase::kItz:
        return n + element_particle(mesh, i) - 1;
      case MesoPhase::kMortar:
        break;
    }
    return 2ULL * n;
  };
  // Counting sort, stable: each group keeps the mesh's order.
  layout.group_offsets.assign(groups + 1, 0);
  for (std::uint32_t i = 0; i < elements; ++i) ++layout.group_offsets[group_of(i) + 1];
  for (std::size_t g = 0; g < groups; ++g) {
    layout.group_offsets[g + 1] += layout.group_offsets[g];
  }
  std::vector<std::uint64_t> next(layout.group_offsets.begin(), layout.group_offsets.end() - 1);
  layout.order.resize(elements);
  for (std::uint32_t i = 0; i < elements; ++i) layout.order[next[group_of(i)]++] = i;
  return layout;
}

void require_good(const std::ostream& out) {
  if (!out.good()) throw IoError(Wording{Sentence::kWriteStreamError, {}});
}

void write_atomically(const std::string& path, Overwrite overwrite,
                      const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  try {
    write(out);
    require_good(out);
  } catch (const IoError&) {
    // A failed write (disk full, file size limit): name the file and the reason.
    if (!out.good()) throw IoError(file.write_error_wording());
    throw;
  }
  file.commit();
}

}  // namespace detail

}  // namespace aggpack
