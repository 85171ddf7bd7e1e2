// The typed failures of a run and the exit codes every program of the project gives for them (docs/output.md,
// "Exit codes"): 2 bad input, 3 numerical failure, 4 I/O, 5 coupling or peer failure (common/coupling/errors.h),
// 1 an unforeseen failure (none of these: a bug to report), 130 interrupted.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace cosim::app {

inline constexpr int kExitUnforeseen = 1, kExitInput = 2, kExitNumerical = 3, kExitIo = 4, kExitCoupling = 5,
                     kExitInterrupted = 130;

// A scene, file or argument that cannot be used (exit code 2).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The state cannot be kept admissible: an inadmissible state, a collapsed step, a surface the solid's deformation
// made invalid (exit code 3).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file or directory that cannot be read or written: a full disk, a missing permission (exit code 4).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The exit code of a failure of these types; 1 for any other exception.
inline int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const InputError*>(&e)) return kExitInput;
  if (dynamic_cast<const NumericalError*>(&e)) return kExitNumerical;
  if (dynamic_cast<const IoError*>(&e)) return kExitIo;
  return kExitUnforeseen;
}

// Runs f, a write of output (a snapshot, a checkpoint part, a summary): a failure that is not already typed is an
// I/O failure, named with `what`.
template <class F>
decltype(auto) as_io(const std::string& what, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const InputError&) { throw; } catch (const NumericalError&) {
    throw;
  } catch (const IoError&) { throw; } catch (const std::exception& e) {
    throw IoError(what + ": " + e.what());
  }
}

}  // namespace cosim::app
