// The bad native files of issue 12 (tests/io/fixtures/bad-inputs/, README.md there), end to end:
// `info` and `export` (STL, VTU) each give exit 2 and one error line naming the file, the field and
// the reason, and leave no output or temporary file. The files h5py writes with its default UTF-8
// variable-length strings are read; an empty packing and an unreadable stored config give a clear
// answer.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/io/native.h"
#include "support/files.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

class NativeBadInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    base_ = fs::temp_directory_path() /
            (std::string("aggpack_bad_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_ / "work");
  }
  void TearDown() override { fs::remove_all(base_); }

  // Runs the CLI inside base_/work; stdout and stderr go beside it, so the folder shows exactly
  // what the command left.
  CliRun run(const std::string& arguments) const {
    const std::string command = "cd '" + (base_ / "work").string() + "' && '" +
                                test::aggpack_binary() + "' " + arguments +
                                " >../stdout.txt 2>../stderr.txt";
    const int status = std::system(command.c_str());
    CliRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = test::file_text(base_ / "stdout.txt");
    result.err = test::file_text(base_ / "stderr.txt");
    return result;
  }

  [[nodiscard]] std::vector<std::string> left_behind() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(base_ / "work")) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

  fs::path base_;
};

struct BadFile {
  const char* name;
  const char* field;   // the dataset or attribute the message must name
  const char* reason;  // part of the reason
};

// What each reproducer must say (the path is checked too).
const BadFile kBadFiles[] = {
    {"alloc_bomb_vertices_2e26rows.h5",
     ": /shapes/vertices: ", "declares 67108864 x 3 float64 values in a 17404-byte file"},
    {"alloc_bomb_fuzz_sem535.h5", ": /particles/position: ", "declares 33554432 x 3 float64"},
    {"settle_hang_scale_1e-200.h5", ": /particles/scale[0] = 1e-200: ", "outside [1e-09, 1000000]"},
    {"stl_accepts_collapsed_shape.h5",
     ": /shapes/vertices (shape 0, rows 0-23): ", "extent is 0 m, below 1e-09 m (collapsed)"},
    {"inverted_shape_mirror.h5", ": /shapes/triangles (shape 0, rows 0-43): volume -",
     "not positive: the triangles turn clockwise seen from outside (inside out"},
    {"stl_inf_coordinates_vertex_1e150.h5", ": /shapes/vertices (shape 0, rows 0-23): ",
     "vertex 0 has a coordinate of magnitude 7.79900365e+148, outside [-1000000, 1000000] m"},
    {"flipped_one_triangle.h5", ": /shapes/triangles (shape 0, rows 0-43): ",
     "runs the same way in triangles 0 and 32: not consistently oriented (a flipped triangle)"},
    {"nonmanifold_triangle.h5", ": /shapes/triangles (shape 0, rows 0-43): ",
     "triangle 0 repeats a vertex (7, 7, 18): degenerate"},
    {"scale_1e200.h5", ": /particles/scale[0] = 1e+200: ", "outside [1e-09, 1000000]"},
    {"scale_1e-300_all.h5", ": /particles/scale[0] = 1e-300: ", "outside [1e-09, 1000000]"},
    {"info_inf_width_5e-324.h5",
     ": /container/width = 4.940656458e-324: ", "outside [1e-09, 1000000] m (a box needs it > 0)"},
    {"position_1e300.h5",
     ": /particles/position[0] = (1e+300, -1e+300, 1e+300): ", "outside [-1000000, 1000000] m"},
    {"container_width_zero.h5",
     ": /container/width = 0: ", "outside [1e-09, 1000000] m (a box needs it > 0)"},
    {"format_version_float_1.9.h5",
     ": /format_version: ", "stored as float64 (1.9), expected an integer"},
    {"shape_id_int64_minus1.h5", ": /particles/shape: ", "stored as int64, expected uint32"},
    // Found on 2026-12-03: refused by info and densify only, or by nothing.
    {"wall_gap_over_half.h5", ": /container/wall_gap = 0.24: ",
     "not below half the smallest container extent; allowed: [0, 0.2) m"},
    {"format_name_embedded_nul.h5", ": /format_name: ",
     "contains a NUL byte at position 15 followed by more text; allowed: text without NUL bytes"},
    // A stored shape the polyhedron itself refuses (its own reason quoted, worded in the window).
    {"triangle_index_outside_shape.h5", ": /shapes/triangles (shape 0, rows 0-43): ",
     "not a polyhedron: invalid polyhedron.triangles = vertex index 1000000 (allowed: < 24)"},
};

