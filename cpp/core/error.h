// The one exception type of the core. Every failure a user can cause (bad file, bad mesh, bad handles,
// too little memory) throws sd::Error with a message that names the problem and a stable code that says
// what kind of problem it is; the binding layer turns it into a JS Error carrying both
// ({ code: "invalid_mesh", message }). Code that reacts to a failure reads the code, never the message.
// `assert` is kept for programmer errors only.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace sd {

// Stable codes: their names (error_code_name) are part of the JS API and of the CLI's output.
enum class ErrorCode {
  InvalidArgument,   // a bad argument or option value, handles, targets, an unknown example name
  InvalidMesh,       // a mesh or cage fails the checks (sd::MeshError carries the findings)
  MeshOutsideCage,   // a mesh vertex is outside its cage or on it (sd::MeshError carries the findings)
  ParseError,        // mesh file bytes that cannot be read as the format they claim (or any format)
  UnreadableFile,    // a file that cannot be opened or read at all, or is no regular file (a FIFO, a device)
  FileTooLarge,      // a file over the size limit of the readers (web/lib/file_limits.js)
  UnwritableFile,    // an output file that cannot be written (a missing folder, a read-only file)
  NoCage,            // the subspace method, or a step that needs a cage, in a session without one
  MemoryBudget,      // W or the dense exact Jacobian would exceed the memory budget the caller set
  OutOfMemory,       // an allocation failed (the wasm heap is full)
  Cancelled,         // a progress callback asked to stop (binding W, generating a cage)
  NumericalFailure,  // a factorization failed or a result was not finite
  CageFailed,        // cage generation found no valid cage of the requested size
  InvalidSkeleton,   // a skeleton's joints or bones are unusable (a joint outside the mesh, a bone out of range)
  Internal,          // a failure that is a bug, not the caller's: an unexpected exception
};

// "invalid_argument", "invalid_mesh", ...: the spelling JS and the CLI see.
const char* error_code_name(ErrorCode code);
// Every code, in declaration order (the JS schema lists them; tests check the names are distinct).
const std::vector<ErrorCode>& all_error_codes();

class Error : public std::runtime_error {
 public:
  // The one-argument form is for argument checks (the most common throw); name the code otherwise.
  explicit Error(const std::string& message) : Error(ErrorCode::InvalidArgument, message) {}
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}

  ErrorCode code() const { return code_; }

 private:
  ErrorCode code_;
};

}  // namespace sd
