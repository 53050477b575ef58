#pragma once
// Exporters: one entry point, write(packing, path, options), that turns a Packing into the files
// 3D printers, finite-element and DEM programs and ParaView read, or into the native .h5 file.
// The format comes from options.format or, when that is kAuto, from the extension of `path`.
// Every format is one row of export_formats() (src/io/export_formats.cpp): its names, extensions,
// what its files can hold and its writer; nothing else lists the formats. docs/formats.md gives
// the exact layout of every format.
//
// Common conventions:
//  - Coordinates are world coordinates (Packing::placed) times options.scale (1000 writes mm).
//  - Particles are numbered from 1 in every file: particle i of the Packing is "P<i+1>". Node and
//    element ids are global, count from 1 and run particle by particle (particle 1's nodes first).
//  - Every tetrahedron is positively oriented (see aggpack/mesh/tetrahedra.h).
//  - Files stream: each particle's mesh is built, written and dropped, in parallel batches whose
//    output order is fixed, so the output is byte-identical for any thread count.
//  - Files are written atomically: a failure leaves no partial file behind.

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/io/stl.h"
#include "aggpack/mesh/quality.h"
#include "aggpack/mesh/tetrahedra.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

namespace detail {
class ExportModel;
}
struct MesoMesh;         // mesh/mesomodel.h
struct MesoFileOptions;  // io/mesomodel_files.h
struct MesoFileSummary;

/// File formats: an id only; what a format is and does is its row in export_formats().
enum class ExportFormat {
  kAuto,       ///< from the extension of the output path
  kStl,        ///< STL surface, binary or ASCII (.stl)
  kRockDat,    ///< the paper's rock.dat: nodes and tetrahedra, comma separated (.dat)
  kAbaqus,     ///< Abaqus / CalculiX input file, C3D4 or C3D10 (.inp)
  kVtu,        ///< VTK XML unstructured grid, surfaces or tetrahedra (.vtu)
  kGmsh,       ///< Gmsh MSH 4.1 ASCII, tetrahedra or surfaces (.msh)
  kLsDyna,     ///< LS-DYNA keyword file (.k, .key)
  kAnsysApdl,  ///< ANSYS APDL macro with N and EN commands (.mac, .apdl)
  kObj,        ///< Wavefront OBJ surface (.obj)
  kYade,       ///< YADE Python script that rebuilds the packing as polyhedra (.py)
  kNative      ///< the native packing file (.h5, aggpack/io/native.h)
};

/// Which cells a format that can hold either (.vtu, .msh) gets.
enum class MeshCells {
  kDefault,    ///< .vtu: surfaces; .msh: tetrahedra
  kSurface,    ///< each particle's surface triangles
  kTetrahedra  ///< each particle's tetrahedra (options.tetrahedra says how they are made)
};

/// How an Abaqus file groups each particle.
enum class AbaqusLayout {
  /// One flat model (one *NODE and one *ELEMENT block per particle) with an element set and node
  /// set per particle. CalculiX (ccx) reads this form.
  kElementSets,
  /// One *PART per particle (its nodes, elements, sets, section and surface) and one *INSTANCE of
  /// it in the *ASSEMBLY. Abaqus/CAE's form; CalculiX does not read parts.
  kPartsInstances
};

/// Material written by the FE formats (.inp, .k, APDL, YADE). SI units: when options.scale is
/// not 1, convert these to the matching units yourself (e.g. mm, tonne, s: density in t/mm^3,
/// modulus in MPa).
struct MaterialOptions {
  std::string name = "AGGREGATE";  ///< letters, digits and _ only, <= 32 characters
  double density = 2700.0;         ///< kg/m^3, > 0
  double youngs_modulus = 50e9;    ///< Pa, > 0
  double poisson_ratio = 0.2;      ///< in (-1, 0.5)
};

/// Which complete, runnable solver model `write` produces around the mesh (`export --deck`).
/// Each is the paper's trough test (paper-notes.md, section 6) in the solver's terms; the deck's
/// own header lists what it assumes. Format: abaqus and calculix write .inp, lsdyna .k, yade .py.
enum class DeckKind {
  kNone,      ///< the mesh (or bodies) only
  kAbaqus,    ///< Abaqus/Explicit: rigid R3D4 walls, moving rigid baffle, general contact
  kCalculix,  ///< CalculiX: fixed floor/walls, moving baffle, contact pairs between neighbours
  kLsDyna,    ///< LS-DYNA: rigid walls, rigid moving baffle, automatic single-surface contact
  kYade       ///< YADE: walls, moving baffle wall, polyhedra engines, time step and O.run
};

