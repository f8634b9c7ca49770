// Contour file readers and writers (JSON, CSL, Ctr2Suf .contour). The CSL and .contour parsers
// are hand-written line/token parsers: both formats are tiny, no library reads them, and a
// hand-written parser can name the exact line of every problem. JSON goes through nlohmann_json.
#include "modeling/contour_io.h"

#include "modeling/curve_repair.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/section_validate.h"
#include "modeling/text_tokens.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace ps {
namespace {

using Warnings = std::vector<std::string>;

// Largest coordinate magnitude accepted: squared distances of such values stay finite.
constexpr double kMaxMagnitude = 1e100;
constexpr double kSilentProjection = 1e-6;  // of the bounding-box diagonal (contours.md)
constexpr double kWarnProjection = 1e-3;    // of the bounding-box diagonal (contours.md)
constexpr double kSamePlaneOffset = 1e-9;   // of the diagonal: planes closer are merged
constexpr double kSameNormal = 1e-12;       // 1 - |cos| below this: same direction

// Shortest text that reads back as the same double.
std::string num(double v) {
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::string short_num(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

bool finite3(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string_view strip_bom(std::string_view s) {
  if (s.size() >= 3 && static_cast<unsigned char>(s[0]) == 0xEF &&
      static_cast<unsigned char>(s[1]) == 0xBB && static_cast<unsigned char>(s[2]) == 0xBF)
    s.remove_prefix(3);
  return s;
}

// Non-blank lines with their 1-based line numbers.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(strip_bom(text)) {}
  // The next non-blank line (trimmed); false at the end.
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      const std::size_t e = std::min(text_.find('\n', pos_), text_.size());
      line = trim(text_.substr(pos_, e - pos_));
      pos_ = e + 1;
      ++line_;
      if (!line.empty()) return true;
    }
    return false;
  }
  int line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

// Whitespace-separated tokens with the line each one is on.
class TokenReader {
 public:
  explicit TokenReader(std::string_view text) : text_(strip_bom(text)) {}
  bool next(std::string_view& tok) {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    const std::size_t b = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    tok = text_.substr(b, pos_ - b);
    tok_line_ = line_;
    return true;
  }
  int line() const { return tok_line_; }      // line of the last token read
  int eof_line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int tok_line_ = 1;
};

// Twice the signed area of a closed 3D polygon projected on a plane with normal n.
double polygon_area2(const std::vector<Vec3>& pts, const Vec3& n) {
  Vec3 s = Vec3::Zero();
  const Vec3 o = pts.front();
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) s += (pts[i] - o).cross(pts[i + 1] - o);
  return s.dot(n);
}


}  // namespace

// === Format names
const char* contour_format_extension(ContourFormat format) {
  switch (format) {
    case ContourFormat::Json: return ".json";
    case ContourFormat::Csl: return ".csl";
    case ContourFormat::Ctr2Suf: return ".contour";
  }
  return "";
}

std::optional<ContourFormat> contour_format_from_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".json") return ContourFormat::Json;
  if (ext == ".csl") return ContourFormat::Csl;
  if (ext == ".contour") return ContourFormat::Ctr2Suf;
  return std::nullopt;
}

std::optional<ContourFormat> sniff_contour_format(std::string_view content) {
  const std::string_view t = trim(strip_bom(content));
  if (t.empty()) return std::nullopt;
  if (t.front() == '{') return ContourFormat::Json;
  if (t.substr(0, 4) == "CSLC") return ContourFormat::Csl;
  TokenReader tr(t);
  std::string_view tok;
  long long count = 0;
  if (!tr.next(tok) || !parse_int(tok, count) || count < 0) return std::nullopt;
  for (int k = 0; k < 4; ++k) {
    double v = 0;
    if (!tr.next(tok) || !parse_double(tok, v)) return count == 0 && k == 0 ? std::optional(ContourFormat::Ctr2Suf) : std::nullopt;
  }
  return ContourFormat::Ctr2Suf;
}

