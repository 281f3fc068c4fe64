#pragma once

namespace gauss {

// The one definition of pi for the library (M_PI is not standard C++, and each file defining its own
// clashed in a unity build).
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace gauss
