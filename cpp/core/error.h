// The one exception type of the core. Every failure a user can cause (bad file, bad mesh, bad handles,
// too little memory) throws sd::Error with a message that names the problem; the binding layer turns it
// into a JS Error with the same text. `assert` is kept for programmer errors only.
#pragma once

#include <stdexcept>
#include <string>

namespace sd {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace sd
