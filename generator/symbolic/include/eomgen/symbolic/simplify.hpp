#pragma once
// Light simplification for showing equations to people (not used by the derivation, which
// keeps expressions unexpanded so they stay small).
#include <ginac/ginac.h>

namespace eomgen {

/// Expands e and removes sin^2 + cos^2 pairs (sin(x)^2 -> 1 - cos(x)^2, then expand again),
/// which turns compounded rotations into the forms one derives by hand, e.g. the double
/// pendulum's M_12 = m2 l1 l2 cos(q2). Cost grows with the expanded size: small systems only.
GiNaC::ex simplify_for_display(const GiNaC::ex& e);
GiNaC::matrix simplify_for_display(const GiNaC::matrix& m);

}  // namespace eomgen
