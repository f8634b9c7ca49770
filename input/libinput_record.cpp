// `libinput record` YAML reader (hand-written subset parser, see libinput_record.h) and the
// evdev tablet protocol -> TabletToolEvent conversion.
#include "input/libinput_record.h"

#include <linux/input-event-codes.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace ps {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Removes a '#' comment (outside double quotes, at line start or after whitespace).
std::string_view strip_comment(std::string_view s) {
  bool quoted = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quoted) {
      if (c == '\\') ++i;
      else if (c == '"') quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t')) {
      return s.substr(0, i);
    }
  }
  return s;
}

std::string unquote(std::string_view v) {
  v = trim(v);
  if (v.size() >= 2 && v.front() == '"' && v.back() == '"') return std::string(v.substr(1, v.size() - 2));
  return std::string(v);
}

bool parse_int(std::string_view s, std::int64_t& out) {
  s = trim(s);
  if (s.empty()) return false;
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (*b == '+') ++b;
  auto r = std::from_chars(b, e, out);
  return r.ec == std::errc() && r.ptr == e;
}

// "[a, b, c]" -> integers; "" on success, else a message.
std::string parse_int_list(std::string_view v, std::vector<std::int64_t>& out) {
  v = trim(v);
  if (v.empty() || v.front() != '[') return "expected a flow sequence '[...]'";
  if (v.back() != ']') return "unterminated flow sequence (missing ']')";
  v = v.substr(1, v.size() - 2);
  out.clear();
  if (trim(v).empty()) return {};
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = v.find(',', pos);
    const std::string_view tok = v.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    std::int64_t x = 0;
    if (!parse_int(tok, x)) {
      std::string m(trim(tok));  // built in steps: GCC 12 warns falsely (-Wrestrict) on "'" + str
      m.insert(0, 1, '\'');
      m += "' is not an integer";
      return m;
    }
    out.push_back(x);
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  return {};
}

bool fits_int(std::int64_t v) { return v >= INT32_MIN && v <= INT32_MAX; }

struct Node {
  int indent;
  std::string key;
  bool item;
};

}  // namespace

