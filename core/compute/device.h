#pragma once
#include <string>

namespace goris {

// Where a buffer lives and where a kernel runs.
enum class Device { CPU, CUDA };

const char* device_name(Device d);

// True when this build has the CUDA backend compiled in (nvcc was found at configure time).
bool cuda_compiled();
// Number of usable CUDA devices; 0 when the build has no CUDA or the machine has no GPU/driver.
// "No CUDA device" is a normal condition and never throws.
int cuda_device_count();
// Human-readable name of CUDA device 0, or an explanation of why there is none.
std::string cuda_device_description();

// Parses "auto" | "cpu" | "cuda". auto picks CUDA when a device is usable, else the CPU.
// "cuda" without a usable device throws goris::Error with the reason.
Device resolve_device(const std::string& choice);

}  // namespace goris
