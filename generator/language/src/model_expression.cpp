// Evaluation of model-file expressions into scalars, physical vectors, columns and matrices.
#include <fmt/format.h>

#include <cmath>

#include <algorithm>
#include <array>
#include <map>
#include <optional>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/mechanics/lean_products.hpp"
#include "model_elaborator.hpp"
#include "model_matrices.hpp"

namespace eomgen::syntax {
namespace {

using GiNaC::ex;

const std::vector<std::string> scalar_functions = {"sin",  "cos",  "tan",  "asin", "acos", "atan", "atan2",
                                                   "sinh", "cosh", "tanh", "sqrt", "exp",  "log",  "abs"};
const std::vector<std::string> other_functions = {"dot",      "norm",        "cross",     "unit", "position",
                                                  "velocity", "angular_velocity", "diag", "transpose", "dcm"};
// dcm is one only with a matrix: dcm(B, A) of two frames is a matrix (call())
const std::vector<std::string> frame_functions = {"rotate", "euler", "axis_angle", "quaternion", "rodrigues", "mrp"};

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// exact rational from decimal text, so 0.1 stays 1/10 in the equations
GiNaC::numeric exact_number(const std::string& text) {
  std::string digits;
  long exponent = 0;
  std::size_t i = 0;
  for (; i < text.size() && text[i] != 'e' && text[i] != 'E'; ++i) {
    if (text[i] == '.') continue;
    digits += text[i];
  }
  const auto dot = text.find('.');
  if (dot != std::string::npos) exponent -= static_cast<long>(std::min(i, text.size()) - dot - 1);
  if (i < text.size()) {
    // GiNaC would happily build 10^999999999; anything beyond a double's range is a typo
    const long written = std::stol(text.substr(i + 1));  // std::out_of_range for absurd lengths
    if (written < -400 || written > 400) throw std::out_of_range("exponent");
    exponent += written;
  }
  return GiNaC::numeric(digits.c_str()) * GiNaC::pow(GiNaC::numeric(10), GiNaC::numeric(exponent));
}

// The largest exponent on an expression that varies: see check_exponents.
constexpr int max_exponent = 100;

// Bits of an exact number: what an exact power of it multiplies by its exponent.
double exact_bits(const GiNaC::numeric& x) {
  if (!x.is_real()) return exact_bits(x.real()) + exact_bits(x.imag());
  if (!x.is_rational()) return 0;  // a float: CLN raises it in constant time
  return static_cast<double>(GiNaC::numer(x).int_length() + GiNaC::denom(x).int_length());
}

// GiNaC raises numbers exactly, so 2.5^1000000000 would take hours and 10^1000000 megabytes.
// Beyond a double's range (either way) the power is refused; a huge exact power within it
// (1.0000001^1000000000) is taken in floating point.
std::optional<ex> bounded_numeric_power(const GiNaC::numeric& base, const GiNaC::numeric& exponent,
                                        const SourceLocation& at) {
  const GiNaC::numeric magnitude = GiNaC::abs(base);
  if (base.is_zero() || magnitude == 1 || !exponent.is_real()) return std::nullopt;
  const double exponent_size = std::fabs(exponent.to_double());
  if (exact_bits(base) * exponent_size <= 65536) return std::nullopt;
  const double decimal_exponent = exponent.to_double() * std::log10(magnitude.to_double());
  if (!std::isfinite(decimal_exponent) || std::fabs(decimal_exponent) > 300)
    throw SourceError(at, fmt::format("the power is about 10^{:.0f}, beyond the range of a double: expected a "
                                      "smaller exponent", decimal_exponent));
  return ex(GiNaC::pow(GiNaC::ex_to<GiNaC::numeric>(base.evalf()), exponent));
}

// A power of something that varies is expanded and differentiated by the derivation, whose work
// grows with the exponent: sin(q)^10000 takes half a minute, (q+1)^100000 hours. Products merge
// powers of one base (x^80 * x^80 is x^160), so a product's factors are checked too.
void check_exponents(const ex& value, const SourceLocation& at) {
  auto check = [&](const ex& factor) {
    if (!GiNaC::is_a<GiNaC::power>(factor) || GiNaC::is_a<GiNaC::numeric>(factor.op(0))) return;
    const ex exponent = factor.op(1);
    if (GiNaC::is_a<GiNaC::numeric>(exponent) && GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(exponent)) > max_exponent)
      throw SourceError(at, fmt::format("the exponent {:g} on an expression that is not a number is out of range: expected "
                                        "an exponent between -{} and {}", GiNaC::ex_to<GiNaC::numeric>(exponent).to_double(),
                                        max_exponent, max_exponent));
  };
  check(value);
  if (GiNaC::is_a<GiNaC::mul>(value))
    for (const ex& factor : value) check(factor);
}

}  // namespace

