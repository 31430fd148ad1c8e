#include "platform/abnormal_exit.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace rockbake {
namespace {

struct Registered {
  std::filesystem::path folder;
  std::string out_of_memory;
  bool empty_parent_too = false;
};

std::mutex registry_mutex;
std::map<int, Registered> registry;  // by id, oldest first
int next_id = 0;
// Address space held back for the handler: when memory ran out, removing a
// folder (opendir's buffer) may still need some. Mapped directly, so that
// unmapping it gives it back to the system whatever allocator malloc is.
void* reserve = MAP_FAILED;
constexpr std::size_t kReserveBytes = std::size_t(4) << 20;

// write(2) straight to stderr: nothing allocates, and nothing is buffered in a
// stream that _Exit would not flush.
void writeStderr(std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data(), text.size());
    if (n <= 0) return;
    text.remove_prefix(std::size_t(n));
  }
}

// One line, as the logger prints an error.
void sayError(std::string_view message) {
  writeStderr("error: ");
  writeStderr(message);
  writeStderr("\n");
}

[[noreturn]] void onTerminate() {
  if (reserve != MAP_FAILED) ::munmap(reserve, kReserveBytes);
  reserve = MAP_FAILED;
  bool out_of_memory = false;
  const char* what = "the process could not continue";
  if (const std::exception_ptr current = std::current_exception()) {
    try {
      std::rethrow_exception(current);
    } catch (const std::bad_alloc&) {
      out_of_memory = true;
    } catch (const std::length_error&) {  // a container asked for more than it can ever hold
      out_of_memory = true;
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
  }
  // Another thread may hold the lock (it was registering when this one
  // failed): then the folders stay for the next bake of the asset to remove.
  const bool locked = registry_mutex.try_lock();
  bool said = false;
  if (locked) {
    for (const auto& [id, entry] : registry) {
      if (out_of_memory && !entry.out_of_memory.empty()) {
        sayError(entry.out_of_memory);
        said = true;
      }
      std::error_code ignored;
      try {
        std::filesystem::remove_all(entry.folder, ignored);
        if (entry.empty_parent_too) std::filesystem::remove(entry.folder.parent_path(), ignored);
      } catch (...) {  // remove_all may still need memory there is none of
      }
    }
  }
  if (!said) sayError(out_of_memory ? "out of memory" : what);
  std::_Exit(1);
}

}  // namespace

void installAbnormalExitHandler() {
  if (reserve == MAP_FAILED)
    reserve = ::mmap(nullptr, kReserveBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  std::set_terminate(onTerminate);
}

OnAbnormalExit::OnAbnormalExit(std::filesystem::path folder, std::string out_of_memory, bool empty_parent_too) {
  const std::lock_guard lock(registry_mutex);
  id_ = next_id++;
  registry.emplace(id_, Registered{std::move(folder), std::move(out_of_memory), empty_parent_too});
}

OnAbnormalExit::~OnAbnormalExit() {
  const std::lock_guard lock(registry_mutex);
  registry.erase(id_);
}

}  // namespace rockbake
