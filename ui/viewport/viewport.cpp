#include "ui/viewport/viewport.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/util/error.h"
#include "ui/gl/imgui_texture.h"

namespace goris::ui {

namespace {
bool same(const ChannelDrawOptions& a, const ChannelDrawOptions& b) {
  return a.channel == b.channel && a.label_overlay == b.label_overlay && a.selection == b.selection &&
         a.photo == b.photo && a.split == b.split;
}
}  // namespace

Viewport::Viewport(int index) : index_(index) {}

std::string Viewport::name() const { return index_ < 0 ? "main" : "grid" + std::to_string(index_); }

void Viewport::draw(const Rect& rect, ViewportContext& ctx, bool photo_half) {
  AppState& st = ctx.state;
  const Channel channel = index_ < 0 ? st.main_channel : st.grid_channels[size_t(index_)];
  ImGui::SetNextWindowPos(ImVec2(rect.x, rect.y));
  ImGui::SetNextWindowSize(ImVec2(rect.w, rect.h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 1.0f);
  ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(12, 12, 14, 255));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                                 ImGuiWindowFlags_NoScrollWithMouse;
  ImGui::Begin(("##viewport_" + name()).c_str(), nullptr, flags);
  ImGui::PopStyleColor();
  ImGui::PopStyleVar(2);

  hovered_ = ImGui::IsWindowHovered();
  Rect area = rect;
  if (photo_half) area.w *= 0.5f;
  image_ = {};
  const char* why_not = ctx.textures.has_frame() ? st.channel_unavailable(channel) : nullptr;
  if (!why_not && ctx.textures.has_frame() && !ctx.textures.has(channel))
    why_not = channel_info(channel).needs == ChannelNeeds::RemovalMasks ? "no mask file for this view" : "rendering ...";
  if (why_not) {
    // The channel cannot be shown here (yet): say why instead of showing a stale or empty image.
    const std::string text = std::string(channel_info(channel).label) + ": " + why_not;
    ImGui::PushTextWrapPos(rect.x + rect.w - 12);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, rect.w - 24);
    ImGui::SetCursorScreenPos(ImVec2(rect.x + std::max(12.0f, 0.5f * (rect.w - size.x)), rect.y + 0.5f * (rect.h - size.y)));
    ImGui::TextDisabled("%s", text.c_str());
    ImGui::PopTextWrapPos();
  } else if (ctx.textures.has_frame()) {
    image_ = fit_aspect(area, float(ctx.textures.width) / float(ctx.textures.height));
    draw_image(ctx, image_, channel);
    if ((channel == Channel::IndirectLight || channel == Channel::TracedIndirect) && ctx.textures.indirect_gain > 1.01f) {
      char gain[48];
      std::snprintf(gain, sizeof gain, "auto exposure x%.1f", double(ctx.textures.indirect_gain));
      ImGui::GetWindowDrawList()->AddText(ImVec2(image_.x + 6, image_.y + image_.h - 20), IM_COL32(255, 255, 255, 200),
                                          gain);
    }
    handle_mouse(ctx);
    if (index_ < 0) tools_.draw_overlay(st, image_);
    if (photo_half && !ctx.textures.photo.empty()) {
      const Rect right{rect.x + area.w, rect.y, rect.w - area.w, rect.h};
      const Rect p = fit_aspect(right, float(ctx.textures.photo.width()) / float(ctx.textures.photo.height()));
      ImGui::SetCursorScreenPos(ImVec2(p.x, p.y));
      ImGui::Image(imgui_texture(ctx.textures.photo.id()), ImVec2(p.w, p.h));  // rows top first: uv as is
      ImGui::GetWindowDrawList()->AddText(ImVec2(p.x + 6, p.y + p.h - 20), IM_COL32(255, 255, 255, 220),
                                          st.comparing_with_before() ? "with the target" : "input photo");
    }
  } else {
    const ImVec2 size = ImGui::CalcTextSize(ctx.empty_text);
    ImGui::SetCursorScreenPos(ImVec2(rect.x + 0.5f * (rect.w - size.x), rect.y + 0.5f * (rect.h - size.y)));
    ImGui::TextDisabled("%s", ctx.empty_text);
  }
  // The last picked surface point, as a small cross on the main viewport wherever the view has moved.
  if (index_ < 0 && st.last_pick && st.last_pick->hit && st.frame && image_.w > 0) {
    const Camera& cam = st.frame->camera;
    const glm::vec3 p = cam.to_camera(st.last_pick->world);
    if (p.z > 1e-6f) {
      const glm::vec2 uv = cam.project_camera(p);
      const float x = image_.x + uv.x * image_.w / float(st.frame->width);
      const float y = image_.y + uv.y * image_.h / float(st.frame->height);
      if (image_.contains(x, y)) {
        ImDrawList* dl = ImGui::GetWindowDrawList();
        const ImU32 col = IM_COL32(255, 230, 0, 255);
        dl->AddLine(ImVec2(x - 7, y), ImVec2(x + 8, y), col, 1.5f);
        dl->AddLine(ImVec2(x, y - 7), ImVec2(x, y + 8), col, 1.5f);
      }
    }
  }
  draw_chooser(ctx, channel);
  ImGui::End();
}