std::string kind_name(Value::Kind kind) {
  switch (kind) {
    case Value::Kind::scalar: return "a scalar";
    case Value::Kind::vector: return "a vector";
    case Value::Kind::column: return "a column [x, y, z]";
    case Value::Kind::matrix: return "a matrix";
  }
  EOMGEN_UNREACHABLE("kind_name: a Value::Kind outside its enumerators");
}

void Elaborator::unknown_name(const std::string& name, const SourceLocation& at,
                              const std::vector<std::string>& candidates, const std::string& what) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  throw SourceError(at, best.empty() ? fmt::format("unknown {} '{}'", what, name)
                                     : fmt::format("unknown {} '{}'; did you mean '{}'?", what, name, best));
}

std::string Elaborator::resolve(const Name& name, const Environment& env) {
  std::string out;
  for (const auto& piece : name.pieces) {
    if (!piece.index) {
      out += piece.literal;
      continue;
    }
    // q{i-1} at i = 0 would give "q-1", which is no identifier (and no valid C++ name later)
    const int index = integer(piece.index, env, "an index in a name");
    if (index < 0)
      throw SourceError(start_of(*piece.index), fmt::format("an index in a name: expected 0 or more, got {}", index));
    out += std::to_string(index);
  }
  return out;
}

GiNaC::numeric Elaborator::constant(const ExprPtr& e, const Environment& env, const std::string& what) {
  const ex value = scalar(e, env, what).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(scalar(e, env, what)) && !GiNaC::is_a<GiNaC::numeric>(value))
    throw SourceError(start_of(*e), fmt::format("{}: expected a constant (numbers and consts only)", what));
  const ex exact = scalar(e, env, what);
  const GiNaC::numeric n = GiNaC::ex_to<GiNaC::numeric>(GiNaC::is_a<GiNaC::numeric>(exact) ? exact : value);
  // sqrt(-1) is a number to GiNaC, and its double would be the real part, 0
  if (!n.is_real())
    throw SourceError(start_of(*e), fmt::format("{}: expected a real number, got a complex one ({} + {}*I)", what,
                                                n.real().to_double(), n.imag().to_double()));
  if (!std::isfinite(n.to_double()))
    throw SourceError(start_of(*e), fmt::format("{}: the value is too large for a double", what));
  return n;
}

int Elaborator::integer(const ExprPtr& e, const Environment& env, const std::string& what) {
  const GiNaC::numeric n = constant(e, env, what);
  if (!n.is_integer())
    throw SourceError(start_of(*e), fmt::format("{}: expected an integer, got {}", what, n.to_double()));
  // to_int() silently wraps beyond 32 bits
  if (GiNaC::abs(n) > 1000000000)
    throw SourceError(start_of(*e), fmt::format("{}: expected an integer between -10^9 and 10^9", what));
  return n.to_int();
}

ex Elaborator::scalar(const ExprPtr& e, const Environment& env, const std::string& what) {
  Value v = evaluate(e, env);
  if (v.kind != Value::Kind::scalar)
    throw SourceError(start_of(*e), fmt::format("{}: expected a scalar, got {}", what, kind_name(v.kind)));
  return v.scalar;
}

