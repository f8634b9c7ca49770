// planesketch reconstruct IN -o OUT.(obj|off|ply|stl) [--report R.json] [--no-improve] [--edits E.json]
//                       [--repair]
// Reads cross sections (contour JSON, CSL or .contour), reconstructs a closed surface and writes
// it with a JSON report (docs: ../shared/docs/contours.md, docs/reconstruction.md).
#include <tbb/global_control.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "modeling/contour_io.h"
#include "modeling/curve_repair.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/progressive_reconstructor.h"
#include "modeling/reconstruct.h"

namespace {

struct Options {
  std::string input, output, report, edits;
  bool no_improve = false;
  int improve_rounds = ps::ReconstructOptions{}.improve_iterations;
  bool repair = false;
  bool world_frame = false;
  int threads = 0;
  bool quiet = false;
};

void write_text_atomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path tmp = target.parent_path() / (".tmp-" + target.filename().string());
  {
    std::ofstream f(tmp);
    if (!f) throw ps::app::CommandFailed(path + ": cannot write report");
    f << text;
    if (!f) throw ps::app::CommandFailed(path + ": cannot write report");
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) throw ps::app::CommandFailed(path + ": cannot write report: " + ec.message());
}

int run(const Options& o) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  if (!ps::is_mesh_extension(o.output))
    throw ps::app::CommandFailed(o.output + ": unknown mesh extension (expected .obj, .off, .ply or .stl)");

  auto ms_since = [](clock::time_point t) { return std::chrono::duration<double, std::milli>(clock::now() - t).count(); };
  std::vector<std::string> warnings;
  auto sections = ps::read_sections(o.input, &warnings);
  if (!sections) throw ps::app::CommandFailed(sections.message());
  if (o.repair) ps::repair_section_curves(*sections, &warnings);
  const double read_ms = ms_since(t0);
  for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";

  ps::ReconstructOptions ro;
  ro.improve = !o.no_improve;
  ro.improve_iterations = o.improve_rounds;
  ro.threads = o.threads;
  ro.rotate_to_planes = !o.world_frame;
  // --threads bounds every parallel loop of the command (the zone unions, and the improvement's
  // and the final checks' self-intersection tests), not only the reconstructor's own.
  std::optional<tbb::global_control> thread_limit;
  if (o.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(o.threads));
  // Progress for runs over a second: a line per stage on stderr once a second has passed.
  auto last = clock::now();
  std::string last_stage;
  ro.progress = [&](const std::string& stage, double fraction) {
    const auto now = clock::now();
    if (now - t0 < std::chrono::seconds(1) || o.quiet) return;
    if (stage != last_stage || now - last > std::chrono::milliseconds(500)) {
      std::cerr << "planesketch: " << stage << " " << static_cast<int>(fraction * 100.0) << "%\n";
      last = now;
      last_stage = stage;
    }
  };
  std::vector<ps::TopologyEdit> edits;
  if (!o.edits.empty()) {
    std::ifstream f(o.edits);
    if (!f) throw ps::app::CommandFailed(o.edits + ": cannot read the edits file");
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    auto parsed = ps::parse_topology_edits(text);
    if (!parsed) throw ps::app::CommandFailed(o.edits + ": " + parsed.message());
    edits = std::move(*parsed);
  }
  ps::ReconstructReport rr;
  ps::ProgressiveReconstructor reconstructor(ro);
  auto mesh = reconstructor.update(*sections, edits, &rr);
  if (!mesh) throw ps::app::CommandFailed(o.input + ": " + mesh.message());
  for (const auto& w : rr.warnings) std::cerr << "planesketch: warning: " << w << "\n";

  auto t = clock::now();
  const auto g = ps::check_guarantees(*mesh);
  const auto pts = sections->all_points();
  const double diag = ps::bounding_box(pts).diagonal();
  const double curve_dist = ps::max_distance_to_surface(*mesh, pts);
  const double checks_ms = ms_since(t);

  t = clock::now();
  if (auto st = ps::write_mesh(o.output, *mesh); !st) throw ps::app::CommandFailed(st.message());
  const double write_ms = ms_since(t);
  const double total_ms = std::chrono::duration<double, std::milli>(clock::now() - t0).count();

  nlohmann::json j;
  j["input"] = o.input;
  j["output"] = o.output;
  j["vertices"] = mesh->vertices.size();
  j["faces"] = mesh->faces.size();
  j["components"] = g.topology.components;
  j["genus"] = g.topology.genus;
  j["closed"] = g.topology.closed;
  j["manifold"] = g.topology.manifold();
  j["outward"] = g.topology.signed_volume > 0.0;
  j["self_intersecting"] = g.self_intersecting;
  j["volume"] = g.topology.signed_volume;
  j["max_curve_distance"] = curve_dist;
  j["max_curve_distance_relative"] = diag > 0.0 ? curve_dist / diag : 0.0;
  j["sections"] = sections->curves.size();
  j["planes"] = sections->planes.size();
  j["zones"] = {{"total", rr.zones}, {"empty", rr.empty_zones}, {"end", rr.end_zones}, {"body", rr.body_zones},
                {"union_by_box", rr.zones_filled}, {"union_in_2d", rr.zones_stacked}};
  j["primitives"] = rr.primitives;
  j["rotated_frame"] = rr.rotated_frame;
  j["topology_edits"] = edits.size();
  j["improve_rounds"] = o.no_improve ? 0 : o.improve_rounds;
  // read (and --repair), the reconstructor's stages and total, then the command's own checks of
  // the result (topology, self-intersection, curve distance) and the mesh file write.
  j["timings_ms"] = {{"read", read_ms}, {"checks", checks_ms}, {"write", write_ms}, {"validate", rr.timings.validate_ms}, {"partition", rr.timings.partition_ms},
                     {"primitives", rr.timings.primitives_ms}, {"union", rr.timings.union_ms},
                     {"improve", rr.timings.improve_ms}, {"improve_refine", rr.timings.improve_refine_ms},
                     {"improve_smooth", rr.timings.improve_smooth_ms}, {"improve_check", rr.timings.improve_check_ms},
                     {"reconstruct_total", rr.timings.total_ms},
                     {"command_total", total_ms}};
  std::vector<std::string> all_warnings = warnings;
  all_warnings.insert(all_warnings.end(), rr.warnings.begin(), rr.warnings.end());
  j["warnings"] = all_warnings;
  const std::string text = j.dump(2) + "\n";
  if (o.report.empty())
    std::cout << text;
  else
    write_text_atomically(o.report, text);
  return 0;
}

