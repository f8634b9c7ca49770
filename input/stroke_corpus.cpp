// Labelled sculpting-stroke corpus (see stroke_corpus.h).
#include "input/stroke_corpus.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "input/log_synth.h"
#include "modeling/polygon_triangulate.h"

namespace ps {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kKnotMs = 70.0;

using Path = std::vector<Vec2>;

Vec2 rot(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

double noise(const std::vector<double>& k, double t_ms) { return knot_noise(k, t_ms, kKnotMs); }

std::vector<double> arc_lengths(const Path& p) {
  std::vector<double> cum(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) cum[i] = cum[i - 1] + (p[i] - p[i - 1]).norm();
  return cum;
}

Vec2 point_at(const Path& p, const std::vector<double>& cum, double s) {
  s = std::clamp(s, 0.0, cum.back());
  const auto it = std::upper_bound(cum.begin(), cum.end(), s);
  const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - cum.begin()), 1, cum.size() - 1);
  const double seg = cum[k] - cum[k - 1];
  const double f = seg > 0.0 ? (s - cum[k - 1]) / seg : 0.0;
  return p[k - 1] + f * (p[k] - p[k - 1]);
}

// The part of p between arc lengths s0 and s1.
Path sub_path(const Path& p, double s0, double s1) {
  const auto cum = arc_lengths(p);
  Path out{point_at(p, cum, s0)};
  for (std::size_t i = 0; i < p.size(); ++i)
    if (cum[i] > s0 && cum[i] < s1) out.push_back(p[i]);
  out.push_back(point_at(p, cum, s1));
  return out;
}

// Corners joined by straight legs, each corner rounded by a quadratic Bezier reaching
// `round` x the shorter adjacent leg along both legs.
Path rounded_polyline(const std::vector<Vec2>& c, double round) {
  Path out{c.front()};
  for (std::size_t i = 1; i + 1 < c.size(); ++i) {
    const double r = round * std::min((c[i] - c[i - 1]).norm(), (c[i + 1] - c[i]).norm());
    const Vec2 a = c[i] + r * (c[i - 1] - c[i]).normalized(), b = c[i] + r * (c[i + 1] - c[i]).normalized();
    for (int k = 0; k <= 8; ++k) {
      const double u = k / 8.0;
      out.push_back((1 - u) * (1 - u) * a + 2 * u * (1 - u) * c[i] + u * u * b);
    }
  }
  out.push_back(c.back());
  return out;
}

Path reversed(Path p) {
  std::reverse(p.begin(), p.end());
  return p;
}

class Generator {
 public:
  Generator(const StrokeCorpusOptions& o, std::vector<CorpusSilhouette> sil)
      : opt_(o), sil_(std::move(sil)), rng_(o.seed) {}

  double u(double lo, double hi) { return rng_.uniform(lo, hi); }
  bool coin(double p = 0.5) { return rng_.uniform() < p; }
  int pick(int n) { return std::min(n - 1, static_cast<int>(rng_.uniform() * n)); }

  const CorpusSilhouette& sil(std::size_t i) const { return sil_[i]; }

  // A random point inside silhouette s at least `margin` from its outline.
  Vec2 interior_point(const CorpusSilhouette& s, double margin) {
    Vec2 lo = s.outline.front(), hi = lo;
    for (const Vec2& p : s.outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const Vec2 p(u(lo.x(), hi.x()), u(lo.y(), hi.y()));
      if (s.inside(p) && s.boundary_distance(p) >= margin) return p;
    }
    return 0.5 * (lo + hi);
  }

