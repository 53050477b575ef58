// Every library error the window can meet, driven through the library as the window drives it
// (Pack's configuration and run, particle.library and its mesh files, Open, Export, the solver
// decks, the mesomodel), worded in Chinese from its parts: each part is a sentence of
// core/error_words.h or a name or number, and no English word of the library's message is left but
// names and values. A message that reaches the window as free-form English text fails here.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <regex>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/io/shape_library_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/shape/descriptors.h"
#include "gui/words.h"
#include "i18n.h"
#include "library_words.h"
#include "support/mesh_files.h"
#include "support/packings.h"
#include "support/paths.h"
#include "system_words.h"

namespace aggpack::gui {
namespace {

namespace fs = std::filesystem;

// A word kept in every language, or a name with an underscore (a key's part, "library_size").
bool is_name(const std::string& word) {
  return test_words::is_kept_name(word) || word.find('_') != std::string::npos;
}

// The error in the Chinese window (then back to English).
std::string chinese_words(const Error& error) {
  set_language(Language::kChinese);
  std::string text = error_words(error);
  set_language(Language::kEnglish);
  return text;
}

// What is wrong with the error's words in Chinese ("" when nothing): they must carry no English
// word of its message but names and values, and its whole message (or the allowed part of a
// refused value) must be a sentence unless it has no words. `chinese` gets the words.
std::string problems_in_chinese(const Error& error, std::string& chinese) {
  std::string problems;
  std::vector<const Wording*> parts = {&error.wording()};
  if (error.has_value()) {
    parts.push_back(&error.value_wording());
    parts.push_back(&error.field_wording());  // last: a field's name is a name
  }
  // A value that is a sentence of its own (Error::worded_values) is worded as one: it must be a
  // sentence, and its own values are checked as the error's.
  for (const WordedValue& worded : error.worded_values()) {
    if (worded.wording.sentence == Sentence::kText) {
      problems += " worded value '" + worded.text + "' is no sentence;";
    }
    parts.push_back(&worded.wording);
  }
  const auto is_worded = [&](const std::string& value) {
    return std::any_of(error.worded_values().begin(), error.worded_values().end(),
                       [&](const WordedValue& worded) { return worded.text == value; });
  };
  std::set<std::string> value_words;
  for (const Wording* part : parts) {
    for (const std::string& value : part->values) {
      if (is_worded(value)) continue;
      // Words in a value (a path, a number with its unit) are names; English words in a value
      // with spaces are prose, unless the window words it (a Phrase* sentence) or it is a path
      // ("/container/width = 0", a file's data by name).
      const std::set<std::string> words = test_words::english_words_of(value);
      value_words.insert(words.begin(), words.end());
      if (part == &error.field_wording() || value.find(' ') == std::string::npos ||
          value.front() == '/') {
        continue;
      }
      std::size_t english = 0;
      for (const std::string& word : words) english += is_name(word) ? 0 : 1;
      const std::string worded =
          chinese_words(LimitExceeded("x", "1", Wording{Sentence::kAtMost, {value}}));
      if (english >= 2 && worded.find(value) != std::string::npos) {
        problems += " English value '" + value + "';";
      }
    }
  }
  if (error.wording().sentence == Sentence::kText) {
    for (const std::string& word : test_words::english_words_of(english(error.wording()))) {
      if (!is_name(word)) problems += " free-form English word '" + word + "';";
    }
  }
  chinese = chinese_words(error);
  if (!test_words::has_chinese_text(chinese)) problems += " no Chinese;";
  const std::set<std::string> left = test_words::english_words_of(chinese);
  for (const std::string& word : test_words::english_words_of(error.what())) {
    if (value_words.count(word) > 0 || is_name(word)) continue;
    if (left.count(word) > 0) problems += " '" + word + "' left;";
  }
  return problems;
}

// Checks the error's Chinese words (AGGPACK_SHOW_WORDS=1 prints both languages).
std::string expect_worded(const Error& error) {
  std::string chinese;
  const std::string problems = problems_in_chinese(error, chinese);
  if (std::getenv("AGGPACK_SHOW_WORDS") != nullptr) {
    std::printf("%s\n%s\n\n", error.what(), chinese.c_str());
  }
  EXPECT_EQ(problems, "") << chinese << "\n(English: " << error.what() << ")";
  return chinese;
}

// Runs `run`, which must throw an aggpack Error, and checks its Chinese words.
std::string expect_chinese_error(const std::function<void()>& run) {
  try {
    run();
  } catch (const Error& error) {
    return expect_worded(error);
  }
  ADD_FAILURE() << "no error thrown";
  return "";
}

// A scratch folder of its own, removed afterwards.
struct ErrorsScratch {
  fs::path folder =
      fs::temp_directory_path() / ("aggpack-gui-errors-" + std::to_string(::getpid()));
  ErrorsScratch() { fs::create_directories(folder); }
  ~ErrorsScratch() { fs::remove_all(folder); }
  [[nodiscard]] std::string path(const std::string& name) const { return (folder / name).string(); }
};

Packing two_cubes(double first_x, double second_x) {
  const ConvexPolyhedron cube = make_box(Vec3::Constant(-0.1), Vec3::Constant(0.1));
  return test::box_with(1.0, {cube, cube}, {Vec3(first_x, 0.5, 0.5), Vec3(second_x, 0.5, 0.5)});
}

TEST(LibraryErrors, FreeFormEnglishFails) {
  // The check itself: a message without a sentence of its own is caught.
  std::string chinese;
  const std::string problems =
      problems_in_chinese(FormatError("x.ply: PLY header has no format line"), chinese);
  EXPECT_NE(problems.find("free-form English word 'header'"), std::string::npos) << problems;
  EXPECT_NE(problems.find("no Chinese"), std::string::npos) << problems;
  // A value in English words is caught too, unless it is a phrase the window words.
  const LimitExceeded prose(Wording{Sentence::kText, {"grading"}},
                            Wording{Sentence::kText, {"sizes out of range"}},
                            Wording{Sentence::kAtMost, {"1"}});
  EXPECT_NE(problems_in_chinese(prose, chinese).find("English value"), std::string::npos);
  const LimitExceeded phrase(
      Wording{Sentence::kText, {"grading"}}, Wording{Sentence::kText, {"1"}},
      Wording{Sentence::kMemorySize, {english_words(Sentence::kPhraseUseLargerParticles)}});
  EXPECT_EQ(problems_in_chinese(phrase, chinese), "") << chinese;
}

TEST(LibraryErrors, WritingAFile) {
  const ErrorsScratch scratch;
  const Packing packing = two_cubes(0.3, 0.7);
  const ExportOptions stl{.format = parse_export_format("stl"), .overwrite = Overwrite::kAllow};
  expect_chinese_error([&] { (void)write(packing, "/nonexistent-aggpack-folder/rock.stl", stl); });
  fs::create_directories(scratch.path("rock.stl"));
  const std::string folder =
      expect_chinese_error([&] { (void)write(packing, scratch.path("rock.stl"), stl); });
  EXPECT_NE(folder.find("文件夹"), std::string::npos) << folder;  // "directory", a phrase
  expect_chinese_error([] { check_writable("", Overwrite::kAllow); });
  expect_chinese_error(
      [&] { check_writable(scratch.path(std::string(300, 'a')), Overwrite::kAllow); });
}

TEST(LibraryErrors, LimitsCheckedBeforeAPack) {
  const std::vector<std::string> random = {"packer.kind=\"random\""};
  auto config_with = [&](std::vector<std::string> sets) {
    sets.insert(sets.begin(), random.begin(), random.end());
    return [sets] { (void)parse_pack_config("", "gui", sets); };
  };
  expect_chinese_error(config_with({"packer.target_count=100000000"}));
  expect_chinese_error(config_with({"packer.target_count=10", "packer.shape_library=1000000"}));
  // Particles too large for the container's interior: the value is a phrase ("smallest size").
  try {
    config_with({"container.length=0.01", "container.width=0.01", "container.depth=0.01",
                 "particle.radius=0.1"})();
    ADD_FAILURE() << "particles larger than the container were accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.value_wording().sentence, Sentence::kSmallestSize) << error.what();
    EXPECT_NE(expect_worded(error).find("最小粒径"), std::string::npos);
  }
  ::setenv("AGGPACK_MEMORY_LIMIT", "1K", 1);
  expect_chinese_error(config_with({"packer.target_count=1000"}));
  ::setenv("AGGPACK_MEMORY_LIMIT", "lots", 1);
  expect_chinese_error(config_with({"packer.target_count=1000"}));
  ::unsetenv("AGGPACK_MEMORY_LIMIT");
}

TEST(LibraryErrors, ShapeLibraryFiles) {
  const ErrorsScratch scratch;
  auto load = [](const std::string& path) {
    return [path] {
      ShapeLibraryOptions options;
      options.paths = {path};
      (void)load_shape_library(options);
    };
  };
  expect_chinese_error(load(scratch.path("missing")));
  expect_chinese_error(load(""));
  fs::create_directories(scratch.path("empty"));
  expect_chinese_error(load(scratch.path("empty")));
  std::ofstream(scratch.path("notes.txt")) << "not a mesh\n";
  expect_chinese_error(load(scratch.path("notes.txt")));
  // Damaged mesh files: each reader's sentence, the file named first.
  std::ofstream(scratch.path("bad.stl")) << "solid x\nfacet normal 0 0 1\nouter loop\n";
  expect_chinese_error(load(scratch.path("bad.stl")));
  std::ofstream(scratch.path("bad.obj")) << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
  expect_chinese_error(load(scratch.path("bad.obj")));
  std::ofstream(scratch.path("junk.stl")) << "junk\n";
  expect_chinese_error(load(scratch.path("junk.stl")));
}

TEST(LibraryErrors, EveryFileSkipped) {
  // particle.library_skip_bad with no usable file: the first file's reason in its own sentence.
  const ErrorsScratch scratch;
  TriangleMesh open = test::dented_cube(10, 3);
  open.triangles.pop_back();
  fs::create_directories(scratch.path("rocks"));
  std::ofstream(scratch.path("rocks/a.obj")) << test::obj_text(open);
  std::ofstream(scratch.path("rocks/b.stl")) << "junk\n";
  ShapeLibraryOptions options;
  options.paths = {scratch.path("rocks")};
  options.is_skipping_bad = true;
  try {
    (void)load_shape_library(options);
    ADD_FAILURE() << "a library of no usable file was loaded";
  } catch (const Error& error) {
    EXPECT_EQ(error.wording().sentence, Sentence::kLibraryAllSkipped) << error.what();
    ASSERT_EQ(error.worded_values().size(), 1U) << error.what();
    EXPECT_EQ(error.worded_values().front().wording.sentence, Sentence::kMeshOpen);
    const std::string chinese = expect_worded(error);
    EXPECT_NE(chinese.find("全部 2 个都被跳过"), std::string::npos) << chinese;
    EXPECT_NE(chinese.find("网格不封闭"), std::string::npos) << chinese;
    // English: the message as the command line prints it, the file by its name.
    EXPECT_NE(std::string(error.what()).find("first: a.obj: mesh is open"), std::string::npos)
        << error.what();
  }
}

// A library of one file (particle.library), loaded as Pack loads it.
std::function<void()> load_library(const std::string& path, double max_hull_excess = 0.0) {
  return [path, max_hull_excess] {
    ShapeLibraryOptions options;
    options.paths = {path};
    options.import.max_hull_excess = max_hull_excess;
    (void)load_shape_library(options);
  };
}

TEST(LibraryErrors, DamagedPlyFiles) {
  const ErrorsScratch scratch;
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string ascii = "ply\nformat ascii 1.0\n";
  const std::vector<std::string> damaged = {
      "junk\n",                                                           // no ply ... end_header
      "ply\nelement vertex 0\nend_header\n",                              // no format line
      ascii + "bogus 1\nend_header\n",                                    // unknown keyword
      ascii + "format\nend_header\n",                                     // format without a name
      "ply\nformat sideways 1.0\nend_header\n",                           // unknown format
      ascii + "element vertex\nend_header\n",                             // element NAME COUNT
      ascii + "property float x\nend_header\n",                           // property first
      ascii + "element vertex 1\nproperty list uchar int\nend_header\n",  // property line
      ascii + "element vertex 1\nproperty list xy int i\nend_header\n",   // list types
      ascii + "element vertex 1\nproperty quad x\nend_header\n",          // unknown type
      ascii + "element vertex 9\n" + xyz + "end_header\n0 0 0\n",         // more than it holds
      ascii + "element vertex 1\nproperty float x\nend_header\n0\n",      // no y, z
      ascii + "element vertex 0\n" + xyz + "element face 0\nproperty int i\nend_header\n",
      ascii + "element vertex 1\n" + xyz + "end_header\n0 0 zero\n",  // not a number
      ascii + "element vertex 1\n" + xyz + "end_header\n0 0 nan\n",   // not finite
      ascii + "element vertex 1\n" + xyz + "end_header\n0 0 0\n",     // no face element
      ascii + "element vertex 3\n" + xyz +
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
          "1 0\n3 0 1 7\n",  // a face naming vertex 7 of 3
      ascii + "element vertex 3\n" + xyz +
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
          "1 0\n2 0 1\n",  // a face of 2 vertices
      ascii + "element vertex 3\n" + xyz +
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
          "1 0\n3 0 1 -2\n",  // a negative index
      ascii + "element vertex 3\n" + xyz +
          "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
          "1 0\n3.5 0 1 2\n1 0\n",  // a list of 3.5 items
  };
  std::set<Sentence> sentences;
  for (std::size_t k = 0; k < damaged.size(); ++k) {
    const std::string file = scratch.path("bad" + std::to_string(k) + ".ply");
    std::ofstream(file, std::ios::binary) << damaged[k];
    try {
      load_library(file)();
      ADD_FAILURE() << "no error for " << damaged[k];
    } catch (const Error& error) {
      sentences.insert(error.wording().sentence);
      expect_worded(error);
    }
  }
  // A binary file cut short: its data ends early.
  std::string binary = test::ply_bytes(test::dented_cube(10, 3), test::PlyEncoding::kLittle);
  binary.resize(binary.size() - 5);
  std::ofstream(scratch.path("short.ply"), std::ios::binary) << binary;
  expect_chinese_error(load_library(scratch.path("short.ply")));
  EXPECT_EQ(sentences.size(), damaged.size()) << "each damage its own sentence";
}

TEST(LibraryErrors, MeshesThatAreNoParticle) {
  const ErrorsScratch scratch;
  TriangleMesh open = test::dented_cube(10, 3);
  open.triangles.pop_back();
  TriangleMesh flipped = test::dented_cube(10, 3);
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  TriangleMesh two = test::dented_cube(10, 3);
  const TriangleMesh other = test::dented_cube(10, 3);
  for (Triangle t : other.triangles) {
    for (auto& v : t) v += static_cast<std::uint32_t>(other.vertices.size());
    two.triangles.push_back(t);
  }
  for (const Vec3& v : other.vertices) two.vertices.push_back(v + Vec3(20, 0, 0));
  TriangleMesh small = test::dented_cube(10, 3);
  small.triangles.resize(3);
  TriangleMesh repeated = test::dented_cube(10, 3);
  repeated.triangles[0][1] = repeated.triangles[0][0];
  TriangleMesh sliver = test::dented_cube(10, 3);
  sliver.vertices[sliver.triangles[0][1]] = sliver.vertices[sliver.triangles[0][0]];  // no area
  // Four points in a plane, joined as a tetrahedron: closed, but spanning no volume.
  const TriangleMesh flat{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)},
                          {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  const std::vector<std::pair<std::string, TriangleMesh>> meshes = {{"open", open},
                                                                    {"flipped", flipped},
                                                                    {"two", two},
                                                                    {"small", small},
                                                                    {"repeated", repeated},
                                                                    {"sliver", sliver},
                                                                    {"fin", test::finned_cube()},
                                                                    {"bowtie", test::bowtie()}};
  std::set<Sentence> sentences;
  for (const auto& [name, mesh] : meshes) {
    const std::string file = scratch.path(name + ".obj");
    std::ofstream(file) << test::obj_text(mesh);
    try {
      load_library(file)();
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& error) {
      sentences.insert(error.wording().sentence);
      EXPECT_EQ(error.wording().values.front(), file) << error.what();  // the file first
      expect_worded(error);
    }
  }
  EXPECT_EQ(sentences.size(), meshes.size()) << "each fault its own sentence";
  // Over particle.library_max_hull_excess: this dented cube's hull adds 15.4 %.
  std::ofstream(scratch.path("dented.obj")) << test::obj_text(test::dented_cube(10, 4));
  const std::string excess = expect_chinese_error(load_library(scratch.path("dented.obj"), 0.05));
  EXPECT_NE(excess.find("particle.library_max_hull_excess"), std::string::npos) << excess;
  // No convex hull: Qhull's own reason stays as it is (a technical detail), the rest is worded.
  std::ofstream(scratch.path("flat.obj")) << test::obj_text(flat);
  try {
    load_library(scratch.path("flat.obj"))();
    ADD_FAILURE() << "a flat mesh has a hull";
  } catch (const Error& error) {
    EXPECT_EQ(error.wording().sentence, Sentence::kMeshNoHull) << error.what();
    EXPECT_NE(chinese_words(error).find("网格没有凸包"), std::string::npos) << chinese_words(error);
  }
  // A file over the reader's size cap (a sparse file: nothing is read).
  const std::string big = scratch.path("big.stl");
  std::ofstream(big).put('x');
  std::error_code error;
  fs::resize_file(big, kMaxMeshFileBytes + 1, error);
  if (!error) expect_chinese_error(load_library(big));
}

// Errors no test can provoke (a worker process or OpenGL that fails, a format's id limit, checks
// that only a bug reaches), as the library words them: each is a sentence worded in Chinese.
// (The checks a misused library meets are provoked in MisusedLibrary.)
TEST(LibraryErrors, ErrorsNoTestProvokes) {
  expect_worded(IoError(Wording{Sentence::kWorkerPipe, {"EMFILE"}}));
  expect_worded(IoError(Wording{Sentence::kWorkerStart, {"EAGAIN"}}));
  expect_worded(IoError(Wording{Sentence::kWorkerWait, {"EINVAL"}}));
  expect_worded(IoError(Wording{Sentence::kOpenGlCompile, {"0:1(10):"}}));
  expect_worded(IoError(Wording{Sentence::kOpenGlLink, {"0:2(3):"}}));
  expect_worded(IoError(Wording{Sentence::kOpenGlVersion, {"2.1"}}));
  expect_worded(LimitExceeded(Wording{Sentence::kFormatIds, {"LS-DYNA"}},
                              Wording{Sentence::kText, {"100000000"}},
                              Wording{Sentence::kAtMost, {"99999999"}}));
  // The densifier's final check, worded with verify()'s finding.
  const Wording apart{Sentence::kVerifyApart, {"3", "5", "-0.001", "0"}};
  Error verify_failed(ErrorKind::kInvalidInput,
                      Wording{Sentence::kDensifyVerifyFailed, {english(apart)}});
  verify_failed.word_value(english(apart), apart);
  EXPECT_EQ(expect_worded(verify_failed).find("are"), std::string::npos);
  expect_worded(Error(ErrorKind::kInvalidInput, Wording{Sentence::kBrokenAdjacency, {}}));
  // TetGen's own failure on a mesomodel: facets that intersect, and the surfaces it names.
  const Wording code{Sentence::kTetGenFacetsIntersect, {"3"}};
  const Wording wall{Sentence::kSurfaceWall, {"1"}};
  const Wording layer{Sentence::kSurfaceItzLayer, {"4"}};
  const Wording surfaces{Sentence::kSurfaceList, {english(wall), english(layer)}};
  LimitExceeded tetgen(Wording{Sentence::kMesomodelMesh, {}},
                       Wording{Sentence::kTetGenIntersecting, {english(code), english(surfaces)}},
                       Wording{Sentence::kTetGenCanMesh, {"packer.gap", "container.wall_gap"}});
  for (const Wording* part : {&code, &wall, &layer, &surfaces}) {
    tetgen.word_value(english(*part), *part);
  }
  const std::string intersecting = expect_worded(tetgen);
  EXPECT_NE(intersecting.find("壁面 1、颗粒 4 的界面过渡区层"), std::string::npos) << intersecting;
  expect_worded(InvalidInput(Wording{Sentence::kShapeVolume, {"3"}},
                             Wording{Sentence::kText, {"-1"}},
                             Wording{Sentence::kClosedConvexBody, {}}));
  // A shape of no volume, driven through the library: an inside-out cube.
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  std::vector<Triangle> flipped = cube.triangles();
  for (Triangle& t : flipped) std::swap(t[1], t[2]);
  expect_chinese_error([&] { (void)describe(ConvexPolyhedron(cube.vertices(), flipped)); });
}

TEST(LibraryErrors, DamagedPackingFiles) {
  // The damaged native files of tests/io/fixtures/bad-inputs (README.md there), read as Open
  // reads them: the field (a name) and the reason in words, the reason a sentence of its own.
  std::set<Sentence> reasons;
  std::size_t damaged = 0;
  for (const auto& entry : fs::directory_iterator(test::bad_inputs_dir())) {
    if (entry.path().extension() != ".h5") continue;
    try {
      (void)read_packing(entry.path().string());
    } catch (const Error& error) {
      ++damaged;
      for (const WordedValue& worded : error.worded_values()) {
        reasons.insert(worded.wording.sentence);
      }
      expect_worded(error);
    }
  }
  EXPECT_GE(damaged, 15U);
  EXPECT_GE(reasons.size(), 12U) << "the fixtures' reasons, each its own sentence";
  // A text file named .h5 and a missing one: the file's own sentences.
  const ErrorsScratch scratch;
  std::ofstream(scratch.path("notes.h5")) << "not a packing\n";
  expect_chinese_error([&] { (void)read_packing(scratch.path("notes.h5")); });
  expect_chinese_error([&] { (void)read_packing(scratch.path("missing.h5")); });
}

// Checks a caller of the library meets only by misusing it (the window never does), driven
// through the library.
TEST(LibraryErrors, MisusedLibrary) {
  // densify() of a start packing whose particles overlap.
  const std::string start =
      expect_chinese_error([] { (void)densify(two_cubes(0.3, 0.35), DensifyOptions{}); });
  EXPECT_NE(start.find("颗粒 0 与 1 相距"), std::string::npos) << start;
  // A packer given a shape library the pipeline has not loaded.
  RandomPackOptions random;
  random.shape.files.options.paths = {"rocks/"};
  expect_chinese_error([&] { (void)pack_random(random); });
  LatticeOptions lattice;
  lattice.files.options.paths = {"rocks/"};
  expect_chinese_error([&] { (void)pack_lattice(lattice); });
}

TEST(LibraryErrors, Mesomodel) {
  MesoOptions options;
  options.itz_thickness = 0.03;  // two cubes 0.05 apart: their layers meet
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.3, 0.55), options); });
  options.itz_thickness = 0.0;  // touching cubes
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.3, 0.5), options); });
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.1, 0.5), options); });  // a wall
}