Result<LibinputRecording> parse_libinput_record(std::string_view text, const std::string& name) {
  auto fail = [&](int line, const std::string& m) {
    return Result<LibinputRecording>::error(name + ":" + std::to_string(line) + ": " + m);
  };
  LibinputRecording rec;
  bool have_version = false, have_devices = false;
  std::vector<Node> stack;
  std::vector<EvdevInputEvent>* frame = nullptr;
  auto path = [&] {
    std::string p;
    for (const Node& n : stack) {
      if (!p.empty()) p += '/';
      p += n.key;
    }
    return p;
  };

  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    ++line_no;
    const std::size_t nl = text.find('\n', pos);
    std::string_view raw = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    std::string_view line = strip_comment(raw);
    if (trim(line).empty()) continue;
    int indent = 0;
    while (static_cast<std::size_t>(indent) < line.size() && line[static_cast<std::size_t>(indent)] == ' ') ++indent;
    if (line[static_cast<std::size_t>(indent)] == '\t') return fail(line_no, "tab in indentation (YAML allows spaces only)");
    std::string_view rest = trim(line.substr(static_cast<std::size_t>(indent)));
    const bool item = rest == "-" || rest.substr(0, 2) == "- ";
    int content_indent = indent;
    std::string_view content = rest;
    if (item) {
      while (!stack.empty() && (stack.back().indent > indent || (stack.back().indent == indent && stack.back().item)))
        stack.pop_back();
      stack.push_back({indent, "-", true});
      if (path() == "devices/-") {
        rec.devices.emplace_back();
        frame = nullptr;
      }
      content = rest.substr(1);
      content_indent = indent + 1;
      while (!content.empty() && content.front() == ' ') content.remove_prefix(1), ++content_indent;
      if (content.empty()) continue;
    } else {
      while (!stack.empty() && stack.back().indent >= indent) stack.pop_back();
    }
    const std::string here = path();

    // === A flow sequence inside a list: an evdev event
    if (content.front() == '[') {
      if (here == "devices/-/events/-/evdev/-") {
        std::vector<std::int64_t> v;
        if (std::string e = parse_int_list(content, v); !e.empty()) return fail(line_no, e);
        if (v.size() != 5) return fail(line_no, "expected [sec, usec, type, code, value]");
        for (int k = 2; k < 5; ++k)
          if (!fits_int(v[static_cast<std::size_t>(k)])) return fail(line_no, "event value out of range");
        if (v[0] < 0 || v[1] < 0 || v[1] >= 1000000) return fail(line_no, "bad event time");
        if (!frame) return fail(line_no, "evdev event outside an evdev frame");
        frame->push_back(EvdevInputEvent{v[0], v[1], static_cast<int>(v[2]), static_cast<int>(v[3]),
                                         static_cast<int>(v[4]), line_no});
      }
      continue;
    }
    if (content.front() == '{') continue;  // flow mappings: libinput/hid events, ignored

    // === key: value, or key: opening a block
    std::size_t colon = std::string_view::npos;
    for (std::size_t i = 0; i < content.size(); ++i)
      if (content[i] == ':' && (i + 1 == content.size() || content[i + 1] == ' ')) {
        colon = i;
        break;
      }
    if (colon == std::string_view::npos) {
      if (item) continue;  // a plain scalar list item (udev properties, quirks): ignored
      return fail(line_no, "expected 'key: value' or '- item', got '" + std::string(content) + "'");
    }
    const std::string key(trim(content.substr(0, colon)));
    const std::string_view value = trim(content.substr(colon + 1));
    if (key.empty()) return fail(line_no, "empty key");
    const std::string full = here.empty() ? key : here + "/" + key;
    if (value.empty()) {
      stack.push_back({content_indent, key, false});
      if (full == "devices") have_devices = true;
      if (full == "devices/-/events/-/evdev") {
        if (rec.devices.empty()) return fail(line_no, "events outside a device");
        rec.devices.back().frames.emplace_back();
        frame = &rec.devices.back().frames.back();
      }
      continue;
    }
    if (full == "version") {
      std::int64_t v = 0;
      if (!parse_int(value, v)) return fail(line_no, "version must be an integer");
      if (v != 1) return fail(line_no, "unsupported libinput record version " + std::to_string(v) + " (reads 1)");
      rec.version = 1;
      have_version = true;
    } else if (full == "devices/-/node") {
      rec.devices.back().node = unquote(value);
    } else if (full == "devices/-/evdev/name") {
      rec.devices.back().name = unquote(value);
    } else if (here == "devices/-/evdev/absinfo") {
      std::int64_t code = 0;
      if (!parse_int(key, code) || code < 0 || code > ABS_MAX) return fail(line_no, "absinfo code '" + key + "' is not an ABS code");
      std::vector<std::int64_t> v;
      if (std::string e = parse_int_list(value, v); !e.empty()) return fail(line_no, e);
      if (v.size() < 5 || v.size() > 6) return fail(line_no, "absinfo expects [min, max, fuzz, flat, resolution]");
      for (std::int64_t x : v)
        if (!fits_int(x)) return fail(line_no, "absinfo value out of range");
      if (v[1] < v[0]) return fail(line_no, "absinfo maximum is below minimum");
      rec.devices.back().absinfo[static_cast<int>(code)] =
          EvdevAbsInfo{static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3]),
                       static_cast<int>(v[4])};
    } else if (full == "devices") {
      return fail(line_no, "'devices' must be a list");
    }
  }
  if (line_no == 0) return fail(1, "empty recording");
  if (!have_version) return fail(1, "missing 'version' (not a libinput record file?)");
  if (!have_devices || rec.devices.empty()) return fail(line_no, "no devices in recording");
  return rec;
}

