// Packing.export(path, **options): every format of the format table (aggpack/io/export.h), with
// the options of `aggpack export` as keywords (the flag's name with '_' for '-').

#include <pybind11/stl.h>

#include <functional>
#include <map>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

using Setter = std::function<void(ExportOptions&, const py::handle&)>;

template <class T>
T as(const py::handle& value, const char* name) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw InvalidInput(name, py::repr(value).cast<std::string>(),
                       std::is_same_v<T, bool>          ? "True or False"
                       : std::is_same_v<T, std::string> ? "a str"
                                                        : "a number");
  }
}

// Keyword -> how it sets the options. Words are parsed by the library's parsers, which name the
// keyword in their messages.
const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> table = {
      {"format",
       [](ExportOptions& o, const py::handle& v) {
         if (!v.is_none()) o.format = parse_export_format(as<std::string>(v, "format"));
       }},
      {"force",
       [](ExportOptions& o, const py::handle& v) {
         o.overwrite = as<bool>(v, "force") ? Overwrite::kAllow : Overwrite::kForbid;
       }},
      {"scale", [](ExportOptions& o, const py::handle& v) { o.scale = as<double>(v, "scale"); }},
      {"cut_to_box",
       [](ExportOptions& o, const py::handle& v) { o.is_cut_to_box = as<bool>(v, "cut_to_box"); }},
      {"per_particle",
       [](ExportOptions& o, const py::handle& v) {
         o.is_per_particle = as<bool>(v, "per_particle");
       }},
      {"ascii",
       [](ExportOptions& o, const py::handle& v) {
         o.stl_encoding = as<bool>(v, "ascii") ? StlEncoding::kAscii : StlEncoding::kBinary;
       }},
      {"cells",
       [](ExportOptions& o, const py::handle& v) {
         o.cells = parse_mesh_cells(as<std::string>(v, "cells"), "cells");
       }},
      {"tet_method",
       [](ExportOptions& o, const py::handle& v) {
         o.tetrahedra.method = parse_tet_method(as<std::string>(v, "tet_method"), "tet_method");
       }},
      {"max_volume",
       [](ExportOptions& o, const py::handle& v) {
         o.tetrahedra.max_volume = as<double>(v, "max_volume");
       }},
      {"radius_edge",
       [](ExportOptions& o, const py::handle& v) {
         o.tetrahedra.radius_edge_ratio = as<double>(v, "radius_edge");
       }},
      {"tet_time_limit",
       [](ExportOptions& o, const py::handle& v) {
         o.tetrahedra.time_limit = as<double>(v, "tet_time_limit");
       }},
      {"split_surface",
       [](ExportOptions& o, const py::handle& v) {
         o.tetrahedra.is_surface_kept = !as<bool>(v, "split_surface");
       }},
      {"quadratic",
       [](ExportOptions& o, const py::handle& v) { o.is_quadratic = as<bool>(v, "quadratic"); }},
      {"inp_layout",
       [](ExportOptions& o, const py::handle& v) {
         o.abaqus_layout = parse_abaqus_layout(as<std::string>(v, "inp_layout"), "inp_layout");
       }},
      {"material_name",
       [](ExportOptions& o, const py::handle& v) {
         o.material.name = as<std::string>(v, "material_name");
       }},
      {"density", [](ExportOptions& o,
                     const py::handle& v) { o.material.density = as<double>(v, "density"); }},
      {"youngs_modulus",
       [](ExportOptions& o, const py::handle& v) {
         o.material.youngs_modulus = as<double>(v, "youngs_modulus");
       }},
      {"poisson_ratio",
       [](ExportOptions& o, const py::handle& v) {
         o.material.poisson_ratio = as<double>(v, "poisson_ratio");
       }},
      {"deck",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.kind = parse_deck_kind(as<std::string>(v, "deck"));
       }},
      {"friction",
       [](ExportOptions& o, const py::handle& v) { o.deck.friction = as<double>(v, "friction"); }},
      {"gravity",
       [](ExportOptions& o, const py::handle& v) { o.deck.gravity = as<double>(v, "gravity"); }},
      {"baffle_position",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.baffle_position = as<double>(v, "baffle_position");
       }},
      {"trough_length",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.trough_length = as<double>(v, "trough_length");
       }},
      {"baffle_speed",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.baffle_speed = as<double>(v, "baffle_speed");
       }},
      {"settle_time",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.settle_time = as<double>(v, "settle_time");
       }},
      {"rest_time", [](ExportOptions& o,
                       const py::handle& v) { o.deck.rest_time = as<double>(v, "rest_time"); }},
      {"contact_distance",
       [](ExportOptions& o, const py::handle& v) {
         o.deck.contact_distance = as<double>(v, "contact_distance");
       }},
      {"time_step", [](ExportOptions& o,
                       const py::handle& v) { o.deck.time_step = as<double>(v, "time_step"); }},
      {"compression",
       [](ExportOptions& o, const py::handle& v) { o.compression = as<int>(v, "compression"); }},
      {"xdmf", [](ExportOptions& o, const py::handle& v) { o.write_xdmf = as<bool>(v, "xdmf"); }},
  };
  return table;
}

