// Session files (issue 7 point 6) and imported base meshes (issue 6): save -> load gives the
// identical state and the bit-identical model; malformed documents are refused naming the JSON
// path and leave the session untouched; a mesh imported as the base is checked, sculpted,
// deformed, undone and saved with the session.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "modeling/deform_tool.h"
#include "modeling/gltf_export.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/session_io.h"
#include "modeling/sketch_session.h"
#include "tests/section_fixtures.h"

namespace ps {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::axis_plane;
using testing::circle;
using testing::window_circle;

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("ps_session_files_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
}

Camera front_camera() { return testing::look_at(Vec3(0, 0, 9), Vec3::Zero(), Vec3::UnitY(), 640, 480); }

// Three slices of the unit sphere on three planes (the sculpting tests' blob), unimproved.
SketchSession blob() {
  SessionParams params;
  params.improve = false;
  SketchSession s(params);
  for (const auto& [axis, offset] : {std::pair{2, 0.05}, std::pair{0, 0.1}, std::pair{1, -0.15}}) {
    const Status st = s.add_section(axis_plane(axis, offset), circle(axis, offset, std::sqrt(1 - offset * offset)));
    EXPECT_TRUE(st) << st.message();
  }
  return s;
}

SculptOp tunnel_op(double radius_px = 30) {
  SculptOp op;
  op.kind = SculptOp::Kind::kTunnel;
  op.camera = front_camera();
  op.stroke = window_circle(Vec2(320, 240), radius_px, 40);
  return op;
}

// A lasso around the whole model seen from the front.
StiffnessOp paint_all(double value) {
  StiffnessOp p;
  p.region.method = VertexSelection::Method::kLasso;
  p.region.camera = front_camera();
  p.region.stroke = {Vec2(50, 20), Vec2(590, 20), Vec2(590, 460), Vec2(50, 460)};
  p.value = value;
  return p;
}

void expect_same_stiffness(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i])) EXPECT_TRUE(std::isnan(b[i])) << i;
    else EXPECT_EQ(a[i], b[i]) << i;
  }
}

// Everything a session is made of, compared exactly: the serialised form covers every field of
// the params, base, sections and ops; the derived state is compared bit for bit.
void expect_same_session(const SketchSession& a, const SketchSession& b) {
  EXPECT_EQ(session_to_json(a.params(), a.state(), "m"), session_to_json(b.params(), b.state(), "m"));
  EXPECT_EQ(a.state().base.vertices, b.state().base.vertices);
  EXPECT_EQ(a.state().base.faces, b.state().base.faces);
  ASSERT_EQ(a.state().sections.curves.size(), b.state().sections.curves.size());
  for (std::size_t i = 0; i < a.state().sections.curves.size(); ++i) {
    EXPECT_EQ(a.state().sections.curves[i].plane, b.state().sections.curves[i].plane);
    EXPECT_EQ(a.state().sections.curves[i].points, b.state().sections.curves[i].points);
  }
  ASSERT_EQ(a.state().sewn.curves.size(), b.state().sewn.curves.size());
  for (std::size_t i = 0; i < a.state().sewn.curves.size(); ++i)
    EXPECT_EQ(a.state().sewn.curves[i].points, b.state().sewn.curves[i].points);
  EXPECT_EQ(a.state().model.vertices, b.state().model.vertices);
  EXPECT_EQ(a.state().model.faces, b.state().model.faces);
  expect_same_stiffness(a.state().stiffness, b.state().stiffness);
  EXPECT_EQ(a.state().hints, b.state().hints);
}

TEST(SessionFiles, SaveLoadGivesTheIdenticalStateAndModel) {
  SketchSession s = blob();
  ASSERT_TRUE(s.paint_stiffness(paint_all(0.25)));
  ASSERT_TRUE(s.sculpt(tunnel_op()));
  ASSERT_TRUE(s.set_parameter("lambda", 0.3));
  TempDir dir;
  const std::string path = dir.file("s.json");
  ASSERT_TRUE(save_session(path, s));
  EXPECT_TRUE(fs::exists(dir.file("s.mesh.ply")));

  SketchSession loaded;
  SessionLoadReport r;
  const Status st = load_session(path, loaded, &r);
  ASSERT_TRUE(st) << st.message();
  EXPECT_TRUE(r.mesh_checked);
  EXPECT_TRUE(r.mesh_matches) << r.mesh_problem;
  EXPECT_EQ(loaded.params().lambda, 0.3);
  EXPECT_FALSE(loaded.params().improve);
  expect_same_session(s, loaded);
  EXPECT_FALSE(loaded.can_undo());  // history starts at the loaded state
  // Saving the loaded session writes the same bytes.
  ASSERT_TRUE(save_session(dir.file("again.json"), loaded));
  json a = json::parse(read_text(path)), b = json::parse(read_text(dir.file("again.json")));
  a["mesh"]["path"] = b["mesh"]["path"] = "";
  EXPECT_EQ(a, b);
  EXPECT_EQ(read_text(dir.file("s.mesh.ply")), read_text(dir.file("again.mesh.ply")));
  // The loaded session goes on like the original: undo-able operations on top.
  ASSERT_TRUE(loaded.paint_stiffness(paint_all(0.9)));
  ASSERT_TRUE(loaded.undo());
  expect_same_session(s, loaded);
}

