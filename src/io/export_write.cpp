// The exporters' entry point write(): the format's row (export_formats()) says how. A mesh format
// gets a view of the particles (ExportModel) in one file or, per particle, in a folder that
// replaces the old one as a whole; a format that holds the packing writes its file itself.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "aggpack/core/child_process.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/cut_to_box.h"
#include "export_detail.h"

namespace aggpack {

namespace fs = std::filesystem;

namespace {

detail::ElementMode element_mode(const FormatInfo& info, const ExportOptions& options) {
  if (options.is_quadratic) return detail::ElementMode::kQuadraticTetrahedra;  // validate(): .inp
  const MeshCells cells = options.cells == MeshCells::kDefault ? info.default_cells : options.cells;
  return cells == MeshCells::kSurface ? detail::ElementMode::kSurface
                                      : detail::ElementMode::kTetrahedra;
}

// The writer of the deck the options ask for, else the format's.
auto mesh_writer(const FormatInfo& info, const ExportOptions& options) {
  for (const DeckInfo& deck : deck_kinds()) {
    if (deck.kind == options.deck.kind) return deck.write_mesh;
  }
  return info.write_mesh;
}

void write_one(const Packing& packing, const std::string& path, const ExportOptions& options,
               const FormatInfo& info, std::size_t first, std::size_t last, Overwrite overwrite,
               ExportSummary& summary) {
  const detail::ExportModel model(packing, options, element_mode(info, options), first, last);
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  try {
    mesh_writer(info, options)(model, out);
  } catch (const IoError&) {
    // A failed write (disk full, file size limit): name the file and the reason.
    if (!out.good()) throw IoError(file.write_error_wording());
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

void write_per_particle(const Packing& packing, const std::string& path,
                        const ExportOptions& options, const FormatInfo& info,
                        ExportSummary& summary) {
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
    throw IoError(Wording{status.type() == fs::file_type::symlink ? Sentence::kReplaceLinkByFolder
                                                                  : Sentence::kReplaceByFolder,
                          {target.string()}});
  }
  if (exists && options.overwrite != Overwrite::kAllow) {
    throw IoError(Wording{Sentence::kFolderExists, {target.string(), "--force"}});
  }
  TemporaryFolder staging(target.parent_path().string(), target.string());
  fs::permissions(staging.path(),
                  fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                      fs::perms::others_read | fs::perms::others_exec,
                  error);
  const std::size_t count = packing.particles.size();
  const int width = std::max<int>(6, static_cast<int>(std::to_string(count).size()));
  std::string extension = ".";
  extension += info.name;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string number = std::to_string(i + 1);
    std::string name = "P";
    name.append(static_cast<std::size_t>(width) - std::min<std::size_t>(width, number.size()), '0');
    name += number;
    name += extension;
    write_one(packing, staging.file(name), options, info, i, i + 1, Overwrite::kForbid, summary);
  }
  // Swap in the new folder; an old one is moved aside first and removed only afterwards, so at
  // every moment `target` is either the complete old or the complete new folder.
  if (exists) {
    TemporaryFolder old_parking(target.parent_path().string(), target.string());
    fs::remove(old_parking.path());
    // From here it holds the user's old folder: a signal must not empty it (at worst it stays
    // behind under its temporary name).
    old_parking.forget_on_signal();
    fs::rename(target, old_parking.path(), error);
    if (error) throw IoError(Wording{Sentence::kReplaceFailed, {target.string(), error.message()}});
    fs::rename(staging.path(), target, error);
    if (error) {
      fs::rename(old_parking.path(), target);
      throw IoError(Wording{Sentence::kRenameInto, {target.string(), error.message()}});
    }
  } else {
    fs::rename(staging.path(), target, error);
    if (error) throw IoError(Wording{Sentence::kRenameInto, {target.string(), error.message()}});
  }
  staging.release();
}

}  // namespace

ExportSummary write(const Packing& whole, const std::string& path, const ExportOptions& options) {
  const ExportFormat format = resolve_format(path, options);
  validate(options, format);
  // --cut-to-box: the pieces of the particles and their images inside the box are written as
  // particles of their own.
  std::optional<Packing> pieces;
  if (options.is_cut_to_box) pieces = cut_to_box(whole);
  const Packing& packing = pieces ? *pieces : whole;
  // A deck models the trough test with walls around the particles; a periodic box has none.
  if (options.deck.kind != DeckKind::kNone) refuse_periodic(packing.container, "--deck");
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    if (packing.particles[i].shape >= packing.shapes.size()) {
      throw InvalidInput("particle " + std::to_string(i) + " shape",
                         std::to_string(packing.particles[i].shape),
                         "< " + std::to_string(packing.shapes.size()));
    }
  }
  const FormatInfo& info = format_info(format);
  ExportSummary summary;
  summary.format = format;
  summary.particles = packing.particles.size();
  if (info.write_file != nullptr) {
    info.write_file(packing, path, options, summary);
  } else if (options.is_per_particle) {
    write_per_particle(packing, path, options, info, summary);
  } else {
    write_one(packing, path, options, info, 0, packing.particles.size(), options.overwrite,
              summary);
  }
  return summary;
}

}  // namespace aggpack
