#pragma once
// Left and right: the index of every per-foot (and per-arm) array in the project.
#include <array>

namespace biped {

enum class Side { Left = 0, Right = 1 };
inline constexpr std::array<Side, 2> kSides = {Side::Left, Side::Right};
inline constexpr int index_of(Side s) { return static_cast<int>(s); }
inline constexpr const char* name_of(Side s) { return s == Side::Left ? "left" : "right"; }
inline constexpr Side other(Side s) { return s == Side::Left ? Side::Right : Side::Left; }

}  // namespace biped
