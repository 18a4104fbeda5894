// How every subcommand reads its model, and the model's notes on standard error.
#include "model_loading.hpp"

#include <iostream>

#include "command_values.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen::tools {

Model load_command_model(const Options& o) {
  Model model = load_model(o.model_path, parse_assignments(o.defines, "--define"), import_options(o));
  print_notes(model);
  return model;
}

void print_notes(const Model& model) {
  for (const Note& note : model.notes) std::cerr << note_text(note) << "\n";
  std::cerr << std::flush;
}

}  // namespace eomgen::tools
