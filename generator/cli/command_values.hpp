#pragma once
// What several subcommands read and print the same way: NAME=VALUE lists, the state and
// parameters of --at and --set, numbers that read back exactly, matrices as text and JSON.
#include <Eigen/Dense>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen::tools {

/// "a, b, c", or "none" for no items
std::string join(const std::vector<std::string>& items);

/// the shortest text that reads back to exactly `x`
std::string number(double x);

/// "a=1", "b=-2.5e3" -> {a: 1, b: -2500}; `option` names the flag in messages
/// \throws UsageError for a malformed item, a value that is not a finite number, a name twice
std::map<std::string, double> parse_assignments(const std::vector<std::string>& items, const std::string& option);

/// Why `name`, given to --set, is no parameter of the model, and where its value goes instead:
/// `state` and `input` are the options that take a coordinate's or rate's value and an input's
/// ("--at" for eval and linearize; "--init" and "--input" for simulate).
std::string not_a_parameter(const Model& model, const std::string& name, const std::string& state,
                            const std::string& input);

/// --at (the state) and --set (parameters) as one set of named values for the evaluation
/// \throws UsageError for a name in both; Error for a --set name that is not a parameter
NamedValues state_and_parameters(const std::vector<std::string>& at, const std::vector<std::string>& set,
                                 const Model& model);

/// --guess: starting values of coordinates and rates (NAME, NAME_dot), none of them in `given`
/// \throws UsageError for a malformed item, another name, or a name also in `given` (via
///   `given_option`)
NamedValues state_guesses(const std::vector<std::string>& items, const NamedValues& given,
                          const std::string& given_option, const Model& model);

/// "TITLE (r x c):" and the rows, columns aligned
std::string matrix_text(const std::string& title, const Eigen::MatrixXd& a);

/// a matrix as an array of rows
nlohmann::ordered_json json_rows(const Eigen::MatrixXd& a);

/// one key per line, each value compact (a matrix on one line as an array of rows);
/// nlohmann writes the shortest decimal that reads back to the same double; a byte of a string
/// that starts no UTF-8 character becomes U+FFFD (JSON is UTF-8), so the document is always whole
std::string json_document(const nlohmann::ordered_json& j);

}  // namespace eomgen::tools