  // === Closed loops
  Path closed_path(const CorpusSilhouette& s, std::string& kind, bool hard) {
    const int shape = pick(4);
    const double a = u(35.0, 190.0);
    const double b = a * u(0.35, 1.0);
    const Vec2 c = interior_point(s, 0.3 * a);
    const double turn = u(0.0, 2 * kPi), phase0 = u(0.0, 2 * kPi);
    const double dir = coin() ? 1.0 : -1.0;
    const double w1 = u(0.0, 0.1), w2 = u(0.0, 0.06), p1 = u(0.0, 6.3), p2 = u(0.0, 6.3);
    const double rho = u(0.45, 0.65);
    auto shape_at = [&](double phi) -> Vec2 {
      switch (shape) {
        case 0: return Vec2(a * std::cos(phi), b * std::sin(phi));
        case 1: {
          const double r = a * (1.0 + w1 * std::sin(2 * phi + p1) + w2 * std::sin(3 * phi + p2));
          return Vec2(r * std::cos(phi), r * std::sin(phi) * (b / a));
        }
        case 2: {
          const double cx = std::cos(phi), sy = std::sin(phi);
          return Vec2(a * std::copysign(std::sqrt(std::abs(cx)), cx), b * std::copysign(std::sqrt(std::abs(sy)), sy));
        }
        default: {  // five-pointed star outline
          const double seg = 2 * kPi / 10.0;
          const double x = std::fmod(phi, 2 * kPi) / seg;
          const int k = static_cast<int>(std::floor(x));
          const double f = x - k;
          auto vert = [&](int j) {
            const double r = (j % 2 == 0) ? a : rho * a;
            return Vec2(r * std::cos(j * seg), r * std::sin(j * seg));
          };
          return (1 - f) * vert(k) + f * vert(k + 1);
        }
      }
    };
    static const char* names[] = {"ellipse", "wobbly-loop", "rounded-square", "star"};
    kind = names[shape];
    // Closure: exact, overshoot, or a gap (hard: slow with a gap).
    const int n = 720;
    Path loop;
    for (int k = 0; k <= n; ++k) loop.push_back(c + rot(shape_at(phase0 + dir * 2 * kPi * k / n + (dir < 0 ? 2 * kPi * 4 : 0)), turn));
    const double per = arc_lengths(loop).back();
    const int closure = hard ? 2 : pick(3);
    Path p;
    if (closure == 0) {
      p = loop;
    } else if (closure == 1) {
      p = loop;
      const double over = u(0.02, 0.15) * per;
      const auto cum = arc_lengths(loop);
      for (std::size_t i = 1; i < loop.size() && cum[i] < over; ++i) p.push_back(loop[i]);
      kind += "-overshoot";
    } else {
      const double gap = hard ? u(12.0, 30.0) : std::min(u(3.0, 25.0), 0.05 * per);
      p = sub_path(loop, 0.0, per - gap);
      kind += hard ? "-slow-gap" : "-gap";
    }
    return p;
  }

  // === Scratch-outs
  Path scratch_path(const CorpusSilhouette& s, std::string& kind) {
    const int legs = 4 + pick(6);  // 3-8 reversals
    const double w = u(30.0, 160.0);
    const double d = w * u(0.0, 0.25) / legs * 2.0;
    const Vec2 c = interior_point(s, 0.3 * w);
    const double turn = u(0.0, 2 * kPi);
    std::vector<Vec2> corners;
    for (int j = 0; j <= legs; ++j) {
      const double side = (j % 2 == 0 ? -0.5 : 0.5) * w * u(0.85, 1.15);
      corners.push_back(c + rot(Vec2(side, (j - 0.5 * legs) * d + u(-0.05, 0.05) * w), turn));
    }
    kind = "scratch-" + std::to_string(legs - 1);
    return rounded_polyline(corners, u(0.03, 0.2));
  }