TEST(LibraryErrors, MesomodelTetGenStopped) {
  // TetGen stopped by the time limit (a fine mortar mesh takes far longer than 1 ms): the worker's
  // failure in words, inside the mesomodel's refusal.
  MesoOptions options;
  options.mortar_size = 0.05;
  options.time_limit = 0.001;
  try {
    (void)build_mesomodel(two_cubes(0.3, 0.7), options);
    ADD_FAILURE() << "TetGen finished within 1 ms";
  } catch (const InvalidInput& error) {
    if (error.field() != "mesomodel") ADD_FAILURE() << error.what();
    GTEST_SKIP() << error.what();  // a build without TetGen
  } catch (const Error& error) {
    EXPECT_EQ(error.value_wording().sentence, Sentence::kTetGenWorker) << error.what();
    const std::string chinese = expect_worded(error);
    EXPECT_NE(chinese.find("超时"), std::string::npos) << chinese;
  }
}

TEST(LibraryErrors, SolverDeckFields) {
  const ErrorsScratch scratch;
  ExportOptions options{.overwrite = Overwrite::kAllow};
  options.deck.kind = DeckKind::kAbaqus;
  for (const DeckInfo& deck : deck_kinds()) {
    if (deck.kind == DeckKind::kAbaqus) options.format = deck.format;
  }
  options.material.poisson_ratio = 0.7;
  const std::string poisson = expect_chinese_error([&] { validate(options, options.format); });
  EXPECT_NE(poisson.find("泊松比"), std::string::npos) << poisson;  // the field's label
  options.material.poisson_ratio = 0.2;
  options.deck.baffle_position = 0.01;  // in front of the particles
  expect_chinese_error(
      [&] { (void)write(two_cubes(0.3, 0.7), scratch.path("trough.inp"), options); });
}

