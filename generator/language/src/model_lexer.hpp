#pragma once
// Tokens of the model language with their positions.
#include <string>
#include <vector>

#include "eomgen/base/source_location.hpp"

namespace eomgen::syntax {

struct Token {
  enum class Kind { identifier, number, string, symbol, newline, end };
  Kind kind;
  std::string text;  // identifier text with any {..} pieces, number text, string contents, symbol
  SourceLocation location;
  std::size_t offset = 0;  // byte offset of the token in the text
  std::size_t end_offset = 0;
};

/// Splits model text into tokens. Newlines inside ( ) and [ ] are dropped, so a statement
/// continues while a bracket is open. \throws SourceError on a character that starts no token.
std::vector<Token> tokenize(const std::string& text, const std::string& file, int first_line = 1,
                            int first_column = 1);

/// A description of a token for error messages: "'x'", "end of line", "end of file".
std::string describe(const Token& token);

}  // namespace eomgen::syntax
