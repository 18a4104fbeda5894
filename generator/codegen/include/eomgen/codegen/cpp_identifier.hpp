#pragma once
// The identifier policy of generated code: how free text of a model (names, descriptions,
// units) becomes C++ identifiers, string literals and comments that cannot clash with the
// generated code's own names or inject code.
#include <string>

namespace eomgen {

/// `name` (a parameter's, the model's, a namespace's: any text) as a C++ identifier. The one
/// mangling of generated code:
/// - a plain name (a letter, then letters, digits and single '_' between them, not ending in
///   '_') stays as it is: m, l1, theta_dot, x_y;
/// - unless it is a C++ keyword, a name the generated code uses (np, fields, Scalar, q, c, T,
///   sin, ...) or a macro of the headers that generated code and the simulation program
///   include (EOF, NULL, NAN, M_PI, errno, linux, ...; header_macros.cpp): those and every
///   other name are escaped and end in '_', which a plain name never does. The escape keeps
///   letters and digits and a '_' before a letter, writes any other '_' as "_1" and any other
///   byte as "_2" and two hex digits, and begins with "v_0" when the name does not begin with
///   a letter: int -> int_, NULL -> NULL_, M_PI -> M_PI_, x_ -> x_1_, x__ -> x_1_1_,
///   x__y -> x_1_y_, _x -> v_0_x_, M_1_PI -> M_11_PI_, my-model -> my_22Dmodel_.
/// Injective (different names never share an identifier), and the result never begins with
/// '_', never contains "__", and is never a keyword, a generated name or a listed macro.
std::string cpp_identifier(const std::string& name);

/// `text` as the contents of a C++ string literal (quotes not included).
std::string cpp_string_contents(const std::string& text);

/// `text` as the contents of a // comment: printable ASCII without backslashes, so nothing
/// can continue or close the comment.
std::string cpp_comment_text(const std::string& text);

}  // namespace eomgen
