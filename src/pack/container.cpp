// Container operations: each one dispatches to the kind the container holds. The geometry of a
// kind lives in its own file (container_box.cpp, container_cylinder.cpp); this file only knows
// the list (ContainerShape in packing.h).
#include "aggpack/pack/container.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

template <class K>
ContainerKindInfo kind_info() {
  static_assert(ContainerKindType<K>, "a container kind must provide every operation");
  ContainerKindInfo info{
      K::kName, K::kDescription,     K::kSummary,
      {},       Container{K{}, 0.0}, [](const Container& c) { return c.get_if<K>() != nullptr; }};
  for (const KindParam<K>& param : K::params()) {
    const auto member = param.member;
    info.params.push_back({param.name, param.description,
                           [member](const Container& c) {
                             const K* kind = c.get_if<K>();
                             return kind != nullptr ? kind->*member : K{}.*member;
                           },
                           [member](Container& c, double value) {
                             if (K* kind = c.get_if<K>()) kind->*member = value;
                           }});
  }
  return info;
}

template <class... K>
std::vector<ContainerKindInfo> all_kinds(const std::variant<K...>*) {
  return {kind_info<K>()...};
}

}  // namespace

const std::vector<ContainerKindInfo>& container_kinds() {
  static const std::vector<ContainerKindInfo> kinds =
      all_kinds(static_cast<const ContainerShape*>(nullptr));
  return kinds;
}

const ContainerKindInfo& container_kind_info(const Container& container) {
  return container_kinds().at(container.shape.index());
}

const ContainerKindInfo* find_container_kind(std::string_view name) {
  for (const auto& info : container_kinds()) {
    if (name == info.name) return &info;
  }
  return nullptr;
}

std::string container_kind_names() {
  std::string text;
  const auto& kinds = container_kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    if (k > 0) text += k + 1 == kinds.size() ? " or " : ", ";
    text += kinds[k].name;
  }
  return text;
}

Aabb Container::bounds() const {
  return visit([](const auto& kind) { return kind.bounds(); });
}

double Container::volume() const {
  return visit([](const auto& kind) { return kind.volume(); });
}

void validate(const Container& container) {
  if (!std::isfinite(container.wall_gap) || container.wall_gap < 0.0) {
    throw InvalidInput("container.wall_gap", format_value(container.wall_gap),
                       Wording{Sentence::kFiniteAtLeastZero, {}});
  }
  for (const ContainerParam& param : container_kind_info(container).params) {
    require_positive(std::string("container.") + param.name, param.get(container));
  }
  const double smallest = container.visit([](const auto& kind) { return kind.smallest_extent(); });
  if (2.0 * container.wall_gap >= smallest) {
    throw InvalidInput("container.wall_gap", format_value(container.wall_gap),
                       {Sentence::kBelowHalfExtent, {format_value(smallest / 2.0)}});
  }
}

std::array<bool, 3> periodic_axes(const Container& container) {
  const BoxContainer* box = container.get_if<BoxContainer>();
  return box != nullptr ? box->periodic : std::array<bool, 3>{};
}

bool is_periodic(const Container& container) {
  const std::array<bool, 3> axes = periodic_axes(container);
  return axes[0] || axes[1] || axes[2];
}

const std::vector<std::string>& periodic_words() {
  static const std::vector<std::string> words{"none", "x", "y", "z", "xy", "xz", "yz", "xyz"};
  return words;
}

std::string periodic_word(const std::array<bool, 3>& axes) {
  std::string word;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (axes[axis]) word += "xyz"[axis];
  }
  return word.empty() ? "none" : word;
}

bool parse_periodic_word(std::string_view word, std::array<bool, 3>& axes) {
  for (const std::string& each : periodic_words()) {
    if (word != each) continue;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      axes[axis] = each.find("xyz"[axis]) != std::string::npos;
    }
    return true;
  }
  return false;
}

ImageShifts image_shifts(const Container& container, const Vec3& point, double reach) {
  ImageShifts result;
  result.shifts[0] = Vec3::Zero();
  result.count = 1;
  const std::array<bool, 3> axes = periodic_axes(container);
  if (!(axes[0] || axes[1] || axes[2])) return result;
  const Aabb box = container.bounds();
  const Vec3 extent = box.extent();
  // Per axis the shifts (in units of the extent) whose image can be within reach of the box.
  std::array<std::array<int, 3>, 3> steps{};
  std::array<int, 3> counts{};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto a = static_cast<int>(axis);
    steps[axis][counts[axis]++] = 0;
    if (!axes[axis]) continue;
    if (point[a] + extent[a] - reach < box.upper[a]) steps[axis][counts[axis]++] = 1;
    if (point[a] - extent[a] + reach > box.lower[a]) steps[axis][counts[axis]++] = -1;
  }
  for (int i = 0; i < counts[0]; ++i) {
    for (int j = 0; j < counts[1]; ++j) {
      for (int k = 0; k < counts[2]; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        result.shifts[static_cast<std::size_t>(result.count++)] =
            Vec3(steps[0][static_cast<std::size_t>(i)] * extent.x(),
                 steps[1][static_cast<std::size_t>(j)] * extent.y(),
                 steps[2][static_cast<std::size_t>(k)] * extent.z());
      }
    }
  }
  return result;
}

