#pragma once
// Cross-section contour files: read and write a SectionSet in three formats.
//
//   .json     the project's interchange format (docs: shared/docs/contours.md, version 1);
//   .csl      the CSL format of the OReX / Bermano et al. data sets (shared/data/csl/README.md);
//   .contour  the input format of Liu et al.'s Ctr2Suf (plane count; per plane `a b c d` for
//             ax+by+cz=d, vertex and edge counts, vertices, edges `v0 v1 labelA labelB`).
//
// Every reader ends with the same checks and repairs (finish_sections), so a SectionSet that
// comes out of any of them satisfies cross_section.h:
//   - every coordinate finite and |x| <= 1e100 (larger values would overflow squared distances);
//   - plane normals scaled to unit length, offsets scaled alike; a zero normal is an error;
//   - with D the bounding-box diagonal of all curve points, a point off its plane by at most
//     1e-6 D is projected silently, by up to 1e-3 D projected with a warning, farther an error;
//   - consecutive duplicate points are dropped; a first point repeated at the end is dropped
//     with a warning; a curve needs at least 3 distinct points and a non-zero area;
//   - planes given twice (same normal up to sign, same offset within 1e-9 D) are merged, the
//     curves re-indexed, with a warning.
// Stroke rules 3 and 4 (curves crossing, disagreeing at shared lines) are NOT checked here:
// that is reconstruction's validation, so files breaking them can still be read and converted.
//
// Error messages name the file and where: `file: $.curves[3].points[7]: ...` for JSON,
// `file:line: ...` for CSL and .contour, `file: curve 4 (plane 2): ...` for the common checks.
// Readers never throw, never crash and never hang on any input (fuzzed: docs/robustness.md).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/status.h"

namespace ps {

enum class ContourFormat { Json, Csl, Ctr2Suf };

// ".json", ".csl", ".contour"
const char* contour_format_extension(ContourFormat format);
// By the file's extension (case-insensitive), or nothing.
std::optional<ContourFormat> contour_format_from_extension(const std::string& path);
// By the content: '{' -> JSON, "CSLC" -> CSL, a count followed by four numbers -> .contour.
std::optional<ContourFormat> sniff_contour_format(std::string_view content);

// === Reading
// Reads a file, choosing the reader by extension or, failing that, by content. Warnings
// (repairs made) are appended to `warnings` when given.
Result<SectionSet> read_sections(const std::string& path,
                                 std::vector<std::string>* warnings = nullptr);

// Parses in-memory content; `name` stands for the file name in messages. These are the entry
// points the fuzz targets use.
Result<SectionSet> parse_sections(std::string_view content, ContourFormat format,
                                  const std::string& name,
                                  std::vector<std::string>* warnings = nullptr);
Result<SectionSet> parse_contour_json(std::string_view content, const std::string& name,
                                      std::vector<std::string>* warnings = nullptr);
Result<SectionSet> parse_csl(std::string_view content, const std::string& name,
                             std::vector<std::string>* warnings = nullptr);
Result<SectionSet> parse_ctr2suf(std::string_view content, const std::string& name,
                                 std::vector<std::string>* warnings = nullptr);

// The checks and repairs every reader applies (see the top of this file). `set` is changed
// only when the result is ok.
Status finish_sections(SectionSet& set, const std::string& name,
                       std::vector<std::string>* warnings = nullptr);

// === Writing
// Text of a set in each format. Numbers are written in shortest round-trip form, so reading
// the text back gives the same doubles. CSL marks curves at odd nesting depth on their plane
// as holes of the innermost curve containing them; .contour writes edges `i i+1 1 0`.
std::string format_contour_json(const SectionSet& set);
std::string format_csl(const SectionSet& set);
std::string format_ctr2suf(const SectionSet& set);

// Writes by the extension of `path` (.json, .csl, .contour), to a temporary file beside the
// target renamed into place, so a failure never leaves a partial file.
Status write_sections(const std::string& path, const SectionSet& set);
Status write_sections(const std::string& path, const SectionSet& set, ContourFormat format);

// Writes `content` to `path` through a temporary file and a rename (shared by the writers).
Status write_file_atomically(const std::string& path, std::string_view content);

}  // namespace ps
