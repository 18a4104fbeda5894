// Operands of a sum read from its pairs (operand.hpp).
#include "eomgen/symbolic/operand.hpp"

namespace eomgen {
namespace {

// GiNaC keeps a sum's pairs in a protected member; a pointer to it, formed through a derived
// class, reads them from any sum.
struct StoredPairs : GiNaC::expairseq {
  static const GiNaC::epvector& of(const GiNaC::expairseq& s) { return s.*(&StoredPairs::seq); }
};

}  // namespace

const GiNaC::epvector* sum_pairs(const GiNaC::ex& e) {
  if (!GiNaC::is_exactly_a<GiNaC::add>(e)) return nullptr;
  return &StoredPairs::of(GiNaC::ex_to<GiNaC::add>(e));
}

GiNaC::ex operand(const GiNaC::ex& e, std::size_t i) {
  if (!GiNaC::is_exactly_a<GiNaC::add>(e)) return e.op(i);
  const GiNaC::epvector& pairs = StoredPairs::of(GiNaC::ex_to<GiNaC::add>(e));
  if (i >= pairs.size()) return e.op(i);  // the sum's number
  const GiNaC::expair& pair = pairs[i];
  if (pair.coeff.is_equal(1)) return pair.rest;
  return GiNaC::mul(pair.rest, pair.coeff).hold();
}

}  // namespace eomgen
