#include "command_values.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <charconv>
#include <cmath>

#include "eomgen/base/error.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return items.empty() ? "none" : out;
}

std::string number(double x) { return fmt::format("{}", x); }

std::map<std::string, double> parse_assignments(const std::vector<std::string>& items, const std::string& option) {
  std::map<std::string, double> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw UsageError(fmt::format("{}: expected NAME=VALUE, got '{}'", option, item));
    const std::string name = item.substr(0, eq);
    std::string text = item.substr(eq + 1);
    if (text[0] == '+') text.erase(0, 1);
    double value = 0.0;
    // from_chars: locale-independent, and must consume the whole text
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range && end == text.data() + text.size())  // 1e400, 1e-400
      throw UsageError(fmt::format("{}: '{}' in '{}' is beyond the range of a double (magnitudes from 2.2e-308 to "
                                   "1.8e308, or 0)",
                                   option, item.substr(eq + 1), item));
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
      throw UsageError(fmt::format("{}: '{}' in '{}' is not a finite number", option, item.substr(eq + 1), item));
    if (!out.emplace(name, value).second) throw UsageError(fmt::format("{}: '{}' is given twice", option, name));
  }
  return out;
}

std::string not_a_parameter(const Model& model, const std::string& name, const std::string& state,
                            const std::string& input) {
  const Variables& v = model.system.variables();
  for (const DerivedParameter& d : v.derived_parameters()) {
    if (d.name != name) continue;
    std::vector<std::string> sources;
    for (std::size_t k : v.parameters_in(d.definition)) sources.push_back(v.parameters()[k].name);
    return fmt::format("'{}' is defined from other parameters of {}, and follows them: expected one of those it is "
                       "defined from: {}", name, model.name, join(sources));
  }
  if (const auto symbol = v.find(name)) {
    switch (*v.kind_of(*symbol)) {
      case SymbolKind::coordinate:
      case SymbolKind::rate:
        return fmt::format("'{}' is a {} of {}, not a parameter: give its value with {} {}=VALUE", name,
                           v.kind_of(*symbol) == SymbolKind::coordinate ? "coordinate" : "rate", model.name, state,
                           name);
      case SymbolKind::input:
        return fmt::format("'{}' is an input of {}, not a parameter: give its value with {} {}=VALUE", name,
                           model.name, input, name);
      case SymbolKind::time:
        return state == "--at" ? "'t' is the time, not a parameter: give it with --at t=VALUE"
                               : "'t' is the time, not a parameter: the run starts at t = 0 and ends at --t-end";
      case SymbolKind::acceleration:
        return fmt::format("'{}' is an acceleration of {}, which the equations of motion give, not a parameter",
                           name, model.name);
      case SymbolKind::parameter:
      case SymbolKind::derived_parameter:  // said above
        break;
    }
    EOMGEN_UNREACHABLE("not_a_parameter: asked about a parameter of the model");
  }
  if (model.constants.count(name))
    return fmt::format("'{}' is a const of {}, fixed when the model is read, not a parameter: change it with "
                       "--define {}=VALUE", name, model.name, name);
  std::vector<std::string> parameters;
  for (const Parameter& p : v.parameters()) parameters.push_back(p.name);
  return fmt::format("'{}' is not a parameter of {}; its parameters: {}", name, model.name, join(parameters));
}

NamedValues state_and_parameters(const std::vector<std::string>& at_items, const std::vector<std::string>& set_items,
                                 const Model& model) {
  const std::map<std::string, double> at = parse_assignments(at_items, "--at");
  const std::map<std::string, double> set = parse_assignments(set_items, "--set");
  NamedValues values = at;
  for (const auto& [name, value] : set)
    if (!values.emplace(name, value).second) throw UsageError(fmt::format("--set: '{}' is also given in --at", name));
  const Variables& v = model.system.variables();
  for (const auto& [name, value] : set) {
    const auto symbol = v.find(name);
    if (!symbol || v.kind_of(*symbol) != SymbolKind::parameter)
      throw Error("--set: " + not_a_parameter(model, name, "--at", "--at"));
  }
  return values;
}

NamedValues state_guesses(const std::vector<std::string>& items, const NamedValues& given,
                          const std::string& given_option, const Model& model) {
  const std::map<std::string, double> guesses = parse_assignments(items, "--guess");
  std::vector<std::string> names;
  for (const auto& c : model.system.variables().coordinates()) names.insert(names.end(), {c.name, c.name + "_dot"});
  for (const auto& [name, value] : guesses) {
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw UsageError(fmt::format("--guess: '{}' is not a coordinate or rate of {}; expected one of {}", name,
                                   model.name, join(names)));
    if (given.count(name))
      throw UsageError(fmt::format("--guess: '{}' is also given in {}; a given value is kept, a guess only starts "
                                   "the solve: give it once",
                                   name, given_option));
  }
  return guesses;
}

std::string matrix_text(const std::string& title, const Eigen::MatrixXd& a) {
  std::string out = fmt::format("{} ({} x {}):", title, a.rows(), a.cols()) + (a.size() == 0 ? " empty" : "") + "\n";
  if (a.size() == 0) return out;
  std::vector<std::size_t> width(static_cast<std::size_t>(a.cols()), 0);
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      width[static_cast<std::size_t>(j)] = std::max(width[static_cast<std::size_t>(j)], number(a(i, j)).size());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    out += "  [";
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      out += (j ? "  " : " ") + fmt::format("{:>{}}", number(a(i, j)), width[static_cast<std::size_t>(j)]);
    out += " ]\n";
  }
  return out;
}

nlohmann::ordered_json json_rows(const Eigen::MatrixXd& a) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (Eigen::Index j = 0; j < a.cols(); ++j) row.push_back(a(i, j));
    out.push_back(row);
  }
  return out;
}

std::string json_document(const nlohmann::ordered_json& j) {
  // a name need not be UTF-8 (a model is named after its file when it has no `model` line), and
  // JSON must be: each byte that starts no UTF-8 character is written as U+FFFD
  const auto dump = [](const nlohmann::ordered_json& value) {
    return value.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  };
  std::string out = "{";
  for (auto it = j.begin(); it != j.end(); ++it)
    out += (it == j.begin() ? "\n  " : ",\n  ") + dump(nlohmann::ordered_json(it.key())) + ": " + dump(it.value());
  return out + "\n}\n";
}

}  // namespace eomgen::tools