eomgen::Vector Elaborator::vector(const ExprPtr& e, const Environment& env, const std::string& what) {
  Value v = evaluate(e, env);
  if (v.kind != Value::Kind::vector)
    throw SourceError(start_of(*e), fmt::format("{}: expected a vector (such as g*a.3 or [x, y, z] in b), got {}",
                                               what, kind_name(v.kind)));
  return v.vector;
}

FrameId Elaborator::frame_named(const Name& name, const Environment& env) {
  const std::string n = resolve(name, env);
  if (!parameters_in_progress_.empty()) reject_in_parameter("frame", n, name.location);
  auto it = frames_.find(n);
  if (it != frames_.end()) return it->second;
  // statements come in any order: a frame named before its definition is built first
  if (frame_instances_.count(n)) return build_frame(n);
  std::vector<std::string> known;
  for (const auto& [k, v] : frames_) known.push_back(k);
  for (const auto& [k, v] : frame_instances_) known.push_back(k);
  unknown_name(n, name.location, known, "frame");
}

PointId Elaborator::point_named(const Name& name, const Environment& env) {
  const std::string n = resolve(name, env);
  if (!parameters_in_progress_.empty()) reject_in_parameter("point", n, name.location);
  auto it = points_.find(n);
  if (it != points_.end()) return it->second;
  if (point_instances_.count(n)) return build_point(n);
  std::vector<std::string> known;
  for (const auto& [k, v] : points_) known.push_back(k);
  for (const auto& [k, v] : point_instances_) known.push_back(k);  // defined later in the file
  unknown_name(n, name.location, known, "point");
}

Value Elaborator::name_value(const Expr& e, const Environment& env) {
  const std::string n = resolve(e.name, env);
  if (auto it = env.find(n); it != env.end()) return Value::of(ex(it->second));
  if (auto it = constants_.find(n); it != constants_.end()) return Value::of(it->second);
  if (n == "pi") return Value::of(GiNaC::Pi);
  if (parameter_instances_.count(n)) return Value::of(parameter_value(n));
  const Variables& vars = model_.system.variables();
  if (auto symbol = vars.find(n)) {
    const auto kind = vars.kind_of(*symbol);
    if (!parameters_in_progress_.empty()) reject_in_parameter(declared_.at(n).kind, n, e.location);
    if (kind == SymbolKind::acceleration)
      throw SourceError(e.location, fmt::format("'{}' is an acceleration; accelerations may not appear in a model "
                                                "(the equations of motion give them): expected coordinates and "
                                                "rates only", n));
    if (kind == SymbolKind::coordinate || kind == SymbolKind::rate)
      used_coordinates_.insert(vars.coordinates()[*vars.coordinate_index(*symbol)].name);
    return Value::of(ex(*symbol));
  }
  if (auto it = declared_.find(n); it != declared_.end()) {
    if (!parameters_in_progress_.empty()) reject_in_parameter(it->second.kind, n, e.location);
    throw SourceError(e.location, fmt::format("expected a scalar or a vector, got the {} '{}'{}", it->second.kind, n,
                                              it->second.kind == "frame"
                                                  ? fmt::format(" (its basis vectors are {0}.1, {0}.2, {0}.3)", n)
                                                  : ""));
  }
  std::vector<std::string> known = {"t", "pi"};
  for (const auto& [k, v] : env) known.push_back(k);
  for (const auto& [k, v] : constants_) known.push_back(k);
  for (const auto& [k, v] : declared_) known.push_back(k);
  for (const auto& c : vars.coordinates()) known.push_back(c.qd.get_name());
  unknown_name(n, e.location, known, "name");
}

