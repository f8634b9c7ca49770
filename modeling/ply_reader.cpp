#include "modeling/ply_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

#include "modeling/text_tokens.h"

namespace ps {
namespace {

// === Header

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

bool scalar_type(std::string_view name, Scalar& t) {
  static const struct {
    const char* a;
    const char* b;
    Scalar t;
  } kTypes[] = {{"char", "int8", Scalar::i8},    {"uchar", "uint8", Scalar::u8},   {"short", "int16", Scalar::i16},
                {"ushort", "uint16", Scalar::u16}, {"int", "int32", Scalar::i32},  {"uint", "uint32", Scalar::u32},
                {"float", "float32", Scalar::f32}, {"double", "float64", Scalar::f64}};
  for (const auto& k : kTypes)
    if (name == k.a || name == k.b) {
      t = k.t;
      return true;
    }
  return false;
}

std::size_t byte_size(Scalar t) {
  switch (t) {
    case Scalar::i8:
    case Scalar::u8: return 1;
    case Scalar::i16:
    case Scalar::u16: return 2;
    case Scalar::i32:
    case Scalar::u32:
    case Scalar::f32: return 4;
    case Scalar::f64: return 8;
  }
  return 1;
}

bool is_integer_type(Scalar t) { return t != Scalar::f32 && t != Scalar::f64; }

struct Property {
  std::string name;
  bool list = false;
  Scalar count_type = Scalar::u8;
  Scalar type = Scalar::f32;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

// A name from the header, cut at 40 characters, for messages (show() quotes a token instead).
std::string cut(std::string_view s) { return std::string(s.substr(0, 40)); }

// A value as it was most likely written: integers without a decimal point.
std::string show_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// === Body readers: one number of a given type at a time

class Body {
 public:
  virtual ~Body() = default;
  // The next value, converted to double; false at the end of the data or on a malformed token.
  virtual bool number(Scalar t, double& v) = 0;
  // Whether `count` more values of type t can still be present (bounds every allocation).
  virtual bool can_hold(double count, Scalar t) const = 0;
  virtual std::string where() const = 0;
};

class AsciiBody final : public Body {
 public:
  AsciiBody(std::string_view text, std::size_t pos) : text_(text), pos_(pos) {}
  bool number(Scalar t, double& v) override {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    if (pos_ == start) return false;
    const std::string_view tok = text_.substr(start, pos_ - start);
    if (!parse_double(tok, v)) {
      bad_ = show(tok);
      return false;
    }
    // A float property holds what a float can, as in a binary file (and CGAL's reader); beyond
    // float's range it is infinite (read_mesh then names the vertex).
    if (t == Scalar::f32 && std::isfinite(v))
      v = std::fabs(v) <= static_cast<double>(std::numeric_limits<float>::max())
              ? static_cast<double>(static_cast<float>(v))
              : std::copysign(std::numeric_limits<double>::infinity(), v);
    return true;
  }
  // Every value takes at least two characters (a digit and a separator), bar the last.
  bool can_hold(double count, Scalar) const override {
    return count <= static_cast<double>(text_.size() - std::min(pos_, text_.size())) / 2.0 + 1.0;
  }
  std::string where() const override {
    return "body line " + std::to_string(line_) + (bad_.empty() ? "" : " (" + bad_ + " is not a number)");
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }
  std::string_view text_;
  std::size_t pos_;
  long long line_ = 1;
  std::string bad_;
};

class BinaryBody final : public Body {
 public:
  BinaryBody(std::string_view bytes, std::size_t pos, bool big_endian) : bytes_(bytes), pos_(pos), big_(big_endian) {}
  bool number(Scalar t, double& v) override {
    const std::size_t n = byte_size(t);
    if (bytes_.size() - pos_ < n) return false;
    unsigned char b[8];
    for (std::size_t k = 0; k < n; ++k)
      b[k] = static_cast<unsigned char>(bytes_[pos_ + (big_ ? n - 1 - k : k)]);  // to little-endian order
    pos_ += n;
    std::uint64_t u = 0;
    for (std::size_t k = n; k-- > 0;) u = (u << 8) | b[k];
    switch (t) {
      case Scalar::i8: v = static_cast<std::int8_t>(static_cast<std::uint8_t>(u)); break;
      case Scalar::u8: v = static_cast<double>(u); break;
      case Scalar::i16: v = static_cast<std::int16_t>(static_cast<std::uint16_t>(u)); break;
      case Scalar::u16: v = static_cast<double>(u); break;
      case Scalar::i32: v = static_cast<std::int32_t>(static_cast<std::uint32_t>(u)); break;
      case Scalar::u32: v = static_cast<double>(u); break;
      case Scalar::f32: {
        const auto w = static_cast<std::uint32_t>(u);
        float f = 0;
        std::memcpy(&f, &w, 4);
        v = static_cast<double>(f);
        break;
      }
      case Scalar::f64: std::memcpy(&v, &u, 8); break;
    }
    return true;
  }
  bool can_hold(double count, Scalar t) const override {
    return count * static_cast<double>(byte_size(t)) <= static_cast<double>(bytes_.size() - pos_);
  }
  std::string where() const override { return "byte " + std::to_string(pos_); }

