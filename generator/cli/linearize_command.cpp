#include "linearize_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <iostream>

#include "command_values.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/stability_sweep.hpp"
#include "file_output.hpp"
#include "gnuplot.hpp"
#include "model_loading.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

namespace {

using json = nlohmann::ordered_json;

std::string latex_matrix(const Eigen::MatrixXd& a) {
  // an empty bmatrix (B of a model without inputs) would be rows of nothing: say what it is
  if (a.size() == 0) return fmt::format("\\text{{(empty, {} \\times {})}}", a.rows(), a.cols());
  std::string out = "\\begin{bmatrix}\n";
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.cols(); ++j) out += (j ? " & " : "  ") + number(a(i, j));
    out += i + 1 < a.rows() ? " \\\\\n" : "\n";
  }
  return out + "\\end{bmatrix}";
}

std::string complex_number(const std::complex<double>& z) {
  if (z.imag() == 0) return number(z.real());
  return fmt::format("{} {} {}i", number(z.real()), z.imag() < 0 ? "-" : "+", number(std::abs(z.imag())));
}

json json_eigenvalues(const Eigen::VectorXcd& eigenvalues) {
  json out = json::array();
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) out.push_back({eigenvalues(i).real(), eigenvalues(i).imag()});
  return out;
}

std::string assignments(const NamedValues& values, const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const std::string& name : names) out.push_back(fmt::format("{} = {}", name, number(values.at(name))));
  return join(out);
}

std::vector<std::string> names_of(const NamedValues& values) {
  std::vector<std::string> out;
  for (const auto& [name, value] : values) out.push_back(name);
  return out;
}

/// whether the accelerations at the point vanish: the stability theorems are about equilibria
bool is_equilibrium(const LinearModel& lin) {
  const double scale = std::max(1.0, lin.A.cwiseAbs().maxCoeff());
  return lin.qdd0.size() == 0 || lin.qdd0.cwiseAbs().maxCoeff() <= 1e-9 * scale;
}

void emit(const Options& o, const std::string& text) {
  if (o.output_path.empty())
    std::cout << text << std::flush;
  else
    write_atomically(o.output_path, text);
}

// ---- one operating point ----

std::string second_order_title(const Model& model, const LinearModel& lin) {
  if (model.system.constraints().empty())
    return "Second-order form M dqdd + D dqd + K dq = B_u du (all coordinates):\n";
  std::vector<std::string> speeds;
  for (const std::string& q : lin.second_order_coordinates) speeds.push_back(q + "_dot");
  return fmt::format("Second-order form M dqdd + D dqd + K dq = B_u du in {} (reduced: M = G^T M G, G the independent "
                     "speeds' {} columns of the null space of Xi):\n",
                     join(lin.second_order_coordinates), join(speeds));
}

std::string point_text(const Model& model, const NamedValues& given, const LinearModel& lin, const std::string& found,
                       const StabilityReport& report) {
  const bool equilibrium = is_equilibrium(lin);
  std::string out = found;
  out += fmt::format("Linearization of {} about {} (others 0, parameters at their defaults)\n", model.name,
                     given.empty() ? std::string("the origin") : assignments(given, names_of(given)));
  if (!lin.solved.empty()) out += fmt::format("Solved from the constraints: {}\n", assignments(lin.point, lin.solved));
  if (!lin.moved.empty())
    out += fmt::format("Moved onto the constraints (the given values admit no consistent state; each moved the least "
                       "it must): {}\n",
                       describe_moved(lin.moved));
  std::vector<std::string> a;
  for (Eigen::Index i = 0; i < lin.qdd0.size(); ++i) a.push_back(number(lin.qdd0(i)));
  out += fmt::format("Accelerations at the point: [{}]{}\n", join(a),
                     equilibrium ? " (an equilibrium or steady motion)"
                                 : " (not an equilibrium: A linearizes about a point of a trajectory)");
  out += fmt::format("State kept: [{}]; dropped as cyclic: {}\n", join(lin.state_names), join(lin.dropped));
  if (!lin.dependent.empty()) out += fmt::format("Determined by the constraints (not states): {}\n", join(lin.dependent));
  out += fmt::format("Inputs: [{}]\n\n", join(lin.input_names));
  out += matrix_text("A", lin.A) + matrix_text("B", lin.B);
  if (lin.M.size() > 0) {
    out += "\n" + second_order_title(model, lin);
    out += matrix_text("M", lin.M) + matrix_text("D (damping and gyroscopic)", lin.D) +
           matrix_text("K (stiffness)", lin.K) + matrix_text("B_u", lin.B_u);
  } else {
    out += fmt::format("\nSecond-order form: none ({})\n", lin.no_second_order);
  }
  std::vector<std::string> eig;
  for (Eigen::Index i = 0; i < report.eigenvalues.size(); ++i) eig.push_back(complex_number(report.eigenvalues(i)));
  out += fmt::format("\nEigenvalues of A: {}\n", join(eig));
  if (!equilibrium) return out + "Stability: not assessed (the point is not an equilibrium)\n";
  out += fmt::format("Linear system (notes, Theorem A.21): {}\n", to_string(report.linear));
  out += fmt::format("Equilibrium, by Lyapunov's indirect method (Theorem A.22): {}\n", to_string(report.nonlinear));
  return out;
}

