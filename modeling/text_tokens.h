#pragma once
// Whitespace-separated tokens of text formats, shared by the contour readers (contour_io.cpp)
// and the mesh readers (off_reader.cpp, ply_reader.cpp).
#include <string>
#include <string_view>
#include <vector>

namespace ps {

// The whole token as a double; a leading '+' allowed. A valid numeral beyond double's range
// reads as +-infinity or a (sub)normal/zero, as strtod gives it, so the caller can name it.
bool parse_double(std::string_view token, double& out);

// The whole token as an integer; a leading '+' allowed.
bool parse_int(std::string_view token, long long& out);

// The tokens of a line, split at std::isspace. The second form refills `out`, keeping its
// capacity (for readers that split line after line).
std::vector<std::string_view> split(std::string_view line);
void split(std::string_view line, std::vector<std::string_view>& out);

// A token shown in a message: in quotes, at most 20 characters, non-printable ones as '?'.
std::string show(std::string_view token);

}  // namespace ps
