// Stroke-log synthesis from known 3D curves (see log_synth.h).
#include "input/log_synth.h"

#include <algorithm>
#include <cmath>

namespace ps {

// === Random numbers

double SynthRandom::uniform() {
  const std::uint64_t a = gen_() >> 5;  // 27 bits
  const std::uint64_t b = gen_() >> 6;  // 26 bits
  return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b)) / 9007199254740992.0;
}

std::vector<double> SynthRandom::knots(std::size_t count) {
  std::vector<double> k(count);
  for (double& x : k) x = uniform(-1.0, 1.0);
  return k;
}

namespace {

constexpr double kKnotMs = 70.0;  // hand jitter and pressure wander at ~14 Hz

// Smooth noise in [-1, 1] from knots spaced kKnotMs apart.
double noise(const std::vector<double>& k, double t_ms) { return knot_noise(k, t_ms, kKnotMs); }

bool inside_viewport(const Camera& cam, const Vec3& p, double margin) {
  const auto q = cam.project(p);
  return q && q->x() >= margin && q->y() >= margin && q->x() <= cam.width - margin &&
         q->y() <= cam.height - margin && q->z() > -1.0 && q->z() < 1.0;
}

}  // namespace

// === Facing view (thesis 3.2.1: the view turns so the selected plane faces the user)

