#include "eomgen/base/bounded_read.hpp"

#include <algorithm>
#include <array>

namespace eomgen {

std::string read_at_most(std::istream& in, std::size_t limit) {
  std::string text;
  std::array<char, 1 << 16> chunk;
  while (text.size() <= limit && in) {
    const std::size_t wanted = std::min(chunk.size(), limit + 1 - text.size());
    in.read(chunk.data(), static_cast<std::streamsize>(wanted));
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  return text;
}

}  // namespace eomgen
