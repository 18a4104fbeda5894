#include "eomgen/symbolic/simplify.hpp"

namespace eomgen {

GiNaC::ex simplify_for_display(const GiNaC::ex& e) {
  const GiNaC::ex x = GiNaC::wild(0);
  // algebraic matching also rewrites sin(x)^3 = sin(x) sin(x)^2 and higher powers
  const GiNaC::ex rule = GiNaC::pow(GiNaC::sin(x), 2) == 1 - GiNaC::pow(GiNaC::cos(x), 2);
  GiNaC::ex out = e.expand();
  for (int pass = 0; pass < 4; ++pass) {
    const GiNaC::ex next = out.subs(rule, GiNaC::subs_options::algebraic).expand();
    if (next.is_equal(out)) break;
    out = next;
  }
  return out;
}

GiNaC::matrix simplify_for_display(const GiNaC::matrix& m) {
  GiNaC::matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = simplify_for_display(m(i, j));
  return out;
}

}  // namespace eomgen
