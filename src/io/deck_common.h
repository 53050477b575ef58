#pragma once
// Internals shared by the deck writers (src/io/deck_*.cpp): the trough test's geometry and times
// in output units, each particle's bounding sphere, bounded-width numbers and the common header.
// Not a public header.

#include <string>
#include <string_view>
#include <vector>

#include "export_detail.h"

namespace aggpack::detail {

/// The trough test of a deck, in output units (lengths and speeds times options.scale).
struct Trough {
  Vec3 lower = Vec3::Zero();  ///< trough start x, side wall y, floor z
  Vec3 upper = Vec3::Zero();  ///< trough end x, other side wall y, top of the walls z
  double baffle = 0.0;        ///< x of the baffle at the start
  double baffle_speed = 0.0;  ///< toward +x in stage 2
  double gravity = 0.0;       ///< along -z
  double friction = 0.0;
  double settle_time = 0.0;     ///< s, stage 1
  double baffle_time = 0.0;     ///< s, stage 2: (upper.x - baffle) / baffle_speed
  double rest_time = 0.0;       ///< s, stage 3
  double largest_radius = 0.0;  ///< largest particle bounding radius

  [[nodiscard]] double travel() const { return upper.x() - baffle; }
  [[nodiscard]] double end_time() const { return settle_time + baffle_time + rest_time; }
  [[nodiscard]] Vec3 extent() const { return upper - lower; }
};

/// A particle's bounding sphere about its centroid, and its bounding box (output units).
struct ParticleBounds {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  Aabb box;
};

/// Bounding spheres and boxes of every particle of the view.
std::vector<ParticleBounds> particle_bounds(const ExportModel& model);

/// The trough around the particles from the deck options.
/// \throw InvalidInput naming the option when the baffle would cut a particle or the trough ends
///        before the baffle.
Trough make_trough(const ExportModel& model, const std::vector<ParticleBounds>& bounds);

/// `value` in at most `width` (>= 7) characters: append_number_fitting (text_number.h).
std::string deck_number(double value, int width = kFeNumberWidth);

/// `value` right-aligned in a fixed field of `width` characters (LS-DYNA cards), as deck_number
/// in width - 1 characters so that a blank always separates fields.
std::string deck_field(double value, int width);

/// The header every deck starts with: what it models, the units, material, friction, the trough,
/// the stages and their times, what the user may want to change, then `extra` (solver lines),
/// each line prefixed with `comment` ("** ", "$ ", "# ").
std::string deck_header(const ExportModel& model, const Trough& trough, std::string_view solver,
                        std::string_view run_command, std::string_view comment,
                        const std::vector<std::string>& extra);

// One writer per deck; each writes the mesh (or bodies) and the model.
void write_deck_abaqus(const ExportModel& model, std::ostream& out);
void write_deck_calculix(const ExportModel& model, std::ostream& out);
void write_deck_lsdyna(const ExportModel& model, std::ostream& out);
void write_deck_yade(const ExportModel& model, std::ostream& out);

}  // namespace aggpack::detail
