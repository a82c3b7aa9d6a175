#pragma once
// Target selection for object removal (docs/design/maths.md, Stage 2; paper Sec. 3.3): the one header the
// editor and the CLI include. A selection is a SelectionMask, one byte per Gaussian of the model
// (1 = target).
//
// Seeds (pick one of):
//   select_by_label(pts, {threshold})      learned label > 0.3, closed by the hull of the selected centres
//                                          (removal/selection/selection_labels.h)
//   labels_from_masks(model, views, ...)   2D object masks, depth-tested votes  (selection_masks.h)
//   GaussianPicker / pick_gaussian(...)    the Gaussian under a pixel           (selection_pick.h)
//   select_in_view_region(model, ...)      a rectangle / lasso / brush disc of a view, through the depth
//                                          or through everything                (selection_region.h)
//   select_sphere / select_box / select_by_colour   volumes and colour range     (removal/selection/selection_ops.h)
// Editing:
//   close_selection(pts, seeds, ...)       outliers out, then everything inside the hull / box added
//   grow_selection / shrink_selection      over the centres' kNN graph, slider 0..1, bounded
//                                          (removal/selection/selection_grow.h); dilate_selection adds rings
//   combine_selections / invert_selection  union, subtract, intersect          (removal/selection/selection_ops.h)
// Storing:
//   write_selection / read_selection       RUN/selection.json + selection.npy, stale-model checks
//                                          (removal/selection/selection_file.h)
//   apply_selection_to_labels(model, m)    the selection as the model's label channel
//   selection_view_mask(model, m, cam)     a view's object mask from the selection's coverage
//                                          (selection_view_masks.h)
// Showing:
//   render_selection_preview(...)          tinted | removed side by side       (selection_preview.h)
//
// Typical editor flow: pts = selection_points(model); graph = build_selection_graph(pts); picker =
// GaussianPicker(model); on click: p = picker.pick(cam, u, v); seeds = {p.gaussian}; on slider g:
// grow_selection(pts, graph, seeds, {.grow = g}); on save: write_selection(selection_json_path(run), ...).
#include "core/scene/select_hull.h"
#include "removal/selection/selection_file.h"
#include "removal/selection/selection_grow.h"
#include "removal/selection/selection_labels.h"
#include "removal/selection/selection_ops.h"
#include "removal/selection/selection_screen.h"
#include "core/scene/selection_points.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_pick.h"
#include "removal/selection/selection_preview.h"
#include "removal/selection/selection_region.h"
#include "removal/selection/selection_view_masks.h"
