#pragma once
// Named styles: the Gauss images of simple solids, in a Z-up frame (Blender's). Each preset is a
// StyleParams with default sigma = 4, mu = 1 and axis contribution 0.5; callers override those.
#include <string>
#include <vector>

#include "gauss/preference_function.h"

namespace gauss {

// Preset names in UI order: cube, tetrahedron, octahedron, dodecahedron, icosahedron,
// square_pyramid, truncated_pyramid, triangular_prism, hexagonal_prism, plane, cylinder, cone,
// double_cone.
const std::vector<std::string>& preset_names();

// Throws std::invalid_argument for an unknown name (the message lists the valid ones).
StyleParams preset_style(const std::string& name);

}  // namespace gauss