std::string keyword_names() {
  std::string text;
  for (const auto& entry : setters()) text += (text.empty() ? "" : ", ") + entry.first;
  return text;
}

py::dict summary_dict(const ExportSummary& summary) {
  py::dict result;
  result["format"] = format_name(summary.format);
  result["particles"] = summary.particles;
  result["nodes"] = summary.nodes;
  result["elements"] = summary.elements;
  result["files"] = summary.files;
  if (summary.quality.tetrahedra > 0) {
    py::dict quality;
    quality["tetrahedra"] = summary.quality.tetrahedra;
    quality["min_dihedral_degrees"] = summary.quality.min_dihedral_degrees;
    quality["max_aspect_ratio"] = summary.quality.max_aspect_ratio;
    quality["below_10_degrees"] = summary.quality.below_10_degrees;
    result["quality"] = quality;
  }
  if (summary.tetgen_shapes > 0) {
    result["tetgen_shapes"] = summary.tetgen_shapes;
    py::list fallbacks;
    for (const TetGenFallback& f : summary.tetgen_fallbacks) {
      py::dict entry;
      entry["shape"] = f.shape;
      entry["failure"] = f.failure;
      entry["particles"] = f.particles;
      fallbacks.append(entry);
    }
    result["tetgen_fallbacks"] = fallbacks;
  }
  return result;
}

}  // namespace

void register_export(py::module_& m) {
  auto packing = m.attr("Packing").cast<py::class_<PyPacking, std::shared_ptr<PyPacking>>>();
  packing.def(
      "export",
      [](const PyPacking& p, const std::string& path, const py::kwargs& keywords) {
        ExportOptions options;
        options.overwrite = Overwrite::kForbid;  // as the CLI without -f
        for (const auto& [key, value] : keywords) {
          const std::string name = key.cast<std::string>();
          const auto found = setters().find(name);
          if (found == setters().end()) {
            throw InvalidInput("export keyword", "'" + name + "'", keyword_names());
          }
          found->second(options, value);
        }
        options.format = resolve_format(path, options);
        validate(options, options.format);
        ExportSummary summary;
        {
          const py::gil_scoped_release release;
          summary = write(p.packing, path, options);
        }
        return summary_dict(summary);
      },
      py::arg("path"),
      R"doc(Writes the packing in any export format, as `aggpack export IN.h5 -o PATH` does (the
same bytes for the same options). The format comes from `format` or the extension of path: stl,
dat (rock.dat), inp (Abaqus/CalculiX), vtu, msh (Gmsh), k (LS-DYNA), mac (ANSYS APDL), obj, py
(YADE), h5 (native). Layouts: docs/formats.md. Particles are numbered P1, P2, ...

Keywords (the CLI flags, '-' written '_'; defaults as the CLI's): format; force=False (as the
CLI's -f: an existing file raises IoError unless force=True); scale=1.0 (1000 writes mm); per_particle=False
(stl/obj: one file per particle in the folder path); ascii=False (stl); cut_to_box=False (stl of
a periodic packing: particles and images clipped to the box); cells='default' |
'surface' | 'tetrahedra' (vtu, msh); tet_method='fan' | 'tetgen'; max_volume, radius_edge,
tet_time_limit, split_surface (tetgen); quadratic=False (inp: C3D10); inp_layout='sets' | 'parts';
material_name, density (kg/m^3), youngs_modulus (Pa), poisson_ratio; deck='none' | 'abaqus' |
'calculix' | 'lsdyna' | 'yade' with friction, gravity (m/s^2), baffle_position (m),
trough_length (m), baffle_speed (m/s), settle_time (s), rest_time (s), contact_distance (m),
time_step (s); compression (h5, 0..9), xdmf (h5).

Returns a dict: format, particles, nodes, elements, files (and quality for tetrahedra, tetgen
fallbacks). Raises InvalidInput naming the keyword, IoError.)doc");
}

}  // namespace aggpack::python
