#pragma once
// Reading and writing stroke logs (JSON Lines, docs/stroke-log.md).
//
// The reader never throws and never crashes on any input: a malformed line gives an error
// "name:line: message" and no log. Unknown event types are skipped with a warning
// "name:line: ...", so logs of later format revisions stay readable. A last line without its
// newline that does not parse (a crash while writing) is dropped with a warning, so a
// session can be recovered after a crash.
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "input/stroke_log.h"
#include "modeling/status.h"

namespace ps {

// === Reading

// Parses a whole log held in memory; `name` is used in messages (a path, or "<string>").
// Warnings (skipped lines) are appended to *warnings when given.
Result<StrokeLog> parse_stroke_log(std::string_view text, const std::string& name,
                                   std::vector<std::string>* warnings = nullptr);
Result<StrokeLog> read_stroke_log(std::istream& in, const std::string& name,
                                  std::vector<std::string>* warnings = nullptr);
Result<StrokeLog> read_stroke_log(const std::string& path,
                                  std::vector<std::string>* warnings = nullptr);

// === Writing

// One line each, without the trailing newline. Values are checked first (finite numbers,
// pressure in [0, 1], a valid camera ...); doubles are written with 17 significant digits so
// reading gives back the same bits.
Result<std::string> format_header(const LogHeader& header);
Result<std::string> format_event(const TimedEvent& event);
// The session-end marker line {"t":t,"type":"end"} (docs/stroke-log.md, "Session end").
Result<std::string> format_end(double t);
// The whole log as JSON Lines (every line ends with '\n'); checks time order too.
Result<std::string> to_jsonl(const StrokeLog& log);
// Writes to `path`; refuses an existing file unless `overwrite`. Writes a temporary file and
// renames it, so a failed write leaves no partial file.
Status write_stroke_log(const std::string& path, const StrokeLog& log, bool overwrite = false);

// === Checks shared by reader, writer and recorder (messages name the offending field)

Status check_camera(const Camera& camera);
Status check_header(const LogHeader& header);
Status check_event(const TimedEvent& event);

}  // namespace ps