void Viewport::draw_image(ViewportContext& ctx, const Rect& r, Channel c) {
  AppState& st = ctx.state;
  ChannelDrawOptions o;
  o.channel = c;
  o.label_overlay = st.label_overlay;
  o.photo = index_ < 0 && st.compare == CompareMode::Slider && !ctx.textures.photo.empty();
  o.split = st.compare_split;
  const bool resized =
      fbo_.resize(int(std::lround(r.w * ctx.framebuffer_scale)), int(std::lround(r.h * ctx.framebuffer_scale)));
  if (resized || !has_drawn_ || drawn_version_ != ctx.textures.version || !same(o, drawn_)) {
    ctx.renderer.draw(fbo_, ctx.textures, o);
    drawn_version_ = ctx.textures.version;
    drawn_ = o;
    has_drawn_ = true;
  }
  ImGui::SetCursorScreenPos(ImVec2(r.x, r.y));
  // The framebuffer's row 0 is the bottom: flip v.
  ImGui::Image(imgui_texture(fbo_.texture()), ImVec2(r.w, r.h), ImVec2(0, 1), ImVec2(1, 0));
}

void Viewport::handle_mouse(ViewportContext& ctx) {
  AppState& st = ctx.state;
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetCursorScreenPos(ImVec2(image_.x, image_.y));
  ImGui::InvisibleButton(
      "##view", ImVec2(std::max(image_.w, 1.0f), std::max(image_.h, 1.0f)),
      ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight | ImGuiButtonFlags_MouseButtonMiddle);
  ImGui::SetItemAllowOverlap();  // the channel chooser drawn on top gets the mouse where it is
  if (ImGui::IsItemActivated()) dragged_ = false;
  // The selection tools take the left button on the main viewport (Alt+drag still orbits).
  const bool tool_took = index_ < 0 && tools_.handle_mouse(st, image_);
  if (tool_took) dragged_ = true;  // no pick on release
  if (ImGui::IsItemActive()) {
    const ImVec2 d = io.MouseDelta;
    const bool moved = d.x != 0 || d.y != 0;
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 3.0f) && moved && !tool_took) {
      dragged_ = true;
      if (ctx.mode == CameraMode::Orbit)
        st.orbit.orbit(-d.x * 0.008f, d.y * 0.008f);
      else
        st.orbit.look(d.x * 0.004f, -d.y * 0.004f);
      st.camera_moved();
    } else if ((ImGui::IsMouseDragging(ImGuiMouseButton_Right, 1.0f) ||
                ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 1.0f)) &&
               moved) {
      dragged_ = true;
      st.orbit.pan(-d.x / std::max(image_.h, 1.0f), -d.y / std::max(image_.h, 1.0f));
      st.camera_moved();
    }
  }
  if (ImGui::IsItemDeactivated() && !dragged_ && ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
    // Click to select: plain replaces the selection, shift adds, ctrl removes.
    const ImVec2 p = io.MouseClickedPos[ImGuiMouseButton_Left];
    const SelectMode mode = io.KeyShift ? SelectMode::Add : io.KeyCtrl ? SelectMode::Remove : SelectMode::Replace;
    try {
      st.mouse_click(p.x - image_.x, p.y - image_.y, image_.w, image_.h, mode);
    } catch (const Error& e) {
      st.message(e.what(), true);
    }
  }
  if (ImGui::IsItemHovered() && io.MouseWheel != 0) {
    st.orbit.zoom(io.MouseWheel);
    st.camera_moved();
  }
}

void Viewport::draw_chooser(ViewportContext& ctx, Channel current) {
  ImGui::SetCursorScreenPos(ImVec2(ImGui::GetWindowPos().x + 4, ImGui::GetWindowPos().y + 4));
  ImGui::SetNextItemWidth(std::min(170.0f, ImGui::GetWindowWidth() - 8));
  if (!ImGui::BeginCombo(("##channel_" + name()).c_str(), channel_info(current).label)) return;
  const ChannelContext cc = ctx.state.channel_context();
  for (const ChannelInfo& info : all_channels()) {
    const char* why = channel_unavailable(info.channel, cc);
    const bool available = why == nullptr;
    const ImGuiSelectableFlags f = available ? ImGuiSelectableFlags_None : ImGuiSelectableFlags_Disabled;
    if (ImGui::Selectable(info.label, info.channel == current, f)) {
      try {
        ctx.state.set_channel(index_, info.channel);
      } catch (const Error& e) {
        ctx.state.message(e.what(), true);
      }
    }
    if (!available && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("%s", why);
  }
  ImGui::EndCombo();
}

}  // namespace goris::ui
