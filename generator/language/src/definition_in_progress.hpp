#pragma once
// A definition being built: frames, points and derived parameters are built on demand, when an
// expression names them, whatever their order in the file, so meeting one of them again before
// it is done is a cycle.
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "model_syntax.hpp"

namespace eomgen::syntax {

class DefinitionInProgress {
 public:
  /// `kind` names the definition in messages ("frame"), `ahead` the definitions of its stack
  /// ("frames and points").
  DefinitionInProgress(std::vector<std::string>& stack, const char* kind, const std::string& name,
                       const SourceLocation& at, const char* ahead)
      : stack_(stack) {
    auto start = std::find(stack.begin(), stack.end(), name);
    if (start != stack.end()) {
      std::string cycle;
      for (auto it = start; it != stack.end(); ++it) cycle += *it + " -> ";
      throw SourceError(at, fmt::format("{} '{}' is defined through a cycle: {}{}", kind, name, cycle, name));
    }
    // each definition built ahead of its turn is a level of recursion
    if (stack.size() == max_definitions_ahead)
      throw SourceError(at, fmt::format("{} '{}' is defined through more than {} {} that come later in the file: "
                                        "expected {}", kind, name, max_definitions_ahead, ahead,
                                        std::string(ahead) == "parameters"
                                            ? "parameters defined before the parameters defined from them"
                                            : "parents defined before their children"));
    stack_.push_back(name);
  }
  DefinitionInProgress(const DefinitionInProgress&) = delete;
  DefinitionInProgress& operator=(const DefinitionInProgress&) = delete;
  ~DefinitionInProgress() { stack_.pop_back(); }

 private:
  std::vector<std::string>& stack_;
};

}  // namespace eomgen::syntax
