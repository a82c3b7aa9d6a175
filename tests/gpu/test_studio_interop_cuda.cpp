// CUDA-GL interop for the editor's viewports: a device buffer copied into a GL texture through interop
// reads back (glGetTexImage) equal to the host upload of the same data, at every channel count and after a
// re-allocation at a new size; and FrameTextures of a CUDA frame hold what they hold for the CPU frame of
// the same G-buffer. Needs a CUDA device and a headless GL context (EGL); skips with a message otherwise.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_studio_scenes.h"
#include "ui/display/display_frame.h"
#include "ui/display/frame_textures.h"
#include "ui/gl/cuda_texture_interop.h"
#include "ui/gl/gl_api.h"
#include "ui/gl/gl_texture.h"

using namespace goris;
using namespace goris::ui;

namespace {

// An OpenGL 3.3 core context without a window: the EGL devices first (on a GPU machine the NVIDIA one,
// which CUDA can share textures with), then EGL_DEFAULT_DISPLAY; a 16x16 pbuffer, or none (surfaceless).
class HeadlessGl {
 public:
  HeadlessGl() {
    std::vector<EGLDisplay> displays;
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDeviceEXT devices[8];
    EGLint n = 0;
    if (query_devices && platform_display && query_devices(8, devices, &n))
      for (EGLint i = 0; i < n; ++i) displays.push_back(platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
    displays.push_back(eglGetDisplay(EGL_DEFAULT_DISPLAY));
    why_ = "no EGL display";
    for (EGLDisplay d : displays) {
      if (d == EGL_NO_DISPLAY || !try_display(d)) continue;
      const char* v = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
      const std::string vendor = v ? v : "";
      const Kept found{display_, context_, surface_};
      if (vendor.find("NVIDIA") != std::string::npos) {
        release(kept_);  // releasing makes no context current: the NVIDIA one again
        eglMakeCurrent(display_, surface_, surface_, context_);
        vendor_ = vendor;
        return;
      }
      if (kept_.display == EGL_NO_DISPLAY) {  // a working context that CUDA may not share: kept as a last resort
        kept_ = found;
        kept_vendor_ = vendor;
      } else {
        release(found);
      }
      display_ = EGL_NO_DISPLAY;
    }
    if (kept_.display != EGL_NO_DISPLAY) {
      display_ = kept_.display;
      context_ = kept_.context;
      surface_ = kept_.surface;
      vendor_ = kept_vendor_;
      eglMakeCurrent(display_, surface_, surface_, context_);
    }
  }
  ~HeadlessGl() { release({display_, context_, surface_}); }
  bool ok() const { return display_ != EGL_NO_DISPLAY; }
  const std::string& why_not() const { return why_; }
  const std::string& vendor() const { return vendor_; }
  bool nvidia() const { return vendor_.find("NVIDIA") != std::string::npos; }

 private:
  bool try_display(EGLDisplay d) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) return fail("eglInitialize failed");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("no desktop OpenGL on this EGL display");
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    const bool have_config = eglChooseConfig(d, config_attribs, &config, 1, &configs) && configs > 0;
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(d, have_config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attribs);
    if (ctx == EGL_NO_CONTEXT) return fail("no OpenGL 3.3 core context");
    EGLSurface surface = EGL_NO_SURFACE;
    if (have_config) {
      const EGLint pbuffer_attribs[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
      surface = eglCreatePbufferSurface(d, config, pbuffer_attribs);
    }
    if (!eglMakeCurrent(d, surface, surface, ctx)) {
      if (surface != EGL_NO_SURFACE) eglDestroySurface(d, surface);
      eglDestroyContext(d, ctx);
      return fail("eglMakeCurrent failed");
    }
    display_ = d;
    context_ = ctx;
    surface_ = surface;
    return true;
  }
  struct Kept {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
  };
  static void release(const Kept& k) {
    if (k.display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(k.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (k.surface != EGL_NO_SURFACE) eglDestroySurface(k.display, k.surface);
    eglDestroyContext(k.display, k.context);
  }
  bool fail(const std::string& why) {
    why_ = why;
    return false;
  }

  Kept kept_;
  std::string kept_vendor_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
  std::string why_, vendor_;
};

// The texture's level 0 as RGBA floats (GL fills missing components: 0 for G and B, 1 for alpha).
std::vector<float> read_rgba(const GlTexture& t) {
  std::vector<float> px(size_t(t.width()) * size_t(t.height()) * 4);
  glBindTexture(GL_TEXTURE_2D, t.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, px.data());
  check_gl("glGetTexImage");
  return px;
}

std::vector<float> random_pixels(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2, 2);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

GBuffer copy_to(const GBuffer& g, Device d) {
  GBuffer c;
  c.width = g.width;
  c.height = g.height;
  c.n_extras = g.n_extras;
  c.color = g.color.copy_to(d);
  c.alpha = g.alpha.copy_to(d);
  c.depth = g.depth.copy_to(d);
  c.median_depth = g.median_depth.copy_to(d);
  c.normal = g.normal.copy_to(d);
  c.extras = g.extras.copy_to(d);
  return c;
}

}  // namespace

TEST(StudioInteropCuda, DeviceCopyReadsBackLikeTheHostUpload) {
  GORIS_REQUIRE_GPU();
  HeadlessGl gl;
  if (!gl.ok()) GTEST_SKIP() << "no headless GL context: " << gl.why_not();
  CudaTextureInterop interop;
  GlTexture via_host, via_cuda;  // after `interop` in scope: destroyed first, as FrameTextures orders them
  unsigned seed = 1;
  for (const auto [w, h] : {std::pair{37, 23}, std::pair{64, 48}}) {  // the second size re-registers
    for (int channels : {1, 2, 4}) {
      const std::vector<float> px = random_pixels(size_t(w) * size_t(h) * size_t(channels), seed++);
      via_host.upload(w, h, channels, px.data());
      const Buffer<float> device(px, Device::CUDA);
      if (via_cuda.width() != w || via_cuda.height() != h || via_cuda.channels() != channels)
        interop.forget(via_cuda.id());
      via_cuda.allocate(w, h, channels);
      try {
        interop.copy(via_cuda.id(), w, h, channels, device.data());
      } catch (const Error& e) {
        if (!gl.nvidia()) GTEST_SKIP() << "the GL context (" << gl.vendor() << ") cannot share with CUDA: " << e.what();
        FAIL() << "interop on " << gl.vendor() << ": " << e.what();
      }
      const std::vector<float> a = read_rgba(via_host), b = read_rgba(via_cuda);
      EXPECT_EQ(a, b) << w << "x" << h << "x" << channels;
      for (size_t p = 0; p < size_t(w) * size_t(h); ++p)
        for (int c = 0; c < channels; ++c) ASSERT_EQ(b[p * 4 + c], px[p * channels + c]) << "pixel " << p;
    }
  }
  EXPECT_THROW(interop.copy(via_cuda.id(), 8, 8, 3, nullptr), Error);  // 3 components: not registrable
}

TEST(StudioInteropCuda, CudaFrameTexturesEqualTheCpuFrameTextures) {
  GORIS_REQUIRE_GPU();
  HeadlessGl gl;
  if (!gl.ok()) GTEST_SKIP() << "no headless GL context: " << gl.why_not();
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1, 1);
  GaussianModel m(Device::CPU);
  m.allocate(150);
  for (int i = 0; i < 150; ++i) {
    test::set_studio_gaussian(m, i, glm::vec3(1.2f * u(rng), 1.0f * u(rng), 0.05f * u(rng)),
                              glm::vec3(0.25f, 0.25f, 0.02f), glm::vec3(u(rng), u(rng), u(rng)));
    for (int k = 0; k < extra::kCount; ++k) m.values(Param::ExtraLogit)[i * extra::kCount + k] = 2.0f * u(rng);
  }
  const Camera cam = test::studio_front_camera();
  const RasterOutput out = rasterize(m.view(true), cam, RasterSettings{}, Device::CPU);
  DisplayFrame host = make_display_frame(out.gbuffer, cam);
  DisplayFrame device = make_display_frame(copy_to(out.gbuffer, Device::CUDA), cam);  // the same G-buffer
  ASSERT_EQ(device.gpu.color.device(), Device::CUDA);
  const std::vector<float> cov = random_pixels(host.pixels(), 4);
  add_selection_coverage(host, Buffer<float>(cov, Device::CPU));
  add_selection_coverage(device, Buffer<float>(cov, Device::CUDA));
  ASSERT_FALSE(device.gpu.selection.empty());

