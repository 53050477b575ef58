// The format table (export_formats(), deck_kinds()): every format has a row with a name, an
// extension that resolves back to it and one writer; every [output] key is a row; the native .h5
// file written through the generic write() is the native writer's file, byte for byte, and reads
// back equal.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "export_fixture.h"
#include "support/files.h"

namespace aggpack {
namespace {

// A switch with no default: a new ExportFormat that this list misses fails the build (-Wswitch),
// and the test below then checks that the table has its row.
bool is_format(ExportFormat format) {
  switch (format) {
    case ExportFormat::kAuto:
      return false;
    case ExportFormat::kStl:
    case ExportFormat::kRockDat:
    case ExportFormat::kAbaqus:
    case ExportFormat::kVtu:
    case ExportFormat::kGmsh:
    case ExportFormat::kLsDyna:
    case ExportFormat::kAnsysApdl:
    case ExportFormat::kObj:
    case ExportFormat::kYade:
    case ExportFormat::kNative:
      return true;
  }
  return false;
}

constexpr ExportFormat kEveryFormat[] = {
    ExportFormat::kStl,  ExportFormat::kRockDat, ExportFormat::kAbaqus,    ExportFormat::kVtu,
    ExportFormat::kGmsh, ExportFormat::kLsDyna,  ExportFormat::kAnsysApdl, ExportFormat::kObj,
    ExportFormat::kYade, ExportFormat::kNative};

TEST(FormatTable, EveryFormatHasOneCompleteRow) {
  std::set<ExportFormat> seen;
  std::set<std::string> words;
  for (const FormatInfo& info : export_formats()) {
    const std::string name(info.name);
    SCOPED_TRACE(name);
    EXPECT_TRUE(is_format(info.format));
    EXPECT_TRUE(seen.insert(info.format).second) << "two rows for one format";
    EXPECT_FALSE(name.empty());
    EXPECT_FALSE(info.output_key.empty());
    EXPECT_FALSE(info.title.empty());
    EXPECT_EQ(&format_info(info.format), &info);
    EXPECT_EQ(format_name(info.format), name);
    // Exactly one writer.
    EXPECT_NE(info.write_mesh == nullptr, info.write_file == nullptr);
    // Its extension, every alias and its [output] key name it (case-insensitive), and no word
    // names two formats.
    EXPECT_EQ(format_from_extension("dir/particles." + name), info.format);
    EXPECT_EQ(parse_export_format(std::string(info.output_key)), info.format);
    EXPECT_TRUE(words.insert(name).second) << name << " names two formats";
    for (const auto alias : info.aliases) {
      EXPECT_EQ(parse_export_format(std::string(alias)), info.format) << alias;
      EXPECT_TRUE(words.insert(std::string(alias)).second) << alias << " names two formats";
    }
    std::string upper = name;
    std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
    EXPECT_EQ(format_from_extension("x." + upper), info.format);
    // It holds something, and its capabilities agree with each other.
    EXPECT_TRUE(info.holds_packing || info.has_surface || info.has_tetrahedra);
    EXPECT_EQ(info.holds_packing, info.write_file != nullptr);
    if (!info.holds_packing) {
      EXPECT_NE(info.default_cells, MeshCells::kDefault);
      EXPECT_TRUE(info.default_cells != MeshCells::kSurface || info.has_surface);
      EXPECT_TRUE(info.default_cells != MeshCells::kTetrahedra || info.has_tetrahedra);
    }
    EXPECT_TRUE(!info.has_quadratic || info.has_tetrahedra);
    EXPECT_FALSE(info.has_per_particle && info.holds_packing);
  }
  for (const ExportFormat format : kEveryFormat) {
    EXPECT_EQ(seen.count(format), 1U) << "no row for format " << static_cast<int>(format);
  }
  EXPECT_EQ(seen.size(), std::size(kEveryFormat));
  EXPECT_THROW(format_info(ExportFormat::kAuto), InvalidInput);
  EXPECT_THROW(parse_export_format("step"), InvalidInput);
}

TEST(FormatTable, OutputKeysAreTheRowsKeys) {
  const auto& names = output_format_names();
  ASSERT_EQ(names.size(), export_formats().size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(names[i], export_formats()[i].output_key);
    EXPECT_EQ(parse_export_format(names[i]), export_formats()[i].format) << names[i];
  }
  // The keys configs already use.
  for (const char* key :
       {"native", "stl", "obj", "vtu", "dat", "inp", "msh", "k", "apdl", "yade"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), key), names.end()) << key;
  }
  EXPECT_EQ(parse_export_format("native"), ExportFormat::kNative);
}

