#pragma once
// Reading a store's metadata JSON (store_metadata.cpp, global_store_metadata.cpp): checked
// fields, and the parse that turns JSON and range errors into an Error. Private to the tile
// format library.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/core/result.hpp"

namespace tellus::metadata_json {

// Heights Tellus stores, metres: anything beyond is a corrupt or hostile store.
inline constexpr double kMaxAbsHeightM = 1e6;

// A JSON number field within [lo, hi]; integers must be integral (no wrap of -1 into a count).
// Throws std::invalid_argument naming the field.
template <typename T>
T numberField(const nlohmann::json& j, const char* key, double lo, double hi) {
  const nlohmann::json& v = j.at(key);
  if (!v.is_number()) throw std::invalid_argument(fmt::format("'{}' is not a number", key));
  if constexpr (std::is_integral_v<T>) {
    if (!v.is_number_integer()) {
      throw std::invalid_argument(fmt::format("'{}' is not an integer", key));
    }
    const double value =
        v.is_number_unsigned() ? double(v.get<std::uint64_t>()) : double(v.get<std::int64_t>());
    if (!(value >= lo && value <= hi)) {
      throw std::invalid_argument(fmt::format("'{}' is {}, outside {}..{}", key, value, lo, hi));
    }
    return v.is_number_unsigned() ? T(v.get<std::uint64_t>()) : T(v.get<std::int64_t>());
  } else {
    const double value = v.get<double>();
    if (!std::isfinite(value) || value < lo || value > hi) {
      throw std::invalid_argument(fmt::format("'{}' is {}, outside {}..{}", key, value, lo, hi));
    }
    return T(value);
  }
}

// Parses `text` as a JSON object and hands it to `parse`, which throws on a missing, mistyped
// (nlohmann::json::exception) or meaningless (std::invalid_argument) field.
template <typename Metadata, typename Parse>
Result<Metadata> parseMetadataJson(std::string_view text, Parse parse) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return makeError("metadata is not a JSON object");
  try {
    return parse(j);
  } catch (const nlohmann::json::exception& e) {
    return makeError("metadata field missing or of the wrong type ({})", e.what());
  } catch (const std::invalid_argument& e) {
    return makeError("metadata makes no sense: {}", e.what());
  }
}

}  // namespace tellus::metadata_json