// The fixtures that are valid packings (checked by the tests below).
const std::vector<std::string> kValidFiles = {"base_s.h5",           "vlen_ascii.h5",
                                              "vlen_format_name.h5", "vlen_utf8_config_toml.h5",
                                              "zero_particles.h5",   "unparsable_config_toml.h5"};

void expect_one_line_error(const CliRun& run, const BadFile& bad, const std::string& command) {
  SCOPED_TRACE(std::string(bad.name) + " with " + command);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  ASSERT_FALSE(run.err.empty());
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // exactly one line
  EXPECT_LT(run.err.size(), 400U) << run.err;
  EXPECT_EQ(run.err.rfind("aggpack: error: " + test::bad_inputs_dir() + bad.name + bad.field, 0),
            0U)
      << run.err;
  EXPECT_NE(run.err.find(bad.reason), std::string::npos) << run.err;
}

// Every .h5 of the fixture folder is either a bad file above or a valid one: a new fixture
// without an expectation fails here.
TEST_F(NativeBadInputTest, EveryFixtureIsChecked) {
  std::size_t bad_count = 0;
  for (const auto& entry : fs::directory_iterator(test::bad_inputs_dir())) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".h5") continue;
    const bool is_bad = std::any_of(std::begin(kBadFiles), std::end(kBadFiles),
                                    [&](const BadFile& bad) { return name == bad.name; });
    const bool is_valid =
        std::find(kValidFiles.begin(), kValidFiles.end(), name) != kValidFiles.end();
    EXPECT_TRUE(is_bad || is_valid) << name << " has no expectation";
    bad_count += is_bad ? 1 : 0;
  }
  EXPECT_EQ(bad_count, std::size(kBadFiles));
}

// Every command that opens a native file refuses every bad file before using it, with the one
// message of read_packing: exit 2, one line, nothing written.
TEST_F(NativeBadInputTest, EveryEntryPointRefusesEveryBadFile) {
  const std::string help = run("--help").out;
  const bool has_sim = help.find("\n  settle ") != std::string::npos;
  const bool has_render = help.find("\n  render ") != std::string::npos;
  std::vector<std::pair<std::string, std::string>> commands = {
      {"info", ""},
      {"export", " --format stl -o out.stl"},
      {"export", " --format vtu -o out.vtu"},
      {"export", " --format inp -o out.inp"},
      {"export", " --deck calculix -o deck.inp"},
      {"densify", " -o dense.h5 --sweeps 10"},
      {"mesomodel", " -o meso.inp"},
      {"mesomodel", " -o phases.vti --voxels 8"},
  };
  // The sanitized build leaves out the simulation and drawing modules (no Bullet, no OpenGL).
  if (has_render) {
    commands.emplace_back("render", " -o view.png --size 64x64");
    commands.emplace_back("render", " --mesomodel-cut z=0.1 -o cut.png");
  }
  if (has_sim) commands.emplace_back("settle", " -o settled.h5 --max-time 0.02");
  for (const BadFile& bad : kBadFiles) {
    const std::string input = "'" + test::bad_inputs_dir() + bad.name + "'";
    for (const auto& [command, options] : commands) {
      expect_one_line_error(run(command + " " + input + options), bad, command + options);
    }
    EXPECT_EQ(left_behind(), std::vector<std::string>{}) << bad.name;
  }
}

// The settle hang of the issue: the file is now rejected before the simulation starts.
TEST_F(NativeBadInputTest, SettleRejectsTheTinyScaleFile) {
  // The sanitized build leaves out the simulation module (no Bullet): no settle subcommand.
  if (run("--help").out.find("\n  settle ") == std::string::npos) {
    GTEST_SKIP() << "aggpack built without the simulation module";
  }
  const BadFile& bad = kBadFiles[2];
  ASSERT_EQ(std::string(bad.name), "settle_hang_scale_1e-200.h5");
  expect_one_line_error(
      run("settle '" + test::bad_inputs_dir() + bad.name + "' -o dense.h5 --max-time 0.02"), bad,
      "settle");
  EXPECT_EQ(left_behind(), std::vector<std::string>{});
}

