#include "stairplan/perception/footfall_track.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

namespace stairplan {
namespace {

// 'F' for a front leg, 'H' for a hind one, 0 when the name does not say.
char LegEnd(const std::string& name) {
  const auto side = [](char c) { return c == 'L' || c == 'R'; };
  const auto end = [](char c) { return c == 'F' || c == 'H'; };
  if (name.size() != 2) return 0;
  if (side(name[0]) && end(name[1])) return name[1];
  if (end(name[0]) && side(name[1])) return name[0];
  return 0;
}

}  // namespace

std::vector<GroundPose> TrackFromFootfalls(const std::vector<Footfall>& footfalls) {
  std::vector<std::size_t> order(footfalls.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return footfalls[a].t < footfalls[b].t; });
  std::set<std::string> legs;
  bool fronts = false, hinds = false, named = true;
  for (const Footfall& f : footfalls) {
    legs.insert(f.leg);
    const char e = LegEnd(f.leg);
    fronts = fronts || e == 'F';
    hinds = hinds || e == 'H';
    named = named && e != 0;
  }
  named = named && fronts && hinds;
  std::map<std::string, Eigen::Vector2d> latest;
  std::vector<GroundPose> track;
  for (const std::size_t i : order) {
    const Footfall& f = footfalls[i];
    latest[f.leg] = f.position.head<2>();
    if (latest.size() < legs.size()) continue;
    GroundPose pose;
    pose.t = f.t;
    Eigen::Vector2d front = Eigen::Vector2d::Zero(), hind = Eigen::Vector2d::Zero();
    int n_front = 0, n_hind = 0;
    for (const auto& [leg, xy] : latest) {
      pose.xy += xy / static_cast<double>(latest.size());
      if (LegEnd(leg) == 'F') front += xy, ++n_front;
      if (LegEnd(leg) == 'H') hind += xy, ++n_hind;
    }
    if (named) {
      const Eigen::Vector2d d = front / n_front - hind / n_hind;
      pose.yaw = std::atan2(d.y(), d.x());
    } else if (!track.empty()) {
      const Eigen::Vector2d d = pose.xy - track.back().xy;
      pose.yaw = d.norm() > 1e-9 ? std::atan2(d.y(), d.x()) : track.back().yaw;
      if (track.size() == 1) track.front().yaw = pose.yaw;
    }
    track.push_back(pose);
  }
  return track;
}

}  // namespace stairplan
