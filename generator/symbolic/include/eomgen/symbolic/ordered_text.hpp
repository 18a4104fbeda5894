#pragma once
// An expression's text that is the same in every process: GiNaC orders the terms of a sum and the
// factors of a product by hashes that differ from run to run, so its own printing does too.
#include <ginac/ginac.h>

#include <string>

namespace eomgen {

/// GiNaC's text of e with the terms of every sum and the factors of every product in the order
/// of their own text (a product's numeric coefficient first): `-F*l`, `L1+L2`, `sin(q)^2`.
std::string ordered_text(const GiNaC::ex& e);

}  // namespace eomgen
