#include "review/library_json.h"

#include <sys/stat.h>

#include <cerrno>

#include "core/error.h"
#include "http/static_files.h"
#include "platform/input_file.h"

namespace rockbake {

namespace fs = std::filesystem;

LibraryJson readLibraryJson(const fs::path& library_dir, const std::string& relative, std::uint64_t max_bytes) {
  LibraryJson out;
  const fs::path file = library_dir / relative;
  struct stat st {};
  if (lstat(file.c_str(), &st) != 0 && errno == ENOENT) return out;
  out.present = true;
  const auto found = http::fileUnder(library_dir, relative);
  if (!found) {
    out.problem = file.string() + " is not a regular file inside " + library_dir.string() +
                  " (a link out of it, a folder, a FIFO or a device)";
    return out;
  }
  try {
    const InputFile in(*found, "");
    if (in.size() > max_bytes) {
      out.problem = file.string() + " has " + std::to_string(in.size()) + " bytes; at most " +
                    std::to_string(max_bytes) + " are read";
      return out;
    }
    out.value = nlohmann::json::parse(in.read(0, in.size()), nullptr, false);
    if (out.value.is_discarded()) {
      out.value = nullptr;
      out.not_json = true;
      out.problem = file.string() + " is not JSON";
    }
  } catch (const InputError& e) {
    out.problem = e.what();
  }
  return out;
}

}  // namespace rockbake