// === Common checks and repairs
Status finish_sections(SectionSet& set, const std::string& name, Warnings* warnings) {
  SectionSet s = set;
  Warnings w;
  // Planes: finite, unit normal (scaled by the largest component first so tiny and huge
  // normals normalise without underflow or overflow).
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    Plane& p = s.planes[i];
    const std::string where = name + ": plane " + std::to_string(i);
    if (!finite3(p.normal) || !std::isfinite(p.offset))
      return Status::error(where + ": normal or offset is not a finite number");
    const double m = p.normal.cwiseAbs().maxCoeff();
    if (m == 0.0) return Status::error(where + ": normal is zero");
    if (m > kMaxMagnitude || std::abs(p.offset) > kMaxMagnitude)
      return Status::error(where + ": normal or offset larger than 1e100 in magnitude");
    // Already unit length (to rounding): keep it, so normalising is idempotent and round
    // trips are bit-exact.
    if (std::abs(p.normal.norm() - 1.0) <= 4 * std::numeric_limits<double>::epsilon()) continue;
    Vec3 n = p.normal / m;
    double d = p.offset / m;
    const double len = n.norm();
    n /= len;
    d /= len;
    if (!std::isfinite(d) || std::abs(d) > kMaxMagnitude)
      return Status::error(where + ": offset too large for its normal (the plane lies beyond 1e100)");
    p.normal = n;
    p.offset = d;
  }
  // Curves: plane index and coordinates.
  Box3 box;
  for (std::size_t c = 0; c < s.curves.size(); ++c) {
    const auto& cv = s.curves[c];
    if (cv.plane < 0 || static_cast<std::size_t>(cv.plane) >= s.planes.size())
      return Status::error(name + ": curve " + std::to_string(c) + ": plane index " +
                           std::to_string(cv.plane) + " out of range (there are " +
                           std::to_string(s.planes.size()) + " planes)");
    for (std::size_t k = 0; k < cv.points.size(); ++k) {
      const Vec3& q = cv.points[k];
      if (!finite3(q))
        return Status::error(name + ": curve " + std::to_string(c) + ": point " + std::to_string(k) +
                             " has a non-finite coordinate");
      if (q.cwiseAbs().maxCoeff() > kMaxMagnitude)
        return Status::error(name + ": curve " + std::to_string(c) + ": point " + std::to_string(k) +
                             " has a coordinate larger than 1e100 in magnitude");
      box.extend(q);
    }
  }
  const double diag = box.diagonal();

  // Coincident planes: merge into the first, re-index curves.
  std::vector<int> remap(s.planes.size());
  std::vector<Plane> kept;
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    remap[i] = -1;
    const Plane& p = s.planes[i];
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const double cosang = kept[k].normal.dot(p.normal);
      if (1.0 - std::abs(cosang) > kSameNormal) continue;
      const double off = cosang > 0 ? p.offset : -p.offset;
      const double tol = diag > 0 ? kSamePlaneOffset * diag
                                  : 1e-12 * std::max({1.0, std::abs(off), std::abs(kept[k].offset)});
      if (std::abs(off - kept[k].offset) <= tol) {
        remap[i] = static_cast<int>(k);
        w.push_back(name + ": plane " + std::to_string(i) + " coincides with plane " +
                    std::to_string(std::find(remap.begin(), remap.end(), static_cast<int>(k)) - remap.begin()) +
                    "; merged (its curves now lie on that plane)");
        break;
      }
    }
    if (remap[i] < 0) {
      remap[i] = static_cast<int>(kept.size());
      kept.push_back(p);
    }
  }
  s.planes = kept;
  for (auto& cv : s.curves) cv.plane = remap[static_cast<std::size_t>(cv.plane)];

  // Per curve: closing repeat, duplicates, distance to the plane, size, area.
  const double dup_tol = 1e-12 * diag;
  for (std::size_t c = 0; c < s.curves.size(); ++c) {
    auto& cv = s.curves[c];
    const Plane& pl = s.planes[static_cast<std::size_t>(cv.plane)];
    const std::string where = name + ": curve " + std::to_string(c) + " (plane " + std::to_string(cv.plane) + ")";
    auto& pts = cv.points;
    // Distance to the plane first, then projection, then duplicates (points that differ only
    // across the plane become duplicates once projected).
    double worst = 0;
    std::size_t worst_k = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const double dist = std::abs(pl.signed_distance(pts[k]));
      if (dist > worst) worst = dist, worst_k = k;
    }
    if (worst > kWarnProjection * diag)
      return Status::error(where + ": point " + std::to_string(worst_k) + " lies " + short_num(worst) +
                           " off its plane, more than 1e-3 of the bounding-box diagonal (" +
                           short_num(diag) + ")");
    if (worst > kSilentProjection * diag)
      w.push_back(where + ": points up to " + short_num(worst) + " off the plane (" +
                  short_num(worst / diag) + " of the diagonal) projected onto it");
    for (auto& q : pts) q = pl.project(q);
    if (pts.size() >= 2 && (pts.front() - pts.back()).norm() <= dup_tol) {
      pts.pop_back();
      w.push_back(where + ": first point repeated at the end; dropped the repeat");
    }
    std::vector<Vec3> clean;
    clean.reserve(pts.size());
    for (const auto& q : pts)
      if (clean.empty() || (q - clean.back()).norm() > dup_tol) clean.push_back(q);
    while (clean.size() >= 2 && (clean.front() - clean.back()).norm() <= dup_tol) clean.pop_back();
    if (clean.size() != pts.size())
      w.push_back(where + ": dropped " + std::to_string(pts.size() - clean.size()) + " repeated point(s)");
    pts.swap(clean);
    if (pts.size() < 3)
      return Status::error(where + ": has " + std::to_string(pts.size()) +
                           " distinct point(s); a curve needs at least 3");
    const double area2 = std::abs(polygon_area2(pts, pl.normal));
    if (!(area2 > 1e-14 * diag * diag)) {
      // Zero signed area has two causes; name the right one. All points on one line, or loops
      // of opposite orientation that cancel (a figure eight: the curve crosses itself).
      std::size_t far = 0;
      for (std::size_t k = 1; k < pts.size(); ++k)
        if ((pts[k] - pts[0]).squaredNorm() > (pts[far] - pts[0]).squaredNorm()) far = k;
      const Vec3 dir = (pts[far] - pts[0]).normalized();
      double off_line = 0;
      for (const auto& q : pts) off_line = std::max(off_line, ((q - pts[0]) - (q - pts[0]).dot(dir) * dir).norm());
      if (far == 0 || !(off_line > 1e-9 * diag))
        return Status::error(where + ": encloses no area (all points on one line)");
      return Status::error(where + ": encloses no area: its loops cancel, so the curve crosses itself (rule 3)");
    }
  }
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
  set = std::move(s);
  return Status::ok();
}

