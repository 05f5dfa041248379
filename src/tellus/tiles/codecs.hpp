#pragma once
// Factories of the individual codecs (one file each). Use makeCodec() from tile_codec.hpp
// unless you need one codec by type.
#include <memory>

#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

std::unique_ptr<TileCodec> makeRawCodec();
std::unique_ptr<TileCodec> makeZstdCodec(const CodecOptions& options);
std::unique_ptr<TileCodec> makeBoundedCodec(const CodecOptions& options);
std::unique_ptr<TileCodec> makeLercCodec(const CodecOptions& options);
std::unique_ptr<TileCodec> makeFractalCodec(const CodecOptions& options);

}  // namespace tellus
