#include "core/inpaint/external_inpainter.h"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <system_error>
#include <vector>

#include "core/inpaint/map_encoding.h"
#include "core/inpaint/shell_command.h"
#include "core/util/error.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

// A temporary folder removed when this goes out of scope (unless kept).
class TempFolder {
 public:
  TempFolder(const fs::path& root, bool keep) : keep_(keep) {
    std::error_code ec;
    const fs::path base = root.empty() ? fs::temp_directory_path(ec) : root;
    if (ec) throw Error("external inpainter: no temporary folder: " + ec.message());
    std::string templ = (base / "goris-inpaint-XXXXXX").string();
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) throw Error(base.string(), "cannot create a temporary folder for the external inpainter");
    path_ = buf.data();
  }
  ~TempFolder() {
    std::error_code ec;
    if (!keep_) fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool keep_;
};

}  // namespace

std::string file_safe(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
  return s.empty() ? "_" : s;
}

ExternalInpainter::ExternalInpainter(std::string command_template, ExternalInpainterOptions options)
    : template_(std::move(command_template)), options_(std::move(options)) {
  if (template_.find("{image}") == std::string::npos || template_.find("{out}") == std::string::npos)
    throw Error("external inpainter command \"" + template_ +
                "\" must contain {image} and {out} (and usually {mask}); they are replaced by quoted file paths");
  if (!(options_.timeout_s > 0)) throw Error("external inpainter: the timeout must be positive");
}

std::string ExternalInpainter::name() const { return "external command \"" + template_ + "\""; }

std::string ExternalInpainter::expand(const std::string& command_template, const std::string& image,
                                      const std::string& mask, const std::string& out, const std::string& view,
                                      const std::string& map) {
  // One pass over the template so that a substituted value containing "{...}" is never expanded again.
  static const char* keys[] = {"{image}", "{mask}", "{out}", "{view}", "{map}"};
  const std::string values[] = {image, mask, out, view, map};
  std::string result;
  for (std::size_t i = 0; i < command_template.size();) {
    bool hit = false;
    for (int k = 0; k < 5 && !hit; ++k) {
      const std::string key = keys[k];
      if (command_template.compare(i, key.size(), key) == 0) {
        result += shell_quote(values[k]);
        i += key.size();
        hit = true;
      }
    }
    if (!hit) result += command_template[i++];
  }
  return result;
}

Image ExternalInpainter::fill(const Image& encoded, const Mask& hole, const MapInfo& info) const {
  TempFolder dir(options_.temp_root, options_.keep_files);
  const std::string stem = file_safe(info.view) + "_" + file_safe(info.map);
  const fs::path image_path = dir.path() / (stem + ".png"), mask_path = dir.path() / (stem + "_mask.png"),
                 out_path = dir.path() / (stem + "_out.png"), log_path = dir.path() / (stem + "_log.txt");
  save_encoded_png(image_path, encoded, info.kind);
  save_mask_png(mask_path, hole);

  const std::string command =
      expand(template_, image_path.string(), mask_path.string(), out_path.string(), info.view, info.map);
  const ShellResult r = run_shell_command(command, options_.timeout_s, log_path, options_.should_stop);
  const std::string what = "external inpainter for " + map_label(info) + ": `" + command + "`";
  auto with_log = [&](std::string msg) {
    const std::string tail = file_tail(log_path);
    if (!tail.empty()) msg += "; its output ended with:\n" + tail;
    if (options_.keep_files) msg += "\n(files kept in " + dir.path().string() + ")";
    return msg;
  };
  if (r.timed_out) throw Error(with_log(what + " timed out after " + std::to_string(int(std::ceil(options_.timeout_s))) + " s and was killed"));
  if (r.stopped) throw Error(with_log(what + " was stopped on request"));
  if (r.signal != 0) throw Error(with_log(what + " was killed by signal " + std::to_string(r.signal)));
  if (r.exit_code != 0) throw Error(with_log(what + " exited with status " + std::to_string(r.exit_code)));
  std::error_code ec;
  if (!fs::is_regular_file(out_path, ec) || fs::file_size(out_path, ec) == 0)
    throw Error(with_log(what + " exited with status 0 but wrote no image at " + out_path.string()));
  Image got;
  try {
    got = read_image(out_path);
  } catch (const Error& e) {
    throw Error(with_log(what + " wrote an unreadable image (" + e.what() + ")"));
  }
  if (got.width != encoded.width || got.height != encoded.height)
    throw Error(with_log(what + " wrote a " + std::to_string(got.width) + "x" + std::to_string(got.height) +
                         " image at " + out_path.string() + ", expected " + std::to_string(encoded.width) + "x" +
                         std::to_string(encoded.height)));
  return adapt_channels(got, encoded);
}

}  // namespace goris
