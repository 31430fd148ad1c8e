#include "platform/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace rockbake {

InputFile::InputFile(const std::filesystem::path& file, std::string hint) : file_(file), hint_(std::move(hint)) {
  // O_NONBLOCK: opening a FIFO with no writer would otherwise wait for one.
  fd_ = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw InputError({file_.string()}, "", std::string("cannot be read: ") + std::strerror(errno), hint_);
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputError(
        {file_.string()}, "",
        S_ISDIR(st.st_mode) ? "is a folder, not a file" : "is not a regular file (a FIFO, a socket or a device)",
        hint_);
  }
  size_ = std::uint64_t(st.st_size);
}

InputFile::~InputFile() {
  ::close(fd_);
}

std::string InputFile::read(std::uint64_t offset, std::uint64_t count) const {
  const auto shrank = [&] {
    throw InputError({file_.string()}, "", "cannot be read (it changed while it was read)", hint_);
  };
  if (count > size_ || offset > size_ - count) shrank();
  std::string bytes(count, '\0');
  for (std::uint64_t done = 0; done < count;) {
    const ssize_t n = ::pread(fd_, bytes.data() + done, count - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError({file_.string()}, "", std::string("cannot be read: ") + std::strerror(errno), hint_);
    if (n == 0) shrank();
    done += std::uint64_t(n);
  }
  return bytes;
}

}  // namespace rockbake
