// Deformation spec reader (nlohmann_json).
#include "modeling/deform_spec.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>


namespace ps {
namespace {

using nlohmann::json;

struct SpecError {
  std::string message;
};

[[noreturn]] void fail(const std::string& field, const std::string& what) { throw SpecError{field + ": " + what}; }

double number(const json& j, const std::string& field) {
  if (!j.is_number()) fail(field, "expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(field, "not a finite number");
  return v;
}

int integer(const json& j, const std::string& field) {
  if (!j.is_number_integer() && !j.is_number_unsigned()) {
    if (j.is_number_float()) {
      const double v = j.get<double>();
      if (!std::isfinite(v)) fail(field, "not a finite number");
    }
    fail(field, "expected an integer");
  }
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) fail(field, "index " + j.dump() + " out of range");
    return static_cast<int>(u);
  }
  const auto v = j.get<std::int64_t>();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail(field, "index " + j.dump() + " out of range");
  return static_cast<int>(v);
}

DeformSpec parse(const json& doc) {
  DeformSpec s;
  if (!doc.is_object()) fail("(top level)", "expected a JSON object");
  static const std::set<std::string> known = {"format", "version", "roi", "handles", "domain", "lambda",
                                              "lambda_per_vertex", "max_iterations", "tolerance"};
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (!known.count(it.key())) fail(it.key(), "unknown field");
  if (!doc.contains("format")) fail("format", "missing (expected \"deformation\")");
  if (!doc["format"].is_string() || doc["format"].get<std::string>() != "deformation")
    fail("format", "expected \"deformation\", got " + doc["format"].dump());
  if (!doc.contains("version")) fail("version", "missing (expected 1)");
  if (integer(doc["version"], "version") != 1) fail("version", "unsupported version " + doc["version"].dump() + " (expected 1)");

  if (!doc.contains("roi")) fail("roi", "missing");
  const json& roi = doc["roi"];
  if (!roi.is_array()) fail("roi", "expected an array of vertex indices");
  if (roi.empty()) fail("roi", "empty (at least one free vertex is needed)");
  for (std::size_t k = 0; k < roi.size(); ++k) {
    const std::string f = "roi[" + std::to_string(k) + "]";
    const int v = integer(roi[k], f);
    if (v < 0) fail(f, "vertex index " + std::to_string(v) + " is negative");
    s.roi.push_back(v);
  }

  if (!doc.contains("handles")) fail("handles", "missing");
  const json& handles = doc["handles"];
  if (!handles.is_array()) fail("handles", "expected an array of {\"vertex\", \"position\"} objects");
  for (std::size_t k = 0; k < handles.size(); ++k) {
    const std::string f = "handles[" + std::to_string(k) + "]";
    const json& h = handles[k];
    if (!h.is_object()) fail(f, "expected an object with \"vertex\" and \"position\"");
    for (auto it = h.begin(); it != h.end(); ++it)
      if (it.key() != "vertex" && it.key() != "position") fail(f + "." + it.key(), "unknown field");
    if (!h.contains("vertex")) fail(f + ".vertex", "missing");
    if (!h.contains("position")) fail(f + ".position", "missing");
    HandleTarget t;
    t.vertex = integer(h["vertex"], f + ".vertex");
    if (t.vertex < 0) fail(f + ".vertex", "vertex index " + std::to_string(t.vertex) + " is negative");
    const json& p = h["position"];
    if (!p.is_array() || p.size() != 3) fail(f + ".position", "expected an array of three numbers");
    for (std::size_t c = 0; c < 3; ++c)
      t.position[static_cast<Eigen::Index>(c)] = number(p[c], f + ".position[" + std::to_string(c) + "]");
    s.handles.push_back(t);
  }

  if (doc.contains("domain")) {
    const json& d = doc["domain"];
    if (!d.is_string()) fail("domain", "expected \"edge-graph\" or \"primal\"");
    const std::string v = d.get<std::string>();
    if (v == "edge-graph") s.domain = DeformDomain::kEdgeGraph;
    else if (v == "primal") s.domain = DeformDomain::kPrimal;
    else fail("domain", "unknown domain \"" + v + "\" (expected \"edge-graph\" or \"primal\")");
  }
  if (doc.contains("lambda")) {
    s.lambda = number(doc["lambda"], "lambda");
    if (!(s.lambda >= 0.0 && s.lambda <= 1.0)) fail("lambda", doc["lambda"].dump() + " is outside [0, 1]");
  }
  if (doc.contains("lambda_per_vertex")) {
    const json& l = doc["lambda_per_vertex"];
    if (!l.is_object()) fail("lambda_per_vertex", "expected an object {\"vertex index\": stiffness}");
    for (auto it = l.begin(); it != l.end(); ++it) {
      const std::string f = "lambda_per_vertex[\"" + it.key() + "\"]";
      std::size_t used = 0;
      long long v = -1;
      try {
        v = std::stoll(it.key(), &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != it.key().size() || it.key().empty() || !(std::isdigit(static_cast<unsigned char>(it.key()[0]))))
        fail(f, "key is not a vertex index");
      if (v > std::numeric_limits<int>::max()) fail(f, "vertex index out of range");
      const double val = number(it.value(), f);
      if (!(val >= 0.0 && val <= 1.0)) fail(f, it.value().dump() + " is outside [0, 1]");
      s.lambda_per_vertex.emplace_back(static_cast<int>(v), val);
    }
  }
  if (doc.contains("max_iterations")) {
    s.max_iterations = integer(doc["max_iterations"], "max_iterations");
    if (s.max_iterations < 0) fail("max_iterations", "must be >= 0");
  }
  if (doc.contains("tolerance")) {
    s.tolerance = number(doc["tolerance"], "tolerance");
    if (s.tolerance < 0.0) fail("tolerance", "must be >= 0");
  }
  return s;
}

}  // namespace

Result<DeformSpec> parse_deform_spec(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    // Also number overflow (e.g. 1e999): JSON has no non-finite numbers.
    return Result<DeformSpec>::error(source + ": not valid JSON (" + e.what() + ")");
  }
  try {
    return parse(doc);
  } catch (const SpecError& e) {
    return Result<DeformSpec>::error(source + ": " + e.message);
  } catch (const json::exception& e) {
    return Result<DeformSpec>::error(source + ": " + e.what());
  }
}

