// The Python module `import aggpack` (issue 17): the library's front end for scripts and
// notebooks, beside the CLI (app/cli) and the GUI (app/gui). Reference: docs/python.md.

#include "bindings.h"

PYBIND11_MODULE(aggpack, m) {
  namespace python = aggpack::python;
  m.doc() = R"doc(aggpack: irregular convex particles (the ARP paper's random aggregate growth),
packed into containers and exported.

  packing = aggpack.pack({"packer": {"kind": "random"}}, progress=print)  # or "run.toml"
  packing.positions, packing.rotations, packing.descriptors(), packing.statistics()
  packing.write("run.h5"); packing.export("run.vtu"); packing.render("run.png")

Main calls:
  pack(config, progress=None)        pack particles (config: PackConfig, dict or TOML path)
  pack_config(source, overrides)     a validated configuration (None = the paper's case)
  read(path)                         a saved packing (.h5)
  generate_particle(...), generate_particles(...)   grown particles and their descriptors
  repose(...), sweep(...)            the angle-of-repose test and its alpha x mu_s sweep
  merge(folder)                      the summary of an ensemble or sweep run in parts
  Packing.write / export / render / statistics / descriptors   (help(aggpack.Packing))

Units are SI (metres). Errors are aggpack.Error subclasses with the CLI's one-line messages.
Reference: docs/python.md.)doc";
  m.attr("__version__") = AGGPACK_VERSION;
  python::register_errors(m);
  python::register_particles(m);
  python::register_config(m);
  python::register_packing(m);
  python::register_pack(m);
  python::register_native(m);
  python::register_export(m);
  python::register_statistics(m);
  python::register_sim(m);
  python::register_study(m);
  python::register_render(m);
}
