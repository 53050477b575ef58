// Export speed: 100,000 paper-size particles (alpha 0.5, r = L = 0.1 m, ~24 vertices and ~44
// triangles each, one shape per particle) written as binary STL, .vtu (surfaces and tetrahedra),
// Abaqus .inp, rock.dat and the other formats. Files go to $AGGPACK_BENCH_DIR (default /tmp) and
// are removed after each run. Bytes/s counters give the output rate.
//
//   build/bench/export_bench --benchmark_filter=Export

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "aggpack/core/parallel.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/shape/generator.h"

namespace {

using namespace aggpack;

const Packing& packing_of(std::size_t count) {
  static Packing packing;
  if (packing.particles.size() == count) return packing;
  packing = Packing{};
  const GeneratorOptions generator{
      .alpha = 0.5, .radius_min = 0.1, .radius_max = 0.1, .edge_length = 0.1, .seed = 1};
  packing.shapes.resize(count);
  auto make = [&](std::size_t i) {
    ConvexPolyhedron body = generate_particle(generator, i).body;
    packing.shapes[i] = body.translated(-mass_properties(body).centroid);
  };
  parallel_for_index(0, count, make);
  const auto side = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(count))));
  for (std::size_t i = 0; i < count; ++i) {
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(i);
    particle.pose.position =
        Vec3(0.25 * static_cast<double>(i % side), 0.25 * static_cast<double>((i / side) % side),
             0.25 * static_cast<double>(i / (side * side)));
    particle.control_radius = 0.1;
    packing.particles.push_back(particle);
  }
  return packing;
}

void export_to(benchmark::State& state, ExportOptions options, const std::string& name) {
  const Packing& packing = packing_of(static_cast<std::size_t>(state.range(0)));
  const char* folder = std::getenv("AGGPACK_BENCH_DIR");
  const std::string path = std::string(folder ? folder : "/tmp") + "/aggpack_bench_" + name;
  options.overwrite = Overwrite::kAllow;
  std::uintmax_t bytes = 0;
  ExportSummary summary;
  for (auto _ : state) {
    summary = write(packing, path, options);
    bytes = std::filesystem::file_size(path);
  }
  std::filesystem::remove(path);
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes) * state.iterations());
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["elements"] = static_cast<double>(summary.elements);
}

void BM_ExportStlBinary(benchmark::State& state) { export_to(state, {}, "p.stl"); }
void BM_ExportStlAscii(benchmark::State& state) {
  export_to(state, {.stl_encoding = StlEncoding::kAscii}, "a.stl");
}
void BM_ExportVtuSurface(benchmark::State& state) { export_to(state, {}, "s.vtu"); }
void BM_ExportVtuTetrahedra(benchmark::State& state) {
  export_to(state, {.cells = MeshCells::kTetrahedra}, "t.vtu");
}
void BM_ExportInpC3D4(benchmark::State& state) { export_to(state, {}, "p.inp"); }
void BM_ExportInpC3D10(benchmark::State& state) {
  export_to(state, {.is_quadratic = true}, "q.inp");
}
void BM_ExportRockDat(benchmark::State& state) { export_to(state, {}, "rock.dat"); }
void BM_ExportGmsh(benchmark::State& state) { export_to(state, {}, "p.msh"); }
void BM_ExportLsDyna(benchmark::State& state) { export_to(state, {}, "p.k"); }
void BM_ExportObj(benchmark::State& state) { export_to(state, {}, "p.obj"); }

#define EXPORT_BENCH(name) \
  BENCHMARK(name)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime()
EXPORT_BENCH(BM_ExportStlBinary);
EXPORT_BENCH(BM_ExportVtuSurface);
EXPORT_BENCH(BM_ExportInpC3D4);
EXPORT_BENCH(BM_ExportVtuTetrahedra);
EXPORT_BENCH(BM_ExportRockDat);
EXPORT_BENCH(BM_ExportStlAscii);
EXPORT_BENCH(BM_ExportInpC3D10);
EXPORT_BENCH(BM_ExportGmsh);
EXPORT_BENCH(BM_ExportLsDyna);
EXPORT_BENCH(BM_ExportObj);

}  // namespace

BENCHMARK_MAIN();