// === JSON
namespace {

using nlohmann::json;

// nlohmann's parser is iterative, but keep hostile nesting out anyway: nothing valid nests
// deeper than 4.
bool too_deep(std::string_view t, int limit) {
  int depth = 0;
  bool in_string = false, escape = false;
  for (char ch : t) {
    if (in_string) {
      if (escape) escape = false;
      else if (ch == '\\') escape = true;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > limit) return true;
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return false;
}

std::string type_name(const json& v) {
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

struct JsonError {
  std::string message;
};

double get_number(const json& v, const std::string& path) {
  if (!v.is_number()) throw JsonError{path + ": expected a number, found " + type_name(v)};
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw JsonError{path + ": number is not finite"};
  return d;
}

long long get_index(const json& v, const std::string& path) {
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
      throw JsonError{path + ": index " + std::to_string(u) + " is too large"};
    return static_cast<long long>(u);
  }
  if (v.is_number_integer()) return v.get<long long>();
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 1e9) return static_cast<long long>(d);
    throw JsonError{path + ": expected a whole number, found " + short_num(d)};
  }
  throw JsonError{path + ": expected a whole number, found " + type_name(v)};
}

Vec3 get_vec3(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 3)
    throw JsonError{path + ": expected an array of 3 numbers, found " +
                    (v.is_array() ? "an array of " + std::to_string(v.size()) : type_name(v))};
  return Vec3(get_number(v[0], path + "[0]"), get_number(v[1], path + "[1]"), get_number(v[2], path + "[2]"));
}

const json& member(const json& obj, const char* key, const std::string& path) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw JsonError{path + ": missing \"" + key + "\""};
  return *it;
}

}  // namespace

Result<SectionSet> parse_contour_json(std::string_view content, const std::string& name, Warnings* warnings) {
  if (trim(content).empty()) return Result<SectionSet>::error(name + ": file is empty");
  if (too_deep(content, 64)) return Result<SectionSet>::error(name + ": JSON nests deeper than 64 levels");
  json j;
  try {
    j = json::parse(strip_bom(content).begin(), strip_bom(content).end());
  } catch (const json::exception& e) {
    std::string m = e.what();
    if (const auto p = m.find("] "); m.rfind("[json.exception", 0) == 0 && p != std::string::npos) m = m.substr(p + 2);
    return Result<SectionSet>::error(name + ": not valid JSON: " + m);
  }
  SectionSet set;
  Warnings w;
  try {
    if (!j.is_object()) throw JsonError{"$: expected an object, found " + type_name(j)};
    if (const auto it = j.find("format"); it != j.end()) {
      if (!it->is_string() || it->get<std::string>() != "cross-sections")
        throw JsonError{"$.format: expected \"cross-sections\", found " +
                        (it->is_string() ? "\"" + it->get<std::string>().substr(0, 40) + "\"" : type_name(*it))};
    }
    if (const auto it = j.find("version"); it != j.end()) {
      const long long v = get_index(*it, "$.version");
      if (v < 1) throw JsonError{"$.version: expected 1, found " + std::to_string(v)};
      if (v > 1) w.push_back(name + ": $.version is " + std::to_string(v) + "; read as version 1, unknown fields ignored");
    }
    if (const auto it = j.find("units"); it != j.end()) {
      if (!it->is_string()) throw JsonError{"$.units: expected a string, found " + type_name(*it)};
      set.units = it->get<std::string>();
    }
    const json& planes = member(j, "planes", "$");
    if (!planes.is_array()) throw JsonError{"$.planes: expected an array, found " + type_name(planes)};
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const std::string path = "$.planes[" + std::to_string(i) + "]";
      const json& p = planes[i];
      if (!p.is_object()) throw JsonError{path + ": expected an object, found " + type_name(p)};
      Plane pl;
      pl.normal = get_vec3(member(p, "normal", path), path + ".normal");
      pl.offset = get_number(member(p, "offset", path), path + ".offset");
      if (pl.normal.cwiseAbs().maxCoeff() == 0.0) throw JsonError{path + ".normal: is zero"};
      set.planes.push_back(pl);
    }
    const json& curves = member(j, "curves", "$");
    if (!curves.is_array()) throw JsonError{"$.curves: expected an array, found " + type_name(curves)};
    for (std::size_t i = 0; i < curves.size(); ++i) {
      const std::string path = "$.curves[" + std::to_string(i) + "]";
      const json& c = curves[i];
      if (!c.is_object()) throw JsonError{path + ": expected an object, found " + type_name(c)};
      CrossSection cs;
      const long long plane = get_index(member(c, "plane", path), path + ".plane");
      if (plane < 0 || plane >= static_cast<long long>(set.planes.size()))
        throw JsonError{path + ".plane: index " + std::to_string(plane) + " out of range (there are " +
                        std::to_string(set.planes.size()) + " planes)"};
      cs.plane = static_cast<int>(plane);
      const json& pts = member(c, "points", path);
      if (!pts.is_array()) throw JsonError{path + ".points: expected an array, found " + type_name(pts)};
      if (pts.size() < 3)
        throw JsonError{path + ".points: has " + std::to_string(pts.size()) + " point(s); a curve needs at least 3"};
      cs.points.reserve(pts.size());
      for (std::size_t k = 0; k < pts.size(); ++k) {
        // Fast path for well-formed points; the slow path builds the JSON path for the message.
        const json& q = pts[k];
        if (q.is_array() && q.size() == 3 && q[0].is_number() && q[1].is_number() && q[2].is_number()) {
          const Vec3 v(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
          if (finite3(v)) {
            cs.points.push_back(v);
            continue;
          }
        }
        cs.points.push_back(get_vec3(q, path + ".points[" + std::to_string(k) + "]"));
      }
      set.curves.push_back(std::move(cs));
    }
  } catch (const JsonError& e) {
    return Result<SectionSet>::error(name + ": " + e.message);
  } catch (const json::exception& e) {
    return Result<SectionSet>::error(name + ": unexpected JSON content: " + e.what());
  }
  if (const Status st = finish_sections(set, name, &w); !st) return st;
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
  return set;
}

