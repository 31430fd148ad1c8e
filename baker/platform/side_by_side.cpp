#include "platform/side_by_side.h"

#include <exception>
#include <vector>

#include <tbb/parallel_for.h>
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

void allSideBySide(std::size_t count, const std::function<void(std::size_t)>& job) {
  std::vector<std::exception_ptr> errors(count);
  tbb::parallel_for(std::size_t(0), count, std::size_t(1), [&](std::size_t i) {
    try {
      job(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace rockbake
