#include "modeling/off_reader.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "modeling/text_tokens.h"

namespace ps {
namespace {

// === Tokens (modeling/text_tokens.h)

// A non-negative integer (written as an integer or an integral decimal, "3" or "3.0") no larger
// than `limit`. Returns false, and leaves the reason in `why`, otherwise.
bool parse_count(std::string_view tok, long long limit, long long& v, std::string& why) {
  double d = 0;
  if (!parse_double(tok, d)) {
    why = show(tok) + " is not a number";
    return false;
  }
  if (!std::isfinite(d) || d != std::floor(d)) {
    why = show(tok) + " is not an integer";
    return false;
  }
  if (d < 0) {
    why = show(tok) + " is negative";
    return false;
  }
  if (d > static_cast<double>(limit)) {
    why = show(tok) + " is larger than " + std::to_string(limit);
    return false;
  }
  v = static_cast<long long>(d);
  return true;
}

// The content line by line, comments ('#' to the end of the line) removed, blank lines skipped.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  // The next line with at least one token; false at the end of the text.
  bool next() {
    while (pos_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      split(line, tokens_);
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::string where() const { return "line " + std::to_string(number_); }
  // Byte offset just past the current line.
  std::size_t offset() const { return std::min(pos_, text_.size()); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  long long number_ = 0;
  std::vector<std::string_view> tokens_;
};

// === Binary body (after the "OFF BINARY" line)

class BigEndian {
 public:
  BigEndian(std::string_view bytes, std::size_t pos) : bytes_(bytes), pos_(pos) {}
  bool int32(std::int32_t& v) {
    std::uint32_t u = 0;
    if (!word(u)) return false;
    std::memcpy(&v, &u, 4);
    return true;
  }
  bool float32(float& v) {
    std::uint32_t u = 0;
    if (!word(u)) return false;
    std::memcpy(&v, &u, 4);
    return true;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::string where() const { return "byte " + std::to_string(pos_); }

 private:
  bool word(std::uint32_t& u) {
    if (remaining() < 4) return false;
    u = 0;
    for (int k = 0; k < 4; ++k) u = (u << 8) | static_cast<unsigned char>(bytes_[pos_ + static_cast<std::size_t>(k)]);
    pos_ += 4;
    return true;
  }
  std::string_view bytes_;
  std::size_t pos_;
};

Result<PolygonSoup> parse_binary(std::string_view content, std::size_t start) {
  BigEndian in(content, start);
  std::int32_t nv = 0, nf = 0, ne = 0;
  if (!in.int32(nv) || !in.int32(nf) || !in.int32(ne))
    return Result<PolygonSoup>::error("binary OFF ends inside its counts");
  if (nv < 0 || nf < 0)
    return Result<PolygonSoup>::error("binary OFF declares " + std::to_string(nv) + " vertices and " +
                                      std::to_string(nf) + " faces (negative)");
  // Every vertex takes 12 bytes and every face at least 20: refuse counts the file cannot hold
  // before reserving memory for them.
  if (static_cast<std::size_t>(nv) * 12 + static_cast<std::size_t>(nf) * 20 > in.remaining())
    return Result<PolygonSoup>::error("binary OFF declares " + std::to_string(nv) + " vertices and " +
                                      std::to_string(nf) + " faces, more than its " +
                                      std::to_string(in.remaining()) + " bytes of data can hold");
  PolygonSoup soup;
  soup.points.resize(static_cast<std::size_t>(nv));
  for (auto& p : soup.points)
    for (double& c : p) {
      float f = 0;
      in.float32(f);  // sizes checked above
      c = static_cast<double>(f);
    }
  soup.polygons.resize(static_cast<std::size_t>(nf));
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    std::int32_t n = 0;
    if (!in.int32(n)) return Result<PolygonSoup>::error("binary OFF ends at face " + std::to_string(f) + " of " + std::to_string(nf));
    if (n < 3 || static_cast<std::size_t>(n) * 4 > in.remaining())
      return Result<PolygonSoup>::error("binary OFF face " + std::to_string(f) + " declares " + std::to_string(n) +
                                        " corners (" + in.where() + ")");
    auto& poly = soup.polygons[f];
    poly.resize(static_cast<std::size_t>(n));
    for (auto& idx : poly) {
      std::int32_t i = 0;
      in.int32(i);
      if (i < 0 || i >= nv)
        return Result<PolygonSoup>::error("binary OFF face " + std::to_string(f) + " references vertex " +
                                          std::to_string(i) + ", out of range (" + std::to_string(nv) + " vertices)");
      idx = static_cast<std::size_t>(i);
    }
    std::int32_t colours = 0;
    if (!in.int32(colours) || colours < 0 || colours > 4 || static_cast<std::size_t>(colours) * 4 > in.remaining())
      return Result<PolygonSoup>::error("binary OFF face " + std::to_string(f) + " has a malformed colour count (" +
                                        in.where() + ")");
    for (std::int32_t k = 0; k < colours; ++k) {
      float ignored = 0;
      in.float32(ignored);
    }
  }
  return soup;
}

}  // namespace

// === ASCII (and the header of binary files)

Result<PolygonSoup> parse_off(const std::string& content) {
  using R = Result<PolygonSoup>;
  const auto size = static_cast<long long>(content.size());
  Lines lines(content);
  if (!lines.next()) return R::error("no OFF header (the file holds only blanks or comments)");
  const std::string_view keyword = lines.tokens()[0];
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    return R::error(lines.where() + ": expected the OFF keyword, found " + show(keyword));
  const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  bool homogeneous = false;
  for (char c : prefix) {
    if (c == 'n') return R::error("nOFF (vertices of a dimension given in the file) is not supported");
    if (c == '4') homogeneous = true;
    else if (c != 'S' && c != 'T' && c != 'C' && c != 'N')
      return R::error(lines.where() + ": unknown OFF keyword " + show(keyword));
  }
  std::vector<std::string_view> counts(lines.tokens().begin() + 1, lines.tokens().end());
  if (!counts.empty() && counts[0] == "BINARY") {
    if (!prefix.empty())
      return R::error("binary " + std::string(keyword) + " is not supported (binary files only as plain OFF)");
    return parse_binary(content, lines.offset());
  }
  if (counts.empty()) {
    if (!lines.next()) return R::error("the file ends before the vertex and face counts");
    counts = lines.tokens();
  }
  if (counts.size() < 2) return R::error(lines.where() + ": expected the vertex and face counts");
  long long nv = 0, nf = 0;
  std::string why;
  if (!parse_count(counts[0], size, nv, why)) return R::error(lines.where() + ": vertex count " + why);
  if (!parse_count(counts[1], size, nf, why)) return R::error(lines.where() + ": face count " + why);

  PolygonSoup soup;
  soup.points.reserve(static_cast<std::size_t>(nv));
  const std::size_t needed = homogeneous ? 4 : 3;
  for (long long i = 0; i < nv; ++i) {
    if (!lines.next())
      return R::error("the file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    double c[4] = {0, 0, 0, 1};
    const auto& t = lines.tokens();
    for (std::size_t k = 0; k < needed; ++k)
      if (k >= t.size() || !parse_double(t[k], c[k]))
        return R::error(lines.where() + ": vertex " + std::to_string(i) + " needs " + std::to_string(needed) +
                        " coordinates" + (k < t.size() ? ", found " + show(t[k]) : ""));
    if (homogeneous) {
      if (c[3] == 0) return R::error(lines.where() + ": vertex " + std::to_string(i) + " has w = 0");
      for (int k = 0; k < 3; ++k) c[k] /= c[3];
    }
    soup.points.push_back({c[0], c[1], c[2]});
  }
  soup.polygons.reserve(static_cast<std::size_t>(nf));
  for (long long f = 0; f < nf; ++f) {
    if (!lines.next())
      return R::error("the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const auto& t = lines.tokens();
    const std::string face = lines.where() + ": face " + std::to_string(f);
    long long n = 0;
    if (!parse_count(t[0], size, n, why)) return R::error(face + ": corner count " + why);
    if (n < 3) return R::error(face + " has " + std::to_string(n) + " corners (at least 3 needed)");
    if (static_cast<long long>(t.size()) < n + 1)
      return R::error(face + " declares " + std::to_string(n) + " corners but lists " + std::to_string(t.size() - 1) + " numbers");
    std::vector<std::size_t> poly(static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < poly.size(); ++k) {
      long long idx = 0;
      if (!parse_count(t[k + 1], nv - 1, idx, why))
        return R::error(face + ": vertex index " + why + (nv == 0 ? " (the file has no vertices)" : " (0-based, " + std::to_string(nv) + " vertices)"));
      poly[k] = static_cast<std::size_t>(idx);
    }
    soup.polygons.push_back(std::move(poly));
  }
  return soup;
}

}  // namespace ps
