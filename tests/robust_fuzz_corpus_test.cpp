// The deformation-spec and reconstruction fuzz targets' bodies (tests/fuzz/robust_entry_points.h)
// over their seed corpora and deterministic mutations, in every build (issue 8, point 1).
#include <gtest/gtest.h>

#include "modeling/mesh_slicer.h"
#include "tests/fuzz/corpus_runner.h"
#include "tests/fuzz/robust_entry_points.h"

TEST(RobustFuzzCorpus, DeformSpec) { ps::fuzz::run_target("deform_spec", ps::fuzz::check_deform_spec_bytes, 150); }

// Each reconstruction takes tens to hundreds of milliseconds, so fewer mutations per seed.
TEST(RobustFuzzCorpus, Reconstruct) { ps::fuzz::run_target("reconstruct", ps::fuzz::check_reconstruct_bytes, 4); }

TEST(RobustFuzzCorpus, ReconstructRandomBytes) {
  ps::fuzz::run_random_bytes(ps::fuzz::check_reconstruct_bytes, 20261122, 40, 160);
}

TEST(RobustFuzzCorpus, ValidSeedsReachTheDeepPaths) {
  // valid_* seeds must keep succeeding, or the corpus stops exercising the solver and the union.
  for (const auto& [name, bytes] : ps::fuzz::corpus("reconstruct")) {
    if (name.rfind("valid_", 0) != 0) continue;
    const auto* d = reinterpret_cast<const std::uint8_t*>(bytes.data());
    ps::ReconstructOptions o;
    o.improve = false;
    o.threads = 1;
    auto m = ps::reconstruct(ps::fuzz::decode_sections(d, bytes.size()), o);
    EXPECT_TRUE(m) << name << ": " << m.message();
  }
  for (const auto& [name, bytes] : ps::fuzz::corpus("deform_spec")) {
    if (name.rfind("valid_", 0) != 0) continue;
    auto s = ps::parse_deform_spec(bytes, name);
    ASSERT_TRUE(s) << name << ": " << s.message();
    EXPECT_TRUE(ps::check_deform_spec(*s, 6, name)) << name;
  }
}
