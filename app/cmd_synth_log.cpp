// `planesketch synth-log --preset vase|figure -o FILE`: a hidden developer command that writes
// a synthesized demo stroke log (input/log_presets.h). Refuses to overwrite without --force.
#include <iostream>

#include "app/commands.h"
#include "input/log_presets.h"
#include "input/stroke_log_io.h"

namespace ps::app {
namespace {

void setup_synth_log(CLI::App& root) {
  struct Opts {
    std::string preset = "vase";
    std::string output;
    std::uint32_t seed = SynthOptions{}.seed;
    bool force = false;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* cmd = root.add_subcommand("synth-log", "write a synthesized demo stroke log (developer)");
  cmd->group("");  // hidden from --help
  cmd->add_option("--preset", opts->preset, "vase or figure")->check(CLI::IsMember(log_preset_names()));
  cmd->add_option("-o,--output", opts->output, "output .jsonl file")->required();
  cmd->add_option("--seed", opts->seed, "random seed for jitter and timing");
  cmd->add_flag("--force", opts->force, "overwrite an existing file");
  cmd->callback([opts] {
    auto res = synthesize_preset(opts->preset, opts->seed);
    if (!res) throw CommandFailed("synth-log: " + res.message());
    if (auto s = write_stroke_log(opts->output, res->log, opts->force); !s) throw CommandFailed(s.message());
    std::cout << opts->output << ": " << res->strokes.size() << " strokes, " << res->log.events.size()
              << " events, " << res->log.events.back().t / 1000.0 << " s\n";
  });
}

}  // namespace
PLANESKETCH_COMMAND(900, setup_synth_log);
}  // namespace ps::app
