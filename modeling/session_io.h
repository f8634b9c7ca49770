#pragma once
// Session files (issue 7 point 6; format: docs/session-format.md): a sketch session's sections,
// operations and parameters as one JSON document, plus the model written next to it as a mesh
// file whose name the document records.
//
// The document holds what the session is made of (SessionParams, the imported base mesh or the
// user's cross sections, the operations in order), never what is computed from it: loading
// rebuilds the model through SketchSession::load, then compares it with the saved mesh, bit for
// bit. Doubles are written with the shortest text that reads back to the same bits, so
// save -> load gives the identical state and the identical model.
//
// Reading is strict: an unknown field, a missing one, a wrong type, a non-finite number, an
// unknown operation kind or another format version is refused with one message
// `NAME: JSON.PATH: what is wrong` (e.g. `s.json: ops[2].roi.method: unknown selection method
// 'circle' (known: radius, lasso, brush)`), and the session being loaded into is left untouched.
#include <cstddef>
#include <string>

#include "modeling/mesh.h"
#include "modeling/sketch_session.h"
#include "modeling/status.h"

namespace ps {

inline constexpr const char* kSessionFormat = "planesketch-session";
inline constexpr int kSessionVersion = 1;

// What a session document holds.
struct SessionFile {
  SessionParams params;
  SessionState state;     // base, sections and ops only; the rest is rebuilt by SketchSession::load
  std::string mesh;       // the saved model's file, relative to the document's folder; empty: none
  std::size_t mesh_vertices = 0, mesh_faces = 0;
};

// The document (pretty-printed JSON, a final newline). `mesh_file` is recorded as the model's
// file (empty: no model saved).
std::string session_to_json(const SessionParams& params, const SessionState& state, const std::string& mesh_file);
// Parses a document; `name` prefixes every message.
Result<SessionFile> session_from_json(const std::string& text, const std::string& name);

// The mesh file saved next to a session: "dir/s.json" -> "dir/s.mesh.ply".
std::string session_mesh_path(const std::string& session_path);

// Writes the model (when there is one) to session_mesh_path(path), then the document to
// `path`, each through a temporary file renamed into place.
Status save_session(const std::string& path, const SessionParams& params, const SessionState& state);
inline Status save_session(const std::string& path, const SketchSession& session) {
  return save_session(path, session.params(), session.state());
}

struct SessionLoadReport {
  std::string mesh_path;       // the saved model's file as resolved (empty: the document has none)
  bool mesh_checked = false;   // the saved mesh was read and compared
  bool mesh_matches = false;   // ... and equals the rebuilt model bit for bit
  std::string mesh_problem;    // why not: unreadable file, or the first difference found
  double read_ms = 0.0;        // reading and parsing the document
  double rebuild_ms = 0.0;     // SketchSession::load (reconstruction and operations)
};

// Reads `path` and loads it into `session` (SketchSession::load: history cleared). A bad
// document, or one whose sections and operations do not rebuild, is refused and `session` is
// unchanged. A saved mesh that is missing or differs from the rebuilt model does not refuse
// the load: the report says so (mesh_matches false, mesh_problem), and callers warn.
Status load_session(const std::string& path, SketchSession& session, SessionLoadReport* report = nullptr);

// Exports a model by the file's extension: .glb (glTF 2.0 binary, gltf_export.h) or a mesh
// format of write_mesh (.obj .off .ply .stl); refuses an empty model or another extension.
Status export_model(const std::string& path, const TriMesh& model);
// True for the extensions export_model writes.
bool is_export_extension(const std::string& path);

// Empty when `a` and `b` have the same vertices (bit for bit) and faces; else the first
// difference, in words ("vertex 12 differs: (0.1, ...) against (...)").
std::string mesh_difference(const TriMesh& a, const TriMesh& b);

}  // namespace ps
