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
          where_(std::move(where)),
          message_(what) {}

    const std::string& where() const { return where_; }
    /// What is wrong, without the `where` in front.
    const std::string& message() const { return message_; }

  private:
    std::string where_, message_;
};

}  // namespace archet
