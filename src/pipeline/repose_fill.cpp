// The fill of the angle-of-repose test, made by the pipeline (when the simulation module is
// built): the one place the CLI's repose/sweep and the Python module get it from.

#include "aggpack/pipeline/pipeline.h"

namespace aggpack {

#ifdef AGGPACK_HAS_SIM
PackResult repose_fill(const ReposeOptions& options) {
  return pack(PackerOptions{repose_fill_options(options)});
}
#endif

}  // namespace aggpack
