#include "core/error.h"

namespace sd {

const std::vector<ErrorCode>& all_error_codes() {
  static const std::vector<ErrorCode> codes = {
      ErrorCode::InvalidArgument, ErrorCode::InvalidMesh,     ErrorCode::MeshOutsideCage, ErrorCode::ParseError,
      ErrorCode::UnreadableFile,  ErrorCode::FileTooLarge,    ErrorCode::UnwritableFile,  ErrorCode::NoCage,
      ErrorCode::MemoryBudget,    ErrorCode::OutOfMemory,     ErrorCode::Cancelled,       ErrorCode::NumericalFailure,
      ErrorCode::CageFailed,      ErrorCode::InvalidSkeleton, ErrorCode::Internal,
  };
  return codes;
}

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidArgument: return "invalid_argument";
    case ErrorCode::InvalidMesh: return "invalid_mesh";
    case ErrorCode::MeshOutsideCage: return "mesh_outside_cage";
    case ErrorCode::ParseError: return "parse_error";
    case ErrorCode::UnreadableFile: return "unreadable_file";
    case ErrorCode::FileTooLarge: return "file_too_large";
    case ErrorCode::UnwritableFile: return "unwritable_file";
    case ErrorCode::NoCage: return "no_cage";
    case ErrorCode::MemoryBudget: return "memory_budget";
    case ErrorCode::OutOfMemory: return "out_of_memory";
    case ErrorCode::Cancelled: return "cancelled";
    case ErrorCode::NumericalFailure: return "numerical_failure";
    case ErrorCode::CageFailed: return "cage_failed";
    case ErrorCode::InvalidSkeleton: return "invalid_skeleton";
    case ErrorCode::Internal: return "internal";
  }
  return "internal";
}

}  // namespace sd