// === CSL
// === CSL labels and hole flags
namespace {
struct CslComponentInfo {
  int plane;
  bool hole;
  int parent;  // index among the plane's components
  int label;
};

// Where a plane's components nest or overlap otherwise than their hole flags say (a
// multi-material file: organs inside organs, none flagged as holes), the plane's curves become
// the boundary of the union of its labelled components (curve_repair.h). Elsewhere nothing
// changes: nesting already carries the meaning (rule 2).
// The 2D frame of a plane scaled to a unit normal: the reader's check of hole flags and the
// writer's nesting both work in it, so that they agree (format_csl).
PlaneFrame unit_plane_frame(const Plane& pl) {
  Plane unit = pl;
  if (const double len = pl.normal.norm(); len > 0) {
    unit.normal /= len;
    unit.offset /= len;
  }
  return plane_frame(unit);
}

void read_csl_labels(SectionSet& set, const std::vector<CslComponentInfo>& info, const std::string& name, Warnings& w) {
  std::vector<std::vector<CrossSection>> by_plane(set.planes.size());
  std::vector<std::vector<CslComponent>> comps(set.planes.size());
  std::vector<PlaneFrame> frames;
  for (const Plane& pl : set.planes) frames.push_back(unit_plane_frame(pl));
  for (std::size_t c = 0; c < set.curves.size(); ++c) {
    const auto p = static_cast<std::size_t>(info[c].plane);
    CslComponent k;
    for (const Vec3& q : set.curves[c].points) k.loop.push_back(frames[p].to_2d(q));
    k.hole = info[c].hole;
    k.parent = info[c].parent;
    k.label = info[c].label;
    comps[p].push_back(std::move(k));
    by_plane[p].push_back(std::move(set.curves[c]));
  }
  set.curves.clear();
  for (std::size_t p = 0; p < by_plane.size(); ++p) {
    if (comps[p].size() < 2 || components_agree_with_nesting(comps[p])) {
      for (auto& c : by_plane[p]) set.curves.push_back(std::move(c));
      continue;
    }
    const std::string where = name + ": plane " + std::to_string(p + 1) + ": ";
    auto region = region_of_components(comps[p]);
    if (!region) {
      w.push_back(where + "its components nest or overlap otherwise than their hole flags say, and " + region.message() +
                  " failed; read as they are");
      for (auto& c : by_plane[p]) set.curves.push_back(std::move(c));
      continue;
    }
    std::vector<const CrossSection*> inputs;
    for (const auto& c : by_plane[p]) inputs.push_back(&c);
    for (auto& c : lift_loops(*region, inputs, frames[p], static_cast<int>(p))) set.curves.push_back(std::move(c));
    w.push_back(where + std::to_string(comps[p].size()) +
                " components nest or overlap otherwise than their hole flags say (several materials); the section is "
                "the union of the labelled ones: " + std::to_string(region->size()) + " curve" +
                (region->size() == 1 ? "" : "s"));
  }
}

}  // namespace

