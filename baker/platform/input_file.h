// An input file opened for reading, refused at once when it is not a regular
// file: a FIFO would block a read for ever and a device (/dev/zero) never ends.
// The file is opened without blocking and checked on the open descriptor, so a
// FIFO swapped in after a path check cannot hang the reader either. Reads are
// sized by the caller, so nothing is read before it is known to be wanted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace rockbake {

class InputFile {
 public:
  // Throws InputError naming `file` ("is not a regular file …", "cannot be
  // read: <reason>"), with `hint` (what to give instead).
  InputFile(const std::filesystem::path& file, std::string hint);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The size when it was opened, in bytes.
  std::uint64_t size() const { return size_; }

  // `count` bytes from `offset`. Throws InputError when the file holds fewer
  // there (it shrank while it was read) or cannot be read.
  std::string read(std::uint64_t offset, std::uint64_t count) const;

 private:
  std::filesystem::path file_;
  std::string hint_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace rockbake
