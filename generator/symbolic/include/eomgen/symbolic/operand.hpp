#pragma once
// Reading the operands of a sum without GiNaC's evaluation of a product per read.
//
// GiNaC keeps a term c*x of a sum, c a number, as the pair (x, c), and op(i) of the sum builds
// the product x*c anew at every read and evaluates it. That evaluation walks every sum among
// x's factors (for their integer content) and distributes c over a sum x, building new nodes
// each time. Which terms are kept as such pairs follows the order of the terms, which follows
// hash values that differ between processes: a walk that reads operands with op() over a large
// graph took 4 to 40 s on one model depending on the process. operand() builds the product
// held instead: the same value, built in time linear in x's factors, never walking further.
#include <cstddef>

#include <ginac/ginac.h>

namespace eomgen {

/// Operand i of e: e.op(i), except that a term c*x of a sum is built as the held product x*c.
/// \pre i < e.nops()
GiNaC::ex operand(const GiNaC::ex& e, std::size_t i);

/// The pairs (x, c) of the terms c*x of e if e is a sum, else null: what operand() reads, for
/// a walk that needs no node of the term itself.
const GiNaC::epvector* sum_pairs(const GiNaC::ex& e);

}  // namespace eomgen