Result<SectionSet> parse_csl(std::string_view content, const std::string& name, Warnings* warnings) {
  LineReader lr(content);
  std::string_view line;
  auto fail = [&](int at, const std::string& why) {
    return Result<SectionSet>::error(name + ":" + std::to_string(at) + ": " + why);
  };
  if (!lr.next(line)) return Result<SectionSet>::error(name + ": file is empty");
  if (line != "CSLC") return fail(lr.line(), "expected the header \"CSLC\", found " + show(line));
  if (!lr.next(line)) return fail(lr.line(), "file ended before the plane and label counts");
  auto tok = split(line);
  long long nplanes = 0, nlabels = 0;
  if (tok.size() != 2 || !parse_int(tok[0], nplanes) || !parse_int(tok[1], nlabels) || nplanes < 0 || nlabels < 0)
    return fail(lr.line(), "expected \"<number of planes> <number of labels>\", found " + show(line));

  SectionSet set;
  Warnings w;
  std::vector<std::vector<Vec3>> plane_vertices;
  std::vector<CslComponentInfo> components;  // per curve read
  for (long long p = 0; p < nplanes; ++p) {
    if (!lr.next(line))
      return fail(lr.line(), "file ended early: expected plane " + std::to_string(p + 1) + " of " + std::to_string(nplanes));
    tok = split(line);
    long long index = 0, nv = 0, nc = 0;
    std::array<double, 4> abcd{};
    if (tok.size() != 7 || !parse_int(tok[0], index) || !parse_int(tok[1], nv) || !parse_int(tok[2], nc))
      return fail(lr.line(), "expected a plane line \"<index> <vertices> <components> A B C D\", found " + show(line));
    for (std::size_t k = 0; k < 4; ++k)
      if (!parse_double(tok[3 + k], abcd[k])) return fail(lr.line(), "plane coefficient " + show(tok[3 + k]) + " is not a number");
    for (double v : abcd)
      if (!std::isfinite(v)) return fail(lr.line(), "plane coefficient is not a finite number");
    if (abcd[0] == 0.0 && abcd[1] == 0.0 && abcd[2] == 0.0) return fail(lr.line(), "plane normal (A, B, C) is zero");
    if (nv < 0 || nc < 0) return fail(lr.line(), "negative vertex or component count");
    if (index != p + 1)
      w.push_back(name + ":" + std::to_string(lr.line()) + ": plane numbered " + std::to_string(index) +
                  ", expected " + std::to_string(p + 1) + "; numbering ignored");
    const int plane_line = lr.line();
    Plane pl;
    pl.normal = Vec3(abcd[0], abcd[1], abcd[2]);
    pl.offset = -abcd[3];
    const int plane_id = static_cast<int>(set.planes.size());
    set.planes.push_back(pl);
    std::vector<Vec3> verts;
    for (long long v = 0; v < nv; ++v) {
      if (!lr.next(line))
        return fail(lr.line(), "file ended early: plane " + std::to_string(p + 1) + " (line " + std::to_string(plane_line) +
                                   ") promises " + std::to_string(nv) + " vertices, found " + std::to_string(v));
      tok = split(line);
      Vec3 q;
      if (tok.size() != 3 || !parse_double(tok[0], q.x()) || !parse_double(tok[1], q.y()) || !parse_double(tok[2], q.z()))
        return fail(lr.line(), "expected a vertex \"x y z\" (vertex " + std::to_string(v) + " of plane " +
                                   std::to_string(p + 1) + "), found " + show(line));
      if (!finite3(q)) return fail(lr.line(), "vertex coordinate is not a finite number");
      verts.push_back(q);
    }
    for (long long c = 0; c < nc; ++c) {
      if (!lr.next(line))
        return fail(lr.line(), "file ended early: plane " + std::to_string(p + 1) + " promises " + std::to_string(nc) +
                                   " components, found " + std::to_string(c));
      tok = split(line);
      if (tok.size() < 2) return fail(lr.line(), "expected a component \"<n>[h[<parent>]] <label> <indices>\", found " + show(line));
      // <n>[h[<parent>]]
      const std::string_view head = tok[0];
      const auto hpos = head.find('h');
      long long count = 0, label = 0, parent = -1;
      if (!parse_int(head.substr(0, hpos), count) || count < 0)
        return fail(lr.line(), "component vertex count " + show(head) + " is not a whole number");
      if (hpos != std::string_view::npos && hpos + 1 < head.size()) {
        if (!parse_int(head.substr(hpos + 1), parent) || parent < 0 || parent >= nc || parent == c)
          return fail(lr.line(), "hole parent in " + show(head) + " is not another component of this plane");
      }
      if (!parse_int(tok[1], label) || label < 0) return fail(lr.line(), "component label " + show(tok[1]) + " is not a whole number >= 0");
      if (static_cast<long long>(tok.size()) - 2 != count)
        return fail(lr.line(), "component promises " + std::to_string(count) + " vertex indices, found " +
                                   std::to_string(tok.size() - 2));
      CrossSection cs;
      cs.plane = plane_id;
      for (std::size_t k = 2; k < tok.size(); ++k) {
        long long vi = 0;
        if (!parse_int(tok[k], vi) || vi < 0 || vi >= nv)
          return fail(lr.line(), "vertex index " + show(tok[k]) + " out of range (plane has " + std::to_string(nv) + " vertices)");
        cs.points.push_back(verts[static_cast<std::size_t>(vi)]);
      }
      if (count < 3)
        return fail(lr.line(), "component has " + std::to_string(count) + " vertices; a curve needs at least 3");
      set.curves.push_back(std::move(cs));
      components.push_back({static_cast<int>(p), hpos != std::string_view::npos, static_cast<int>(parent),
                            static_cast<int>(std::min<long long>(label, 1 << 30))});
    }
    plane_vertices.push_back(std::move(verts));
  }
  if (lr.next(line)) return fail(lr.line(), "unexpected content after the last plane: " + show(line));

  // Some published files (rose.csl) write Ax+By+Cz = D instead of Ax+By+Cz+D = 0. When every
  // vertex of a plane fits the flipped sign and not the documented one, use the flipped sign.
  Box3 box;
  for (const auto& vs : plane_vertices)
    for (const auto& q : vs) box.extend(q);
  const double diag = box.diagonal();
  for (std::size_t p = 0; p < set.planes.size(); ++p) {
    if (plane_vertices[p].empty()) continue;
    Plane a = set.planes[p], b = a;
    const double len = a.normal.norm();
    if (!(len > 0) || !std::isfinite(len)) continue;
    b.offset = -b.offset;
    double da = 0, db = 0;
    for (const auto& q : plane_vertices[p]) {
      da = std::max(da, std::abs(a.signed_distance(q)) / len);
      db = std::max(db, std::abs(b.signed_distance(q)) / len);
    }
    if (da > kWarnProjection * diag && db <= kWarnProjection * diag) {
      set.planes[p] = b;
      w.push_back(name + ": plane " + std::to_string(p + 1) +
                  ": vertices lie on Ax+By+Cz = D rather than Ax+By+Cz+D = 0; read with that sign");
    }
  }
  read_csl_labels(set, components, name, w);
  if (const Status st = finish_sections(set, name, &w); !st) return st;
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
  return set;
}

