#include "linearization_source.hpp"

namespace eomgen {

std::string linearization_source(bool is_constrained) {
  // the solves are the runtime's (eomrt/linearization.hpp); the header only says where to find them
  return is_constrained ? R"cpp(
  // A and B about an operating point: eomrt::linearization<Model> (eomrt/linearization.hpp)
  // solves the KKT system there for qdd0 and lambda0, evaluates linearization_terms at them
  // and solves the KKT system again for the derivatives of qdd.
)cpp"
                        : R"cpp(
  // A and B about an operating point: eomrt::linearization<Model> (eomrt/linearization.hpp);
  // the second-order form M, D, K, B_u: eomrt::second_order_linearization<Model>. Both take
  // linearization_terms at the point's own accelerations qdd0 = M^-1 F.
)cpp";
}

}  // namespace eomgen
