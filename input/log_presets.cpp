// Demo presets: a vase and a figure, sliced from analytic solids.
#include "input/log_presets.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

// === Vase: surface of revolution with a four-lobed section and an open cavity

constexpr double kVaseBottom = -1.0, kVaseTop = 1.0, kCavityFloor = 0.2, kLobes = 0.08;

double vase_radius(double z) {
  const double belly = 0.28 * std::exp(-std::pow((z + 0.3) / 0.45, 2.0));
  const double neck = 0.12 * std::exp(-std::pow((z - 0.55) / 0.25, 2.0));
  const double lip = 0.1 * std::pow(std::max(0.0, (z - 0.7) / 0.3), 2.0);
  return 0.45 + belly - neck + lip;
}

double cavity_radius(double z) {
  return z > kCavityFloor ? 0.38 * std::sqrt((z - kCavityFloor) / (kVaseTop - kCavityFloor)) : 0.0;
}

double vase_field(const Vec3& p) {
  const double rho = std::hypot(p.x(), p.y());
  const double lobes = 1.0 + kLobes * std::cos(4.0 * std::atan2(p.y(), p.x()));
  const double outer = std::max({rho - vase_radius(p.z()) * lobes, kVaseBottom - p.z(), p.z() - kVaseTop});
  const double cavity = std::max(rho - cavity_radius(p.z()) * lobes, kCavityFloor - p.z());
  return std::max(outer, -cavity);
}

// === Figure: union of ellipsoids

struct Ellipsoid {
  Vec3 c;
  Eigen::Matrix3d axes;  // rows: unit axes
  Vec3 r;                // semi-axes along those rows

  double field(const Vec3& p) const {
    const Vec3 q = axes * (p - c);
    const double s = std::sqrt((q.array() / r.array()).square().sum());
    return (s - 1.0) * r.minCoeff();  // roughly the distance near the surface
  }
};

Ellipsoid box_ellipsoid(const Vec3& c, const Vec3& r) { return {c, Eigen::Matrix3d::Identity(), r}; }

// A limb from a to b with radius rad, its ends extended by `overhang`.
Ellipsoid limb(const Vec3& a, const Vec3& b, double rad, double overhang) {
  const Vec3 axis = (b - a).normalized();
  const Vec3 side = axis.cross(Vec3::UnitY()).norm() > 0.1 ? axis.cross(Vec3::UnitY()).normalized()
                                                            : axis.cross(Vec3::UnitX()).normalized();
  Eigen::Matrix3d m;
  m.row(0) = axis.transpose();
  m.row(1) = side.transpose();
  m.row(2) = axis.cross(side).transpose();
  return {0.5 * (a + b), m, Vec3(0.5 * (b - a).norm() + overhang, rad, rad)};
}

std::vector<Ellipsoid> figure_parts() {
  std::vector<Ellipsoid> e;
  e.push_back(box_ellipsoid(Vec3(0, 0, 0.2), Vec3(0.36, 0.22, 0.5)));   // torso
  e.push_back(box_ellipsoid(Vec3(0, 0, 0.84), Vec3(0.16, 0.18, 0.22)));  // head
  for (double sx : {-1.0, 1.0}) {
    e.push_back(limb(Vec3(sx * 0.3, 0, 0.55), Vec3(sx * 0.62, 0, -0.15), 0.09, 0.05));   // arm
    e.push_back(limb(Vec3(sx * 0.16, 0, -0.2), Vec3(sx * 0.26, 0, -1.25), 0.12, 0.03));  // leg
  }
  return e;
}

// === Building presets

Camera preset_camera(const Vec3& eye, const Vec3& target) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.up = Vec3::UnitZ();
  c.fov_y_deg = 40.0;
  c.width = 1280;
  c.height = 800;
  return c;
}

struct PlaneSpec {
  int axis;
  double offset;
};

Result<std::vector<SketchStep>> slice_steps(const ScalarField& f, const std::vector<PlaneSpec>& specs,
                                            const Vec3& centre, double half_extent) {
  std::vector<SketchStep> steps;
  for (const PlaneSpec& sp : specs) {
    Plane pl{Vec3::Unit(sp.axis), sp.offset};
    auto loops = slice_implicit(f, pl, SliceWindow{centre, half_extent, 360});
    if (!loops)
      return Result<std::vector<SketchStep>>::error("slice " + std::string(1, "xyz"[sp.axis]) + " = " +
                                                    std::to_string(sp.offset) + ": " + loops.message());
    if (loops->empty())
      return Result<std::vector<SketchStep>>::error("slice " + std::string(1, "xyz"[sp.axis]) + " = " +
                                                    std::to_string(sp.offset) + " misses the solid");
    steps.push_back(SketchStep{sp.axis, sp.offset, std::move(*loops)});
  }
  return steps;
}

}  // namespace

std::vector<std::string> log_preset_names() { return {"vase", "figure"}; }

Result<LogPreset> make_log_preset(std::string_view name) {
  LogPreset p;
  p.name = std::string(name);
  p.planes = LogHeader::default_reference_planes();
  std::vector<PlaneSpec> specs;
  Vec3 centre;
  double half = 1.0;
  if (name == "vase") {
    p.solid = vase_field;
    p.camera = preset_camera(Vec3(3.2, -4.2, 2.4), Vec3(0, 0, 0));
    specs = {{2, -0.7}, {2, -0.3}, {2, 0.1}, {2, 0.5}, {2, 0.85}, {0, 0.0}, {1, 0.0}};
    centre = Vec3::Zero();
    half = 1.25;
    p.scale = Vec3(2 * 0.8, 2 * 0.8, 2.0).norm();
  } else if (name == "figure") {
    const auto parts = figure_parts();
    p.solid = [parts](const Vec3& q) {
      double f = 1e300;
      for (const Ellipsoid& e : parts) f = std::min(f, e.field(q));
      return f;
    };
    p.camera = preset_camera(Vec3(3.5, -5.0, 2.0), Vec3(0, 0, -0.1));
    specs = {{2, 0.86}, {2, 0.45}, {2, 0.0}, {2, -0.6}, {2, -1.0}, {1, 0.0}, {0, 0.0}, {0, 0.17}};
    centre = Vec3(0, 0, -0.1);
    half = 1.5;
    p.scale = Vec3(1.5, 0.5, 2.5).norm();
  } else {
    return Result<LogPreset>::error("unknown preset '" + std::string(name) + "' (vase, figure)");
  }
  auto steps = slice_steps(p.solid, specs, centre, half);
  if (!steps) return Result<LogPreset>::error(p.name + ": " + steps.message());
  p.steps = std::move(*steps);
  return p;
}

Result<SynthResult> synthesize_preset(std::string_view name, std::uint32_t seed) {
  auto preset = make_log_preset(name);
  if (!preset) return preset.status();
  return synthesize_preset(*preset, seed);
}

Result<SynthResult> synthesize_preset(const LogPreset& preset, std::uint32_t seed) {
  SynthOptions opt;
  opt.seed = seed;
  opt.units = "unit";
  opt.generator = "planesketch synth-log --preset " + preset.name + " --seed " + std::to_string(seed);
  return synthesize_log(preset.camera, preset.planes, preset.steps, opt);
}

}  // namespace ps
