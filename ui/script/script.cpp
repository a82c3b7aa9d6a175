#include "ui/script/script.h"

#include <algorithm>
#include <charconv>
#include <iterator>
#include <fstream>
#include <sstream>

#include "core/util/error.h"
#include "ui/selection/selection_tools.h"

namespace goris::ui {

namespace {

using Kind = ScriptAction::Kind;

struct KindName {
  Kind kind;
  const char* name;
};
constexpr KindName kNames[] = {{Kind::Open, "open"},
                               {Kind::Out, "out"},
                               {Kind::Set, "set"},
                               {Kind::Train, "train"},
                               {Kind::Grid, "grid"},
                               {Kind::Panels, "panels"},
                               {Kind::Channel, "channel"},
                               {Kind::Snap, "snap"},
                               {Kind::Click, "click"},
                               {Kind::SelectClick, "select_click"},
                               {Kind::SelectGrow, "select_grow"},
                               {Kind::SelectLabels, "select_labels"},
                               {Kind::SelectMasks, "select_masks"},
                               {Kind::Undo, "undo"},
                               {Kind::Redo, "redo"},
                               {Kind::SaveSelection, "save_selection"},
                               {Kind::Remove, "remove"},
                               {Kind::RemoveStart, "remove_start"},
                               {Kind::RemoveWait, "remove_wait"},
                               {Kind::RemoveCancel, "remove_cancel"},
                               {Kind::ExpectStepComplete, "expect_step_complete"},
                               {Kind::ExportDialog, "export_dialog"},
                               {Kind::ExportFrom, "export_from"},
                               {Kind::Export, "export"},
                               {Kind::ExportStart, "export_start"},
                               {Kind::ExportWait, "export_wait"},
                               {Kind::ExportCancel, "export_cancel"},
                               {Kind::ExpectExportError, "expect_export_error"},
                               {Kind::Compare, "compare"},
                               {Kind::CompareWith, "compare_with"},
                               {Kind::BeforeAfter, "before_after"},
                               {Kind::Screenshot, "screenshot"},
                               {Kind::ScreenshotNow, "screenshot_now"},
                               {Kind::WaitFrames, "wait_frames"},
                               {Kind::Quit, "quit"},
                               {Kind::SelectRect, "select_rect"},
                               {Kind::SelectPolygon, "select_polygon"},
                               {Kind::SelectBrush, "select_brush"},
                               {Kind::SelectThrough, "select_through"},
                               {Kind::SelectSphere, "select_sphere"},
                               {Kind::SelectBox, "select_box"},
                               {Kind::SelectColour, "select_colour"},
                               {Kind::SelectTool, "select_tool"},
                               {Kind::Invert, "invert"},
                               {Kind::GrowStep, "grow_step"},
                               {Kind::ShrinkStep, "shrink_step"},
                               {Kind::Hide, "hide"},
                               {Kind::Lock, "lock"},
                               {Kind::Unhide, "unhide"},
                               {Kind::Unlock, "unlock"},
                               {Kind::UseAsTargetMasks, "use_as_target_masks"},
                               {Kind::ExpectSelected, "expect_selected"},
                               {Kind::Drag, "drag"},
                               {Kind::ImportCapture, "import_capture"},
                               {Kind::ImportCaptureStart, "import_capture_start"},
                               {Kind::ImportWait, "import_wait"},
                               {Kind::ImportCancel, "import_cancel"},
                               {Kind::ExpectImportError, "expect_import_error"},
                               {Kind::Press, "press"},
                               {Kind::DragHandle, "drag_handle"},
                               {Kind::TwoClick, "two_click"}};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> words;
  std::istringstream in(s);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// Words, where a double-quoted string (spaces allowed) is one word without its quotes; an unmatched
// quote sets `problem`.
std::vector<std::string> split_quoted(const std::string& s, std::string& problem) {
  std::vector<std::string> words;
  size_t i = 0;
  while (i < s.size()) {
    if (s[i] == ' ' || s[i] == '\t' || s[i] == '\r') {
      ++i;
      continue;
    }
    if (s[i] == '"') {
      const size_t end = s.find('"', i + 1);
      if (end == std::string::npos) {
        problem = "unmatched double quote";
        return words;
      }
      words.push_back(s.substr(i + 1, end - i - 1));
      i = end + 1;
      continue;
    }
    const size_t end = s.find_first_of(" \t\r", i);
    words.push_back(s.substr(i, end == std::string::npos ? std::string::npos : end - i));
    i = end == std::string::npos ? s.size() : end;
  }
  return words;
}

class LineParser {
 public:
  LineParser(std::string where, std::string name) : where_(std::move(where)), name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& problem) const { throw Error(where_, name_ + ": " + problem); }

