#pragma once
// Topology editing by sketch (thesis 6.4) on the primitives of the orthogonal reconstruction.
//
// The reconstruction keeps its zones and primitives (progressive_reconstructor.h); an edit
// changes a few body-zone prisms (Eq. 4.1), so only the unions of the zones it touches are
// recomputed (the per-zone cache keys on the primitives).
//
//   Join  (a stroke from one surface part to another): the prisms nearest the stroke's first and
//         last points are found. In one zone, the first prism's top is translated towards the
//         second prism (a shear of the whole prism, so it stays valid) in steps of 5% of the
//         centroid offset until the two solids overlap, plus two steps of margin. The top stays
//         inside the zone by 0.5% of its extent.
//         In different zones (6.4.1, figure 6.8): the chain of face-adjacent zones along the
//         segment from the first prism's top to the middle of the second prism. The first
//         prism's bottom is projected onto the first common face (its new top), towards the
//         point where the segment crosses that face; that top is the bottom of a frustum in the
//         next zone, projected onto the next common face, and so on; in the second part's zone
//         the carried section is translated towards that part's middle until they overlap, as
//         in one zone. Tops are shrunk towards their centre (to 30%) to fit inside their face.
//         The carried frusta replace the first prism and join the chain's zones as primitives
//         of their own (not body prisms: later edits leave them alone).
//   Split (a stroke across a local part): the body zone holding the stroke's middle point, and
//         in it the group of prisms connected by overlap that contains the prism nearest that
//         point. Every prism of the group is shrunk towards its bottom (heights times 0.8, 0.64,
//         ... down to 0.1) until no two of them overlap. A prism whose wall lies in a side face
//         carrying no section continues in the neighbour zone; that continuation is shrunk by
//         the same factor, so the zone faces still match.
//
// Edits are geometric (the stroke, in the reconstruction's coordinates), not indices, so they
// are resolved again on every update and survive sections added elsewhere. What is refused, with
// the reason: a join across zones whose chain crosses a zone face holding a section, a zone
// holding other material, or another frustum on a face it crosses; a join or split that would
// move a prism reaching a side face or continuing into an end zone; a carried frustum that would
// fold or not fit its face; a stroke over no body zone; a part of a single prism.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "modeling/cylinder_builder.h"
#include "modeling/mesh.h"
#include "modeling/status.h"
#include "modeling/zone_partition.h"

namespace ps {

enum class TopologyEditKind { kJoin, kSplit };

struct TopologyEdit {
  TopologyEditKind kind = TopologyEditKind::kJoin;
  std::vector<Vec3> stroke;  // join: first and last points select the parts; split: across the part
};

// Applies one edit to `prims` (as built by build_cylinders on `part`, with their info). On error
// `prims` is unchanged.
Status apply_topology_edit(const Partition& part, std::vector<ZonePrimitives>& prims, const TopologyEdit& edit);

// "join" / "split".
const char* topology_edit_name(TopologyEditKind kind);

// The edits file (docs/reconstruction.md, "Topology editing"):
//   {"edits": [{"kind": "join" | "split", "stroke": [[x, y, z], ...]}, ...]}
// Errors name the edit index and the field.
Result<std::vector<TopologyEdit>> parse_topology_edits(const std::string& text);
// One edit's object {"kind": ..., "stroke": ...}, shared by the edits file and session files'
// "edits". On error `where` (when given) receives the failing field relative to the object
// ("kind", "stroke[3]"; empty for the object itself). Other keys are not looked at.
Result<TopologyEdit> topology_edit_from_json(const nlohmann::json& j, std::string* where = nullptr);
nlohmann::json topology_edit_to_json(const TopologyEdit& edit);
std::string format_topology_edits(const std::vector<TopologyEdit>& edits);

}  // namespace ps
