#pragma once
// Golden-image comparison for the tests that render on lavapipe (engine_render_test,
// app_sketch_guides_test). Goldens live in tests/goldens/*.png; scripts/update-goldens sets
// PLANESKETCH_UPDATE_GOLDENS=1 and runs those tests, which then write the goldens instead. A
// failing comparison writes the actual image and an amplified difference image into the
// test's working directory (<name>.actual.png, <name>.diff.png).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/image.h"

namespace ps::engine {

struct Tolerance {
  int max_channel_diff;   // a pixel "differs" when a channel differs by more than this
  double max_fraction;    // fraction of differing pixels allowed
};
// lavapipe output is byte-identical run to run; allow one level of rounding noise anywhere
// and a handful of edge pixels beyond it (a different CPU's LLVM code generation).
constexpr Tolerance kGoldenTolerance{1, 0.002};

inline bool update_goldens() {
  const char* v = std::getenv("PLANESKETCH_UPDATE_GOLDENS");
  return v && *v && std::string(v) != "0";
}

inline ::testing::AssertionResult matches_golden(const Image& actual, const std::string& name,
                                          Tolerance tol) {
  const std::filesystem::path golden = std::filesystem::path(PLANESKETCH_SOURCE_DIR) / "tests" / "goldens" / (name + ".png");
  if (update_goldens()) {
    if (auto st = write_png(golden.string(), actual); !st)
      return ::testing::AssertionFailure() << "cannot update golden: " << st.message();
    return ::testing::AssertionSuccess() << "updated " << golden;
  }
  if (!std::filesystem::exists(golden))
    return ::testing::AssertionFailure()
           << "golden " << golden << " is missing; run scripts/update-goldens";
  auto expected = read_png(golden.string());
  if (!expected) return ::testing::AssertionFailure() << expected.message();
  const ImageDiff d = compare_images(actual, *expected, tol.max_channel_diff);
  if (d.same_size && d.differing_fraction <= tol.max_fraction) return ::testing::AssertionSuccess();
  const std::filesystem::path out_dir = std::filesystem::current_path();
  (void)write_png((out_dir / (name + ".actual.png")).string(), actual);
  if (d.same_size)
    (void)write_png((out_dir / (name + ".diff.png")).string(), difference_image(actual, *expected));
  auto fail = ::testing::AssertionFailure() << "image '" << name << "' differs from " << golden;
  if (!d.same_size)
    return fail << ": size " << actual.width << "x" << actual.height << " vs "
                << expected->width << "x" << expected->height;
  return fail << ": " << d.differing_pixels << " pixels (" << 100.0 * d.differing_fraction
              << "%, allowed " << 100.0 * tol.max_fraction << "%) differ by more than "
              << tol.max_channel_diff << "; largest channel difference " << d.max_channel_diff
              << "; see " << (out_dir / (name + ".actual.png")) << " and .diff.png";
}

// Reports the caller's file and line (gtest's EXPECT_PRED_FORMAT-style macro).
#define EXPECT_IMAGE_MATCHES_GOLDEN(image, name) \
  EXPECT_TRUE(::ps::engine::matches_golden((image), (name), ::ps::engine::kGoldenTolerance))

}  // namespace ps::engine
