#pragma once
// Overloaded lambdas for std::visit: std::visit(Overloaded{[](const A&) {...}, [](const B&) {...}},
// v). With no catch-all overload, an alternative without its lambda fails to compile.

namespace aggpack {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace aggpack
