#pragma once
// Harmonic (membrane) fill: each channel inside the hole solves Laplace's equation with the known
// pixels around the hole as fixed values (and a zero normal derivative where the hole meets the image
// border). It reproduces affine functions exactly, and inverse depth is affine in the pixel coordinates
// on any plane, so on depth maps (which inpaint_map fills in inverse depth) a planar surface behind the
// removed object comes back as that plane: the right filler for depth before the 3D lift, where
// Telea / Navier-Stokes leave errors of a few pixels' worth of slope. Smooth, textureless elsewhere.
// Solved by successive over-relaxation (red-black order) on a cascade of half-size levels (each level
// starts from the coarser solution; the coarsest from an onion-peel fill), so large holes stay fast.
#include "core/inpaint/inpainter.h"

namespace goris {

class HarmonicInpainter final : public Inpainter {
 public:
  // Stops when no value moves by more than `tolerance` (in encoded units, see map_encoding.h) in one
  // sweep, or after `max_sweeps`.
  explicit HarmonicInpainter(double tolerance = 1e-6, int max_sweeps = 20000)
      : tolerance_(tolerance), max_sweeps_(max_sweeps) {}
  std::string name() const override { return "harmonic"; }
  Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const override;

 private:
  double tolerance_;
  int max_sweeps_;
};

}  // namespace goris
