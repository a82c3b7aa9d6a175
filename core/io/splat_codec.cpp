// The splat codecs' shared pieces (core/io/splat_codec.h): input checks, quaternions, gzip via zlib.
#include "core/io/splat_codec.h"

#include <zlib.h>

namespace goris::splat_detail {

namespace {
// Throws Error(name, prefix + "<attribute> of Gaussian <i> is not a finite number") for the first one.
void check_finite(const GaussianPly& g, const std::string& name, const std::string& prefix) {
  auto finite = [&](const std::vector<float>& v, size_t per, const char* what) {
    for (size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k]))
        throw Error(name, prefix + what + " of Gaussian " + std::to_string(k / per) + " is not a finite number");
  };
  finite(g.positions, 3, "position");
  finite(g.f_dc, 3, "f_dc");
  finite(g.f_rest, std::max<size_t>(1, GaussianPly::rest_per_gaussian(g.sh_degree)), "f_rest");
  finite(g.opacity, 1, "opacity");
  finite(g.scales, 3, "scale");
  finite(g.rotations, 4, "rotation");
}
}  // namespace

void check_encodable(const GaussianPly& g, const std::string& name) {
  g.check_consistent(name);
  check_finite(g, name, "cannot encode: ");
}

void check_decoded(const GaussianPly& g, const std::string& name) { check_finite(g, name, "decodes to values out of range: "); }

void unit_quaternion(const GaussianPly& g, size_t i, float q[4]) {
  const float* r = &g.rotations[i * 4];
  double n2 = 0;
  for (int k = 0; k < 4; ++k) n2 += double(r[k]) * r[k];
  if (!(n2 > 0) || !std::isfinite(n2)) {
    q[0] = 1, q[1] = q[2] = q[3] = 0;
    return;
  }
  const double inv = 1.0 / std::sqrt(n2);
  for (int k = 0; k < 4; ++k) q[k] = float(r[k] * inv);
}

std::vector<uint8_t> gzip_compress(const std::vector<uint8_t>& data, const std::string& name) {
  z_stream s{};
  // windowBits 15 + 16: a gzip header and trailer rather than zlib's.
  if (deflateInit2(&s, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error(name, "zlib: cannot start compression");
  std::vector<uint8_t> out(deflateBound(&s, uLong(data.size())) + 64);
  s.next_in = const_cast<Bytef*>(data.data());
  s.avail_in = uInt(data.size());
  s.next_out = out.data();
  s.avail_out = uInt(out.size());
  const int rc = deflate(&s, Z_FINISH);
  const size_t produced = out.size() - s.avail_out;
  deflateEnd(&s);
  if (rc != Z_STREAM_END) throw Error(name, "zlib: compression failed");
  out.resize(produced);
  return out;
}

std::vector<uint8_t> gzip_decompress(const uint8_t* data, size_t size, size_t max_out, const std::string& name,
                                     bool prefix_only) {
  z_stream s{};
  if (inflateInit2(&s, 15 + 16) != Z_OK) throw Error(name, "zlib: cannot start decompression");
  std::vector<uint8_t> out;
  std::vector<uint8_t> buf(1 << 16);
  s.next_in = const_cast<Bytef*>(data);
  s.avail_in = uInt(size);
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    s.next_out = buf.data();
    s.avail_out = uInt(buf.size());
    rc = inflate(&s, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      const std::string why = rc == Z_BUF_ERROR ? "the gzip stream is truncated"
                                                : std::string("the gzip stream is corrupt (") + (s.msg ? s.msg : "zlib error") + ")";
      inflateEnd(&s);
      throw Error(name, why);
    }
    const size_t got = buf.size() - s.avail_out;
    if (out.size() + got > max_out) {
      inflateEnd(&s);
      if (prefix_only) {
        out.insert(out.end(), buf.begin(), buf.begin() + std::ptrdiff_t(max_out - out.size()));
        return out;
      }
      throw Error(name, "decompresses to more than " + std::to_string(max_out) + " bytes");
    }
    out.insert(out.end(), buf.begin(), buf.begin() + std::ptrdiff_t(got));
    if (rc == Z_OK && s.avail_in == 0 && got == 0) {
      inflateEnd(&s);
      throw Error(name, "the gzip stream is truncated");
    }
  }
  inflateEnd(&s);
  return out;
}

}  // namespace goris::splat_detail
