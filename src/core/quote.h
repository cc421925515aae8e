// A value from a file, a script or the command line, quoted for a one-line message: cut to 40 bytes (on a
// UTF-8 character boundary, "..." marking the cut) and with control bytes shown as \xHH, since any input may
// hold anything and the message must stay one readable line. Used by the script parser and the world loader.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace core {

inline constexpr std::size_t kMaxQuoted = 40; // bytes of the value kept in a message

std::string quoteForMessage(std::string_view value);

// A number for a message, as %g writes it: a rejected 1e300 reads as 1e+300, not as 301 digits.
std::string numberForMessage(double value);

// The shortest text that reads back (std::from_chars) as exactly this number, bit for bit: what recordings and
// panel edits write, so a replay takes the same values.
std::string shortestText(float value);
std::string shortestText(double value);

// The parts of `text` between the separators: "a,,b" gives "a", "", "b"; "" gives one empty part. The
// views point into `text`. The one splitter of the text formats (scripts, recordings, gamepad mappings,
// panel edits).
std::vector<std::string_view> splitAt(std::string_view text, char separator);

} // namespace core
