#include "removal/selection/selection_grow.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/util/error.h"
#include "core/util/median.h"
#include "removal/selection/select_kdtree.h"

namespace goris {

SelectionGraph build_selection_graph(const SelectionPoints& pts, int k_wanted) {
  if (k_wanted < 1) throw Error("selection", "the neighbour graph needs k >= 1, got " + std::to_string(k_wanted));
  const std::size_t n = pts.size();
  SelectionGraph g;
  g.spacing.assign(n, 0.0f);
  g.offsets.assign(n + 1, 0);
  if (n < 2) return g;
  const int k = int(std::min<std::size_t>(std::size_t(k_wanted), n - 1));
  g.k = k;

  const PointKdTree tree(pts.position);
  std::vector<std::uint32_t> nb(n * std::size_t(k));
  std::vector<float> nd(n * std::size_t(k));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<Neighbor> found;
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const std::size_t i = tree.spatial_order()[s];
      tree.knn(pts.position[i], k, found, i);
      for (int j = 0; j < k; ++j) {
        nb[i * k + j] = found[j].index;
        nd[i * k + j] = std::sqrt(found[j].dist2);
      }
      g.spacing[i] = nd[i * k + (k - 1) / 2];  // sorted: the median of the k distances
    }
  });

  // Symmetrise: i also becomes a neighbour of every j in kNN(i) that does not list i itself.
  auto lists = [&](std::size_t j, std::uint32_t i) {
    const std::uint32_t* b = &nb[j * k];
    return std::find(b, b + k, i) != b + k;
  };
  std::vector<std::uint32_t> extra(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < k; ++a) {
      const std::uint32_t j = nb[i * k + a];
      if (!lists(j, std::uint32_t(i))) ++extra[j];
    }
  for (std::size_t i = 0; i < n; ++i) g.offsets[i + 1] = g.offsets[i] + std::uint32_t(k) + extra[i];
  g.neighbors.resize(g.offsets[n]);
  g.distances.resize(g.offsets[n]);
  std::vector<std::uint32_t> fill(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < k; ++a) {
      g.neighbors[g.offsets[i] + a] = nb[i * k + a];
      g.distances[g.offsets[i] + a] = nd[i * k + a];
    }
    fill[i] = g.offsets[i] + std::uint32_t(k);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < k; ++a) {
      const std::uint32_t j = nb[i * k + a];
      if (lists(j, std::uint32_t(i))) continue;
      g.neighbors[fill[j]] = std::uint32_t(i);
      g.distances[fill[j]] = nd[i * k + a];
      ++fill[j];
    }
  return g;
}

