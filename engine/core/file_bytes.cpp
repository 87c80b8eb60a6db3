// Whole files read into memory (file_bytes.h).
#include "core/file_bytes.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace quadra {

std::vector<std::uint8_t> readWholeFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw makeError(path, "is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw makeError(path, "cannot open file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw makeError(path, "cannot read file");
  if (size == 0) throw makeError(path, "file is empty");
  if (std::uint64_t(size) > kMaxFileSize) throw makeError(path, "file is larger than 4 GiB");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.seekg(0, std::ios::beg);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw makeError(path, "cannot read file");
  }
  return bytes;
}

}  // namespace quadra
