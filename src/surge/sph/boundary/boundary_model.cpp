#include "surge/sph/boundary/boundary_model.hpp"

#include <stdexcept>

namespace surge::sph {

// Each model's file defines its factory.
std::unique_ptr<BoundaryModel> make_dynamic_boundary(const InitialState& init, const WcsphParams& prm);
std::unique_ptr<BoundaryModel> make_mdbc_boundary(const InitialState& init, const WcsphParams& prm);

const std::vector<BoundaryModelInfo>& boundary_models() {
  static const std::vector<BoundaryModelInfo> models{
      {"dynamic", make_dynamic_boundary},
      {"mdbc", make_mdbc_boundary},
  };
  return models;
}

const BoundaryModelInfo& boundary_model(const std::string& name) {
  std::string known;
  for (const auto& m : boundary_models()) {
    if (name == m.name) return m;
    known += (known.empty() ? "" : ", ") + std::string(m.name);
  }
  throw std::invalid_argument("unknown SPH boundary model '" + name + "' (known: " + known + ")");
}

} // namespace surge::sph
