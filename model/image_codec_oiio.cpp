// The image codec module (model/image_codec.hpp): the only code that includes OpenImageIO, built
// as librastercmp_image_codec.so and opened with dlopen.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "model/image_codec.hpp"

namespace rastercmp {
namespace {

OIIO::TypeDesc to_oiio(PixelType type) {
  switch (type) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::UInt32: return OIIO::TypeDesc::UINT32;
    case PixelType::Float: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UINT8;
}

std::string write_image(const std::string& file, const std::string& format_of, const ImageView& image) {
  OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels), to_oiio(image.type));
  if (image.zip) spec.attribute("compression", "zip");
  // Same input, same bytes: OpenImageIO would stamp the current time (TIFF DateTime, EXR capDate).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  auto out = OIIO::ImageOutput::create(format_of);  // the format from format_of's extension
  const bool written = out && out->open(file, spec) && out->write_image(spec.format, image.pixels);
  // The close is the last flush: it must succeed too.
  const bool closed = out && out->close();
  if (written && closed) return "";
  const std::string why = out ? out->geterror() : OIIO::geterror();
  return why.empty() ? std::string("write failed") : why;
}

std::string read_u32(const std::string& file, ImageU32& image) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) {
    const std::string why = OIIO::geterror();
    return why.empty() ? std::string("open failed") : why;
  }
  const OIIO::ImageSpec& spec = in->spec();
  image.width = uint32_t(spec.width);
  image.height = uint32_t(spec.height);
  image.channels = uint32_t(spec.nchannels);
  image.pixels.assign(size_t(image.width) * image.height * image.channels, 0);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT32, image.pixels.data())) {
    const std::string why = in->geterror();
    return why.empty() ? std::string("read failed") : why;
  }
  return "";
}

std::string inferno(const float* values, size_t count, uint8_t* rgb) {
  if (count == 0) return "";
  OIIO::ImageBuf level(OIIO::ImageSpec(int(count), 1, 1, OIIO::TypeDesc::FLOAT));
  level.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, values);
  OIIO::ImageBuf coloured = OIIO::ImageBufAlgo::color_map(level, 0, "inferno");
  if (coloured.has_error()) return "color_map inferno: " + coloured.geterror();
  coloured.get_pixels(OIIO::ROI(0, int(count), 0, 1, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, rgb);
  return "";
}

const ImageCodec kCodec{kImageCodecAbi, write_image, read_u32, inferno};

}  // namespace
}  // namespace rastercmp

extern "C" __attribute__((visibility("default"))) const rastercmp::ImageCodec* rastercmp_image_codec() {
  return &rastercmp::kCodec;
}
