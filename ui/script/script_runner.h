#pragma once
// Runs a parsed script one step per GUI frame, through the same AppState actions as the mouse and the
// panels. Actions that change what is shown wait until the display has settled (the open finished,
// training done, the new frame rendered and drawn) before the next line runs, so screenshots are
// deterministic.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "ui/document/app_state.h"
#include "ui/script/script.h"
#include "ui/script/scripted_mouse.h"

namespace goris::ui {

// GUI frame times while the trainer ran (the editor must stay responsive meanwhile).
struct FrameStats {
  long frames = 0;
  double mean_ms = 0, max_ms = 0;
};

// What the runner needs from the editor besides the AppState.
class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  virtual AppState& state() = 0;
  // Nothing in flight: no open, no training, no render queued, the last frame drawn for a while.
  virtual bool settled() const = 0;
  // Size in window pixels of the main viewport's image (0 x 0 without one).
  virtual glm::vec2 main_image_size() const = 0;
  // Its top left corner in window pixels.
  virtual glm::vec2 main_image_origin() const { return {0, 0}; }
  // Drives the mouse from the next frame on (`drag`); nullopt gives it back to the real pointer.
  virtual void set_scripted_mouse(const std::optional<ScriptedMouse>& /*mouse*/) {}
  // Asks for a screenshot at the end of this frame; screenshot_pending() turns false when it is written,
  // screenshot_error() then says whether it failed.
  virtual void request_screenshot(const std::filesystem::path& png) = 0;
  virtual bool screenshot_pending() const = 0;
  virtual std::optional<std::string> screenshot_error() const = 0;
  virtual void quit() = 0;
  // Expands the sidebar panels with these titles and collapses the others (case-insensitive); throws
  // goris::Error naming an unknown title. Hosts without panels ignore it.
  virtual void show_panels(const std::vector<std::string>& /*titles*/) {}
  // Frame times since the last training started (zero frames when unknown).
  virtual FrameStats training_frame_stats() const { return {}; }
};

class ScriptRunner {
 public:
  enum class Status { Running, Finished, Failed };
  ScriptRunner(std::vector<ScriptAction> actions, std::string source);

  // One frame's worth: starts the current action or checks whether it has completed.
  Status step(ScriptHost& host);
  Status status() const { return status_; }
  // "FILE:LINE: action: problem" once Failed.
  const std::string& error() const { return error_; }
  // The line being run (0 when finished), for the status bar.
  int current_line() const;

 private:
  bool run_action(ScriptHost& host, const ScriptAction& a);  // true when the action is complete
  // Selection edits: starts one (phase 0), waits for its job, fails on its error when `strict`, then waits
  // until the tinted frame is shown.
  bool run_selection_edit(ScriptHost& host, const ScriptAction& a, bool strict,
                          const std::function<std::uint64_t()>& start);
  // Plays a drag (the mouse of one frame per step), then waits for the edit it made.
  bool run_drag(ScriptHost& host, const ScriptAction& a);
  // The tool bar's buttons, the volume handles and the two-click flow (ui/script/script_tools.cpp).
  bool run_press(ScriptHost& host, const ScriptAction& a);
  bool run_drag_handle(ScriptHost& host, const ScriptAction& a);
  bool run_two_click(ScriptHost& host, const ScriptAction& a);
  // Starts the removal (or, with !start, takes the running one) and waits until it has ended.
  bool run_remove(ScriptHost& host, const ScriptAction& a, bool start);
  // The lines on one of the editor's background jobs: Run starts it and waits until it is done, Start only
  // starts it, Wait waits for the one started, Cancel cancels the running one and waits until it has
  // ended, ExpectError waits for the one started to fail with the line's text in its status.
  enum class JobLine { Run, Start, Wait, Cancel, ExpectError };
  // What those lines need of a job (the export, the import).
  struct JobLines {
    JobLines(const char* noun, const JobReadout& job) : noun(noun), job(job) {}
    const char* noun;       // "export", "import": the messages' word
    const JobReadout& job;  // its state and status
    std::function<void()> start;       // the line's choices, then the button
    std::function<void()> cancel;
    std::function<bool()> reported;    // the editor has taken in the run that ended (null: at once)
    std::function<void()> print_done;  // what a finished run made, on stdout
    bool print_refusal = false;        // an expected error is printed ("import refused: ...")
  };
  static JobLines export_lines(AppState& st, const ScriptAction& a);
  static JobLines import_lines(AppState& st, const ScriptAction& a);
  // One job line a frame; true once it is complete. The job's end is waited for (phase 1), then the display
  // settling; a Run or Wait that ended well leaves phase_ at 2.
  bool run_job_line(ScriptHost& host, const ScriptAction& a, JobLine line, const JobLines& lines);
  // Sets the Export dialog's choices to the line's one part (if it names one) and presses its Export button.
  static void start_export(AppState& st, const ScriptAction& a);
  // The Open panel's import fields from the line, then its Import button.
  static void start_import(AppState& st, const ScriptAction& a);
  // After an import ended well: waits for its data set to be open and the display settled.
  bool imported_data_open(ScriptHost& host, const ScriptAction& a);
  void fail(const ScriptAction& a, const std::string& problem);

  std::vector<ScriptAction> actions_;
  std::string source_;
  size_t next_ = 0;
  int phase_ = 0;        // progress within the current action
  int frames_left_ = 0;  // wait_frames
  std::vector<ScriptedMouse> drag_;  // drag: the mouse of each frame still to come
  std::uint64_t job_ = 0;  // the selection edit being waited for
  ScriptAction handle_drag_;  // drag_handle: the drag it plays
  Status status_ = Status::Running;
  std::string error_;
};

}  // namespace goris::ui
