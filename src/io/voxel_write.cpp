// Files of the mesomodel's phase image (io/voxel_image.h).

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/text_number.h"
#include "aggpack/io/voxel_image.h"

namespace aggpack {

namespace {

// Shortest text that reads back to exactly `value`.
std::string number(double value) {
  std::string text;
  append_number_fitting(text, value, 32);
  return text;
}

template <class T>
void write_block(std::ostream& out, const std::vector<T>& values) {
  const std::uint64_t bytes = values.size() * sizeof(T);
  out.write(reinterpret_cast<const char*>(&bytes), sizeof bytes);
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(bytes));
}

void commit(AtomicFile& file) {
  if (!file.stream()) throw IoError(file.write_error_wording());
  file.commit();
}

}  // namespace

void write_vti(const std::string& path, const VoxelImage& image, Overwrite overwrite) {
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  const auto& d = image.dims;
  const std::string extent =
      "0 " + std::to_string(d[0]) + " 0 " + std::to_string(d[1]) + " 0 " + std::to_string(d[2]);
  const std::uint64_t phase_bytes = image.phase.size();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <ImageData WholeExtent=\"" << extent << "\" Origin=\"" << number(image.origin.x())
      << ' ' << number(image.origin.y()) << ' ' << number(image.origin.z()) << "\" Spacing=\""
      << number(image.spacing) << ' ' << number(image.spacing) << ' ' << number(image.spacing)
      << "\">\n"
      << "    <Piece Extent=\"" << extent << "\">\n"
      << "      <CellData Scalars=\"phase\">\n"
      << "        <DataArray type=\"UInt8\" Name=\"phase\" format=\"appended\" offset=\"0\"/>\n"
      << "        <DataArray type=\"UInt32\" Name=\"particle\" format=\"appended\" offset=\""
      << (sizeof(std::uint64_t) + phase_bytes) << "\"/>\n"
      << "      </CellData>\n"
      << "    </Piece>\n"
      << "  </ImageData>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";
  write_block(out, image.phase);
  write_block(out, image.particle);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  commit(file);
}

void write_voxel_raw(const std::string& base, const VoxelImage& image, const Packing& packing,
                     double itz_thickness, Overwrite overwrite) {
  const std::string phase_path = base + ".phase.raw";
  const std::string particle_path = base + ".particle.raw";
  const std::string header_path = base + ".json";
  for (const auto* path : {&phase_path, &particle_path, &header_path}) {
    check_writable(*path, overwrite);
  }
  OutputTransaction transaction;
  for (const auto* path : {&phase_path, &particle_path, &header_path}) transaction.add(*path);
  {
    AtomicFile file(phase_path, overwrite);
    file.stream().write(reinterpret_cast<const char*>(image.phase.data()),
                        static_cast<std::streamsize>(image.phase.size()));
    commit(file);
  }
  {
    AtomicFile file(particle_path, overwrite);
    file.stream().write(reinterpret_cast<const char*>(image.particle.data()),
                        static_cast<std::streamsize>(image.particle.size() * 4));
    commit(file);
  }
  double aggregate_volume = 0.0;
  double shell_volume = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron body = packing.local_body(i);
    aggregate_volume += mass_properties(body).volume;
    if (itz_thickness > 0.0) shell_volume += offset_shell_volume(body, itz_thickness);
  }
  const auto counts = image.phase_counts();
  const double voxel = image.spacing * image.spacing * image.spacing;
  const double inside = static_cast<double>(counts[0] + counts[1] + counts[2]);
  nlohmann::ordered_json json;
  json["aggpack_version"] = AGGPACK_VERSION;
  json["dims"] = {image.dims[0], image.dims[1], image.dims[2]};
  json["spacing_m"] = image.spacing;
  json["origin_m"] = {image.origin.x(), image.origin.y(), image.origin.z()};
  json["order"] = "x fastest, then y, then z (C order [z][y][x])";
  // Names relative to the header's folder (where the three files are).
  const auto name = [](const std::string& path) {
    return std::filesystem::path(path).filename().string();
  };
  json["files"] = {{"phase", {{"path", name(phase_path)}, {"type", "uint8"}}},
                   {"particle",
                    {{"path", name(particle_path)},
                     {"type", "uint32 little-endian"},
                     {"note", "1-based particle of aggregate and ITZ voxels, 0 = none"}}}};
  json["phases"] = {{"0", "mortar"}, {"1", "itz"}, {"2", "aggregate"}, {"3", "outside"}};
  json["itz_thickness_m"] = itz_thickness;
  json["voxels"] = {
      {"mortar", counts[0]}, {"itz", counts[1]}, {"aggregate", counts[2]}, {"outside", counts[3]}};
  json["voxel_volume_fractions"] = {{"mortar", counts[0] / inside},
                                    {"itz", counts[1] / inside},
                                    {"aggregate", counts[2] / inside}};
  json["exact"] = {
      {"container_volume_m3", packing.container.volume()},
      {"aggregate_volume_m3", aggregate_volume},
      {"aggregate_fraction", aggregate_volume / packing.container.volume()},
      {"itz_volume_m3", shell_volume},
      {"itz_fraction", shell_volume / packing.container.volume()},
      {"note",
       "ITZ: sum of the offset shells (Steiner), exact while shells neither overlap nor "
       "cross a wall"}};
  json["voxel_volume_m3"] = voxel;
  AtomicFile file(header_path, overwrite);
  file.stream() << json.dump(2) << '\n';
  commit(file);
  transaction.commit();
}

}  // namespace aggpack