  // An open curve of length L along direction `turn` centred at c: line, bow or wave.
  Path open_curve(const Vec2& c, double L, double turn, int type, double bow, double amp, double cycles,
                  double phase) {
    Path p;
    const int n = std::max(50, static_cast<int>(L));
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      double y = 0.0;
      if (type >= 1) y += bow * L * std::sin(kPi * t);
      if (type == 2) y += amp * std::sin(2 * kPi * cycles * t + phase);
      p.push_back(c + rot(Vec2((t - 0.5) * L, y), turn));
    }
    return p;
  }

  // === Cutting strokes: across the silhouette, ends outside it
  bool cutting_path(const CorpusSilhouette& s, bool hard, Path& out, std::string& kind) {
    const Vec2 c = interior_point(s, 10.0);
    const int type = pick(3);
    const double turn = u(0.0, 2 * kPi), bow = u(-0.15, 0.15), cycles = u(2.0, 5.0);
    const double L = 2000.0;
    const double amp = u(0.02, 0.12) * 500.0 / cycles;
    const Path full = open_curve(c, L, turn, type, bow * 0.3, amp, cycles * 4.0, u(0.0, 6.3));
    const auto cum = arc_lengths(full);
    std::size_t first = full.size(), last = 0;
    for (std::size_t i = 0; i < full.size(); ++i)
      if (s.inside(full[i])) first = std::min(first, i), last = i;
    if (first >= full.size()) return false;
    const double m0 = hard && coin() ? u(4.0, 9.0) : u(4.0, 80.0);
    const double m1 = hard ? u(4.0, 9.0) : u(4.0, 80.0);
    out = sub_path(full, cum[first] - m0, cum[last] + m1);
    for (const Vec2& e : {out.front(), out.back()})
      if (s.inside(e) || s.boundary_distance(e) < 4.0 || e.x() < 2 || e.y() < 2 || e.x() > opt_.width - 2 ||
          e.y() > opt_.height - 2)
        return false;
    static const char* names[] = {"cut-line", "cut-bow", "cut-wave"};
    kind = std::string(names[type]) + (hard ? "-just-outside" : "");
    return true;
  }

  // === Deformation strokes: on the model
  bool deformation_path(const CorpusSilhouette& s, int hard_kind, Path& out, std::string& kind) {
    const double turn = u(0.0, 2 * kPi);
    double L = u(40.0, 380.0);
    const Vec2 c = interior_point(s, 10.0);
    if (hard_kind == 1) {  // long wavy stroke
      L = u(200.0, 450.0);
      const double cycles = u(2.0, 6.0);
      out = open_curve(c, L, turn, 2, u(-0.05, 0.05), u(0.04, 0.18) * L / cycles, cycles, u(0.0, 6.3));
      kind = "long-wavy";
    } else if (hard_kind == 2) {  // zig-zag with only 2 reversals
      const double w = u(40.0, 160.0), d = w * u(0.1, 0.4);
      std::vector<Vec2> corners;
      for (int j = 0; j < 4; ++j)
        corners.push_back(c + rot(Vec2((j % 2 == 0 ? -0.5 : 0.5) * w * u(0.85, 1.15), (j - 1.5) * d), turn));
      out = rounded_polyline(corners, u(0.03, 0.2));
      kind = "zigzag-2";
    } else if (hard_kind == 3) {  // ends 4-7 px inside the outline
      const Vec2 dirv = rot(Vec2(1.0, 0.0), turn);
      const double target = u(4.0, 7.0);
      Path p{c};
      while (p.size() < 4000) {
        const Vec2 q = p.back() + dirv;
        if (!s.inside(q) || s.boundary_distance(q) < target) break;
        p.push_back(q);
      }
      if (p.size() < 30) return false;
      const double back = std::min(u(40.0, 250.0), 20.0 * s.boundary_distance(c));
      Path head;
      for (double t = back; t > 0.0; t -= 1.0) head.push_back(c - t * dirv);
      head.insert(head.end(), p.begin(), p.end());
      out = head;
      kind = "just-inside";
    } else {
      const int type = pick(3);
      const double cycles = u(1.0, 4.0);
      out = open_curve(c, L, turn, type, u(-0.2, 0.2), u(0.03, 0.15) * L / cycles, cycles, u(0.0, 6.3));
      static const char* names[] = {"deform-line", "deform-bow", "deform-wave"};
      kind = names[type];
    }
    const double margin = hard_kind == 3 ? 3.5 : 6.0;
    for (const Vec2& p : out)
      if (!s.inside(p) || s.boundary_distance(p) < margin) return false;
    return true;
  }

  // === Drawing a path as pen samples
  std::vector<PenSample> draw(const Path& path) {
    const auto cum = arc_lengths(path);
    const double total = cum.back();
    const double speed = std::exp(u(std::log(opt_.min_speed_px_s), std::log(opt_.max_speed_px_s)));
    const double jitter = u(0.0, opt_.max_jitter_px);
    const double dt = opt_.sample_interval_ms;
    const double duration = std::max(total / speed * 1000.0, 3.0 * dt);
    const std::size_t ns = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(duration / dt)) + 1);
    const double span = static_cast<double>(ns - 1) * dt;
    const std::size_t nk = static_cast<std::size_t>(span / kKnotMs) + 3;
    const auto jx = rng_.knots(nk), jy = rng_.knots(nk), jp = rng_.knots(nk);
    std::vector<PenSample> out;
    for (std::size_t k = 0; k < ns; ++k) {
      const double t = static_cast<double>(k) * dt;
      const double tau = static_cast<double>(k) / static_cast<double>(ns - 1);
      const double ease = 0.75 * tau + 0.25 * tau * tau * (3.0 - 2.0 * tau);
      const Vec2 p = point_at(path, cum, ease * total) + jitter * Vec2(noise(jx, t), noise(jy, t)) +
                     0.3 * jitter * Vec2(u(-1.0, 1.0), u(-1.0, 1.0));
      PenSample s;
      s.t = t;
      // Quarter-pixel positions, as tablets report them; keeps the logs' numbers short.
      s.x = std::round(4.0 * p.x()) / 4.0;
      s.y = std::round(4.0 * p.y()) / 4.0;
      const double env = smoothstep(t / 90.0) * smoothstep((span - t) / 70.0);
      s.pressure = std::clamp(std::round((0.05 + 0.6 * (1.0 + 0.2 * noise(jp, t)) * env) * 1024.0) / 1024.0, 0.0, 1.0);
      s.tilt_x = 28.0;
      s.tilt_y = -14.0;
      s.phase = k == 0 ? Phase::kDown : (k + 1 == ns ? Phase::kUp : Phase::kMove);
      if (s.phase == Phase::kUp) s.pressure = 0.0;
      out.push_back(s);
    }
    return out;
  }

  // The whole corpus.
  std::vector<LabelledStroke> run() {
    std::vector<LabelledStroke> all;
    const StrokeClass classes[] = {StrokeClass::kClosed, StrokeClass::kScratchOut, StrokeClass::kOpenCutting,
                                   StrokeClass::kOpenDeformation};
    for (int i = 0; i < opt_.per_class; ++i)
      for (StrokeClass cls : classes) {
        LabelledStroke ls;
        ls.label = cls;
        ls.silhouette = static_cast<std::size_t>(i) % sil_.size();
        const CorpusSilhouette& s = sil_[ls.silhouette];
        const bool hard = coin(opt_.hard_fraction);
        Path p;
        for (int attempt = 0; attempt < 500; ++attempt) {
          bool ok = true;
          if (cls == StrokeClass::kClosed) p = closed_path(s, ls.kind, hard);
          else if (cls == StrokeClass::kScratchOut) p = scratch_path(s, ls.kind);
          else if (cls == StrokeClass::kOpenCutting) ok = cutting_path(s, hard, p, ls.kind);
          else ok = deformation_path(s, hard ? 1 + pick(3) : 0, p, ls.kind);
          bool in_window = true;
          for (const Vec2& q : p)
            in_window = in_window && q.x() >= 2 && q.y() >= 2 && q.x() <= opt_.width - 2 && q.y() <= opt_.height - 2;
          if (ok && in_window) break;
          p.clear();
        }
        if (p.size() < 2) continue;
        if (coin()) p = reversed(p);
        ls.samples = draw(p);
        all.push_back(std::move(ls));
      }
    return all;
  }

 private:
  StrokeCorpusOptions opt_;
  std::vector<CorpusSilhouette> sil_;
  SynthRandom rng_;
};

}  // namespace

