// Bad paths and options give a clear error and leave no file behind; the format is picked by
// extension or name; output is byte-identical for any thread count; the CLI end to end.

#include <unistd.h>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "export_fixture.h"
#include "support/paths.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// Every format of the table, the native .h5 file included (export_registry_test.cpp checks that
// the table is complete).
std::vector<ExportFormat> all_formats() {
  std::vector<ExportFormat> formats;
  for (const FormatInfo& info : export_formats()) formats.push_back(info.format);
  return formats;
}

TEST(ExportFormatChoice, ByExtensionAndByName) {
  EXPECT_EQ(format_from_extension("a/b.stl"), ExportFormat::kStl);
  EXPECT_EQ(format_from_extension("rock.dat"), ExportFormat::kRockDat);
  EXPECT_EQ(format_from_extension("x.INP"), ExportFormat::kAbaqus);
  EXPECT_EQ(format_from_extension("x.vtu"), ExportFormat::kVtu);
  EXPECT_EQ(format_from_extension("x.msh"), ExportFormat::kGmsh);
  EXPECT_EQ(format_from_extension("x.k"), ExportFormat::kLsDyna);
  EXPECT_EQ(format_from_extension("x.key"), ExportFormat::kLsDyna);
  EXPECT_EQ(format_from_extension("x.mac"), ExportFormat::kAnsysApdl);
  EXPECT_EQ(format_from_extension("x.obj"), ExportFormat::kObj);
  EXPECT_EQ(format_from_extension("x.py"), ExportFormat::kYade);
  EXPECT_EQ(parse_export_format("abaqus"), ExportFormat::kAbaqus);
  EXPECT_EQ(parse_export_format("LS-DYNA"), ExportFormat::kLsDyna);
  EXPECT_EQ(parse_export_format("yade"), ExportFormat::kYade);
  for (ExportFormat format : all_formats()) {
    EXPECT_EQ(parse_export_format(format_name(format)), format);
  }
  EXPECT_THROW(format_from_extension("x.xyz"), InvalidInput);
  EXPECT_THROW(format_from_extension("noextension"), InvalidInput);
  try {
    parse_export_format("step");
    FAIL();
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "format");
    // Every format of the table, with its aliases.
    EXPECT_NE(std::string(error.what()).find("h5 (native), stl, obj, vtu (vtk), dat (rock.dat"),
              std::string::npos)
        << error.what();
  }
}

TEST(ExportOptionsCheck, OutOfRangeOptionsNameTheField) {
  const Packing packing = test::grid_packing(1, 1, 1);
  ScratchFolder folder;
  auto field_of = [&](const std::string& name, const ExportOptions& options) {
    try {
      write(packing, folder.file(name), options);
    } catch (const InvalidInput& error) {
      return error.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of("a.stl", {.scale = 0.0}), "scale");
  EXPECT_EQ(field_of("a.stl", {.scale = -1.0}), "scale");
  EXPECT_EQ(field_of("a.stl", {.is_quadratic = true}), "quadratic");
  EXPECT_EQ(field_of("a.inp", {.is_per_particle = true}), "per-particle");
  EXPECT_EQ(field_of("a.inp", {.cells = MeshCells::kSurface}), "cells");
  EXPECT_EQ(field_of("a.inp", {.material = {.density = 0}}), "density");
  EXPECT_EQ(field_of("a.inp", {.material = {.youngs_modulus = -5}}), "youngs modulus");
  EXPECT_EQ(field_of("a.inp", {.material = {.poisson_ratio = 0.5}}), "poisson ratio");
  EXPECT_EQ(field_of("a.inp", {.material = {.name = "bad name"}}), "material name");
  EXPECT_EQ(field_of("a.inp", {.tetrahedra = {.radius_edge_ratio = 0.9}}), "radius-edge ratio");
  EXPECT_EQ(field_of("a.xyz", {}), "output extension");
  EXPECT_TRUE(folder.entries().empty());
}

TEST(ExportPaths, MissingFolderExistingFileAndNoPermissionLeaveNothing) {
  const Packing packing = test::grid_packing(2, 1, 1);
  ScratchFolder folder;
  for (ExportFormat format : all_formats()) {
    const ExportOptions options{.format = format};
    // Missing folder.
    try {
      write(packing, folder.file("missing/out.file"), options);
      FAIL() << format_name(format);
    } catch (const IoError& error) {
      EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos);
    }
    // Existing file without overwrite: untouched; with overwrite: replaced.
    const std::string existing = folder.file("existing." + format_name(format));
    std::ofstream(existing) << "keep me";
    try {
      write(packing, existing, options);
      FAIL() << format_name(format);
    } catch (const IoError& error) {
      EXPECT_NE(std::string(error.what()).find("--force"), std::string::npos);
    }
    EXPECT_EQ(test::read_text(existing), "keep me");
    ExportOptions forced = options;
    forced.overwrite = Overwrite::kAllow;
    write(packing, existing, forced);
    EXPECT_NE(test::read_text(existing), "keep me");
  }
  // No permission: a read-only folder (root ignores permission bits, so also try a folder in
  // which nobody can create files).
  const std::string locked = folder.file("locked");
  std::filesystem::create_directory(locked);
  std::filesystem::permissions(
      locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::geteuid() != 0) {
    EXPECT_THROW(write(packing, locked + "/out.stl"), IoError);
    EXPECT_TRUE(std::filesystem::is_empty(locked));
  }
  EXPECT_THROW(write(packing, "/proc/aggpack_export_test.stl"), IoError);
  EXPECT_FALSE(std::filesystem::exists("/proc/aggpack_export_test.stl"));
  std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
  // Only the files written on purpose remain: no temporaries.
  for (const auto& name : folder.entries()) {
    EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
  }
}

