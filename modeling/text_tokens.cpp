#include "modeling/text_tokens.h"

#include <cctype>
#include <charconv>
#include <cstdlib>

namespace ps {

bool parse_double(std::string_view t, double& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  if (r.ec == std::errc::result_out_of_range && r.ptr == t.data() + t.size()) {
    // Valid syntax, magnitude beyond double: strtod gives +-HUGE_VAL or a (sub)normal/zero.
    const std::string copy(t);
    out = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

bool parse_int(std::string_view t, long long& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  split(line, out);
  return out;
}

void split(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t b = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > b) out.push_back(line.substr(b, i - b));
  }
}

std::string show(std::string_view t) {
  std::string out;
  for (char c : t.substr(0, 20)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (t.size() > 20) out += "...";
  return "'" + out + "'";
}

}  // namespace ps
