// Runs the stroke-log fuzz entry (tests/fuzz/stroke_log_fuzz.cpp) over seed logs and
// deterministic mutations, so the reader's robustness is exercised in every build, ASan included.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "fuzz/stroke_log_fuzz.cpp"  // NOLINT: the fuzz entry itself is under test

namespace {

int run(const std::string& s) {
  return LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

std::vector<std::string> seeds() {
  std::vector<std::string> out;
  // The head of the committed demo log: header, actions and real pen lines.
  std::ifstream in(std::string(PLANESKETCH_SOURCE_DIR) + "/assets/logs/demo.jsonl");
  std::string line, head;
  for (int i = 0; i < 40 && std::getline(in, line); ++i) head += line + "\n";
  if (!head.empty()) out.push_back(head);
  ps::StrokeLog log;
  log.events.push_back({0, 0, ps::SetToolMode{"sketch"}});
  log.events.push_back({1, 0, ps::TranslatePlane{1, -0.5}});
  log.events.push_back({2, 0, ps::CameraChange{ps::Camera{}}});
  ps::PenSample s;
  s.t = 3;
  s.phase = ps::Phase::kDown;
  s.pressure = 0.5;
  s.buttons = 1;
  log.events.push_back({3, 0, s});
  log.events.push_back({4, 0, ps::SetParameter{"lambda", 0.5}});
  log.events.push_back({5, 0, ps::DeleteSection{2}});
  log.events.push_back({6, 0, ps::Save{"x.obj"}});
  log.events.push_back({7, 0, ps::Undo{}});
  log.events.push_back({8, 0, ps::Redo{}});
  out.push_back(*ps::to_jsonl(log));
  out.push_back(out.back() + "{\"t\":9,\"type\":\"future_event\",\"k\":[1,2]}\n{\"t\":10,\"type\":\"pen\",\"x\":1");
  out.push_back("");
  out.push_back("{}\n");
  // Inputs the fuzzer once crashed on (kept in its corpus).
  for (const char* name : {"regression_empty_type.jsonl"}) {
    std::ifstream f(std::string(PLANESKETCH_SOURCE_DIR) + "/tests/fuzz/corpus/stroke_log/" + name, std::ios::binary);
    std::ostringstream text;
    text << f.rdbuf();
    out.push_back(text.str());
  }
  return out;
}

TEST(StrokeLogFuzz, SeedsPass) {
  for (const std::string& s : seeds()) EXPECT_EQ(run(s), 0);
}

TEST(StrokeLogFuzz, MutationsNeverBreakTheReadersContract) {
  std::mt19937 g(20261122);
  const std::string tokens[] = {"{", "}", "[", "]", ",", ":", "\"", "\n", "\\", "1e999", "-0", "null",
                                "true", "\"pen\"", "\"t\"", "0.5", "\xff", "\"phase\":\"up\"", "NaN", "   "};
  const auto base = seeds();
  int accepted = 0, runs = 0;
  for (const std::string& seed : base) {
    if (seed.empty()) continue;
    for (int i = 0; i < 600; ++i) {
      std::string m = seed;
      const int edits = 1 + static_cast<int>(g() % 3);
      for (int k = 0; k < edits && !m.empty(); ++k) {
        const std::size_t at = g() % m.size();
        switch (g() % 5) {
          case 0: m[at] = static_cast<char>(m[at] ^ (1 << (g() % 8))); break;
          case 1: m.erase(at, 1 + g() % 12); break;
          case 2: m.insert(at, tokens[g() % (sizeof(tokens) / sizeof(tokens[0]))]); break;
          case 3: m.resize(at); break;  // crash mid-write
          default: {                    // duplicate a line elsewhere
            const std::size_t a = m.rfind('\n', at), b = m.find('\n', at);
            if (a != std::string::npos && b != std::string::npos) m.insert(g() % m.size(), m.substr(a + 1, b - a));
          }
        }
      }
      EXPECT_EQ(run(m), 0);
      ++runs;
      std::vector<std::string> w;
      accepted += ps::parse_stroke_log(m, "fuzz", &w) ? 1 : 0;
    }
  }
  EXPECT_GT(runs, 1000);
  EXPECT_GT(accepted, 0);  // some mutations stay valid, so the round-trip checks ran
}

}  // namespace
