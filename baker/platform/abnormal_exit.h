// When the process cannot unwind: some libraries are not exception-safe when
// memory runs out (OpenVDB's dilation, for one, throws again from a destructor
// while std::bad_alloc unwinds through it, which ends in std::terminate). The
// handler installed here turns such an end into what an unwound failure gives:
// the registered folders (a bake's staging folder) are removed, the message
// registered for running out of memory (or the exception's own) is printed as
// "error: ...", and the process exits with status 1 instead of aborting.
#pragma once

#include <filesystem>
#include <string>

namespace rockbake {

// Once, at the start of main: std::set_terminate, and 4 MiB of address space
// held back for the handler to release.
void installAbnormalExitHandler();

// While it lives, `folder` is removed (and then its parent, if that is left
// empty and `empty_parent_too`) and `out_of_memory` is said, should the process
// end in std::terminate. Several may live at once (a library's jobs).
class OnAbnormalExit {
 public:
  OnAbnormalExit(std::filesystem::path folder, std::string out_of_memory, bool empty_parent_too = false);
  ~OnAbnormalExit();
  OnAbnormalExit(const OnAbnormalExit&) = delete;
  OnAbnormalExit& operator=(const OnAbnormalExit&) = delete;

 private:
  int id_;
};

}  // namespace rockbake
