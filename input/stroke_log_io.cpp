// Stroke-log reader and writer (JSON Lines via nlohmann_json; format in docs/stroke-log.md).
#include "input/stroke_log_io.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

namespace ps {

using json = nlohmann::ordered_json;

// === Names

namespace {
constexpr std::size_t kMaxLineBytes = 1 << 20;  // a pen line is ~200 bytes; 1 MiB is generous
constexpr int kMaxNesting = 16;                 // the format nests 3 levels deep
}  // namespace

std::string_view event_type_name(const Event& e) {
  return std::visit(
      [](const auto& v) -> std::string_view {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, PenSample>) return "pen";
        else if constexpr (std::is_same_v<T, SelectPlane>) return "select_plane";
        else if constexpr (std::is_same_v<T, TranslatePlane>) return "translate_plane";
        else if constexpr (std::is_same_v<T, CameraChange>) return "camera";
        else if constexpr (std::is_same_v<T, SetToolMode>) return "tool_mode";
        else if constexpr (std::is_same_v<T, SetParameter>) return "parameter";
        else if constexpr (std::is_same_v<T, Undo>) return "undo";
        else if constexpr (std::is_same_v<T, Redo>) return "redo";
        else if constexpr (std::is_same_v<T, DeleteSection>) return "delete";
        else if constexpr (std::is_same_v<T, Save>) return "save";
        else {
          static_assert(std::is_same_v<T, OpenFile>, "unhandled event type");
          return "open";
        }
      },
      e);
}

bool is_pen_sample(const Event& e) { return std::holds_alternative<PenSample>(e); }

std::string_view tool_name(Tool t) {
  switch (t) {
    case Tool::kPen: return "pen";
    case Tool::kEraser: return "eraser";
    case Tool::kMouse: return "mouse";
  }
  return "pen";
}

std::string_view phase_name(Phase p) {
  switch (p) {
    case Phase::kDown: return "down";
    case Phase::kMove: return "move";
    case Phase::kUp: return "up";
    case Phase::kProximityIn: return "proximity-in";
    case Phase::kProximityOut: return "proximity-out";
  }
  return "move";
}