 private:
  std::string_view bytes_;
  std::size_t pos_;
  bool big_;
};

bool is_index(double v) { return v >= 0 && v == std::floor(v) && v < 9007199254740992.0; }

}  // namespace

Result<PolygonSoup> parse_ply(const std::string& content) {
  using R = Result<PolygonSoup>;
  const std::string_view text(content);
  // --- header, line by line up to end_header
  std::size_t pos = 0;
  long long line_no = 0;
  auto next_line = [&](std::string_view& line) {
    if (pos >= text.size()) return false;
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    line = text.substr(pos, end - pos);
    pos = std::min(end + 1, text.size());
    ++line_no;
    return true;
  };
  std::string_view line;
  if (!next_line(line) || split(line) != std::vector<std::string_view>{"ply"})
    return R::error("not a PLY file (the first line is not 'ply')");
  enum class Format { none, ascii, little, big } format = Format::none;
  std::vector<Element> elements;
  bool ended = false;
  while (!ended && next_line(line)) {
    const auto w = split(line);
    const std::string at = "header line " + std::to_string(line_no);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      ended = true;
    } else if (w[0] == "format") {
      if (w.size() < 2) return R::error(at + ": format line without a format");
      if (w[1] == "ascii") format = Format::ascii;
      else if (w[1] == "binary_little_endian") format = Format::little;
      else if (w[1] == "binary_big_endian") format = Format::big;
      else return R::error(at + ": unknown format " + show(w[1]));
    } else if (w[0] == "element") {
      if (w.size() != 3) return R::error(at + ": expected 'element <name> <count>'");
      long long count = -1;
      if (!parse_int(w[2], count) || count < 0)
        return R::error(at + ": element " + cut(w[1]) + " has count " + show(w[2]) + ", not a non-negative integer");
      // No element can have more items than the file has bytes.
      if (count > static_cast<long long>(text.size()))
        return R::error(at + ": element " + cut(w[1]) + " declares " + cut(w[2]) + " items, more than the file's " +
                        std::to_string(text.size()) + " bytes can hold");
      elements.push_back(Element{std::string(w[1]), count, {}});
    } else if (w[0] == "property") {
      if (elements.empty()) return R::error(at + ": a property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        p.list = true;
        if (!scalar_type(w[2], p.count_type) || !scalar_type(w[3], p.type))
          return R::error(at + ": unknown type in 'property list " + cut(w[2]) + " " + cut(w[3]) + "'");
        if (!is_integer_type(p.count_type)) return R::error(at + ": a list count of type " + cut(w[2]) + ", not an integer type");
        p.name = std::string(w[4]);
      } else if (w.size() == 3) {
        if (!scalar_type(w[1], p.type)) return R::error(at + ": unknown property type " + show(w[1]));
        p.name = std::string(w[2]);
      } else {
        return R::error(at + ": expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      elements.back().properties.push_back(std::move(p));
    } else {
      return R::error(at + ": unknown header keyword " + show(w[0]));
    }
  }
  if (!ended) return R::error("the header has no end_header line");
  if (format == Format::none) return R::error("the header has no format line");

  // --- which properties hold what
  PolygonSoup soup;
  const Element* vertex_element = nullptr;
  for (const auto& e : elements) {
    const bool is_vertex = e.name == "vertex" || e.name == "vertices";
    const bool is_face = e.name == "face" || e.name == "faces";
    if (is_vertex && vertex_element) return R::error("two vertex elements");
    if (is_vertex) {
      vertex_element = &e;
      for (const char* c : {"x", "y", "z"}) {
        const auto it = std::find_if(e.properties.begin(), e.properties.end(), [&](const Property& p) { return p.name == c; });
        if (it == e.properties.end()) return R::error(std::string("the vertex element has no ") + c + " property");
        if (it->list) return R::error(std::string("vertex property ") + c + " is a list, not a number");
      }
    }
    if (is_face && e.count > 0) {
      const bool found = std::any_of(e.properties.begin(), e.properties.end(), [](const Property& p) {
        return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
      });
      if (!found) return R::error("the face element has no vertex_indices list");
    }
  }

  // --- body
  std::unique_ptr<Body> body;
  if (format == Format::ascii) body = std::make_unique<AsciiBody>(text, pos);
  else body = std::make_unique<BinaryBody>(text, pos, format == Format::big);
  for (const auto& e : elements) {
    const bool is_vertex = &e == vertex_element;
    const bool is_face = e.name == "face" || e.name == "faces";
    if (is_vertex) soup.points.reserve(static_cast<std::size_t>(e.count));
    for (long long item = 0; item < e.count; ++item) {
      // Built only for a message: this loop runs once per vertex and face.
      const auto at = [&] { return "element " + cut(e.name) + " item " + std::to_string(item); };
      std::array<double, 3> xyz = {0, 0, 0};
      std::array<bool, 3> xyz_set = {false, false, false};
      bool face_list_taken = false;
      for (const auto& p : e.properties) {
        if (!p.list) {
          double v = 0;
          if (!body->number(p.type, v))
            return R::error("the body ends or is malformed in " + at() + ", property " + cut(p.name) + " (" + body->where() + ")");
          if (is_vertex)
            for (std::size_t k = 0; k < 3; ++k)
              if (!xyz_set[k] && p.name.size() == 1 && p.name[0] == "xyz"[k]) {
                xyz[k] = v;
                xyz_set[k] = true;  // the first property of that name, as CGAL did
              }
          continue;
        }
        double n = 0;
        if (!body->number(p.count_type, n))
          return R::error("the body ends or is malformed in " + at() + ", list " + cut(p.name) + " (" + body->where() + ")");
        if (!is_index(n) || !body->can_hold(n, p.type))
          return R::error(at() + ": list " + cut(p.name) + " declares " + show_number(n) +
                          " values, more than the rest of the file can hold (" + body->where() + ")");
        const bool indices = is_face && !face_list_taken && (p.name == "vertex_indices" || p.name == "vertex_index");
        std::vector<std::size_t> poly;
        if (indices) {
          face_list_taken = true;
          if (!is_integer_type(p.type)) return R::error(at() + ": vertex indices of a floating-point type");
          if (n < 3) return R::error(at() + " has " + std::to_string(static_cast<long long>(n)) + " corners (at least 3 needed)");
          poly.reserve(static_cast<std::size_t>(n));
        }
        for (double k = 0; k < n; ++k) {
          double v = 0;
          if (!body->number(p.type, v))
            return R::error("the body ends or is malformed in " + at() + ", list " + cut(p.name) + " (" + body->where() + ")");
          if (indices) {
            if (!is_index(v)) return R::error(at() + ": vertex index " + show_number(v) + " is negative or not an integer");
            poly.push_back(static_cast<std::size_t>(v));
          }
        }
        if (indices) soup.polygons.push_back(std::move(poly));
      }
      if (is_vertex) soup.points.push_back(xyz);
    }
  }
  for (std::size_t f = 0; f < soup.polygons.size(); ++f)
    for (std::size_t v : soup.polygons[f])
      if (v >= soup.points.size())
        return R::error("face " + std::to_string(f) + " references vertex " + std::to_string(v) + ", out of range (" +
                        std::to_string(soup.points.size()) + " vertices)");
  return soup;
}

}  // namespace ps
