#pragma once
// Synthesizes realistic stroke logs from known 3D curves (demo logs, test input).
//
// Each sketch step selects a reference plane, translates it to the step's offset, turns the
// camera to face the plane (the sketching tool faces the selected plane, thesis 3.2.1) and
// then draws the step's closed curves: proximity-in, down, moves every ~5 ms with pressure
// rising and falling, up, proximity-out. Pen positions are the curve points (plus a small,
// smooth, seeded in-plane jitter) projected through the camera with Camera::project, so every
// sample lifts back through the log's camera onto the selected plane onto exactly the drawn
// 3D point. Randomness is std::mt19937 with our own distribution code, so the output is the
// same with every standard library.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "input/stroke_log.h"
#include "modeling/status.h"

namespace ps {

struct SketchStep {
  int plane = 2;        // reference plane index (the log header's planes)
  double offset = 0.0;  // the plane is translated here before drawing
  std::vector<std::vector<Vec3>> curves;  // closed curves on that plane, drawn in order
};

struct SynthOptions {
  std::uint32_t seed = 20261122;
  double sample_interval_ms = 5.0;  // a 200 Hz tablet
  double speed_px_per_s = 550.0;    // mean pen speed along a stroke
  double jitter_px = 0.5;           // amplitude of the in-plane hand jitter, in pixels
  double face_tilt_deg = 15.0;      // facing view: angle between view direction and plane normal
  double fill = 0.6;                // fraction of the viewport a step's curves fill
  std::string units = "unit";
  std::string generator;            // written into the header
};

// One drawn stroke: which log events carry it and the 3D point each of them shows.
struct SynthStroke {
  std::size_t step = 0;
  std::size_t curve = 0;
  std::vector<std::size_t> events;  // indices into log.events: proximity-in, down..up, proximity-out
  std::vector<Vec3> drawn;          // same length as events; on the step's plane
};

struct SynthResult {
  StrokeLog log;
  std::vector<SynthStroke> strokes;
};

// `camera` is the initial camera (its width/height is the viewport); `planes` the initial
// reference planes. Fails, naming the step and curve, when a curve is not on its plane, has
// fewer than 3 points, or does not fit in the viewport.
Result<SynthResult> synthesize_log(const Camera& camera, const std::vector<Plane>& planes,
                                   const std::vector<SketchStep>& steps, const SynthOptions& options = {});

// The camera the synthesizer turns to before drawing `curves` on `plane`, coming from
// `current`: looks at the curves' centre from the side `current` is on, face_tilt_deg off the
// normal (leaning toward where `current` was), framing the curves to `fill` of the viewport.
Camera facing_camera(const Camera& current, const Plane& plane, const std::vector<std::vector<Vec3>>& curves,
                     double face_tilt_deg, double fill);

// Deterministic random numbers: std::mt19937 (its output sequence is fixed by the standard)
// with our own conversions, unlike std::uniform_real_distribution whose results differ
// between standard libraries.
class SynthRandom {
 public:
  explicit SynthRandom(std::uint32_t seed) : gen_(seed) {}
  double uniform();                          // [0, 1), 53 random bits
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Smooth noise in [-1, 1]: random knots every `knot_ms`, smoothstep between them.
  std::vector<double> knots(std::size_t count);

 private:
  std::mt19937 gen_;
};

// Hand-like smooth noise shared by the synthesizers: smoothstep x*x*(3-2x) of x clamped to
// [0, 1], and the value at time t_ms of knots spaced `knot_ms` apart, blended by smoothstep
// (knots in [-1, 1] give noise in [-1, 1]; at least two knots).
double smoothstep(double x);
double knot_noise(const std::vector<double>& knots, double t_ms, double knot_ms);

}  // namespace ps
