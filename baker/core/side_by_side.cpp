#include "core/side_by_side.h"

#include <exception>

#include <tbb/parallel_invoke.h>

namespace rockbake {

void sideBySide(const std::function<void()>& first, const std::function<void()>& second) {
  std::exception_ptr first_error, second_error;
  const auto guarded = [](const std::function<void()>& job, std::exception_ptr& error) {
    try {
      job();
    } catch (...) {
      error = std::current_exception();
    }
  };
  tbb::parallel_invoke([&] { guarded(first, first_error); }, [&] { guarded(second, second_error); });
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
}

}  // namespace rockbake