// The library gives the same message (without the CLI prefix) as a FormatError.
TEST_F(NativeBadInputTest, ReadPackingThrowsTheSameMessage) {
  for (const BadFile& bad : kBadFiles) {
    try {
      read_packing(test::bad_inputs_dir() + bad.name);
      ADD_FAILURE() << bad.name << " was accepted";
    } catch (const FormatError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(test::bad_inputs_dir() + bad.name + bad.field, 0), 0U) << message;
      EXPECT_NE(message.find(bad.reason), std::string::npos) << message;
    }
  }
}

// h5py's default str attributes (variable-length UTF-8) and variable-length ASCII are read.
TEST_F(NativeBadInputTest, VariableLengthStringsAreRead) {
  const Packing base = read_packing(test::bad_inputs_dir() + "base_s.h5");
  for (const char* name : {"vlen_utf8_config_toml.h5", "vlen_format_name.h5", "vlen_ascii.h5"}) {
    SCOPED_TRACE(name);
    const Packing packing = read_packing(test::bad_inputs_dir() + name);
    EXPECT_EQ(packing.particles.size(), base.particles.size());
    EXPECT_EQ(packing.provenance.config_toml, base.provenance.config_toml);
    const CliRun info = run("info '" + test::bad_inputs_dir() + name + "'");
    EXPECT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("particles        12"), std::string::npos) << info.out;
    EXPECT_EQ(info.out.find("stored configuration not readable"), std::string::npos);
    const CliRun stl =
        run("export '" + test::bad_inputs_dir() + name + "' --format stl -o out.stl");
    EXPECT_EQ(stl.exit_code, 0) << stl.err;
    EXPECT_TRUE(fs::is_regular_file(base_ / "work" / "out.stl"));
    fs::remove(base_ / "work" / "out.stl");
  }
}

// No particles is a valid, empty packing: `info` reports 0 (documented in docs/formats.md).
TEST_F(NativeBadInputTest, ZeroParticlesIsAnEmptyPacking) {
  const CliRun info = run("info '" + test::bad_inputs_dir() + "zero_particles.h5'");
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(info.err, "");
  EXPECT_NE(info.out.find("particles        0 "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("solid fraction   0.0000"), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find("nan"), std::string::npos) << info.out;
}

// A stored config that is not TOML is provenance only: `info` still reports, with one note line
// naming the attribute and the parse error.
TEST_F(NativeBadInputTest, UnreadableStoredConfigIsOneNoteLine) {
  const CliRun info = run("info '" + test::bad_inputs_dir() + "unparsable_config_toml.h5'");
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("note            stored configuration not readable "
                          "(/provenance/config_toml:2:8: TOML syntax error"),
            std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("); no target grading\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("particles        12"), std::string::npos) << info.out;
}

// Fuzzing finds (tests/fuzz/crashes/): a variable-length string whose HDF5 global heap is corrupt
// made HDF5 itself spin forever or copy terabytes (SIGSEGV). The string is read in a child
// process now, so each is one line, exit 2, within the read's time limit.
TEST_F(NativeBadInputTest, CorruptGlobalHeapIsOneLineNotACrashOrHang) {
  const std::string crashes = test::source_dir() + "/tests/fuzz/crashes/";
  for (const char* name :
       {"native_reader-crash-vlen-global-heap-memcpy.h5", "native_reader-hang-vlen-global-heap.h5",
        "native_reader-hang-vlen-utf8-config.h5"}) {
    SCOPED_TRACE(name);
    const CliRun info = run("info '" + crashes + name + "'");
    EXPECT_EQ(info.exit_code, 2) << info.err;
    EXPECT_EQ(info.out, "");
    EXPECT_EQ(info.err.find('\n'), info.err.size() - 1) << info.err;
    EXPECT_EQ(info.err.rfind("aggpack: error: " + crashes + name + ": /", 0), 0U) << info.err;
    EXPECT_NE(info.err.find("cannot read the variable-length string"), std::string::npos)
        << info.err;
    EXPECT_EQ(left_behind(), std::vector<std::string>{});
  }
}

}  // namespace
}  // namespace aggpack