TEST(SessionFiles, EveryOperationKindRoundTripsExactly) {
  // Values that need all 17 digits, and every field of every operation.
  auto cam = [](double k) {
    Camera c = front_camera();
    c.eye = Vec3(0.1 + k, -1.0 / 3.0, 9.0 + M_PI * 1e-9);
    c.fov_y_deg = 37.123456789012345 + k;
    c.orthographic = k > 1.5;
    c.ortho_height = 2.0 / 7.0;
    c.width = 641;
    return c;
  };
  SessionState st;
  st.sections.planes = {axis_plane(2, 0.1 / 3.0)};
  st.sections.curves.push_back(CrossSection{0, circle(2, 0.1 / 3.0, 0.7, 7)});
  for (auto kind : {SculptOp::Kind::kCut, SculptOp::Kind::kTunnel, SculptOp::Kind::kSmooth, SculptOp::Kind::kExtrude}) {
    SculptOp op;
    op.kind = kind;
    op.stroke = window_circle(Vec2(320.1, 240.2), 30.3, 9);
    op.camera = cam(static_cast<double>(kind));
    if (kind == SculptOp::Kind::kCut) op.side = Vec2(1.0 / 3.0, 2.0 / 3.0);
    if (kind == SculptOp::Kind::kExtrude) {
      op.silhouette = window_circle(Vec2(10, 20), 5.5, 5);
      op.silhouette_camera = cam(2.0);
    }
    st.ops.push_back(op);
    if (kind == SculptOp::Kind::kExtrude) {  // the same on a turned reference plane
      op.spin = -1.0 / 3.0;
      op.tilt = M_PI / 7.0;
      st.ops.push_back(op);
    }
  }
  DeformOp d;
  d.handle = {Vec2(1.1, 2.2), Vec2(3.3, 4.4)};
  d.handle_camera = cam(0.5);
  d.target = {Vec2(5.5, 6.6), Vec2(7.7, 8.8), Vec2(9.9, 0.1)};
  d.target_camera = cam(0.25);
  d.shadow = {Vec2(0.3, 0.7), Vec2(1e-300, 1e300)};
  d.shadow_camera = cam(3.0);
  d.roi.method = VertexSelection::Method::kBrush;
  d.roi.radius = 0.123456789;
  d.roi.stroke = {Vec2(4, 5)};
  d.roi.camera = cam(0.75);
  d.plane_rotation = -M_PI / 7.0;
  d.lambda = 1.0 / 3.0;
  st.ops.push_back(d);
  StiffnessOp p = paint_all(0.7);
  p.region.radius = 0.05;
  st.ops.push_back(p);
  st.model.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  st.model.faces = {Face{0, 1, 2}};
  SessionParams params;
  params.lambda = 0.1;
  params.stroke.min_spacing_px = 12.5;
  params.stroke.viewport_px = Vec2(1280, 800);
  params.improve_max_faces = 1234;

  const std::string text = session_to_json(params, st, "x.ply");
  auto f = session_from_json(text, "t.json");
  ASSERT_TRUE(f) << f.message();
  EXPECT_TRUE(f->state.model.empty());  // the model is never read from the document
  f->state.model = st.model;
  EXPECT_EQ(session_to_json(f->params, f->state, f->mesh), text);
  ASSERT_EQ(f->state.ops.size(), 7u);
  // The plane's rotation is written only when it was turned, and read back exactly.
  const json doc = json::parse(text);
  EXPECT_FALSE(doc["ops"][3].contains("spin") || doc["ops"][3].contains("tilt"));
  EXPECT_EQ(std::get<SculptOp>(f->state.ops[3]).spin, 0.0);
  EXPECT_EQ(std::get<SculptOp>(f->state.ops[4]).spin, -1.0 / 3.0);
  EXPECT_EQ(std::get<SculptOp>(f->state.ops[4]).tilt, M_PI / 7.0);
  const auto& d2 = std::get<DeformOp>(f->state.ops[5]);
  EXPECT_EQ(d2.plane_rotation, d.plane_rotation);
  EXPECT_EQ(d2.lambda, d.lambda);
  EXPECT_EQ(d2.shadow, d.shadow);
  EXPECT_EQ(d2.shadow_camera.eye, d.shadow_camera.eye);
  EXPECT_EQ(d2.shadow_camera.fov_y_deg, d.shadow_camera.fov_y_deg);
  EXPECT_TRUE(d2.shadow_camera.orthographic);
  EXPECT_EQ(d2.roi.method, VertexSelection::Method::kBrush);
  EXPECT_EQ(d2.roi.radius, d.roi.radius);
  const auto& cut = std::get<SculptOp>(f->state.ops[0]);
  EXPECT_EQ(cut.kind, SculptOp::Kind::kCut);
  EXPECT_EQ(cut.side, Vec2(1.0 / 3.0, 2.0 / 3.0));
  const auto& ex = std::get<SculptOp>(f->state.ops[3]);
  EXPECT_EQ(ex.silhouette, std::get<SculptOp>(st.ops[3]).silhouette);
  EXPECT_EQ(std::get<StiffnessOp>(f->state.ops[6]).value, 0.7);
  EXPECT_EQ(f->params.stroke.min_spacing_px, 12.5);
  EXPECT_EQ(f->params.improve_max_faces, 1234u);
  EXPECT_EQ(f->state.sections.planes[0].offset, 0.1 / 3.0);
  EXPECT_EQ(f->state.sections.curves[0].points, st.sections.curves[0].points);
  EXPECT_EQ(f->mesh, "x.ply");
  EXPECT_EQ(f->mesh_vertices, 3u);
  EXPECT_EQ(f->mesh_faces, 1u);
  EXPECT_EQ(session_to_json(params, st, "").find("x.ply"), std::string::npos);
}

