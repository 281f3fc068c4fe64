// Prints the solver's settings table, its options, preset registry, methods and size limits (settings.h,
// presets.h) as JSON: the same facts gauss_core exports as DEFAULTS, LIMITS, PRESETS, METHODS and
// SIZE_LIMITS. The build writes this to the staged add-on's core_facts.json, which the add-on reads when
// the native module cannot be loaded (another Python, a missing runtime): its properties then still
// register with the solver's defaults and ranges.
#include <cstdio>
#include <string>

#include "gauss/style/presets.h"
#include "gauss/settings.h"

namespace {

// A JSON number that reads back as a Python float for real-valued settings (4.0, not 4).
std::string number(double v, bool integer) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  std::string out = text;
  if (!integer && out.find_first_of(".eE") == std::string::npos) out += ".0";
  return out;
}

}  // namespace

// usage: gauss_facts [OUT.json]   (default: standard output)
int main(int argc, char** argv) {
  namespace settings = gauss::settings;
  if (argc > 1 && std::freopen(argv[1], "w", stdout) == nullptr) {
    std::perror(argv[1]);
    return 1;
  }
  std::printf("{\n  \"DEFAULTS\": {");
  for (const gauss::Setting* s : settings::all)
    std::printf("\"%s\": %s, ", s->name, number(s->default_value, s->integer).c_str());
  for (const gauss::Option* o : settings::options)
    std::printf("\"%s\": %s, ", o->name, o->default_value ? "true" : "false");
  std::printf("\"preset\": \"%s\", \"method\": \"%s\"},\n  \"LIMITS\": {", settings::default_preset,
              settings::default_method);
  bool first = true;
  for (const gauss::Setting* s : settings::all) {
    std::printf("%s\"%s\": [%s, %s]", first ? "" : ", ", s->name, number(s->min, s->integer).c_str(),
                number(s->max, s->integer).c_str());
    first = false;
  }
  std::printf("},\n  \"PRESETS\": [");
  first = true;
  for (const std::string& name : gauss::preset_names()) {
    std::printf("%s\"%s\"", first ? "" : ", ", name.c_str());
    first = false;
  }
  std::printf("],\n  \"METHODS\": [");
  first = true;
  for (const char* name : settings::method_names) {
    std::printf("%s\"%s\"", first ? "" : ", ", name);
    first = false;
  }
  std::printf("],\n  \"SIZE_LIMITS\": {\"normals\": %d, \"rings\": %d}\n}\n", settings::max_style_normals,
              settings::max_style_rings);
  return 0;
}