Value Elaborator::call(const Expr& e, const Environment& env) {
  const std::string f = resolve(e.name, env);
  auto arity = [&](std::size_t lo, std::size_t hi) {
    if (e.args.size() < lo || e.args.size() > hi)
      throw SourceError(e.location, lo == hi ? fmt::format("{}() takes {} argument{}, got {}", f, lo, lo == 1 ? "" : "s", e.args.size())
                                             : fmt::format("{}() takes {} to {} arguments, got {}", f, lo, hi, e.args.size()));
  };
  auto arg_scalar = [&](std::size_t i) { return scalar(e.args[i], env, fmt::format("argument {} of {}()", i + 1, f)); };
  auto arg_vector = [&](std::size_t i) { return vector(e.args[i], env, fmt::format("argument {} of {}()", i + 1, f)); };
  auto arg_name = [&](std::size_t i) -> const Name& {
    if (e.args[i]->kind != Expr::Kind::name)
      throw SourceError(e.args[i]->location, fmt::format("argument {} of {}(): expected a name", i + 1, f));
    return e.args[i]->name;
  };
  // a position or an attitude may not depend on rates
  auto need_kinematics = [&] {
    if (!kinematics_ready_)
      throw SourceError(e.location, fmt::format("{}() may not be used in frame or point definitions: a position or "
                                                "an attitude depends on coordinates and time, not on rates", f));
  };
  const MechanicalSystem& s = model_.system;
  if (std::find(scalar_functions.begin(), scalar_functions.end(), f) != scalar_functions.end()) try {
    if (f == "atan2") {
      arity(2, 2);
      return Value::of(GiNaC::atan2(arg_scalar(0), arg_scalar(1)));
    }
    arity(1, 1);
    const ex x = arg_scalar(0);
    if (f == "sin") return Value::of(GiNaC::sin(x));
    if (f == "cos") return Value::of(GiNaC::cos(x));
    if (f == "tan") return Value::of(GiNaC::tan(x));
    if (f == "asin") return Value::of(GiNaC::asin(x));
    if (f == "acos") return Value::of(GiNaC::acos(x));
    if (f == "atan") return Value::of(GiNaC::atan(x));
    if (f == "sinh") return Value::of(GiNaC::sinh(x));
    if (f == "cosh") return Value::of(GiNaC::cosh(x));
    if (f == "tanh") return Value::of(GiNaC::tanh(x));
    if (f == "sqrt") return Value::of(GiNaC::sqrt(x));
    if (f == "exp") return Value::of(GiNaC::exp(x));
    if (f == "log") return Value::of(GiNaC::log(x));
    return Value::of(GiNaC::abs(x));
  } catch (const GiNaC::pole_error&) {
    // GiNaC evaluates log(0), tan(pi/2)... eagerly and throws; that is an error in the file
    throw SourceError(e.location, fmt::format("{}() is infinite at this argument: expected an argument where it is "
                                              "finite", f));
  }
  if (f == "diag") {
    arity(3, 3);
    Value v;
    v.kind = Value::Kind::matrix;
    v.matrix = GiNaC::matrix(3, 3);
    for (unsigned i = 0; i < 3; ++i) v.matrix(i, i) = arg_scalar(i);
    return v;
  }
  if (f == "transpose") {
    arity(1, 1);
    const Value m = evaluate(e.args[0], env);
    if (!has_shape(m))
      throw SourceError(start_of(*e.args[0]), fmt::format("argument 1 of transpose(): expected a matrix or a column, "
                                                          "got {}", kind_name(m.kind)));
    return transposed(m);
  }
  if (f == "dcm") {
    // dcm(PARENT, MATRIX) defines a frame (build_frame); in an expression only two frames make sense
    arity(2, 2);
    for (std::size_t i = 0; i < 2; ++i)
      if (e.args[i]->kind != Expr::Kind::name)
        throw SourceError(start_of(*e.args[i]), fmt::format("argument {} of dcm(): expected a frame: dcm(B, A) is the "
                                                            "matrix C_BA of two frames (dcm(PARENT, MATRIX) defines "
                                                            "a frame: 'frame NAME = dcm(...)')", i + 1));
    return Value::of_matrix(eomgen::dcm(s, frame_named(arg_name(0), env), frame_named(arg_name(1), env)));
  }
  // in a definition, the lean forms: a position or an attitude enters every later derivation,
  // whereas elsewhere (loads, constraints, outputs of large models) simplifying would cost more
  // than it saves
  const bool lean = !kinematics_ready_;
  if (f == "dot" || f == "cross") {
    arity(2, 2);
    const eomgen::Vector u = arg_vector(0), v = arg_vector(1);
    if (f == "dot") return Value::of(lean ? lean_dot(s, u, v) : eomgen::dot(s, u, v));
    return Value::of(lean ? lean_cross(s, u, v) : eomgen::cross(s, u, v));
  }
  if (f == "norm") {
    arity(1, 1);
    const eomgen::Vector u = arg_vector(0);
    return Value::of(lean ? lean_norm(s, u) : GiNaC::sqrt(eomgen::dot(s, u, u)));
  }
  if (f == "unit") {
    arity(1, 1);
    const eomgen::Vector u = arg_vector(0);
    const ex length = lean_norm(s, u);
    reject_zero_vector(u, length, start_of(*e.args[0]), "unit()");
    return Value::of(ex(1) / length * u);
  }
  if (f == "position") {
    arity(1, 2);
    const PointId p = point_named(arg_name(0), env);
    return Value::of(eomgen::position(s, p, e.args.size() == 2 ? point_named(arg_name(1), env) : s.origin()));
  }
  if (f == "velocity") {
    arity(1, 1);
    need_kinematics();
    return Value::of(eomgen::velocity(s, point_named(arg_name(0), env)));
  }
  if (f == "angular_velocity") {
    arity(1, 2);
    need_kinematics();
    const FrameId b = frame_named(arg_name(0), env);
    return Value::of(eomgen::angular_velocity(s, b, e.args.size() == 2 ? frame_named(arg_name(1), env) : s.inertial_frame()));
  }
  if (std::find(frame_functions.begin(), frame_functions.end(), f) != frame_functions.end())
    throw SourceError(e.location, fmt::format("{}() defines a frame: use it as 'frame NAME = {}(...)'", f, f));
  std::vector<std::string> known = scalar_functions;
  known.insert(known.end(), other_functions.begin(), other_functions.end());
  unknown_name(f, e.location, known, "function");
}

