#pragma once
// A note on a model: something the reader of a model file should know that is no error (a
// constraint left out as redundant). The model keeps its notes; the commands print them on
// standard error, so that what they print on standard output stays the same.
#include <string>

#include "eomgen/base/source_location.hpp"

namespace eomgen {

struct Note {
  SourceLocation location;
  std::string message;  // without the position
};

/// "file:line:col: note: message", in the form of SourceError's "file:line:col: error: message".
inline std::string note_text(const Note& note) {
  return note.location.file + ":" + std::to_string(note.location.line) + ":" + std::to_string(note.location.column) +
         ": note: " + note.message;
}

}  // namespace eomgen
