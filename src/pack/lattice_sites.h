#pragma once
// Internal to the lattice packer (lattice_packer.cpp, lattice_files.cpp): the sites of a lattice.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aggpack/core/parallel.h"
#include "aggpack/pack/lattice_packer.h"

namespace aggpack::lattice_detail {

// One lattice: grid coordinates -> site index (-1 where a cylinder drops the site), site centres.
struct Lattice {
  std::array<std::uint32_t, 3> counts{};
  std::vector<Vec3> sites;
  std::vector<std::int64_t> index;  // over counts[0] * counts[1] * counts[2] grid points
  std::vector<std::array<std::int64_t, 3>> coordinates;  // per site
};

// Centre-to-centre spacing: options.spacing, or 2 R + gap when it is 0.
double effective_spacing(const LatticeOptions& options);

// The sites of the options' lattice (x fastest, then y, then z).
Lattice make_lattice(const LatticeOptions& options);

// The sites before site i (smaller index) whose centres are closer than reach to site i's, in
// grid order; spacing is the lattice's (effective_spacing).
std::vector<std::size_t> earlier_sites_within(const Lattice& lattice, std::size_t i, double reach,
                                              double spacing);

// Fills the report's counts, volumes, stop reason and seconds since start at the end of a run
// (done of site_count sites placed, solid = their volume summed in site order).
void finish_report(PackReport& report, const LatticeOptions& options, std::size_t site_count,
                   std::size_t done, double solid, bool was_cancelled,
                   std::chrono::steady_clock::time_point start);

// The lattice packer with shapes from mesh files (options.files.loaded; lattice_files.cpp).
PackResult pack_lattice_files(const LatticeOptions& options, const Lattice& lattice,
                              const PackControl& control);

}  // namespace aggpack::lattice_detail
