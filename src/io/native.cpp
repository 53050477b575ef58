#include "aggpack/io/native.h"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// ---- HDF5 plumbing ----------------------------------------------------------------------------

// HDF5 prints its whole error stack to stderr by default; a corrupt file must instead become one
// FormatError. The previous handler is restored so that we do not change global state for others.
class SilenceHdf5Errors {
 public:
  SilenceHdf5Errors() {
    // HDF5 1.10 leaks free-list blocks on some corrupt-metadata error paths and then prints
    // "HDF5: infinite loop closing library" from its atexit handler, after our one-line error.
    // Skipping that handler is harmless: every file we open is closed before we return, and the
    // process's memory goes back to the OS at exit. Must run before the library initialises.
    static const bool is_atexit_skipped = [] { return H5dont_atexit() >= 0; }();
    (void)is_atexit_skipped;
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  SilenceHdf5Errors(const SilenceHdf5Errors&) = delete;
  SilenceHdf5Errors& operator=(const SilenceHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// The innermost HDF5 error description (e.g. "truncated file: eof = ..."), which says more than
// the outer "unable to open file".
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        auto* text = static_cast<std::string*>(data);
        if (text->empty() && error->desc != nullptr) *text = error->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "HDF5 error" : reason;
}

// Owns one hid_t and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.id_;
      closer_ = other.closer_;
      other.id_ = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool is_valid() const { return id_ >= 0; }
  /// Closes now and reports whether closing succeeded (H5Fclose flushes, so it can fail).
  bool close() {
    const herr_t status = id_ >= 0 ? closer_(id_) : 0;
    id_ = -1;
    return status >= 0;
  }

 private:
  void reset() {
    if (id_ >= 0) closer_(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// ---- writing ----------------------------------------------------------------------------------

class Writer {
 public:
  Writer(const std::string& display_path, int compression)
      : display_path_(display_path), compression_(compression) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw IoError("cannot write " + display_path_ + ": " + what + " (" + hdf5_reason() + ")");
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

const char* container_kind_name(ContainerKind kind) {
  return kind == ContainerKind::kCylinder ? "cylinder" : "box";
}

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
    writer.write_attribute_string(group.get(), "kind", container_kind_name(c.kind));
    const std::pair<const char*, double> lengths[] = {
        {"length", c.length}, {"width", c.width},   {"depth", c.depth},
        {"radius", c.radius}, {"height", c.height}, {"wall_gap", c.wall_gap}};
    for (const auto& [name, value] : lengths) {
      writer.write_attribute_number(group.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value);
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

// ---- reading ----------------------------------------------------------------------------------

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& what) const { throw FormatError(path_ + ": " + what); }
  [[noreturn]] void fail_hdf5(const std::string& what) const {
    fail(what + " (" + hdf5_reason() + "; the file is truncated or corrupted)");
  }

  // H5Lexists / H5Aexists: < 0 means the lookup itself failed (corrupt metadata), 0 absent.
  bool exists(htri_t status, const std::string& what) const {
    if (status < 0) fail_hdf5("cannot look up " + what);
    return status > 0;
  }

  Handle open_group(hid_t parent, const char* name) const {
    if (!exists(H5Lexists(parent, name, H5P_DEFAULT), std::string("group /") + name)) {
      fail(std::string("missing group /") + name);
    }
    const hid_t id = H5Gopen2(parent, name, H5P_DEFAULT);
    if (id < 0) fail_hdf5(std::string("cannot open group /") + name);
    return {id, H5Gclose};
  }

  Handle open_attribute(hid_t object, const char* name) const {
    if (!exists(H5Aexists(object, name), std::string("attribute ") + name)) {
      fail(std::string("missing attribute ") + name);
    }
    const hid_t id = H5Aopen(object, name, H5P_DEFAULT);
    if (id < 0) fail_hdf5(std::string("cannot open attribute ") + name);
    return {id, H5Aclose};
  }

  std::string read_attribute_string(hid_t object, const char* name) const {
    Handle attribute = open_attribute(object, name);
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    if (!type.is_valid() || H5Tget_class(type.get()) != H5T_STRING) {
      fail(std::string("attribute ") + name + " is not a string");
    }
    Handle space(H5Aget_space(attribute.get()), H5Sclose);
    if (!space.is_valid() || H5Sget_simple_extent_type(space.get()) != H5S_SCALAR) {
      fail(std::string("attribute ") + name + " is not a scalar");
    }
    if (H5Tis_variable_str(type.get()) > 0) {
      // Written e.g. by h5py; accept it although aggpack writes fixed-length strings.
      Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory_type.get(), H5T_VARIABLE);
      char* text = nullptr;
      if (H5Aread(attribute.get(), memory_type.get(), &text) < 0) {
        fail_hdf5(std::string("cannot read attribute ") + name);
      }
      std::string value = text == nullptr ? "" : text;
      H5free_memory(text);
      return value;
    }
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > (std::size_t{1} << 30)) {
      fail(std::string("attribute ") + name + " has an implausible size");
    }
    std::vector<char> buffer(size + 1, '\0');
    if (H5Aread(attribute.get(), type.get(), buffer.data()) < 0) {
      fail_hdf5(std::string("cannot read attribute ") + name);
    }
    return {buffer.data(), ::strnlen(buffer.data(), size)};
  }

  template <typename T>
  T read_attribute_number(hid_t object, const char* name, hid_t memory_type) const {
    Handle attribute = open_attribute(object, name);
    Handle space(H5Aget_space(attribute.get()), H5Sclose);
    if (!space.is_valid() || H5Sget_simple_extent_npoints(space.get()) != 1) {
      fail(std::string("attribute ") + name + " is not a single number");
    }
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    const H5T_class_t type_class = type.is_valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (type_class != H5T_INTEGER && type_class != H5T_FLOAT) {
      fail(std::string("attribute ") + name + " is not a number");
    }
    T value{};
    if (H5Aread(attribute.get(), memory_type, &value) < 0) {
      fail_hdf5(std::string("cannot read attribute ") + name);
    }
    return value;
  }

  double read_finite(hid_t object, const char* name) const {
    const auto value = read_attribute_number<double>(object, name, H5T_NATIVE_DOUBLE);
    if (!std::isfinite(value)) fail(std::string("attribute ") + name + " is not finite");
    return value;
  }

  // Reads a dataset of `columns` columns (0 = 1-D) and numeric class `type_class` into `out`.
  template <typename T>
  void read_dataset(hid_t parent, const char* group_name, const char* name, hid_t memory_type,
                    H5T_class_t type_class, std::size_t columns, std::vector<T>& out,
                    std::size_t& rows) const {
    const std::string full_name = std::string("/") + group_name + "/" + name;
    if (!exists(H5Lexists(parent, name, H5P_DEFAULT), "dataset " + full_name)) {
      fail("missing dataset " + full_name);
    }
    Handle dataset(H5Dopen2(parent, name, H5P_DEFAULT), H5Dclose);
    if (!dataset.is_valid()) fail_hdf5("cannot open dataset " + full_name);
    Handle type(H5Dget_type(dataset.get()), H5Tclose);
    if (!type.is_valid() || H5Tget_class(type.get()) != type_class) {
      fail("dataset " + full_name + " has the wrong element type");
    }
    Handle space(H5Dget_space(dataset.get()), H5Sclose);
    const int rank = space.is_valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    const int expected_rank = columns == 0 ? 1 : 2;
    if (rank != expected_rank) {
      fail("dataset " + full_name + " has rank " + std::to_string(rank) + ", expected " +
           std::to_string(expected_rank));
    }
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    if (columns != 0 && dims[1] != columns) {
      fail("dataset " + full_name + " has " + std::to_string(dims[1]) + " columns, expected " +
           std::to_string(columns));
    }
    // A corrupted dimension must not turn into a huge allocation.
    constexpr hsize_t kMaxElements = hsize_t{1} << 36;
    const hsize_t elements = dims[0] * std::max<hsize_t>(columns, 1);
    if (dims[0] > kMaxElements || elements > kMaxElements) {
      fail("dataset " + full_name + " claims an implausible size");
    }
    rows = dims[0];
    try {
      out.assign(elements, T{});
    } catch (const std::bad_alloc&) {
      fail("dataset " + full_name + " is too large to load");
    }
    if (elements > 0 &&
        H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
      fail_hdf5("cannot read dataset " + full_name);
    }
  }

 private:
  std::string path_;
};

// The HDF5 signature sits at offset 0 or, after a user block, at 512, 1024, 2048, ... We check it
// ourselves because H5Fis_hdf5 can leave a half-opened file behind in the library on bad input.
bool has_hdf5_signature(const std::string& path) {
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  for (std::uint64_t offset = 0; offset + 8 <= size; offset = offset == 0 ? 512 : 2 * offset) {
    char bytes[8] = {};
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(bytes, 8)) return false;
    if (std::memcmp(bytes, kSignature, 8) == 0) return true;
  }
  return false;
}

Packing read_hdf5(const std::string& path) {
  const Reader reader(path);
  if (!has_hdf5_signature(path)) {
    throw FormatError(path + ": not an HDF5 file (expected an aggpack packing, format " +
                      kNativeFormatName + ")");
  }
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // Strong close: closing the file closes every object still open in it, so a read that failed
  // half-way cannot leave the file open inside the library (HDF5 would then hand the stale, cached
  // file to the next open of the same path).
  H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose);
  if (!file.is_valid()) reader.fail_hdf5("cannot open as HDF5");
  const hid_t root = file.get();