bool CorpusSilhouette::inside(const Vec2& p) const { return point_in_polygon_2d(p, outline); }

double CorpusSilhouette::boundary_distance(const Vec2& p) const {
  double best = 1e300;
  const std::size_t n = outline.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = outline[i], d = outline[(i + 1) % n] - a;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - p).norm());
  }
  return best;
}

std::vector<CorpusSilhouette> corpus_silhouettes(int width, int height) {
  const Vec2 c(0.5 * width, 0.5 * height);
  const double r = 0.33 * std::min(width, height);
  std::vector<CorpusSilhouette> out(3);
  out[0].name = "disc";
  out[1].name = "ellipse";
  out[2].name = "blob";
  const int n = 256;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * k / n;
    out[0].outline.push_back(c + r * Vec2(std::cos(t), std::sin(t)));
    out[1].outline.push_back(c + rot(Vec2(1.55 * r * std::cos(t), 0.8 * r * std::sin(t)), 0.35));
    const double rb = 1.05 * r * (1.0 + 0.32 * std::cos(3 * t) + 0.08 * std::sin(2 * t));
    out[2].outline.push_back(c + rb * Vec2(std::cos(t), std::sin(t)));
  }
  return out;
}

std::vector<LabelledStroke> make_stroke_corpus(const StrokeCorpusOptions& options) {
  Generator g(options, corpus_silhouettes(options.width, options.height));
  return g.run();
}

