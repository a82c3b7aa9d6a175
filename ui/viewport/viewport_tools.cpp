#include "ui/viewport/viewport_tools.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/util/error.h"

namespace goris::ui {

namespace {

constexpr float kHandleRadius = 6.0f;  // window pixels
const ImU32 kShapeColour = IM_COL32(255, 255, 255, 220);
const ImU32 kVolumeColour = IM_COL32(80, 200, 255, 220);
const ImU32 kHandleColour = IM_COL32(255, 200, 40, 255);

bool shape_tool(SelectTool t) { return t == SelectTool::Rect || t == SelectTool::Lasso || t == SelectTool::Brush; }

SelectMode modifier_mode(const ImGuiIO& io) {
  return io.KeyShift ? SelectMode::Add : io.KeyCtrl ? SelectMode::Remove : SelectMode::Replace;
}

// A world point in window pixels on the main viewport's image (nullopt: behind the camera or no frame).
std::optional<glm::vec2> to_window(const AppState& st, const Rect& image, const glm::vec3& world) {
  if (!st.frame || image.w <= 0) return std::nullopt;
  const Camera& cam = st.frame->camera;
  const glm::vec3 p = cam.to_camera(world);
  if (p.z <= 1e-6f) return std::nullopt;
  const glm::vec2 uv = cam.project_camera(p);
  return glm::vec2(image.x + uv.x * image.w / float(st.frame->width), image.y + uv.y * image.h / float(st.frame->height));
}

ImVec2 im(glm::vec2 p) { return ImVec2(p.x, p.y); }

// The world lines that outline the volume: a sphere's three great circles, a box's twelve edges.
std::vector<std::pair<glm::vec3, glm::vec3>> volume_lines(const VolumeRegion& v) {
  std::vector<std::pair<glm::vec3, glm::vec3>> lines;
  if (v.kind == VolumeRegion::Kind::Sphere) {
    constexpr int kSegments = 48;
    for (int axis = 0; axis < 3; ++axis)
      for (int k = 0; k < kSegments; ++k) {
        auto at = [&](int i) {
          const float a = 6.2831853f * float(i) / float(kSegments);
          glm::vec3 d(0.0f);
          d[(axis + 1) % 3] = std::cos(a);
          d[(axis + 2) % 3] = std::sin(a);
          return v.centre + v.radius * d;
        };
        lines.emplace_back(at(k), at(k + 1));
      }
    return lines;
  }
  const SelectionBox b = volume_box(v);
  auto corner = [&](int i) {
    const glm::vec3 s((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f);
    return b.centre + b.rotation * (s * b.half_extent);
  };
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) lines.emplace_back(corner(i), corner(i | bit));
  return lines;
}

bool flow_takes_clicks(FlowStep s) {
  return s == FlowStep::FirstClick || s == FlowStep::SecondClick || s == FlowStep::Review;
}

// The two-click flow on the snapped training view: its mask (the review), the clicks made in this view
// and the point offered for the second click.
void draw_flow_overlay(const AppState& st, const Rect& image) {
  const TwoClickFlow& f = st.two_click;
  const std::shared_ptr<const FlowResult>& r = f.result();
  if (!r || !f.active() || f.step() == FlowStep::Done || !st.snapped || st.snapped_test) return;
  const std::size_t v = st.snapped_index;
  if (v >= r->masks.size()) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const Mask& m = r->masks[v];
  const float sx = image.w / float(m.width), sy = image.h / float(m.height);
  dl->PushClipRect(ImVec2(image.x, image.y), ImVec2(image.x + image.w, image.y + image.h), true);
  if (f.step() == FlowStep::Review || f.step() == FlowStep::Removing)
    for (int y = 0; y < m.height; ++y)  // one rectangle per run of mask pixels in a row
      for (int x = 0; x < m.width;) {
        if (!m(x, y)) {
          ++x;
          continue;
        }
        const int x0 = x;
        while (x < m.width && m(x, y)) ++x;
        dl->AddRectFilled(ImVec2(image.x + float(x0) * sx, image.y + float(y) * sy),
                          ImVec2(image.x + float(x) * sx, image.y + float(y + 1) * sy), IM_COL32(255, 60, 200, 90));
      }
  auto marker = [&](int x, int y, ImU32 c) {
    const ImVec2 p(image.x + (float(x) + 0.5f) * sx, image.y + (float(y) + 0.5f) * sy);
    dl->AddCircle(p, 7.0f, IM_COL32(0, 0, 0, 220), 16, 3.0f);
    dl->AddCircle(p, 7.0f, c, 16, 1.5f);
  };
  for (const FlowClick& c : f.clicks())
    if (c.view == v) marker(c.x, c.y, IM_COL32(255, 255, 255, 255));
  if (f.step() == FlowStep::SecondClick && r->offered && r->offered->view == v)
    marker(r->offered->x, r->offered->y, IM_COL32(255, 200, 40, 255));
  dl->PopClipRect();
}

}  // namespace

std::vector<std::pair<ViewportTools::Handle, glm::vec2>> ViewportTools::handles(const AppState& st,
                                                                                const Rect& image) const {
  std::vector<std::pair<Handle, glm::vec2>> out;
  if (!st.tools.volume_tool() || !st.frame) return out;
  const VolumeRegion& v = st.tools.tool == SelectTool::Box ? st.tools.box : st.tools.sphere;
  auto add = [&](Handle h, const glm::vec3& world) {
    if (const auto p = to_window(st, image, world)) out.emplace_back(h, *p);
  };
  add(Handle::Centre, v.centre);
  if (v.kind == VolumeRegion::Kind::Sphere) {
    const glm::mat3& R = st.frame->camera.R;
    const glm::vec3 right(R[0][0], R[1][0], R[2][0]);  // the camera's x axis in world coordinates
    add(Handle::Radius, v.centre + v.radius * right);
  } else {
    const SelectionBox b = volume_box(v);
    add(Handle::AxisX, b.centre + b.rotation[0] * b.half_extent.x);
    add(Handle::AxisY, b.centre + b.rotation[1] * b.half_extent.y);
    add(Handle::AxisZ, b.centre + b.rotation[2] * b.half_extent.z);
  }
  return out;
}

void ViewportTools::drag_handle(AppState& st, const Rect& image, glm::vec2 delta) {
  VolumeRegion& v = st.tools.volume();
  const auto hs = handles(st, image);
  auto where = [&](Handle h) -> std::optional<glm::vec2> {
    for (const auto& [k, p] : hs)
      if (k == h) return p;
    return std::nullopt;
  };
  const std::optional<glm::vec2> centre = where(Handle::Centre), handle = where(dragging_);
  if (!centre || !handle) return;
  if (dragging_ == Handle::Centre) {
    // Moves in the view's plane at the centre's depth.
    const Camera& cam = st.frame->camera;
    const float z = cam.to_camera(v.centre).z;
    const float px = float(st.frame->width) / image.w;  // frame pixels per window pixel
    const glm::mat3& R = cam.R;
    const glm::vec3 right(R[0][0], R[1][0], R[2][0]), down(R[0][1], R[1][1], R[2][1]);
    v.centre += (delta.x * px * z / cam.fx) * right + (delta.y * px * z / cam.fy) * down;
    return;
  }
  // A size handle follows the mouse along its own direction on screen: the projected length is the size.
  const glm::vec2 dir = *handle - *centre;
  const float len = glm::length(dir);
  if (len < 1.0f) return;
  const float moved = glm::dot(delta, dir / len);
  float* size = dragging_ == Handle::Radius ? &v.radius
                : dragging_ == Handle::AxisX ? &v.half_extent.x
                : dragging_ == Handle::AxisY ? &v.half_extent.y
                                             : &v.half_extent.z;
  *size = std::max(1e-4f, *size * (1.0f + moved / len));
}

void ViewportTools::finish_shape(AppState& st, const Rect& image) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 display(image.w, image.h);
  const SelectMode mode = modifier_mode(io);
  try {
    switch (st.tools.tool) {
      case SelectTool::Rect:
        st.select_rect(points_.front(), points_.back(), display, mode);
        break;
      case SelectTool::Lasso:
        if (points_.size() >= 3) st.select_polygon(points_, display, mode);
        break;
      case SelectTool::Brush:
        st.select_brush(points_, st.tools.brush_radius, display, mode);
        break;
      default:
        break;
    }
  } catch (const Error& e) {
    st.message(e.what(), true);
  }
}

