#include "eomgen/codegen/lower.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "eomgen/base/error.hpp"
#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using ir::Op;

// A node of the shared graph before it is put in emission order.
struct Node {
  Op op;
  std::vector<std::size_t> args;
  double number = 0.0;
  ir::Variable variable;        // Op::variable
  std::string name;             // Op::variable: its name in the signature
  std::uint64_t signature = 0;  // from content only: names, values, structure
};

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  // FNV-1a over the 8 bytes of v
  for (int i = 0; i < 8; ++i) {
    h ^= (v >> (8 * i)) & 0xffu;
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t mix(std::uint64_t h, const std::string& s) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return mix(h, s.size());
}

bool commutative(Op op) { return op == Op::add || op == Op::multiply; }

// the op's number in content signatures: fixed per op, so reordering or extending Op leaves
// the order of operands, and so every generated header, as it is
std::uint64_t signature_code(Op op) {
  switch (op) {
    case Op::number: return 0;
    case Op::variable: return 1;
    case Op::add: return 2;
    case Op::multiply: return 3;
    case Op::divide: return 4;
    case Op::negate: return 5;
    EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE) return ir::call_op(op).code;
  }
  EOMGEN_UNREACHABLE("an ir::Op value that is not an enumerator");
}

class Lowering {
 public:
  Lowering(const std::vector<const Subexpressions*>& sets, const VariableNames& variables) : variables_(variables) {
    for (const Subexpressions* z : sets)
      for (const auto& d : z->definitions()) definitions_.emplace(d.symbol, d.value);
  }

  std::size_t node(const ex& e) {
    if (const std::size_t* known = memo_.find(e)) return *known;
    const std::size_t id = build(e);
    memo_.emplace(e, id);
    return id;
  }

  ir::Program finish(const std::vector<std::pair<ir::Target, std::size_t>>& outputs) {
    // emission order: depth-first from the outputs in their order, arguments in canonical order
    std::vector<std::size_t> order(nodes_.size(), SIZE_MAX);
    ir::Program program;
    std::vector<std::pair<std::size_t, bool>> stack;
    for (const auto& [target, root] : outputs) {
      stack.push_back({root, false});
      while (!stack.empty()) {
        auto [n, expanded] = stack.back();
        stack.pop_back();
        if (order[n] != SIZE_MAX) continue;
        if (!expanded) {
          stack.push_back({n, true});
          for (auto a = nodes_[n].args.rbegin(); a != nodes_[n].args.rend(); ++a)
            if (order[*a] == SIZE_MAX) stack.push_back({*a, false});
          continue;
        }
        ir::Instruction in{nodes_[n].op, {}, nodes_[n].number, nodes_[n].variable};
        for (std::size_t a : nodes_[n].args) in.args.push_back(order[a]);
        order[n] = program.instructions.size();
        program.instructions.push_back(std::move(in));
      }
      program.outputs.push_back(ir::Assignment{target, order[root]});
    }
    return program;
  }

  bool is_zero(std::size_t n) const { return nodes_[n].op == Op::number && nodes_[n].number == 0.0; }

 private:
  std::size_t intern(Node n) {
    if (commutative(n.op))
      std::sort(n.args.begin(), n.args.end(), [&](std::size_t a, std::size_t b) {
        return std::tie(nodes_[a].signature, a) < std::tie(nodes_[b].signature, b);
      });
    std::uint64_t h = mix(14695981039346656037ull, signature_code(n.op));
    std::uint64_t bits = 0;
    std::memcpy(&bits, &n.number, sizeof bits);
    h = mix(h, bits);
    h = mix(h, n.name);
    for (std::size_t a : n.args) h = mix(h, nodes_[a].signature);
    n.signature = h;
    const auto [first, last] = interned_.equal_range(h);
    for (auto it = first; it != last; ++it) {
      const Node& m = nodes_[it->second];
      if (m.op == n.op && m.args == n.args && std::memcmp(&m.number, &n.number, sizeof bits) == 0 &&
          m.variable == n.variable)
        return it->second;
    }
    nodes_.push_back(std::move(n));
    interned_.emplace(h, nodes_.size() - 1);
    return nodes_.size() - 1;
  }