  void expect_args(const std::vector<std::string>& args, size_t lo, size_t hi, const char* usage) const {
    if (args.size() < lo || args.size() > hi) fail("expected '" + std::string(usage) + "'");
  }
  int integer(const std::string& s, int lo, int hi, const char* what) const {
    int v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size()) fail(std::string(what) + " '" + s + "' is not a whole number");
    if (v < lo || v > hi)
      fail(std::string(what) + " " + s + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
  }
  float number(const std::string& s, const char* what) const {
    float v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || !(v == v))
      fail(std::string(what) + " '" + s + "' is not a number");
    return v;
  }
  // A coordinate in pixels, or in percent of the image ("45%", 0..100).
  float coordinate(const std::string& s, const char* what, bool& fraction) const {
    fraction = !s.empty() && s.back() == '%';
    if (!fraction) return number(s, what);
    const float v = number(s.substr(0, s.size() - 1), what);
    if (v < 0 || v > 100) fail(std::string(what) + " " + s + " is outside 0%..100%");
    return v / 100.0f;
  }
  std::string path(const std::string& rest) const {
    std::string p = trim(rest);
    if (p.size() >= 2 && p.front() == '"' && p.back() == '"') p = p.substr(1, p.size() - 2);
    if (p.empty()) fail("expected a path");
    return p;
  }

 private:
  std::string where_, name_;
};

// two_click STEP [ARGS]: the step in `what`; a view, click or iteration count in `count` (-1: none given),
// a click's coordinates in x, y.
void parse_two_click(const LineParser& p, const std::vector<std::string>& args, ScriptAction& a) {
  const char* usage = "two_click start [VIEW] | view N | click X Y | offered | take_back K | undo | cancel | use "
                      "[ITERS] | expect STEP";
  if (args.empty()) p.fail(std::string("expected '") + usage + "'");
  a.what = args[0];
  a.count = -1;
  const std::string& w = a.what;
  if (w == "start" || w == "use") {
    p.expect_args(args, 1, 2, usage);
    if (args.size() == 2) a.count = p.integer(args[1], 0, 1000000, w == "use" ? "ITERS" : "VIEW");
  } else if (w == "view" || w == "take_back") {
    p.expect_args(args, 2, 2, usage);
    a.count = p.integer(args[1], w == "view" ? 0 : 1, 1000000, w == "view" ? "N" : "K");
  } else if (w == "click") {
    p.expect_args(args, 3, 3, usage);
    a.x = p.coordinate(args[1], "X", a.x_fraction);
    a.y = p.coordinate(args[2], "Y", a.y_fraction);
  } else if (w == "offered" || w == "undo" || w == "cancel") {
    p.expect_args(args, 1, 1, usage);
  } else if (w == "expect") {
    p.expect_args(args, 2, 2, usage);
    static const char* kSteps[] = {"off", "first_click", "second_click", "review", "removing", "done"};
    if (std::find(std::begin(kSteps), std::end(kSteps), args[1]) == std::end(kSteps))
      p.fail("unknown step '" + args[1] + "' (off, first_click, second_click, review, removing, done)");
    a.text = args[1];
  } else {
    p.fail("unknown step '" + w + "' (" + usage + ")");
  }
}

