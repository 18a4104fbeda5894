#include "eomgen/codegen/cpp_identifier.hpp"

#include <fmt/format.h>

#include <cctype>
#include <set>

#include "eomgen/codegen/ir.hpp"

namespace eomgen {
namespace {

// keywords, the generated code's own names and every call's <cmath> function
std::set<std::string> reserved_words() {
  std::set<std::string> words = {
    "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
    "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
    "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
    "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
    "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
    "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
    "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
    "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
    "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
    // names the generated code itself uses
    "Scalar", "Model", "Parameters", "Eigen", "std", "M", "F", "Xi", "Xi_t", "b", "phi", "y", "p", "q", "qd",
    "u", "t", "NDEBUG", "assert", "errno"};
  for (const ir::CallOp& call : ir::call_ops) words.insert(call.cpp_name);
  return words;
}

}  // namespace

std::string cpp_identifier(const std::string& name) {
  std::string id;
  for (char c : name) id += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "_" + id;
  // leading underscores and double underscores are reserved for the implementation
  if (id[0] == '_') id = "v" + id;
  while (id.find("__") != std::string::npos) id.replace(id.find("__"), 2, "_");
  static const std::set<std::string> reserved = reserved_words();
  if (reserved.count(id) || id.back() == '_') id += "_";
  return id;
}

std::string cpp_string_contents(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c >= 32 && c < 127 && c != '?') {  // '?' avoids trigraph surprises in old compilers
      out += static_cast<char>(c);
    } else {
      out += fmt::format("\\{:03o}", c);
    }
  }
  return out;
}

std::string cpp_comment_text(const std::string& text) {
  std::string out;
  for (char c : text)
    if (c >= 32 && c < 127 && c != '\\') out += c;
  return out;
}

}  // namespace eomgen
