#pragma once
// CPU images: the renderer's read-back result, PNG files, and image comparison for goldens.
//
// Image layout: width * height pixels, row-major from the TOP row down (pixel (x, y) with y
// down, as ps::Camera), 4 bytes per pixel R, G, B, A (8-bit, alpha 255 = opaque).
#include <cstdint>
#include <string>
#include <vector>

#include "modeling/status.h"

namespace ps::engine {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 bytes

  const uint8_t* pixel(int x, int y) const {
    return rgba.data() + 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(x));
  }
};

// Write an RGBA PNG. The file is written to a temporary name beside `path` and renamed into
// place, so a failure never leaves a partial file at `path`.
Status write_png(const std::string& path, const Image& image);

// Read a PNG (any channel count, converted to RGBA).
Result<Image> read_png(const std::string& path);

// How two images of the same size differ.
struct ImageDiff {
  bool same_size = false;
  int max_channel_diff = 0;         // largest |a - b| over all channels of all pixels
  std::size_t differing_pixels = 0;  // pixels where some channel differs by more than `threshold`
  double differing_fraction = 0.0;   // differing_pixels / pixel count
};

// Compare two images; a pixel "differs" when any channel differs by more than `threshold`.
ImageDiff compare_images(const Image& a, const Image& b, int threshold = 0);

// An image showing where a and b differ (black = equal, brighter = larger difference), for
// looking at failed golden tests. Requires equal sizes.
Image difference_image(const Image& a, const Image& b);

}  // namespace ps::engine
