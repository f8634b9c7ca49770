// `planesketch synth-log --preset vase|figure [--sections N] -o FILE`: a hidden developer
// command that writes a synthesized demo stroke log (input/log_presets.h). Refuses to overwrite
// without --force.
//
// --sections N replaces the preset's horizontal sections so that there are N in all (a
// benchmark input, e.g. the 20-section window latency log in bench/results/window.md): the
// preset's vertical sections are kept (drawn last, as in the presets) and N minus their number
// z planes are spaced evenly over the middle 90 % of the preset curves' height. Every curve is
// still a slice of the one solid, so the stroke rules hold. (Off-centre vertical planes cross
// the vase's lobes at shallow angles, where the drawn curves miss rule 4's tolerance.)
#include <iostream>

#include "app/commands.h"
#include "input/implicit_slice.h"
#include "input/log_presets.h"
#include "input/stroke_log_io.h"
#include "modeling/mesh.h"

namespace ps::app {
namespace {

Status reslice(LogPreset& preset, int sections) {
  std::vector<Vec3> pts;
  std::vector<SketchStep> vertical;
  for (const auto& step : preset.steps) {
    for (const auto& c : step.curves) pts.insert(pts.end(), c.begin(), c.end());
    if (step.plane != 2) vertical.push_back(step);
  }
  const int count = sections - static_cast<int>(vertical.size());
  if (count < 1) return Status::error("--sections must exceed the preset's " + std::to_string(vertical.size()) + " vertical sections");
  const Box3 box = bounding_box(pts);
  std::vector<SketchStep> steps;
  for (int i = 0; i < count; ++i) {
    const double offset = box.min.z() + (0.05 + 0.9 * (i + 0.5) / count) * box.size().z();
    auto loops = slice_implicit(preset.solid, Plane{Vec3::UnitZ(), offset},
                                SliceWindow{box.center(), 0.625 * box.size().maxCoeff(), 360});
    if (!loops) return Status::error("slice z = " + std::to_string(offset) + ": " + loops.message());
    if (loops->empty()) return Status::error("slice z = " + std::to_string(offset) + " misses the solid");
    steps.push_back(SketchStep{2, offset, std::move(*loops)});
  }
  steps.insert(steps.end(), vertical.begin(), vertical.end());
  preset.steps = std::move(steps);
  return Status::ok();
}

void setup_synth_log(CLI::App& root) {
  struct Opts {
    std::string preset = "vase";
    std::string output;
    std::uint32_t seed = SynthOptions{}.seed;
    int sections = 0;
    bool force = false;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* cmd = root.add_subcommand("synth-log", "write a synthesized demo stroke log (developer)");
  cmd->group("");  // hidden from --help
  cmd->add_option("--preset", opts->preset, "vase or figure")->check(CLI::IsMember(log_preset_names()));
  cmd->add_option("-o,--output", opts->output, "output .jsonl file")->required();
  cmd->add_option("--seed", opts->seed, "random seed for jitter and timing");
  cmd->add_option("--sections", opts->sections, "this many sections in all: the preset's vertical ones and evenly spaced horizontal ones (5..60)")
      ->check(CLI::Range(5, 60));
  cmd->add_flag("--force", opts->force, "overwrite an existing file");
  cmd->callback([opts] {
    auto preset = make_log_preset(opts->preset);
    if (!preset) throw CommandFailed("synth-log: " + preset.message());
    if (opts->sections > 0)
      if (auto st = reslice(*preset, opts->sections); !st) throw CommandFailed("synth-log: " + st.message());
    auto res = synthesize_preset(*preset, opts->seed);
    if (!res) throw CommandFailed("synth-log: " + res.message());
    if (opts->sections > 0) res->log.header.generator += " --sections " + std::to_string(opts->sections);
    if (auto s = write_stroke_log(opts->output, res->log, opts->force); !s) throw CommandFailed(s.message());
    std::cout << opts->output << ": " << res->strokes.size() << " strokes, " << res->log.events.size()
              << " events, " << res->log.events.back().t / 1000.0 << " s\n";
  });
}

}  // namespace
PLANESKETCH_COMMAND(900, setup_synth_log);
}  // namespace ps::app
