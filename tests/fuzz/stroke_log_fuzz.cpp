// libFuzzer entry for the stroke-log reader (built with clang -fsanitize=fuzzer by a later
// step; tests/input_fuzz_test.cpp runs it over seeds and mutations in every build).
//
// Besides "never crash", it checks the reader's contract: a failure names "fuzz:<line>: ...",
// and a log that reads writes back and reads again to the same text (write . read is a
// fixed point), and can be replayed and grouped into strokes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"

namespace {

class CountingSink : public ps::EventSink {
 public:
  std::size_t n = 0;
  void on_header(const ps::LogHeader&) override { ++n; }
  void on_pen_sample(const ps::PenSample&) override { ++n; }
  void on_action(const ps::TimedEvent&) override { ++n; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  auto log = ps::parse_stroke_log(text, "fuzz", &warnings);
  if (!log) {
    if (log.message().rfind("fuzz:", 0) != 0) __builtin_trap();
    return 0;
  }
  for (const std::string& w : warnings)
    if (w.rfind("fuzz:", 0) != 0) __builtin_trap();
  auto written = ps::to_jsonl(*log);
  if (!written) __builtin_trap();
  auto again = ps::parse_stroke_log(*written, "fuzz-again");
  if (!again || again->events.size() != log->events.size()) __builtin_trap();
  auto rewritten = ps::to_jsonl(*again);
  if (!rewritten || *rewritten != *written) __builtin_trap();
  CountingSink sink;
  ps::replay(*log, sink);
  if (sink.n != log->events.size() + 1) __builtin_trap();
  (void)ps::group_strokes(*log);
  return 0;
}
