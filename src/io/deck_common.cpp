// The trough test shared by the decks: geometry, times, bounded numbers and the common header.

#include "deck_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "aggpack/core/error.h"

namespace aggpack::detail {

std::vector<ParticleBounds> particle_bounds(const ExportModel& model) {
  std::vector<ParticleBounds> bounds(model.size());
  const double scale = model.options().scale;
  std::vector<Vec3> nodes;
  for (std::size_t k = 0; k < model.size(); ++k) {
    model.surface_nodes(k, nodes);
    ParticleBounds& b = bounds[k];
    // Stored shapes have their centroid at the origin, so the centroid is the pose's position.
    b.centre = scale * model.packing().particles[model.particle_index(k)].pose.position;
    b.box = Aabb{nodes.front(), nodes.front()};
    for (const Vec3& node : nodes) {
      b.radius = std::max(b.radius, (node - b.centre).norm());
      b.box.lower = b.box.lower.cwiseMin(node);
      b.box.upper = b.box.upper.cwiseMax(node);
    }
  }
  return bounds;
}

Trough make_trough(const ExportModel& model, const std::vector<ParticleBounds>& bounds) {
  const ExportOptions& options = model.options();
  const DeckOptions& deck = options.deck;
  const double scale = options.scale;
  if (bounds.empty()) {
    throw InvalidInput(Wording{Sentence::kDeckField, {}}, Wording{Sentence::kEmptyPacking, {}},
                       Wording{Sentence::kAtLeastOneParticle, {}});
  }
  const Aabb container = model.packing().container.bounds();
  Trough t;
  t.lower = scale * container.lower;
  t.upper = scale * container.upper;
  for (const ParticleBounds& b : bounds) {
    t.lower = t.lower.cwiseMin(b.box.lower);
    t.upper = t.upper.cwiseMax(b.box.upper);
    t.largest_radius = std::max(t.largest_radius, b.radius);
  }
  const double particles_end = t.upper.x();
  t.baffle = particles_end;
  if (deck.baffle_position > 0.0) {
    t.baffle = scale * deck.baffle_position;
    if (t.baffle < particles_end) {
      throw InvalidInput("baffle position", format_value(deck.baffle_position),
                         Wording{Sentence::kBehindBaffle, {format_value(particles_end / scale)}});
    }
  }
  t.upper.x() = t.lower.x() + 2.0 * (t.baffle - t.lower.x());
  if (deck.trough_length > 0.0) {
    t.upper.x() = t.lower.x() + scale * deck.trough_length;
    if (!(t.upper.x() > t.baffle)) {
      throw InvalidInput("trough length", format_value(deck.trough_length),
                         Wording{Sentence::kBeyondBaffle,
                                 {format_value((t.baffle - t.lower.x()) / scale),
                                  format_value(t.lower.x() / scale)}});
    }
  }
  t.gravity = scale * deck.gravity;
  t.baffle_speed = scale * deck.baffle_speed;
  t.friction = deck.friction;
  const double fall = (t.upper.z() - t.lower.z()) / scale;
  t.settle_time =
      deck.settle_time > 0.0 ? deck.settle_time : 2.0 * std::sqrt(2.0 * fall / deck.gravity);
  t.baffle_time = t.travel() / t.baffle_speed;
  t.rest_time = deck.rest_time;
  return t;
}

std::string deck_number(double value, int width) {
  std::string text;
  append_number_fitting(text, value, width);
  return text;
}

std::string deck_field(double value, int width) {
  std::string text = deck_number(value, width - 1);  // at least one blank between fields
  text.insert(0, static_cast<std::size_t>(width) - text.size(), ' ');
  return text;
}

std::string deck_header(const ExportModel& model, const Trough& t, std::string_view solver,
                        std::string_view run_command, std::string_view comment,
                        const std::vector<std::string>& extra) {
  const ExportOptions& options = model.options();
  const MaterialOptions& material = options.material;
  // Six significant digits for reading; the model data below carries the exact values.
  const auto n = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return std::string(text);
  };
  std::vector<std::string> lines = {
      "aggpack " AGGPACK_VERSION " " + std::string(solver) +
          " deck: the paper's trough test (angle of repose) with " + std::to_string(model.size()) +
          " particles.",
      "Run: " + std::string(run_command),
      "ASSUMPTIONS (change them here or with the export options named in brackets):",
      "- Units: SI (m, kg, s, N, Pa); lengths, gravity and speeds times the export scale " +
          n(options.scale) + " [--scale]. Density and modulus are written as given: convert",
      "  them yourself when the scale is not 1 (mm: t/mm^3 and MPa).",
      "- Particles: elastic, material " + material.name + ", density " + n(material.density) +
          ", Young's modulus " + n(material.youngs_modulus) + ", Poisson's ratio " +
          n(material.poisson_ratio) + " [--density --youngs-modulus --poisson-ratio].",
      "- Contact: Coulomb friction mu_s = " + n(t.friction) +
          " between particles and between particles and walls, penalty normal contact "
          "[--friction].",
      "- Gravity " + n(t.gravity) + " along -z [--gravity].",
      "- Trough: x " + n(t.lower.x()) + " .. " + n(t.upper.x()) + ", y " + n(t.lower.y()) + " .. " +
          n(t.upper.y()) + ", floor z = " + n(t.lower.z()) + ", walls up to z = " + n(t.upper.z()) +
          "; floor and walls rigid and fixed [--trough-length].",
      "- Baffle: the plane x = " + n(t.baffle) + " across the trough, rigid, particles behind it " +
          "[--baffle-position].",
      "- Step SETTLE, " + n(t.settle_time) +
          " s: the particles fall and settle, the baffle stands still [--settle-time].",
      "- Step BAFFLE, " + n(t.baffle_time) + " s: the baffle moves toward +x at " +
          n(t.baffle_speed) + " to the trough end (" + n(t.travel()) + ") [--baffle-speed].",
      "- Step REST, " + n(t.rest_time) + " s: the pile comes to rest [--rest-time]. End time " +
          n(t.end_time()) + " s.",
      "YOU MAY WANT TO CHANGE: the friction (the paper sweeps mu_s 0.05 .. 1.0); the settle time "
      "(the pile must be at rest before the baffle moves); a softer modulus or mass scaling (rock "
      "stiffness makes explicit time increments tiny); the output intervals. Then measure the "
      "angle of repose from the final pile's side view (aggpack repose does it for its own "
      "simulation)."};
  lines.insert(lines.end(), extra.begin(), extra.end());
  // Wrapped to 80 characters (LS-DYNA reads 80-column lines), continuations indented.
  const std::size_t width = 80 - comment.size();
  std::string out;
  for (const std::string& line : lines) {
    std::string_view rest = line;
    bool is_first = true;
    while (!rest.empty()) {
      const std::size_t room = is_first ? width : width - 4;
      std::size_t cut = rest.size();
      if (cut > room) {
        cut = rest.rfind(' ', room);
        if (cut == std::string_view::npos || cut == 0) cut = room;
      }
      out += comment;
      if (!is_first) out += "    ";
      out += rest.substr(0, cut);
      out += '\n';
      rest.remove_prefix(cut);
      while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
      is_first = false;
    }
  }
  return out;
}

}  // namespace aggpack::detail
