// A DEM material: what the contact laws mix for a pair of spheres (or a sphere and a
// wall), and the friction, rolling, twisting and bond properties every law shares.
#pragma once
#include "surge/core/types.hpp"

namespace surge::dem {

struct Material {
  Real density = 2500;
  Real young = Real(1e6);     // E [Pa] (linear spring: stiffness per length in the two-spring formula)
  Real nu = Real(0.2);        // linear spring: shear-to-normal stiffness ratio; Hertz-Mindlin: Poisson's ratio
  Real tan_phi = Real(0.577); // friction coefficient tan(phi)
  Real restitution = Real(0.5);
  Real k_roll = 0, k_roll_max = 0;   // rolling stiffness factor and cap factor
  Real k_twist = 0, k_twist_max = 0; // twisting
  bool bonded = false;               // touching spheres of two bonded materials are bonded at the start (CFM)
  Real bond_cn = 0;                  // bond tensile strength C_n [Pa]: breaks beyond C_n r'^2 in tension
  Real bond_cs = 0;                  // bond shear strength C_s [Pa]: breaks beyond |F_n| tan(phi) + C_s r'^2
  Real damping = 0;                  // derived by the solver from the restitution, by the contact law
};

} // namespace surge::dem
