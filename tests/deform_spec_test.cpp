// Deformation spec files (../shared/docs/deform-spec.md) and the `planesketch deform` command.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "modeling/deform_spec.h"
#include "modeling/mesh_io.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

const char* kValid = R"({
  "format": "deformation", "version": 1,
  "roi": [12, 13, 14, 15],
  "handles": [ { "vertex": 40, "position": [0.1, 0.5, 0.2] } ],
  "domain": "edge-graph", "lambda": 0.5,
  "lambda_per_vertex": { "13": 1.0, "14": 0.0 },
  "max_iterations": 10, "tolerance": 1e-5
})";

// Replace `from` by `to` in the valid spec.
std::string edit(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

void expect_error(const std::string& text, const std::string& field) {
  auto r = parse_deform_spec(text, "spec.json");
  ASSERT_FALSE(r) << "accepted: " << text;
  EXPECT_EQ(r.message().rfind("spec.json: ", 0), 0u) << r.message();
  EXPECT_NE(r.message().find(field), std::string::npos) << "message '" << r.message() << "' should name " << field;
}

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("deform_spec_test_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = (path / name).string();
    std::ofstream(p) << text;
    return p;
  }
};

int run(const std::string& args, std::string* err = nullptr, const fs::path& dir = fs::temp_directory_path()) {
  const std::string errfile = (dir / "stderr.txt").string();
  const int rc = std::system((std::string(PLANESKETCH_BINARY) + " " + args + " 2>" + errfile + " >/dev/null").c_str());
  if (err) {
    std::ifstream f(errfile);
    std::stringstream ss;
    ss << f.rdbuf();
    *err = ss.str();
  }
  return rc;
}

// An open 4 x 4 grid of unit squares (25 vertices) as OFF text.
std::string grid_off(bool quads = false) {
  std::stringstream s;
  const int n = 4;
  s << "OFF\n" << (n + 1) * (n + 1) << " " << (quads ? n * n : 2 * n * n) << " 0\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s << i << " " << j << " 0\n";
  auto id = [](int i, int j) { return j * 5 + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (quads) {
        s << "4 " << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << " " << id(i, j + 1) << "\n";
      } else {
        s << "3 " << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << "\n";
        s << "3 " << id(i, j) << " " << id(i + 1, j + 1) << " " << id(i, j + 1) << "\n";
      }
    }
  return s.str();
}

}  // namespace

TEST(DeformSpec, ParsesTheDocumentedExample) {
  auto r = parse_deform_spec(kValid, "spec.json");
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->roi, (std::vector<int>{12, 13, 14, 15}));
  ASSERT_EQ(r->handles.size(), 1u);
  EXPECT_EQ(r->handles[0].vertex, 40);
  EXPECT_EQ(r->handles[0].position, Vec3(0.1, 0.5, 0.2));
  EXPECT_EQ(r->domain, DeformDomain::kEdgeGraph);
  EXPECT_EQ(r->lambda, 0.5);
  ASSERT_EQ(r->lambda_per_vertex.size(), 2u);
  EXPECT_EQ(r->max_iterations, 10);
  EXPECT_EQ(r->tolerance, 1e-5);
  const DeformParameters p = deform_parameters(*r, 50);
  ASSERT_EQ(p.vertex_lambda.size(), 50u);
  EXPECT_EQ(p.vertex_lambda[13], 1.0);
  EXPECT_EQ(p.vertex_lambda[14], 0.0);
  EXPECT_TRUE(std::isnan(p.vertex_lambda[12]));
  // Defaults.
  auto d = parse_deform_spec(R"({"format":"deformation","version":1,"roi":[1],"handles":[]})", "s");
  ASSERT_TRUE(d) << d.message();
  EXPECT_EQ(d->domain, DeformDomain::kEdgeGraph);
  EXPECT_EQ(d->lambda, 0.5);
  auto primal = parse_deform_spec(edit("\"edge-graph\"", "\"primal\""), "s");
  ASSERT_TRUE(primal);
  EXPECT_EQ(primal->domain, DeformDomain::kPrimal);
}

TEST(DeformSpec, ErrorsNameTheField) {
  expect_error("{", "not valid JSON");
  expect_error("[]", "top level");
  expect_error(edit("\"deformation\"", "\"contours\""), "format");
  expect_error(edit("\"version\": 1", "\"version\": 2"), "version");
  expect_error(edit("[12, 13, 14, 15]", "[]"), "roi");
  expect_error(edit("[12, 13, 14, 15]", "[12, -3]"), "roi[1]");
  expect_error(edit("[12, 13, 14, 15]", "[12, 1.5]"), "roi[1]");
  expect_error(edit("[12, 13, 14, 15]", "\"all\""), "roi");
  expect_error(edit("[0.1, 0.5, 0.2]", "[0.1, 0.5]"), "handles[0].position");
  expect_error(edit("[0.1, 0.5, 0.2]", "[0.1, 1e999, 0.2]"), "1e999");  // overflow: caught while parsing
  expect_error(edit("[0.1, 0.5, 0.2]", "[0.1, NaN, 0.2]"), "not valid JSON");
  expect_error(edit("[0.1, 0.5, 0.2]", "[0.1, \"x\", 0.2]"), "handles[0].position[1]");
  expect_error(edit("\"vertex\": 40", "\"vertx\": 40"), "handles[0].vertx");
  expect_error(edit("\"edge-graph\"", "\"dual\""), "domain");
  expect_error(edit("\"lambda\": 0.5", "\"lambda\": 1.5"), "lambda");
  expect_error(edit("\"lambda\": 0.5", "\"lambda\": -0.1"), "lambda");
  expect_error(edit("\"13\": 1.0", "\"13\": 2.0"), "lambda_per_vertex[\"13\"]");
  expect_error(edit("\"13\": 1.0", "\"x\": 1.0"), "lambda_per_vertex[\"x\"]");
  expect_error(edit("\"max_iterations\": 10", "\"max_iterations\": -1"), "max_iterations");
  expect_error(edit("\"tolerance\": 1e-5", "\"tolerance\": -1e-5"), "tolerance");
  expect_error(edit("\"tolerance\": 1e-5", "\"tolerance\": 1e-5, \"lamda\": 1"), "lamda");
}

