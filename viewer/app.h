// app.h: geomview's two ways to run over an open session (options.h).
#pragma once
#include "options.h"

namespace viewer {

// Headless: one PNG per technique (or the --compare grid), pass times with
// --frames, the HUD with --hud, the error with --error. Returns the exit code.
int run_headless(Options& o, Session& s);

// The window: orbit camera, keys, ImGui panels, HUD, error overlay, grid.
int run_window(Options& o, Session& s);

}  // namespace viewer