TEST(ExportDeterminism, SameBytesWithOneThreadAndWithAll) {
  const Packing packing = test::grid_packing(6, 5, 4, 77, /*share_shapes=*/false);
  ScratchFolder folder;
  for (ExportFormat format : all_formats()) {
    const std::string name = format_name(format);
    write(packing, folder.file("all." + name), {.format = format});
    {
      const ThreadLimit one(1);
      write(packing, folder.file("one." + name), {.format = format});
    }
    EXPECT_EQ(test::read_text(folder.file("all." + name)),
              test::read_text(folder.file("one." + name)))
        << name;
  }
}

// The CLI: load a native file, export, refuse to overwrite, and a write that fails midway (file
// size limit) leaves neither the file nor a temporary behind.
TEST(ExportCli, ExportsNativeFileAndFailsCleanly) {
  const Packing packing = test::grid_packing(4, 3, 2, 12);
  ScratchFolder folder;
  const std::string native = folder.file("run.h5");
  write_packing(packing, native);
  const std::string binary = test::aggpack_binary();
  const std::string inp = folder.file("run.inp");
  auto run = [&](const std::string& arguments) {
    return test::run_command(binary + " export " + native + " " + arguments);
  };
  auto ok = run("-o " + inp + " --density 2600");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("24 particles"), std::string::npos) << ok.output;
  EXPECT_NE(test::read_text(inp).find("*DENSITY\n2600,"), std::string::npos);
  auto exists = run("-o " + inp);
  EXPECT_EQ(exists.exit_code, 3) << exists.output;
  EXPECT_NE(exists.output.find("use --force"), std::string::npos) << exists.output;
  EXPECT_EQ(run("-o " + inp + " --force --quadratic").exit_code, 0);
  EXPECT_NE(test::read_text(inp).find("C3D10"), std::string::npos);
  auto bad = run("-o " + folder.file("x.stl") + " --scale -2");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("scale"), std::string::npos) << bad.output;
  EXPECT_EQ(run("-o " + folder.file("x.vtu") + " --format nope").exit_code, 2);
  auto per = run("-o " + folder.file("prints") + " --format stl --per-particle --scale 1000");
  ASSERT_EQ(per.exit_code, 0) << per.output;
  EXPECT_TRUE(std::filesystem::exists(folder.file("prints/P000024.stl")));
  // 8 KiB limit: the .vtu needs far more. SIGXFSZ is ignored so the write fails with EFBIG and
  // aggpack reports it instead of being killed.
  const auto limited = test::run_command("trap '' XFSZ; ulimit -f 16; " + binary + " export " +
                                         native + " -o " + folder.file("big.vtu"));
  EXPECT_EQ(limited.exit_code, 3) << limited.output;
  EXPECT_NE(limited.output.find("cannot write " + folder.file("big.vtu") +
                                ": file too large (file size limit)"),
            std::string::npos)
      << limited.output;
  EXPECT_FALSE(std::filesystem::exists(folder.file("big.vtu")));
  for (const auto& name : folder.entries()) {
    EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace aggpack