namespace {

bool parse_tool(std::string_view s, Tool& out) {
  for (Tool t : {Tool::kPen, Tool::kEraser, Tool::kMouse})
    if (tool_name(t) == s) return out = t, true;
  return false;
}

bool parse_phase(std::string_view s, Phase& out) {
  for (Phase p : {Phase::kDown, Phase::kMove, Phase::kUp, Phase::kProximityIn, Phase::kProximityOut})
    if (phase_name(p) == s) return out = p, true;
  return false;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// === Checks

Status check_finite(double v, const char* field) {
  if (!std::isfinite(v)) return Status::error(std::string("field '") + field + "' is not finite");
  return Status::ok();
}

Status check_vec3(const Vec3& v, const char* field) {
  if (!v.allFinite()) return Status::error(std::string("field '") + field + "' is not finite");
  return Status::ok();
}

}  // namespace

Status check_camera(const Camera& c) {
  if (auto s = check_vec3(c.eye, "camera.eye"); !s) return s;
  if (auto s = check_vec3(c.target, "camera.target"); !s) return s;
  if (auto s = check_vec3(c.up, "camera.up"); !s) return s;
  for (auto [v, n] : {std::pair{c.fov_y_deg, "camera.fov_y_deg"}, {c.ortho_height, "camera.ortho_height"},
                      {c.near_plane, "camera.near"}, {c.far_plane, "camera.far"}})
    if (auto s = check_finite(v, n); !s) return s;
  const Vec3 f = c.target - c.eye;
  if (!(f.norm() > 0.0)) return Status::error("camera eye and target coincide");
  if (!(c.up.norm() > 0.0) || f.normalized().cross(c.up.normalized()).norm() < 1e-9)
    return Status::error("camera up is zero or parallel to the view direction");
  if (!(c.fov_y_deg > 0.0 && c.fov_y_deg < 180.0))
    return Status::error("camera fov_y_deg " + num(c.fov_y_deg) + " is outside (0, 180)");
  if (!(c.ortho_height > 0.0)) return Status::error("camera ortho_height must be > 0");
  if (!(c.near_plane > 0.0 && c.far_plane > c.near_plane))
    return Status::error("camera needs 0 < near < far");
  if (c.width <= 0 || c.height <= 0 || c.width > 65536 || c.height > 65536)
    return Status::error("camera viewport " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                         " is not in 1..65536");
  return Status::ok();
}

Status check_header(const LogHeader& h) {
  if (h.version != kStrokeLogVersion)
    return Status::error("unsupported stroke-log version " + std::to_string(h.version) +
                         " (this build reads version " + std::to_string(kStrokeLogVersion) + ")");
  if (h.viewport_width <= 0 || h.viewport_height <= 0 || h.viewport_width > 65536 ||
      h.viewport_height > 65536)
    return Status::error("viewport size must be in 1..65536");
  if (auto s = check_camera(h.camera); !s) return s;
  if (h.camera.width != h.viewport_width || h.camera.height != h.viewport_height)
    return Status::error("camera size " + std::to_string(h.camera.width) + "x" +
                         std::to_string(h.camera.height) + " differs from viewport " +
                         std::to_string(h.viewport_width) + "x" + std::to_string(h.viewport_height));
  for (std::size_t i = 0; i < h.planes.size(); ++i) {
    const Plane& p = h.planes[i];
    if (!p.normal.allFinite() || !std::isfinite(p.offset))
      return Status::error("plane " + std::to_string(i) + " is not finite");
    if (std::abs(p.normal.norm() - 1.0) > 1e-9)
      return Status::error("plane " + std::to_string(i) + " normal is not unit length");
  }
  return Status::ok();
}

Status check_event(const TimedEvent& e) {
  if (!std::isfinite(e.t) || e.t < 0.0) return Status::error("time t must be finite and >= 0");
  return std::visit(
      [&](const auto& v) -> Status {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, PenSample>) {
          for (auto [x, n] : {std::pair{v.x, "x"}, {v.y, "y"}, {v.pressure, "pressure"},
                              {v.tilt_x, "tilt_x"}, {v.tilt_y, "tilt_y"}})
            if (auto s = check_finite(x, n); !s) return s;
          if (v.t != e.t) return Status::error("pen sample time differs from event time");
          if (v.pressure < 0.0 || v.pressure > 1.0)
            return Status::error("pressure " + num(v.pressure) + " is outside [0, 1]");
          if (std::abs(v.tilt_x) > 90.0 || std::abs(v.tilt_y) > 90.0)
            return Status::error("tilt is outside [-90, 90] degrees");
          if (v.buttons > 0xffffu) return Status::error("buttons mask out of range");
        } else if constexpr (std::is_same_v<T, SelectPlane>) {
          if (v.plane < 0) return Status::error("plane index must be >= 0");
        } else if constexpr (std::is_same_v<T, TranslatePlane>) {
          if (v.plane < 0) return Status::error("plane index must be >= 0");
          return check_finite(v.offset, "offset");
        } else if constexpr (std::is_same_v<T, CameraChange>) {
          return check_camera(v.camera);
        } else if constexpr (std::is_same_v<T, SetToolMode>) {
          if (v.mode.empty()) return Status::error("field 'mode' is empty");
        } else if constexpr (std::is_same_v<T, SetParameter>) {
          if (v.name.empty()) return Status::error("field 'name' is empty");
          return check_finite(v.value, "value");
        } else if constexpr (std::is_same_v<T, DeleteSection>) {
          if (v.section < 0) return Status::error("section index must be >= 0");
        } else if constexpr (std::is_same_v<T, Save>) {
          if (v.path.empty()) return Status::error("field 'path' is empty");
        } else if constexpr (std::is_same_v<T, OpenFile>) {
          if (v.kind != "session" && v.kind != "mesh")
            return Status::error("field 'kind' must be \"session\" or \"mesh\" (found \"" + v.kind + "\")");
          if (v.path.empty()) return Status::error("field 'path' is empty");
          if (v.digest.size() != 16 || v.digest.find_first_not_of("0123456789abcdef") != std::string::npos)
            return Status::error("field 'digest' must be 16 lower-case hex digits");
        }
        return Status::ok();
      },
      e.event);
}

