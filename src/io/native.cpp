#include "aggpack/io/native.h"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "hdf5_util.h"
#include "native_container.h"

namespace aggpack {

namespace {

using hdf5::Handle;
using hdf5::hdf5_reason;
using hdf5::SilenceHdf5Errors;

// ---- writing ----------------------------------------------------------------------------------

class Writer {
 public:
  Writer(const std::string& display_path, int compression)
      : display_path_(display_path), compression_(compression) {}

  // One line: "disk full" (and the like) from the errno that HDF5 records in its error stack,
  // else the innermost HDF5 description up to its first line break.
  [[noreturn]] void fail(const std::string& what) const {
    int error = 0;
    H5Ewalk2(
        H5E_DEFAULT, H5E_WALK_UPWARD,
        [](unsigned, const H5E_error2_t* entry, void* data) -> herr_t {
          const char* found =
              entry->desc != nullptr ? std::strstr(entry->desc, "errno = ") : nullptr;
          if (found != nullptr && *static_cast<int*>(data) == 0) {
            *static_cast<int*>(data) = std::atoi(found + 8);
          }
          return 0;
        },
        &error);
    if (error != 0) {
      H5Eclear2(H5E_DEFAULT);
      throw IoError(write_failure_wording(display_path_, error));
    }
    std::string reason = hdf5_reason();
    reason = reason.substr(0, std::min(reason.find('\n'), std::size_t{200}));
    throw IoError(Wording{Sentence::kWriteHdf5Failed, {display_path_, what, reason}});
  }

  Handle checked(hid_t id, Handle::Closer closer, const std::string& what) const {
    if (id < 0) fail(what);
    return {id, closer};
  }

  Handle create_group(hid_t parent, const char* name) const {
    Handle properties = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "group properties");
    // Timestamps would make two runs of the same input differ byte for byte.
    H5Pset_obj_track_times(properties.get(), false);
    return checked(H5Gcreate2(parent, name, H5P_DEFAULT, properties.get(), H5P_DEFAULT), H5Gclose,
                   std::string("group ") + name);
  }

  void write_attribute_string(hid_t object, const char* name, const std::string& value) const {
    Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
    H5Tset_size(type.get(), value.size() + 1);  // + 1: a fixed-length type may not be empty
    H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
    H5Tset_cset(type.get(), H5T_CSET_UTF8);
    Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "dataspace");
    Handle attribute =
        checked(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose, std::string("attribute ") + name);
    if (H5Awrite(attribute.get(), type.get(), value.c_str()) < 0) {
      fail(std::string("attribute ") + name);
    }
  }

  template <typename T>
  void write_attribute_number(hid_t object, const char* name, hid_t file_type, hid_t memory_type,
                              T value) const {
    Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "dataspace");
    Handle attribute =
        checked(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose, std::string("attribute ") + name);
    if (H5Awrite(attribute.get(), memory_type, &value) < 0) {
      fail(std::string("attribute ") + name);
    }
  }

  // rows x columns array (columns = 0 means a 1-D dataset).
  void write_dataset(hid_t parent, const char* name, hid_t file_type, hid_t memory_type,
                     std::size_t rows, std::size_t columns, const void* data) const {
    const int rank = columns == 0 ? 1 : 2;
    const hsize_t dims[2] = {rows, columns};
    Handle space = checked(H5Screate_simple(rank, dims, nullptr), H5Sclose, "dataspace");
    Handle properties = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
    H5Pset_obj_track_times(properties.get(), false);
    if (rows > 0) {
      // Chunked so that the Fletcher-32 filter can checksum the data; about 1 MiB per chunk.
      const std::size_t row_bytes = H5Tget_size(file_type) * std::max<std::size_t>(columns, 1);
      const std::size_t chunk_rows =
          std::clamp<std::size_t>((std::size_t{1} << 20) / row_bytes, 1, rows);
      const hsize_t chunk[2] = {chunk_rows, columns};
      H5Pset_chunk(properties.get(), rank, chunk);
      if (compression_ > 0) {
        H5Pset_shuffle(properties.get());
        H5Pset_deflate(properties.get(), static_cast<unsigned>(compression_));
      }
      H5Pset_fletcher32(properties.get());
    }
    Handle dataset = checked(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT,
                                        properties.get(), H5P_DEFAULT),
                             H5Dclose, std::string("dataset ") + name);
    if (rows > 0 && H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
      fail(std::string("dataset ") + name);
    }
  }

 private:
  std::string display_path_;
  int compression_;
};

