// Session files (docs/session-format.md):
//   planesketch export SESSION.json -o OUT [--strict] [--report R.json]
//     loads the session (rebuilds the model from its sections and operations, checks it against
//     the saved mesh) and writes the model as .obj, .off, .ply, .stl or .glb (or, to a .json,
//     saves the loaded session again: a check and a measure of saving);
//   planesketch import MESH -o SESSION.json
//     makes a session whose base is MESH (closed, manifold, oriented; refused otherwise), to
//     sculpt or deform with `planesketch replay LOG --session SESSION.json` or the window.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "modeling/mesh_io.h"
#include "modeling/session_io.h"

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct ExportOptions {
  std::string session, out, report;
  bool strict = false;
};

bool is_json(const std::string& path) { return std::filesystem::path(path).extension() == ".json"; }

void run_export(const ExportOptions& o) {
  if (!ps::is_export_extension(o.out) && !is_json(o.out))
    throw ps::app::CommandFailed(o.out + ": unknown export extension (expected .obj, .off, .ply, .stl, .glb, or .json to save the session again)");
  ps::SketchSession session;
  ps::SessionLoadReport r;
  if (auto st = ps::load_session(o.session, session, &r); !st) throw ps::app::CommandFailed(st.message());
  if (!r.mesh_problem.empty()) {
    if (o.strict) throw ps::app::CommandFailed(o.session + ": " + r.mesh_problem, 4);
    std::cerr << "planesketch: warning: " << o.session << ": " << r.mesh_problem << "\n";
  }
  const auto& st = session.state();
  const auto t0 = std::chrono::steady_clock::now();
  if (auto s = is_json(o.out) ? ps::save_session(o.out, session) : ps::export_model(o.out, st.model); !s)
    throw ps::app::CommandFailed(s.message());
  const double export_ms = ms_since(t0);
  std::cerr << "planesketch: " << o.session << ": " << st.sections.curves.size() << " sections"
            << (st.base.empty() ? "" : " (imported base)") << ", " << st.ops.size() << " operations, model "
            << st.model.vertices.size() << " vertices / " << st.model.faces.size() << " faces"
            << (r.mesh_matches ? ", equal to the saved mesh" : "") << " -> " << o.out << "\n";
  if (!o.report.empty()) {
    nlohmann::json j;
    j["session"] = o.session;
    j["output"] = o.out;
    j["sections"] = st.sections.curves.size();
    j["ops"] = st.ops.size();
    j["imported_base"] = !st.base.empty();
    j["vertices"] = st.model.vertices.size();
    j["faces"] = st.model.faces.size();
    j["mesh"] = r.mesh_path;
    j["mesh_checked"] = r.mesh_checked;
    j["mesh_matches"] = r.mesh_matches;
    j["mesh_problem"] = r.mesh_problem;
    j["read_ms"] = r.read_ms;
    j["rebuild_ms"] = r.rebuild_ms;
    j["export_ms"] = export_ms;
    std::ofstream f(o.report);
    f << j.dump(2) << "\n";
    if (!f) throw ps::app::CommandFailed(o.report + ": cannot write report");
  }
}

void run_import(const std::string& mesh_path, const std::string& out) {
  if (out.empty()) throw ps::app::CommandFailed("import: -o SESSION.json is required");
  auto mesh = ps::read_mesh(mesh_path);
  if (!mesh) throw ps::app::CommandFailed(mesh.message());
  ps::SketchSession session;
  if (auto st = session.import_base(std::move(*mesh)); !st) throw ps::app::CommandFailed(mesh_path + ": " + st.message());
  if (auto st = ps::save_session(out, session); !st) throw ps::app::CommandFailed(st.message());
  std::cerr << "planesketch: " << mesh_path << ": imported as the base of " << out << " ("
            << session.state().model.vertices.size() << " vertices / " << session.state().model.faces.size()
            << " faces)\n";
}

void setup(CLI::App& root) {
  auto o = std::make_shared<ExportOptions>();
  auto* ex = root.add_subcommand("export", "Load a session file, rebuild and check its model, and export it (.obj .off .ply .stl .glb)");
  ex->add_option("session", o->session, "Session file (.json)")->required();
  ex->add_option("-o,--output", o->out, "Output (.obj, .off, .ply, .stl or .glb)")->required();
  ex->add_option("--report", o->report, "Write a JSON summary here");
  ex->add_flag("--strict", o->strict, "Fail (exit 4) when the rebuilt model differs from the saved mesh");
  ex->callback([o] { run_export(*o); });

  auto mesh = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto* im = root.add_subcommand("import", "Make a session whose base is a mesh file (to sculpt or deform it)");
  im->add_option("mesh", *mesh, "Closed, manifold, oriented mesh (.obj, .off, .ply, .stl)")->required();
  im->add_option("-o,--output", *out, "Session file to write (.json)")->required();
  im->callback([mesh, out] { run_import(*mesh, *out); });
}

}  // namespace

PLANESKETCH_COMMAND(40, setup);
