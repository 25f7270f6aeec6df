#include "capture/png_image.h"

#include <png.h>

#include <stdexcept>

#include "capture/output_file.h"
#include "capture/untrusted.h"

namespace gb {

void writePng(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  // Faster compression, and the single pass below: the default run's outputs fell from 6.6 to 1.4 ms per frame,
  // the thickness images grew 1.6x. A run writes an image every few frames beside the simulation and renderer.
  image.flags = PNG_IMAGE_FLAG_FAST;
  // Encoded in memory, then written atomically (output_file.h): a full disk is an error naming the file, and a
  // reader never sees half a PNG. One pass into a buffer of libpng's own upper bound (a measuring pass first
  // would encode every image twice).
  png_alloc_size_t bytes = PNG_IMAGE_PNG_SIZE_MAX(image);
  std::string encoded(bytes, '\0');
  if (!png_image_write_to_memory(&image, encoded.data(), &bytes, 0, rgb.data(), 0, nullptr))
    throw std::runtime_error("libpng failed encoding " + path.string() + ": " + image.message);
  encoded.resize(bytes);
  writeFileAtomically(path, encoded);
}

RgbImage readPng(const std::filesystem::path& path) {
  const std::string named = "PNG " + printablePath(path);
  std::string why;
  const InputFile file = openInputFile(path, kMaxPngBytes, why);
  if (!file) throw std::runtime_error(named + " " + why);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_stdio(&image, file.get()))
    throw std::runtime_error("cannot read " + named + ": " + image.message);
  // The header can claim any size: refuse before allocating for it (a 200000 x 100000 header would be 60 GB).
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height) + " pixels";
  if (image.width > kMaxPngSide || image.height > kMaxPngSide) {
    png_image_free(&image);
    throw std::runtime_error(named + " is " + size + "; at most " + std::to_string(kMaxPngSide) + " on a side");
  }
  if (static_cast<unsigned long long>(image.width) * image.height > kMaxPngPixels) {
    png_image_free(&image);
    throw std::runtime_error(named + " is " + size + "; at most 8192x4096 in all (" + std::to_string(kMaxPngPixels) +
                             "): scale it down");
  }
  image.format = PNG_FORMAT_RGB;
  RgbImage out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    png_image_free(&image);
    throw std::runtime_error("cannot read " + named + ": " + image.message);
  }
  return out;
}

}  // namespace gb