TEST(FormatTable, EveryDeckNamesAMeshFormatAndAWriter) {
  std::set<DeckKind> seen;
  std::set<std::string> titles;
  for (const DeckInfo& deck : deck_kinds()) {
    const std::string name(deck.name);
    SCOPED_TRACE(name);
    EXPECT_NE(deck.kind, DeckKind::kNone);
    EXPECT_TRUE(seen.insert(deck.kind).second);
    EXPECT_NE(deck.write_mesh, nullptr);
    EXPECT_FALSE(deck.title.empty()) << "the GUI's menus show the solver's name";
    EXPECT_TRUE(titles.insert(std::string(deck.title)).second);
    EXPECT_NE(format_info(deck.format).write_mesh, nullptr) << "a deck is written around a mesh";
    EXPECT_EQ(parse_deck_kind(name), deck.kind);
    EXPECT_EQ(deck_name(deck.kind), name);
    for (const auto alias : deck.aliases) EXPECT_EQ(parse_deck_kind(std::string(alias)), deck.kind);
    ExportOptions options;
    options.deck.kind = deck.kind;
    EXPECT_EQ(resolve_format("trough", options), deck.format);
    // A deck's own options (the GUI shows their fields for this deck only) are named so by the
    // library's check: a bad value is refused under that name.
    const std::map<std::string_view, double DeckOptions::*> members = {
        {"contact distance", &DeckOptions::contact_distance},
        {"time step", &DeckOptions::time_step}};
    for (const std::string_view own : deck.own_options) {
      ASSERT_EQ(members.count(own), 1U) << own;
      ExportOptions bad = options;
      bad.deck.*members.at(own) = -1.0;
      try {
        validate(bad, deck.format);
        ADD_FAILURE() << own << " = -1 was accepted";
      } catch (const InvalidInput& invalid) {
        EXPECT_EQ(invalid.field(), own);
      }
    }
  }
  EXPECT_EQ(seen.size(), 4U);
  EXPECT_EQ(parse_deck_kind("none"), DeckKind::kNone);
}

// write() to .h5 is write_packing: the same bytes, with and without the native options, and the
// file reads back equal.
TEST(FormatTable, NativeThroughTheGenericEntry) {
  test::ScratchFolder folder;
  const Packing packing = test::grid_packing(3, 2, 2, 4, true);
  const ExportSummary summary = write(packing, folder.file("generic.h5"));
  EXPECT_EQ(summary.format, ExportFormat::kNative);
  EXPECT_EQ(summary.particles, packing.particles.size());
  EXPECT_EQ(summary.files, 1U);
  write_packing(packing, folder.file("direct.h5"));
  EXPECT_TRUE(test::same_bytes(test::file_text(folder.file("generic.h5")),
                               test::file_text(folder.file("direct.h5"))));

  const Packing loaded = read_packing(folder.file("generic.h5"));
  ASSERT_EQ(loaded.shapes.size(), packing.shapes.size());
  ASSERT_EQ(loaded.particles.size(), packing.particles.size());
  for (std::size_t s = 0; s < packing.shapes.size(); ++s) {
    EXPECT_EQ(loaded.shapes[s].vertices(), packing.shapes[s].vertices());
    EXPECT_EQ(loaded.shapes[s].triangles(), packing.shapes[s].triangles());
  }
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Particle& a = packing.particles[i];
    const Particle& b = loaded.particles[i];
    EXPECT_EQ(a.shape, b.shape);
    EXPECT_EQ(a.pose.position, b.pose.position);
    EXPECT_EQ(a.pose.rotation.coeffs(), b.pose.rotation.coeffs());
    EXPECT_EQ(a.scale, b.scale);
    EXPECT_EQ(a.control_radius, b.control_radius);
    EXPECT_EQ(a.size_class, b.size_class);
  }
  EXPECT_EQ(loaded.container, packing.container);
  EXPECT_EQ(loaded.provenance.packer, packing.provenance.packer);
  EXPECT_EQ(loaded.provenance.seed, packing.provenance.seed);

  // Native options, and the format named instead of taken from the extension.
  const ExportSummary both =
      write(packing, folder.file("options.data"),
            {.format = ExportFormat::kNative, .compression = 6, .write_xdmf = true});
  EXPECT_EQ(both.files, 2U);
  write_packing(packing, folder.file("direct6.data"), {.compression = 6, .write_xdmf = true});
  EXPECT_TRUE(test::same_bytes(test::file_text(folder.file("options.data")),
                               test::file_text(folder.file("direct6.data"))));
  EXPECT_NE(test::file_text(folder.file("options.xdmf")).find("options.data"), std::string::npos);

  // An existing file is kept unless overwrite allows it.
  EXPECT_THROW(write(packing, folder.file("generic.h5")), IoError);
  write(packing, folder.file("generic.h5"), {.overwrite = Overwrite::kAllow});
}

// The native options belong to the native row, the mesh options to the mesh rows.
TEST(FormatTable, OptionsOutsideTheirFormatsAreRefused) {
  test::ScratchFolder folder;
  const Packing packing = test::grid_packing(1, 1, 2);
  EXPECT_THROW(write(packing, folder.file("a.stl"), {.compression = 3}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.vtu"), {.write_xdmf = true}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.h5"), {.scale = 1000.0}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.h5"), {.is_per_particle = true}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.h5"), {.is_quadratic = true}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.h5"), {.cells = MeshCells::kSurface}), InvalidInput);
  EXPECT_THROW(write(packing, folder.file("a.h5"), {.compression = 10}), InvalidInput);
  EXPECT_TRUE(folder.entries().empty()) << "no file written for refused options";
}

}  // namespace
}  // namespace aggpack
