#include "app/journal.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/commands.h"

namespace ps::app {

namespace fs = std::filesystem;

fs::path journal_dir() {
  const char* state = std::getenv("XDG_STATE_HOME");
  if (state && *state) return fs::path(state) / "planesketch";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : "/tmp") / ".local/state/planesketch";
}

std::string new_journal_path(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  const auto secs = std::chrono::duration_cast<std::chrono::seconds>(now).count();
  return (dir / ("journal-" + std::to_string(secs) + "-" + std::to_string(::getpid()) + ".jsonl")).string();
}

bool journal_finished(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) return false;
  const std::streamoff take = std::min<std::streamoff>(size, 4096);
  in.seekg(size - take);
  std::string tail(static_cast<std::size_t>(take), '\0');
  in.read(tail.data(), take);
  if (!in) return false;
  // The last non-blank line.
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r' || tail.back() == ' ' || tail.back() == '\t'))
    tail.pop_back();
  const auto nl = tail.rfind('\n');
  const std::string last = nl == std::string::npos ? tail : tail.substr(nl + 1);
  const auto j = nlohmann::json::parse(last, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return false;
  const auto it = j.find("type");
  return it != j.end() && it->is_string() && it->get<std::string>() == "end";
}

bool journal_in_use(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // also drops the shared lock if we got it
  return busy;
}

std::optional<JournalInfo> newest_unfinished_journal(const fs::path& dir) {
  for (auto& j : list_journals(dir))
    if (!j.finished && !j.in_use) return j;
  return std::nullopt;
}

std::vector<JournalInfo> list_journals(const fs::path& dir) {
  std::vector<JournalInfo> out;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    if (name.rfind("journal-", 0) != 0 || p.extension() != ".jsonl") continue;
    std::error_code e2;
    if (!it->is_regular_file(e2)) continue;
    JournalInfo info;
    info.path = p;
    info.mtime = it->last_write_time(e2);
    info.finished = journal_finished(p);
    info.in_use = !info.finished && journal_in_use(p);
    out.push_back(std::move(info));
  }
  std::sort(out.begin(), out.end(), [](const JournalInfo& a, const JournalInfo& b) {
    if (a.mtime != b.mtime) return a.mtime > b.mtime;
    return a.path.filename() > b.path.filename();
  });
  return out;
}

void JournalingSink::on_pen_sample(const PenSample& sample) {
  if (auto st = rec_.record(sample); !st) throw CommandFailed("cannot write the journal: " + st.message());
  next_.on_pen_sample(sample);
}

void JournalingSink::on_action(const TimedEvent& event) {
  if (auto st = rec_.record(event.t, event.event); !st)
    throw CommandFailed("cannot write the journal: " + st.message());
  next_.on_action(event);
}

Result<std::string> file_digest(const std::string& path) {
  using R = Result<std::string>;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return R::error(path + ": is a directory, not a file");
  std::ifstream f(path, std::ios::binary);
  if (!f) return R::error(path + ": cannot be read");
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  char buf[1 << 16];
  while (f) {
    f.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < f.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[i]);
      h *= 1099511628211ull;
    }
  }
  if (f.bad()) return R::error(path + ": read error");
  static const char* const hex = "0123456789abcdef";
  std::string out(16, '0');
  for (int k = 15; k >= 0; --k, h >>= 4) out[static_cast<std::size_t>(k)] = hex[h & 0xf];
  return out;
}

Result<OpenFile> open_file_event(const std::string& kind, const std::string& path) {
  auto digest = file_digest(path);
  if (!digest) return digest.status();
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec);
  return OpenFile{kind, ec ? path : abs.lexically_normal().string(), *digest};
}

}  // namespace ps::app
