#pragma once
// An error in something the user gave us (a model, a gesture, a command-line value).
// It names the element at fault and says what to change; the CLI maps it to exit status 2.

#include <stdexcept>
#include <string>

namespace archet {

class InputError : public std::runtime_error {
  public:
    /// `where` names the file, element or option at fault ("link l3", "--pitch");
    /// `what` says what is wrong and how to fix it.
    InputError(std::string where, const std::string& what)
        : std::runtime_error(where.empty() ? what : where + ": " + what),
          where_(std::move(where)) {}

    const std::string& where() const { return where_; }

  private:
    std::string where_;
};

}  // namespace archet
