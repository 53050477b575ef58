// The Python module `import aggpack` (issue 17): the library's front end for scripts and
// notebooks, beside the CLI (app/cli) and the GUI (app/gui). Reference: docs/python.md.

#include "bindings.h"

PYBIND11_MODULE(aggpack, m) {
  namespace python = aggpack::python;
  m.doc() = R"doc(aggpack: irregular convex particles (the ARP paper's random aggregate growth),
packed into containers and exported.

  config = aggpack.pack_config({"packer": {"kind": "random"}})   # or TOML text, or None
  packing = aggpack.pack(config, progress=print)
  packing.positions, packing.rotations, packing.descriptors(), packing.statistics()
  packing.write("run.h5"); packing.export("run.vtu"); packing.render("run.png")

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
  python::register_render(m);
}