  if (!reader.exists(H5Aexists(root, "format_name"), "attribute format_name")) {
    reader.fail(std::string("not an aggpack packing (no format_name attribute; expected ") +
                kNativeFormatName + ")");
  }
  const std::string format_name = reader.read_attribute_string(root, "format_name");
  if (format_name != kNativeFormatName) {
    reader.fail("not an aggpack packing (format_name is '" + format_name + "', expected '" +
                kNativeFormatName + "')");
  }
  const auto version = reader.read_attribute_number<int>(root, "format_version", H5T_NATIVE_INT);
  if (version != kNativeFormatVersion) {
    reader.fail("format version " + std::to_string(version) + " is not supported (this aggpack " +
                AGGPACK_VERSION + " reads version " + std::to_string(kNativeFormatVersion) + ")");
  }

  Packing packing;
  {
    Handle group = reader.open_group(root, "container");
    Container& c = packing.container;
    const std::string kind = reader.read_attribute_string(group.get(), "kind");
    if (kind == "box") {
      c.kind = ContainerKind::kBox;
    } else if (kind == "cylinder") {
      c.kind = ContainerKind::kCylinder;
    } else {
      reader.fail("unknown container kind '" + kind + "' (expected box or cylinder)");
    }
    c.length = reader.read_finite(group.get(), "length");
    c.width = reader.read_finite(group.get(), "width");
    c.depth = reader.read_finite(group.get(), "depth");
    c.radius = reader.read_finite(group.get(), "radius");
    c.height = reader.read_finite(group.get(), "height");
    c.wall_gap = reader.read_finite(group.get(), "wall_gap");
    if (c.length < 0 || c.width < 0 || c.depth < 0 || c.radius < 0 || c.height < 0 ||
        c.wall_gap < 0) {
      reader.fail("container has a negative length");
    }
  }

