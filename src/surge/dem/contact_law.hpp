// What a DEM contact law is, and the laws the case file can name (`dem.contact`).
//
// A law is a small type of static host/device functions over its per-pair constants
// (`Pair`, trivially copyable, at most four numbers): how two materials and radii mix
// into them (`pair`, `wall`), the normal force, the shear stiffness and damping at an
// overlap, a material's damping constant from its restitution, the time scale the step
// is taken from, and which materials it cannot take. The solver runs one pair loop and
// one history (shear spring, rolling and twisting rotation, bond) for every law; friction,
// rolling and twisting resistance and bonds are shared (dem_solver.cpp, pair_terms).
//
// Adding a law: a header with its type (as contact_hertz_mindlin.hpp), one entry in
// `ContactLaws` below (the case file's choices follow), a test against its closed forms.
#pragma once
#include "surge/dem/contact_hertz_mindlin.hpp"
#include "surge/dem/contact_linear_spring.hpp"
#include "surge/dem/material.hpp"

#include <concepts>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace surge::dem {

// A listed pair's law constants, whatever the law (read and written through load/store).
struct PairLaw {
  Real c[4];
};

template <class L>
concept ContactLaw = std::is_trivially_copyable_v<typename L::Pair> && sizeof(typename L::Pair) <= sizeof(PairLaw) &&
                     requires(const Material& m, Real x, bool b, const typename L::Pair& p, const char** key) {
  { L::name } -> std::convertible_to<const char*>;
  { L::time_scale_name } -> std::convertible_to<const char*>;
  { L::damps_shear } -> std::convertible_to<bool>;
  { L::damping(x) } -> std::same_as<Real>;
  { L::unsuitable(m, key) } -> std::same_as<const char*>;
  { L::pair(m, m, x, x, x) } -> std::same_as<typename L::Pair>;
  { L::wall(m, m, x, x) } -> std::same_as<typename L::Pair>;
  { L::normal_force(p, x, x, b) } -> std::same_as<Real>;
  { L::shear_stiffness(p, x) } -> std::same_as<Real>;
  { L::shear_damping(p, x) } -> std::same_as<Real>;
  { L::time_scale(m, x, x) } -> std::same_as<Real>;
};

template <ContactLaw... L>
struct LawList {};

// The registry: the laws by index (index 0 is the default).
using ContactLaws = LawList<LinearSpring, HertzMindlin>;

template <class P>
[[nodiscard]] SURGE_HD inline P load_law(const PairLaw& s) {
  P p;
  std::memcpy(&p, &s, sizeof(P));
  return p;
}
template <class P>
SURGE_HD inline void store_law(PairLaw& s, const P& p) {
  std::memcpy(&s, &p, sizeof(P));
}

// Calls f(L{}) with the law of index `law`.
template <class F, class... L>
void with_law(int law, F&& f, LawList<L...> /*list*/) {
  int k = 0;
  (void)((k++ == law ? (f(L{}), true) : false) || ...);
}
template <class F>
void with_contact_law(int law, F&& f) {
  with_law(law, std::forward<F>(f), ContactLaws{});
}

// The laws' names, in the registry's order; the index of a name (-1: unknown).
template <class... L>
std::vector<std::string> law_names(LawList<L...> /*list*/) {
  return {L::name...};
}
inline std::vector<std::string> contact_law_names() { return law_names(ContactLaws{}); }
// Why law `law` refuses material m (nullptr: it takes it), with the key at fault.
inline const char* unsuitable_material(int law, const Material& m, const char** key) {
  const char* why = nullptr;
  with_contact_law(law, [&](auto l) { why = decltype(l)::unsuitable(m, key); });
  return why;
}
inline int contact_law_index(const std::string& name) {
  const auto names = contact_law_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<int>(k);
  return -1;
}

} // namespace surge::dem