void require_periodic_room(const Container& container, double largest_radius, double gap) {
  const std::array<bool, 3> axes = periodic_axes(container);
  const Vec3 extent = container.bounds().extent();
  const double needed = 2.0 * largest_radius + gap;
  static constexpr std::array<const char*, 3> kExtentKeys{"container.length", "container.width",
                                                          "container.depth"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (axes[axis] && !(extent[static_cast<int>(axis)] > needed)) {
      throw InvalidInput("container.periodic", "\"" + periodic_word(axes) + "\"",
                         {Sentence::kPeriodicRoom,
                          {format_value(needed), kExtentKeys[axis],
                           format_value(extent[static_cast<int>(axis)])}});
    }
  }
}

void refuse_periodic(const Container& container, const std::string& what) {
  if (is_periodic(container)) {
    throw InvalidInput("container.periodic", "\"" + periodic_word(periodic_axes(container)) + "\"",
                       {Sentence::kPeriodicUnsupported, {"\"none\"", what}});
  }
}

double wall_clearance(const Container& container, const Vec3& point) {
  return container.visit([&point](const auto& kind) { return kind.clearance(point); });
}

double wall_clearance(const Container& container, const ConvexPolyhedron& body, const Pose& pose) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const Vec3& vertex : body.vertices()) {
    clearance = std::min(clearance, wall_clearance(container, pose.apply(vertex)));
  }
  return clearance;
}

bool contains(const Container& container, const ConvexPolyhedron& body, const Pose& pose) {
  const Mat3 rotation = pose.rotation.toRotationMatrix();
  return container.visit([&](const auto& kind) {
    return kind.contains(body, rotation, pose.position, container.wall_gap);
  });
}

Aabb centre_region(const Container& container, double radius) {
  const double margin = radius + container.wall_gap;
  const std::array<bool, 3> axes = periodic_axes(container);
  Aabb region = container.bounds();
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (axes[axis]) continue;  // no walls: the whole extent
    region.lower[static_cast<int>(axis)] += margin;
    region.upper[static_cast<int>(axis)] -= margin;
  }
  return region;
}

bool is_in_centre_region(const Container& container, double radius, const Vec3& centre) {
  const double margin = radius + container.wall_gap;
  return container.visit(
      [&](const auto& kind) { return kind.is_in_centre_region(margin, centre); });
}

double container_slab_volume(const Container& container, int axis, double lo, double hi) {
  if (axis < 0 || axis > 2) throw InvalidInput("axis", std::to_string(axis), "0, 1 or 2");
  const Aabb box = container.bounds();
  lo = std::max(lo, box.lower[axis]);
  hi = std::min(hi, box.upper[axis]);
  if (hi <= lo) return 0.0;
  return container.visit([&](const auto& kind) { return kind.slab_volume(axis, lo, hi); });
}

bool centre_region_is_bounds(const Container& container) {
  return container.visit(
      []<class K>(const K&) { return static_cast<bool>(K::kCentreRegionIsBounds); });
}

double container_floor_area(const Container& container) {
  return container.visit([](const auto& kind) { return kind.floor_area(); });
}

std::vector<ContainerWall> container_walls(const Container& container, double thickness,
                                           double min_height) {
  return container.visit([&](const auto& kind) { return kind.walls(thickness, min_height); });
}

std::vector<OutlineSegment> container_outline(const Container& container) {
  return container.visit([](const auto& kind) { return kind.outline(); });
}

Vec3 container_ratio(const Container& from, const Container& other) {
  return from.visit([&other]<class K>(const K& kind) {
    const K* same = other.get_if<K>();
    if (same == nullptr) {
      throw InvalidInput("container kind", container_kind_info(other).name,
                         std::string("the same kind (") + K::kName + ")");
    }
    return kind.ratio(*same);
  });
}

std::vector<Vec3> container_prism_floor(const Container& container, int sides) {
  return container.visit([sides](const auto& kind) { return kind.prism_floor(sides); });
}

Aabb prism_bounds(const Container& container, int sides) {
  Aabb box;
  for (const Vec3& p : container_prism_floor(container, sides)) box.expand(p);
  box.expand(Vec3(box.lower.x(), box.lower.y(), container.bounds().upper.z()));
  return box;
}

bool is_on_prism_side(const Container& container, const Vec3& point, int sides, double tolerance) {
  return container.visit(
      [&](const auto& kind) { return kind.is_on_prism_side(point, sides, tolerance); });
}

std::string prism_summary(const Container& container, int sides) {
  std::string text =
      container.visit([]<class K>(const K&) { return std::string(K::kPrismSummary); });
  const std::size_t slot = text.find("{}");
  if (slot != std::string::npos) text.replace(slot, 2, std::to_string(sides));
  return text;
}

Container container_scaled(const Container& container, const Vec3& factor) {
  Container result = container;
  result.shape = container.visit(
      [&factor](const auto& kind) -> ContainerShape { return kind.scaled(factor); });
  return result;
}

}  // namespace aggpack