Camera facing_camera(const Camera& cur, const Plane& pl, const std::vector<std::vector<Vec3>>& curves,
                     double face_tilt_deg, double fill) {
  Box3 box;
  for (const auto& c : curves)
    for (const Vec3& p : c) box.extend(p);
  const Vec3 c = box.empty() ? pl.project(cur.target) : pl.project(box.center());
  const Vec3 n = pl.normal;
  const Vec3 d = n.dot(cur.eye - c) < 0.0 ? Vec3(-n) : n;  // stay on the side the user is on
  const Vec3 up_ref = std::abs(n.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitY();
  Vec3 w = (cur.eye - c) - (cur.eye - c).dot(d) * d;  // lean toward where the view was
  if (w.norm() < 1e-6 * std::max(1.0, (cur.eye - c).norm())) w = up_ref - up_ref.dot(d) * d;
  w.normalize();
  const double a = face_tilt_deg * M_PI / 180.0;
  const Vec3 dir = (std::cos(a) * d + std::sin(a) * w).normalized();  // from target to eye

  Camera cam = cur;
  cam.target = c;
  cam.up = up_ref;
  const Vec3 f = -dir;
  const Vec3 s = f.cross(cam.up).normalized();
  const Vec3 u = s.cross(f);
  double hw = 0.0, hh = 0.0, depth = 0.0;
  for (const auto& cv : curves)
    for (const Vec3& p : cv) {
      const Vec3 r = p - c;
      hw = std::max(hw, std::abs(s.dot(r)));
      hh = std::max(hh, std::abs(u.dot(r)));
      depth = std::max(depth, std::abs(f.dot(r)));
    }
  const double half = std::max({hh, hw / cam.aspect(), 1e-6});
  double dist;
  if (cam.orthographic) {
    cam.ortho_height = 2.0 * half / fill;
    dist = 3.0 * std::max(hw, hh) + depth + 1.0;
  } else {
    dist = half / (fill * std::tan(0.5 * cam.fov_y_deg * M_PI / 180.0)) + depth;
  }
  // Perspective enlarges the near side; back off until every point is well inside.
  for (int attempt = 0; attempt < 40; ++attempt) {
    cam.eye = c + dist * dir;
    cam.far_plane = std::max(cur.far_plane, 4.0 * (dist + depth));
    cam.near_plane = std::min(cur.near_plane, 0.1 * std::max(dist - depth, 1e-3));
    bool ok = true;
    for (const auto& cv : curves)
      for (const Vec3& p : cv) ok = ok && inside_viewport(cam, p, 0.05 * cam.height);
    if (ok) break;
    dist *= 1.15;
    if (cam.orthographic) cam.ortho_height *= 1.15;
  }
  return cam;
}

// === Synthesis

Result<SynthResult> synthesize_log(const Camera& camera, const std::vector<Plane>& planes,
                                   const std::vector<SketchStep>& steps, const SynthOptions& opt) {
  auto fail = [](const std::string& m) { return Result<SynthResult>::error(m); };
  if (!(opt.sample_interval_ms > 0.0) || !(opt.speed_px_per_s > 0.0) || !(opt.jitter_px >= 0.0) ||
      !(opt.fill > 0.0 && opt.fill <= 1.0) || !(std::abs(opt.face_tilt_deg) < 80.0))
    return fail("synth options out of range");
  SynthResult res;
  LogHeader& h = res.log.header;
  h.camera = camera;
  h.viewport_width = camera.width;
  h.viewport_height = camera.height;
  h.planes = planes;
  h.units = opt.units;
  h.generator = opt.generator;

  SynthRandom rng(opt.seed);
  std::vector<TimedEvent>& ev = res.log.events;
  Camera cam = camera;
  std::vector<Plane> cur_planes = planes;
  int selected = -1;
  double t = 0.0;
  auto push = [&](Event e) {
    if (auto* s = std::get_if<PenSample>(&e)) s->t = t;
    ev.push_back(TimedEvent{t, 0, std::move(e)});
    return ev.size() - 1;
  };
  push(SetToolMode{"sketch"});

  for (std::size_t si = 0; si < steps.size(); ++si) {
    const SketchStep& step = steps[si];
    const std::string where = "step " + std::to_string(si);
    if (step.plane < 0 || static_cast<std::size_t>(step.plane) >= cur_planes.size())
      return fail(where + ": no reference plane " + std::to_string(step.plane));
    Plane pl = cur_planes[static_cast<std::size_t>(step.plane)];
    pl.offset = step.offset;
    for (std::size_t ci = 0; ci < step.curves.size(); ++ci) {
      const auto& curve = step.curves[ci];
      if (curve.size() < 3) return fail(where + " curve " + std::to_string(ci) + ": fewer than 3 points");
      for (std::size_t k = 0; k < curve.size(); ++k) {
        const double dist = std::abs(pl.signed_distance(curve[k]));
        if (!curve[k].allFinite() || dist > 1e-9 * (1.0 + curve[k].norm()))
          return fail(where + " curve " + std::to_string(ci) + " point " + std::to_string(k) + " is " +
                      std::to_string(dist) + " off its plane");
      }
    }

    // === Plane and view
    t = std::round(t + rng.uniform(600.0, 900.0));
    if (selected != step.plane) {
      push(SelectPlane{step.plane});
      selected = step.plane;
      t += 150.0;
    }
    if (cur_planes[static_cast<std::size_t>(step.plane)].offset != step.offset) {
      push(TranslatePlane{step.plane, step.offset});
      cur_planes[static_cast<std::size_t>(step.plane)].offset = step.offset;
      t += 150.0;
    }
    cam = facing_camera(cam, pl, step.curves, opt.face_tilt_deg, opt.fill);
    push(CameraChange{cam});

    const double world_per_px =
        cam.orthographic ? cam.ortho_height / cam.height
                         : 2.0 * (cam.eye - cam.target).norm() * std::tan(0.5 * cam.fov_y_deg * M_PI / 180.0) /
                               cam.height;
    Vec3 pu, pv;
    pl.basis(pu, pv);

    for (std::size_t ci = 0; ci < step.curves.size(); ++ci) {
      const auto& src = step.curves[ci];
      const std::string where_c = where + " curve " + std::to_string(ci);
      // === Start where a hand would: the curve point highest on screen
      std::size_t start = 0;
      double best = 1e300, len_px = 0.0;
      for (std::size_t k = 0; k < src.size(); ++k) {
        const auto q = cam.project(src[k]);
        const auto q2 = cam.project(src[(k + 1) % src.size()]);
        if (!q || !q2) return fail(where_c + ": behind the camera");
        if (q->y() < best) best = q->y(), start = k;
        len_px += (q->head<2>() - q2->head<2>()).norm();
      }
      std::vector<Vec3> loop(src.size() + 1);
      for (std::size_t k = 0; k <= src.size(); ++k) loop[k] = src[(start + k) % src.size()];
      std::vector<double> cum(loop.size(), 0.0);
      for (std::size_t k = 1; k < loop.size(); ++k) cum[k] = cum[k - 1] + (loop[k] - loop[k - 1]).norm();
      const double total = cum.back();
      if (!(total > 0.0)) return fail(where_c + ": has zero length");
      auto point_at = [&](double s) -> Vec3 {
        s = std::clamp(s, 0.0, total);
        const auto it = std::upper_bound(cum.begin(), cum.end(), s);
        const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - cum.begin()), cum.size() - 1);
        const std::size_t k0 = k - 1;
        const double seg = cum[k] - cum[k0];
        const double f = seg > 0.0 ? (s - cum[k0]) / seg : 0.0;
        return loop[k0] + f * (loop[k] - loop[k0]);
      };

      // === Timing and the hand's wander
      const double dt = opt.sample_interval_ms;
      const double duration = std::clamp(len_px / opt.speed_px_per_s * 1000.0, 300.0, 10000.0);
      const std::size_t ns = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(duration / dt)) + 1);
      const double span = static_cast<double>(ns - 1) * dt;
      const std::size_t nk = static_cast<std::size_t>(span / kKnotMs) + 3;
      const auto jx = rng.knots(nk), jy = rng.knots(nk), jp = rng.knots(nk), tx = rng.knots(nk),
                 ty = rng.knots(nk);
      const double jitter = opt.jitter_px * world_per_px;

      SynthStroke st;
      st.step = si;
      st.curve = ci;
      auto emit = [&](Phase phase, const Vec3& p, double pressure, double local_t) -> Status {
        const auto q = cam.project(p);
        if (!q || q->x() < 0.0 || q->y() < 0.0 || q->x() > cam.width || q->y() > cam.height)
          return Status::error(where_c + ": leaves the viewport");
        PenSample s;
        s.x = q->x();
        s.y = q->y();
        // Tablets report pressure in levels and tilt in whole or quarter degrees; dyadic steps
        // also keep the log's numbers short.
        s.pressure = std::clamp(std::round(pressure * 1024.0) / 1024.0, 0.0, 1.0);
        s.tilt_x = std::round(4.0 * (28.0 + 4.0 * noise(tx, local_t))) / 4.0;
        s.tilt_y = std::round(4.0 * (-14.0 + 4.0 * noise(ty, local_t))) / 4.0;
        s.tool = Tool::kPen;
        s.phase = phase;
        st.events.push_back(push(s));
        st.drawn.push_back(p);
        return Status::ok();
      };

      t = std::round(t + rng.uniform(350.0, 600.0));
      std::vector<Vec3> drawn(ns);
      for (std::size_t k = 0; k < ns; ++k) {
        const double lt = static_cast<double>(k) * dt;
        const double tau = static_cast<double>(k) / static_cast<double>(ns - 1);
        const double ease = 0.75 * tau + 0.25 * tau * tau * (3.0 - 2.0 * tau);  // slower at both ends
        drawn[k] = point_at(ease * total) + jitter * (noise(jx, lt) * pu + noise(jy, lt) * pv);
      }
      if (auto s = emit(Phase::kProximityIn, drawn.front(), 0.0, 0.0); !s) return fail(s.message());
      t += std::round(rng.uniform(60.0, 120.0));
      const double t0 = t;
      for (std::size_t k = 0; k < ns; ++k) {
        const double lt = static_cast<double>(k) * dt;
        t = t0 + lt;
        const double envelope = smoothstep(lt / 90.0) * smoothstep((span - lt) / 70.0);
        const double pressure = 0.05 + 0.6 * (1.0 + 0.2 * noise(jp, lt)) * envelope;
        const Phase ph = k == 0 ? Phase::kDown : (k + 1 == ns ? Phase::kUp : Phase::kMove);
        if (auto s = emit(ph, drawn[k], ph == Phase::kUp ? 0.0 : pressure, lt); !s) return fail(s.message());
      }
      t += std::round(rng.uniform(80.0, 160.0));
      if (auto s = emit(Phase::kProximityOut, drawn.back(), 0.0, span); !s) return fail(s.message());
      res.strokes.push_back(std::move(st));
    }
  }
  return res;
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double knot_noise(const std::vector<double>& k, double t_ms, double knot_ms) {
  const double x = std::max(0.0, t_ms / knot_ms);
  const std::size_t i = std::min(static_cast<std::size_t>(x), k.size() - 2);
  const double f = smoothstep(x - static_cast<double>(i));
  return k[i] * (1.0 - f) + k[i + 1] * f;
}

}  // namespace ps
