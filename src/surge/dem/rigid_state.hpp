// A sphere's rigid state for the coupling: the one rigid-body view of core/rigid_state.hpp.
#pragma once
#include "surge/core/rigid_state.hpp"

namespace surge::dem {
using surge::rigid_point;
using surge::RigidPoint;
using surge::RigidState;
using surge::rotate;
} // namespace surge::dem
