#include "core/inpaint/fsr_inpainter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/inpaint/map_encoding.h"
#include "core/util/error.h"

#if defined(GORIS_WITH_XPHOTO)
#include <opencv2/xphoto.hpp>
#endif

namespace goris {

namespace {
constexpr int kMargin = 32;  // known context around the hole (FSR blocks are 16 px in 32 px windows)
}

bool fsr_available() {
#if defined(GORIS_WITH_XPHOTO)
  return true;
#else
  return false;
#endif
}

FsrInpainter::FsrInpainter(Quality quality) : quality_(quality) {
  if (!fsr_available())
    throw Error("inpainter fsr: this build has no OpenCV xphoto module (install libopencv-contrib-dev and "
                "re-run CMake), use telea or ns instead");
}

std::string FsrInpainter::name() const { return quality_ == Quality::Fast ? "xphoto-fsr-fast" : "xphoto-fsr-best"; }

Image FsrInpainter::fill(const Image& encoded, const Mask& hole, const MapInfo& info) const {
#if defined(GORIS_WITH_XPHOTO)
  const int W = encoded.width, H = encoded.height, C = encoded.channels;
  int x0 = W, y0 = H, x1 = -1, y1 = -1;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (hole(x, y)) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
  const std::vector<float> in = encoded.pixels.to_host();
  Image out(W, H, C, Device::CPU);
  out.pixels.upload(in.data(), in.size());
  if (x1 < 0) return out;
  x0 = std::max(0, x0 - kMargin);
  y0 = std::max(0, y0 - kMargin);
  x1 = std::min(W - 1, x1 + kMargin);
  y1 = std::min(H - 1, y1 + kMargin);
  const int cw = x1 - x0 + 1, ch = y1 - y0 + 1;

  cv::Mat known(ch, cw, CV_8UC1), src(ch, cw, CV_8UC1), dst;
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x) known.at<std::uint8_t>(y, x) = hole(x0 + x, y0 + y) ? 0 : 255;
  auto at = [&](int x, int y, int c) { return (std::size_t(y0 + y) * W + (x0 + x)) * C + c; };
  for (int c = 0; c < C; ++c) {
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x)
        if (known.at<std::uint8_t>(y, x)) {
          lo = std::min(lo, in[at(x, y, c)]);
          hi = std::max(hi, in[at(x, y, c)]);
        }
    if (lo > hi) throw Error(map_label(info), name() + ": no known pixel around the hole");
    const float scale = hi > lo ? 255.0f / (hi - lo) : 0.0f;
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x) {
        const float v = known.at<std::uint8_t>(y, x) ? (in[at(x, y, c)] - lo) * scale : 0.0f;
        src.at<std::uint8_t>(y, x) = std::uint8_t(std::clamp(std::lround(v), 0L, 255L));
      }
    try {
      cv::xphoto::inpaint(src, known, dst,
                          quality_ == Quality::Fast ? cv::xphoto::INPAINT_FSR_FAST : cv::xphoto::INPAINT_FSR_BEST);
    } catch (const cv::Exception& e) {
      throw Error(map_label(info), name() + " failed: " + e.what());
    }
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x)
        if (!known.at<std::uint8_t>(y, x))
          out.pixels[at(x, y, c)] = hi > lo ? lo + float(dst.at<std::uint8_t>(y, x)) / scale : lo;
  }
  return out;
#else
  throw Error(map_label(info), "inpainter fsr: this build has no OpenCV xphoto module");
#endif
}

}  // namespace goris