std::string point_json(const Model& model, const LinearModel& lin, const StabilityReport& report) {
  const bool equilibrium = is_equilibrium(lin);
  json j;
  j["model"] = model.name;
  json point = json::object();
  for (const auto& [name, value] : lin.point) point[name] = value;
  j["point"] = point;
  j["solved"] = lin.solved;
  json moved = json::array();
  for (const MovedValue& m : lin.moved) moved.push_back({{"name", m.name}, {"given", m.requested}, {"used", m.used}});
  j["moved"] = moved;
  j["qdd0"] = std::vector<double>(lin.qdd0.data(), lin.qdd0.data() + lin.qdd0.size());
  j["equilibrium"] = equilibrium;
  j["states"] = lin.state_names;
  j["dropped"] = lin.dropped;
  j["dependent"] = lin.dependent;
  j["inputs"] = lin.input_names;
  j["A"] = json_rows(lin.A);
  j["B"] = json_rows(lin.B);
  if (lin.M.size() > 0) {
    j["second_order"] = {{"coordinates", lin.second_order_coordinates}, {"M", json_rows(lin.M)},
                         {"D", json_rows(lin.D)}, {"K", json_rows(lin.K)}, {"B_u", json_rows(lin.B_u)}};
  } else {
    j["second_order"] = nullptr;
    j["no_second_order"] = lin.no_second_order;
  }
  j["eigenvalues"] = json_eigenvalues(report.eigenvalues);
  j["linear"] = equilibrium ? json(to_string(report.linear)) : json(nullptr);
  j["nonlinear"] = equilibrium ? json(to_string(report.nonlinear)) : json(nullptr);
  return json_document(j);
}

std::string point_latex(const Model& model, const LinearModel& lin) {
  std::string out = fmt::format("% linearization of {} about {}\n", model.name,
                                assignments(lin.point, names_of(lin.point)));
  out += "A = " + latex_matrix(lin.A) + "\n\nB = " + latex_matrix(lin.B) + "\n\n";
  if (lin.M.size() > 0)
    out += "M = " + latex_matrix(lin.M) + "\n\nD = " + latex_matrix(lin.D) + "\n\nK = " + latex_matrix(lin.K) +
           "\n\nB_u = " + latex_matrix(lin.B_u) + "\n";
  return out;
}

// ---- a sweep ----

/// "NAME=FROM:TO:STEP"
SweepRange parse_sweep(const std::string& text) {
  const auto fail = [&] {
    return UsageError(fmt::format("--sweep: expected NAME=FROM:TO:STEP with finite numbers, got '{}'", text));
  };
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw fail();
  SweepRange range;
  range.name = text.substr(0, eq);
  double* fields[] = {&range.from, &range.to, &range.step};
  std::size_t start = eq + 1;
  for (int k = 0; k < 3; ++k) {
    const std::size_t end = k < 2 ? text.find(':', start) : text.size();
    if (end == std::string::npos) throw fail();
    std::string field = text.substr(start, end - start);
    if (!field.empty() && field[0] == '+') field.erase(0, 1);
    const auto [stop, ec] = std::from_chars(field.data(), field.data() + field.size(), *fields[k]);
    if (field.empty() || ec != std::errc() || stop != field.data() + field.size() || !std::isfinite(*fields[k]))
      throw fail();
    start = end + 1;
  }
  try {
    range.values();  // the range's own checks, as a usage error
  } catch (const Error& e) {
    throw UsageError(fmt::format("--sweep: {}", e.what()));
  }
  return range;
}

/// the swept name must be something the point or the parameters can hold, and not given twice
void check_swept_name(const Model& model, const NamedValues& given, const std::string& name) {
  std::vector<std::string> names{"t"};
  const Variables& v = model.system.variables();
  for (const auto& c : v.coordinates()) names.push_back(c.name), names.push_back(c.name + "_dot");
  for (const auto& u : v.inputs()) names.push_back(u.name);
  for (const auto& p : v.parameters()) names.push_back(p.name);
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    for (const DerivedParameter& d : v.derived_parameters())
      if (d.name == name) throw UsageError("--sweep: " + not_a_parameter(model, name, "--at", "--at"));
    throw UsageError(fmt::format("--sweep: '{}' is not a parameter, coordinate, rate, input or t of {}", name, model.name));
  }
  if (given.count(name)) throw UsageError(fmt::format("--sweep: '{}' is also given in --at or --set", name));
}

