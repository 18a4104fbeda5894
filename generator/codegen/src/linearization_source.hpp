#pragma once
// What the generated header adds to its linearization as text. The model-specific derivative
// terms (linearization_terms, forward_dynamics_derivatives of a model without constraints) are
// lowered from the expression graph like every other function. A constrained model's
// derivatives of its KKT accelerations and multipliers are composed of the header's functions
// and a small LU solve written out, since they solve a system of numbers.
#include <string>

namespace eomgen {

/// Text for the body of the generated Model after linearization_terms: without constraints a
/// comment naming the runtime algorithms that use it; with constraints kkt_derivatives,
/// forward_dynamics_derivatives and multiplier_derivatives, with the comment.
std::string linearization_source(bool constrained);

}  // namespace eomgen
