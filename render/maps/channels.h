#pragma once
// The channels of a rendered view that the editor's viewports and `goris export --channel` show
// (docs/user/editor.md, What the viewports show). Most come from the rasterizer's G-buffer with the material
// extras; the glossy term, light and visibility come from the intrinsic renderer (intrinsic runs only), the
// two masks of the removal from the files stage 2 leaves in RUN/removal/ (for the training camera the view
// is snapped to). Whether a channel can be shown depends on what is open: see channel_unavailable(). The
// colours of each map: export/frames/channel_image.h on the CPU, shaders/channel.frag.glsl in the editor.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace goris {

enum class Channel {
  Final,            // rendered colour (the shaded C for intrinsic runs)
  Diffuse,          // diffuse albedo (extras 0..2)
  Fresnel,          // F0 (extras 3..5)
  Roughness,        // extras 6
  Normal,           // camera-space normal as rgb
  Depth,            // expected depth through TURBO on inverse depth
  Region,           // region weight (1 = rough, 0 = glossy), extras 7
  Label,            // object label, extras 8
  Alpha,            // accumulated opacity
  Glossy,           // the glossy reflection term G
  IndirectLight,    // L_ind' (traced, filtered)
  Visibility,       // V' (traced, filtered)
  EnvLight,         // L_dir' from the environment map
  ScreenRoughness,  // R_s, the roughness net's blur level (screen-space filter on)
  TracedIndirect,   // L_ind as the reflection rays brought it back, before the filter (filter on)
  TracedVisibility, // V as traced, before the filter (filter on)
  LightingMask,     // lighting-aware mask of the target's reflections (RUN/removal/lighting_masks) and its
                    // shadow (RUN/removal/shadow, grey: the share of the light it took)
  InpaintMask,      // pixels no view saw behind the target (RUN/removal/inpaint_masks)
};

// How the display shader turns a channel into colours.
enum class ColorMap { Rgb, Grey, TurboInverseDepth, NormalRgb };

// What a channel needs besides a rendered model.
enum class ChannelNeeds { Model, Intrinsic, ScreenFilter, RemovalMasks };

struct ChannelInfo {
  Channel channel;
  const char* id;     // script / settings name, e.g. "depth"
  const char* label;  // shown in the chooser
  ColorMap map;
  ChannelNeeds needs;
};

// What is open, as far as channels care.
struct ChannelContext {
  bool intrinsic = false;          // the shown model is shaded by the intrinsic renderer
  bool screen_filter = false;      // ... with the screen-space filter (R_s exists)
  bool removal_masks = false;      // the run has RUN/removal/{lighting,inpaint}_masks
  bool snapped_training = false;   // the view is exactly a training camera
};

std::span<const ChannelInfo> all_channels();
const ChannelInfo& channel_info(Channel c);
// By id ("final", "diffuse", ...); nullopt for an unknown name.
std::optional<Channel> channel_from_id(std::string_view id);
// The ids, comma separated, for error messages.
std::string channel_id_list();
// Null when `c` can be shown in `ctx`; else why not (tooltip and error text, e.g. "needs an intrinsic run").
const char* channel_unavailable(Channel c, const ChannelContext& ctx);

}  // namespace goris