void setup(CLI::App& root) {
  auto opts = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("reconstruct", "Reconstruct a closed surface from cross sections (contour JSON, CSL, .contour)");
  cmd->add_option("input", opts->input, "Cross sections file (.json, .csl, .contour)")->required();
  cmd->add_option("-o,--output", opts->output, "Output mesh (.obj, .off, .ply, .stl)")->required();
  cmd->add_option("--report", opts->report, "Write the JSON report here instead of standard output");
  cmd->add_option("--edits", opts->edits,
                  "Topology edits to apply (JSON: {\"edits\": [{\"kind\": \"join\"|\"split\", \"stroke\": [[x,y,z],...]}]})");
  auto* no_improve = cmd->add_flag("--no-improve", opts->no_improve, "Skip refinement and smoothing");
  // Each round refines and smooths the whole surface and checks it for self-intersections; more
  // rounds cost more time and do not always give a smoother surface (docs/mesh-improvement.md).
  cmd->add_option("--improve-rounds", opts->improve_rounds,
                  "Rounds of refinement and smoothing, 1 to 100 (default 4; the thesis has 10)")
      ->check(CLI::Range(1, 100))
      ->excludes(no_improve);
  cmd->add_flag("--repair", opts->repair,
                "Split curves that touch or cross themselves into simple curves (traced contours; docs/formats.md)");
  cmd->add_flag("--world-frame", opts->world_frame,
                "Reconstruct tilted planes in the world frame (chapter 6's convex zones), not on the grid in their own "
                "frame (docs/reconstruction.md)");
  cmd->add_option("--threads", opts->threads, "Worker threads (0: all)");
  cmd->add_flag("-q,--quiet", opts->quiet, "No progress lines");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace

PLANESKETCH_COMMAND(30, setup);