// A trailing "add" or "remove" sets the selection mode and is taken off `args`.
void take_select_mode(std::vector<std::string>& args, ScriptAction& a) {
  if (!args.empty() && (args.back() == "add" || args.back() == "remove")) {
    a.select_mode = args.back();
    args.pop_back();
  }
}

// Coordinates "x y x y ..." (pixels or percent), at least `min_points` pairs.
void parse_coords(const LineParser& p, const std::vector<std::string>& args, size_t first, size_t min_points,
                  const char* usage, ScriptAction& a) {
  if (args.size() < first + 2 * min_points || (args.size() - first) % 2 != 0) p.fail(std::string("expected '") + usage + "'");
  for (size_t k = first; k < args.size(); ++k) {
    ScriptAction::Coord c;
    c.value = p.coordinate(args[k], k % 2 == first % 2 ? "X" : "Y", c.fraction);
    a.coords.push_back(c);
  }
}

// Exactly one of `counts` numbers.
void parse_values(const LineParser& p, const std::vector<std::string>& args, std::vector<size_t> counts,
                  const char* usage, ScriptAction& a) {
  bool ok = false;
  for (size_t c : counts) ok |= args.size() == c;
  if (!ok) p.fail(std::string("expected '") + usage + "'");
  for (const std::string& s : args) a.values.push_back(p.number(s, "value"));
}

