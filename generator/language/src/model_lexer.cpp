#include "model_lexer.hpp"

#include <fmt/format.h>

#include <cctype>

#include "eomgen/base/error.hpp"
#include "eomgen/base/utf8.hpp"

namespace eomgen::syntax {
namespace {

bool is_ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// ".649262481663582", as published robot descriptions write numbers: a '.' followed by a digit
// that does not follow a name or a closing bracket (there it picks an axis, "b.2")
bool starts_fraction(const std::string& text, std::size_t i) {
  if (text[i] != '.' || i + 1 >= text.size() || !is_digit(text[i + 1])) return false;
  if (i == 0) return true;
  const char before = text[i - 1];
  return !(std::isalnum(static_cast<unsigned char>(before)) || before == '_' || before == ')' || before == ']' ||
           before == '}' || before == '.');
}

}  // namespace

std::string describe(const Token& token) {
  switch (token.kind) {
    case Token::Kind::newline: return "end of line";
    case Token::Kind::end: return "end of file";
    case Token::Kind::string: return fmt::format("string \"{}\"", token.text);
    case Token::Kind::identifier:
    case Token::Kind::number:
    case Token::Kind::symbol: return fmt::format("'{}'", token.text);
  }
  EOMGEN_UNREACHABLE("describe: a Token::Kind outside its enumerators");
}

std::vector<Token> tokenize(const std::string& text, const std::string& file, int first_line, int first_column) {
  std::vector<Token> tokens;
  int line = first_line, column = first_column;
  // open ( and [ with their positions: an unclosed one swallows the rest of the file, so it is
  // reported where it was opened rather than wherever the parser first stumbles
  std::vector<Token> open;
  std::size_t i = 0;
  auto here = [&] { return SourceLocation{file, line, column}; };
  auto advance = [&](std::size_t n) {
    for (std::size_t k = 0; k < n && i < text.size(); ++k, ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
  };
  auto push = [&](Token::Kind kind, std::string s, SourceLocation loc, std::size_t start) {
    tokens.push_back(Token{kind, std::move(s), std::move(loc), start, i});
  };
  while (i < text.size()) {
    const char c = text[i];
    const SourceLocation loc = here();
    const std::size_t start = i;
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') advance(1);
    } else if (c == '\n') {
      advance(1);
      if (open.empty() && !tokens.empty() && tokens.back().kind != Token::Kind::newline)
        push(Token::Kind::newline, "\n", loc, start);
    } else if (c == ' ' || c == '\t' || c == '\r') {
      advance(1);
    } else if (is_ident_start(c)) {
      // identifier, with {expression} pieces kept verbatim for the parser
      while (i < text.size() && (is_ident_char(text[i]) || text[i] == '{')) {
        if (text[i] == '{') {
          int braces = 0;
          do {
            if (text[i] == '{') ++braces;
            if (text[i] == '}') --braces;
            if (text[i] == '\n' || (i + 1 == text.size() && braces > 0))
              throw SourceError(loc, "unterminated '{' in a name: expected '}'");
            advance(1);
          } while (i < text.size() && braces > 0);
        } else {
          advance(1);
        }
      }
      push(Token::Kind::identifier, text.substr(start, i - start), loc, start);
    } else if (is_digit(c) || starts_fraction(text, i)) {
      while (i < text.size() && is_digit(text[i])) advance(1);
      // a '.' belongs to the number only when a digit follows ("1..n" is a range)
      if (i + 1 < text.size() && text[i] == '.' && is_digit(text[i + 1])) {
        advance(1);
        while (i < text.size() && is_digit(text[i])) advance(1);
      }
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t j = i + 1;
        if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
        if (j < text.size() && is_digit(text[j])) {
          advance(j - i);
          while (i < text.size() && is_digit(text[i])) advance(1);
        }
      }
      push(Token::Kind::number, text.substr(start, i - start), loc, start);
    } else if (c == '"') {
      advance(1);
      std::string s;
      while (i < text.size() && text[i] != '"' && text[i] != '\n') {
        s += text[i];
        advance(1);
      }
      if (i >= text.size() || text[i] != '"') throw SourceError(loc, "unterminated string: expected '\"'");
      if (const std::size_t bad = invalid_utf8_at(s); bad != std::string::npos) {
        SourceLocation at = loc;
        at.column += static_cast<int>(bad) + 1;
        throw SourceError(at, fmt::format("byte 0x{:02x} in a string is not UTF-8: expected UTF-8 text",
                                          static_cast<unsigned char>(s[bad])));
      }
      advance(1);
      push(Token::Kind::string, s, loc, start);
    } else if (c == '.' && i + 1 < text.size() && text[i + 1] == '.') {
      advance(2);
      push(Token::Kind::symbol, "..", loc, start);
    } else if (std::string("+-*/^()[],=:.").find(c) != std::string::npos) {
      advance(1);
      push(Token::Kind::symbol, std::string(1, c), loc, start);
      if (c == '(' || c == '[') open.push_back(tokens.back());
      if ((c == ')' || c == ']') && !open.empty()) open.pop_back();
    } else {
      // a control byte or a byte of UTF-8 is named by its value, not written raw into the message
      const auto byte = static_cast<unsigned char>(c);
      throw SourceError(loc, byte >= 32 && byte < 127 ? fmt::format("unexpected character '{}'", std::string(1, c))
                                                      : fmt::format("unexpected byte 0x{:02x}: expected ASCII "
                                                                    "model text (names, numbers, operators)", byte));
    }
  }
  if (!open.empty())
    throw SourceError(open.back().location, fmt::format("'{}' is never closed: expected '{}'", open.back().text,
                                                        open.back().text == "(" ? ")" : "]"));
  if (!tokens.empty() && tokens.back().kind != Token::Kind::newline)
    tokens.push_back(Token{Token::Kind::newline, "\n", here(), i, i});
  tokens.push_back(Token{Token::Kind::end, "", here(), i, i});
  return tokens;
}

}  // namespace eomgen::syntax
