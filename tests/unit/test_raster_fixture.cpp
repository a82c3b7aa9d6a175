// The forward pass against the external reference ../shared/fixtures/rasterizer_garden (gsplat's reference
// projection and SH in double precision, images composited with the original 3DGS tile rule): per Gaussian
// means2d, depths, conics, colours and radii, and the images and alpha maps of its three cameras.
#include <cmath>
#include <string>
#include <vector>

#include "core/io/npy.h"
#include "render/raster/raster_pipeline.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"

using namespace goris;

namespace {

const char* kFixture = "fixtures/rasterizer_garden";

struct Fixture {
  int n = 0, width = 162, height = 105;
  std::vector<float> positions, log_scales, rotations, logits, sh;
  NpyArray viewmats, Ks, means2d, depths, conics, radii, colors;

  explicit Fixture(const std::filesystem::path& dir) {
    const NpyArray means = load_npy(dir / "means.npy"), quats = load_npy(dir / "quats_wxyz.npy"),
                   scales = load_npy(dir / "scales.npy"), opac = load_npy(dir / "opacities.npy"),
                   shc = load_npy(dir / "sh.npy");
    n = int(means.shape[0]);
    for (double v : means.data) positions.push_back(float(v));
    for (double v : quats.data) rotations.push_back(float(v));
    for (double v : scales.data) log_scales.push_back(float(std::log(v)));
    for (double v : opac.data) logits.push_back(float(std::log(v / (1 - v))));
    for (double v : shc.data) sh.push_back(float(v));
    viewmats = load_npy(dir / "viewmats.npy");
    Ks = load_npy(dir / "Ks.npy");
    means2d = load_npy(dir / "ref_means2d.npy");
    depths = load_npy(dir / "ref_depths.npy");
    conics = load_npy(dir / "ref_conics.npy");
    radii = load_npy(dir / "ref_radii.npy");
    colors = load_npy(dir / "ref_colors.npy");
  }

  GaussianView view() const {
    GaussianView v;
    v.count = n;
    v.positions = positions.data();
    v.log_scales = log_scales.data();
    v.rotations = rotations.data();
    v.opacity_logits = logits.data();
    v.sh = sh.data();
    v.sh_degree = 3;
    return v;
  }

  Camera camera(int c) const {
    Camera cam;
    cam.width = width;
    cam.height = height;
    const double* K = &Ks.data[9 * c];
    cam.fx = float(K[0]), cam.cx = float(K[2]), cam.fy = float(K[4]), cam.cy = float(K[5]);
    const double* V = &viewmats.data[16 * c];
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) cam.R[k][r] = float(V[4 * r + k]);
      cam.t[r] = float(V[4 * r + 3]);
    }
    return cam;
  }
};

RasterSettings fixture_settings() {
  RasterSettings s = RasterSettings::classic_3dgs();
  s.near_plane = 0.01f;  // gsplat's default, used by the reference
  return s;
}

double rel_err(double a, double b, double scale) { return std::abs(a - b) / std::max(scale, 1e-12); }

}  // namespace

TEST(RasterFixture, PerGaussianProjectionAndColour) {
  GORIS_REQUIRE_SHARED(kFixture);
  const Fixture fx(test::shared_dir() / kFixture);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("camera " + std::to_string(c));
    const RasterOutput out = rasterize(fx.view(), fx.camera(c), fixture_settings(), Device::CPU);
    const RasterState& st = out.state;
    int visible = 0, radius_mismatch = 0, culling_mismatch = 0;
    double worst_mean = 0, worst_depth = 0, worst_conic = 0, worst_color = 0;
    for (int i = 0; i < fx.n; ++i) {
      const std::size_t ci = std::size_t(c) * fx.n + i;
      const int ref_r = int(fx.radii.data[ci]);
      if ((ref_r > 0) != (st.radii[i] > 0)) {
        // gsplat keeps a Gaussian whose box enters the image by less than a pixel; 3DGS's tile rule (ours,
        // and the reference images') touches no tile for it. Anything else is a mismatch.
        const double* m = &fx.means2d.data[2 * ci];
        const raster::TileRect tr = raster::tile_rect(m[0], m[1], double(ref_r), (fx.width + 15) / 16, (fx.height + 15) / 16);
        if (ref_r == 0 || (tr.x1 > tr.x0 && tr.y1 > tr.y0)) ++culling_mismatch;
        continue;
      }
      if (ref_r == 0) continue;
      ++visible;
      if (std::abs(ref_r - st.radii[i]) > 1) ++radius_mismatch;
      const double* m = &fx.means2d.data[2 * ci];
      const double mscale = std::max({std::abs(m[0]), std::abs(m[1]), 1.0});
      worst_mean = std::max({worst_mean, rel_err(st.means2d[2 * i], m[0], mscale), rel_err(st.means2d[2 * i + 1], m[1], mscale)});
      worst_depth = std::max(worst_depth, rel_err(st.depths[i], fx.depths.data[ci], fx.depths.data[ci]));
      const double* q = &fx.conics.data[3 * ci];
      const double qscale = std::max(std::abs(q[0]), std::abs(q[2]));
      for (int k = 0; k < 3; ++k) worst_conic = std::max(worst_conic, rel_err(st.conics[3 * i + k], q[k], qscale));
      const double* col = &fx.colors.data[3 * ci];
      for (int k = 0; k < 3; ++k)
        worst_color = std::max(worst_color, rel_err(st.colors[3 * i + k], col[k], std::max(std::abs(col[k]), 0.1)));
    }
    EXPECT_GT(visible, 1000);
    EXPECT_EQ(culling_mismatch, 0) << "visibility differs from the reference";
    EXPECT_EQ(radius_mismatch, 0);
    EXPECT_LT(worst_mean, 1e-4);
    EXPECT_LT(worst_depth, 1e-4);
    EXPECT_LT(worst_conic, 1e-4);
    EXPECT_LT(worst_color, 1e-4);
  }
}

TEST(RasterFixture, ImagesAndAlpha) {
  GORIS_REQUIRE_SHARED(kFixture);
  const std::filesystem::path dir = test::shared_dir() / kFixture;
  const Fixture fx(dir);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("camera " + std::to_string(c));
    const NpyArray ref = load_npy(dir / ("ref_image_" + std::to_string(c) + ".npy"));
    const NpyArray ref_alpha = load_npy(dir / ("ref_alpha_" + std::to_string(c) + ".npy"));
    const RasterOutput out = rasterize(fx.view(), fx.camera(c), fixture_settings(), Device::CPU);
    const std::size_t P = out.gbuffer.pixels();
    ASSERT_EQ(ref.data.size(), 3 * P);
    double se = 0, se_alpha = 0;
    for (std::size_t p = 0; p < P; ++p) {
      for (int k = 0; k < 3; ++k) {  // reference is [H][W][3], ours planar [3][H][W]
        const double d = out.gbuffer.color[k * P + p] - ref.data[3 * p + k];
        se += d * d;
      }
      const double da = out.gbuffer.alpha[p] - ref_alpha.data[p];
      se_alpha += da * da;
    }
    const double psnr = 10 * std::log10(1.0 / (se / (3.0 * P)));
    const double psnr_alpha = 10 * std::log10(1.0 / (se_alpha / double(P)));
    EXPECT_GT(psnr, 45.0);
    EXPECT_GT(psnr_alpha, 45.0);
    std::printf("camera %d: image PSNR %.1f dB, alpha PSNR %.1f dB\n", c, psnr, psnr_alpha);
  }
}
