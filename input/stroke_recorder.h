#pragma once
// Records a stroke log while the app runs (docs/stroke-log.md).
//
// The header is written when the file is opened; every event is appended as one line with a
// single write(2), so a crash leaves at most a truncated last line, which the reader drops
// with a warning. On pen-up (a completed stroke) and on every UI action the file is also
// fsync'ed, so a completed stroke survives even a power cut. Events are checked before they
// are written (finite values, pressure range, time order); a refused event leaves the file
// unchanged and returns the reason. While open, the file holds an exclusive flock(2), so crash
// recovery can tell a journal of a live session from one whose app died.
#include <string>

#include "input/stroke_log.h"
#include "modeling/status.h"

namespace ps {

class StrokeRecorder {
 public:
  enum class OpenMode { kCreateNew, kOverwrite };

  // Opens `path` and writes the header. Refuses an existing file unless kOverwrite.
  static Result<StrokeRecorder> open(const std::string& path, const LogHeader& header,
                                     OpenMode mode = OpenMode::kCreateNew);

  StrokeRecorder(StrokeRecorder&& other) noexcept;
  StrokeRecorder& operator=(StrokeRecorder&& other) noexcept;
  StrokeRecorder(const StrokeRecorder&) = delete;
  StrokeRecorder& operator=(const StrokeRecorder&) = delete;
  ~StrokeRecorder();

  Status record(const PenSample& sample);     // time = sample.t
  Status record(double t, const Event& event);  // any event; a PenSample needs t == sample.t
  // fsync now (the recorder also does this itself on pen-up and actions).
  Status sync();
  // Syncs and closes; further records fail. The destructor closes too (ignoring errors).
  // A log closed this way has no end marker: crash recovery treats it as unfinished.
  Status close();
  // Clean end of the session: appends the end marker {"t":t,"type":"end"} (t >= the last
  // event's time), syncs and closes. Only a finished journal is skipped by crash recovery.
  Status finish(double t);
  Status finish() { return finish(last_t_); }

  const std::string& path() const { return path_; }
  bool is_open() const { return fd_ >= 0; }
  std::size_t events_written() const { return count_; }
  double last_time() const { return last_t_; }

 private:
  StrokeRecorder(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  Status write_line(const std::string& line);

  int fd_ = -1;
  std::string path_;
  double last_t_ = 0.0;
  std::size_t count_ = 0;
};

}  // namespace ps