// A bad document: refused with `words` in the message, and the session it was loaded into is
// untouched.
class BadSessionFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    good_ = blob();
    ASSERT_TRUE(good_.sculpt(tunnel_op()));
    path_ = dir_.file("good.json");
    ASSERT_TRUE(save_session(path_, good_));
    doc_ = json::parse(read_text(path_));
    target_ = blob();  // the session a bad file is loaded into
  }
  void expect_refused(const std::string& text, const std::string& words) {
    const std::string bad = dir_.file("bad.json");
    write_text(bad, text);
    const std::string before = session_to_json(target_.params(), target_.state(), "m");
    const TriMesh model = target_.state().model;
    const Status st = load_session(bad, target_);
    ASSERT_FALSE(st) << "accepted; expected: " << words;
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    EXPECT_EQ(st.message().rfind(bad, 0), 0u) << "the message names the file: " << st.message();
    EXPECT_EQ(session_to_json(target_.params(), target_.state(), "m"), before);
    EXPECT_EQ(target_.state().model.vertices, model.vertices);
    EXPECT_TRUE(target_.can_undo());  // history kept
  }
  void expect_refused(const json& j, const std::string& words) { expect_refused(j.dump(), words); }

  TempDir dir_;
  SketchSession good_, target_;
  std::string path_;
  json doc_;
};

TEST_F(BadSessionFiles, TruncatedAndNotJson) {
  const std::string text = read_text(path_);
  expect_refused(text.substr(0, text.size() / 2), "not valid JSON");
  expect_refused(std::string(), std::string("file is empty"));
  expect_refused(std::string("[1, 2]"), "(document): must be an object (found an array)");
}

TEST_F(BadSessionFiles, NonFiniteNumbers) {
  std::string text = doc_.dump();
  const std::string key = "\"lambda\":0.5";
  ASSERT_NE(text.find(key), std::string::npos);
  expect_refused(std::string(text).replace(text.find(key), key.size(), "\"lambda\":NaN"), "not valid JSON");
  expect_refused(std::string(text).replace(text.find(key), key.size(), "\"lambda\":1e999"), "not valid JSON (number overflow parsing '1e999')");
}