ScriptAction parse_line(const std::string& line, const std::string& where) {
  const std::string text = trim(line);
  const size_t sp = text.find_first_of(" \t");
  const std::string name = text.substr(0, sp);
  const std::string rest = sp == std::string::npos ? "" : text.substr(sp + 1);
  std::vector<std::string> args = split_words(rest);
  LineParser p(where, name);

  ScriptAction a;
  bool known = false;
  for (const KindName& k : kNames)
    if (name == k.name) {
      a.kind = k.kind;
      known = true;
    }
  if (!known) {
    std::string list;
    for (const KindName& k : kNames) list += (list.empty() ? "" : ", ") + std::string(k.name);
    throw Error(where, "unknown action '" + name + "' (known: " + list + ")");
  }
  switch (a.kind) {
    case Kind::Open:
    case Kind::Out:
    case Kind::Screenshot:
    case Kind::ScreenshotNow:
      a.path = p.path(rest);
      break;
    case Kind::Set: {
      p.expect_args(args, 2, size_t(-1), "set KEY VALUE");
      a.key = args[0];
      a.value = trim(trim(rest).substr(args[0].size()));
      break;
    }
    case Kind::Train:
      p.expect_args(args, 1, 1, "train N");
      a.count = p.integer(args[0], 1, 100000000, "iteration count");
      break;
    case Kind::Grid:
      p.expect_args(args, 1, 1, "grid N");
      a.count = p.integer(args[0], 0, 8, "tile count");
      break;
    case Kind::Panels:
      a.names = args;  // checked against the editor's panels when the line runs
      break;
    case Kind::WaitFrames:
      p.expect_args(args, 1, 1, "wait_frames N");
      a.count = p.integer(args[0], 0, 1000000, "frame count");
      break;
    case Kind::Channel: {
      p.expect_args(args, 2, 2, "channel VIEWPORT NAME");
      a.viewport = args[0] == "main" ? -1 : p.integer(args[0], 0, 7, "viewport");
      const auto c = channel_from_id(args[1]);
      if (!c) p.fail("unknown channel '" + args[1] + "' (" + channel_id_list() + ")");
      a.channel = *c;
      break;
    }
    case Kind::Snap:
      p.expect_args(args, 1, 2, "snap INDEX [train|test]");
      a.camera = p.integer(args[0], 0, 1000000, "camera index");
      if (args.size() == 2) {
        if (args[1] != "train" && args[1] != "test") p.fail("expected train or test, not '" + args[1] + "'");
        a.test_split = args[1] == "test";
      }
      break;
    case Kind::Click:
      p.expect_args(args, 2, 2, "click X Y");
      a.x = p.coordinate(args[0], "X", a.x_fraction);
      a.y = p.coordinate(args[1], "Y", a.y_fraction);
      break;
    case Kind::SelectClick:
      p.expect_args(args, 2, 3, "select_click X Y [add|remove]");
      a.x = p.coordinate(args[0], "X", a.x_fraction);
      a.y = p.coordinate(args[1], "Y", a.y_fraction);
      if (args.size() == 3) {
        if (args[2] != "add" && args[2] != "remove") p.fail("expected add or remove, not '" + args[2] + "'");
        a.select_mode = args[2];
      }
      break;
    case Kind::SelectGrow:
      p.expect_args(args, 1, 1, "select_grow G");
      a.grow = p.number(args[0], "G");
      if (a.grow < -1 || a.grow > 1) p.fail("G " + args[0] + " is outside -1..1");
      break;
    case Kind::Remove:
    case Kind::RemoveStart:
      p.expect_args(args, 0, 1, a.kind == Kind::Remove ? "remove [ITERS]" : "remove_start [ITERS]");
      a.count = args.empty() ? 0 : p.integer(args[0], 1, 100000000, "iteration count");
      break;
    case Kind::ExportDialog:
      p.expect_args(args, 0, 1, "export_dialog [open|close]");
      a.what = args.empty() ? "open" : args[0];
      if (a.what != "open" && a.what != "close") p.fail("expected open or close, not '" + a.what + "'");
      break;
    case Kind::ExportFrom:
      p.expect_args(args, 1, 1, "export_from run|removal");
      a.what = args[0];
      if (a.what != "run" && a.what != "removal") p.fail("expected run or removal, not '" + a.what + "'");
      break;
    case Kind::Export:
    case Kind::ExportStart: {
      std::string problem;
      const std::vector<std::string> w = split_quoted(rest, problem);
      if (!problem.empty()) p.fail(problem);
      const char* usage =
          "export | export ply PATH | export baked PATH [ITERS] | export renders DIR [test|train|orbit] [N]";
      if (w.empty()) break;  // the dialog's choices as they are
      if (w.size() < 2) p.fail(std::string("expected '") + usage + "'");
      a.what = w[0];
      a.path = w[1];
      if (a.path.empty()) p.fail("expected a path");
      if (a.what == "ply") {
        if (w.size() != 2) p.fail("expected 'export ply PATH'");
      } else if (a.what == "baked") {
        if (w.size() > 3) p.fail("expected 'export baked PATH [ITERS]'");
        if (w.size() == 3) a.count = p.integer(w[2], 1, 100000000, "iteration count");
      } else if (a.what == "renders") {
        size_t k = 2;
        if (k < w.size() && (w[k] == "test" || w[k] == "train" || w[k] == "orbit")) a.render_path = w[k++];
        if (k < w.size()) a.count = p.integer(w[k++], 0, 100000, "frame count");
        if (k != w.size()) p.fail("expected 'export renders DIR [test|train|orbit] [N]'");
      } else {
        p.fail("unknown export '" + a.what + "' (ply, baked, renders)");
      }
      break;
    }
    case Kind::ImportCapture:
    case Kind::ImportCaptureStart: {
      std::string problem;
      const std::vector<std::string> w = split_quoted(rest, problem);
      if (!problem.empty()) p.fail(problem);
      const std::string usage = std::string(action_name(a.kind)) +
                                " INPUT OUT [--max-images N] [--resolution W] [--matcher exhaustive|sequential] "
                                "[--masks DIR]";
      if (w.size() < 2 || w[0].empty() || w[1].empty()) p.fail("expected '" + usage + "'");
      a.path = w[0];
      a.out = w[1];
      for (size_t k = 2; k < w.size(); k += 2) {
        if (k + 1 >= w.size()) p.fail("'" + w[k] + "' needs a value ('" + usage + "')");
        const std::string& v = w[k + 1];
        if (w[k] == "--max-images") a.count = p.integer(v, 0, 100000, "--max-images");
        else if (w[k] == "--resolution") a.width = p.integer(v, 0, 100000, "--resolution");
        else if (w[k] == "--matcher" && (v == "exhaustive" || v == "sequential")) a.matcher = v;
        else if (w[k] == "--matcher") p.fail("unknown matcher '" + v + "' (exhaustive, sequential)");
        else if (w[k] == "--masks") a.masks = v;
        else p.fail("unknown option '" + w[k] + "' ('" + usage + "')");
      }
      break;
    }
    case Kind::ImportWait:
    case Kind::ImportCancel:
      p.expect_args(args, 0, 0, action_name(a.kind));
      break;
    case Kind::ExpectImportError:
    case Kind::ExpectExportError: {
      a.text = trim(rest);
      if (a.text.size() >= 2 && a.text.front() == '"' && a.text.back() == '"')
        a.text = a.text.substr(1, a.text.size() - 2);
      break;
    }
    case Kind::ExportWait:
    case Kind::ExportCancel:
    case Kind::SelectLabels:
    case Kind::SelectMasks:
    case Kind::Undo:
    case Kind::Redo:
    case Kind::SaveSelection:
    case Kind::RemoveWait:
    case Kind::RemoveCancel:
    case Kind::ExpectStepComplete:
      p.expect_args(args, 0, 0, action_name(a.kind));
      break;
    case Kind::Compare:
      p.expect_args(args, 1, 2, "compare off|side_by_side|slider [SPLIT]");
      a.mode = args[0];
      if (a.mode != "off" && a.mode != "side_by_side" && a.mode != "slider")
        p.fail("unknown mode '" + a.mode + "' (off, side_by_side, slider)");
      if (args.size() == 2) {
        a.split = p.number(args[1], "split");
        if (a.split < 0 || a.split > 1) p.fail("split " + args[1] + " is outside 0..1");
      }
      break;
    case Kind::CompareWith:
      p.expect_args(args, 1, 1, "compare_with photo|before");
      a.what = args[0];
      if (a.what != "photo" && a.what != "before") p.fail("expected photo or before, not '" + a.what + "'");
      break;
    case Kind::BeforeAfter:
      p.expect_args(args, 1, 1, "before_after before|after");
      a.what = args[0];
      if (a.what != "before" && a.what != "after") p.fail("expected before or after, not '" + a.what + "'");
      break;
    case Kind::Quit:
    case Kind::Invert:
    case Kind::Hide:
    case Kind::Lock:
    case Kind::Unhide:
    case Kind::Unlock:
      p.expect_args(args, 0, 0, action_name(a.kind));
      break;
    case Kind::SelectRect:
      take_select_mode(args, a);
      p.expect_args(args, 4, 4, "select_rect X0 Y0 X1 Y1 [add|remove]");
      parse_coords(p, args, 0, 2, "select_rect X0 Y0 X1 Y1 [add|remove]", a);
      break;
    case Kind::SelectPolygon:
      take_select_mode(args, a);
      parse_coords(p, args, 0, 3, "select_polygon X Y X Y X Y ... [add|remove]", a);
      break;
    case Kind::SelectBrush:
      take_select_mode(args, a);
      if (args.empty()) p.fail("expected 'select_brush R X Y [X Y ...] [add|remove]'");
      a.radius.value = p.coordinate(args[0], "R", a.radius.fraction);
      if (!(a.radius.value > 0)) p.fail("the radius must be positive");
      parse_coords(p, args, 1, 1, "select_brush R X Y [X Y ...] [add|remove]", a);
      break;
    case Kind::SelectThrough:
      p.expect_args(args, 1, 1, "select_through visible|all");
      a.what = args[0];
      if (a.what != "visible" && a.what != "all") p.fail("expected visible or all, not '" + a.what + "'");
      break;
    case Kind::SelectSphere:
      take_select_mode(args, a);
      parse_values(p, args, {4}, "select_sphere CX CY CZ R [add|remove]", a);
      if (a.values[3] < 0) p.fail("the radius must not be negative");
      break;
    case Kind::SelectBox:
      take_select_mode(args, a);
      parse_values(p, args, {6, 9}, "select_box CX CY CZ HX HY HZ [RX RY RZ] [add|remove]", a);
      if (a.values[3] < 0 || a.values[4] < 0 || a.values[5] < 0) p.fail("half extents must not be negative");
      break;
    case Kind::SelectColour:
      take_select_mode(args, a);
      parse_values(p, args, {4}, "select_colour R G B D [add|remove]", a);
      if (a.values[3] < 0) p.fail("the distance must not be negative");
      break;
    case Kind::SelectTool:
      p.expect_args(args, 1, 1, "select_tool click|rect|lasso|brush|sphere|box");
      if (!select_tool_from_id(args[0])) p.fail("unknown tool '" + args[0] + "' (click, rect, lasso, brush, sphere, box)");
      a.what = args[0];
      break;
    case Kind::GrowStep:
    case Kind::ShrinkStep:
      p.expect_args(args, 0, 1, a.kind == Kind::GrowStep ? "grow_step [N]" : "shrink_step [N]");
      a.count = args.empty() ? 1 : p.integer(args[0], 1, 100, "step count");
      break;
    case Kind::UseAsTargetMasks:
      if (!trim(rest).empty()) a.path = p.path(rest);
      break;
    case Kind::Drag:
      if (!args.empty() && (args.back() == "shift" || args.back() == "ctrl" || args.back() == "alt")) {
        a.modifier = args.back();
        args.pop_back();
      }
      parse_coords(p, args, 0, 2, "drag X Y X Y ... [shift|ctrl|alt]", a);
      break;
    case Kind::Press:
      a.text = trim(rest);
      if (a.text.empty()) p.fail("expected a button's label");
      break;
    case Kind::DragHandle:
      if (!args.empty() && (args.back() == "shift" || args.back() == "ctrl" || args.back() == "alt")) {
        a.modifier = args.back();
        args.pop_back();
      }
      p.expect_args(args, 3, 3, "drag_handle centre|radius|x|y|z DX DY [shift|ctrl|alt]");
      if (args[0] != "centre" && args[0] != "radius" && args[0] != "x" && args[0] != "y" && args[0] != "z")
        p.fail("unknown handle '" + args[0] + "' (centre, radius, x, y, z)");
      a.what = args[0];
      a.values = {p.number(args[1], "DX"), p.number(args[2], "DY")};
      break;
    case Kind::TwoClick:
      parse_two_click(p, args, a);
      break;
    case Kind::ExpectSelected:
      p.expect_args(args, 1, 2, "expect_selected MIN [MAX]");
      a.count = p.integer(args[0], 0, 2000000000, "MIN");
      a.count_max = args.size() == 2 ? p.integer(args[1], a.count, 2000000000, "MAX") : a.count;
      break;
  }
  return a;
}

}  // namespace

const char* action_name(ScriptAction::Kind kind) {
  for (const KindName& k : kNames)
    if (k.kind == kind) return k.name;
  return "?";
}

std::vector<ScriptAction> parse_script(const std::string& text, const std::string& source) {
  std::vector<ScriptAction> actions;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    ScriptAction a = parse_line(t, source + ":" + std::to_string(number));
    a.line = number;
    actions.push_back(std::move(a));
  }
  return actions;
}

std::vector<ScriptAction> load_script(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), std::filesystem::exists(path) ? "cannot be read" : "no such script file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_script(text.str(), path.string());
}

}  // namespace goris::ui
