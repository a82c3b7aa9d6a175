#include "tools/synth/cameras.h"

#include <cmath>

namespace goris::synth {

std::vector<CameraView> hemisphere_cameras(const CameraRing& ring, int count, double phase) {
  const double golden = 0.3819660112501051;  // 2 - phi: the golden angle as a fraction of a turn
  const double z0 = std::sin(ring.min_elevation), z1 = std::sin(ring.max_elevation);
  const double full_turn = ring.max_azimuth - ring.min_azimuth >= 6.28318;
  std::vector<CameraView> views;
  for (int i = 0; i < count; ++i) {
    // Uniform in z gives uniform density over the sphere's area (Archimedes).
    double t = std::fmod((i + 0.5 + 0.37 * phase) / count, 1.0);
    double z = z0 + (z1 - z0) * t;
    double turn = std::fmod(i * golden + phase, 1.0);
    // In a sector, sweep back and forth so neighbouring elevations still spread over the sector.
    double azimuth = ring.min_azimuth + (ring.max_azimuth - ring.min_azimuth) * (full_turn ? turn : std::abs(2 * turn - 1));
    double r = std::sqrt(1.0 - z * z);
    CameraView v;
    v.look_at = ring.look_at;
    v.location = {ring.look_at[0] + ring.radius * r * std::cos(azimuth), ring.look_at[1] + ring.radius * r * std::sin(azimuth),
                  ring.look_at[2] + ring.radius * z};
    views.push_back(v);
  }
  return views;
}

}  // namespace goris::synth
