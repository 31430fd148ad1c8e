#include "platform/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <system_error>

namespace rockbake {
namespace {

namespace fs = std::filesystem;

// generic_category().message() is strerror's text without strerror's shared buffer.
[[noreturn]] void fail(const fs::path& target, const std::string& step, int error) {
  throw std::runtime_error("cannot write " + target.string() + ": " + step + ": " +
                           std::generic_category().message(error));
}

// A std::streambuf over a POSIX descriptor (std::ofstream cannot fsync). It
// remembers the first errno so the caller can report the OS reason.
class DescriptorBuffer final : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }

  std::streamsize xsputn(const char* data, std::streamsize size) override {
    if (size <= epptr() - pptr()) {
      std::memcpy(pptr(), data, std::size_t(size));
      pbump(int(size));
      return size;
    }
    // Large blocks bypass the buffer rather than being copied through it.
    if (!drain() || !writeAll(data, std::size_t(size))) return 0;
    return size;
  }

  int sync() override { return drain() ? 0 : -1; }

  // Seeking lets a writer patch what it wrote earlier (a header that depends on the content).
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override {
    if (!(which & std::ios_base::out) || !drain()) return pos_type(off_type(-1));
    const int whence = dir == std::ios_base::beg ? SEEK_SET : dir == std::ios_base::cur ? SEEK_CUR : SEEK_END;
    const off_t at = ::lseek(fd_, off_t(off), whence);
    if (at < 0) {
      error_ = errno;
      return pos_type(off_type(-1));
    }
    return pos_type(off_type(at));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }

 private:
  bool drain() {
    const bool ok = writeAll(pbase(), std::size_t(pptr() - pbase()));
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return ok;
  }

  bool writeAll(const char* data, std::size_t size) {
    if (error_ != 0) return false;
    while (size > 0) {
      const ssize_t written = ::write(fd_, data, size);
      if (written < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      data += written;
      size -= std::size_t(written);
    }
    return true;
  }

  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_;
};

// The hidden temporary next to the target; removed on destruction unless renamed.
class TemporaryFile {
 public:
  explicit TemporaryFile(const fs::path& target) : target_(target) {
    static std::atomic<unsigned> counter{0};
    std::string stem = ".";  // built by appending: GCC 12 misreports "." + string (-Wrestrict)
    stem += target.filename().string();
    stem += ".tmp-" + std::to_string(::getpid()) + "-";
    // O_EXCL: never clobber another writer's temporary; retry with the next number.
    int error = 0;
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = target.parent_path() / (stem + std::to_string(counter.fetch_add(1)));
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd_ >= 0) return;
      error = errno;
      if (error != EEXIST && error != EINTR) break;
    }
    fail(target_, "cannot create temporary file " + path_.string(), error);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  ~TemporaryFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!renamed_) ::unlink(path_.c_str());
  }

  int fd() const { return fd_; }

  void syncAndClose() {
    if (::fsync(fd_) != 0) {
      const int error = errno;
      fail(target_, "fsync of " + path_.string() + " failed", error);
    }
    const int fd = fd_;
    fd_ = -1;  // close() releases the descriptor even when it reports an error
    if (::close(fd) != 0) {
      const int error = errno;
      fail(target_, "close of " + path_.string() + " failed", error);
    }
  }

  void renameOverTarget() {
    if (::rename(path_.c_str(), target_.c_str()) != 0) {
      const int error = errno;
      fail(target_, "cannot rename " + path_.string() + " over it", error);
    }
    renamed_ = true;
  }

 private:
  fs::path target_;
  fs::path path_;
  int fd_ = -1;
  bool renamed_ = false;
};

// Makes the rename itself durable. Best effort: the new content is already in
// place, and some file systems refuse fsync on a folder.
void syncFolder(const fs::path& folder) {
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void writeFileAtomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  if (!target.has_filename()) fail(target, "not a file name", EINVAL);
  const fs::path folder = target.parent_path();
  if (!folder.empty()) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) fail(target, "cannot create folder " + folder.string(), error.value());
  }

  TemporaryFile temporary(target);
  {
    DescriptorBuffer buffer(temporary.fd());
    std::ostream stream(&buffer);
    write(stream);
    stream.flush();
    if (buffer.error() != 0) fail(target, "write failed", buffer.error());
    if (!stream) fail(target, "the stream reported an error", EIO);
  }
  temporary.syncAndClose();
  temporary.renameOverTarget();
  syncFolder(folder);
}

void writeFileAtomically(const fs::path& target, std::string_view bytes) {
  writeFileAtomically(target, [bytes](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace rockbake
