#pragma once
// An overload set built from lambdas, the visitor of a std::variant:
//   std::visit(Overloaded{[](const A& a) { ... }, [](const B& b) { ... }}, v);
// Without a generic (auto) lambda among them, an alternative with no handler does not compile.

namespace eomgen {

template <class... Handlers>
struct Overloaded : Handlers... {
  using Handlers::operator()...;
};
template <class... Handlers>
Overloaded(Handlers...) -> Overloaded<Handlers...>;

}  // namespace eomgen
