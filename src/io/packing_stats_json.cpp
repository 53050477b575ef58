#include "aggpack/io/packing_stats_json.h"

#include <nlohmann/json.hpp>

namespace aggpack {

namespace {

nlohmann::ordered_json summary_json(const SummaryStatistics& stats) {
  return {{"mean", stats.mean},
          {"standard_deviation", stats.standard_deviation},
          {"minimum", stats.minimum},
          {"maximum", stats.maximum},
          {"count", stats.count}};
}

std::string dump(const nlohmann::ordered_json& json, int indent) {
  // Non-finite numbers would come out as null; they cannot occur in valid statistics.
  return json.dump(indent < 0 ? -1 : indent) + (indent < 0 ? "" : "\n");
}

nlohmann::ordered_json grading_json(const std::vector<GradingPoint>& points) {
  nlohmann::ordered_json grading = nlohmann::ordered_json::array();
  for (const auto& point : points) {
    grading.push_back({{"size_m", point.size},
                       {"target_percent", point.target_percent},
                       {"achieved_percent", point.achieved_percent}});
  }
  return grading;
}

}  // namespace

std::string to_json(const PackingStatistics& statistics, int indent) {
  nlohmann::ordered_json json;
  json["particle_count"] = statistics.particle_count;
  json["shape_count"] = statistics.shape_count;
  json["solid_volume_m3"] = statistics.solid_volume;
  json["container_volume_m3"] = statistics.container_volume;
  json["solid_fraction"] = statistics.solid_fraction;
  nlohmann::ordered_json profiles = nlohmann::ordered_json::object();
  const char* names[3] = {"x", "y", "z"};
  for (const auto& profile : statistics.profiles) {
    profiles[names[profile.axis]] = {{"lower_m", profile.lower},
                                     {"bin_width_m", profile.bin_width},
                                     {"solid_fraction", profile.solid_fraction}};
  }
  json["profiles"] = profiles;
  json["grading"] = grading_json(statistics.grading);
  nlohmann::ordered_json descriptors = nlohmann::ordered_json::object();
  for (const auto& descriptor : statistics.descriptors) {
    nlohmann::ordered_json entry = summary_json(descriptor.stats);
    entry["unit"] = descriptor.unit;
    descriptors[descriptor.name] = entry;
  }
  json["descriptors"] = descriptors;
  return dump(json, indent);
}

std::string to_json(const PackReport& report, int indent) {
  nlohmann::ordered_json json;
  json["stop_reason"] = to_string(report.stop_reason);
  json["is_target_reached"] = report.is_target_reached;
  json["placed"] = report.placed;
  json["requested"] = report.requested;
  json["rejected"] = report.rejected;
  json["shrunk"] = report.shrunk;
  json["attempts"] = report.attempts;
  json["solid_volume_m3"] = report.solid_volume;
  json["container_volume_m3"] = report.container_volume;
  json["solid_fraction"] = report.solid_fraction;
  json["target_solid_fraction"] = report.target_solid_fraction;
  json["shape_seconds"] = report.shape_seconds;
  json["placement_seconds"] = report.placement_seconds;
  return dump(json, indent);
}

std::string to_json(const std::vector<GradingPoint>& grading, int indent) {
  return dump(grading_json(grading), indent);
}

std::string to_json(const DensifyReport& report, int indent) {
  nlohmann::ordered_json json;
  json["stop"] = to_string(report.stop);
  json["sweeps"] = report.sweeps;
  json["moves_tried"] = report.moves_tried;
  json["moves_accepted"] = report.moves_accepted;
  json["compressions"] = report.compressions;
  json["start_fraction"] = report.start_fraction;
  json["solid_fraction"] = report.solid_fraction;
  json["bulk_fraction"] = report.bulk_fraction;
  json["bulk_lower_m"] = report.bulk_lower;
  json["bulk_upper_m"] = report.bulk_upper;
  json["surface_height_m"] = report.surface_height;
  json["seconds"] = report.seconds;
  json["verified_pairs"] = report.verified_pairs;
  json["min_distance_m"] = report.min_distance;
  return dump(json, indent);
}

}  // namespace aggpack