  {
    Handle group = reader.open_group(root, "shapes");
    std::vector<double> vertices;
    std::vector<std::uint32_t> triangles;
    std::vector<std::uint64_t> vertex_offsets;
    std::vector<std::uint64_t> triangle_offsets;
    std::size_t vertex_rows = 0;
    std::size_t triangle_rows = 0;
    std::size_t shape_rows = 0;
    std::size_t triangle_shape_rows = 0;
    reader.read_dataset(group.get(), "shapes", "vertices", H5T_NATIVE_DOUBLE, H5T_FLOAT, 3,
                        vertices, vertex_rows);
    reader.read_dataset(group.get(), "shapes", "triangles", H5T_NATIVE_UINT32, H5T_INTEGER, 3,
                        triangles, triangle_rows);
    reader.read_dataset(group.get(), "shapes", "vertex_offsets", H5T_NATIVE_UINT64, H5T_INTEGER, 0,
                        vertex_offsets, shape_rows);
    reader.read_dataset(group.get(), "shapes", "triangle_offsets", H5T_NATIVE_UINT64, H5T_INTEGER,
                        0, triangle_offsets, triangle_shape_rows);
    if (shape_rows == 0 || triangle_shape_rows != shape_rows) {
      reader.fail("shape offset tables are empty or of different lengths");
    }
    if (vertex_offsets.front() != 0 || triangle_offsets.front() != 0 ||
        vertex_offsets.back() != vertex_rows || triangle_offsets.back() != triangle_rows) {
      reader.fail("shape offsets do not cover the vertex and triangle arrays");
    }
    for (double value : vertices) {
      if (!std::isfinite(value)) reader.fail("a shape vertex is not finite");
    }
    const std::size_t shape_count = shape_rows - 1;
    packing.shapes.reserve(shape_count);
    for (std::size_t s = 0; s < shape_count; ++s) {
      const std::uint64_t v0 = vertex_offsets[s];
      const std::uint64_t v1 = vertex_offsets[s + 1];
      const std::uint64_t t0 = triangle_offsets[s];
      const std::uint64_t t1 = triangle_offsets[s + 1];
      if (v1 < v0 || t1 < t0 || v1 > vertex_rows || t1 > triangle_rows) {
        reader.fail("shape " + std::to_string(s) + " has decreasing offsets");
      }
      std::vector<Vec3> shape_vertices;
      shape_vertices.reserve(v1 - v0);
      for (std::uint64_t v = v0; v < v1; ++v) {
        shape_vertices.emplace_back(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
      }
      std::vector<Triangle> shape_triangles;
      shape_triangles.reserve(t1 - t0);
      for (std::uint64_t t = t0; t < t1; ++t) {
        shape_triangles.push_back({triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]});
      }
      try {
        packing.shapes.emplace_back(std::move(shape_vertices), std::move(shape_triangles));
      } catch (const InvalidInput& error) {
        reader.fail("shape " + std::to_string(s) + " is not a valid polyhedron: " + error.what());
      }
    }
  }

