#pragma once
// Whole-file reads with errors that name the file, and the temporary-file-then-rename step every writer
// uses so that a failed write never destroys what was there before.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace goris {

// The file's bytes; throws goris::Error naming the file when it is missing, a folder or unreadable.
std::vector<uint8_t> read_file_bytes(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// Writes `bytes` to `path` through a temporary file (see below).
void write_file_bytes(const std::filesystem::path& path, const void* bytes, size_t size);

// Calls write(tmp) with a temporary path in the same folder as `path`, then renames tmp onto `path`.
// If write throws, the temporary file is removed and `path` is left untouched.
void write_via_temp_file(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

}  // namespace goris
