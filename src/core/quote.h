// A value from a file, a script or the command line, quoted for a one-line message: cut to 40 bytes (on a
// UTF-8 character boundary, "..." marking the cut) and with control bytes shown as \xHH, since any input may
// hold anything and the message must stay one readable line. Used by the script parser and the world loader.
#pragma once

#include <string>
#include <string_view>

namespace core {

inline constexpr std::size_t kMaxQuoted = 40; // bytes of the value kept in a message

std::string quoteForMessage(std::string_view value);

} // namespace core