TEST_F(BadSessionFiles, WrongTypes) {
  json j = doc_;
  j["params"]["lambda"] = "half";
  expect_refused(j, "params.lambda: must be a number (found a string)");
  j = doc_;
  j["ops"][0]["stroke"][3] = json::array({1, "x"});
  expect_refused(j, "ops[0].stroke[3][1]: must be a number (found a string)");
  j = doc_;
  j["sections"]["curves"][1]["plane"] = 0.5;
  expect_refused(j, "sections.curves[1].plane: must be an integer (found a number)");
  j = doc_;
  j["ops"][0]["camera"]["orthographic"] = 0;
  expect_refused(j, "ops[0].camera.orthographic: must be true or false");
  j = doc_;
  j["sections"]["curves"][0]["points"][0] = json::array({1, 2});
  expect_refused(j, "sections.curves[0].points[0]: must be an array of 3 numbers (found 2)");
  j = doc_;
  j["sections"]["curves"][0]["plane"] = 7;
  expect_refused(j, "sections.curves[0].plane: must lie in [0, 2] (found 7)");
  j = doc_;
  j["params"]["lambda"] = 1.5;
  expect_refused(j, "params.lambda: must lie in [0, 1]");
  j = doc_;
  j["ops"][0] = json{{"kind", "extrude"}, {"stroke", json::array()}, {"camera", j["ops"][0]["camera"]},
                     {"silhouette", json::array()}, {"silhouette_camera", j["ops"][0]["camera"]}, {"tilt", "steep"}};
  expect_refused(j, "ops[0].tilt: must be a number (found a string)");
}

TEST_F(BadSessionFiles, UnknownKindsAndFields) {
  json j = doc_;
  j["ops"][0]["kind"] = "twist";
  expect_refused(j, "ops[0].kind: unknown operation kind 'twist' (known: cut, tunnel, smooth, extrude, deform, stiffness)");
  j = doc_;
  j["params"]["lamda"] = 0.5;
  expect_refused(j, "params.lamda: unknown field");
  j = doc_;
  j["ops"][0]["side"] = json::array({1, 2});  // a tunnel has no side
  expect_refused(j, "ops[0].side: unknown field");
}

TEST_F(BadSessionFiles, MissingFields) {
  json j = doc_;
  j.erase("sections");
  expect_refused(j, "sections: missing field");
  j = doc_;
  j["ops"][0]["camera"].erase("eye");
  expect_refused(j, "ops[0].camera.eye: missing field");
  j = doc_;
  j["params"]["stroke"].erase("min_spacing_px");
  expect_refused(j, "params.stroke.min_spacing_px: missing field");
}

TEST_F(BadSessionFiles, FormatAndVersion) {
  json j = doc_;
  j["version"] = 2;
  expect_refused(j, "version: unsupported session version 2 (this planesketch reads version 1)");
  j = doc_;
  j["version"] = "1";
  expect_refused(j, "version: must be an integer");
  j = doc_;
  j["format"] = "planesketch-stroke-log";
  expect_refused(j, "format: must be \"planesketch-session\"");
}

TEST_F(BadSessionFiles, OperationsThatNoLongerApply) {
  json j = doc_;
  for (auto& p : j["ops"][0]["stroke"]) p[0] = p[0].get<double>() + 500.0;  // the tunnel misses the model
  expect_refused(j, "do not rebuild");
}

TEST_F(BadSessionFiles, AChangedSavedMeshIsReportedNotLoadedOver) {
  TriMesh m = *read_mesh(dir_.file("good.mesh.ply"));
  m.vertices[5].x() += 1e-12;
  ASSERT_TRUE(write_mesh(dir_.file("good.mesh.ply"), m));
  SketchSession s;
  SessionLoadReport r;
  ASSERT_TRUE(load_session(path_, s, &r));
  EXPECT_TRUE(r.mesh_checked);
  EXPECT_FALSE(r.mesh_matches);
  EXPECT_NE(r.mesh_problem.find("differs from the saved mesh"), std::string::npos) << r.mesh_problem;
  EXPECT_NE(r.mesh_problem.find("vertex 5"), std::string::npos) << r.mesh_problem;
  EXPECT_EQ(s.state().model.vertices, good_.state().model.vertices);  // the rebuilt model is kept
  fs::remove(dir_.file("good.mesh.ply"));
  ASSERT_TRUE(load_session(path_, s, &r));
  EXPECT_FALSE(r.mesh_checked);
  EXPECT_NE(r.mesh_problem.find("cannot be read"), std::string::npos) << r.mesh_problem;
}

// === Imported base meshes

TriMesh solid() {
  SketchSession s = blob();
  return s.state().model;
}