  std::size_t number(double v) { return intern(Node{Op::number, {}, v, {}, {}}); }
  std::size_t unary(Op op, std::size_t a) { return intern(Node{op, {a}, 0.0, {}, {}}); }

  // Signs are canonical: GiNaC writes the same value as l*(a - b) in one run and -l*(b - a)
  // in another (its term order follows address-seeded hashes), so every negation is moved
  // to the outside of products and quotients and every sum starts with a positive term.
  bool negated(std::size_t n) const { return nodes_[n].op == Op::negate; }
  std::size_t magnitude(std::size_t n) const { return negated(n) ? nodes_[n].args[0] : n; }
  std::size_t negate(std::size_t n) { return negated(n) ? nodes_[n].args[0] : unary(Op::negate, n); }
  std::size_t with_sign(bool negative, std::size_t n) { return negative ? negate(n) : n; }

  std::size_t nary(Op op, std::vector<std::size_t> args) {
    if (args.size() == 1) return args[0];
    if (op == Op::multiply) {
      bool negative = false;
      for (std::size_t& a : args) {
        negative ^= negated(a);
        a = magnitude(a);
      }
      return with_sign(negative, intern(Node{op, std::move(args), 0.0, {}, {}}));
    }
    if (op == Op::add) {
      // x and -x cancel: terms that are distinct GiNaC nodes can lower to one value (a quantity
      // derived both in the equations' intermediates and in the recursions'), and left in the
      // sum they cost operations and tie the choice of its orientation below
      std::map<std::size_t, long> net;  // magnitude -> number of times added, less subtracted
      for (std::size_t a : args) net[magnitude(a)] += negated(a) ? -1 : 1;
      if (net.size() < args.size()) {
        std::vector<std::size_t> kept;
        for (std::size_t a : args) {
          long& count = net[magnitude(a)];
          if (count > 0 && !negated(a)) kept.push_back(a), --count;
          else if (count < 0 && negated(a)) kept.push_back(a), ++count;
        }
        if (kept.empty()) return number(0.0);
        if (kept.size() == 1) return kept[0];
        args = std::move(kept);
      }
      // the term whose magnitude sorts first decides the orientation of the sum
      const auto first = std::min_element(args.begin(), args.end(), [&](std::size_t a, std::size_t b) {
        return std::tie(nodes_[magnitude(a)].signature, a) < std::tie(nodes_[magnitude(b)].signature, b);
      });
      const bool flip = negated(*first);
      if (flip)
        for (std::size_t& a : args) a = negate(a);
      return with_sign(flip, intern(Node{op, std::move(args), 0.0, {}, {}}));
    }
    return intern(Node{op, std::move(args), 0.0, {}, {}});
  }

  std::size_t quotient(std::size_t a, std::size_t b) {
    return with_sign(negated(a) != negated(b), intern(Node{Op::divide, {magnitude(a), magnitude(b)}, 0.0, {}, {}}));
  }

  // x^n for a positive integer n by repeated squaring, so x^4 = (x*x)*(x*x) shares x*x;
  // (-x)^n = x^n for even n
  std::size_t integer_power(std::size_t x, long n) {
    if (n == 1) return x;
    if (negated(x)) return with_sign(n % 2 == 1, integer_power(magnitude(x), n));
    const std::size_t half = integer_power(x, n / 2);
    const std::size_t square = nary(Op::multiply, {half, half});
    return n % 2 ? nary(Op::multiply, {square, x}) : square;
  }

  std::size_t power(const ex& base, const ex& exponent) {
    const std::size_t b = node(base);
    if (GiNaC::is_a<GiNaC::numeric>(exponent)) {
      const GiNaC::numeric e = GiNaC::ex_to<GiNaC::numeric>(exponent);
      if (e.is_integer() && e.is_pos_integer()) return integer_power(b, e.to_long());
      if (e.is_integer()) return quotient(number(1.0), integer_power(b, -e.to_long()));
      if (e == GiNaC::numeric(1, 2)) return unary(Op::sqrt, b);
      if (e == GiNaC::numeric(-1, 2)) return quotient(number(1.0), unary(Op::sqrt, b));
      if (e.is_rational() && e.denom() == 2) {
        // x^(k/2) = sqrt(x)^k
        const std::size_t root = unary(Op::sqrt, b);
        const long k = e.numer().to_long();
        return k > 0 ? integer_power(root, k) : quotient(number(1.0), integer_power(root, -k));
      }
    }
    return intern(Node{Op::power, {b, node(exponent)}, 0.0, {}, {}});
  }