// === Writing

namespace {

json vec_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json camera_json(const Camera& c) {
  json j;
  j["eye"] = vec_json(c.eye);
  j["target"] = vec_json(c.target);
  j["up"] = vec_json(c.up);
  j["fov_y_deg"] = c.fov_y_deg;
  j["orthographic"] = c.orthographic;
  j["ortho_height"] = c.ortho_height;
  j["near"] = c.near_plane;
  j["far"] = c.far_plane;
  j["width"] = c.width;
  j["height"] = c.height;
  return j;
}

Result<std::string> dump_line(const json& j) {
  try {
    return j.dump();
  } catch (const json::exception&) {
    return Result<std::string>::error("a text field is not valid UTF-8");
  }
}

}  // namespace

Result<std::string> format_header(const LogHeader& h) {
  if (auto s = check_header(h); !s) return s;
  json j;
  j["format"] = kStrokeLogFormat;
  j["version"] = h.version;
  j["viewport"] = json{{"width", h.viewport_width}, {"height", h.viewport_height}};
  j["units"] = h.units;
  j["camera"] = camera_json(h.camera);
  json planes = json::array();
  for (const Plane& p : h.planes) planes.push_back(json{{"normal", vec_json(p.normal)}, {"offset", p.offset}});
  j["planes"] = std::move(planes);
  if (!h.generator.empty()) j["generator"] = h.generator;
  return dump_line(j);
}

Result<std::string> format_event(const TimedEvent& e) {
  if (auto s = check_event(e); !s) return s;
  json j;
  j["t"] = e.t;
  j["type"] = event_type_name(e.event);
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, PenSample>) {
          j["x"] = v.x;
          j["y"] = v.y;
          j["pressure"] = v.pressure;
          j["tilt_x"] = v.tilt_x;
          j["tilt_y"] = v.tilt_y;
          j["tool"] = tool_name(v.tool);
          j["phase"] = phase_name(v.phase);
          if (v.buttons != 0) j["buttons"] = v.buttons;
        } else if constexpr (std::is_same_v<T, SelectPlane>) {
          j["plane"] = v.plane;
        } else if constexpr (std::is_same_v<T, TranslatePlane>) {
          j["plane"] = v.plane;
          j["offset"] = v.offset;
        } else if constexpr (std::is_same_v<T, CameraChange>) {
          j["camera"] = camera_json(v.camera);
        } else if constexpr (std::is_same_v<T, SetToolMode>) {
          j["mode"] = v.mode;
        } else if constexpr (std::is_same_v<T, SetParameter>) {
          j["name"] = v.name;
          j["value"] = v.value;
        } else if constexpr (std::is_same_v<T, DeleteSection>) {
          j["section"] = v.section;
        } else if constexpr (std::is_same_v<T, Save>) {
          j["path"] = v.path;
        } else if constexpr (std::is_same_v<T, OpenFile>) {
          j["kind"] = v.kind;
          j["path"] = v.path;
          j["digest"] = v.digest;
        }
      },
      e.event);
  return dump_line(j);
}

