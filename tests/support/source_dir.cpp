#include "support/source_dir.hpp"

namespace eomgen::testing {

std::filesystem::path source_dir() { return EOMGEN_SOURCE_DIR; }

}  // namespace eomgen::testing