namespace {

// Seed sets smaller than this start their statistics from a median over their neighbourhood.
constexpr std::size_t kRobustStartBelow = 8;

struct Candidate {
  float cost;
  std::uint32_t id;
  bool operator>(const Candidate& o) const { return cost > o.cost || (cost == o.cost && id > o.id); }
};

struct Reference {
  glm::vec3 colour;
  float label;
};

// What grown Gaussians are compared with: the seeds' mean colour and label, or for fewer than
// kRobustStartBelow seeds (a click: one Gaussian, whose DC colour is a noisy sample of its surface, with
// highlights and view-dependent colour leaking into it) the component-wise median over the seeds and all
// their graph neighbours.
Reference reference_of(const SelectionPoints& pts, const SelectionGraph& graph, const SelectionMask& mask,
                       std::size_t seeds) {
  const std::size_t n = pts.size();
  Reference ref{glm::vec3(0.0f), 0.0f};
  if (seeds >= kRobustStartBelow) {
    glm::dvec3 c(0.0);
    double l = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (mask[i]) {
        c += glm::dvec3(pts.color[i]);
        l += pts.label[i];
      }
    ref.colour = glm::vec3(c / double(seeds));
    ref.label = float(l / double(seeds));
    return ref;
  }
  std::vector<float> cr, cg, cb, lab;
  auto take = [&](std::size_t j) {
    cr.push_back(pts.color[j].r);
    cg.push_back(pts.color[j].g);
    cb.push_back(pts.color[j].b);
    lab.push_back(pts.label[j]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    take(i);
    for (std::uint32_t e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) take(graph.neighbors[e]);
  }
  ref.colour = glm::vec3(median_of(std::move(cr)), median_of(std::move(cg)), median_of(std::move(cb)));
  ref.label = median_of(std::move(lab));
  return ref;
}

void check_settings(const GrowSettings& s) {
  auto in01 = [](float v) { return v >= 0.0f && v <= 1.0f; };
  if (!in01(s.grow)) throw Error("selection", "grow " + std::to_string(s.grow) + " is outside [0, 1]");
  if (!(s.max_fraction > 0.0f && s.max_fraction <= 1.0f))
    throw Error("selection", "max fraction " + std::to_string(s.max_fraction) + " is outside (0, 1]");
  if (!(s.colour_tolerance > 0.0f) || !(s.label_tolerance > 0.0f))
    throw Error("selection", "grow colour and label tolerances must be positive");
}

}  // namespace

GrowResult grow_selection(const SelectionPoints& pts, const SelectionGraph& graph, const SelectionMask& seeds,
                          const GrowSettings& s) {
  check_settings(s);
  const std::size_t n = pts.size();
  if (seeds.size() != n || graph.size() != n)
    throw Error("selection", "grow: seed mask (" + std::to_string(seeds.size()) + ") or neighbour graph (" +
                                 std::to_string(graph.size()) + ") does not match the " + std::to_string(n) +
                                 " Gaussians");
  GrowResult r;
  r.mask = seeds;
  for (auto& m : r.mask) m = m ? 1 : 0;
  r.seeds = count_selected(r.mask);
  r.limit = std::size_t(std::floor(double(s.max_fraction) * double(n)));
  if (r.seeds > r.limit) {
    r.hit_limit = true;
    return r;
  }
  if (s.grow <= 0.0f || r.seeds == 0) return r;

  const float tol_d = 1.0f + 2.0f * s.grow;
  const float tol_c = s.colour_tolerance * s.grow * s.grow;
  const float tol_l = s.label_tolerance * s.grow;
  const Reference ref = reference_of(pts, graph, r.mask, r.seeds);
  // Edge and node tests against fixed references: a larger g admits a superset of nodes and edges, so the
  // grown region (a connected component through them) only ever grows with the slider.
  auto cost_of = [&](std::uint32_t i, std::uint32_t j, float d) {
    const float sp = std::min(graph.spacing[i], graph.spacing[j]);
    const float geo = d <= 0.0f ? 0.0f : (sp > 0.0f ? d / sp : INFINITY);
    const float c = glm::length(pts.color[j] - ref.colour) / tol_c;
    const float l = std::abs(pts.label[j] - ref.label) / tol_l;
    return std::max({geo / tol_d, c, l});
  };
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> queue;
  auto push_neighbours = [&](std::uint32_t i) {
    for (std::uint32_t e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
      const std::uint32_t j = graph.neighbors[e];
      if (r.mask[j]) continue;
      const float c = cost_of(i, j, graph.distances[e]);
      if (c <= 1.0f) queue.push(Candidate{c, j});
    }
  };
  for (std::size_t i = 0; i < n; ++i)
    if (r.mask[i]) push_neighbours(std::uint32_t(i));

  // Most similar first, so that what growth holds when it meets the limit is the most similar part.
  std::size_t count = r.seeds;
  while (!queue.empty()) {
    const Candidate top = queue.top();
    queue.pop();
    if (r.mask[top.id]) continue;
    if (count + 1 > r.limit) {
      r.hit_limit = true;
      break;
    }
    r.mask[top.id] = 1;
    ++count;
    ++r.added;
    push_neighbours(top.id);
  }
  return r;
}

GrowResult grow_selection(const SelectionPoints& pts, const SelectionMask& seeds, const GrowSettings& settings) {
  check_settings(settings);
  return grow_selection(pts, build_selection_graph(pts), seeds, settings);
}

namespace {

// `steps` rounds of morphology over the graph: erode (shrink) deselects every selected Gaussian with an
// unselected neighbour, dilate selects every unselected Gaussian with a selected neighbour.
SelectionMask graph_morphology(const SelectionGraph& graph, const SelectionMask& mask, int steps, bool dilate) {
  const char* what = dilate ? "dilate" : "shrink";
  if (mask.size() != graph.size())
    throw Error("selection", std::string(what) + ": mask has " + std::to_string(mask.size()) +
                                 " entries for a graph of " + std::to_string(graph.size()) + " Gaussians");
  if (steps < 0) throw Error("selection", std::string(what) + " steps must be >= 0");
  SelectionMask cur = mask;
  for (auto& m : cur) m = m ? 1 : 0;
  const std::uint8_t from = dilate ? 0 : 1;  // the Gaussians a step may change
  for (int step = 0; step < steps; ++step) {
    SelectionMask next = cur;
    bool changed = false;
    for (std::size_t i = 0; i < cur.size(); ++i) {
      if (cur[i] != from) continue;
      for (std::uint32_t e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
        if (cur[graph.neighbors[e]] != from) {
          next[i] = 1 - from;
          changed = true;
          break;
        }
    }
    cur.swap(next);
    if (!changed) break;
  }
  return cur;
}

}  // namespace

SelectionMask shrink_selection(const SelectionGraph& graph, const SelectionMask& mask, int steps) {
  return graph_morphology(graph, mask, steps, false);
}

SelectionMask dilate_selection(const SelectionGraph& graph, const SelectionMask& mask, int steps) {
  return graph_morphology(graph, mask, steps, true);
}

}  // namespace goris