  {
    Handle group = reader.open_group(root, "particles");
    std::vector<std::uint32_t> shape;
    std::vector<std::uint32_t> size_class;
    std::vector<double> position;
    std::vector<double> rotation;
    std::vector<double> control_radius;
    std::vector<double> scale;
    std::size_t rows[6] = {};
    reader.read_dataset(group.get(), "particles", "shape", H5T_NATIVE_UINT32, H5T_INTEGER, 0, shape,
                        rows[0]);
    reader.read_dataset(group.get(), "particles", "position", H5T_NATIVE_DOUBLE, H5T_FLOAT, 3,
                        position, rows[1]);
    reader.read_dataset(group.get(), "particles", "rotation", H5T_NATIVE_DOUBLE, H5T_FLOAT, 4,
                        rotation, rows[2]);
    reader.read_dataset(group.get(), "particles", "control_radius", H5T_NATIVE_DOUBLE, H5T_FLOAT, 0,
                        control_radius, rows[3]);
    reader.read_dataset(group.get(), "particles", "size_class", H5T_NATIVE_UINT32, H5T_INTEGER, 0,
                        size_class, rows[4]);
    reader.read_dataset(group.get(), "particles", "scale", H5T_NATIVE_DOUBLE, H5T_FLOAT, 0, scale,
                        rows[5]);
    const std::size_t n = rows[0];
    if (!std::all_of(std::begin(rows), std::end(rows), [n](std::size_t r) { return r == n; })) {
      reader.fail("particle datasets have different lengths");
    }
    packing.particles.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Particle& p = packing.particles[i];
      if (shape[i] >= packing.shapes.size()) {
        reader.fail("particle " + std::to_string(i) + " refers to shape " +
                    std::to_string(shape[i]) + " of " + std::to_string(packing.shapes.size()));
      }
      p.shape = shape[i];
      p.size_class = size_class[i];
      p.control_radius = control_radius[i];
      p.scale = scale[i];
      p.pose.position = Vec3(position[3 * i], position[3 * i + 1], position[3 * i + 2]);
      p.pose.rotation =
          Quat(rotation[4 * i], rotation[4 * i + 1], rotation[4 * i + 2], rotation[4 * i + 3]);
      if (!p.pose.position.allFinite() || !p.pose.rotation.coeffs().allFinite() ||
          !std::isfinite(p.control_radius) || p.control_radius < 0 || !std::isfinite(p.scale) ||
          p.scale <= 0) {
        reader.fail("particle " + std::to_string(i) +
                    " has a non-finite or negative position, rotation, radius or scale");
      }
      // Written from unit quaternions; anything far from unit length is corruption.
      if (std::abs(p.pose.rotation.squaredNorm() - 1.0) > 1e-6) {
        reader.fail("particle " + std::to_string(i) +
                    " has a rotation that is not a unit "
                    "quaternion");
      }
    }
  }

  {
    Handle group = reader.open_group(root, "provenance");
    Provenance& p = packing.provenance;
    p.aggpack_version = reader.read_attribute_string(group.get(), "aggpack_version");
    p.config_toml = reader.read_attribute_string(group.get(), "config_toml");
    p.packer = reader.read_attribute_string(group.get(), "packer");
    p.seed = reader.read_attribute_number<std::uint64_t>(group.get(), "seed", H5T_NATIVE_UINT64);
  }
  return packing;
}

}  // namespace

std::string xdmf_path_for(const std::string& path) {
  return std::filesystem::path(path).replace_extension(".xdmf").string();
}

void write_packing(const std::string& path, const Packing& packing,
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

Packing read_packing(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw IoError("cannot read " + path + ": no such file");
  if (std::filesystem::is_directory(path, error)) {
    throw IoError("cannot read " + path + ": it is a folder");
  }
  if (!std::ifstream(path, std::ios::binary)) {
    throw IoError("cannot read " + path + ": permission denied");
  }
  const SilenceHdf5Errors silence;
  return read_hdf5(path);
}

}  // namespace aggpack