namespace aggpack {
namespace {

// Edits of base_s.h5 made with h5py (Debian python3-h5py, a test dependency; checksums valid).
class NativeH5pyEditTest : public NativeBadInputTest {
 protected:
  // Copies base_s.h5 to `name` in the test folder and runs `edit` on it (h5py file object `f`).
  std::string edited(const std::string& name, const std::string& edit) const {
    const fs::path path = base_ / name;
    fs::copy_file(test::bad_inputs_dir() + "base_s.h5", path);
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    const std::string script = "import h5py, numpy as np\nf = h5py.File('" + path.string() +
                               "', 'r+')\n" + edit + "\nf.close()\n";
    std::ofstream(base_ / "edit.py") << script;
    const std::string command = "/usr/bin/python3 '" + (base_ / "edit.py").string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << "h5py edit failed: " << edit;
    return path.string();
  }

  static std::string message_of(const std::string& path) {
    try {
      read_packing(path);
    } catch (const FormatError& error) {
      return error.what();
    }
    return "";
  }
};

// A compressed dataset may declare more than the file holds, but at most 1032 times what it
// stores (deflate's limit); a forged extent with one chunk stored is rejected before allocating.
TEST_F(NativeH5pyEditTest, CompressedDatasetsAreBoundedByTheDeflateRatio) {
  const std::string bomb =
      edited("bomb.h5",
             "v = f['shapes/vertices'][...]; del f['shapes/vertices']\n"
             "d = f['shapes'].create_dataset('vertices', shape=(2**24, 3), dtype='<f8', "
             "chunks=(65536, 3), compression='gzip', fletcher32=True)\n"
             "d[:v.shape[0]] = v");
  const std::string message = message_of(bomb);
  EXPECT_EQ(message.rfind(bomb + ": /shapes/vertices: declares 16777216 x 3 float64 values "
                                 "(402653184 bytes) but ",
                          0),
            0U)
      << message;
  EXPECT_NE(message.find(" bytes are stored compressed in a "), std::string::npos) << message;
  // The same data compressed in full is read.
  const std::string fine =
      edited("fine.h5",
             "v = f['shapes/vertices'][...]; del f['shapes/vertices']\n"
             "f['shapes'].create_dataset('vertices', data=v, chunks=True, compression='gzip', "
             "compression_opts=9)");
  EXPECT_EQ(message_of(fine), "");
  EXPECT_EQ(read_packing(fine).shapes.size(), 12U);
}

TEST_F(NativeH5pyEditTest, ElementTypesAreExact) {
  const std::pair<const char*, const char*> cases[] = {
      {"s = f['particles/shape'][...].astype('u2'); "
       "del f['particles/shape']; f['particles'].create_dataset('shape', data=s)",
       "/particles/shape: stored as uint16, expected uint32"},
      {"s = f['particles/scale'][...].astype('f4'); del f['particles/scale']; "
       "f['particles'].create_dataset('scale', data=s)",
       "/particles/scale: stored as float32, expected float64"},
      {"del f['container'].attrs['width']; f['container'].attrs['width'] = 1",
       "/container/width: stored as int64, expected float64"},
      {"del f['provenance'].attrs['seed']; f['provenance'].attrs['seed'] = np.int64(-3)",
       "/provenance/seed = -3: negative, expected >= 0"},
      {"f.attrs['format_version'] = np.int64(1)", ""},  // h5py's default int: accepted
      {"f.attrs['format_name'] = 'x' * 500 + '\\n'",
       "/format_name = \"xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\"...: not an "
       "aggpack packing"},
  };
  const std::string external = (base_ / "raw.bin").string();
  const std::string external_edit =
      "v = f['shapes/vertices'][...]; del f['shapes/vertices']; v.tofile('" + external +
      "')\nf['shapes'].create_dataset('vertices', shape=v.shape, dtype='<f8', external=[('" +
      external + "', 0, v.nbytes)])";
  const std::string external_message =
      "/shapes/vertices: stored outside the file (external or virtual dataset)";
  std::vector<std::pair<const char*, const char*>> all(std::begin(cases), std::end(cases));
  all.emplace_back(external_edit.c_str(), external_message.c_str());
  int k = 0;
  for (const auto& [edit, expected] : all) {
    const std::string path = edited("t" + std::to_string(k++) + ".h5", edit);
    const std::string message = message_of(path);
    if (std::string(expected).empty()) {
      EXPECT_EQ(message, "") << edit;
    } else {
      EXPECT_EQ(message.rfind(path + ": " + expected, 0), 0U) << message;
    }
  }
}

}  // namespace
}  // namespace aggpack