  // The numeric factor of a term of a sum (1 for a term without one).
  static GiNaC::numeric coefficient_of(const ex& term) {
    if (GiNaC::is_a<GiNaC::numeric>(term)) return GiNaC::ex_to<GiNaC::numeric>(term);
    GiNaC::numeric c = 1;
    if (GiNaC::is_a<GiNaC::mul>(term))
      for (std::size_t i = 0; i < term.nops(); ++i)
        if (GiNaC::is_a<GiNaC::numeric>(term.op(i))) c *= GiNaC::ex_to<GiNaC::numeric>(term.op(i));
    return c;
  }

  // Multiplications by coefficients other than +-1 in the terms of \p sum times c.
  static int scaled_terms(const ex& sum, const GiNaC::numeric& c) {
    int count = 0;
    for (std::size_t i = 0; i < sum.nops(); ++i)
      if (!GiNaC::is_a<GiNaC::numeric>(sum.op(i)) && GiNaC::abs(c * coefficient_of(sum.op(i))) != 1) ++count;
    return count;
  }

  // GiNaC keeps a sum that is a factor of a product primitive, with its rational content in the
  // product's coefficient: 0.1845*x*z + y*z is held as 1/2000*(369*x + 2000*y)*z, which costs
  // three multiplications by numbers where one does. The sum (or the intermediate it is) whose
  // terms the coefficient makes cheapest takes the coefficient back; a call then computes
  // (0.1845*x + y)*z.
  std::optional<std::size_t> folded_product(const ex& e) {
    GiNaC::numeric c = 1;
    for (std::size_t i = 0; i < e.nops(); ++i)
      if (GiNaC::is_a<GiNaC::numeric>(e.op(i))) c *= GiNaC::ex_to<GiNaC::numeric>(e.op(i));
    if (c == 1 || c == -1) return std::nullopt;
    std::optional<std::size_t> best;
    ex best_sum;
    int best_saving = 0;
    std::uint64_t best_signature = 0;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      ex f = e.op(i);
      if (GiNaC::is_a<GiNaC::symbol>(f))
        if (const ex* definition = definitions_.find(f)) f = *definition;
      if (!GiNaC::is_a<GiNaC::add>(f)) continue;
      const int saving = 1 + scaled_terms(f, 1) - scaled_terms(f, c);
      if (saving <= 0) continue;
      // between sums that save alike, the one first by content: GiNaC's order of the factors
      // follows hash values that change from process to process
      const std::uint64_t signature = nodes_[magnitude(node(f))].signature;
      if (saving > best_saving || (saving == best_saving && signature < best_signature))
        best = i, best_sum = f, best_saving = saving, best_signature = signature;
    }
    if (!best) return std::nullopt;
    std::vector<std::size_t> terms;
    for (std::size_t i = 0; i < best_sum.nops(); ++i) terms.push_back(node(c * best_sum.op(i)));
    std::vector<std::size_t> factors{nary(Op::add, terms)};
    ex rest = 1;
    for (std::size_t i = 0; i < e.nops(); ++i)
      if (i != *best && !GiNaC::is_a<GiNaC::numeric>(e.op(i))) rest *= e.op(i);
    if (!rest.is_equal(1)) factors.push_back(node(rest));
    return factors.size() == 1 ? factors[0] : nary(Op::multiply, factors);
  }

  std::size_t product(const ex& e) {
    if (const std::optional<std::size_t> folded = folded_product(e)) return *folded;
    // numeric coefficient, factors above and below the line
    double coefficient = 1.0;
    std::vector<std::size_t> above, below;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex f = e.op(i);
      if (GiNaC::is_a<GiNaC::numeric>(f)) {
        coefficient *= GiNaC::ex_to<GiNaC::numeric>(f).to_double();
      } else if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::numeric>(f.op(1)) &&
                 GiNaC::ex_to<GiNaC::numeric>(f.op(1)).is_negative()) {
        below.push_back(node(GiNaC::pow(f.op(0), -f.op(1))));
      } else {
        above.push_back(node(f));
      }
    }
    const bool negative = coefficient < 0;
    if (std::fabs(coefficient) != 1.0) above.push_back(number(std::fabs(coefficient)));
    std::size_t value = above.empty() ? number(1.0) : nary(Op::multiply, above);
    if (!below.empty()) value = quotient(value, nary(Op::multiply, below));
    return with_sign(negative, value);
  }

  // a GiNaC function lowers to the call of the same name (GiNaC has no function named sqrt or
  // pow: those come from powers)
  std::size_t function(const ex& e) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    const auto call = std::find_if(std::begin(ir::call_ops), std::end(ir::call_ops),
                                   [&](const ir::CallOp& c) { return name == c.cpp_name; });
    if (call == std::end(ir::call_ops))
      throw EmitError(fmt::format("code emission: the function '{}' has no C++ form", name));
    Node n{call->op, {}, 0.0, {}, {}};
    for (std::size_t i = 0; i < e.nops(); ++i) n.args.push_back(node(e.op(i)));
    if (n.args.size() != call->arity)
      throw EmitError(fmt::format("code emission: '{}' called with {} arguments", name, n.args.size()));
    // odd functions take the argument's sign outside, even ones drop it
    if (n.args.size() == 1 && negated(n.args[0]) && call->symmetry != ir::Symmetry::none) {
      n.args[0] = magnitude(n.args[0]);
      return with_sign(call->symmetry == ir::Symmetry::odd, intern(std::move(n)));
    }
    return intern(std::move(n));
  }

  std::size_t build(const ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) {
      const GiNaC::numeric v = GiNaC::ex_to<GiNaC::numeric>(e);
      if (!v.is_real()) throw EmitError("code emission: complex number in an expression");
      const double d = v.to_double();
      return d < 0 ? negate(number(-d)) : number(d);
    }
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      if (const ex* definition = definitions_.find(e)) return node(*definition);
      auto var = variables_.find(e);
      if (var == variables_.end())
        throw EmitError(fmt::format("code emission: the symbol '{}' is not an input of this function",
                                    GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
      return intern(Node{Op::variable, {}, 0.0, var->second.variable, var->second.name});
    }
    if (GiNaC::is_a<GiNaC::constant>(e)) return number(GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double());
    if (GiNaC::is_a<GiNaC::add>(e)) {
      std::vector<std::size_t> terms;
      for (std::size_t i = 0; i < e.nops(); ++i) terms.push_back(node(e.op(i)));
      return nary(Op::add, terms);
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) return product(e);
    if (GiNaC::is_a<GiNaC::power>(e)) return power(e.op(0), e.op(1));
    if (GiNaC::is_a<GiNaC::function>(e)) return function(e);
    throw EmitError(fmt::format("code emission: cannot print the expression '{}'", ex_to_string(e)));
  }

  static std::string ex_to_string(const ex& e) {
    std::ostringstream s;
    s << e;
    return s.str();
  }

  const VariableNames& variables_;
  // by value, looked up only (expression_map.hpp)
  ExpressionMap<ex> definitions_;
  ExpressionMap<std::size_t> memo_;
  std::vector<Node> nodes_;
  // the nodes by their content signature; equal signatures are compared field by field
  std::unordered_multimap<std::uint64_t, std::size_t> interned_;
};

}  // namespace

ir::Program lower(const std::vector<LoweringTarget>& targets, const Subexpressions& subexpressions,
                  const VariableNames& variables) {
  return lower_functions({targets}, {&subexpressions}, variables).front();
}

std::vector<ir::Program> lower_functions(const std::vector<std::vector<LoweringTarget>>& functions,
                                         const std::vector<const Subexpressions*>& subexpressions,
                                         const VariableNames& variables) {
  Lowering lowering(subexpressions, variables);
  std::vector<ir::Program> programs;
  for (const std::vector<LoweringTarget>& targets : functions) {
    std::vector<std::pair<ir::Target, std::size_t>> outputs;
    for (const LoweringTarget& t : targets) {
      const std::size_t n = lowering.node(t.value);
      if (!lowering.is_zero(n)) outputs.emplace_back(t.target, n);
    }
    programs.push_back(lowering.finish(outputs));
  }
  return programs;
}

}  // namespace eomgen