// === Ctr2Suf .contour
Result<SectionSet> parse_ctr2suf(std::string_view content, const std::string& name, Warnings* warnings) {
  if (trim(content).empty()) return Result<SectionSet>::error(name + ": file is empty");
  TokenReader tr(content);
  std::string_view tok;
  auto fail = [&](int at, const std::string& why) {
    return Result<SectionSet>::error(name + ":" + std::to_string(at) + ": " + why);
  };
  // Messages are built only on failure (building them per token dominated parse time).
  auto next_int = [&](long long& v) -> bool { return tr.next(tok) && parse_int(tok, v); };
  auto next_double = [&](double& v) -> bool { return tr.next(tok) && parse_double(tok, v); };
  auto bad = [&](const std::string& what) {
    if (tok.empty()) return fail(tr.eof_line(), "file ended early: expected " + what);
    return fail(tr.line(), "expected " + what + ", found " + show(tok));
  };
  // Track end-of-file separately from a bad token.
  long long nplanes = 0;
  tok = {};
  if (!next_int(nplanes) || nplanes < 0) return bad("the number of planes");

  SectionSet set;
  Warnings w;
  for (long long p = 0; p < nplanes; ++p) {
    const std::string pn = "plane " + std::to_string(p);
    std::array<double, 4> abcd{};
    for (std::size_t k = 0; k < 4; ++k) {
      tok = {};
      if (!next_double(abcd[k])) return bad("coefficient " + std::string(1, "abcd"[k]) + " of " + pn + " (a b c d for ax+by+cz=d)");
      if (!std::isfinite(abcd[k])) return fail(tr.line(), "plane coefficient of " + pn + " is not a finite number");
    }
    const int plane_line = tr.line();
    if (abcd[0] == 0.0 && abcd[1] == 0.0 && abcd[2] == 0.0) return fail(plane_line, pn + ": normal (a, b, c) is zero");
    long long nv = 0, ne = 0;
    tok = {};
    if (!next_int(nv) || nv < 0) return bad("the vertex count of " + pn);
    tok = {};
    if (!next_int(ne) || ne < 0) return bad("the edge count of " + pn);
    Plane pl;
    pl.normal = Vec3(abcd[0], abcd[1], abcd[2]);
    pl.offset = abcd[3];
    const int plane_id = static_cast<int>(set.planes.size());
    set.planes.push_back(pl);
    std::vector<Vec3> verts;
    for (long long v = 0; v < nv; ++v) {
      Vec3 q;
      for (int k = 0; k < 3; ++k) {
        tok = {};
        if (!next_double(q[k])) return bad("coordinate of vertex " + std::to_string(v) + " of " + pn);
      }
      if (!finite3(q)) return fail(tr.line(), "vertex " + std::to_string(v) + " of " + pn + " has a non-finite coordinate");
      verts.push_back(q);
    }
    struct Edge {
      std::size_t a, b;
      int line;
    };
    std::vector<Edge> edges;
    std::size_t skipped = 0;
    for (long long e = 0; e < ne; ++e) {
      std::array<long long, 4> f{};
      for (std::size_t k = 0; k < 4; ++k) {
        tok = {};
        if (!next_int(f[k]))
          return bad(std::string(k < 2 ? "a vertex index" : "a material label") + " of edge " + std::to_string(e) +
                     " of " + pn);
      }
      const int line = tr.line();
      if (f[0] < 0 || f[0] >= nv || f[1] < 0 || f[1] >= nv)
        return fail(line, "edge " + std::to_string(e) + " of " + pn + " references a vertex out of range (" +
                              std::to_string(nv) + " vertices)");
      if (f[0] == f[1]) return fail(line, "edge " + std::to_string(e) + " of " + pn + " joins vertex " + std::to_string(f[0]) + " to itself");
      if (f[2] < 0 || f[3] < 0) return fail(line, "edge " + std::to_string(e) + " of " + pn + " has a negative label");
      // Only edges between outside (0) and inside (any other label) bound the object.
      if ((f[2] == 0) == (f[3] == 0)) {
        ++skipped;
        continue;
      }
      edges.push_back({static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]), line});
    }
    if (skipped)
      w.push_back(name + ": " + pn + ": ignored " + std::to_string(skipped) +
                  " edge(s) with both labels inside or both outside (not on the object's boundary)");
    // Assemble edges into closed loops: every vertex used needs exactly two boundary edges.
    std::vector<std::array<std::size_t, 2>> adj(verts.size());
    std::vector<int> degree(verts.size(), 0);
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto key = std::minmax(edges[e].a, edges[e].b);
      if (!seen.insert(key).second)
        return fail(edges[e].line, pn + ": edge " + std::to_string(key.first) + "-" + std::to_string(key.second) + " is given twice");
      for (std::size_t v : {edges[e].a, edges[e].b}) {
        if (degree[v] == 2)
          return fail(edges[e].line, pn + ": vertex " + std::to_string(v) +
                                         " has more than two boundary edges (the edges branch)");
        adj[v][static_cast<std::size_t>(degree[v]++)] = e;
      }
    }
    for (const auto& e : edges)
      for (std::size_t v : {e.a, e.b})
        if (degree[v] == 1)
          return fail(e.line, pn + ": vertex " + std::to_string(v) + " has only one boundary edge (the edges form an open chain)");
    std::vector<bool> used(edges.size(), false);
    for (std::size_t e0 = 0; e0 < edges.size(); ++e0) {
      if (used[e0]) continue;
      CrossSection cs;
      cs.plane = plane_id;
      std::size_t e = e0, v = edges[e0].a;
      while (!used[e]) {
        used[e] = true;
        cs.points.push_back(verts[v]);
        v = edges[e].a == v ? edges[e].b : edges[e].a;
        e = adj[v][0] == e ? adj[v][1] : adj[v][0];
      }
      set.curves.push_back(std::move(cs));
    }
  }
  if (tr.next(tok)) return fail(tr.line(), "unexpected content after the last plane: " + show(tok));
  if (const Status st = finish_sections(set, name, &w); !st) return st;
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
  return set;
}