bool ViewportTools::handle_mouse(AppState& st, const Rect& image) {
  const ImGuiIO& io = ImGui::GetIO();
  const SelectTool tool = st.tools.tool;
  const glm::vec2 mouse(io.MousePos.x - image.x, io.MousePos.y - image.y);
  if (tool == SelectTool::Click && flow_takes_clicks(st.two_click.step())) {
    // The two-click flow takes a plain click (a drag still orbits).
    if (ImGui::IsItemDeactivated() && ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
        io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 9.0f && !io.KeyAlt) {
      const ImVec2 p = io.MouseClickedPos[ImGuiMouseButton_Left];
      try {
        st.two_click.click(st, p.x - image.x, p.y - image.y, glm::vec2(image.w, image.h));
      } catch (const Error& e) {
        st.message(e.what(), true);
      }
      return true;
    }
    return false;
  }
  if (shape_tool(tool) && (drawing_ || !io.KeyAlt)) {
    if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      drawing_ = true;
      points_ = {glm::vec2(io.MouseClickedPos[ImGuiMouseButton_Left].x - image.x,
                           io.MouseClickedPos[ImGuiMouseButton_Left].y - image.y)};
    }
    if (!drawing_) return false;
    if (ImGui::IsItemActive()) {
      if (tool == SelectTool::Rect)
        points_.resize(1), points_.push_back(mouse);
      else if (glm::length(mouse - points_.back()) >= 2.0f)
        points_.push_back(mouse);
      return true;
    }
    drawing_ = false;
    // Released: a drag selects; a click without one (a short stroke for the brush) falls through to the pick.
    const glm::vec2 extent = points_.back() - points_.front();
    const bool dragged = tool == SelectTool::Brush || std::abs(extent.x) > 3 || std::abs(extent.y) > 3 ||
                         (tool == SelectTool::Lasso && points_.size() >= 3);
    if (!dragged) return false;
    finish_shape(st, image);
    points_.clear();
    return true;
  }
  if (st.tools.volume_tool()) {
    st.place_volumes_if_needed();
    if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      const glm::vec2 at(io.MousePos.x, io.MousePos.y);
      float best = 2.0f * kHandleRadius;
      for (const auto& [h, p] : handles(st, image))
        if (glm::length(p - at) < best) best = glm::length(p - at), dragging_ = h;
    }
    if (dragging_ == Handle::None) return false;
    if (ImGui::IsItemActive()) {
      drag_handle(st, image, glm::vec2(io.MouseDelta.x, io.MouseDelta.y));
      return true;
    }
    dragging_ = Handle::None;
    return true;
  }
  return false;
}