/// The trough test a deck models. Lengths and speeds in metres (scaled by ExportOptions::scale
/// like the coordinates), times in seconds. The trough is x in [x0, trough end], y and z the
/// container's (or the particles', where they reach further) with the floor at the container's
/// bottom; the baffle stands at baffle_position, the particles behind it (x below).
/// Stage 1 (SETTLE, settle_time): the particles fall under gravity, baffle still. Stage 2
/// (BAFFLE): the baffle moves toward +x at baffle_speed until it reaches the trough end. Stage 3
/// (REST, rest_time): everything settles.
struct DeckOptions {
  DeckKind kind = DeckKind::kNone;
  double friction = 0.5;         ///< Coulomb mu_s, particle-particle and particle-wall, [0, 10]
  double gravity = 9.81;         ///< m/s^2, > 0, along -z
  double baffle_position = 0.0;  ///< m, x of the baffle; 0 = the container's (particles') end
  double trough_length = 0.0;    ///< m, from the trough's start; 0 = 2 x (baffle - start)
  double baffle_speed = 0.5;     ///< m/s toward +x in stage 2, > 0
  double settle_time = 0.0;      ///< s, stage 1; 0 = 2 x free fall of the highest particle
  double rest_time = 1.0;        ///< s, stage 3, >= 0
  /// CalculiX: particles whose bounding spheres are closer than this (m) get a contact pair, as
  /// do particles this close to a wall or the baffle; 0 = 0.5 x the largest particle radius.
  double contact_distance = 0.0;
  /// YADE: time step (s); 0 = 0.2 sqrt(m / (young pi r^2)) of the lightest particle (mass m,
  /// equivalent radius r; PolyhedraMat.young is the volumetric contact stiffness).
  double time_step = 0.0;
};

struct ExportOptions {
  ExportFormat format = ExportFormat::kAuto;
  double scale = 1.0;                        ///< multiply coordinates by this, > 0 (1000 = mm)
  Overwrite overwrite = Overwrite::kForbid;  ///< whether an existing file or folder is replaced
  /// STL and OBJ only: `path` is a folder (created; it must not exist unless overwrite allows)
  /// that gets one file per particle, named P000001.stl ... (zero-padded to the same width).
  bool is_per_particle = false;
  StlEncoding stl_encoding = StlEncoding::kBinary;  ///< STL only
  MeshCells cells = MeshCells::kDefault;            ///< .vtu and .msh only
  TetOptions tetrahedra = {};                       ///< how particles are cut into tetrahedra
  /// .inp only: 10-node tetrahedra (C3D10) with straight mid-side nodes instead of C3D4.
  bool is_quadratic = false;
  AbaqusLayout abaqus_layout = AbaqusLayout::kElementSets;  ///< .inp only
  MaterialOptions material = {};
  DeckOptions deck = {};    ///< a complete solver model instead of the mesh alone (.inp, .k, .py)
  int compression = 0;      ///< native .h5 only: deflate level of the datasets, 0 (none) .. 9
  bool write_xdmf = false;  ///< native .h5 only: also /world and the .xdmf side file (native.h)
  /// STL only, a periodic packing only: every particle and its periodic images clipped to the
  /// box (pack/cut_to_box.h), so copies of the file tile space; one solid per piece.
  bool is_cut_to_box = false;
};

/// A shape that TetGen could not mesh (--tet-method tetgen) and that was cut as the paper's
/// centroid fan instead, which always exists for a convex body.
struct TetGenFallback {
  std::uint32_t shape = 0;               ///< index into Packing::shapes (0-based)
  std::string failure;                   ///< what TetGen did (TetGenOutcome::failure)
  std::vector<std::uint64_t> particles;  ///< the written particles of this shape, 1-based (P<n>)
};

/// What write() produced.
struct ExportSummary {
  ExportFormat format = ExportFormat::kAuto;  ///< the format actually written
  std::uint64_t particles = 0;
  std::uint64_t nodes = 0;     ///< nodes (vertices) written, over all files
  std::uint64_t elements = 0;  ///< triangles or tetrahedra written, over all files
  std::uint64_t files = 0;
  std::uint64_t tetgen_shapes = 0;               ///< shapes given to TetGen (TetMethod::kTetGen)
  std::vector<TetGenFallback> tetgen_fallbacks;  ///< of those, the ones cut as fans, by shape
  /// Tetrahedral formats: the shape quality of every tetrahedron written (C3D10: of its straight
  /// linear tetrahedron); quality.tetrahedra == 0 for surface formats.
  TetQuality quality = {};
};

/// Writes `packing` to `path` in the chosen format, atomically. The native .h5 file too
/// (write_packing with options.overwrite, compression, write_xdmf; the same bytes).
/// \throw InvalidInput (options out of range, a format that cannot hold the request, e.g.
///        is_quadratic for STL, no format given and an unknown extension),
///        IoError (folder missing or not writable, file exists without Overwrite::kAllow, write
///        failure), LimitExceeded (more ids than the format can number). A shape TetGen fails
///        on does not throw: it is cut as a centroid fan and listed in tetgen_fallbacks.
ExportSummary write(const Packing& packing, const std::string& path,
                    const ExportOptions& options = {});