// === Dispatch
Result<SectionSet> parse_sections(std::string_view content, ContourFormat format, const std::string& name,
                                  Warnings* warnings) {
  switch (format) {
    case ContourFormat::Json: return parse_contour_json(content, name, warnings);
    case ContourFormat::Csl: return parse_csl(content, name, warnings);
    case ContourFormat::Ctr2Suf: return parse_ctr2suf(content, name, warnings);
  }
  return Result<SectionSet>::error(name + ": unknown format");
}

Result<SectionSet> read_sections(const std::string& path, Warnings* warnings) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Result<SectionSet>::error(path + ": no such file");
  if (fs::is_directory(path, ec)) return Result<SectionSet>::error(path + ": is a directory, not a contour file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Result<SectionSet>::error(path + ": cannot be opened for reading");
  std::string content;
  {
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return Result<SectionSet>::error(path + ": read error");
    content = ss.str();
  }
  if (trim(content).empty()) return Result<SectionSet>::error(path + ": file is empty");
  const auto by_ext = contour_format_from_extension(path);
  const auto by_content = sniff_contour_format(content);
  const auto format = by_ext ? by_ext : by_content;
  if (!format)
    return Result<SectionSet>::error(path + ": unknown contour format (extension is not .json, .csl or .contour "
                                            "and the content looks like none of them)");
  auto r = parse_sections(content, *format, path, warnings);
  if (!r && by_ext && by_content && *by_content != *by_ext)
    return Result<SectionSet>::error(r.message() + " (the content looks like " +
                                     contour_format_extension(*by_content) + " rather than " +
                                     contour_format_extension(*by_ext) + ")");
  return r;
}

// === Writers
std::string format_contour_json(const SectionSet& set) {
  std::string s = "{\n  \"format\": \"cross-sections\",\n  \"version\": 1,\n";
  if (!set.units.empty()) s += "  \"units\": " + nlohmann::json(set.units).dump() + ",\n";
  auto v3 = [](const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; };
  s += "  \"planes\": [";
  for (std::size_t i = 0; i < set.planes.size(); ++i)
    s += std::string(i ? "," : "") + "\n    {\"normal\": " + v3(set.planes[i].normal) + ", \"offset\": " + num(set.planes[i].offset) + "}";
  s += set.planes.empty() ? "],\n" : "\n  ],\n";
  s += "  \"curves\": [";
  for (std::size_t i = 0; i < set.curves.size(); ++i) {
    s += std::string(i ? "," : "") + "\n    {\"plane\": " + std::to_string(set.curves[i].plane) + ", \"points\": [";
    const auto& pts = set.curves[i].points;
    for (std::size_t k = 0; k < pts.size(); ++k) s += std::string(k ? "," : "") + "\n      " + v3(pts[k]);
    s += "]}";
  }
  s += set.curves.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return s;
}

namespace {
// Per plane: the curve indices on it.
std::vector<std::vector<std::size_t>> curves_by_plane(const SectionSet& set) {
  std::vector<std::vector<std::size_t>> by(set.planes.size());
  for (std::size_t c = 0; c < set.curves.size(); ++c) {
    const int p = set.curves[c].plane;
    if (p >= 0 && static_cast<std::size_t>(p) < by.size()) by[static_cast<std::size_t>(p)].push_back(c);
  }
  return by;
}
}  // namespace