// a + b - c ...: the terms are collected and summed once, per frame for vectors and per entry for
// matrices, because adding them one by one re-sorts a growing sum each time (quadratic in a long sum)
Value Elaborator::sum(const Expr& e, const Environment& env) {
  using K = Value::Kind;
  const Value first = evaluate(e.args[0], env);
  const unsigned rows = has_shape(first) ? first.matrix.rows() : 0;
  const unsigned cols = has_shape(first) ? first.matrix.cols() : 0;
  GiNaC::exvector scalar_terms;
  std::map<FrameId, std::array<GiNaC::exvector, 3>> vector_terms;
  std::vector<GiNaC::exvector> entry_terms(rows * cols);  // row by row
  auto collect = [&](const Value& v, bool negated) {
    auto signed_term = [&](const ex& term) { return negated ? -term : term; };
    switch (v.kind) {
      case K::scalar: scalar_terms.push_back(signed_term(v.scalar)); return;
      case K::vector:
        for (const auto& [frame, components] : v.vector.terms())
          for (unsigned i = 0; i < 3; ++i) vector_terms[frame][i].push_back(signed_term(components(i, 0)));
        return;
      case K::column:
      case K::matrix:
        for (unsigned i = 0; i < rows; ++i)
          for (unsigned j = 0; j < cols; ++j) entry_terms[i * cols + j].push_back(signed_term(v.matrix(i, j)));
        return;
    }
  };
  collect(first, false);
  for (std::size_t k = 1; k < e.args.size(); ++k) {
    const Expr::Operation& op = e.operations[k - 1];
    const Value v = evaluate(e.args[k], env);
    const char* operation = op.inverse ? "subtract" : "add";
    if (v.kind != first.kind && !(has_shape(v) && has_shape(first)))
      throw SourceError(op.location, fmt::format("cannot {} {} and {}", operation, shape_name(first), shape_name(v)));
    if (has_shape(v) && (v.matrix.rows() != rows || v.matrix.cols() != cols))
      throw SourceError(op.location, fmt::format("cannot {} {} and {}: expected the same shape, {}x{}", operation,
                                                 shape_name(first), shape_name(v), rows, cols));
    collect(v, op.inverse);
  }
  switch (first.kind) {
    case K::scalar: return Value::of(ex(GiNaC::add(scalar_terms)));
    case K::vector: {
      eomgen::Vector total;
      for (const auto& [frame, c] : vector_terms)
        total += eomgen::Vector(frame, GiNaC::add(c[0]), GiNaC::add(c[1]), GiNaC::add(c[2]));
      return Value::of(total);
    }
    case K::column:
    case K::matrix: {
      GiNaC::matrix total(rows, cols);
      for (unsigned i = 0; i < rows; ++i)
        for (unsigned j = 0; j < cols; ++j) total(i, j) = GiNaC::add(entry_terms[i * cols + j]);
      return Value::of_matrix(total);
    }
  }
  EOMGEN_UNREACHABLE("sum: a Value::Kind outside its enumerators");
}

