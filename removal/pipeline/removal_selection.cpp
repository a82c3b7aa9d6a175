#include "removal/pipeline/removal_selection.h"

#include <algorithm>
#include <cstdint>

#include "core/scene/plane_from_masks.h"
#include "core/util/error.h"
#include "removal/selection/selection.h"
#include "removal/selection/target_underside.h"

namespace goris {

namespace {

Error selection_error(const std::string& problem) {
  return Error(std::string("goris remove (") + removal_step_name(RemovalStep::Selection) + "): " + problem);
}

// The target's mirror twin below a planar glossy surface (core/scene/mirror_twins.h). On an intrinsic model
// the plane is fitted to the flat glossy Gaussians (region < 0.5); on a radiance model it comes from the
// photos' glossy masks.
MirrorTwins mirror_twins_of(const GaussianModel& model, const std::vector<glm::vec3>& centres,
                            const SelectionMask& target, bool intrinsic, const std::vector<Camera>& cameras,
                            const std::vector<TrainView>& views) {
  // The plane comes from the photos' glossy masks where there are any (plane_from_masks.h), in both modes:
  // a radiance model of a mirror-like surface has no Gaussians on the surface to fit a plane to (it shows a
  // mirror world behind it), and an intrinsic model's flat glossy Gaussians can lie in another plane (the
  // tops of the objects on a mirror table) when few of them make the surface.
  const std::vector<const std::vector<float>*> masks = glossy_masks_of(views);
  if (std::any_of(masks.begin(), masks.end(), [](const auto* m) { return m != nullptr; })) {
    const PlaneFromMasks pm =
        plane_from_glossy_masks(cameras, masks, {}, target_rest_heights(cameras, masks, centres, target));
    if (pm.plane.found || !intrinsic) return twins_below_plane(centres, target, pm.plane);
  }
  // No masks, or no plane through them: the plane of the intrinsic model's flat glossy Gaussians (its region
  // channel).
  std::vector<std::uint8_t> glossy(model.count(), 0);
  if (intrinsic) {
    const std::vector<float> ex = model.tensor(Param::ExtraLogit).value.to_host();
    if (model.tensor(Param::ExtraLogit).width == extra::kCount)
      for (std::size_t i = 0; i < model.count(); ++i) glossy[i] = ex[i * extra::kCount + extra::kRegion] < 0.0f;
  }
  return select_mirror_twins(centres, glossy, target, {}, flat_normals(model));
}

}  // namespace

RemovalSelection select_for_removal(const std::filesystem::path& run_dir, const GaussianModel& model,
                                    const RemovalOptions& o, bool intrinsic, bool glossy_masks,
                                    const std::vector<Camera>& cameras, const std::vector<TrainView>& views) {
  RemovalSelection r;
  const SelectionPoints points = selection_points(model);  // one host copy for the labels, twin and underside
  if (std::filesystem::exists(selection_json_path(run_dir))) {
    StoredSelection st = read_selection(run_dir, model);
    r.selected = std::move(st.mask);
    r.record = st.record;
  } else {
    r.selected = select_by_label(points, {o.label_threshold, {}}).mask;
    r.record.method = "labels";
    r.record.parameters = {{"threshold", o.label_threshold}};
  }
  const std::size_t chosen = count_selected(r.selected);
  if (chosen == 0)
    throw selection_error("nothing is selected: no Gaussian has a label above " + std::to_string(o.label_threshold) +
                          " (train in intrinsic mode on a data set with object masks), and no RUN/selection.json "
                          "(make one with `goris select RUN --click VIEW X Y` or `--masks`)");
  if (chosen * 2 > model.count())
    throw selection_error(std::to_string(chosen) + " of " + std::to_string(model.count()) +
                          " Gaussians are selected (more than half the scene): the labels are not learned well "
                          "enough; select with `goris select RUN --masks` or `--labels --threshold 0.5`");
  r.target = r.selected;
  r.twins.assign(r.selected.size(), 0);
  // The glossy plane serves the twin and the planar reflection (and the shadow's support plane): it is
  // found unless both are switched off.
  const bool want_plane = !o.ablate.count("twins") || !o.ablate.count("reflection");
  if ((intrinsic || glossy_masks) && want_plane) {
    MirrorTwins t = mirror_twins_of(model, points.position, r.selected, intrinsic, cameras, views);
    r.glossy_plane = t.plane;
    // On a radiance model the twin stays: removing it opened see-through holes in the mirror world that the
    // fill did not close (on the generalization suite, docs/lab/2026-12-02-generalization-suite.md), while
    // the planar reflection mask repaints the reflection wherever the model keeps it.
    if (o.ablate.count("twins") || !intrinsic) t.twins.assign(t.twins.size(), 0), t.count = 0, t.candidates = 0;
    for (std::size_t i = 0; i < r.selected.size(); ++i) r.selected[i] |= t.twins[i];
    r.twins = t.twins;
    r.mirror_twins = t.count;
    r.record.parameters["mirror_twins"] = t.count;
    if (t.plane.found && t.count > 0)
      r.note = " (" + std::to_string(t.count) + " of them the target's mirror twin)";
    else if (t.plane.found && t.candidates > 0)
      r.note = "; no mirror twin (" + std::to_string(t.candidates) + " Gaussians mirror " +
               std::to_string(t.target_above) + " of the target's: not a mirror world)";
    else if (!t.plane.found && t.plane.candidates > 0)
      r.note = "; no mirror twin (no glossy plane: at most " + std::to_string(t.plane.inliers) + " of " +
               std::to_string(t.plane.candidates) + " flat glossy Gaussians lie in one)";
    else if (!t.plane.found)
      r.note = "; no mirror twin (no glossy plane: " + std::to_string(t.plane.glossy) + " glossy Gaussians, " +
               std::to_string(t.plane.candidates) + " of them flat)";
  }
  r.shadow_excluded = r.selected;
  if (r.glossy_plane.found && !o.ablate.count("underside")) {
    const SelectionMask under = target_underside(points.position, r.target, r.selected, r.glossy_plane);
    r.underside = count_selected(under);
    for (std::size_t i = 0; i < r.selected.size(); ++i) r.selected[i] |= under[i];
    r.record.parameters["underside"] = r.underside;
    if (r.underside) r.note += "; " + std::to_string(r.underside) + " under the target";
  }
  return r;
}

}  // namespace goris
