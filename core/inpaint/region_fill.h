#pragma once
// Filling a hole's part on one surface from that surface alone. Where a removed object stood on a glossy
// table, its hole borders both the table and the other objects; an inpainter fed every known pixel drags
// the neighbours' colours across the table (a smudge in every view the fill is lifted into). Filling the
// hole's pixels inside the region with every pixel outside the region unknown takes the table's colours
// only; the rest of the hole is left to the ordinary fill.
#include <vector>

#include "core/inpaint/inpainter.h"

namespace goris {

// `filled` (HWC, the map after the ordinary fill of `hole`) with the hole's pixels inside `region`
// ([H][W], > 0.5 = inside) refilled from `map`'s pixels that are inside the region and outside the hole.
// Nothing changes when the region holds no such pixel or no hole pixel. Throws goris::Error for sizes that
// differ.
Image refill_inside_region(const Inpainter& inpainter, const Image& map, const Image& filled, const Mask& hole,
                           const std::vector<float>& region, const MapInfo& info);

}  // namespace goris
