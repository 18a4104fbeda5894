#pragma once
// A stable 64-bit hash of text (FNV-1a): the model hash in generated headers and the key of
// `eomgen simulate`'s build cache. Not cryptographic; stable across runs, platforms and versions.
#include <cstdint>
#include <string_view>

namespace eomgen {

/// FNV-1a over the bytes of `text`.
std::uint64_t content_hash(std::string_view text);

}  // namespace eomgen
