#include "tellus/tiles/tile_codec.hpp"

#include <fmt/format.h>

#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/fractal_encoder.hpp"

namespace tellus {

const std::vector<std::string>& codecNames() {
  static const std::vector<std::string> names{"raw", "zstd", "bounded", "lerc", "fractal"};
  return names;
}

std::string_view codecName(CodecId id) {
  switch (id) {
    case CodecId::Raw:
      return "raw";
    case CodecId::Zstd:
      return "zstd";
    case CodecId::Bounded:
      return "bounded";
    case CodecId::Lerc:
      return "lerc";
    case CodecId::Fractal:
      return "fractal";
  }
  return "unknown";
}

Result<std::unique_ptr<TileCodec>> makeCodec(std::string_view name, const CodecOptions& options) {
  if (name == "raw") return makeRawCodec();
  if (name == "zstd") return makeZstdCodec(options);
  if (name == "bounded") return makeBoundedCodec(options);
  if (name == "lerc") return makeLercCodec(options);
  if (name == "fractal") {
    if (Status s = fractal::checkOptions(options.fractal); !s) return s.error();
    return makeFractalCodec(options);
  }
  return makeError("unknown codec '{}' (choose one of: {})", name, fmt::join(codecNames(), ", "));
}

Result<std::unique_ptr<TileCodec>> makeCodec(CodecId id, const CodecOptions& options) {
  const std::string_view name = codecName(id);
  if (name == "unknown") return makeError("unknown codec id {}", std::uint32_t(id));
  return makeCodec(name, options);
}

}  // namespace tellus