Result<LibinputRecording> read_libinput_record(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Result<LibinputRecording>::error(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  return parse_libinput_record(s.str(), path);
}

std::optional<Vec2> tablet_size_mm(const EvdevRecordedDevice& d) {
  auto x = d.absinfo.find(ABS_X), y = d.absinfo.find(ABS_Y);
  if (x == d.absinfo.end() || y == d.absinfo.end() || x->second.resolution <= 0 || y->second.resolution <= 0)
    return std::nullopt;
  return Vec2(static_cast<double>(x->second.maximum - x->second.minimum) / x->second.resolution,
              static_cast<double>(y->second.maximum - y->second.minimum) / y->second.resolution);
}

// === evdev tablet protocol -> libinput-style events

Result<std::vector<TabletToolEvent>> tablet_events_from_evdev(const EvdevRecordedDevice& d) {
  using R = Result<std::vector<TabletToolEvent>>;
  const auto ax = d.absinfo.find(ABS_X), ay = d.absinfo.find(ABS_Y);
  if (ax == d.absinfo.end() || ay == d.absinfo.end())
    return R::error("device '" + d.name + "' has no ABS_X/ABS_Y (not a tablet)");
  const EvdevAbsInfo X = ax->second, Y = ay->second;
  const bool in_mm = X.resolution > 0 && Y.resolution > 0;
  auto info = [&](int code) -> const EvdevAbsInfo* {
    auto it = d.absinfo.find(code);
    return it == d.absinfo.end() ? nullptr : &it->second;
  };
  const EvdevAbsInfo* P = info(ABS_PRESSURE);
  const EvdevAbsInfo* TX = info(ABS_TILT_X);
  const EvdevAbsInfo* TY = info(ABS_TILT_Y);
  auto norm = [](int v, const EvdevAbsInfo& a) {
    return a.maximum > a.minimum ? static_cast<double>(v - a.minimum) / (a.maximum - a.minimum) : 0.0;
  };
  // Tilt: resolution is units per radian (kernel ABI); without one, units are taken as degrees.
  auto tilt = [](int v, const EvdevAbsInfo* a) {
    if (!a) return 0.0;
    const double centre = (a->minimum < 0 && a->maximum > 0) ? 0.0 : 0.5 * (a->minimum + a->maximum);
    const double units = v - centre;
    return a->resolution > 0 ? units / a->resolution * 180.0 / M_PI : units;
  };

  struct State {
    std::map<int, int> abs;
    int tool_code = 0;  // the BTN_TOOL_* held, 0 when out of proximity
    bool touch = false;
    std::uint32_t buttons = 0;
  };
  State st;
  std::vector<TabletToolEvent> out;
  bool have_t0 = false;
  double t0 = 0.0;

  auto make = [&](const State& s, TabletEventKind kind, double t) {
    TabletToolEvent e;
    e.kind = kind;
    e.time_ms = t;
    e.position_in_mm = in_mm;
    const int xv = s.abs.count(ABS_X) ? s.abs.at(ABS_X) : X.minimum;
    const int yv = s.abs.count(ABS_Y) ? s.abs.at(ABS_Y) : Y.minimum;
    e.x = in_mm ? static_cast<double>(xv - X.minimum) / X.resolution : norm(xv, X);
    e.y = in_mm ? static_cast<double>(yv - Y.minimum) / Y.resolution : norm(yv, Y);
    e.pressure = P ? std::clamp(norm(s.abs.count(ABS_PRESSURE) ? s.abs.at(ABS_PRESSURE) : P->minimum, *P), 0.0, 1.0)
                   : (s.touch ? 1.0 : 0.0);
    e.tilt_x_deg = tilt(s.abs.count(ABS_TILT_X) ? s.abs.at(ABS_TILT_X) : 0, TX);
    e.tilt_y_deg = tilt(s.abs.count(ABS_TILT_Y) ? s.abs.at(ABS_TILT_Y) : 0, TY);
    e.tip_down = s.touch;
    e.in_proximity = s.tool_code != 0;
    e.tool = s.tool_code == BTN_TOOL_RUBBER                                       ? Tool::kEraser
             : (s.tool_code == BTN_TOOL_MOUSE || s.tool_code == BTN_TOOL_LENS) ? Tool::kMouse
                                                                                  : Tool::kPen;
    e.buttons = s.buttons;
    return e;
  };
  auto axes_of = [](const State& s) {
    std::array<int, 5> a{};
    const int codes[5] = {ABS_X, ABS_Y, ABS_PRESSURE, ABS_TILT_X, ABS_TILT_Y};
    for (int k = 0; k < 5; ++k) a[static_cast<std::size_t>(k)] = s.abs.count(codes[k]) ? s.abs.at(codes[k]) : 0;
    return a;
  };

  for (const auto& fr : d.frames) {
    State next = st;
    bool pending = false;
    double t = 0.0;
    auto flush = [&] {
      const bool was_in = st.tool_code != 0, now_in = next.tool_code != 0;
      const bool axes_changed = axes_of(st) != axes_of(next);
      State outgoing = next;  // a tool leaving keeps the tool it had for its last events
      if (!now_in) outgoing.tool_code = st.tool_code;
      if (!was_in && now_in) out.push_back(make(next, TabletEventKind::kProximity, t));
      const bool tip_down = !st.touch && next.touch && now_in;
      const bool tip_up = st.touch && !next.touch;
      if (tip_down) out.push_back(make(next, TabletEventKind::kTip, t));
      else if (axes_changed && was_in && (now_in || tip_up)) {
        State s = outgoing;
        s.touch = st.touch;      // the axis event before a tip-up still has the tip down
        s.buttons = st.buttons;  // and a button changed in this frame follows it
        if (now_in || tip_up) out.push_back(make(s, TabletEventKind::kAxis, t));
      }
      if (st.buttons != next.buttons && (now_in || was_in)) out.push_back(make(outgoing, TabletEventKind::kButton, t));
      if (tip_up) {
        State s = outgoing;
        s.touch = false;
        out.push_back(make(s, TabletEventKind::kTip, t));
      }
      if (was_in && !now_in) {
        // Tablets reset their axes as the tool leaves; libinput reports the last position.
        State s = st;
        s.touch = false;
        s.buttons = 0;
        TabletToolEvent e = make(s, TabletEventKind::kProximity, t);
        e.in_proximity = false;
        out.push_back(e);
        next.buttons = 0;
      }
      st = next;
      pending = false;
    };
    for (const EvdevInputEvent& ev : fr) {
      const double tm = static_cast<double>(ev.sec) * 1000.0 + static_cast<double>(ev.usec) / 1000.0;
      if (!have_t0) {
        t0 = tm;
        have_t0 = true;
      }
      t = tm - t0;
      pending = true;
      if (ev.type == EV_ABS) {
        next.abs[ev.code] = ev.value;
      } else if (ev.type == EV_KEY) {
        switch (ev.code) {
          case BTN_TOOL_PEN:
          case BTN_TOOL_RUBBER:
          case BTN_TOOL_BRUSH:
          case BTN_TOOL_PENCIL:
          case BTN_TOOL_AIRBRUSH:
          case BTN_TOOL_MOUSE:
          case BTN_TOOL_LENS:
            if (ev.value) next.tool_code = ev.code;
            else if (next.tool_code == ev.code) next.tool_code = 0;
            break;
          case BTN_TOUCH: next.touch = ev.value != 0; break;
          case BTN_STYLUS:
            next.buttons = ev.value ? (next.buttons | kPenButtonPrimary) : (next.buttons & ~std::uint32_t{kPenButtonPrimary});
            break;
          case BTN_STYLUS2:
            next.buttons = ev.value ? (next.buttons | kPenButtonSecondary) : (next.buttons & ~std::uint32_t{kPenButtonSecondary});
            break;
          default: break;
        }
      } else if (ev.type == EV_SYN && ev.code == SYN_REPORT) {
        flush();
      }
    }
    if (pending) flush();  // a frame without its SYN_REPORT (cut-off recording)
  }
  return out;
}

Result<std::vector<PenSample>> pen_samples_from_recording(const LibinputRecording& rec, double window_width,
                                                          double window_height) {
  using R = Result<std::vector<PenSample>>;
  for (const EvdevRecordedDevice& d : rec.devices) {
    if (!d.absinfo.count(ABS_X) || !d.absinfo.count(ABS_Y)) continue;
    auto events = tablet_events_from_evdev(d);
    if (!events) return events.status();
    TabletMapping m;
    if (const auto size = tablet_size_mm(d)) {
      m = TabletMapping::fit(size->x(), size->y(), window_width, window_height);
    } else {
      m.window_width = window_width;
      m.window_height = window_height;
    }
    std::vector<PenSample> out;
    for (const TabletToolEvent& e : *events) {
      auto s = translate_tablet_event(e, m);
      if (!s) return R::error(d.node + ": " + s.message());
      out.push_back(*s);
    }
    return out;
  }
  return R::error("no tablet device (with ABS_X and ABS_Y) in the recording");
}

}  // namespace ps
