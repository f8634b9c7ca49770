// Pen input translation, mouse fallback and the live libinput tablet reader.
#include "input/pen_input.h"

#include <fcntl.h>
#include <libinput.h>
#include <libudev.h>
#include <linux/input-event-codes.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstring>

namespace ps {

// === Translation

TabletMapping TabletMapping::fit(double tw, double th, double ww, double wh) {
  TabletMapping m;
  m.window_width = ww;
  m.window_height = wh;
  const double window_aspect = ww / wh;
  if (tw / th > window_aspect) {  // tablet wider: use its full height
    m.area_height_mm = th;
    m.area_width_mm = th * window_aspect;
    m.area_x_mm = 0.5 * (tw - m.area_width_mm);
  } else {
    m.area_width_mm = tw;
    m.area_height_mm = tw / window_aspect;
    m.area_y_mm = 0.5 * (th - m.area_height_mm);
  }
  return m;
}

Result<PenSample> translate_tablet_event(const TabletToolEvent& e, const TabletMapping& m) {
  for (double v : {e.time_ms, e.x, e.y, e.pressure, e.tilt_x_deg, e.tilt_y_deg})
    if (!std::isfinite(v)) return Result<PenSample>::error("tablet event has a non-finite value");
  if (!(m.area_width_mm > 0.0) || !(m.area_height_mm > 0.0) || !(m.window_width > 0.0) ||
      !(m.window_height > 0.0))
    return Result<PenSample>::error("tablet mapping has an empty area or window");
  PenSample s;
  s.t = e.time_ms;
  if (e.position_in_mm) {
    s.x = m.window_x + (e.x - m.area_x_mm) / m.area_width_mm * m.window_width;
    s.y = m.window_y + (e.y - m.area_y_mm) / m.area_height_mm * m.window_height;
  } else {
    s.x = m.window_x + e.x * m.window_width;
    s.y = m.window_y + e.y * m.window_height;
  }
  s.pressure = std::clamp(e.pressure, 0.0, 1.0);
  s.tilt_x = std::clamp(e.tilt_x_deg, -90.0, 90.0);
  s.tilt_y = std::clamp(e.tilt_y_deg, -90.0, 90.0);
  s.tool = e.tool;
  s.buttons = e.buttons;
  switch (e.kind) {
    case TabletEventKind::kProximity:
      s.phase = e.in_proximity ? Phase::kProximityIn : Phase::kProximityOut;
      break;
    case TabletEventKind::kTip:
      s.phase = e.tip_down ? Phase::kDown : Phase::kUp;
      break;
    case TabletEventKind::kAxis:
    case TabletEventKind::kButton:
      s.phase = Phase::kMove;
      break;
  }
  if (s.phase == Phase::kUp || s.phase == Phase::kProximityOut) s.pressure = 0.0;
  return s;
}

PenSample pointer_sample(double t_ms, double x, double y, bool button_down, bool was_down) {
  PenSample s;
  s.t = t_ms;
  s.x = x;
  s.y = y;
  s.tool = Tool::kMouse;
  s.pressure = button_down ? 1.0 : 0.0;
  s.phase = button_down == was_down ? Phase::kMove : (button_down ? Phase::kDown : Phase::kUp);
  return s;
}

// === Live reader

struct LibinputTabletReader::Impl {
  udev* u = nullptr;
  libinput* li = nullptr;
  int refused = 0;       // device nodes we had no permission for
  int open_failures = 0;
  std::string last_refused;
  libinput_device* tablet = nullptr;

  ~Impl() {
    if (li) libinput_unref(li);
    if (u) udev_unref(u);
  }
};

namespace {

int open_restricted(const char* path, int flags, void* user_data) {
  auto* impl = static_cast<LibinputTabletReader::Impl*>(user_data);
  const int fd = ::open(path, flags | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == EACCES || err == EPERM) {
      ++impl->refused;
      impl->last_refused = path;
    } else {
      ++impl->open_failures;
    }
    return -err;
  }
  return fd;
}

void close_restricted(int fd, void*) { ::close(fd); }

const libinput_interface kInterface = {open_restricted, close_restricted};

// libinput's own messages would go to stderr; the reader reports one reason instead.
void quiet_log(libinput*, libinput_log_priority, const char*, va_list) {}

Tool tool_of(libinput_tablet_tool* tool) {
  switch (libinput_tablet_tool_get_type(tool)) {
    case LIBINPUT_TABLET_TOOL_TYPE_ERASER: return Tool::kEraser;
    case LIBINPUT_TABLET_TOOL_TYPE_MOUSE:
    case LIBINPUT_TABLET_TOOL_TYPE_LENS: return Tool::kMouse;
    default: return Tool::kPen;
  }
}

}  // namespace

LibinputTabletReader::LibinputTabletReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LibinputTabletReader::~LibinputTabletReader() = default;

