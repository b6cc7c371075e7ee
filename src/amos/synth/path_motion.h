#pragma once
// Back-and-forth travel along a floor polyline with rests at both ends: where a walker, a pushed box or a
// rolling chair is at time t. A pure function of t (frames can be rendered in any order).
#include <Eigen/Core>
#include <vector>

namespace amos::synth {

struct TravelState {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading = 0;       // yaw of the direction of travel (turns on the spot during rests)
  double speed = 0;         // m/s at this instant
  double distance = 0;      // total distance travelled since t = 0 (drives the gait)
  double leg_progress = 0;  // 0..1 along the current traversal
  bool resting = false;
};

class PingPongPath {
 public:
  // speed: average speed while travelling (m/s); rest_s: pause at each end; ease in [0, 1]: 0 constant speed,
  // 1 smooth start and stop (peak speed twice the average); start_offset_s shifts the schedule.
  PingPongPath(std::vector<Eigen::Vector2d> waypoints, double speed, double rest_s, double ease, double start_offset_s);

  TravelState at(double t) const;
  double length() const { return length_; }

 private:
  Eigen::Vector2d pointAt(double arc) const;
  double headingAt(double arc, int direction) const;

  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;
  double length_ = 0, speed_, rest_, ease_, offset_, travel_time_;
};

}  // namespace amos::synth
