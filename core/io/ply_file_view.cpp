// Whole-file access for the PLY reader: a read-only memory map when possible.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/io/file_bytes.h"
#include "core/io/ply_header.h"

namespace goris::ply_detail {

FileView::FileView(const std::filesystem::path& path) {
  // Mapping saves a copy of the whole file (a quarter of the read time for a million Gaussians); files
  // that cannot be mapped (empty, special, odd file systems) are read into memory instead.
  require_regular_file(path, "PLY file");  // a FIFO or device is refused before open() could block
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    void* p = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (p != MAP_FAILED) {
      map_ = p;
      size_ = size_t(st.st_size);
    }
  }
  if (fd >= 0) ::close(fd);
  if (!map_) copy_ = read_file_bytes(path);  // also gives the errors for missing files and folders
}

FileView::~FileView() {
  if (map_) ::munmap(map_, size_);
}

}  // namespace goris::ply_detail
