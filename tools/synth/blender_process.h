#pragma once
// Finding and running Blender headless: run_logged (core/util/logged_process.h) merges the child's stdout
// and stderr, copies them into a log file and hands each line to a callback (render_scene.py prints
// "GORIS_FRAME i n" after each view).
#include <filesystem>

#include "core/util/logged_process.h"

namespace goris::synth {

// `requested` (from --blender) when given, else `blender` on PATH. Throws goris::Error naming the
// install command when there is none.
std::filesystem::path find_blender(const std::filesystem::path& requested = {});

using goris::ProcessResult;
using goris::run_logged;

}  // namespace goris::synth
