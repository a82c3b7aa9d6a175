#pragma once
// Whole-file reads with errors that name the file, and the temporary-file-then-rename step every writer
// uses so that a failed write never destroys what was there before.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace goris {

// Throws goris::Error naming the path unless it is a regular file: missing, a folder, a FIFO, a device or a
// socket are refused by type before anything opens it (opening a FIFO would wait for a writer forever).
// `what` names what was wanted ("file", "image file", "PLY file").
void require_regular_file(const std::filesystem::path& path, const std::string& what = "file");
// The same check without throwing: "" for a regular file, otherwise the problem without the path
// ("is a FIFO (named pipe), not a checkpoint file", "file not found").
std::string regular_file_problem(const std::filesystem::path& path, const std::string& what = "file");

// The file's bytes; throws goris::Error naming the file when it is missing, a folder, not a regular file or
// unreadable.
std::vector<uint8_t> read_file_bytes(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// Writes `bytes` to `path` through a temporary file (see below).
void write_file_bytes(const std::filesystem::path& path, const void* bytes, size_t size);

// Calls write(tmp) with a temporary path in the same folder as `path`, then renames tmp onto `path`.
// If write throws, the temporary file is removed and `path` is left untouched.
void write_via_temp_file(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

// Removes the temporary files write_via_temp_file left in `dir` when its process was killed mid-write
// (a kill during a checkpoint): those whose writing process no longer runs.
void remove_stale_temp_files(const std::filesystem::path& dir);

}  // namespace goris