std::string format_csl(const SectionSet& set) {
  std::string s = "CSLC\n" + std::to_string(set.planes.size()) + " 2\n";
  const auto by = curves_by_plane(set);
  for (std::size_t p = 0; p < set.planes.size(); ++p) {
    const Plane& pl = set.planes[p];
    const auto& ids = by[p];
    std::size_t nv = 0;
    for (std::size_t c : ids) nv += set.curves[c].points.size();
    s += "\n" + std::to_string(p + 1) + " " + std::to_string(nv) + " " + std::to_string(ids.size()) + " " +
         num(pl.normal.x()) + " " + num(pl.normal.y()) + " " + num(pl.normal.z()) + " " + num(-pl.offset) + "\n\n";
    // Nesting on the plane: depth = number of curves containing most of the curve's vertices;
    // parent = the deepest of those. The same test and the same 2D frame as the reader's check
    // of hole flags (components_agree_with_nesting), so a written hole reads back as a hole.
    // (Until 2026-12-07 the first vertex decided; csl_fuzz found a curve whose first vertex lay
    // on another curve's edge: written as its hole, and read back the two were united.)
    const PlaneFrame frame = unit_plane_frame(pl);
    std::vector<std::vector<Vec2>> flat;
    for (std::size_t c : ids) {
      std::vector<Vec2> f;
      for (const auto& q : set.curves[c].points) f.push_back(frame.to_2d(q));
      flat.push_back(std::move(f));
    }
    std::vector<std::vector<char>> inside(ids.size(), std::vector<char>(ids.size(), 0));
    std::vector<int> depth(ids.size(), 0), parent(ids.size(), -1);
    for (std::size_t a = 0; a < ids.size(); ++a)
      for (std::size_t b = 0; b < ids.size(); ++b)
        if (a != b && !flat[a].empty() && flat[b].size() >= 3 && loop_mostly_inside(flat[a], flat[b])) {
          inside[a][b] = 1;
          ++depth[a];
        }
    for (std::size_t a = 0; a < ids.size(); ++a)
      for (std::size_t b = 0; b < ids.size(); ++b)
        if (inside[a][b] && (parent[a] < 0 || depth[b] > depth[static_cast<std::size_t>(parent[a])]))
          parent[a] = static_cast<int>(b);
    for (std::size_t c : ids)
      for (const auto& q : set.curves[c].points) s += num(q.x()) + " " + num(q.y()) + " " + num(q.z()) + "\n";
    s += "\n";
    std::size_t base = 0;
    for (std::size_t a = 0; a < ids.size(); ++a) {
      const std::size_t n = set.curves[ids[a]].points.size();
      s += std::to_string(n);
      if (depth[a] % 2 == 1 && parent[a] >= 0) {
        s += 'h';
        s += std::to_string(parent[a]);
      }
      s += " 1";
      for (std::size_t k = 0; k < n; ++k) {
        s += ' ';
        s += std::to_string(base + k);
      }
      s += "\n";
      base += n;
    }
  }
  return s;
}

std::string format_ctr2suf(const SectionSet& set) {
  std::string s = std::to_string(set.planes.size()) + "\n";
  const auto by = curves_by_plane(set);
  for (std::size_t p = 0; p < set.planes.size(); ++p) {
    const Plane& pl = set.planes[p];
    std::size_t nv = 0;
    for (std::size_t c : by[p]) nv += set.curves[c].points.size();
    s += num(pl.normal.x()) + " " + num(pl.normal.y()) + " " + num(pl.normal.z()) + " " + num(pl.offset) + "\n";
    s += std::to_string(nv) + " " + std::to_string(nv) + "\n";
    for (std::size_t c : by[p])
      for (const auto& q : set.curves[c].points) s += num(q.x()) + " " + num(q.y()) + " " + num(q.z()) + "\n";
    std::size_t base = 0;
    for (std::size_t c : by[p]) {
      const std::size_t n = set.curves[c].points.size();
      for (std::size_t k = 0; k < n; ++k)
        s += std::to_string(base + k) + " " + std::to_string(base + (k + 1) % n) + " 1 0\n";
      base += n;
    }
  }
  return s;
}

Status write_file_atomically(const std::string& path, std::string_view content) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) return Status::error("no output file name given");
  if (fs::is_directory(path, ec)) return Status::error(path + ": is a directory");
  const fs::path target(path);
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = target.parent_path() / (".tmp-" + target.filename().string() + "-" + std::to_string(::getpid()) +
                                               "-" + std::to_string(counter++));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return Status::error(path + ": cannot create the output file (does the folder exist and is it writable?)");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      return Status::error(path + ": write failed (disk full?)");
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    return Status::error(path + ": cannot move the written file into place: " + ec.message());
  }
  return Status::ok();
}

Status write_sections(const std::string& path, const SectionSet& set, ContourFormat format) {
  for (const auto& c : set.curves)
    if (c.plane < 0 || static_cast<std::size_t>(c.plane) >= set.planes.size())
      return Status::error(path + ": a curve refers to plane " + std::to_string(c.plane) + ", which does not exist");
  switch (format) {
    case ContourFormat::Json: return write_file_atomically(path, format_contour_json(set));
    case ContourFormat::Csl: return write_file_atomically(path, format_csl(set));
    case ContourFormat::Ctr2Suf: return write_file_atomically(path, format_ctr2suf(set));
  }
  return Status::error(path + ": unknown format");
}

Status write_sections(const std::string& path, const SectionSet& set) {
  const auto f = contour_format_from_extension(path);
  if (!f) return Status::error(path + ": unknown contour extension (expected .json, .csl or .contour)");
  return write_sections(path, set, *f);
}

}  // namespace ps
