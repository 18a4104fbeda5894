#pragma once
#include <string>

namespace eomgen {

/// A position in a model file: 1-based line and column.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

}  // namespace eomgen
