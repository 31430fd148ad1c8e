// The checkpoint reader (`rockbake resume`), from bytes in memory. The first
// byte's lowest bit set: the rest is a checkpoint without its checksum, and
// the valid SHA-256 is appended, so that mutations reach the header and the
// arrays; clear: the rest is the whole file. Refusals are InputError naming
// the file. A checkpoint that reads fits its own grid, as a simulation started
// from it needs, and is written back to bytes that read the same.
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/sha256.h"
#include "fuzz_support.h"
#include "sim/checkpoint_format.h"

using namespace rockbake;

namespace {

void checkFitsItsGrid(const Checkpoint& c) {
  const VoxelRock& rock = c.snapshot.rock;
  const GridLayout& g = rock.layout;
  if (g.nx <= 0 || g.ny <= 0 || g.nz <= 0 || g.margin < 0 || !(g.h > 0)) fuzz::finding("a layout that is no grid");
  const std::size_t rows = std::size_t(g.ny) * std::size_t(g.nz);
  if (rock.material.size() != g.cellCount()) fuzz::finding("materials are not one per cell");
  for (const RowSpans* spans : {&rock.integrity, &rock.durability}) {
    if (spans->nx != g.nx || spans->first.size() != rows || spans->values.size() != rows)
      fuzz::finding("row spans that do not fit the grid");
    for (std::size_t row = 0; row < rows; ++row)
      if (spans->first[row] < 0 || spans->first[row] + std::int64_t(spans->values[row].size()) > g.nx)
        fuzz::finding("a row span outside its row");
  }
  if (!rock.rind.empty() && rock.rind.size() != g.cellCount()) fuzz::finding("a rind that is not one per cell");
  if (c.snapshot.colluvium_columns.size() != std::size_t(g.nx) * std::size_t(g.ny))
    fuzz::finding("colluvium accumulators that are not one per column");
  if (c.snapshot.cycle < 0) fuzz::finding("a negative cycle");
  if (!c.cycles.is_array()) fuzz::finding("per-cycle statistics that are not a list");
}

// Reads `bytes`; false for a refusal. Anything but an InputError naming the file is a finding.
bool reads(const std::string& bytes, Checkpoint& out) {
  static const std::filesystem::path kName = "fuzz.rbk";
  try {
    out = parseCheckpoint(bytes, kName);
    return true;
  } catch (const InputError& e) {
    if (e.where().file != kName.string())
      fuzz::finding(std::string("a refusal that does not name the file: ") + e.what());
    return false;
  } catch (const std::exception& e) {
    fuzz::finding(std::string("unexpected ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fuzz::finding("unexpected non-standard exception");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 1) bytes += sha256Hex(bytes);
  Checkpoint checkpoint;
  if (!reads(bytes, checkpoint)) return 0;
  checkFitsItsGrid(checkpoint);
  const std::string written = checkpointBytes(checkpoint);
  Checkpoint again;
  if (!reads(written, again)) fuzz::finding("a checkpoint that reads is written back to one that does not");
  if (checkpointBytes(again) != written) fuzz::finding("a checkpoint written back reads differently");
  return 0;
}
