// `planesketch slice MESH -o OUT [--axis-planes NX,NY,NZ | --random-planes N --seed S]`
// (hidden): slice a closed mesh into cross sections, the way tests and benchmarks make real
// inputs from CGAL's data meshes. OUT's extension picks the contour format.
#include <array>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "modeling/contour_io.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_slicer.h"

namespace ps::app {
namespace {

struct SliceArgs {
  std::string mesh, out;
  std::vector<int> axis{3, 3, 3};
  int random = 0;
  std::uint64_t seed = 1;
  double spacing = 0;
};

void setup_slice(CLI::App& root) {
  auto a = std::make_shared<SliceArgs>();
  auto* cmd = root.add_subcommand("slice", "Slice a closed mesh into cross sections (test-data tool)");
  cmd->group("");  // hidden from the help listing
  cmd->add_option("MESH", a->mesh, "closed triangle mesh (.obj .off .ply .stl)")->required();
  cmd->add_option("-o,--output", a->out, "output contour file (.json .csl .contour)")->required();
  auto* ax = cmd->add_option("--axis-planes", a->axis, "planes per axis, NX,NY,NZ (default 3,3,3)")
                 ->delimiter(',')
                 ->expected(3);
  auto* rnd = cmd->add_option("--random-planes", a->random, "N planes of random orientation")->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", a->seed, "seed for --random-planes (default 1)");
  cmd->add_option("--spacing", a->spacing, "target point spacing (default: diagonal / 60)")->check(CLI::NonNegativeNumber);
  ax->excludes(rnd);
  cmd->callback([a]() {
    if (!contour_format_from_extension(a->out))
      throw CommandFailed(a->out + ": unknown output extension (expected .json, .csl or .contour)");
    auto mesh = read_mesh(a->mesh);
    if (!mesh) throw CommandFailed(mesh.message());
    const Box3 box = bounding_box(mesh->vertices);
    std::vector<Plane> planes;
    if (a->random > 0) {
      planes = random_planes(box, a->random, a->seed);
    } else {
      for (int c : a->axis)
        if (c < 0 || c > 100) throw CommandFailed("--axis-planes: counts must be between 0 and 100");
      planes = axis_planes(box, {a->axis[0], a->axis[1], a->axis[2]});
    }
    SliceOptions opt;
    opt.spacing = a->spacing;
    std::vector<std::string> warnings;
    auto sections = slice_mesh(*mesh, planes, opt, &warnings);
    if (!sections) throw CommandFailed(a->mesh + ": " + sections.message());
    for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";
    if (sections->curves.empty()) throw CommandFailed(a->mesh + ": no plane cuts the mesh in a closed curve");
    if (const Status st = write_sections(a->out, *sections); !st) throw CommandFailed(st.message());
    std::cerr << "planesketch: wrote " << a->out << " (" << sections->planes.size() << " planes, "
              << sections->curves.size() << " curves)\n";
  });
}

}  // namespace
PLANESKETCH_COMMAND(41, setup_slice);
}  // namespace ps::app