TEST(LibraryErrors, StoredShapeOwnRefusal) {
  // A packing file whose shape the polyhedron itself refuses: its reason, quoted after "not a
  // polyhedron", is worded as a sentence of its own (with its value and allowed part).
  const std::string chinese = expect_chinese_error(
      [] { (void)read_packing(test::bad_inputs_dir() + "triangle_index_outside_shape.h5"); });
  EXPECT_NE(
      chinese.find("不是多面体：polyhedron.triangles = 顶点索引 1000000 无效（允许：小于 24）"),
      std::string::npos)
      << chinese;
  // Each refusal of the polyhedron, as a program using the library meets it.
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const std::vector<Vec3> three(cube.vertices().begin(), cube.vertices().begin() + 3);
  expect_chinese_error([&] { (void)ConvexPolyhedron(three, cube.triangles()); });
  expect_chinese_error([&] {
    (void)ConvexPolyhedron(cube.vertices(),
                           {cube.triangles().begin(), cube.triangles().begin() + 3});
  });
  std::vector<Vec3> infinite = cube.vertices();
  infinite[2].y() = std::numeric_limits<double>::infinity();
  EXPECT_NE(expect_chinese_error([&] {
              (void)ConvexPolyhedron(infinite, cube.triangles());
            }).find("坐标不是有限数"),
            std::string::npos);
  std::vector<Triangle> open = cube.triangles();
  open.pop_back();
  expect_chinese_error([&] { (void)ConvexPolyhedron(cube.vertices(), open).edges(); });
}

