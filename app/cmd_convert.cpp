// `planesketch convert IN OUT`: convert cross-section files between contour JSON, CSL and
// Ctr2Suf .contour (formats chosen by extension; the input falls back to content sniffing).
// Repairs made while reading are printed as warnings on stderr; the output is written to a
// temporary file and renamed into place, so a failure never leaves a partial file.
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "modeling/contour_io.h"
#include "modeling/curve_repair.h"

namespace ps::app {
namespace {

void setup_convert(CLI::App& root) {
  auto* cmd = root.add_subcommand("convert", "Convert cross sections between .json, .csl and .contour");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto repair = std::make_shared<bool>(false);
  cmd->add_option("IN", *in, "input file (.json, .csl, .contour)")->required();
  cmd->add_option("OUT", *out, "output file (.json, .csl, .contour)")->required();
  cmd->add_flag("--repair", *repair, "Split curves that touch or cross themselves into simple curves");
  cmd->callback([in, out, repair]() {
    if (!contour_format_from_extension(*out))
      throw CommandFailed(*out + ": unknown output extension (expected .json, .csl or .contour)");
    std::vector<std::string> warnings;
    auto sections = read_sections(*in, &warnings);
    if (!sections) throw CommandFailed(sections.message());
    if (*repair) repair_section_curves(*sections, &warnings);
    for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";
    if (const Status st = write_sections(*out, *sections); !st) throw CommandFailed(st.message());
    std::cerr << "planesketch: wrote " << *out << " (" << sections->planes.size() << " planes, "
              << sections->curves.size() << " curves)\n";
  });
}

}  // namespace
PLANESKETCH_COMMAND(40, setup_convert);
}  // namespace ps::app
