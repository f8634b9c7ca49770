// Stroke-log recorder: append-only JSON Lines with fsync at stroke and action boundaries.
#include "input/stroke_recorder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "input/stroke_log_io.h"

namespace ps {

Result<StrokeRecorder> StrokeRecorder::open(const std::string& path, const LogHeader& header,
                                            OpenMode mode) {
  auto head = format_header(header);
  if (!head) return Result<StrokeRecorder>::error(path + ": header: " + head.message());
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == OpenMode::kCreateNew ? O_EXCL : O_TRUNC);
  const int fd = ::open(path.c_str(), flags, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      return Result<StrokeRecorder>::error(path + ": exists (refusing to overwrite a stroke log)");
    return Result<StrokeRecorder>::error(path + ": cannot open for writing: " + std::strerror(errno));
  }
  // An exclusive advisory lock for as long as the recorder is open (the kernel drops it when
  // the process dies, even by SIGKILL): crash recovery skips journals still locked by a live
  // session. Best effort; a file system without flock still records.
  (void)::flock(fd, LOCK_EX | LOCK_NB);
  StrokeRecorder rec(fd, path);
  if (auto s = rec.write_line(*head); !s) return s;
  if (auto s = rec.sync(); !s) return s;
  return rec;
}

StrokeRecorder::StrokeRecorder(StrokeRecorder&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)), path_(std::move(o.path_)), last_t_(o.last_t_), count_(o.count_) {}

StrokeRecorder& StrokeRecorder::operator=(StrokeRecorder&& o) noexcept {
  if (this != &o) {
    (void)close();
    fd_ = std::exchange(o.fd_, -1);
    path_ = std::move(o.path_);
    last_t_ = o.last_t_;
    count_ = o.count_;
  }
  return *this;
}

StrokeRecorder::~StrokeRecorder() { (void)close(); }

Status StrokeRecorder::write_line(const std::string& line) {
  if (fd_ < 0) return Status::error(path_ + ": recorder is closed");
  std::string buf = line;
  buf += '\n';
  // One write per line: a crash can only truncate the last line.
  std::size_t done = 0;
  while (done < buf.size()) {
    const ssize_t n = ::write(fd_, buf.data() + done, buf.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Status::error(path_ + ": write failed: " + std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
  return Status::ok();
}

Status StrokeRecorder::record(const PenSample& sample) { return record(sample.t, Event{sample}); }

Status StrokeRecorder::record(double t, const Event& event) {
  if (fd_ < 0) return Status::error(path_ + ": recorder is closed");
  TimedEvent te{t, 0, event};
  auto line = format_event(te);
  if (!line) return Status::error(path_ + ": event refused: " + line.message());
  if (t < last_t_)
    return Status::error(path_ + ": event refused: time " + std::to_string(t) + " ms is before the previous event (" +
                         std::to_string(last_t_) + " ms)");
  if (auto s = write_line(*line); !s) return s;
  last_t_ = t;
  ++count_;
  const auto* pen = std::get_if<PenSample>(&event);
  if (!pen || pen->phase == Phase::kUp) return sync();
  return Status::ok();
}

Status StrokeRecorder::finish(double t) {
  if (fd_ < 0) return Status::error(path_ + ": recorder is closed");
  if (t < last_t_)
    return Status::error(path_ + ": end marker refused: time " + std::to_string(t) +
                         " ms is before the previous event (" + std::to_string(last_t_) + " ms)");
  auto line = format_end(t);
  if (!line) return Status::error(path_ + ": end marker refused: " + line.message());
  if (auto s = write_line(*line); !s) return s;
  last_t_ = t;
  return close();
}

Status StrokeRecorder::sync() {
  if (fd_ < 0) return Status::error(path_ + ": recorder is closed");
  if (::fsync(fd_) != 0) return Status::error(path_ + ": fsync failed: " + std::strerror(errno));
  return Status::ok();
}

Status StrokeRecorder::close() {
  if (fd_ < 0) return Status::ok();
  Status s = sync();
  if (::close(fd_) != 0 && s) s = Status::error(path_ + ": close failed: " + std::strerror(errno));
  fd_ = -1;
  return s;
}

}  // namespace ps
