#pragma once
// Scripted mode (`goris-studio --script FILE`): one UI action per line, run through the same code paths
// as the mouse and the panels. Blank lines and lines starting with # are ignored.
//
//   open PATH                  open a data set or a run folder (waits until loaded)
//   out PATH                   run folder for the next `train` (default: a new folder, docs/user/editor.md)
//   set KEY VALUE              a training setting for a new run (a config.json key, VALUE as JSON or text)
//   train N                    train N more iterations with the session of the Training panel; waits
//   grid N                     N small viewports under the main one (0..8)
//   panels NAME...             expand these sidebar panels (Open, Training, Plots, Selection, Removal,
//                              Camera, Display), collapse the others
//   channel VIEWPORT NAME      VIEWPORT = main or a grid tile index 0..7; NAME as in the channel chooser
//   snap INDEX [train|test]    put the view camera on a data set camera (default: train)
//   click X Y                  a plain left click at pixel (X, Y) of the main viewport's image: reports what
//                              lies there and selects what it hits (a miss is reported, not a failure)
//   select_click X Y [add|remove]  the same with shift (add) or ctrl (remove); fails when nothing is hit
//   select_grow G              the grow / shrink slider, G in -1..1 (> 0 grows clicked regions, < 0 erodes)
//   select_labels              select by the learned object label (> 0.3, closed)
//   select_masks               select by the data set's training object masks (mask_XXX.png votes, closed)
//   select_rect X0 Y0 X1 Y1 [add|remove]       the Rect tool: Gaussians whose centre lies in this rectangle
//                              of the main viewport's image (only what the view shows, unless select_through all)
//   select_polygon X Y X Y X Y ... [add|remove]   the Lasso tool: the same inside this polygon
//   select_brush R X Y [X Y ...] [add|remove]     the Brush tool: a stroke through these points, radius R
//   select_through visible|all the screen tools take what the view shows, or everything behind it too
//   select_sphere CX CY CZ R [add|remove]         the Sphere tool: centres inside (world units)
//   select_box CX CY CZ HX HY HZ [RX RY RZ] [add|remove]   the Box tool: centre, half extents, degrees
//   select_colour R G B D [add|remove]            base colours within D of (R, G, B) (0..1)
//   select_tool NAME           choose the viewport's tool: click, rect, lasso, brush, sphere, box
//   invert                     select everything else (hidden and locked Gaussians stay out)
//   grow_step [N] | shrink_step [N]   N graph steps out / in (default 1)
//   hide | lock                hide (not drawn, not selectable) / lock (not selectable) the selection
//   unhide | unlock            show / unlock every Gaussian again
//   use_as_target_masks [DIR]  write every training view's object mask of the selection to DIR (default
//                              RUN/target_masks) and select by their votes: the removal's target
//   expect_selected MIN [MAX]  fails unless MIN..MAX Gaussians are selected (MAX default: MIN)
//   drag X Y X Y ... [shift|ctrl|alt]   the mouse: press the left button at the first point of the main
//                              viewport's image, move through the others, release (holding the key); waits
//                              for the selection edit it makes
//   press LABEL                the mouse presses the Selection panel's tool-bar button (or tool) LABEL,
//                              e.g. "Invert", "Grow step", "Sphere", "volume Select", "colour Add"; waits
//                              for the selection edit it makes
//   drag_handle NAME DX DY [shift|ctrl|alt]   the mouse drags the sphere / box tool's handle NAME (centre,
//                              radius, x, y, z) by (DX, DY) pixels of the main viewport's image; a size
//                              handle's DX is along its direction from the centre (outward), DY across it
//   two_click start [VIEW] | view N | click X Y | offered | take_back K | undo | cancel | use [ITERS] |
//             expect STEP      the Two-click panel (ui/document/two_click_flow.h): start on training view
//                              VIEW, show training view N, click at (X, Y) of the main viewport's image (the
//                              mouse's path), click the point offered in the second view, take back click K
//                              (1-based), undo a step, cancel the flow, use the masks and remove (waits
//                              until the removal has ended, fails unless it finished), or fail unless the
//                              flow is at STEP (off, first_click, second_click, review, removing, done);
//                              each waits until the flow's step is done and fails when it failed
//   undo | redo                undo / redo the last selection edit
//   save_selection             write RUN/selection.json (+ .npy) for `goris remove`
//   remove [ITERS]             run stage 2 on the run (ITERS fine-tune iterations; default: the panel's);
//                              waits until it has finished, fails when it fails or is cancelled
//   remove_start [ITERS]       starts stage 2 and goes on at once (progress screenshots, cancelling)
//   remove_wait                waits for the running removal; fails unless it completes
//   remove_cancel              cancels the running removal and waits until it has stopped
//   expect_step_complete       fails unless every stage-2 step of the last removal reached 100 %
//   export_dialog [open|close] show or hide the Export dialog (File > Export...; default: open)
//   export_from run|removal    what the dialog exports: the run, or its cleaned scene RUN/removal
//   export                     the Export dialog's button with its choices as they are (the remembered
//                              settings); waits like the lines below
//   export ply PATH            the Export dialog's button with only "intrinsic PLY" chosen, to PATH
//   export baked PATH [ITERS]  ... only "baked PLY" (ITERS distillation iterations; default: the dialog's)
//   export renders DIR [test|train|orbit] [N]   ... only "renders" (default: test, N = 0: every view;
//                              orbit: N frames, 0 = 36); each `export` waits until it has finished and fails
//                              when it fails or is cancelled
//   export_start [WHAT ...]    the same as `export`, going on at once (progress screenshots, cancelling)
//   export_wait                waits for the running export; fails unless it completes
//   export_cancel              cancels the running export and waits until it has stopped
//   expect_export_error [TEXT] waits for the export to end; fails unless it failed with TEXT in its message
//   import_capture INPUT OUT [--max-images N] [--resolution W] [--matcher exhaustive|sequential] [--masks DIR]
//                              the Open panel's "Import photos / video" (COLMAP: a folder of photos or a
//                              video into the new data set OUT); waits until it has ended and the new data
//                              set is open, fails when the import fails or is cancelled
//   import_capture_start INPUT OUT [...]   the same, going on at once (progress screenshots, cancelling)
//   import_wait                waits for the running import; fails unless it completes and its data set opens
//   import_cancel              cancels the running import and waits until it has stopped
//   expect_import_error [TEXT] waits for the import to end; fails unless it failed with TEXT in its message
//   compare MODE [SPLIT]       off | side_by_side | slider (SPLIT in 0..1 for the slider)
//   compare_with photo|before  what the compare modes set the render against: the nearest input photo, or
//                              (a cleaned scene) the scene with the target
//   before_after before|after  a cleaned scene (opened, or shown when a removal finishes): show the scene
//                              with the target, or the cleaned one
//   screenshot PATH            the whole window as PNG, plus PATH's stem + .layout.json (viewport rectangles),
//                              once nothing runs and the display has settled
//   screenshot_now PATH        the same at the next frame, while work goes on (progress displays)
//   wait_frames N              let N frames pass
//   quit                       close the editor (exit status 0)
//
// PATH is the rest of the line (it may contain spaces; surrounding double quotes are removed), except in
// `export` and `import_capture` lines, where PATH is one word or a double-quoted string; relative paths
// are taken from the current directory. X and Y may be given in percent of the image ("45%").
#include <filesystem>
#include <string>
#include <vector>

