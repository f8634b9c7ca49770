#pragma once
// Demo presets for log synthesis: analytic solids sliced by reference planes, so the curves
// obey the stroke rules (thesis 3.3.2) by construction.
//
//   "vase":   a surface of revolution r(z) with a four-lobed section (z up, z in [-1, 1]) and
//             an open cavity from z = 0.2 up; five horizontal sections (z = c), the two
//             above the cavity floor are rings (outer + inner curve, rule 2), plus the
//             profiles on x = 0 and y = 0 (rule 4 holds: they are slices of one solid).
//   "figure": a standing figure made of ellipsoids (torso, head, arms, legs); horizontal
//             sections through head, shoulders, arms, legs (several curves per plane, rule
//             1), and vertical sections x = 0, x = 0.17 (through a leg) and y = 0.
#include <string>
#include <string_view>
#include <vector>

#include "input/implicit_slice.h"
#include "input/log_synth.h"

namespace ps {

struct LogPreset {
  std::string name;
  Camera camera;              // initial camera (1280 x 800)
  std::vector<Plane> planes;  // initial reference planes (the three basic planes)
  std::vector<SketchStep> steps;
  ScalarField solid;          // the solid the curves slice (< 0 inside)
  double scale = 1.0;         // bounding-box diagonal of the solid, for tolerances
};

std::vector<std::string> log_preset_names();
Result<LogPreset> make_log_preset(std::string_view name);

// The preset's log with `seed` (generator text names the command that reproduces it).
Result<SynthResult> synthesize_preset(std::string_view name, std::uint32_t seed = SynthOptions{}.seed);
Result<SynthResult> synthesize_preset(const LogPreset& preset, std::uint32_t seed = SynthOptions{}.seed);

}  // namespace ps
