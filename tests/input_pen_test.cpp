// Pen input translation (synthetic libinput values), mouse fallback, the live reader's
// fallback reasons, and replaying a `libinput record` file into pen samples.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "input/libinput_record.h"
#include "input/pen_input.h"

namespace ps {
namespace {

TabletToolEvent ev(TabletEventKind kind, double x, double y, double p = 0.5) {
  TabletToolEvent e;
  e.kind = kind;
  e.time_ms = 12.5;
  e.x = x;
  e.y = y;
  e.pressure = p;
  e.tilt_x_deg = 30;
  e.tilt_y_deg = -20;
  e.tip_down = true;
  return e;
}

// === Translation

TEST(PenInput, FitKeepsAspectAndMapsTheAreaOntoTheWindow) {
  // A 16:10 tablet into a 4:3 window: full height, centred width.
  const TabletMapping m = TabletMapping::fit(160, 100, 800, 600);
  EXPECT_DOUBLE_EQ(m.area_height_mm, 100);
  EXPECT_DOUBLE_EQ(m.area_width_mm, 100 * 800.0 / 600.0);
  EXPECT_DOUBLE_EQ(m.area_x_mm, 0.5 * (160 - m.area_width_mm));
  auto corner = [&](double x, double y) { return *translate_tablet_event(ev(TabletEventKind::kAxis, x, y), m); };
  const PenSample a = corner(m.area_x_mm, 0), b = corner(m.area_x_mm + m.area_width_mm, 100);
  EXPECT_NEAR(a.x, 0, 1e-12);
  EXPECT_NEAR(a.y, 0, 1e-12);
  EXPECT_NEAR(b.x, 800, 1e-12);
  EXPECT_NEAR(b.y, 600, 1e-12);
  // Equal mm distances give equal pixel distances in x and y (circles stay circles).
  const PenSample c = corner(80, 50), dx = corner(90, 50), dy = corner(80, 60);
  EXPECT_NEAR(dx.x - c.x, dy.y - c.y, 1e-9);
  // A tall tablet: full width, centred height.
  const TabletMapping t = TabletMapping::fit(100, 200, 800, 600);
  EXPECT_DOUBLE_EQ(t.area_width_mm, 100);
  EXPECT_DOUBLE_EQ(t.area_y_mm, 0.5 * (200 - 75));
}

TEST(PenInput, PhasesFollowProximityTipAndAxes) {
  const TabletMapping m = TabletMapping::fit(100, 100, 500, 500);
  TabletToolEvent e = ev(TabletEventKind::kProximity, 10, 20, 0.0);
  e.in_proximity = true;
  e.tip_down = false;
  EXPECT_EQ(translate_tablet_event(e, m)->phase, Phase::kProximityIn);
  e.in_proximity = false;
  EXPECT_EQ(translate_tablet_event(e, m)->phase, Phase::kProximityOut);
  e = ev(TabletEventKind::kTip, 10, 20, 0.3);
  const PenSample down = *translate_tablet_event(e, m);
  EXPECT_EQ(down.phase, Phase::kDown);
  EXPECT_EQ(down.pressure, 0.3);
  EXPECT_EQ(down.t, 12.5);
  EXPECT_EQ(down.tilt_x, 30);
  EXPECT_EQ(down.tilt_y, -20);
  EXPECT_DOUBLE_EQ(down.x, 50);
  EXPECT_DOUBLE_EQ(down.y, 100);
  e.tip_down = false;
  const PenSample up = *translate_tablet_event(e, m);
  EXPECT_EQ(up.phase, Phase::kUp);
  EXPECT_EQ(up.pressure, 0.0);
  e = ev(TabletEventKind::kButton, 10, 20);
  e.buttons = kPenButtonSecondary;
  const PenSample b = *translate_tablet_event(e, m);
  EXPECT_EQ(b.phase, Phase::kMove);
  EXPECT_EQ(b.buttons, kPenButtonSecondary);
  e = ev(TabletEventKind::kAxis, 10, 20);
  e.tool = Tool::kEraser;
  EXPECT_EQ(translate_tablet_event(e, m)->tool, Tool::kEraser);
}

TEST(PenInput, ClampsIntoLogRangesAndRefusesNonFiniteValues) {
  const TabletMapping m = TabletMapping::fit(100, 100, 500, 500);
  TabletToolEvent e = ev(TabletEventKind::kAxis, 10, 20, 1.5);
  e.tilt_x_deg = 120;
  e.tilt_y_deg = -95;
  const PenSample s = *translate_tablet_event(e, m);
  EXPECT_EQ(s.pressure, 1.0);
  EXPECT_EQ(s.tilt_x, 90.0);
  EXPECT_EQ(s.tilt_y, -90.0);
  e.x = std::nan("");
  EXPECT_FALSE(translate_tablet_event(e, m));
  TabletMapping bad = m;
  bad.area_width_mm = 0;
  EXPECT_FALSE(translate_tablet_event(ev(TabletEventKind::kAxis, 1, 1), bad));
}

TEST(PenInput, NormalizedPositionsUseTheWindowAndTranslationIsAffine) {
  TabletMapping m;
  m.window_x = 10;
  m.window_y = 20;
  m.window_width = 640;
  m.window_height = 480;
  TabletToolEvent e = ev(TabletEventKind::kAxis, 0.25, 0.5);
  e.position_in_mm = false;
  const PenSample s = *translate_tablet_event(e, m);
  EXPECT_DOUBLE_EQ(s.x, 10 + 160);
  EXPECT_DOUBLE_EQ(s.y, 20 + 240);
  // Metamorphic: shifting the tablet area and the event by the same mm leaves pixels unchanged;
  // shifting the window shifts pixels by the same amount.
  std::mt19937 g(5);
  for (int i = 0; i < 50; ++i) {
    const double x = static_cast<double>(g() % 1000) / 10.0, y = static_cast<double>(g() % 1000) / 10.0,
                 d = static_cast<double>(g() % 100) / 7.0;
    TabletMapping a = TabletMapping::fit(150, 90, 1280, 800), b = a;
    b.area_x_mm += d;
    b.area_y_mm -= d;
    b.window_x += 3;
    const PenSample pa = *translate_tablet_event(ev(TabletEventKind::kAxis, x, y), a);
    const PenSample pb = *translate_tablet_event(ev(TabletEventKind::kAxis, x + d, y - d), b);
    EXPECT_NEAR(pb.x - 3, pa.x, 1e-9);
    EXPECT_NEAR(pb.y, pa.y, 1e-9);
  }
}

TEST(PenInput, PointerFallbackIsAMouseWithFullPressure) {
  const PenSample hover = pointer_sample(1, 5, 6, false, false);
  EXPECT_EQ(hover.tool, Tool::kMouse);
  EXPECT_EQ(hover.phase, Phase::kMove);
  EXPECT_EQ(hover.pressure, 0.0);
  const PenSample down = pointer_sample(2, 5, 6, true, false);
  EXPECT_EQ(down.phase, Phase::kDown);
  EXPECT_EQ(down.pressure, 1.0);
  const PenSample drag = pointer_sample(3, 7, 8, true, true);
  EXPECT_EQ(drag.phase, Phase::kMove);
  EXPECT_EQ(drag.pressure, 1.0);
  EXPECT_EQ(drag.x, 7);
  EXPECT_EQ(drag.t, 3);
  const PenSample up = pointer_sample(4, 7, 8, false, true);
  EXPECT_EQ(up.phase, Phase::kUp);
  EXPECT_EQ(up.pressure, 0.0);
}

TEST(PenInput, LiveReaderOpensATabletOrSaysWhyNot) {
  auto r = LibinputTabletReader::open(TabletMapping::fit(150, 95, 1280, 800));
  if (r) {
    std::vector<PenSample> out;
    EXPECT_TRUE((*r)->poll(out));  // non-blocking: returns at once
    EXPECT_GE((*r)->fd(), 0);
    GTEST_SKIP() << "a tablet is attached: " << (*r)->device_name();
  }
  const std::string& why = r.message();
  const bool known = why.find("no permission for /dev/input") != std::string::npos ||
                     why.find("no tablet") != std::string::npos;
  EXPECT_TRUE(known) << why;
}

// === libinput record

std::string data(const char* name) { return std::string(PLANESKETCH_SOURCE_DIR) + "/tests/data/libinput/" + name; }

TEST(LibinputRecord, ParsesTheDeviceAndFrames) {
  auto rec = read_libinput_record(data("pen-stroke.yml"));
  ASSERT_TRUE(rec) << rec.message();
  ASSERT_EQ(rec->devices.size(), 1u);
  const EvdevRecordedDevice& d = rec->devices[0];
  EXPECT_EQ(d.node, "/dev/input/event7");
  EXPECT_EQ(d.name, "Hand-written Test Tablet Pen");
  ASSERT_EQ(d.absinfo.size(), 6u);
  EXPECT_EQ(d.absinfo.at(0).maximum, 15200);
  EXPECT_EQ(d.absinfo.at(0).resolution, 100);
  EXPECT_EQ(d.absinfo.at(26).minimum, -64);
  EXPECT_EQ(d.absinfo.at(26).resolution, 57);
  ASSERT_EQ(d.frames.size(), 12u);
  EXPECT_EQ(d.frames[0].size(), 8u);
  EXPECT_EQ(d.frames[0].front().code, 0);
  EXPECT_EQ(d.frames[0].front().value, 3040);
  EXPECT_EQ(d.frames[11].back().type, 0);  // SYN_REPORT ends every frame
  const auto size = tablet_size_mm(d);
  ASSERT_TRUE(size);
  EXPECT_DOUBLE_EQ(size->x(), 152);
  EXPECT_DOUBLE_EQ(size->y(), 95);
}

TEST(LibinputRecord, ReplaysThePenStrokeIntoSamples) {
  auto rec = read_libinput_record(data("pen-stroke.yml"));
  ASSERT_TRUE(rec) << rec.message();
  auto samples = pen_samples_from_recording(*rec, 1280, 800);
  ASSERT_TRUE(samples) << samples.message();
  const std::vector<Phase> want = {Phase::kProximityIn, Phase::kMove, Phase::kDown, Phase::kMove, Phase::kMove,
                                   Phase::kMove,        Phase::kMove, Phase::kMove, Phase::kMove, Phase::kMove,
                                   Phase::kMove,        Phase::kMove, Phase::kUp,   Phase::kMove, Phase::kProximityOut};
  ASSERT_EQ(samples->size(), want.size());
  const double px_per_unit = 1280.0 / 15200.0;  // the 152 x 95 mm tablet fills the 1280 x 800 window exactly
  struct Want {
    double t;
    int x, y, pressure;
    std::uint32_t buttons;
  };
  const Want w[] = {{0, 3040, 4750, 0, 0},     {5, 3100, 4760, 0, 0},     {10, 3150, 4770, 410, 0},
                    {15, 3300, 4800, 1024, 0}, {20, 3500, 4850, 2048, 0}, {25, 3700, 4900, 3072, 0},
                    {30, 3900, 4950, 2600, 0}, {40, 4100, 4950, 2600, 0}, {40, 4100, 4950, 2600, 1},
                    {45, 4300, 5000, 1500, 1}, {45, 4300, 5000, 1500, 0}, {50, 4350, 5000, 0, 0},
                    {50, 4350, 5000, 0, 0},    {55, 4400, 5000, 0, 0},    {60, 4400, 5000, 0, 0}};
  for (std::size_t i = 0; i < want.size(); ++i) {
    const PenSample& s = (*samples)[i];
    SCOPED_TRACE(i);
    EXPECT_EQ(s.phase, want[i]);
    EXPECT_DOUBLE_EQ(s.t, w[i].t);
    EXPECT_NEAR(s.x, w[i].x * px_per_unit, 1e-9);
    EXPECT_NEAR(s.y, w[i].y * px_per_unit, 1e-9);
    EXPECT_NEAR(s.pressure, w[i].pressure / 4095.0, 1e-12);
    EXPECT_EQ(s.buttons, w[i].buttons);
    EXPECT_EQ(s.tool, Tool::kPen);
  }
  // Tilt: 20 units at 57 units/radian.
  EXPECT_NEAR((*samples)[0].tilt_x, 20.0 / 57.0 * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR((*samples)[0].tilt_y, -10.0 / 57.0 * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR((*samples)[4].tilt_x, 22.0 / 57.0 * 180.0 / M_PI, 1e-9);
}

TEST(LibinputRecord, ManPageIndentationReadsTheSame) {
  // The man page indents device keys one level deeper than libinput record prints them.
  const std::string text =
      "version: 1\nndevices: 1\nlibinput:\n  version: 1.10.0\n"
      "system:\n  os: \"fedora:26\"\n  dmi: \"dmi:bvnLENOVO:bvr#2\" # a comment\n"
      "devices:\n  - node: /dev/input/event9\n    evdev:\n      # Name: Pen\n      name: Pen\n"
      "      id: [29, 1739, 0, 0]\n      codes:\n        0: [0, 1] # EV_SYN\n"
      "      absinfo:\n        0: [0, 1000, 0, 0, 10]\n        1: [0, 500, 0, 0, 10]\n"
      "        24: [0, 255, 0, 0, 0]\n      properties: [0, 2]\n"
      "    hid: [12, 23, 34, 45]\n    udev:\n      properties:\n      - ID_INPUT=1\n"
      "    events:\n      - evdev:\n        - [  0,      0,   1, 320,     1] # EV_KEY / BTN_TOOL_PEN\n"
      "        - [  0,      0,   3,   0,   500] # EV_ABS / ABS_X\n"
      "        - [  0,      0,   3,   1,   250]\n        - [  0,      0,   0,   0,     0]\n"
      "      - libinput:\n        - {time: 0.0, type: TABLET_TOOL_PROXIMITY}\n"
      "      - evdev:\n        - [  0,  11879,   3,   0,   600]\n        - [  0,  11879,   0,   0,     0]\n";
  auto rec = parse_libinput_record(text, "man.yml");
  ASSERT_TRUE(rec) << rec.message();
  ASSERT_EQ(rec->devices.size(), 1u);
  EXPECT_EQ(rec->devices[0].name, "Pen");
  ASSERT_EQ(rec->devices[0].frames.size(), 2u);
  auto samples = pen_samples_from_recording(*rec, 1000, 500);
  ASSERT_TRUE(samples) << samples.message();
  ASSERT_EQ(samples->size(), 2u);
  EXPECT_EQ((*samples)[0].phase, Phase::kProximityIn);
  EXPECT_NEAR((*samples)[0].x, 500, 1e-9);  // 100 x 50 mm tablet -> 1000 x 500 window
  EXPECT_NEAR((*samples)[0].y, 250, 1e-9);
  EXPECT_EQ((*samples)[1].phase, Phase::kMove);
  EXPECT_NEAR((*samples)[1].x, 600, 1e-9);
  EXPECT_NEAR((*samples)[1].t, 11.879, 1e-9);
}

TEST(LibinputRecord, MalformedFilesReportFileLine) {
  const std::string head = "version: 1\ndevices:\n- node: /dev/input/event1\n  evdev:\n    absinfo:\n      0: [0, 10, 0, 0, 1]\n      1: [0, 10, 0, 0, 1]\n  events:\n  - evdev:\n";
  struct Case {
    std::string text;
    int line;
    std::string needle;
  };
  const Case cases[] = {
      {"", 1, "empty recording"},
      {"ndevices: 1\n", 1, "missing 'version'"},
      {"version: 2\n", 1, "unsupported libinput record version 2"},
      {"version: x\n", 1, "version must be an integer"},
      {"version: 1\n", 1, "no devices"},
      {head + "    - [0, 0, 3, 0]\n", 10, "expected [sec, usec, type, code, value]"},
      {head + "    - [0, 0, 3, 0, 5\n", 10, "unterminated flow sequence"},
      {head + "    - [0, 0, 3, zero, 5]\n", 10, "'zero' is not an integer"},
      {head + "    - [0, 2000000, 3, 0, 5]\n", 10, "bad event time"},
      {head + "    - [0, 0, 3, 0, 99999999999]\n", 10, "out of range"},
      {"version: 1\ndevices:\n- node: x\n  evdev:\n    absinfo:\n      0: [10, 0, 0, 0, 1]\n", 6, "maximum is below minimum"},
      {"version: 1\ndevices:\n- node: x\n  evdev:\n    absinfo:\n      99999: [0, 1, 0, 0, 1]\n", 6, "not an ABS code"},
      {"version: 1\n\tdevices:\n", 2, "tab in indentation"},
      {"version: 1\njust some words\n", 2, "expected 'key: value'"},
  };
  for (const Case& c : cases) {
    auto r = parse_libinput_record(c.text, "rec.yml");
    ASSERT_FALSE(r) << c.text;
    const std::string prefix = "rec.yml:" + std::to_string(c.line) + ": ";
    EXPECT_EQ(r.message().rfind(prefix, 0), 0u) << r.message();
    EXPECT_NE(r.message().find(c.needle), std::string::npos) << r.message();
  }
  auto missing = read_libinput_record(data("absent.yml"));
  EXPECT_FALSE(missing);
  // A device without ABS_X/ABS_Y is not a tablet.
  auto keyboard = parse_libinput_record("version: 1\ndevices:\n- node: /dev/input/event2\n  events:\n", "kbd.yml");
  ASSERT_TRUE(keyboard) << keyboard.message();
  EXPECT_FALSE(pen_samples_from_recording(*keyboard, 100, 100));
}

TEST(LibinputRecord, MutatedRecordingsNeverCrash) {
  auto rec = read_libinput_record(data("pen-stroke.yml"));
  ASSERT_TRUE(rec);
  std::string base;
  {
    std::ifstream in(data("pen-stroke.yml"));
    std::ostringstream s;
    s << in.rdbuf();
    base = s.str();
  }
  std::mt19937 g(1234);
  const char alphabet[] = "-[]:, \n#\"0123456789ab\t{}";
  int parsed = 0;
  for (int i = 0; i < 1500; ++i) {
    std::string m = base;
    const int edits = 1 + static_cast<int>(g() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = g() % m.size();
      switch (g() % 3) {
        case 0: m[at] = alphabet[g() % (sizeof(alphabet) - 1)]; break;
        case 1: m.erase(at, 1 + g() % 8); break;
        default: m.insert(at, 1, alphabet[g() % (sizeof(alphabet) - 1)]); break;
      }
      if (m.empty()) m.push_back('x');
    }
    auto r = parse_libinput_record(m, "fuzz.yml");
    if (r) {
      ++parsed;
      auto s = pen_samples_from_recording(*r, 1280, 800);
      if (s) {
        for (const PenSample& p : *s) EXPECT_TRUE(p.pressure >= 0 && p.pressure <= 1);
      }
    } else {
      EXPECT_EQ(r.message().rfind("fuzz.yml:", 0), 0u) << r.message();
    }
  }
  EXPECT_GT(parsed, 0);
}

}  // namespace
}  // namespace ps