  FrameTextures th, td;
  th.upload(host);
  td.upload(device);
  if (!td.interop_failure().empty()) {
    std::cout << "[ NOTE     ] interop fell back to host copies on " << gl.vendor() << ": " << td.interop_failure()
              << "\n";
    EXPECT_FALSE(gl.nvidia()) << "an NVIDIA GL context should share its textures with CUDA";
  }
  EXPECT_TRUE(td.has_selection);
  struct Pair {
    const GlTexture *a, *b;
    const char* what;
    float tolerance;  // normals are normalised by the GPU's own division and square root
  };
  for (const Pair& p : {Pair{&th.color, &td.color, "color", 0}, Pair{&th.normal, &td.normal, "normal", 1e-6f},
                        Pair{&th.diffuse, &td.diffuse, "diffuse", 0}, Pair{&th.fresnel, &td.fresnel, "fresnel", 0},
                        Pair{&th.misc, &td.misc, "misc", 0}, Pair{&th.depth, &td.depth, "depth", 0},
                        Pair{&th.selection, &td.selection, "selection", 0}}) {
    ASSERT_EQ(p.a->width(), p.b->width()) << p.what;
    const std::vector<float> a = read_rgba(*p.a), b = read_rgba(*p.b);
    ASSERT_EQ(a.size(), b.size()) << p.what;
    for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], p.tolerance) << p.what << " float " << i;
  }
  // A second, smaller frame re-allocates (and re-registers) the textures.
  const Camera small = cam.resized(24, 20);
  const RasterOutput out2 = rasterize(m.view(true), small, RasterSettings{}, Device::CPU);
  th.upload(make_display_frame(out2.gbuffer, small));
  td.upload(make_display_frame(copy_to(out2.gbuffer, Device::CUDA), small));
  EXPECT_EQ(td.color.width(), 24);
  EXPECT_EQ(read_rgba(th.color), read_rgba(td.color));
  EXPECT_EQ(read_rgba(th.misc), read_rgba(td.misc));
}