Result<DeformSpec> read_deform_spec(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Result<DeformSpec>::error(path + ": cannot be opened for reading");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_deform_spec(ss.str(), path);
}

Status check_deform_spec(const DeformSpec& s, std::size_t num_vertices, const std::string& source) {
  const auto n = static_cast<long long>(num_vertices);
  auto range = [&](const std::string& field, int v) {
    return source + ": " + field + ": vertex index " + std::to_string(v) + " out of range (mesh has " +
           std::to_string(n) + " vertices)";
  };
  for (std::size_t k = 0; k < s.roi.size(); ++k)
    if (s.roi[k] < 0 || s.roi[k] >= n) return Status::error(range("roi[" + std::to_string(k) + "]", s.roi[k]));
  std::map<int, std::size_t> first;
  for (std::size_t k = 0; k < s.handles.size(); ++k) {
    const int v = s.handles[k].vertex;
    const std::string f = "handles[" + std::to_string(k) + "].vertex";
    if (v < 0 || v >= n) return Status::error(range(f, v));
    auto [it, fresh] = first.emplace(v, k);
    if (!fresh)
      return Status::error(source + ": " + f + ": vertex " + std::to_string(v) + " is already handles[" +
                           std::to_string(it->second) + "] (a vertex can be constrained only once)");
  }
  for (const auto& [v, l] : s.lambda_per_vertex)
    if (v < 0 || v >= n) return Status::error(range("lambda_per_vertex[\"" + std::to_string(v) + "\"]", v));
  return Status::ok();
}

DeformParameters deform_parameters(const DeformSpec& s, std::size_t num_vertices) {
  DeformParameters p;
  p.domain = s.domain;
  p.lambda = s.lambda;
  p.max_iterations = s.max_iterations;
  p.tolerance = s.tolerance;
  if (!s.lambda_per_vertex.empty()) {
    p.vertex_lambda.assign(num_vertices, std::numeric_limits<double>::quiet_NaN());
    for (const auto& [v, l] : s.lambda_per_vertex) p.vertex_lambda[static_cast<std::size_t>(v)] = l;
  }
  return p;
}

}  // namespace ps
