// PNG IO through stb (stb_image_write / stb_image); the only translation unit defining their
// implementations.
#include "engine/image.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace ps::engine {

Status write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0)
    return Status::error(path + ": cannot write an empty image (" + std::to_string(image.width) +
                         "x" + std::to_string(image.height) + ")");
  const std::size_t expected =
      4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.rgba.size() != expected)
    return Status::error(path + ": image has " + std::to_string(image.rgba.size()) +
                         " bytes, expected " + std::to_string(expected));
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) return Status::error(path + ": is a directory");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    return Status::error(path + ": folder " + dir.string() + " does not exist");
  // Temporary file beside the target so the rename stays on one file system.
  std::string tmp_name = target.filename().string();
  tmp_name.insert(tmp_name.begin(), '.');
  tmp_name += ".tmp";
  tmp_name += std::to_string(::getpid());
  const fs::path tmp = dir / tmp_name;
  const int ok = stbi_write_png(tmp.c_str(), image.width, image.height, 4, image.rgba.data(),
                                image.width * 4);
  if (!ok) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot write PNG (permission denied or disk full?)");
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    return Status::error(path + ": cannot move PNG into place: " + ec.message());
  }
  return Status::ok();
}

Result<Image> read_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) {
    const char* why = stbi_failure_reason();
    return Result<Image>::error(path + ": cannot read PNG: " + (why ? why : "unknown error"));
  }
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.assign(data, data + 4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  stbi_image_free(data);
  return img;
}

ImageDiff compare_images(const Image& a, const Image& b, int threshold) {
  ImageDiff d;
  d.same_size = a.width == b.width && a.height == b.height && a.rgba.size() == b.rgba.size();
  if (!d.same_size) return d;
  const std::size_t n = a.rgba.size() / 4;
  for (std::size_t i = 0; i < n; ++i) {
    int worst = 0;
    for (std::size_t c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(int(a.rgba[4 * i + c]) - int(b.rgba[4 * i + c])));
    d.max_channel_diff = std::max(d.max_channel_diff, worst);
    if (worst > threshold) ++d.differing_pixels;
  }
  d.differing_fraction = n ? static_cast<double>(d.differing_pixels) / static_cast<double>(n) : 0.0;
  return d;
}

Image difference_image(const Image& a, const Image& b) {
  Image out;
  out.width = a.width;
  out.height = a.height;
  out.rgba.assign(a.rgba.size(), 0);
  if (a.rgba.size() != b.rgba.size()) return out;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      // Amplified so one-level differences are visible.
      const int diff = std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c]));
      out.rgba[i + c] = static_cast<uint8_t>(std::min(255, diff * 16));
    }
    out.rgba[i + 3] = 255;
  }
  return out;
}

}  // namespace ps::engine
