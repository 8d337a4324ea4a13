// Hazard maps (issue 22): on the lattice of the terrain's grid, accumulated at every gauge
// time during the run (not from particle files afterwards) — the highest free surface, the
// greatest depth, the greatest depth-averaged speed and the first time the surface stood
// arrival_height above the still level — and the run-up along lines: the highest ground
// the water wetted. Every map cell and run-up point is a water column read as a wave
// gauge reads it (sph/gauges.hpp: a dry bed reads dry whatever flies above it), so the maps
// are the same bits on any number of processes; they travel in checkpoints as bytes.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/raster.hpp"
#include "surge/sph/gauges.hpp"
#include "surge/sph/initial_state.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::sph {

class HazardMaps {
public:
  // Reads the first terrain wall's grid; nothing to do when the case has no hazard section.
  HazardMaps(const Case& c, const InitialState& init);
  [[nodiscard]] bool enabled() const { return cols_ != nullptr; }
  // Reads every column at time t and updates the maps.
  void sample(double t, WcsphSolver& solver, const Distribution& dist = {});
  // The maps' lattice (the terrain grid's every coarsen-th node; its values: the ground).
  [[nodiscard]] const geometry::Raster& lattice() const { return lattice_; }
  // max_elevation, max_depth, max_speed, arrival_time, on the lattice (NaN: never wet /
  // never reached).
  [[nodiscard]] std::vector<std::vector<double>> maps() const;
  [[nodiscard]] static std::vector<std::string> map_names();
  // runup.csv: per line, the highest wetted ground point, the highest water surface over
  // it (the run-up), that above the still level, and when the water first reached it.
  [[nodiscard]] std::string run_up_csv() const;
  // The accumulated state, for checkpoints.
  [[nodiscard]] std::string save() const;
  void restore(const std::string& bytes, const std::string& checkpoint_path);

private:
  HazardConfig cfg_;
  geometry::Raster lattice_;
  std::unique_ptr<Gauges> cols_; // map cells first, then the run-up points
  std::size_t n_cells_ = 0;
  std::vector<double> max_eta_, max_depth_, max_speed_, arrival_;
  struct RunUpPoint {
    int line;
    double x, y;
  };
  std::vector<RunUpPoint> run_up_points_;
  std::vector<double> first_wet_; // per run-up point: the first time it was wet (NaN: never)
  std::vector<double> ground_;    // per run-up point: the ground there
  std::vector<double> top_;       // per run-up point: the highest water surface over it (NaN: never wet)
};

} // namespace surge::sph
