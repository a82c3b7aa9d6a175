#pragma once
// Durations for people: progress lines of the CLI and the editor's panels (elapsed time, ETA).
#include <string>

namespace goris {

// "12s", "3m05s", "1h02m"; "--" when unknown (negative, not finite or absurdly long).
std::string duration_text(double seconds);

}  // namespace goris