Result<std::unique_ptr<LibinputTabletReader>> LibinputTabletReader::open(const TabletMapping& mapping,
                                                                         const std::string& seat) {
  using R = Result<std::unique_ptr<LibinputTabletReader>>;
  auto impl = std::make_unique<Impl>();
  struct stat st {};
  if (::stat("/dev/input", &st) != 0) return R::error("no tablet: /dev/input does not exist");
  impl->u = udev_new();
  if (!impl->u) return R::error("no tablet: udev is unavailable");
  impl->li = libinput_udev_create_context(&kInterface, impl.get(), impl->u);
  if (!impl->li) return R::error("no tablet: cannot create a libinput context");
  libinput_log_set_handler(impl->li, quiet_log);
  if (libinput_udev_assign_seat(impl->li, seat.c_str()) != 0)
    return R::error("no tablet: cannot assign udev seat '" + seat + "'");
  libinput_dispatch(impl->li);
  int devices = 0;
  std::string name;
  while (libinput_event* ev = libinput_get_event(impl->li)) {
    if (libinput_event_get_type(ev) == LIBINPUT_EVENT_DEVICE_ADDED) {
      ++devices;
      libinput_device* d = libinput_event_get_device(ev);
      if (!impl->tablet && libinput_device_has_capability(d, LIBINPUT_DEVICE_CAP_TABLET_TOOL)) {
        impl->tablet = d;
        name = libinput_device_get_name(d);
      }
    }
    libinput_event_destroy(ev);
  }
  if (!impl->tablet) {
    if (impl->refused > 0)
      return R::error("no permission for /dev/input (" + std::to_string(impl->refused) +
                      " device nodes refused, e.g. " + impl->last_refused +
                      "; add the user to the 'input' group)");
    return R::error("no tablet tool device on " + seat + " (" + std::to_string(devices) + " input devices)");
  }
  std::unique_ptr<LibinputTabletReader> r(new LibinputTabletReader(std::move(impl)));
  r->mapping_ = mapping;
  r->device_name_ = name;
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  r->origin_ms_ = static_cast<double>(now.tv_sec) * 1000.0 + static_cast<double>(now.tv_nsec) / 1e6;
  return R(std::move(r));
}

int LibinputTabletReader::fd() const { return libinput_get_fd(impl_->li); }

Status LibinputTabletReader::poll(std::vector<PenSample>& out) {
  Status status = Status::ok();
  if (libinput_dispatch(impl_->li) != 0) status = Status::error("libinput dispatch failed");
  while (libinput_event* ev = libinput_get_event(impl_->li)) {
    const libinput_event_type type = libinput_event_get_type(ev);
    if (type == LIBINPUT_EVENT_DEVICE_REMOVED && libinput_event_get_device(ev) == impl_->tablet) {
      impl_->tablet = nullptr;
      status = Status::error("tablet '" + device_name_ + "' was removed");
    }
    if (type == LIBINPUT_EVENT_TABLET_TOOL_AXIS || type == LIBINPUT_EVENT_TABLET_TOOL_PROXIMITY ||
        type == LIBINPUT_EVENT_TABLET_TOOL_TIP || type == LIBINPUT_EVENT_TABLET_TOOL_BUTTON) {
      libinput_event_tablet_tool* t = libinput_event_get_tablet_tool_event(ev);
      libinput_tablet_tool* tool = libinput_event_tablet_tool_get_tool(t);
      TabletToolEvent e;
      e.kind = type == LIBINPUT_EVENT_TABLET_TOOL_PROXIMITY ? TabletEventKind::kProximity
               : type == LIBINPUT_EVENT_TABLET_TOOL_TIP     ? TabletEventKind::kTip
               : type == LIBINPUT_EVENT_TABLET_TOOL_BUTTON  ? TabletEventKind::kButton
                                                            : TabletEventKind::kAxis;
      e.time_ms = static_cast<double>(libinput_event_tablet_tool_get_time_usec(t)) / 1000.0 - origin_ms_;
      e.position_in_mm = true;
      e.x = libinput_event_tablet_tool_get_x(t);
      e.y = libinput_event_tablet_tool_get_y(t);
      e.pressure = libinput_tablet_tool_has_pressure(tool) ? libinput_event_tablet_tool_get_pressure(t)
                                                            : (libinput_event_tablet_tool_get_tip_state(t) ==
                                                                       LIBINPUT_TABLET_TOOL_TIP_DOWN
                                                                   ? 1.0
                                                                   : 0.0);
      if (libinput_tablet_tool_has_tilt(tool)) {
        e.tilt_x_deg = libinput_event_tablet_tool_get_tilt_x(t);
        e.tilt_y_deg = libinput_event_tablet_tool_get_tilt_y(t);
      }
      e.tip_down = libinput_event_tablet_tool_get_tip_state(t) == LIBINPUT_TABLET_TOOL_TIP_DOWN;
      e.in_proximity =
          libinput_event_tablet_tool_get_proximity_state(t) == LIBINPUT_TABLET_TOOL_PROXIMITY_STATE_IN;
      e.tool = tool_of(tool);
      if (type == LIBINPUT_EVENT_TABLET_TOOL_BUTTON) {
        const std::uint32_t code = libinput_event_tablet_tool_get_button(t);
        const std::uint32_t bit = code == BTN_STYLUS ? kPenButtonPrimary : code == BTN_STYLUS2 ? kPenButtonSecondary : 0u;
        if (libinput_event_tablet_tool_get_button_state(t) == LIBINPUT_BUTTON_STATE_PRESSED) buttons_ |= bit;
        else buttons_ &= ~bit;
      }
      if (type == LIBINPUT_EVENT_TABLET_TOOL_PROXIMITY && !e.in_proximity) buttons_ = 0;
      e.buttons = buttons_;
      if (auto s = translate_tablet_event(e, mapping_)) out.push_back(*s);
    }
    libinput_event_destroy(ev);
  }
  return status;
}

}  // namespace ps
