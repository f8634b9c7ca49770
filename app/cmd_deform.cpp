// planesketch deform MESH --spec SPEC.json -o OUT [--report R.json]
// Deforms a triangle mesh as a deformation spec (../shared/docs/deform-spec.md) describes, with
// the edge-graph (or primal) flexible deformation of thesis chapter 5.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.h"
#include "modeling/deform_spec.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_topology.h"

namespace ps::app {
namespace {

struct DeformArgs {
  std::string mesh, spec, out, report;
};

nlohmann::json report_json(const DeformSpec& spec, const DeformStats& st) {
  nlohmann::json r;
  r["format"] = "deformation-report";
  r["version"] = 1;
  r["domain"] = spec.domain == DeformDomain::kEdgeGraph ? "edge-graph" : "primal";
  r["lambda"] = spec.lambda;
  r["iterations"] = st.iterations;
  r["converged"] = st.converged;
  // Anderson acceleration of the iterations (docs/deformation.md): iterations that took the
  // accelerated iterate, and restarts of its history.
  r["accelerated_iterations"] = st.accelerated_iterations;
  r["acceleration_restarts"] = st.rejected_accelerations;
  r["initial_energy"] = st.energies.empty() ? 0.0 : st.energies.front();
  r["final_energy"] = st.energies.empty() ? 0.0 : st.energies.back();
  r["energies"] = st.energies;
  r["max_handle_residual"] = st.max_handle_residual;
  r["free_vertices"] = st.free_vertices;
  r["handle_vertices"] = spec.handles.size();
  r["nodes"] = st.nodes;
  r["matrix_nonzeros"] = st.matrix_nonzeros;
  r["factor_nonzeros"] = st.factor_nonzeros;
  r["clamped_cotangents"] = st.clamped_cotangents;
  r["degenerate_triangles"] = st.degenerate_triangles;
  r["mesh_ms"] = st.mesh_ms;
  r["build_ms"] = st.build_ms;
  r["factor_ms"] = st.factor_ms;
  r["initial_solve_ms"] = st.initial_solve_ms;
  r["iteration_ms"] = st.iteration_ms;
  double sum = 0;
  for (double t : st.iteration_ms) sum += t;
  r["mean_iteration_ms"] = st.iteration_ms.empty() ? 0.0 : sum / static_cast<double>(st.iteration_ms.size());
  r["total_ms"] = st.mesh_ms + st.build_ms + st.factor_ms + st.total_ms;
  if (st.clamped_cotangents > 0 || st.degenerate_triangles > 0)
    r["warnings"] = {std::to_string(st.clamped_cotangents) + " cotangents of near-degenerate angles clamped to +-1000; " +
                     std::to_string(st.degenerate_triangles) + " zero-area triangles"};
  return r;
}

void run(const DeformArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!is_mesh_extension(a.out))
    throw CommandFailed(a.out + ": unknown mesh extension for the output (expected .obj, .off, .ply or .stl)");
  auto spec = read_deform_spec(a.spec);
  if (!spec) throw CommandFailed(spec.message());
  MeshReadOptions triangles;
  triangles.triangles_only = true;  // the spec's vertex indices refer to the file's own triangles
  auto mesh = read_mesh(a.mesh, triangles);
  if (!mesh) throw CommandFailed(mesh.message());
  const MeshTopology topo = mesh_topology(*mesh);
  if (!topo.manifold())
    throw CommandFailed(a.mesh + ": mesh is not 2-manifold (" + std::to_string(topo.nonmanifold_edges) +
                        " non-manifold edges, " + std::to_string(topo.nonmanifold_vertices) +
                        " non-manifold vertices); deformation needs a manifold triangle mesh");
  // Open or inconsistently oriented meshes deform correctly (the energy uses unsigned angles
  // and areas, boundary edges have fewer neighbours), but the user should know what they gave.
  if (topo.boundary_edges > 0)
    std::cerr << "planesketch: warning: " << a.mesh << ": mesh is open (" << topo.boundary_edges
              << " boundary edges); it is deformed as an open surface\n";
  if (!topo.consistently_oriented)
    std::cerr << "planesketch: warning: " << a.mesh
              << ": faces are not consistently oriented; each face keeps its orientation\n";
  if (Status ok = check_deform_spec(*spec, mesh->num_vertices(), a.spec); !ok) throw CommandFailed(ok.message());

  EdgeGraphDeformer deformer;
  if (Status ok = deformer.set_mesh(*mesh); !ok) throw CommandFailed(a.mesh + ": " + ok.message());
  std::vector<int> handles;
  std::vector<Vec3> targets;
  for (const auto& h : spec->handles) handles.push_back(h.vertex), targets.push_back(h.position);
  if (Status ok = deformer.set_region(spec->roi, handles, deform_parameters(*spec, mesh->num_vertices())); !ok)
    throw CommandFailed(a.spec + ": " + ok.message());
  if (Status ok = deformer.deform(targets); !ok) throw CommandFailed(a.spec + ": " + ok.message());

  nlohmann::json report = report_json(*spec, deformer.stats());
  report["wall_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (Status ok = write_mesh(a.out, deformer.result()); !ok) throw CommandFailed(ok.message());
  if (!a.report.empty()) {
    const std::string tmp = a.report + ".tmp";
    std::ofstream f(tmp);
    f << report.dump(2) << "\n";
    f.close();
    std::error_code ec;
    if (!f) {
      std::filesystem::remove(tmp, ec);
      std::filesystem::remove(a.out, ec);
      throw CommandFailed(a.report + ": cannot write the report");
    }
    std::filesystem::rename(tmp, a.report, ec);
    if (ec) {
      std::filesystem::remove(tmp, ec);
      std::filesystem::remove(a.out, ec);
      throw CommandFailed(a.report + ": cannot write the report");
    }
  }
}

void setup(CLI::App& root) {
  auto args = std::make_shared<DeformArgs>();
  CLI::App* cmd = root.add_subcommand("deform", "Deform a triangle mesh as a deformation spec (JSON) describes");
  cmd->add_option("mesh", args->mesh, "Input triangle mesh (.obj .off .ply .stl)")->required();
  cmd->add_option("--spec", args->spec, "Deformation spec (JSON, see docs/deformation.md)")->required();
  cmd->add_option("-o,--output", args->out, "Output mesh")->required();
  cmd->add_option("--report", args->report, "Write a JSON report (iterations, energy, timings)");
  cmd->callback([args] { run(*args); });
}

}  // namespace

PLANESKETCH_COMMAND(40, setup);

}  // namespace ps::app