TEST(ImportedBase, SculptDeformUndoAndRefusals) {
  const TriMesh mesh = solid();
  SketchSession s;
  const Status st = s.import_base(mesh);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(s.state().model.vertices, mesh.vertices);
  EXPECT_TRUE(s.state().sections.curves.empty());
  ASSERT_TRUE(s.paint_stiffness(paint_all(1.0)));
  const Status tunnel = s.sculpt(tunnel_op());
  ASSERT_TRUE(tunnel) << tunnel.message();
  EXPECT_EQ(mesh_topology(s.state().model).genus, 1);
  EXPECT_TRUE(check_guarantees(s.state().model).valid());
  // Section edits are refused with the reason, the state unchanged.
  const TriMesh sculpted = s.state().model;
  const Status add = s.add_section(axis_plane(2, 0.3), circle(2, 0.3, 0.5));
  ASSERT_FALSE(add);
  EXPECT_NE(add.message().find("imported mesh"), std::string::npos) << add.message();
  EXPECT_FALSE(s.delete_section(0));
  EXPECT_FALSE(s.add_window_stroke(window_circle(Vec2(320, 240), 50, 30), front_camera(), axis_plane(2, 0)));
  EXPECT_EQ(s.state().model.vertices, sculpted.vertices);
  // A second import is refused; undo goes back to the base, then to the empty session.
  EXPECT_FALSE(s.import_base(mesh));
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.state().model.vertices, mesh.vertices);
  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.state().model.empty());
  EXPECT_TRUE(s.state().base.empty());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.state().model.vertices, mesh.vertices);
}

TEST(ImportedBase, InvalidMeshesAreRefusedWithTheReason) {
  const TriMesh mesh = solid();
  auto refused = [](SketchSession& s, const TriMesh& m, const std::string& words) {
    const Status st = s.import_base(m);
    ASSERT_FALSE(st);
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    EXPECT_TRUE(s.state().base.empty());
    EXPECT_FALSE(s.can_undo());
  };
  SketchSession s;
  TriMesh open = mesh;
  open.faces.pop_back();
  refused(s, open, "closed");
  TriMesh inward = mesh;
  for (auto& f : inward.faces) std::swap(f[1], f[2]);
  refused(s, inward, "oriented");
  TriMesh bad = mesh;
  bad.faces[0][0] = static_cast<int>(bad.vertices.size());
  refused(s, bad, "out of range");
  refused(s, TriMesh{}, "no faces");
  // Not into a session that has sections.
  SketchSession sketched = blob();
  const Status st = sketched.import_base(mesh);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("empty session"), std::string::npos) << st.message();
}

TEST(ImportedBase, SavedAndLoadedWithTheSession) {
  SketchSession s;
  ASSERT_TRUE(s.import_base(solid()));
  ASSERT_TRUE(s.sculpt(tunnel_op()));
  TempDir dir;
  ASSERT_TRUE(save_session(dir.file("b.json"), s));
  SketchSession loaded;
  SessionLoadReport r;
  const Status st = load_session(dir.file("b.json"), loaded, &r);
  ASSERT_TRUE(st) << st.message();
  EXPECT_TRUE(r.mesh_matches) << r.mesh_problem;
  expect_same_session(s, loaded);
  // A base that is not a solid is refused on load too, naming it.
  json j = json::parse(read_text(dir.file("b.json")));
  j["base"]["faces"].erase(0);
  write_text(dir.file("c.json"), j.dump());
  const Status bad = load_session(dir.file("c.json"), loaded);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("base: "), std::string::npos) << bad.message();
  expect_same_session(s, loaded);
  j = json::parse(read_text(dir.file("b.json")));
  j["sections"]["planes"].push_back({{"normal", {0, 0, 1}}, {"offset", 0}});
  j["sections"]["curves"].push_back({{"plane", 0}, {"points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}});
  write_text(dir.file("d.json"), j.dump());
  const Status both = load_session(dir.file("d.json"), loaded);
  ASSERT_FALSE(both);
  EXPECT_NE(both.message().find("sections.curves: must be empty"), std::string::npos) << both.message();
}

TEST(ExportModel, EveryFormatReadsBack) {
  const TriMesh m = solid();
  TempDir dir;
  for (const char* ext : {".obj", ".ply", ".off", ".stl"}) {
    const std::string p = dir.file(std::string("m") + ext);
    ASSERT_TRUE(export_model(p, m)) << ext;
    auto back = read_mesh(p);
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back->faces.size(), m.faces.size()) << ext;
    if (std::string(ext) != ".stl") {
      EXPECT_EQ(back->vertices, m.vertices) << ext;  // STL stores floats
    }
  }
  const std::string glb = dir.file("m.glb");
  ASSERT_TRUE(export_model(glb, m));
  const std::string bytes = read_text(glb);
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_FALSE(export_model(dir.file("m.xyz"), m));
  EXPECT_FALSE(export_model(dir.file("e.obj"), TriMesh{}));
  EXPECT_FALSE(fs::exists(dir.file("e.obj")));
}

}  // namespace
}  // namespace ps
