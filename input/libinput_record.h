#pragma once
// Reader for recordings made with `libinput record` (libinput-record(1)): the devices with
// their absinfo, and the evdev event frames. Tablet frames are turned into the same plain
// TabletToolEvents the live reader produces, then through translate_tablet_event(), so a
// recording replays exactly like a live pen.
//
// The YAML is parsed by hand, and only the subset libinput record writes: block mappings and
// block sequences by indentation, one-line flow sequences of integers ("[a, b, c]"), plain or
// double-quoted scalars, and '#' comments. Unknown keys are ignored, as the format asks of
// parsers. No YAML library is in the dependency set, and this subset is small enough that a
// hand parser gives better messages ("file:line: ...").
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "input/pen_input.h"
#include "modeling/status.h"

namespace ps {

struct EvdevAbsInfo {
  int minimum = 0, maximum = 0, fuzz = 0, flat = 0, resolution = 0;  // resolution: units/mm (x, y), units/radian (tilt)
};

struct EvdevInputEvent {
  std::int64_t sec = 0, usec = 0;
  int type = 0, code = 0, value = 0;
  int line = 0;  // source line
};

struct EvdevRecordedDevice {
  std::string node;
  std::string name;
  std::map<int, EvdevAbsInfo> absinfo;                 // by ABS_* code
  std::vector<std::vector<EvdevInputEvent>> frames;    // each ends with SYN_REPORT
};

struct LibinputRecording {
  int version = 0;
  std::vector<EvdevRecordedDevice> devices;
};

Result<LibinputRecording> parse_libinput_record(std::string_view text, const std::string& name);
Result<LibinputRecording> read_libinput_record(const std::string& path);

// Tablet size in mm from the ABS_X / ABS_Y ranges and resolutions; nothing if unknown.
std::optional<Vec2> tablet_size_mm(const EvdevRecordedDevice& d);

// Follows the evdev tablet protocol frame by frame (BTN_TOOL_PEN / BTN_TOOL_RUBBER ... for
// proximity, BTN_TOUCH for the tip, BTN_STYLUS / BTN_STYLUS2 for buttons, ABS_X/Y/PRESSURE/
// TILT_X/TILT_Y for axes) and emits events in libinput's order: proximity-in, tip-down (with
// the frame's axes), axis, button, tip-up, proximity-out. Times are relative to the first
// frame. Fails when the device lacks ABS_X or ABS_Y.
Result<std::vector<TabletToolEvent>> tablet_events_from_evdev(const EvdevRecordedDevice& d);

// The first device with ABS_X, ABS_Y and a pen tool, replayed into pen samples. With no
// mapping given, the tablet is fitted to a window of `window_width` x `window_height`.
Result<std::vector<PenSample>> pen_samples_from_recording(const LibinputRecording& rec, double window_width,
                                                          double window_height);

}  // namespace ps
