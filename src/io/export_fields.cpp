// Fixed-width fields and id limits shared by the exporters (export_detail.h).

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "export_detail.h"

namespace aggpack::detail {

void append_field(std::string& out, std::uint64_t value, int width) {
  char text[32];
  const int length =
      std::snprintf(text, sizeof text, "%*llu", width, static_cast<unsigned long long>(value));
  out.append(text, static_cast<std::size_t>(length));
}

void append_field(std::string& out, double value, int width) {
  // Width - 7 significant digits after the point leaves room for sign, "d.", and "e+NN".
  char text[48];
  const int length = std::snprintf(text, sizeof text, "%*.*e", width, width - 8, value);
  out.append(text, static_cast<std::size_t>(length));
}

void require_ids_fit(const ExportModel& model, std::uint64_t max_id, const std::string& format) {
  const std::uint64_t largest =
      std::max({model.node_count(), model.element_count(),
                static_cast<std::uint64_t>(model.particle_index(model.size()))});
  if (largest > max_id) {
    throw LimitExceeded(Wording{Sentence::kFormatIds, {format}},
                        Wording{Sentence::kText, {std::to_string(largest)}},
                        Wording{Sentence::kAtMost, {std::to_string(max_id)}});
  }
}

}  // namespace aggpack::detail
