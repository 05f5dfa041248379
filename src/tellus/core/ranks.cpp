#include "tellus/core/ranks.hpp"

namespace tellus {

Status agree(Ranks& ranks, const Status& local) {
  const std::string message = local ? std::string() : local.error().message;
  // An empty message is success; a failure always says something.
  const std::string sent = local ? std::string() : (message.empty() ? "failed" : message);
  Result<std::vector<std::vector<std::byte>>> all =
      ranks.allGather(std::as_bytes(std::span(sent.data(), sent.size())));
  if (!all) return all.error();
  if (!local) return local;
  for (std::size_t k = 0; k < all->size(); ++k) {
    const std::vector<std::byte>& bytes = (*all)[k];
    if (bytes.empty()) continue;
    return makeError("rank {}: {}", k,
                     std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  }
  return {};
}

}  // namespace tellus
