#pragma once
// Frequency Selective Reconstruction from OpenCV contrib's xphoto module (cv::xphoto::inpaint with
// INPAINT_FSR_FAST / INPAINT_FSR_BEST): textured fills where diffusion only smears. Compiled in only
// when CMake finds xphoto (GORIS_WITH_XPHOTO); otherwise constructing one throws a goris::Error.
//
// Facts this wrapper handles: xphoto's mask is the OPPOSITE of cv::inpaint's (non-zero = KNOWN pixel,
// zero = fill), and OpenCV 4.6's FSR works in 8 bits internally (its float path even fails to allocate
// the output). So each channel is cropped to the hole's bounding box plus a 32-pixel margin (FSR's
// block context; also much faster than the whole image), stretched to 0..255 by the known pixels'
// range inside that crop (keeping precision for smooth maps such as depth), filled, and stretched back.
// FSR_FAST takes seconds and FSR_BEST minutes on a 512x512 hole (docs/design/architecture.md,
// Toolchain notes).
#include "core/inpaint/inpainter.h"

namespace goris {

// True when this build has cv::xphoto.
bool fsr_available();

class FsrInpainter final : public Inpainter {
 public:
  enum class Quality { Fast, Best };
  explicit FsrInpainter(Quality quality = Quality::Fast);  // throws when !fsr_available()
  std::string name() const override;
  Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const override;

 private:
  Quality quality_;
};

}  // namespace goris