/// One row of the format table: everything aggpack knows about a format. Adding a format is one
/// row in export_formats() (src/io/export_formats.cpp) and its writer.
struct FormatInfo {
  ExportFormat format = ExportFormat::kAuto;
  /// Short name: messages, format_name(), --format, and the extension of per-particle files.
  std::string_view name;
  /// Its key in a config's [output] table (output_format_names()).
  std::string_view output_key;
  /// Other words naming it (--format, output extension), case-insensitive; the name and the
  /// output key are among name + aliases.
  std::vector<std::string_view> aliases;
  std::string_view title;  ///< for help texts, e.g. "Abaqus .inp"
  // What its files can hold.
  bool holds_packing = false;   ///< the whole Packing, read back by read_packing (native)
  bool has_surface = false;     ///< each particle's surface triangles
  bool has_tetrahedra = false;  ///< each particle's linear tetrahedra
  bool has_quadratic = false;   ///< 10-node tetrahedra (ExportOptions::is_quadratic)
  MeshCells default_cells = MeshCells::kDefault;  ///< cells written for MeshCells::kDefault
  bool has_per_particle = false;  ///< one file per particle in a folder (is_per_particle)
  bool has_ascii = false;         ///< binary or ASCII (stl_encoding)
  // The writer: exactly one of the two is set.
  /// Streams the particles of a mesh view (src/io/export_<format>.cpp); write() opens the file(s).
  void (*write_mesh)(const detail::ExportModel& model, std::ostream& out) = nullptr;
  /// Writes the whole file itself and counts it in `summary` (the native file).
  void (*write_file)(const Packing& packing, const std::string& path, const ExportOptions& options,
                     ExportSummary& summary) = nullptr;
  /// Writes a concrete mesomodel in this format (io/mesomodel_files.h, write_mesomodel with the
  /// same contract); nullptr when the format has none.
  MesoFileSummary (*write_mesomodel)(const std::string& path, const MesoMesh& mesh,
                                     const MesoFileOptions& options) = nullptr;
};

/// Every format, in documentation order (the order of docs/formats.md and of help texts).
const std::vector<FormatInfo>& export_formats();

/// The row of `format`. \throw InvalidInput for ExportFormat::kAuto.
const FormatInfo& format_info(ExportFormat format);

/// The names accepted as keys of a config's [output] table: every row's output_key, in table
/// order ("native" is the .h5 packing file).
const std::vector<std::string>& output_format_names();

/// One row of the deck table: a complete solver model written around a format's mesh.
struct DeckInfo {
  DeckKind kind = DeckKind::kNone;
  std::string_view name;                      ///< "calculix"
  std::string_view title;                     ///< the solver as its users name it: "CalculiX"
  std::vector<std::string_view> aliases;      ///< "ccx"
  ExportFormat format = ExportFormat::kAuto;  ///< the format the deck is written in
  /// The DeckOptions only this deck reads, by the names validate() gives them ("time step").
  std::vector<std::string_view> own_options = {};
  void (*write_mesh)(const detail::ExportModel& model, std::ostream& out) = nullptr;
};

/// Every deck (DeckKind::kNone has no row).
const std::vector<DeckInfo>& deck_kinds();

/// The format a name or extension denotes: a row's name or one of its aliases ("stl", "dat" or
/// "rock.dat", "inp" or "abaqus", "h5" or "native", ...); case-insensitive.
/// \throw InvalidInput listing the names.
ExportFormat parse_export_format(const std::string& name);

/// The format write() uses: options.format, or when that is kAuto the extension of `path`, or
/// STL for a per-particle folder without an extension. \throw InvalidInput as
/// format_from_extension.
ExportFormat resolve_format(const std::string& path, const ExportOptions& options);

/// The format chosen by the extension of `path`. \throw InvalidInput for an unknown extension.
ExportFormat format_from_extension(const std::string& path);

/// The deck a name denotes: "none", "abaqus", "calculix" (or "ccx"), "lsdyna" (or "ls-dyna"),
/// "yade"; case-insensitive. \throw InvalidInput listing the names.
DeckKind parse_deck_kind(const std::string& name);

/// Short name of a deck ("none", "abaqus", "calculix", "lsdyna", "yade").
std::string deck_name(DeckKind kind);

/// The cells a word names: "default", "surface", "tetrahedra" (`export --cells`). `field` names
/// the option in the message. \throw InvalidInput "invalid <field> = '<word>' (allowed: surface |
/// tetrahedra)".
MeshCells parse_mesh_cells(const std::string& word, const std::string& field);

/// The tetrahedra method a word names: "fan" or "tetgen" (`export --tet-method`).
/// \throw InvalidInput naming `field`.
TetMethod parse_tet_method(const std::string& word, const std::string& field);

/// The Abaqus layout a word names: "sets" or "parts" (`export --inp-layout`).
/// \throw InvalidInput naming `field`.
AbaqusLayout parse_abaqus_layout(const std::string& word, const std::string& field);

/// Short name of a format, its row's name ("stl", "dat", "inp", "vtu", "msh", "k", "mac", "obj",
/// "py", "h5").
std::string format_name(ExportFormat format);

/// Throws InvalidInput naming the field unless the options are usable for `format`.
void validate(const ExportOptions& options, ExportFormat format);

}  // namespace aggpack
