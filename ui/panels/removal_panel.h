#pragma once
// Stage 2 (object removal) with progress: the options of `goris remove` (inpainter, ablations, fine-tune
// iterations), one button that runs it on a worker thread, the seven steps each with a progress bar, its
// detail and time, the overall progress and ETA, Cancel, thumbnails of every reference view's inpainted
// maps once the 2D inpainting is done, and when it is done: open the cleaned scene, show the masks.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "ui/gl/gl_texture.h"
#include "ui/panels/panel.h"

namespace goris::ui {

class RemovalPanel final : public Panel {
 public:
  const char* title() const override { return "Removal"; }
  void draw(AppState& state) override;

 private:
  struct Thumbnail {
    std::string view, map;
    GlTexture texture;
  };
  void draw_options(AppState& st, bool active);
  void draw_steps(AppState& st);
  void draw_result(AppState& st);
  // (Re)loads RUN/removal/inpainted/VIEW_MAP.png of the views in reference.json when `key` changed.
  void update_thumbnails(AppState& st, const std::filesystem::path& dir, const std::string& key);

  std::string custom_command_;   // the cmd: inpainter's command line
  std::string thumbnails_key_;   // what the thumbnails were loaded for
  std::vector<Thumbnail> thumbnails_;
};

}  // namespace goris::ui