Result<std::string> to_jsonl(const StrokeLog& log) {
  auto head = format_header(log.header);
  if (!head) return Result<std::string>::error("header: " + head.message());
  std::string out = *head + "\n";
  double last = 0.0;
  for (std::size_t i = 0; i < log.events.size(); ++i) {
    const TimedEvent& e = log.events[i];
    auto line = format_event(e);
    if (!line) return Result<std::string>::error("event " + std::to_string(i) + ": " + line.message());
    if (e.t < last)
      return Result<std::string>::error("event " + std::to_string(i) + ": time " + num(e.t) +
                                        " ms goes back (previous " + num(last) + " ms)");
    last = e.t;
    out += *line;
    out += '\n';
  }
  if (log.end_t) {
    if (*log.end_t < last)
      return Result<std::string>::error("end marker: time " + num(*log.end_t) + " ms goes back (previous " +
                                        num(last) + " ms)");
    auto line = format_end(*log.end_t);
    if (!line) return Result<std::string>::error("end marker: " + line.message());
    out += *line;
    out += '\n';
  }
  return out;
}

Result<std::string> format_end(double t) {
  if (!std::isfinite(t) || t < 0.0) return Result<std::string>::error("time t must be finite and >= 0");
  json j;
  j["t"] = t;
  j["type"] = "end";
  return dump_line(j);
}

Status write_stroke_log(const std::string& path, const StrokeLog& log, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!overwrite && fs::exists(path, ec))
    return Status::error(path + ": exists (refusing to overwrite)");
  auto text = to_jsonl(log);
  if (!text) return Status::error(path + ": " + text.message());
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return Status::error(tmp + ": cannot open for writing: " + std::strerror(errno));
    out.write(text->data(), static_cast<std::streamsize>(text->size()));
    out.flush();
    if (!out) {
      fs::remove(tmp, ec);
      return Status::error(tmp + ": write failed");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot rename temporary file: " + ec.message());
  }
  return Status::ok();
}

// === Reading

namespace {

// Field access with messages that name the field. Each returns an empty string on success.
struct Obj {
  const json& j;

  std::string number(const char* key, double& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_number()) return std::string("field '") + key + "' must be a number";
    out = it->get<double>();
    if (!std::isfinite(out)) return std::string("field '") + key + "' is not finite";
    return {};
  }
  std::string integer(const char* key, long long lo, long long hi, int& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_number_integer()) return std::string("field '") + key + "' must be an integer";
    long long v = 0;
    if (it->is_number_unsigned()) {
      const auto u = it->get<unsigned long long>();
      v = u > static_cast<unsigned long long>(hi) ? hi + 1 : static_cast<long long>(u);
    } else {
      v = it->get<long long>();
    }
    if (v < lo || v > hi)
      return std::string("field '") + key + "' = " + std::to_string(v) + " is outside " +
             std::to_string(lo) + ".." + std::to_string(hi);
    out = static_cast<int>(v);
    return {};
  }
  std::string string(const char* key, std::string& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_string()) return std::string("field '") + key + "' must be a string";
    out = it->get<std::string>();
    return {};
  }
  std::string boolean(const char* key, bool& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_boolean()) return std::string("field '") + key + "' must be true or false";
    out = it->get<bool>();
    return {};
  }
  std::string vec3(const char* key, Vec3& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_array() || it->size() != 3) return std::string("field '") + key + "' must be [x, y, z]";
    for (int k = 0; k < 3; ++k) {
      const json& e = (*it)[static_cast<std::size_t>(k)];
      if (!e.is_number()) return std::string("field '") + key + "' must hold numbers";
      out[k] = e.get<double>();
      if (!std::isfinite(out[k])) return std::string("field '") + key + "' is not finite";
    }
    return {};
  }
  std::string object(const char* key, const json*& out) const {
    auto it = j.find(key);
    if (it == j.end()) return std::string("missing field '") + key + "'";
    if (!it->is_object()) return std::string("field '") + key + "' must be an object";
    out = &*it;
    return {};
  }
};

#define PS_TRY(expr)                      \
  do {                                    \
    if (std::string e_ = (expr); !e_.empty()) return e_; \
  } while (0)

