#pragma once
// Named styles: the Gauss images of simple solids, in a Z-up frame (Blender's), and Sheet Metal (a
// developable style, preference_function.h). Each preset is a StyleParams with the default sigma, mu and
// axis contribution (settings.h; Sheet Metal's sigma is settings::sheet_metal_sigma); callers override
// those.
//
// The preset table in presets.cpp is the one list of presets: preset_names(), gauss_core.PRESETS,
// the add-on's core_facts.json and the add-on's style enum all derive from it. Its order IS the
// registry of the enum numbers that saved .blend files store: append new presets at the end, never
// reorder, rename or remove one (a saved file would open with another style).
#include <string>
#include <vector>

#include "gauss/style/preference_function.h"
#include "gauss/settings.h"

namespace gauss {

// Preset names in table order (= UI order, = the saved enum numbers).
const std::vector<std::string>& preset_names();

// The named preset's normals/rings. Throws std::invalid_argument for an unknown name (the message
// lists the valid ones).
StyleParams preset_style(const std::string& name);

// The style every face has until told otherwise (GaussSolver, gauss_core.Solver): the preset
// settings::default_preset with the default sigma, mu and axis contribution.
inline StyleParams default_style() { return preset_style(settings::default_preset); }

}  // namespace gauss
