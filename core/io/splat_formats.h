#pragma once
// Splat file formats other software reads and writes, besides the 3DGS PLY of core/io/ply.h. Each codec
// works on GaussianPly (positions, log scales, w x y z quaternions, logit opacity, SH in the PLY's
// channel-major f_rest layout); what a format cannot hold (normals, extra properties, SH above its
// degree) is dropped on writing and zero on reading. Every format but the 3DGS PLY quantizes; the
// quantization of each is stated beside its functions below and tested in tests/unit/test_splat_formats.cpp.
//
// Decoders never trust a count or size in a file: every problem (truncation, a bad magic number, an
// unsupported version, sizes that disagree, non-finite values) throws goris::Error naming the file and
// the problem. Writers go through a temporary file renamed into place (core/io/file_bytes.h).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/ply.h"

namespace goris {

enum class SplatFormat { Ply, CompressedPly, Spz, Antimatter, Glb };

// For writing: from the file name alone. "*.compressed.ply" is CompressedPly, "*.spz" Spz, "*.splat"
// Antimatter, "*.glb" Glb, "*.ply" Ply; any other name is a goris::Error listing them.
SplatFormat splat_format_from_name(const std::filesystem::path& path);
// For reading: from the content (gzip magic: SPZ; "glTF": GLB; a PLY header with a `chunk` element:
// compressed PLY; other PLY: 3DGS PLY), the name only for .splat, which has no magic number.
SplatFormat detect_splat_format(const uint8_t* data, size_t size, const std::filesystem::path& path);
const char* splat_format_name(SplatFormat format);
// True when the name ends in one of the extensions above (a model file rather than a data set).
bool is_splat_file_name(const std::filesystem::path& path);

// --- Niantic SPZ, versions 2 and 3 (written: 3) ------------------------------------------------------
// A gzip stream of a 16-byte header (magic 0x5053474e "NGSP", version, count, SH degree, fractional
// bits, flags, reserved) and then, attribute by attribute for all Gaussians: positions as 24-bit signed
// fixed point (12 fractional bits, fewer when the scene needs the range: 1/4096 units), opacity as
// sigmoid * 255 in a byte, DC colour as f_dc * 0.15 * 255 + 127.5 in a byte (step 1/38.25), log scales as
// (s + 10) * 16 in a byte (step 1/16, range -10..5.94), rotations (v3: "smallest three", the index of the
// largest component in 2 bits and the other three as sign + 9-bit magnitude of |q| / sqrt(1/2); v2: x y z
// as bytes with w >= 0 rebuilt) and SH rest coefficients as bytes of x * 128 + 128 rounded to buckets of 8
// (degree 1, 5 bits) or 16 (degrees 2 and 3, 4 bits), coefficient-major with the colour channel fastest.
// SPZ's axes are right-up-back (RUB), the PLY's right-down-front (RDF): y and z (and the matching
// rotation components and SH coefficients) change sign on the way in and out. Version 4 (zstd) and files
// with SPZ extensions are refused with a message saying so.
std::vector<uint8_t> encode_spz(const GaussianPly& g, const std::string& name_for_errors, uint32_t version = 3);
GaussianPly decode_spz(const uint8_t* data, size_t size, const std::string& name_for_errors);

// --- PlayCanvas compressed PLY -----------------------------------------------------------------------
// A binary PLY with an element `chunk` (one per 256 Gaussians: float min/max of x y z, of the log scales
// clamped to [-20, 20] and of the colours f_dc * SH_C0 + 0.5: 18 floats), an element `vertex` of four
// uint32 per Gaussian (packed_position and packed_scale: 11-10-11 bits of x y z normalised to the chunk's
// range; packed_rotation: 2 bits for the largest component of rot_0..3 and the other three in 10 bits each
// as q * sqrt(1/2) + 0.5; packed_color: r g b normalised to the chunk's range and sigmoid(opacity), 8
// bits each) and, for SH degree > 0, an element `sh` of uchar f_rest_<i> (trunc((x / 8 + 0.5) * 256),
// step 1/32, range -4..4). The writer sorts the Gaussians in Morton order of their positions first (as
// PlayCanvas' tools do) so that a chunk covers a small region; compressed_ply_order gives that order:
// decoded Gaussian i is source Gaussian order[i]. The reader accepts the 12-float chunk variant without
// colour ranges too.
std::vector<uint8_t> encode_compressed_ply(const GaussianPly& g, const std::string& name_for_errors);
GaussianPly decode_compressed_ply(const uint8_t* data, size_t size, const std::string& name_for_errors);
std::vector<uint32_t> compressed_ply_order(const GaussianPly& g);

// --- antimatter15 .splat -----------------------------------------------------------------------------
// No header: 32 bytes per Gaussian, little endian: position 3 x float32, scale (linear, exp of the log
// scale) 3 x float32, colour r g b (f_dc * SH_C0 + 0.5) and opacity (sigmoid) as 4 bytes of value * 255,
// rotation w x y z of the normalised quaternion as 4 bytes of q * 128 + 128. No SH above degree 0.
std::vector<uint8_t> encode_antimatter_splat(const GaussianPly& g, const std::string& name_for_errors);
GaussianPly decode_antimatter_splat(const uint8_t* data, size_t size, const std::string& name_for_errors);

// --- glTF 2.0 binary (GLB) with KHR_gaussian_splatting (Khronos, release candidate) ----------------------
// One mesh primitive of mode POINTS (0) with float32 accessors, as PlayCanvas' splat-transform writes them:
// POSITION (VEC3, with min/max), KHR_gaussian_splatting:ROTATION (VEC4 x y z w, unit), :SCALE (VEC3,
// linear: exp of the log scale), :OPACITY (SCALAR, after the sigmoid), :SH_DEGREE_0_COEF_0 (VEC3, f_dc as
// is) and :SH_DEGREE_<l>_COEF_<c> (VEC3, r g b of each higher coefficient). Lossless but for float
// rounding in exp/log and sigmoid/logit. glTF's axes are left-up-front (LUF), the PLY's right-down-front:
// x and y (and the matching rotation components and SH coefficients) change sign. The reader takes float
// or normalised-byte accessors at any stride, falls back to COLOR_0 for colour and opacity, and takes the
// SH degree from the coefficients present.
std::vector<uint8_t> encode_glb(const GaussianPly& g, const std::string& name_for_errors);
GaussianPly decode_glb(const uint8_t* data, size_t size, const std::string& name_for_errors);

// --- any of them -------------------------------------------------------------------------------------
// Reads a model file in any of the formats above (detect_splat_format); errors name the file.
GaussianPly read_gaussians(const std::filesystem::path& path);
GaussianPly parse_gaussians_any(const uint8_t* data, size_t size, const std::filesystem::path& path);
// Writes `g` in the format the name says (splat_format_from_name), through a temporary file.
void write_gaussians(const std::filesystem::path& path, const GaussianPly& g);
// `goris info` for a model file of any format.
std::string gaussians_summary(const std::filesystem::path& path);

}  // namespace goris