std::string parse_camera(const json& j, Camera& c) {
  Obj o{j};
  PS_TRY(o.vec3("eye", c.eye));
  PS_TRY(o.vec3("target", c.target));
  PS_TRY(o.vec3("up", c.up));
  PS_TRY(o.number("fov_y_deg", c.fov_y_deg));
  PS_TRY(o.boolean("orthographic", c.orthographic));
  PS_TRY(o.number("ortho_height", c.ortho_height));
  PS_TRY(o.number("near", c.near_plane));
  PS_TRY(o.number("far", c.far_plane));
  PS_TRY(o.integer("width", 1, 65536, c.width));
  PS_TRY(o.integer("height", 1, 65536, c.height));
  if (auto s = check_camera(c); !s) return s.message();
  return {};
}

std::string parse_header(const json& j, LogHeader& h) {
  if (!j.is_object()) return "header must be a JSON object";
  Obj o{j};
  std::string format;
  if (j.find("format") == j.end())
    return "missing field 'format' (the first line must be the planesketch-stroke-log header)";
  PS_TRY(o.string("format", format));
  if (format != kStrokeLogFormat)
    return "format is '" + format + "', expected '" + std::string(kStrokeLogFormat) + "'";
  PS_TRY(o.integer("version", std::numeric_limits<int>::min(), std::numeric_limits<int>::max(), h.version));
  if (h.version != kStrokeLogVersion)
    return "unsupported stroke-log version " + std::to_string(h.version) + " (this build reads version " +
           std::to_string(kStrokeLogVersion) + ")";
  const json* vp = nullptr;
  PS_TRY(o.object("viewport", vp));
  PS_TRY((Obj{*vp}.integer("width", 1, 65536, h.viewport_width)));
  PS_TRY((Obj{*vp}.integer("height", 1, 65536, h.viewport_height)));
  PS_TRY(o.string("units", h.units));
  const json* cam = nullptr;
  PS_TRY(o.object("camera", cam));
  if (std::string e = parse_camera(*cam, h.camera); !e.empty()) return "camera: " + e;
  if (auto it = j.find("planes"); it != j.end()) {
    if (!it->is_array()) return "field 'planes' must be an array";
    h.planes.clear();
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& pj = (*it)[i];
      if (!pj.is_object()) return "planes[" + std::to_string(i) + "] must be an object";
      Plane p;
      Obj po{pj};
      if (std::string e = po.vec3("normal", p.normal); !e.empty()) return "planes[" + std::to_string(i) + "]: " + e;
      if (std::string e = po.number("offset", p.offset); !e.empty()) return "planes[" + std::to_string(i) + "]: " + e;
      const double n = p.normal.norm();
      if (!(std::abs(n - 1.0) <= 1e-6)) return "planes[" + std::to_string(i) + "]: normal is not unit length";
      // Normalize only what is not already unit length, so reading is idempotent bit for bit.
      if (std::abs(n - 1.0) > 4.0 * std::numeric_limits<double>::epsilon()) p.normal /= n;
      h.planes.push_back(p);
    }
  }
  if (auto it = j.find("generator"); it != j.end()) {
    if (!it->is_string()) return "field 'generator' must be a string";
    h.generator = it->get<std::string>();
  }
  if (auto s = check_header(h); !s) return s.message();
  return {};
}

