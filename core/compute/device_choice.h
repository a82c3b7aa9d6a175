#pragma once
// Where a user asks a computation to run (`--device`, `device` in config.json), and the device it resolves
// to (core/compute/device.h).
#include <array>
#include <utility>

#include "core/compute/device.h"
#include "core/util/named_enum.h"

namespace goris {

// Auto picks CUDA when a device is usable, else the CPU.
enum class DeviceChoice { Auto, CPU, CUDA };
template <>
struct EnumNames<DeviceChoice> {
  static constexpr std::array<std::pair<DeviceChoice, const char*>, 3> names{
      {{DeviceChoice::Auto, "auto"}, {DeviceChoice::CPU, "cpu"}, {DeviceChoice::CUDA, "cuda"}}};
};

// The device a choice runs on. CUDA without a usable device throws goris::Error with the reason.
Device resolve_device(DeviceChoice choice);

}  // namespace goris