TEST(LibraryErrors, OperatingSystemReasons) {
  // Every errno and signal of the table, as the library quotes it (std::strerror, error_code,
  // strsignal), in Chinese words; a reason outside the table stays as the system gives it.
  for (const int number : worded_errnos()) {
    const std::string chinese = expect_worded(
        IoError(Wording{Sentence::kReadSystemError, {"run.h5", std::strerror(number)}}));
    set_language(Language::kChinese);
    const std::string reason = system_reason_words(std::strerror(number));
    set_language(Language::kEnglish);
    EXPECT_TRUE(test_words::has_chinese_text(reason)) << number;
    EXPECT_NE(chinese.find(reason), std::string::npos) << chinese;
  }
  for (const int number : worded_signals()) {
    const std::string chinese = expect_worded(
        IoError(Wording{Sentence::kWorkerSignal, {std::to_string(number), ::strsignal(number)}}));
    for (const std::string& word : test_words::english_words_of(chinese)) {
      EXPECT_TRUE(is_name(word)) << chinese;  // "CPU"
    }
  }
  EXPECT_NE(expect_worded(IoError(Wording{Sentence::kWorkerSignal, {"9", ::strsignal(9)}}))
                .find("已杀死"),
            std::string::npos);
  EXPECT_EQ(system_reason_words("Killed by a cosmic ray"), "");
  // An operating-system failure outside the library's errors: its reason and paths.
  const std::filesystem::filesystem_error missing(
      "cannot copy", "/nowhere/a.h5", std::make_error_code(std::errc::no_such_file_or_directory));
  set_language(Language::kChinese);
  const std::string chinese = error_words(missing);
  set_language(Language::kEnglish);
  EXPECT_EQ(chinese, "错误：没有那个文件或目录（/nowhere/a.h5）");
  EXPECT_EQ(error_words(missing), std::string("Error: ") + missing.what());
}

}  // namespace
}  // namespace aggpack::gui
