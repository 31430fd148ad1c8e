// Atomic file replacement: readers see either the old file or the complete new
// one, never a partial write, even if the bake dies halfway (docs/command-line.md).
//
// The bytes go to a hidden temporary in the target's folder
// (".<name>.tmp-<pid>-<n>"), are flushed and fsync'ed, then renamed over the
// target. Missing parent folders are created. On any failure the temporary is
// removed and the target is left as it was.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace rockbake {

// Throws std::runtime_error naming the target and the OS reason.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

// `write` streams the content, and may seek (seekp) to patch what it wrote
// earlier; a stream error becomes std::runtime_error as above, and an
// exception thrown by `write` itself propagates unchanged (after the
// temporary is removed).
void writeFileAtomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

}  // namespace rockbake
