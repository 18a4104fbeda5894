#include "eomgen/base/content_hash.hpp"

namespace eomgen {

std::uint64_t content_hash(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace eomgen
