#pragma once
// Text from a file or a command line shown back to the user: ids and names may hold only
// printable characters, and any text echoed in a message is quoted with control bytes
// escaped, so that an ESC in a model can never reach the terminal.

#include <string>
#include <string_view>

namespace archet {

/// True when `text` is valid UTF-8 without control characters (C0, DEL or C1).
bool is_printable_text(std::string_view text);

/// `text` between double quotes, with quotes, backslashes, control characters and bytes that
/// are not valid UTF-8 escaped as \" \\ \xNN: safe to print anywhere. Past `limit` bytes of
/// `text` it is cut, and "..." says so.
std::string quoted_text(std::string_view text, std::size_t limit = std::string_view::npos);

/// `text` with every control character but newline and tab, and every byte that is not valid
/// UTF-8, escaped as \xNN: for messages that quote the user's input.
std::string printable_message(std::string_view text);

}  // namespace archet
