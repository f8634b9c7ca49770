#include "modeling/session_io.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "modeling/gltf_export.h"
#include "modeling/mesh_io.h"

namespace ps {
namespace {

using json = nlohmann::json;

// ============================================================ writing

json vec(const Vec2& v) { return json::array({v.x(), v.y()}); }
json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json points(const std::vector<Vec2>& pts) {
  json a = json::array();
  for (const auto& p : pts) a.push_back(vec(p));
  return a;
}

json camera_json(const Camera& c) {
  return {{"eye", vec(c.eye)},           {"target", vec(c.target)}, {"up", vec(c.up)},
          {"fov_y_deg", c.fov_y_deg},    {"orthographic", c.orthographic},
          {"ortho_height", c.ortho_height}, {"near", c.near_plane}, {"far", c.far_plane},
          {"width", c.width},            {"height", c.height}};
}

json selection_json(const VertexSelection& s) {
  return {{"method", selection_method_name(s.method)},
          {"radius", s.radius},
          {"stroke", points(s.stroke)},
          {"camera", camera_json(s.camera)}};
}

json op_json(const SessionOp& op) {
  json j;
  if (const auto* s = std::get_if<SculptOp>(&op)) {
    j["kind"] = sculpt_kind_name(s->kind);
    j["stroke"] = points(s->stroke);
    j["camera"] = camera_json(s->camera);
    if (s->kind == SculptOp::Kind::kCut) j["side"] = vec(s->side);
    if (s->kind == SculptOp::Kind::kExtrude) {
      j["silhouette"] = points(s->silhouette);
      j["silhouette_camera"] = camera_json(s->silhouette_camera);
      // Written only when the plane was turned, so files of unturned extrusions read anywhere.
      if (s->spin != 0.0 || s->tilt != 0.0) {
        j["spin"] = s->spin;
        j["tilt"] = s->tilt;
      }
    }
  } else if (const auto* d = std::get_if<DeformOp>(&op)) {
    j["kind"] = "deform";
    j["handle"] = points(d->handle);
    j["handle_camera"] = camera_json(d->handle_camera);
    j["target"] = points(d->target);
    j["target_camera"] = camera_json(d->target_camera);
    j["shadow"] = points(d->shadow);
    j["shadow_camera"] = camera_json(d->shadow_camera);
    j["roi"] = selection_json(d->roi);
    j["plane_rotation"] = d->plane_rotation;
    j["lambda"] = d->lambda;
  } else {
    const auto& p = std::get<StiffnessOp>(op);
    j["kind"] = "stiffness";
    j["region"] = selection_json(p.region);
    j["value"] = p.value;
  }
  return j;
}

json params_json(const SessionParams& p) {
  const StrokeParams& s = p.stroke;
  return {{"improve", p.improve},
          {"improve_max_faces", p.improve_max_faces},
          {"lambda", p.lambda},
          {"stroke",
           {{"min_spacing_px", s.min_spacing_px},
            {"target_spacing_px", s.target_spacing_px},
            {"min_points", s.min_points},
            {"min_points_closed", s.min_points_closed},
            {"max_points", s.max_points},
            {"fixed_count", s.fixed_count},
            {"smoothing_passes", s.smoothing_passes},
            {"closed_gap_factor", s.closed_gap_factor},
            {"closed_gap_max_fraction", s.closed_gap_max_fraction},
            {"force_closed", s.force_closed},
            {"force_open", s.force_open},
            {"min_length_px", s.min_length_px},
            {"min_length_fraction", s.min_length_fraction},
            {"viewport_px", vec(s.viewport_px)},
            {"min_area_ratio", s.min_area_ratio}}}};
}

// ============================================================ reading
// Every accessor takes the JSON path of the value it reads and throws Bad naming it.

struct Bad {
  std::string path, what;
};

std::string at_key(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at_index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

const char* type_name(const json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

[[noreturn]] void wrong_type(const json& j, const std::string& path, const char* expected) {
  throw Bad{path, std::string("must be ") + expected + " (found " + type_name(j) + ")"};
}

// The object at `path`, refusing fields outside `known`.
const json& object(const json& j, const std::string& path, std::initializer_list<const char*> known) {
  if (!j.is_object()) wrong_type(j, path, "an object");
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (!ok) {
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      throw Bad{at_key(path, key), "unknown field (known here: " + list + ")"};
    }
  }
  return j;
}

const json& field(const json& obj, const std::string& path, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw Bad{at_key(path, key), "missing field"};
  return *it;
}

double number(const json& j, const std::string& path) {
  if (!j.is_number()) wrong_type(j, path, "a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw Bad{path, "must be a finite number"};
  return v;
}

double number_in(const json& j, const std::string& path, double lo, double hi) {
  const double v = number(j, path);
  if (v < lo || v > hi) {
    std::ostringstream m;
    m << "must lie in [" << lo << ", " << hi << "] (found " << v << ")";
    throw Bad{path, m.str()};
  }
  return v;
}

double positive(const json& j, const std::string& path) {
  const double v = number(j, path);
  if (!(v > 0.0)) throw Bad{path, "must be positive"};
  return v;
}

long long integer(const json& j, const std::string& path, long long lo, long long hi) {
  if (!j.is_number_integer()) wrong_type(j, path, "an integer");
  const long long v = j.is_number_unsigned() && j.get<unsigned long long>() > static_cast<unsigned long long>(hi)
                          ? hi + 1
                          : j.get<long long>();
  if (v < lo || v > hi)
    throw Bad{path, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (found " + j.dump() + ")"};
  return v;
}

bool boolean(const json& j, const std::string& path) {
  if (!j.is_boolean()) wrong_type(j, path, "true or false");
  return j.get<bool>();
}

std::string string(const json& j, const std::string& path) {
  if (!j.is_string()) wrong_type(j, path, "a string");
  return j.get<std::string>();
}

const json& array(const json& j, const std::string& path) {
  if (!j.is_array()) wrong_type(j, path, "an array");
  return j;
}

template <int N>
Eigen::Matrix<double, N, 1> vec_n(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != static_cast<std::size_t>(N))
    throw Bad{path, "must be an array of " + std::to_string(N) + " numbers" +
                        (j.is_array() ? " (found " + std::to_string(j.size()) + ")" : std::string(" (found ") + type_name(j) + ")")};
  Eigen::Matrix<double, N, 1> v;
  for (int k = 0; k < N; ++k) v[k] = number(j[static_cast<std::size_t>(k)], at_index(path, static_cast<std::size_t>(k)));
  return v;
}

std::vector<Vec2> points_from(const json& j, const std::string& path) {
  std::vector<Vec2> out;
  const json& a = array(j, path);
  out.reserve(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out.push_back(vec_n<2>(a[i], at_index(path, i)));
  return out;
}

Camera camera_from(const json& j, const std::string& path) {
  const json& o = object(j, path, {"eye", "target", "up", "fov_y_deg", "orthographic", "ortho_height", "near", "far",
                                   "width", "height"});
  Camera c;
  c.eye = vec_n<3>(field(o, path, "eye"), at_key(path, "eye"));
  c.target = vec_n<3>(field(o, path, "target"), at_key(path, "target"));
  c.up = vec_n<3>(field(o, path, "up"), at_key(path, "up"));
  c.fov_y_deg = number_in(field(o, path, "fov_y_deg"), at_key(path, "fov_y_deg"), 0.0, 180.0);
  c.orthographic = boolean(field(o, path, "orthographic"), at_key(path, "orthographic"));
  c.ortho_height = positive(field(o, path, "ortho_height"), at_key(path, "ortho_height"));
  c.near_plane = positive(field(o, path, "near"), at_key(path, "near"));
  c.far_plane = positive(field(o, path, "far"), at_key(path, "far"));
  c.width = static_cast<int>(integer(field(o, path, "width"), at_key(path, "width"), 1, 65536));
  c.height = static_cast<int>(integer(field(o, path, "height"), at_key(path, "height"), 1, 65536));
  if (!(c.far_plane > c.near_plane)) throw Bad{at_key(path, "far"), "must be greater than near"};
  if (!((c.target - c.eye).norm() > 0.0)) throw Bad{at_key(path, "target"), "must differ from eye"};
  return c;
}

VertexSelection selection_from(const json& j, const std::string& path) {
  const json& o = object(j, path, {"method", "radius", "stroke", "camera"});
  VertexSelection s;
  const std::string m = string(field(o, path, "method"), at_key(path, "method"));
  if (m == "radius") s.method = VertexSelection::Method::kRadius;
  else if (m == "lasso") s.method = VertexSelection::Method::kLasso;
  else if (m == "brush") s.method = VertexSelection::Method::kBrush;
  else throw Bad{at_key(path, "method"), "unknown selection method '" + m + "' (known: radius, lasso, brush)"};
  s.radius = number(field(o, path, "radius"), at_key(path, "radius"));
  s.stroke = points_from(field(o, path, "stroke"), at_key(path, "stroke"));
  s.camera = camera_from(field(o, path, "camera"), at_key(path, "camera"));
  return s;
}

SessionOp op_from(const json& j, const std::string& path) {
  if (!j.is_object()) wrong_type(j, path, "an object");
  const std::string kind = string(field(j, path, "kind"), at_key(path, "kind"));
  auto key = [&](const char* k) { return at_key(path, k); };
  auto get = [&](const char* k) -> const json& { return field(j, path, k); };
  if (kind == "cut" || kind == "tunnel" || kind == "smooth" || kind == "extrude") {
    SculptOp s;
    if (kind == "cut") {
      s.kind = SculptOp::Kind::kCut;
      object(j, path, {"kind", "stroke", "camera", "side"});
      s.side = vec_n<2>(get("side"), key("side"));
    } else if (kind == "extrude") {
      s.kind = SculptOp::Kind::kExtrude;
      object(j, path, {"kind", "stroke", "camera", "silhouette", "silhouette_camera", "spin", "tilt"});
      s.silhouette = points_from(get("silhouette"), key("silhouette"));
      s.silhouette_camera = camera_from(get("silhouette_camera"), key("silhouette_camera"));
      // Optional (absent: the plane was not turned); the range is checked when the op is applied.
      if (j.contains("spin")) s.spin = number(get("spin"), key("spin"));
      if (j.contains("tilt")) s.tilt = number(get("tilt"), key("tilt"));
    } else {
      s.kind = kind == "tunnel" ? SculptOp::Kind::kTunnel : SculptOp::Kind::kSmooth;
      object(j, path, {"kind", "stroke", "camera"});
    }
    s.stroke = points_from(get("stroke"), key("stroke"));
    s.camera = camera_from(get("camera"), key("camera"));
    return s;
  }
  if (kind == "deform") {
    object(j, path, {"kind", "handle", "handle_camera", "target", "target_camera", "shadow", "shadow_camera", "roi",
                     "plane_rotation", "lambda"});
    DeformOp d;
    d.handle = points_from(get("handle"), key("handle"));
    d.handle_camera = camera_from(get("handle_camera"), key("handle_camera"));
    d.target = points_from(get("target"), key("target"));
    d.target_camera = camera_from(get("target_camera"), key("target_camera"));
    d.shadow = points_from(get("shadow"), key("shadow"));
    d.shadow_camera = camera_from(get("shadow_camera"), key("shadow_camera"));
    d.roi = selection_from(get("roi"), key("roi"));
    d.plane_rotation = number(get("plane_rotation"), key("plane_rotation"));
    d.lambda = number_in(get("lambda"), key("lambda"), 0.0, 1.0);
    return d;
  }
  if (kind == "stiffness") {
    object(j, path, {"kind", "region", "value"});
    StiffnessOp p;
    p.region = selection_from(get("region"), key("region"));
    p.value = number_in(get("value"), key("value"), 0.0, 1.0);
    return p;
  }
  throw Bad{key("kind"), "unknown operation kind '" + kind + "' (known: cut, tunnel, smooth, extrude, deform, stiffness)"};
}

SessionParams params_from(const json& j, const std::string& path) {
  const json& o = object(j, path, {"improve", "improve_max_faces", "lambda", "stroke"});
  SessionParams p;
  p.improve = boolean(field(o, path, "improve"), at_key(path, "improve"));
  p.improve_max_faces = static_cast<std::size_t>(
      integer(field(o, path, "improve_max_faces"), at_key(path, "improve_max_faces"), 0, 1'000'000'000));
  p.lambda = number_in(field(o, path, "lambda"), at_key(path, "lambda"), 0.0, 1.0);
  const std::string sp = at_key(path, "stroke");
  const json& s = object(field(o, path, "stroke"), sp,
                         {"min_spacing_px", "target_spacing_px", "min_points", "min_points_closed", "max_points",
                          "fixed_count", "smoothing_passes", "closed_gap_factor", "closed_gap_max_fraction",
                          "force_closed", "force_open", "min_length_px", "min_length_fraction", "viewport_px",
                          "min_area_ratio"});
  auto num = [&](const char* k) { return number(field(s, sp, k), at_key(sp, k)); };
  auto pos = [&](const char* k) { return positive(field(s, sp, k), at_key(sp, k)); };
  auto cnt = [&](const char* k) { return static_cast<int>(integer(field(s, sp, k), at_key(sp, k), 0, 1'000'000)); };
  auto flag = [&](const char* k) { return boolean(field(s, sp, k), at_key(sp, k)); };
  StrokeParams& st = p.stroke;
  st.min_spacing_px = pos("min_spacing_px");
  st.target_spacing_px = pos("target_spacing_px");
  st.min_points = cnt("min_points");
  st.min_points_closed = cnt("min_points_closed");
  st.max_points = cnt("max_points");
  st.fixed_count = cnt("fixed_count");
  st.smoothing_passes = cnt("smoothing_passes");
  st.closed_gap_factor = num("closed_gap_factor");
  st.closed_gap_max_fraction = num("closed_gap_max_fraction");
  st.force_closed = flag("force_closed");
  st.force_open = flag("force_open");
  st.min_length_px = num("min_length_px");
  st.min_length_fraction = num("min_length_fraction");
  st.viewport_px = vec_n<2>(field(s, sp, "viewport_px"), at_key(sp, "viewport_px"));
  st.min_area_ratio = num("min_area_ratio");
  return p;
}

SectionSet sections_from(const json& j, const std::string& path) {
  const json& o = object(j, path, {"planes", "curves"});
  SectionSet set;
  const std::string pp = at_key(path, "planes");
  const json& planes = array(field(o, path, "planes"), pp);
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const std::string ip = at_index(pp, i);
    const json& pl = object(planes[i], ip, {"normal", "offset"});
    Plane plane;
    plane.normal = vec_n<3>(field(pl, ip, "normal"), at_key(ip, "normal"));
    if (std::abs(plane.normal.norm() - 1.0) > 1e-9) throw Bad{at_key(ip, "normal"), "must have unit length"};
    plane.offset = number(field(pl, ip, "offset"), at_key(ip, "offset"));
    set.planes.push_back(plane);
  }
  const std::string cp = at_key(path, "curves");
  const json& curves = array(field(o, path, "curves"), cp);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const std::string ip = at_index(cp, i);
    const json& c = object(curves[i], ip, {"plane", "points"});
    CrossSection cs;
    if (set.planes.empty()) throw Bad{at_key(ip, "plane"), "refers to a plane but 'planes' is empty"};
    cs.plane = static_cast<int>(integer(field(c, ip, "plane"), at_key(ip, "plane"), 0,
                                        static_cast<long long>(set.planes.size()) - 1));
    const std::string ptp = at_key(ip, "points");
    const json& pts = array(field(c, ip, "points"), ptp);
    if (pts.size() < 3) throw Bad{ptp, "a cross section needs at least 3 points (found " + std::to_string(pts.size()) + ")"};
    for (std::size_t k = 0; k < pts.size(); ++k) cs.points.push_back(vec_n<3>(pts[k], at_index(ptp, k)));
    set.curves.push_back(std::move(cs));
  }
  return set;
}

TopologyEdit edit_from(const json& j, const std::string& path) {
  object(j, path, {"kind", "stroke"});
  std::string where;
  auto e = topology_edit_from_json(j, &where);
  if (!e) throw Bad{where.empty() ? path : path + "." + where, e.message()};
  return std::move(*e);
}

TriMesh base_from(const json& j, const std::string& path) {
  const json& o = object(j, path, {"vertices", "faces"});
  TriMesh m;
  const std::string vp = at_key(path, "vertices");
  const json& vs = array(field(o, path, "vertices"), vp);
  m.vertices.reserve(vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i) m.vertices.push_back(vec_n<3>(vs[i], at_index(vp, i)));
  const std::string fp = at_key(path, "faces");
  const json& fs = array(field(o, path, "faces"), fp);
  if (fs.empty()) throw Bad{fp, "the base mesh has no faces"};
  const long long last = static_cast<long long>(m.vertices.size()) - 1;
  for (std::size_t i = 0; i < fs.size(); ++i) {
    const std::string ip = at_index(fp, i);
    if (!fs[i].is_array() || fs[i].size() != 3) throw Bad{ip, "must be an array of 3 vertex indices"};
    Face f;
    for (std::size_t k = 0; k < 3; ++k) f[k] = static_cast<int>(integer(fs[i][k], at_index(ip, k), 0, last));
    m.faces.push_back(f);
  }
  return m;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Status write_text_atomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path tmp = target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return Status::error(path + ": cannot be opened for writing");
    f << text;
    f.flush();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      return Status::error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot be written (" + ec.message() + ")");
  }
  return Status::ok();
}

}  // namespace

std::string session_to_json(const SessionParams& params, const SessionState& state, const std::string& mesh_file) {
  json j;
  j["format"] = kSessionFormat;
  j["version"] = kSessionVersion;
  j["units"] = state.sections.units.empty() ? std::string("unit") : state.sections.units;
  j["params"] = params_json(params);
  if (state.base.empty()) {
    j["base"] = nullptr;
  } else {
    json vs = json::array(), fs = json::array();
    for (const auto& v : state.base.vertices) vs.push_back(vec(v));
    for (const auto& f : state.base.faces) fs.push_back(json::array({f[0], f[1], f[2]}));
    j["base"] = {{"vertices", std::move(vs)}, {"faces", std::move(fs)}};
  }
  json planes = json::array(), curves = json::array();
  for (const auto& p : state.sections.planes) planes.push_back({{"normal", vec(p.normal)}, {"offset", p.offset}});
  for (const auto& c : state.sections.curves) {
    json pts = json::array();
    for (const auto& p : c.points) pts.push_back(vec(p));
    curves.push_back({{"plane", c.plane}, {"points", std::move(pts)}});
  }
  j["sections"] = {{"planes", std::move(planes)}, {"curves", std::move(curves)}};
  json ops = json::array();
  for (const auto& op : state.ops) ops.push_back(op_json(op));
  j["ops"] = std::move(ops);
  // Written only when there are some: files without topology edits stay as they were.
  if (!state.edits.empty()) {
    json edits = json::array();
    for (const auto& e : state.edits) edits.push_back(topology_edit_to_json(e));
    j["edits"] = std::move(edits);
  }
  if (mesh_file.empty() || state.model.empty()) {
    j["mesh"] = nullptr;
  } else {
    j["mesh"] = {{"path", mesh_file}, {"vertices", state.model.vertices.size()}, {"faces", state.model.faces.size()}};
  }
  return j.dump(1) + "\n";
}

Result<SessionFile> session_from_json(const std::string& text, const std::string& name) {
  using R = Result<SessionFile>;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    return R::error(name + ": not valid JSON (" + what + ")");
  }
  try {
    const json& o = object(j, "", {"format", "version", "units", "params", "base", "sections", "ops", "edits", "mesh"});
    if (string(field(o, "", "format"), "format") != kSessionFormat)
      throw Bad{"format", std::string("must be \"") + kSessionFormat + "\" (found " + field(o, "", "format").dump() + ")"};
    const json& v = field(o, "", "version");
    if (!v.is_number_integer()) wrong_type(v, "version", "an integer");
    if (v.get<long long>() != kSessionVersion)
      throw Bad{"version", "unsupported session version " + v.dump() + " (this planesketch reads version " +
                               std::to_string(kSessionVersion) + ")"};
    SessionFile f;
    f.params = params_from(field(o, "", "params"), "params");
    if (const json& b = field(o, "", "base"); !b.is_null()) f.state.base = base_from(b, "base");
    f.state.sections = sections_from(field(o, "", "sections"), "sections");
    f.state.sections.units = string(field(o, "", "units"), "units");
    if (!f.state.base.empty() && !f.state.sections.curves.empty())
      throw Bad{"sections.curves", "must be empty when the session has an imported base mesh"};
    const json& ops = array(field(o, "", "ops"), "ops");
    for (std::size_t i = 0; i < ops.size(); ++i) f.state.ops.push_back(op_from(ops[i], at_index("ops", i)));
    if (o.contains("edits")) {
      const json& edits = array(o["edits"], "edits");
      for (std::size_t i = 0; i < edits.size(); ++i) f.state.edits.push_back(edit_from(edits[i], at_index("edits", i)));
      if (!f.state.edits.empty() && !f.state.base.empty())
        throw Bad{"edits", "must be empty when the session has an imported base mesh"};
    }
    if (const json& m = field(o, "", "mesh"); !m.is_null()) {
      const json& mo = object(m, "mesh", {"path", "vertices", "faces"});
      f.mesh = string(field(mo, "mesh", "path"), "mesh.path");
      if (f.mesh.empty()) throw Bad{"mesh.path", "must not be empty"};
      f.mesh_vertices = static_cast<std::size_t>(integer(field(mo, "mesh", "vertices"), "mesh.vertices", 0, 2'000'000'000));
      f.mesh_faces = static_cast<std::size_t>(integer(field(mo, "mesh", "faces"), "mesh.faces", 0, 2'000'000'000));
    }
    return f;
  } catch (const Bad& b) {
    return R::error(name + ": " + (b.path.empty() ? std::string("(document)") : b.path) + ": " + b.what);
  }
}

std::string session_mesh_path(const std::string& session_path) {
  std::filesystem::path p(session_path);
  std::filesystem::path stem = p;
  if (p.extension() == ".json") stem.replace_extension();
  return stem.string() + ".mesh.ply";
}

Status save_session(const std::string& path, const SessionParams& params, const SessionState& state) {
  if (path.empty()) return Status::error("no session file name given");
  std::string mesh_file;
  if (!state.model.empty()) {
    const std::string mesh_path = session_mesh_path(path);
    if (auto st = write_mesh(mesh_path, state.model); !st) return st;
    mesh_file = std::filesystem::path(mesh_path).filename().string();
  }
  return write_text_atomically(path, session_to_json(params, state, mesh_file));
}

namespace {
bool is_glb(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ".glb";
}
}  // namespace

bool is_export_extension(const std::string& path) { return is_glb(path) || is_mesh_extension(path); }

Status export_model(const std::string& path, const TriMesh& model) {
  if (model.empty()) return Status::error(path + ": there is no model to export");
  if (is_glb(path)) return write_glb(path, model);
  if (!is_mesh_extension(path))
    return Status::error(path + ": unknown export extension (expected .obj, .off, .ply, .stl or .glb)");
  return write_mesh(path, model);
}

std::string mesh_difference(const TriMesh& a, const TriMesh& b) {
  auto str = [](const Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return s.str();
  };
  if (a.vertices.size() != b.vertices.size() || a.faces.size() != b.faces.size())
    return std::to_string(a.vertices.size()) + " vertices / " + std::to_string(a.faces.size()) + " faces against " +
           std::to_string(b.vertices.size()) + " / " + std::to_string(b.faces.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if (a.vertices[i] != b.vertices[i]) {
      double worst = 0.0;
      for (std::size_t k = 0; k < a.vertices.size(); ++k) worst = std::max(worst, (a.vertices[k] - b.vertices[k]).norm());
      std::ostringstream m;
      m << "vertex " << i << " differs: " << str(a.vertices[i]) << " against " << str(b.vertices[i])
        << " (largest distance over all vertices " << worst << ")";
      return m.str();
    }
  for (std::size_t i = 0; i < a.faces.size(); ++i)
    if (a.faces[i] != b.faces[i])
      return "face " + std::to_string(i) + " differs: (" + std::to_string(a.faces[i][0]) + ", " +
             std::to_string(a.faces[i][1]) + ", " + std::to_string(a.faces[i][2]) + ") against (" +
             std::to_string(b.faces[i][0]) + ", " + std::to_string(b.faces[i][1]) + ", " + std::to_string(b.faces[i][2]) + ")";
  return {};
}

Status load_session(const std::string& path, SketchSession& session, SessionLoadReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string text;
  {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return Status::error(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) return Status::error(path + ": is a directory, not a session file");
    std::ifstream f(path, std::ios::binary);
    if (!f) return Status::error(path + ": cannot be opened for reading");
    std::ostringstream s;
    s << f.rdbuf();
    text = s.str();
    if (text.empty()) return Status::error(path + ": file is empty");
  }
  auto file = session_from_json(text, path);
  if (!file) return file.status();
  SessionLoadReport r;
  r.read_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  if (auto st = session.load(file->params, file->state); !st)
    return Status::error(path + ": the saved sections and operations do not rebuild: " + st.message());
  r.rebuild_ms = ms_since(t1);
  if (!file->mesh.empty()) {
    const std::filesystem::path mp = std::filesystem::path(file->mesh).is_absolute()
                                         ? std::filesystem::path(file->mesh)
                                         : std::filesystem::path(path).parent_path() / file->mesh;
    r.mesh_path = mp.string();
    auto saved = read_mesh(r.mesh_path);
    if (!saved) {
      r.mesh_problem = "the saved mesh cannot be read: " + saved.message();
    } else {
      r.mesh_checked = true;
      r.mesh_problem = mesh_difference(session.state().model, *saved);
      if (!r.mesh_problem.empty()) r.mesh_problem = "the rebuilt model differs from the saved mesh " + r.mesh_path + ": " + r.mesh_problem;
      r.mesh_matches = r.mesh_problem.empty();
    }
  } else if (!session.state().model.empty()) {
    r.mesh_problem = "the document records no saved mesh to check the rebuilt model against";
  }
  if (report) *report = std::move(r);
  return Status::ok();
}

}  // namespace ps
