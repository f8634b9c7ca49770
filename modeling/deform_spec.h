#pragma once
// Deformation specification files (JSON, version 1): ../shared/docs/deform-spec.md.
//
//   {"format": "deformation", "version": 1, "roi": [...], "handles": [{"vertex": i,
//    "position": [x, y, z]}], "domain": "edge-graph" | "primal", "lambda": 0.5,
//    "lambda_per_vertex": {"13": 1.0}, "max_iterations": 10, "tolerance": 1e-5}
//
// parse_deform_spec checks the form (types, ranges that need no mesh, unknown fields);
// check_deform_spec checks it against a mesh's vertex count. Every message names the field,
// e.g. "spec.json: handles[2].position[1]: not a finite number".
#include <string>
#include <utility>
#include <vector>

#include "modeling/edge_graph_deformer.h"
#include "modeling/status.h"

namespace ps {

struct DeformSpec {
  std::vector<int> roi;
  std::vector<HandleTarget> handles;
  DeformDomain domain = DeformDomain::kEdgeGraph;
  double lambda = 0.5;
  std::vector<std::pair<int, double>> lambda_per_vertex;  // (vertex, stiffness), file order
  int max_iterations = 10;
  double tolerance = 1e-5;
};

// `source` prefixes every message (the file name).
Result<DeformSpec> parse_deform_spec(const std::string& json_text, const std::string& source);
Result<DeformSpec> read_deform_spec(const std::string& path);

// Index ranges against the mesh; a vertex that is a handle twice (with a static/handle clash
// in the spec's words: a vertex cannot be constrained to two places).
Status check_deform_spec(const DeformSpec& spec, std::size_t num_vertices, const std::string& source);

// The solver parameters the spec describes, for a mesh with `num_vertices` vertices.
DeformParameters deform_parameters(const DeformSpec& spec, std::size_t num_vertices);

}  // namespace ps
