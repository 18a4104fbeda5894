#pragma once
// How every subcommand reads its model: one place, so that each prints the model's notes once.
#include "command_line.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen::tools {

/// The model of the command's file: load_model with --define and, for a URDF, the import
/// options. Its notes are printed on standard error (print_notes) before the command prints
/// anything, so standard output holds what it did without them.
Model load_command_model(const Options& o);

/// Each note of the model on standard error, "file:line:col: note: ...", in the model's order.
void print_notes(const Model& model);

}  // namespace eomgen::tools
