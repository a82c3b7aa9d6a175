#include <cstdlib>
#include <string>

#include "core/inpaint/external_inpainter.h"
#include "core/inpaint/fsr_inpainter.h"
#include "core/inpaint/harmonic_inpainter.h"
#include "core/inpaint/inpainter.h"
#include "core/inpaint/opencv_inpainter.h"
#include "core/inpaint/precomputed_inpainter.h"
#include "core/util/error.h"

namespace goris {

namespace {

constexpr const char* kChoices = "telea, telea:RADIUS, ns, ns:RADIUS, harmonic, fsr, fsr-fast, fsr-best, cmd:COMMAND, dir:FOLDER";

double parse_radius(const std::string& spec, const std::string& text) {
  char* end = nullptr;
  const double r = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(r > 0) || r > 100)
    throw Error("inpainter \"" + spec + "\": the radius must be a number of pixels in (0, 100]");
  return r;
}

}  // namespace

std::unique_ptr<Inpainter> make_inpainter(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  const std::string head = spec.substr(0, colon), rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (head == "telea" || head == "ns") {
    const double radius = colon == std::string::npos ? 3.0 : parse_radius(spec, rest);
    return std::make_unique<OpenCvInpainter>(
        head == "telea" ? OpenCvInpainter::Method::Telea : OpenCvInpainter::Method::NavierStokes, radius);
  }
  if (spec == "harmonic") return std::make_unique<HarmonicInpainter>();
  if (colon == std::string::npos && (spec == "fsr" || spec == "fsr-fast"))
    return std::make_unique<FsrInpainter>(FsrInpainter::Quality::Fast);
  if (colon == std::string::npos && spec == "fsr-best") return std::make_unique<FsrInpainter>(FsrInpainter::Quality::Best);
  if (head == "cmd" && colon != std::string::npos) {
    if (rest.empty()) throw Error("inpainter \"cmd:\" needs a command, e.g. cmd:python lama.py {image} {mask} {out}");
    return std::make_unique<ExternalInpainter>(rest);
  }
  if (head == "dir" && colon != std::string::npos) {
    if (rest.empty()) throw Error("inpainter \"dir:\" needs a folder of inpainted images");
    return std::make_unique<PrecomputedInpainter>(rest);
  }
  throw Error("unknown inpainter \"" + spec + "\" (choose one of: " + kChoices + ")");
}

}  // namespace goris
