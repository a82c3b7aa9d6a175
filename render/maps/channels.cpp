#include "render/maps/channels.h"

#include <array>

namespace goris {

namespace {
using N = ChannelNeeds;

constexpr std::array<ChannelInfo, 18> kChannels{{
    {Channel::Final, "final", "Final colour", ColorMap::Rgb, N::Model},
    {Channel::Diffuse, "diffuse", "Diffuse / albedo", ColorMap::Rgb, N::Model},
    {Channel::Fresnel, "f0", "Fresnel F0", ColorMap::Rgb, N::Model},
    {Channel::Roughness, "roughness", "Roughness", ColorMap::Grey, N::Model},
    {Channel::Normal, "normal", "Normal", ColorMap::NormalRgb, N::Model},
    {Channel::Depth, "depth", "Depth", ColorMap::TurboInverseDepth, N::Model},
    {Channel::Region, "region", "Region mask", ColorMap::Grey, N::Model},
    {Channel::Label, "label", "Object label", ColorMap::Grey, N::Model},
    {Channel::Alpha, "alpha", "Opacity", ColorMap::Grey, N::Model},
    {Channel::Glossy, "glossy", "Glossy term G", ColorMap::Rgb, N::Intrinsic},
    {Channel::IndirectLight, "lind", "Indirect light L_ind", ColorMap::Rgb, N::Intrinsic},
    {Channel::Visibility, "visibility", "Visibility V", ColorMap::Grey, N::Intrinsic},
    {Channel::EnvLight, "env", "Environment light L_dir", ColorMap::Rgb, N::Intrinsic},
    {Channel::ScreenRoughness, "screen_roughness", "Screen roughness R_s", ColorMap::Grey, N::ScreenFilter},
    {Channel::TracedIndirect, "lind_traced", "Traced L_ind (before the filter)", ColorMap::Rgb, N::ScreenFilter},
    {Channel::TracedVisibility, "visibility_traced", "Traced V (before the filter)", ColorMap::Grey, N::ScreenFilter},
    {Channel::LightingMask, "lighting_mask", "Lighting-aware mask", ColorMap::Grey, N::RemovalMasks},
    {Channel::InpaintMask, "inpaint_mask", "Inpainting mask", ColorMap::Grey, N::RemovalMasks},
}};
}  // namespace

std::span<const ChannelInfo> all_channels() { return kChannels; }

const ChannelInfo& channel_info(Channel c) {
  for (const ChannelInfo& i : kChannels)
    if (i.channel == c) return i;
  return kChannels[0];  // unreachable: every enumerator is in the table (checked by the unit test)
}

std::optional<Channel> channel_from_id(std::string_view id) {
  for (const ChannelInfo& i : kChannels)
    if (id == i.id) return i.channel;
  return std::nullopt;
}

std::string channel_id_list() {
  std::string s;
  for (const ChannelInfo& i : kChannels) s += (s.empty() ? "" : ", ") + std::string(i.id);
  return s;
}

const char* channel_unavailable(Channel c, const ChannelContext& ctx) {
  switch (channel_info(c).needs) {
    case N::Model:
      return nullptr;
    case N::Intrinsic:
      return ctx.intrinsic ? nullptr : "needs an intrinsic run (train with mode intrinsic or auto)";
    case N::ScreenFilter:
      if (!ctx.intrinsic) return "needs an intrinsic run (train with mode intrinsic or auto)";
      return ctx.screen_filter ? nullptr : "needs the screen-space filter (intrinsic_screen_space_filter)";
    case N::RemovalMasks:
      if (!ctx.removal_masks) return "needs removal (run it in the Removal panel)";
      return ctx.snapped_training ? nullptr : "shown for training cameras only: snap to one (Camera panel)";
  }
  return nullptr;
}

}  // namespace goris