TEST(DeformSpec, MeshChecksNameTheField) {
  auto s = parse_deform_spec(kValid, "spec.json");
  ASSERT_TRUE(s);
  EXPECT_TRUE(check_deform_spec(*s, 41, "spec.json"));
  auto r = check_deform_spec(*s, 40, "spec.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("handles[0].vertex"), std::string::npos) << r.message();
  r = check_deform_spec(*s, 15, "spec.json");
  EXPECT_NE(r.message().find("roi[3]"), std::string::npos) << r.message();
  auto twice = parse_deform_spec(edit("[ { \"vertex\": 40, \"position\": [0.1, 0.5, 0.2] } ]",
                                      "[ {\"vertex\": 40, \"position\": [0,0,0]}, {\"vertex\": 40, \"position\": [1,0,0]} ]"),
                                 "spec.json");
  ASSERT_TRUE(twice);
  r = check_deform_spec(*twice, 100, "spec.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("handles[1].vertex"), std::string::npos) << r.message();
}

TEST(DeformCommand, DeformsWritesAReportAndRefusesBadInput) {
  if (!fs::exists(PLANESKETCH_BINARY)) GTEST_SKIP() << "no planesketch binary";
  TempDir dir;
  const std::string mesh = dir.file("grid.off", grid_off());
  // Free: the inner 3 x 3 vertices; handle: the centre (12), lifted; boundary static.
  const std::string spec = dir.file("spec.json", R"({"format":"deformation","version":1,
    "roi":[6,7,8,11,13,16,17,18],"handles":[{"vertex":12,"position":[2,2,1]}],"lambda":0.5})");
  const std::string out = (dir.path / "out.off").string(), report = (dir.path / "r.json").string();
  std::string err;
  ASSERT_EQ(run("deform " + mesh + " --spec " + spec + " -o " + out + " --report " + report, &err, dir.path), 0) << err;
  auto result = read_mesh(out);
  ASSERT_TRUE(result) << result.message();
  EXPECT_EQ(result->vertices[12], Vec3(2, 2, 1));
  EXPECT_EQ(result->vertices[0], Vec3(0, 0, 0));
  EXPECT_GT(result->vertices[7].z(), 0.0);
  std::ifstream rf(report);
  const auto rep = nlohmann::json::parse(rf);
  for (const char* key : {"iterations", "final_energy", "max_handle_residual", "build_ms", "factor_ms",
                          "iteration_ms", "mean_iteration_ms", "total_ms", "clamped_cotangents"})
    EXPECT_TRUE(rep.contains(key)) << key;
  EXPECT_EQ(rep["max_handle_residual"].get<double>(), 0.0);

  // Errors: one line naming the file and field, non-zero exit, no output file.
  auto refuse = [&](const std::string& args, const std::string& needle) {
    const std::string o = (dir.path / "refused.off").string();
    std::string e;
    EXPECT_NE(run("deform " + args + " -o " + o, &e, dir.path), 0) << args;
    EXPECT_NE(e.find(needle), std::string::npos) << "stderr '" << e << "' should contain " << needle;
    EXPECT_FALSE(fs::exists(o)) << args;
  };
  refuse(mesh + " --spec " + dir.file("bad1.json", R"({"format":"deformation","version":1,"roi":[6,99],"handles":[]})"),
         "roi[1]");
  refuse(mesh + " --spec " + dir.file("bad2.json", R"({"format":"deformation","version":1,"roi":[6],"handles":[],"lambda":3})"),
         "lambda");
  refuse(mesh + " --spec " + dir.file("bad3.json", R"({"format":"deformation","version":1,"roi":[],"handles":[]})"), "roi");
  refuse(dir.file("quads.off", grid_off(true)) + " --spec " + spec, "triangle mesh");
  // Non-manifold: a third triangle on edge (0, 1).
  std::string nm = grid_off();
  nm.replace(nm.find("25 32 0"), 7, "26 33 0");
  const auto vend = nm.find("3 ");
  nm.insert(vend, "0.5 -1 1\n");
  nm += "3 0 1 25\n";
  refuse(dir.file("nonmanifold.off", nm) + " --spec " + spec, "manifold");
  refuse((dir.path / "missing.off").string() + " --spec " + spec, "missing.off");
}
