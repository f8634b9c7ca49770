// Runs every fuzz target's body (tests/fuzz/fuzz_entry_points.h) over its seed corpus
// (tests/fuzz/corpus/<target>/) and over deterministic mutations of each seed, in every build,
// so the fuzz entry points are exercised even where libFuzzer is not available.
#include <gtest/gtest.h>

#include "tests/fuzz/corpus_runner.h"
#include "tests/fuzz/fuzz_entry_points.h"

using ps::fuzz::corpus;
using ps::fuzz::run_target;

TEST(FormatsFuzzCorpus, ContourJson) { run_target("contour_json", ps::fuzz::check_contour_json, 200); }
TEST(FormatsFuzzCorpus, Csl) { run_target("csl", ps::fuzz::check_csl, 200); }
TEST(FormatsFuzzCorpus, Ctr2Suf) { run_target("ctr2suf", ps::fuzz::check_ctr2suf, 200); }
TEST(FormatsFuzzCorpus, MeshImport) { run_target("mesh_import", ps::fuzz::check_mesh_import, 40); }

TEST(FormatsFuzzCorpus, ValidSeedsReadSuccessfully) {
  // The valid_* seeds must stay valid, so the corpus keeps reaching the deep code paths.
  for (const char* target : {"contour_json", "csl", "ctr2suf"})
    for (const auto& [name, bytes] : corpus(target)) {
      if (name.rfind("valid_", 0) != 0) continue;
      const auto fmt = std::string(target) == "contour_json" ? ps::ContourFormat::Json
                       : std::string(target) == "csl"        ? ps::ContourFormat::Csl
                                                             : ps::ContourFormat::Ctr2Suf;
      auto r = ps::parse_sections(bytes, fmt, name);
      EXPECT_TRUE(r) << target << "/" << name << ": " << r.message();
    }
}