// a * b / c ...: scalar factors collected and multiplied once, and either at most one vector or the
// columns and matrices multiplied in their order (their products do not commute)
Value Elaborator::product(const Expr& e, const Environment& env) {
  using K = Value::Kind;
  GiNaC::exvector factors;
  std::optional<eomgen::Vector> vector_factor;
  std::optional<Value> matrix_factor;  // the product of the columns and matrices so far
  for (std::size_t k = 0; k < e.args.size(); ++k) {
    const Value v = evaluate(e.args[k], env);
    const SourceLocation& at = k == 0 ? e.location : e.operations[k - 1].location;
    if (k > 0 && e.operations[k - 1].inverse) {
      if (v.kind != K::scalar) throw SourceError(at, fmt::format("cannot divide by {}", shape_name(v)));
      if (v.scalar.is_zero()) throw SourceError(at, "division by zero");
      factors.push_back(GiNaC::pow(v.scalar, -1));
      continue;
    }
    switch (v.kind) {
      case K::scalar: factors.push_back(v.scalar); break;
      case K::vector:
        if (vector_factor) throw SourceError(at, "cannot multiply two vectors: use dot(u, v) or cross(u, v)");
        if (matrix_factor)
          throw SourceError(at, fmt::format("cannot multiply {} and a vector: expected a scalar, a column or a "
                                            "matrix", shape_name(*matrix_factor)));
        vector_factor = v.vector;
        break;
      case K::column:
      case K::matrix:
        if (vector_factor)
          throw SourceError(at, fmt::format("cannot multiply a vector and {}: expected a scalar", shape_name(v)));
        if (!matrix_factor) {
          matrix_factor = v;
          break;
        }
        if (Value p = matrix_product(*matrix_factor, v, at); p.kind == K::scalar) {
          factors.push_back(p.scalar);  // a row times a column
          matrix_factor.reset();
        } else {
          matrix_factor = std::move(p);
        }
        break;
    }
  }
  const ex scale = GiNaC::mul(factors);
  check_exponents(scale, e.location);
  if (vector_factor) return Value::of(scale * *vector_factor);
  if (matrix_factor) return Value::of_matrix(matrix_factor->matrix.mul_scalar(scale));
  return Value::of(scale);
}