#include "render/maps/channels.h"
#include "ui/selection/selection_edit.h"

namespace goris::ui {

struct ScriptAction {
  enum class Kind {
    Open, Out, Set, Train, Grid, Panels, Channel, Snap, Click, SelectClick, SelectGrow, SelectLabels, SelectMasks, Undo, Redo,
    SaveSelection, Remove, RemoveStart, RemoveWait, RemoveCancel, ExpectStepComplete, ExportDialog, ExportFrom,
    Export, ExportStart, ExportWait, ExportCancel, ExpectExportError, Compare, CompareWith, BeforeAfter, Screenshot, ScreenshotNow,
    WaitFrames, Quit, SelectRect, SelectPolygon, SelectBrush, SelectThrough, SelectSphere, SelectBox, SelectColour,
    SelectTool, Invert, GrowStep, ShrinkStep, Hide, Lock, Unhide, Unlock, UseAsTargetMasks, ExpectSelected, Drag,
    ImportCapture, ImportCaptureStart, ImportWait, ImportCancel, ExpectImportError, Press, DragHandle, TwoClick
  };
  // A coordinate on the main viewport's image: pixels, or a fraction of its width / height ("45%").
  struct Coord {
    float value = 0;
    bool fraction = false;
  };
  Kind kind = Kind::Quit;
  int line = 0;            // 1-based line in the script
  std::string path;        // open, out, screenshot, export, use_as_target_masks
  std::string what;        // export: ply | baked | renders ("": the dialog's choices); export_from: run | removal;
                           // select_through: visible | all; select_tool: its name;
                           // export_dialog: open | close; compare_with: photo | before; before_after: before | after;
                           // drag_handle: the handle; two_click: the step (start, view, click, ...)
  std::string render_path = "test";  // export renders
  std::string text;        // expect_export_error, expect_import_error; press: the label
  // import_capture: path = INPUT, out = OUT, count = --max-images, width = --resolution
  std::string out, masks, matcher = "exhaustive";
  int width = 0;
  std::vector<std::string> names;  // panels
  std::string key, value;  // set
  int count = 0;           // train, grid, wait_frames, remove, export (0 = default); grow_step, shrink_step;
                           // expect_selected MIN
  int count_max = 0;       // expect_selected MAX
  int viewport = -1;       // channel: -1 = main, else grid tile index
  Channel channel = Channel::Final;
  int camera = 0;           // snap
  bool test_split = false;  // snap ... test
  float x = 0, y = 0;       // click, select_click (pixels, or fractions of the image when *_fraction)
  bool x_fraction = false, y_fraction = false;
  std::string select_mode = "replace";  // select_click, select_rect, ...: replace | add | remove
  std::string modifier;                 // drag: "", shift, ctrl or alt
  std::vector<Coord> coords;            // select_rect, select_polygon, select_brush: x, y, x, y, ...
  Coord radius;                         // select_brush (a fraction: of the image's width)
  std::vector<float> values;            // select_sphere, select_box, select_colour
  float grow = 0;                       // select_grow
  std::string mode;         // compare
  float split = 0.5f;       // compare slider position
};

// The name of an action kind as written in scripts ("open", "train", ...).
const char* action_name(ScriptAction::Kind kind);

// Parses a whole script; `source` names it in errors ("FILE:LINE: problem"). Throws goris::Error for an
// unknown action, missing or extra arguments, or a bad number.
std::vector<ScriptAction> parse_script(const std::string& text, const std::string& source);
// Reads and parses a script file; throws goris::Error naming the file when it cannot be read.
std::vector<ScriptAction> load_script(const std::filesystem::path& path);

}  // namespace goris::ui
