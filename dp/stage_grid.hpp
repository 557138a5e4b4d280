// StageGrid: the discretisation of the DP. Positions s_i = i * ds (the last step may be shorter
// so the grid ends exactly at the stop), and at each position the speeds 0, dv, 2 dv, ... below
// the speed envelope plus one node exactly on the envelope. The envelope node lets the grid
// represent "on the limit" and "on the braking curve" exactly; the final stage has the single
// node v = 0 (the stop). A speed between nodes is located by its lower node and a weight for
// linear interpolation of the cost-to-go.
#pragma once

#include <vector>

#include "physics/speed_envelope.hpp"

namespace ecorail::dp {

struct GridSpec {
  double ds_m = 5.0;
  double dv_kmh = 0.2;
  double substep_m = 2.5;  // integration substep inside a DP transition (Heun)
};

class StageGrid {
 public:
  StageGrid(const physics::SpeedEnvelope& envelope, double length_m, const GridSpec& spec);

  int stage_count() const { return static_cast<int>(s_.size()); }  // positions incl. the stop
  double position(int i) const { return s_[i]; }
  const std::vector<double>& positions() const { return s_; }
  int node_count(int i) const { return offset_[i + 1] - offset_[i]; }
  int offset(int i) const { return offset_[i]; }
  int total_nodes() const { return offset_.back(); }
  double speed(int i, int j) const;
  double dv_ms() const { return dv_; }
  // Stage whose position is the first strictly after s (the next decision position).
  int next_stage_after(double s_m) const;
  // Lower node (global index) and interpolation weight of speed v at stage i.
  void locate(int i, double v_ms, int* lower, double* weight) const;
  // Where v lies among the uniform speeds 0, dv, 2 dv, ... of any stage: the lower one's index
  // floor(max(0, v) / dv) and the fraction above it (locate's arithmetic between uniform nodes).
  void uniform_position(double v_ms, int* lower, double* weight) const;
  // Whether locate(i, v) is offset(i) plus uniform_position(v), bit for bit: v below the top
  // node and between two uniform nodes of stage i.
  bool locates_uniformly(int i, double v_ms) const;

 private:
  double dv_;
  std::vector<double> s_;
  std::vector<double> top_;   // envelope speed at each stage
  std::vector<int> uniform_;  // number of uniform nodes below the top node
  std::vector<int> offset_;
};

}  // namespace ecorail::dp
