#pragma once
// Growing and shrinking a selection over the k-nearest-neighbour graph of the Gaussian centres (the
// editor's click -> grow slider, docs/design/architecture.md, The editor; `goris select --grow`).
//
// Growing takes the connected component of the seeds through the Gaussians that pass a node test, along
// graph edges that pass a distance test. A neighbour j reached from region member i is admitted when all of
//   distance  |mu_i - mu_j| / min(spacing_i, spacing_j)  <= 1 + 2 g        (spacing: median distance to
//                                                                          the k nearest centres)
//   colour    |c_j - reference colour|  (SH DC colour, RGB distance)   <= colour_tolerance * g^2
//   label     |l_j - reference label|                                 <= label_tolerance * g
// hold, where g in [0, 1] is the grow slider: 0 adds nothing, 1 is the most permissive. The distance test
// keeps growth from jumping across gaps (the neighbours of a centre at an object's edge may lie on the
// other side of a gap); colour and label keep it from spreading onto a touching surface that differs.
// The references are fixed for the whole growth: the seeds' mean colour and label, or, for fewer than 8
// seeds (a click), the component-wise median over the seeds and their graph neighbours, because one
// Gaussian's DC colour is a noisy sample of its surface. Fixed references make the slider monotone: a
// larger g never selects less. (Seeded region growing with a running mean, Adams & Bischof 1994, adapts
// better to slow colour gradients but can jump back and forth as the slider moves.)
// The colour tolerance grows with g^2 up to 1.5 (most of the RGB cube's diagonal, 1.73): fine steps at the
// low end for clean reconstructions, and at the top an almost colour-blind growth (geometry and label
// only) for models whose DC colours are noisy - early in training, or where view-dependent SH bands carry
// much of the colour.
// Candidates are admitted most similar first (a priority queue, ties broken by Gaussian index), so growth
// is deterministic, and bounded: it stops, and says so, before the selection would exceed max_fraction of
// all Gaussians, holding the most similar part.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/scene/selection_points.h"

namespace goris {

// Symmetric k-nearest-neighbour graph of the centres (j in kNN(i) or i in kNN(j)) in CSR form.
struct SelectionGraph {
  int k = 0;
  std::vector<std::uint32_t> offsets;    // [N + 1]
  std::vector<std::uint32_t> neighbors;  // neighbours of i: neighbors[offsets[i] .. offsets[i + 1])
  std::vector<float> distances;          // the edge lengths, same layout
  std::vector<float> spacing;            // [N] median distance to the k nearest centres
  std::size_t size() const { return spacing.size(); }
};

// Builds the graph (a k-d tree query per Gaussian, in parallel). k is clamped to N - 1.
SelectionGraph build_selection_graph(const SelectionPoints& pts, int k = 10);

struct GrowSettings {
  float grow = 0.5f;              // the slider g, 0..1
  float colour_tolerance = 1.5f;  // RGB distance to the region's mean colour allowed at g = 1
  float label_tolerance = 0.6f;   // label difference to the region's mean label allowed at g = 1
  float max_fraction = 0.5f;      // the selection may never hold more than this fraction of the Gaussians
};

struct GrowResult {
  SelectionMask mask;
  std::size_t seeds = 0;      // selected in the input
  std::size_t added = 0;      // admitted by growing
  bool hit_limit = false;     // growth stopped at max_fraction (the mask is what it held then)
  std::size_t limit = 0;      // the largest selection allowed: floor(max_fraction * N)
};

// Grows `seeds` (size N, else goris::Error; settings outside their ranges are errors too). Seeds above the
// limit are not trimmed: growing then adds nothing and reports hit_limit.
GrowResult grow_selection(const SelectionPoints& pts, const SelectionGraph& graph, const SelectionMask& seeds,
                          const GrowSettings& settings = {});
// The same with a graph built for this call (the editor keeps one per model instead).
GrowResult grow_selection(const SelectionPoints& pts, const SelectionMask& seeds, const GrowSettings& settings = {});

// Erodes the selection `steps` times: each step deselects every selected Gaussian with an unselected graph
// neighbour. A selection with no unselected neighbour at all (an isolated object) does not shrink.
SelectionMask shrink_selection(const SelectionGraph& graph, const SelectionMask& mask, int steps = 1);
// Dilates it `steps` times: each step selects every unselected Gaussian with a selected graph neighbour
// (no similarity test: a plain "grow by one ring of neighbours").
SelectionMask dilate_selection(const SelectionGraph& graph, const SelectionMask& mask, int steps = 1);

}  // namespace goris