void ViewportTools::draw_overlay(AppState& st, const Rect& image) const {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const glm::vec2 o(image.x, image.y);
  const SelectTool tool = st.tools.tool;
  draw_flow_overlay(st, image);
  if (drawing_ && !points_.empty()) {
    if (tool == SelectTool::Rect) {
      dl->AddRect(im(o + glm::min(points_.front(), points_.back())), im(o + glm::max(points_.front(), points_.back())),
                  kShapeColour, 0.0f, 0, 1.5f);
    } else if (tool == SelectTool::Lasso) {
      std::vector<ImVec2> pts;
      for (const glm::vec2& p : points_) pts.push_back(im(o + p));
      dl->AddPolyline(pts.data(), int(pts.size()), kShapeColour, ImDrawFlags_Closed, 1.5f);
    } else if (tool == SelectTool::Brush) {
      for (const glm::vec2& p : points_) dl->AddCircleFilled(im(o + p), st.tools.brush_radius, IM_COL32(255, 255, 255, 40));
    }
  }
  if (tool == SelectTool::Brush && ImGui::IsWindowHovered()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    if (image.contains(m.x, m.y)) dl->AddCircle(m, st.tools.brush_radius, kShapeColour, 32, 1.5f);
  }
  if (!st.tools.volume_tool() || !st.frame) return;
  const VolumeRegion& v = tool == SelectTool::Box ? st.tools.box : st.tools.sphere;
  dl->PushClipRect(ImVec2(image.x, image.y), ImVec2(image.x + image.w, image.y + image.h), true);
  for (const auto& [a, b] : volume_lines(v)) {
    const auto pa = to_window(st, image, a), pb = to_window(st, image, b);
    if (pa && pb) dl->AddLine(im(*pa), im(*pb), kVolumeColour, 1.5f);
  }
  for (const auto& [h, p] : handles(st, image)) {
    dl->AddCircleFilled(im(p), kHandleRadius, h == dragging_ ? IM_COL32(255, 255, 255, 255) : kHandleColour);
    dl->AddCircle(im(p), kHandleRadius, IM_COL32(0, 0, 0, 200), 16, 1.0f);
  }
  dl->PopClipRect();
}

}  // namespace goris::ui