std::vector<Vec2> stroke_positions(const std::vector<PenSample>& samples) {
  std::vector<Vec2> out;
  out.reserve(samples.size());
  for (const PenSample& s : samples)
    if (s.phase == Phase::kDown || s.phase == Phase::kMove || s.phase == Phase::kUp) out.emplace_back(s.x, s.y);
  return out;
}

StrokeLog corpus_log(const std::vector<LabelledStroke>& strokes, int width, int height, const std::string& generator) {
  StrokeLog log;
  log.header.viewport_width = width;
  log.header.viewport_height = height;
  log.header.camera.width = width;
  log.header.camera.height = height;
  log.header.generator = generator;
  double t = 0.0;
  auto push = [&](Event e) {
    log.events.emplace_back();
    log.events.back().t = t;
    log.events.back().event = std::move(e);
  };
  push(SetToolMode{"sculpt"});
  for (const LabelledStroke& ls : strokes) {
    if (ls.samples.empty()) continue;
    t += 600.0;
    PenSample prox = ls.samples.front();
    prox.t = t;
    prox.phase = Phase::kProximityIn;
    prox.pressure = 0.0;
    push(prox);
    t += 80.0;
    const double t0 = t;
    for (PenSample s : ls.samples) {
      s.t = t0 + s.t;
      t = s.t;
      push(s);
    }
    t += 100.0;
    prox = ls.samples.back();
    prox.t = t;
    prox.phase = Phase::kProximityOut;
    prox.pressure = 0.0;
    push(prox);
  }
  return log;
}

std::string format_stroke_labels(const StrokeLabels& labels) {
  nlohmann::ordered_json j;
  j["silhouette"] = nlohmann::ordered_json::array();
  for (const Vec2& p : labels.silhouette) j["silhouette"].push_back({p.x(), p.y()});
  j["labels"] = nlohmann::ordered_json::array();
  for (StrokeClass c : labels.labels) j["labels"].push_back(std::string(stroke_class_name(c)));
  return j.dump() + "\n";
}

Result<StrokeLabels> parse_stroke_labels(const std::string& text, const std::string& name) {
  using R = Result<StrokeLabels>;
  const auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return R::error(name + ": not a JSON object");
  StrokeLabels out;
  if (!j.contains("silhouette") || !j["silhouette"].is_array()) return R::error(name + ": 'silhouette' must be an array");
  for (const auto& p : j["silhouette"]) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      return R::error(name + ": silhouette points must be [x, y] numbers");
    out.silhouette.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  if (out.silhouette.size() < 3) return R::error(name + ": silhouette needs at least 3 points");
  if (!j.contains("labels") || !j["labels"].is_array()) return R::error(name + ": 'labels' must be an array");
  for (const auto& l : j["labels"]) {
    StrokeClass c;
    if (!l.is_string() || !parse_stroke_class(l.get<std::string>(), c))
      return R::error(name + ": unknown label " + l.dump());
    out.labels.push_back(c);
  }
  return out;
}

}  // namespace ps
