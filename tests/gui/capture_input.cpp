// gui_capture_input: the input of the GUI import test (tests/gui/studio_import_capture.cmake).
//
//   gui_capture_input DATA_SET CLIP.mp4
//       a short orbit video of the data set's training views (tests/support/capture_inputs.h, as the capture
//       unit test makes it); prints the number of frames.
// Exits 1 with the reason on failure.
#include <cstdio>

#include "core/io/dataset.h"
#include "core/util/error.h"
#include "tests/support/capture_inputs.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: gui_capture_input DATA_SET CLIP.mp4\n");
    return 1;
  }
  try {
    const int frames = goris::test::write_orbit_clip(goris::load_dataset(argv[1]), argv[2]);
    if (frames == 0) {
      std::fprintf(stderr, "FAILED: OpenCV cannot write %s\n", argv[2]);
      return 1;
    }
    std::printf("%d\n", frames);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAILED: %s\n", e.what());
    return 1;
  }
  return 0;
}