void write_hdf5(const std::string& file_path, const std::string& display_path,
                const Packing& packing, const NativeWriteOptions& options) {
  const Writer writer(display_path, options.compression);
  Handle creation = writer.checked(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file properties");
  H5Pset_obj_track_times(creation.get(), false);  // the root group too
  Handle access = writer.checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file properties");
  // 1.8+ object format: checksummed superblock, object headers and chunk indexes.
  H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST);
  Handle file =
      writer.checked(H5Fcreate(file_path.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()),
                     H5Fclose, "create file");
  const hid_t root = file.get();
  writer.write_attribute_string(root, "format_name", kNativeFormatName);
  writer.write_attribute_number(root, "format_version", H5T_STD_I32LE, H5T_NATIVE_INT,
                                kNativeFormatVersion);

  {
    const Container& c = packing.container;
    Handle group = writer.create_group(root, "container");
    writer.write_attribute_string(group.get(), "kind", container_kind_info(c).name);
    const std::vector<double> values = native_detail::container_values(c);
    std::size_t field = 0;
    auto write = [&](const char* name) {
      writer.write_attribute_number(group.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                                    values[field++]);
    };
    for (const ContainerKindInfo& kind : container_kinds()) {
      for (const ContainerParam& param : kind.params) write(param.name);
    }
    write("wall_gap");
    // Only a periodic box has it: a walled container's file reads as before this attribute.
    if (is_periodic(c)) {
      writer.write_attribute_string(group.get(), "periodic", periodic_word(periodic_axes(c)));
    }
  }

  {
    std::vector<double> vertices;
    std::vector<std::uint32_t> triangles;
    std::vector<std::uint64_t> vertex_offsets{0};
    std::vector<std::uint64_t> triangle_offsets{0};
    for (const auto& shape : packing.shapes) {
      for (const auto& v : shape.vertices()) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
      for (const auto& t : shape.triangles()) triangles.insert(triangles.end(), t.begin(), t.end());
      vertex_offsets.push_back(vertex_offsets.back() + shape.vertex_count());
      triangle_offsets.push_back(triangle_offsets.back() + shape.triangle_count());
    }
    Handle group = writer.create_group(root, "shapes");
    writer.write_dataset(group.get(), "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                         vertices.size() / 3, 3, vertices.data());
    writer.write_dataset(group.get(), "triangles", H5T_STD_U32LE, H5T_NATIVE_UINT32,
                         triangles.size() / 3, 3, triangles.data());
    writer.write_dataset(group.get(), "vertex_offsets", H5T_STD_U64LE, H5T_NATIVE_UINT64,
                         vertex_offsets.size(), 0, vertex_offsets.data());
    writer.write_dataset(group.get(), "triangle_offsets", H5T_STD_U64LE, H5T_NATIVE_UINT64,
                         triangle_offsets.size(), 0, triangle_offsets.data());
  }

  {
    const std::size_t n = packing.particles.size();
    std::vector<std::uint32_t> shape(n);
    std::vector<std::uint32_t> size_class(n);
    std::vector<double> position(3 * n);
    std::vector<double> rotation(4 * n);
    std::vector<double> control_radius(n);
    std::vector<double> scale(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Particle& p = packing.particles[i];
      shape[i] = p.shape;
      size_class[i] = p.size_class;
      control_radius[i] = p.control_radius;
      scale[i] = p.scale;
      for (int axis = 0; axis < 3; ++axis) position[3 * i + axis] = p.pose.position[axis];
      rotation[4 * i + 0] = p.pose.rotation.w();
      rotation[4 * i + 1] = p.pose.rotation.x();
      rotation[4 * i + 2] = p.pose.rotation.y();
      rotation[4 * i + 3] = p.pose.rotation.z();
    }
    Handle group = writer.create_group(root, "particles");
    writer.write_dataset(group.get(), "shape", H5T_STD_U32LE, H5T_NATIVE_UINT32, n, 0,
                         shape.data());
    writer.write_dataset(group.get(), "position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 3,
                         position.data());
    writer.write_dataset(group.get(), "rotation", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 4,
                         rotation.data());
    writer.write_dataset(group.get(), "scale", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 0,
                         scale.data());
    writer.write_dataset(group.get(), "control_radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 0,
                         control_radius.data());
    writer.write_dataset(group.get(), "size_class", H5T_STD_U32LE, H5T_NATIVE_UINT32, n, 0,
                         size_class.data());
  }

  {
    const Provenance& p = packing.provenance;
    Handle group = writer.create_group(root, "provenance");
    writer.write_attribute_string(group.get(), "aggpack_version", p.aggpack_version);
    writer.write_attribute_string(group.get(), "config_toml", p.config_toml);
    writer.write_attribute_string(group.get(), "packer", p.packer);
    writer.write_attribute_number(group.get(), "seed", H5T_STD_U64LE, H5T_NATIVE_UINT64, p.seed);
    // Only for a packing of library shapes: earlier readers never see it, files stay the same.
    if (!p.shape_library.empty()) {
      writer.write_attribute_string(group.get(), "shape_library", p.shape_library);
    }
  }

  if (options.write_xdmf) {
    std::vector<double> vertices;
    std::vector<std::int64_t> triangles;
    std::vector<std::int32_t> particle_of_triangle;
    for (std::size_t i = 0; i < packing.particles.size(); ++i) {
      const auto base = static_cast<std::int64_t>(vertices.size() / 3);
      const ConvexPolyhedron body = packing.placed(i);
      for (const auto& v : body.vertices()) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
      for (const auto& t : body.triangles()) {
        triangles.insert(triangles.end(), {base + t[0], base + t[1], base + t[2]});
        // 1-based, as every export names particles (P1..PN).
        particle_of_triangle.push_back(static_cast<std::int32_t>(i + 1));
      }
    }
    Handle group = writer.create_group(root, "world");
    writer.write_dataset(group.get(), "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                         vertices.size() / 3, 3, vertices.data());
    writer.write_dataset(group.get(), "triangles", H5T_STD_I64LE, H5T_NATIVE_INT64,
                         triangles.size() / 3, 3, triangles.data());
    writer.write_dataset(group.get(), "particle", H5T_STD_I32LE, H5T_NATIVE_INT32,
                         particle_of_triangle.size(), 0, particle_of_triangle.data());
  }

  if (!file.close()) writer.fail("flush and close");
}

std::string xdmf_text(const std::string& h5_name, const Packing& packing) {
  std::size_t vertex_count = 0;
  std::size_t triangle_count = 0;
  for (const auto& p : packing.particles) {
    vertex_count += packing.shapes[p.shape].vertex_count();
    triangle_count += packing.shapes[p.shape].triangle_count();
  }
  const std::string v = std::to_string(vertex_count);
  const std::string t = std::to_string(triangle_count);
  return "<?xml version=\"1.0\" ?>\n"
         "<!-- aggpack: every particle's surface in world coordinates (m); cell attribute "
         "particle = 1-based particle number (P1..PN) -->\n"
         "<Xdmf Version=\"3.0\">\n"
         "  <Domain>\n"
         "    <Grid Name=\"particles\" GridType=\"Uniform\">\n"
         "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"" +
         t +
         "\">\n"
         "        <DataItem Dimensions=\"" +
         t +
         " 3\" NumberType=\"Int\" Precision=\"8\" "
         "Format=\"HDF\">" +
         h5_name +
         ":/world/triangles</DataItem>\n"
         "      </Topology>\n"
         "      <Geometry GeometryType=\"XYZ\">\n"
         "        <DataItem Dimensions=\"" +
         v +
         " 3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">" +
         h5_name +
         ":/world/vertices</DataItem>\n"
         "      </Geometry>\n"
         "      <Attribute Name=\"particle\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
         "        <DataItem Dimensions=\"" +
         t +
         "\" NumberType=\"Int\" Precision=\"4\" "
         "Format=\"HDF\">" +
         h5_name +
         ":/world/particle</DataItem>\n"
         "      </Attribute>\n"
         "    </Grid>\n"
         "  </Domain>\n"
         "</Xdmf>\n";
}

}  // namespace

std::string xdmf_path_for(const std::string& path) {
  return std::filesystem::path(path).replace_extension(".xdmf").string();
}

void write_packing(const Packing& packing, const std::string& path,
                   const NativeWriteOptions& options) {
  require_in_range("native compression", options.compression, 0, 9);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    if (packing.particles[i].shape >= packing.shapes.size()) {
      throw InvalidInput("particles[" + std::to_string(i) + "].shape",
                         std::to_string(packing.particles[i].shape),
                         "[0, " + std::to_string(packing.shapes.size()) + ")");
    }
  }
  const std::string side_path = xdmf_path_for(path);
  if (options.write_xdmf) check_writable(side_path, options.overwrite);

  AtomicFile file(path, options.overwrite);
  file.stream().close();  // HDF5 opens the temporary file by name
  {
    const SilenceHdf5Errors silence;
    write_hdf5(file.temporary_path(), path, packing, options);
  }
  if (options.write_xdmf) {
    AtomicFile side(side_path, options.overwrite, std::ios::out);
    side.stream() << xdmf_text(std::filesystem::path(path).filename().string(), packing);
    file.commit();
    side.commit();
  } else {
    file.commit();
  }
}

}  // namespace aggpack
