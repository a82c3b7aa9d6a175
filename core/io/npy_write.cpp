#include "core/io/npy_write.h"

#include "core/io/file_bytes.h"
#include "core/util/error.h"

namespace goris {

std::vector<std::uint8_t> npy_bytes(const std::string& descr, const std::vector<std::size_t>& shape, const void* data,
                                    std::size_t data_bytes) {
  std::string dims;
  for (std::size_t d : shape) dims += std::to_string(d) + ",";
  if (shape.size() > 1) dims.pop_back();  // (n,) for one dimension, (a,b) otherwise
  std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  // Magic (6) + version (2) + header length (2) + header + '\n', padded so the data starts at a multiple of 64.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::vector<std::uint8_t> bytes = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, std::uint8_t(header.size() & 0xff),
                                     std::uint8_t(header.size() >> 8)};
  bytes.insert(bytes.end(), header.begin(), header.end());
  const auto* p = static_cast<const std::uint8_t*>(data);
  bytes.insert(bytes.end(), p, p + data_bytes);
  return bytes;
}

namespace {

template <class T>
void save(const std::filesystem::path& path, const std::vector<T>& data, const std::vector<std::size_t>& shape,
          const char* descr) {
  std::size_t n = 1;
  for (std::size_t d : shape) n *= d;
  if (n != data.size())
    throw Error(path.string(), "array of " + std::to_string(data.size()) + " values does not match its shape");
  const std::vector<std::uint8_t> b = npy_bytes(descr, shape, data.data(), data.size() * sizeof(T));
  write_file_bytes(path, b.data(), b.size());
}

}  // namespace

void save_npy(const std::filesystem::path& path, const std::vector<float>& data, const std::vector<std::size_t>& shape) {
  save(path, data, shape, "<f4");
}

void save_npy(const std::filesystem::path& path, const std::vector<std::uint8_t>& data,
              const std::vector<std::size_t>& shape) {
  save(path, data, shape, "|u1");
}

}  // namespace goris
