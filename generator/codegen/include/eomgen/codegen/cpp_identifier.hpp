#pragma once
// The identifier policy of generated code: how free text of a model (names, descriptions,
// units) becomes C++ identifiers, string literals and comments that cannot clash with the
// generated code's own names or inject code.
#include <string>

namespace eomgen {

/// `name` as a C++ identifier that cannot clash with keywords, reserved names, the <cmath>
/// functions of the IR's calls or the generated code's own locals: a trailing '_' is added
/// where needed.
std::string cpp_identifier(const std::string& name);

/// `text` as the contents of a C++ string literal (quotes not included).
std::string cpp_string_contents(const std::string& text);

/// `text` as the contents of a // comment: printable ASCII without backslashes, so nothing
/// can continue or close the comment.
std::string cpp_comment_text(const std::string& text);

}  // namespace eomgen