// Parses one event line. Sets `unknown` (and returns "") for an unknown type, and `end` for the
// session-end marker (only out.t is set then).
std::string parse_event(const json& j, TimedEvent& out, std::string& unknown, bool& end) {
  if (!j.is_object()) return "event must be a JSON object";
  Obj o{j};
  std::string type;
  if (j.find("type") == j.end()) {
    if (j.find("format") != j.end()) return "unexpected second header";
    return "missing field 'type'";
  }
  PS_TRY(o.string("type", type));
  // An empty type is not an unknown one to skip: the caller tells them apart by `unknown` being
  // non-empty, and an empty one let a default event through (found by stroke_log_fuzz).
  if (type.empty()) return "field 'type' is empty";
  PS_TRY(o.number("t", out.t));
  if (out.t < 0.0) return "time t = " + num(out.t) + " is negative";
  if (type == "pen") {
    PenSample s;
    s.t = out.t;
    PS_TRY(o.number("x", s.x));
    PS_TRY(o.number("y", s.y));
    PS_TRY(o.number("pressure", s.pressure));
    if (s.pressure < 0.0 || s.pressure > 1.0) return "pressure " + num(s.pressure) + " is outside [0, 1]";
    PS_TRY(o.number("tilt_x", s.tilt_x));
    PS_TRY(o.number("tilt_y", s.tilt_y));
    std::string tool, phase;
    PS_TRY(o.string("tool", tool));
    if (!parse_tool(tool, s.tool)) return "unknown tool '" + tool + "' (pen, eraser, mouse)";
    PS_TRY(o.string("phase", phase));
    if (!parse_phase(phase, s.phase))
      return "unknown phase '" + phase + "' (down, move, up, proximity-in, proximity-out)";
    if (j.find("buttons") != j.end()) {
      int b = 0;
      PS_TRY(o.integer("buttons", 0, 0xffff, b));
      s.buttons = static_cast<std::uint32_t>(b);
    }
    out.event = s;
  } else if (type == "select_plane") {
    SelectPlane a;
    PS_TRY(o.integer("plane", 0, std::numeric_limits<int>::max(), a.plane));
    out.event = a;
  } else if (type == "translate_plane") {
    TranslatePlane a;
    PS_TRY(o.integer("plane", 0, std::numeric_limits<int>::max(), a.plane));
    PS_TRY(o.number("offset", a.offset));
    out.event = a;
  } else if (type == "camera") {
    CameraChange a;
    const json* cam = nullptr;
    PS_TRY(o.object("camera", cam));
    if (std::string e = parse_camera(*cam, a.camera); !e.empty()) return "camera: " + e;
    out.event = a;
  } else if (type == "tool_mode") {
    SetToolMode a;
    PS_TRY(o.string("mode", a.mode));
    out.event = a;
  } else if (type == "parameter") {
    SetParameter a;
    PS_TRY(o.string("name", a.name));
    PS_TRY(o.number("value", a.value));
    out.event = a;
  } else if (type == "undo") {
    out.event = Undo{};
  } else if (type == "redo") {
    out.event = Redo{};
  } else if (type == "delete") {
    DeleteSection a;
    PS_TRY(o.integer("section", 0, std::numeric_limits<int>::max(), a.section));
    out.event = a;
  } else if (type == "save") {
    Save a;
    PS_TRY(o.string("path", a.path));
    out.event = a;
  } else if (type == "open") {
    OpenFile a;
    PS_TRY(o.string("kind", a.kind));
    PS_TRY(o.string("path", a.path));
    PS_TRY(o.string("digest", a.digest));
    out.event = a;
  } else if (type == "end") {
    end = true;
    return {};
  } else {
    unknown = type;
    return {};
  }
  if (auto s = check_event(out); !s) return s.message();
  return {};
}

#undef PS_TRY

