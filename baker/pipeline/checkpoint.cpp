#include "pipeline/checkpoint.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "platform/atomic_file.h"
#include "platform/input_file.h"

namespace rockbake {

void writeCheckpoint(const std::filesystem::path& file, const Checkpoint& checkpoint) {
  writeFileAtomically(file, checkpointBytes(checkpoint));
}

Checkpoint readCheckpoint(const std::filesystem::path& file) {
  const InputFile in(file, "check the path (checkpoints are OUT/<name>/checkpoints/<time>.rbk)");
  const std::uint64_t size = in.size();
  const std::uint64_t header =
      checkpointHeaderLength(in.read(0, std::min<std::uint64_t>(size, kCheckpointPrefixBytes)), size, file);
  const std::uint64_t most = checkpointMostBytes(in.read(kCheckpointPrefixBytes, header), size, file);
  if (size > most)
    throw InputError({file.string()}, "",
                     fmt::format("the checkpoint is corrupt (the file is {} bytes; a checkpoint of its grid holds "
                                 "at most {})",
                                 size, most),
                     "use another checkpoint, or bake again");
  return parseCheckpoint(in.read(0, size), file);
}

}  // namespace rockbake