Value Elaborator::evaluate(const ExprPtr& ptr, const Environment& env) {
  const Expr& e = *ptr;
  using K = Value::Kind;
  switch (e.kind) {
    case Expr::Kind::number:
      try {
        return Value::of(ex(exact_number(e.number_text)));
      } catch (const std::out_of_range&) {
        throw SourceError(e.location, fmt::format("number '{}' is out of range: expected an exponent between -400 "
                                                  "and 400", e.number_text));
      }
    case Expr::Kind::name:
      return name_value(e, env);
    case Expr::Kind::call:
      return call(e, env);
    case Expr::Kind::negate: {
      Value v = evaluate(e.args[0], env);
      if (v.kind == K::scalar) return Value::of(-v.scalar);
      if (v.kind == K::vector) return Value::of(-v.vector);
      return Value::of_matrix(v.matrix.mul_scalar(-1));
    }
    case Expr::Kind::sum:
      return sum(e, env);
    case Expr::Kind::product:
      return product(e, env);
    case Expr::Kind::power: {
      const Value a = evaluate(e.args[0], env);
      // M^T: a matrix has no other exponent, so T here is the transpose whatever else it names
      const Expr& exponent = *e.args[1];
      if (has_shape(a) && exponent.kind == Expr::Kind::name && exponent.name.is_plain() && exponent.name.plain() == "T")
        return transposed(a);
      if (a.kind != K::scalar) throw non_scalar_power(a, nullptr, e.location);
      const Value b = evaluate(e.args[1], env);
      if (b.kind != K::scalar) throw non_scalar_power(a, &b, e.location);
      // GiNaC evaluates 0^-k eagerly and throws from inside pow(), leaking the half-built
      // power: reject it before GiNaC sees it
      if (a.scalar.is_zero() && GiNaC::is_a<GiNaC::numeric>(b.scalar) &&
          GiNaC::ex_to<GiNaC::numeric>(b.scalar).is_negative())
        throw SourceError(e.location, "zero raised to a negative power: expected a non-zero base");
      if (GiNaC::is_a<GiNaC::numeric>(a.scalar) && GiNaC::is_a<GiNaC::numeric>(b.scalar))
        if (auto p = bounded_numeric_power(GiNaC::ex_to<GiNaC::numeric>(a.scalar), GiNaC::ex_to<GiNaC::numeric>(b.scalar),
                                           e.location))
          return Value::of(*p);
      try {
        const ex power = GiNaC::pow(a.scalar, b.scalar);
        check_exponents(power, e.location);
        return Value::of(power);
      } catch (const GiNaC::pole_error&) {  // 0^-1 is evaluated (and thrown) eagerly
        throw SourceError(e.location, "zero raised to a negative power: expected a non-zero base");
      }
    }
    case Expr::Kind::list: {
      std::vector<Value> items;
      for (const auto& item : e.args) items.push_back(evaluate(item, env));
      Value v;
      if (!items.empty() && std::all_of(items.begin(), items.end(), [](const Value& x) { return x.kind == K::scalar; })) {
        v.kind = K::column;
        v.matrix = GiNaC::matrix(static_cast<unsigned>(items.size()), 1);
        for (unsigned i = 0; i < items.size(); ++i) v.matrix(i, 0) = items[i].scalar;
        return v;
      }
      if (!items.empty() && std::all_of(items.begin(), items.end(), [&](const Value& x) {
            return x.kind == K::column && x.matrix.rows() == items[0].matrix.rows();
          })) {
        v.kind = K::matrix;
        v.matrix = GiNaC::matrix(static_cast<unsigned>(items.size()), items[0].matrix.rows());
        for (unsigned i = 0; i < items.size(); ++i)
          for (unsigned j = 0; j < items[0].matrix.rows(); ++j) v.matrix(i, j) = items[i].matrix(j, 0);
        return v;
      }
      throw SourceError(e.location, "expected a list of scalars [x, y, z] or of equally long rows [[...], [...]]");
    }
    case Expr::Kind::in_frame: {
      const Value list = evaluate(e.args[0], env);
      if (list.kind != K::column || list.matrix.rows() != 3)
        throw SourceError(e.location, "expected three scalar components before 'in': [x, y, z] in FRAME");
      return Value::of(eomgen::Vector(frame_named(e.name, env), list.matrix));
    }
    case Expr::Kind::basis: {
      GiNaC::matrix unit(3, 1);
      unit(e.basis_index - 1, 0) = 1;
      return Value::of(eomgen::Vector(frame_named(e.name, env), unit));
    }
    case Expr::Kind::text:
      throw SourceError(e.location, fmt::format("expected an expression, got the string \"{}\" (only a mesh's 'file' "
                                                "is a string)", e.number_text));
  }
  EOMGEN_UNREACHABLE("evaluate: an Expr::Kind outside its enumerators");
}

}  // namespace eomgen::syntax