std::string verdict(const SweepPoint& p) { return p.equilibrium ? to_string(p.linear) : "not an equilibrium"; }

std::string changes_text(const StabilitySweep& sweep) {
  if (sweep.changes.empty()) return "Stability changes: none in the range\n";
  std::string out = "Stability changes (located by bisection):\n";
  for (const StabilityChange& c : sweep.changes)
    out += fmt::format("  {} = {:.12g}: {} -> {}\n", sweep.name, c.value, to_string(c.below), to_string(c.above));
  return out;
}

std::string sweep_text(const Model& model, const SweepRange& range, const StabilitySweep& sweep) {
  std::string out = fmt::format("Stability of {} against {} from {} to {} in steps of {}\n", model.name, range.name,
                                number(range.from), number(range.to), number(range.step));
  for (const SweepPoint& p : sweep.points) {
    std::vector<std::string> eig;
    for (Eigen::Index i = 0; i < p.eigenvalues.size(); ++i) eig.push_back(complex_number(p.eigenvalues(i)));
    out += fmt::format("  {} = {}: {}; eigenvalues {}\n", range.name, number(p.value), verdict(p), join(eig));
  }
  return out + changes_text(sweep);
}

Eigen::Index most_eigenvalues(const StabilitySweep& sweep) {
  Eigen::Index most = 0;
  for (const SweepPoint& p : sweep.points) most = std::max(most, p.eigenvalues.size());
  return most;
}

/// value, verdict, then Re and Im of each eigenvalue in assess_stability's order (by real part)
std::string sweep_csv(const StabilitySweep& sweep) {
  const Eigen::Index most = most_eigenvalues(sweep);
  std::string out = sweep.name + ",verdict";
  for (Eigen::Index k = 1; k <= most; ++k) out += fmt::format(",re{0},im{0}", k);
  out += "\n";
  for (const SweepPoint& p : sweep.points) {
    out += number(p.value) + "," + verdict(p);
    for (Eigen::Index k = 0; k < most; ++k)
      out += k < p.eigenvalues.size()
                 ? fmt::format(",{},{}", number(p.eigenvalues(k).real()), number(p.eigenvalues(k).imag()))
                 : std::string(",,");
    out += "\n";
  }
  return out;
}

std::string sweep_json(const Model& model, const StabilitySweep& sweep) {
  json points = json::array();
  for (const SweepPoint& p : sweep.points)
    points.push_back({{"value", p.value}, {"verdict", verdict(p)}, {"states", p.state_names},
                      {"eigenvalues", json_eigenvalues(p.eigenvalues)}});
  json changes = json::array();
  for (const StabilityChange& c : sweep.changes)
    changes.push_back({{"value", c.value}, {"below", to_string(c.below)}, {"above", to_string(c.above)}});
  json j;
  j["model"] = model.name;
  j["swept"] = sweep.name;
  j["points"] = points;
  j["changes"] = changes;
  return json_document(j);
}

/// the classic figure: real parts (filled) and nonzero imaginary parts (open) of every
/// eigenvalue against the swept value, the changes of verdict as labelled vertical lines
std::string sweep_plot_script(const Model& model, const StabilitySweep& sweep, const std::string& image,
                              const std::string& plot_path) {
  const Eigen::Index most = most_eigenvalues(sweep);
  std::string s = gnuplot_terminal(plot_path, 1000, 650);
  s += "set output " + gnuplot_path(image) + "\n";
  s += "$eigenvalues << EOD\n";
  for (const SweepPoint& p : sweep.points) {
    s += fmt::format("{:.17g}", p.value);
    for (Eigen::Index k = 0; k < most; ++k)
      s += k < p.eigenvalues.size() ? fmt::format(" {:.17g} {:.17g}", p.eigenvalues(k).real(), p.eigenvalues(k).imag())
                                    : std::string(" NaN NaN");
    s += "\n";
  }
  s += "EOD\n";
  s += "set title " + gnuplot_text(fmt::format("{}: eigenvalues against {}", model.name, sweep.name)) + "\n";
  s += "set xlabel " + gnuplot_text(sweep.name) + "\nset ylabel 'eigenvalue [1/s]'\nset grid\n";
  s += "set key inside left bottom opaque box\nset xzeroaxis lt -1\n";
  for (const StabilityChange& c : sweep.changes) {
    s += fmt::format("set arrow from {0:.17g}, graph 0 to {0:.17g}, graph 1 nohead dt 2 lc rgb 'gray40'\n", c.value);
    s += fmt::format("set label {} at {:.17g}, graph 0.96 left offset 0.5,0\n", gnuplot_text(fmt::format("{:.6g}", c.value)),
                     c.value);
  }
  s += fmt::format("plot for [k=1:{0}] $eigenvalues using 1:(column(2*k)) with points pt 7 ps 0.4 lc rgb '#1f5fbf' "
                   "title (k == 1 ? 'real part' : ''), \\\n"
                   "     for [k=1:{0}] $eigenvalues using 1:(column(2*k+1) != 0 ? column(2*k+1) : NaN) with points "
                   "pt 6 ps 0.4 lc rgb '#d9541e' title (k == 1 ? 'imaginary part (where not 0)' : '')\n",
                   most);
  return s + "set output\n";
}

