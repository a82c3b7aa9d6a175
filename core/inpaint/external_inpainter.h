#pragma once
// An external inpainting program (a user's LaMa or Stable Diffusion script) run once per map:
//
//   ExternalInpainter inp("python lama.py --image {image} --mask {mask} --out {out}");
//
// For each map, a fresh temporary folder receives
//   {image}  VIEW_MAP.png       the encoded map (map_encoding.h): 8-bit for colour, unit and normal maps,
//                               16-bit for depth (normalised inverse depth, near = bright) and data maps;
//                               grey for one channel, RGB for three (a 2-channel map gets a zero blue)
//   {mask}   VIEW_MAP_mask.png  8-bit grey, 255 = fill, 0 = keep (for depth maps this includes the
//                               pixels without a surface)
//   {out}    VIEW_MAP_out.png   where the program must write its result (same width and height; any
//                               bit depth or channel count read_image reads: a grey result fills every
//                               channel, a colour result for a one-channel map is averaged over R, G, B,
//                               an alpha channel is ignored)
// {view} and {map} expand to the view and map names. Every placeholder is substituted as one quoted
// shell word, so do not quote them in the template. The line runs under /bin/sh -c with stdin from
// /dev/null; its stdout and stderr go to a log whose tail appears in the error when it fails, times out
// (the process group is killed), or leaves no readable image of the right size at {out}. The folder is
// removed afterwards unless keep_files is set.
#include <filesystem>
#include <functional>
#include <string>

#include "core/inpaint/inpainter.h"

namespace goris {

struct ExternalInpainterOptions {
  double timeout_s = 600;                 // per map
  bool keep_files = false;                // leave the temporary folders (their paths are printed in errors)
  std::filesystem::path temp_root;        // where the folders go; empty = the system temporary folder
  std::function<bool()> should_stop;      // polled while the program runs (Ctrl-C): kill it and throw
};

class ExternalInpainter final : public Inpainter {
 public:
  // Throws goris::Error when the template lacks {image} or {out}, or the timeout is not positive.
  explicit ExternalInpainter(std::string command_template, ExternalInpainterOptions options = {});
  std::string name() const override;
  Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const override;

  // The template with each placeholder replaced by the quoted value (exposed for tests and logs).
  static std::string expand(const std::string& command_template, const std::string& image, const std::string& mask,
                            const std::string& out, const std::string& view, const std::string& map);

 private:
  std::string template_;
  ExternalInpainterOptions options_;
};

// Makes a name safe as a file name: characters other than letters, digits, '.', '-' and '_' become '_'.
std::string file_safe(const std::string& name);

}  // namespace goris