// Rejects lines nested deeper than the format ever needs before handing them to the JSON
// parser, so hostile input cannot exhaust the stack anywhere downstream.
bool nesting_ok(std::string_view line) {
  int depth = 0;
  bool in_string = false, escape = false;
  for (char ch : line) {
    if (in_string) {
      if (escape) escape = false;
      else if (ch == '\\') escape = true;
      else if (ch == '"') in_string = false;
      continue;
    }
    if (ch == '"') in_string = true;
    else if (ch == '[' || ch == '{') {
      if (++depth > kMaxNesting) return false;
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return true;
}

// Parses JSON text; returns "" or a message.
std::string parse_json(std::string_view line, json& out) {
  if (line.size() > kMaxLineBytes) return "line longer than 1 MiB";
  if (!nesting_ok(line)) return "bad JSON: nested deeper than " + std::to_string(kMaxNesting) + " levels";
  try {
    out = json::parse(line.begin(), line.end());
  } catch (const json::parse_error& e) {
    // e.what() = "[json.exception.parse_error.101] parse error at line 1, column 7: ..."
    std::string m = e.what();
    if (auto p = m.find("] "); p != std::string::npos) m = m.substr(p + 2);
    return "bad JSON: " + m;
  } catch (const json::out_of_range& e) {
    // id 406: a literal such as 1e999 overflows a double (JSON has no inf or NaN).
    std::string m = e.what();
    if (auto p = m.find("] "); p != std::string::npos) m = m.substr(p + 2);
    return "a number is not finite (" + m + ")";
  } catch (const json::exception& e) {
    return std::string("bad JSON: ") + e.what();
  }
  return {};
}

bool blank(std::string_view s) {
  for (char c : s)
    if (c != ' ' && c != '\t' && c != '\r') return false;
  return true;
}

}  // namespace

Result<StrokeLog> parse_stroke_log(std::string_view text, const std::string& name,
                                   std::vector<std::string>* warnings) {
  auto fail = [&](int line, const std::string& msg) {
    return Result<StrokeLog>::error(name + ":" + std::to_string(line) + ": " + msg);
  };
  StrokeLog log;
  bool have_header = false;
  double last_t = 0.0;
  int last_t_line = 0;
  int end_line = 0;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    ++line_no;
    const std::size_t nl = text.find('\n', pos);
    const bool terminated = nl != std::string_view::npos;
    std::string_view line = text.substr(pos, terminated ? nl - pos : std::string_view::npos);
    pos = terminated ? nl + 1 : text.size();
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (blank(line)) continue;
    const bool last_unterminated = !terminated;

    json j;
    std::string err = parse_json(line, j);
    if (!have_header) {
      if (!err.empty()) {
        if (last_unterminated) return fail(line_no, "truncated header line (" + err + ")");
        return fail(line_no, "header: " + err);
      }
      if (std::string e = parse_header(j, log.header); !e.empty()) return fail(line_no, e);
      have_header = true;
      continue;
    }
    if (!err.empty()) {
      if (last_unterminated) {
        if (warnings)
          warnings->push_back(name + ":" + std::to_string(line_no) +
                              ": truncated last line dropped (" + err + ")");
        break;
      }
      return fail(line_no, err);
    }
    if (log.end_t)
      return fail(line_no, "line after the session's end marker (line " + std::to_string(end_line) + ")");
    TimedEvent ev;
    ev.line = line_no;
    std::string unknown;
    bool end = false;
    if (std::string e = parse_event(j, ev, unknown, end); !e.empty()) return fail(line_no, e);
    if (end) {
      if (ev.t < last_t)
        return fail(line_no, "end marker time t = " + num(ev.t) + " ms goes back (line " +
                                 std::to_string(last_t_line) + " has t = " + num(last_t) + " ms)");
      log.end_t = ev.t;
      end_line = line_no;
      continue;
    }
    if (!unknown.empty()) {
      if (warnings)
        warnings->push_back(name + ":" + std::to_string(line_no) + ": skipped unknown event type '" +
                            unknown + "'");
      continue;
    }
    if (ev.t < last_t)
      return fail(line_no, "time t = " + num(ev.t) + " ms goes back (line " + std::to_string(last_t_line) +
                               " has t = " + num(last_t) + " ms)");
    last_t = ev.t;
    last_t_line = line_no;
    log.events.push_back(std::move(ev));
  }
  if (!have_header) return fail(line_no == 0 ? 1 : line_no, "empty stroke log (no header line)");
  return log;
}

Result<StrokeLog> read_stroke_log(std::istream& in, const std::string& name,
                                  std::vector<std::string>* warnings) {
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) return Result<StrokeLog>::error(name + ": read error");
  return parse_stroke_log(buf.str(), name, warnings);
}

Result<StrokeLog> read_stroke_log(const std::string& path, std::vector<std::string>* warnings) {
  // An ifstream opens a directory without complaint and reads nothing from it.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return Result<StrokeLog>::error(path + ": is a directory, not a stroke log");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Result<StrokeLog>::error(path + ": cannot open: " + std::strerror(errno));
  return read_stroke_log(in, path, warnings);
}

}  // namespace ps
