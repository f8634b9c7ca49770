#pragma once
// Pen input: tablet-tool events (libinput, live or recorded) and the mouse fallback, translated
// into PenSamples in window pixels (docs/input.md).
//
// The translation is a pure function over a small plain struct of event values, so it is
// tested with synthetic values and shared by the live reader and the `libinput record` reader
// (input/libinput_record.h). No window-system header is included here: the app passes GLFW's
// cursor values to pointer_sample().
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "input/stroke_log.h"
#include "modeling/status.h"

namespace ps {

// === Plain tablet-tool event values

enum class TabletEventKind { kAxis, kProximity, kTip, kButton };

struct TabletToolEvent {
  TabletEventKind kind = TabletEventKind::kAxis;
  double time_ms = 0.0;          // on the log's clock (the caller subtracts its origin)
  bool position_in_mm = true;    // true: x, y are mm from the tablet's top-left corner;
                                 // false: normalized [0, 1] over the tablet's range
  double x = 0.0;
  double y = 0.0;
  double pressure = 0.0;         // [0, 1]
  double tilt_x_deg = 0.0;       // libinput's convention: positive x tilt leans right
  double tilt_y_deg = 0.0;       // positive y tilt leans toward the user (bottom)
  bool tip_down = false;         // tip state after this event
  bool in_proximity = true;      // proximity state after this event
  Tool tool = Tool::kPen;        // pen-like tools -> kPen, eraser -> kEraser, mouse/lens -> kMouse
  std::uint32_t buttons = 0;     // PenButton mask after this event
};

// Tablet area (mm) -> window rectangle (pixels). Positions outside the area map outside the
// window (the app decides what to do with them); nothing is clamped.
struct TabletMapping {
  double area_x_mm = 0.0, area_y_mm = 0.0;
  double area_width_mm = 1.0, area_height_mm = 1.0;
  double window_x = 0.0, window_y = 0.0;
  double window_width = 1.0, window_height = 1.0;

  // The largest centred tablet area with the window's aspect ratio mapped onto the whole
  // window, so circles stay circles.
  static TabletMapping fit(double tablet_width_mm, double tablet_height_mm, double window_width,
                           double window_height);
};

// Proximity -> proximity-in/out, tip -> down/up, axis and button -> move. Pressure and tilt are
// clamped into the log's ranges. Fails on non-finite values or a degenerate mapping.
Result<PenSample> translate_tablet_event(const TabletToolEvent& e, const TabletMapping& m);

// === Mouse fallback

// A GLFW cursor sample: tool mouse, pressure 1 while the button is held (0 otherwise); the
// phase is down / up when the button state changed since the previous sample, else move.
PenSample pointer_sample(double t_ms, double x, double y, bool button_down, bool was_down);

// === Live tablet reader (libinput on a udev seat)

// Opens the seat with libinput (device nodes opened with open(2)) and polls it without
// blocking. open() fails with the reason when no tablet can be used ("no permission for
// /dev/input ...", "no tablet tool device on seat0 ...") so the app can fall back to the
// mouse and say why once.
class LibinputTabletReader {
 public:
  static Result<std::unique_ptr<LibinputTabletReader>> open(const TabletMapping& mapping,
                                                            const std::string& seat = "seat0");
  ~LibinputTabletReader();
  LibinputTabletReader(const LibinputTabletReader&) = delete;
  LibinputTabletReader& operator=(const LibinputTabletReader&) = delete;

  // Appends the samples of all pending tablet-tool events; never blocks. Fails (once) when the
  // tablet was unplugged.
  Status poll(std::vector<PenSample>& out);
  // libinput's file descriptor, for the app's poll()/select() loop.
  int fd() const;
  void set_mapping(const TabletMapping& m) { mapping_ = m; }
  // Sample times are libinput's CLOCK_MONOTONIC time in ms minus this origin.
  void set_time_origin_ms(double origin) { origin_ms_ = origin; }
  const std::string& device_name() const { return device_name_; }

  struct Impl;

 private:
  explicit LibinputTabletReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  TabletMapping mapping_;
  double origin_ms_ = 0.0;
  std::uint32_t buttons_ = 0;
  std::string device_name_;
};

}  // namespace ps
