#pragma once
/// \file
/// Reading a user's file that has a size limit.
#include <cstddef>
#include <istream>
#include <string>

namespace eomgen {

/// The bytes of \p in up to \p limit + 1 of them: one more than the limit tells a file over it,
/// and no more, since a file may be endless (/dev/zero, a pipe). Read in chunks, so that the cost
/// follows the file, not the limit. The caller checks `in.bad()` for a read error.
std::string read_at_most(std::istream& in, std::size_t limit);

}  // namespace eomgen