int run_sweep(const Options& o, const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
               const NamedValues& given, const SweepRange& range, const LinearizeOptions& options) {
  const StabilitySweep sweep = sweep_stability(model, eom, symbolic, given, range, options);
  const std::string document = o.format == "json" ? sweep_json(model, sweep)
                               : o.format == "csv" ? sweep_csv(sweep)
                                                   : sweep_text(model, range, sweep);
  emit(o, document);
  // the changes belong with a written file or a CSV too; not in the middle of the CSV's rows
  if (o.format == "csv" || !o.output_path.empty())
    (o.output_path.empty() ? std::cerr : std::cout) << changes_text(sweep);
  if (!o.output_path.empty()) std::cout << fmt::format("{}: {}\n", o.format, o.output_path);
  if (!o.sweep_plot.empty()) {
    std::cout << std::flush;
    try {
      plot_with_gnuplot(o.sweep_plot,
                        [&](const std::string& image) { return sweep_plot_script(model, sweep, image, o.sweep_plot); });
    } catch (const Error& e) {
      return report_plot_failure(o.sweep_plot,
                                 o.output_path.empty() ? "the sweep printed above"
                                                       : fmt::format("the sweep's {} '{}'", o.format, o.output_path),
                                 e);
    }
    std::cout << fmt::format("plot: {}\n", o.sweep_plot);
  }
  return 0;
}

}  // namespace

int run_linearize(const Options& o) {
  check_output_files({{"-o", o.output_path}, {"--plot", o.sweep_plot}}, o.model_path);
  const Model model = load_command_model(o);
  const NamedValues given = state_and_parameters(o.at, o.set, model);
  if (o.sweep.empty() && !o.sweep_plot.empty()) throw UsageError("--plot: plots a sweep; give --sweep too");
  if (o.sweep.empty() && o.format == "csv") throw UsageError("--format csv: a table of a sweep; give --sweep too");
  if (!o.sweep.empty() && o.find_equilibrium)
    throw UsageError("--equilibrium: not with --sweep (each point of a sweep is taken as given)");
  // the whole request is checked before the derivation, which takes the time
  SweepRange range;
  if (!o.sweep.empty()) {
    range = parse_sweep(o.sweep);
    check_swept_name(model, given, range.name);
    if (o.format == "latex") throw UsageError("--format latex: a sweep is printed as text, json or csv");
    if (!o.sweep_plot.empty()) require_plot_target(o.sweep_plot, "--plot", "leave out --plot");
  }
  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization symbolic = linearize_symbolic(model, eom);
  LinearizeOptions options;
  options.drop_cyclic = o.drop_cyclic;
  options.guesses = state_guesses(o.guesses, given, "--at", model);
  if (!o.sweep.empty()) return run_sweep(o, model, eom, symbolic, given, range, options);

  NamedValues at = given;
  std::string found;
  if (o.find_equilibrium) {
    NamedValues guess = given;
    guess.insert(options.guesses.begin(), options.guesses.end());
    const Equilibrium eq = find_equilibrium(model, eom, symbolic, guess);
    at = eq.point;
    std::vector<std::string> q;
    for (const auto& c : model.system.variables().coordinates()) q.push_back(fmt::format("{} = {}", c.name, number(at.at(c.name))));
    found = fmt::format("Equilibrium found from the guess by Newton's method in {} iterations: {} (residual {:.3g})\n",
                        eq.iterations, join(q), eq.residual);
  }
  const LinearModel lin = linearize(model, eom, symbolic, at, options);
  const StabilityReport report = assess_stability(lin.A);
  if (o.format == "latex")
    emit(o, point_latex(model, lin));
  else if (o.format == "json")
    emit(o, point_json(model, lin, report));
  else
    emit(o, point_text(model, at, lin, found, report));
  return 0;
}

}  // namespace eomgen::tools
