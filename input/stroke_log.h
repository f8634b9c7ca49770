#pragma once
// Stroke-log values: what a pen and the UI did, in order, with times (docs/stroke-log.md).
//
// A stroke log is the record of one modeling session: a header (viewport, initial camera,
// reference planes, units) and a time-ordered list of events. Replaying it through the same
// EventSink the live app implements rebuilds the same model, so logs serve as the demo, the
// regression corpus and crash recovery.
//
// Conventions:
//   Times t are milliseconds since the start of the log (virtual clock), finite, >= 0 and
//   non-decreasing along the log (equal times allowed).
//   Pen positions are window pixels of the viewport: x right, y DOWN, origin top-left
//   (modeling/camera.h). Pressure is normalized to [0, 1]; tilt is in degrees, positive x tilt
//   leans the pen to the right, positive y tilt leans it toward the user, both in [-90, 90].
//   Reference plane indices: planes[k] of the header; 0, 1, 2 are the thesis's basic planes
//   x = c, y = c, z = c (thesis 3.2.1). A TranslatePlane sets the plane's absolute offset.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"

namespace ps {

// === Pen samples

enum class Tool { kPen, kEraser, kMouse };

// A stroke is down, move..., up. A move outside down..up is a hover sample. proximity-in /
// proximity-out bracket everything the pen does near the tablet.
enum class Phase { kDown, kMove, kUp, kProximityIn, kProximityOut };

// Barrel buttons held during the sample (bit mask).
enum PenButton : std::uint32_t { kPenButtonPrimary = 1u, kPenButtonSecondary = 2u };

struct PenSample {
  double t = 0.0;         // ms since log start
  double x = 0.0;         // window pixels, right
  double y = 0.0;         // window pixels, down
  double pressure = 0.0;  // [0, 1]
  double tilt_x = 0.0;    // degrees
  double tilt_y = 0.0;    // degrees
  Tool tool = Tool::kPen;
  Phase phase = Phase::kMove;
  std::uint32_t buttons = 0;  // PenButton mask
};
static_assert(std::is_trivially_copyable_v<PenSample>);

// === UI actions: everything that changes the model or how input is read

struct SelectPlane {
  int plane = 0;  // reference plane index
};
struct TranslatePlane {
  int plane = 0;
  double offset = 0.0;  // new absolute offset: the plane becomes normal . p == offset
};
struct CameraChange {
  Camera camera;  // full camera, including the viewport size (width, height)
};
struct SetToolMode {
  std::string mode;  // e.g. "sketch", "sculpt", "deform"
};
struct SetParameter {
  std::string name;  // e.g. "lambda"
  double value = 0.0;
};
struct Undo {};
struct Redo {};
struct DeleteSection {
  int section = 0;  // index of the cross section in the model's curve list
};
struct Save {
  std::string path;
};
// A file opened into the session: a saved session, which replaces it (`kind` "session"), or a
// mesh made its base ("mesh"). `digest` is the file's content as opened (FNV-1a 64 of its
// bytes, 16 lower-case hex digits), so a replay can tell that the file changed since and
// refuse to open a different one; `path` is absolute.
struct OpenFile {
  std::string kind;
  std::string path;
  std::string digest;
};

using Event = std::variant<PenSample, SelectPlane, TranslatePlane, CameraChange, SetToolMode,
                           SetParameter, Undo, Redo, DeleteSection, Save, OpenFile>;

struct TimedEvent {
  double t = 0.0;  // ms; for a PenSample equal to sample.t
  int line = 0;    // 1-based source line when read from a file, 0 when made in memory
  Event event;
};

// The log's "type" string for an event ("pen", "select_plane", ...).
std::string_view event_type_name(const Event& e);
bool is_pen_sample(const Event& e);

std::string_view tool_name(Tool t);
std::string_view phase_name(Phase p);

// === Header and whole log

inline constexpr std::string_view kStrokeLogFormat = "planesketch-stroke-log";
inline constexpr int kStrokeLogVersion = 1;

struct LogHeader {
  int version = kStrokeLogVersion;
  int viewport_width = 1280;  // window pixels; equals camera.width / camera.height
  int viewport_height = 800;
  Camera camera;              // initial camera
  std::string units = "unit";  // what one scene unit means ("unit", "mm", ...)
  // Initial reference planes; default: the three basic planes x = 0, y = 0, z = 0.
  std::vector<Plane> planes = default_reference_planes();
  std::string generator;  // free text: who wrote the log (optional)

  static std::vector<Plane> default_reference_planes() {
    return {Plane{Vec3::UnitX(), 0.0}, Plane{Vec3::UnitY(), 0.0}, Plane{Vec3::UnitZ(), 0.0}};
  }
};

struct StrokeLog {
  LogHeader header;
  std::vector<TimedEvent> events;
  // The session-end marker (`{"t":..,"type":"end"}`, always the last line): the time at which
  // the app closed the log cleanly. Absent in a journal whose app died (crash recovery looks
  // for those) and in logs written before the marker existed. Not an event: sinks never see it.
  std::optional<double> end_t;
};

// A pen stroke: the samples from down through up (no hover, no proximity samples).
struct Stroke {
  std::vector<PenSample> samples;
  Tool tool = Tool::kPen;
  bool ended_with_up = true;  // false when cut off by proximity-out, a new down or log end
};

}  // namespace ps
