// The C++ side of the Python modules' bit-for-bit test (test_reference_values.py): evaluates the
// header a module was compiled from (EOMGEN_MODEL, the module's model.hpp) at the states
// states.py defines, and prints every value as a hexadecimal float, which Python reads back
// exactly. One line per function and state: "NAME K v0 v1 ..." (matrices row by row).
#include <cstdio>
#include <string>

#include "eomrt/linearization.hpp"
#include "model.hpp"

namespace {


// entry i of state k: exact in binary (an integer over a power of two times a small odd
// number, divided once, as Python divides), so both languages see the same bits
double entry(int i, int k, int a, int b, int modulus) {
  return static_cast<double>((i * a + k * b) % modulus) / (modulus / 2.0) - 1.0;
}

template <class Matrix>
void print(const char* name, int k, const Matrix& m) {
  std::printf("%s %d", name, k);
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) std::printf(" %a", m(r, c));
  std::printf("\n");
}

void print(const char* name, int k, double v) { std::printf("%s %d %a\n", name, k, v); }

// a template, so that `if constexpr` leaves out what the model lacks
template <class Model>
void print_values() {
  using Types = eomrt::ModelTypes<Model, double>;
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>{}};
  for (int k = 0; k < 5; ++k) {
    const double t = k / 4.0;
    typename Types::Coordinates q, qd, qdd;
    typename Types::Inputs u;
    for (int i = 0; i < Model::nq; ++i) q(i) = entry(i, k, 31, 17, 97), qd(i) = entry(i, k, 13, 29, 89),
                                        qdd(i) = entry(i, k, 5, 3, 79);
    for (int i = 0; i < Model::nu; ++i) u(i) = entry(i, k, 7, 11, 23);

    typename Types::MassMatrix M;
    typename Types::Coordinates F;
    Model::mass_matrix(t, q, c, M);
    Model::forcing(t, q, qd, u, c, F);
    print("mass_matrix", k, M);
    print("forcing", k, F);
    typename Types::ConstraintJacobian Xi;
    typename Types::ConstraintVector Xi_t, b;
    typename Types::HolonomicVector phi;
    Model::constraint_jacobian(t, q, c, Xi);
    Model::constraint_rate_term(t, q, c, Xi_t);
    Model::constraint_acceleration_term(t, q, qd, c, b);
    Model::holonomic_residuals(t, q, c, phi);
    print("constraint_jacobian", k, Xi);
    print("constraint_rate_term", k, Xi_t);
    print("constraint_acceleration_term", k, b);
    print("holonomic_residuals", k, phi);
    print("kinetic_energy", k, Model::kinetic_energy(t, q, qd, c));
    print("potential_energy", k, Model::potential_energy(t, q, c));
    Eigen::Matrix<double, Model::ny, 1> y;
    Model::outputs(t, q, qd, u, c, y);
    print("outputs", k, y);
    if constexpr (Model::has_forward_dynamics) {
      typename Types::Coordinates a;
      if (Model::forward_dynamics(t, q, qd, u, c, a)) print("forward_dynamics", k, a);
    }
    if constexpr (Model::nc == 0) {
      typename Types::Coordinates tau;
      Model::inverse_dynamics(t, q, qd, qdd, u, c, tau);
      print("inverse_dynamics", k, tau);
    }
    eomrt::LinearizationWorkspace<Model, double> ws;
    if (eomrt::linearization<Model>(c, ws, t, q, qd, u) == eomrt::DynamicsStatus::ok) {
      print("linearization.A", k, ws.A);
      print("linearization.B", k, ws.B);
    }
  }
}

}  // namespace

int main() {
  print_values<EOMGEN_MODEL>();
  return 0;
}
