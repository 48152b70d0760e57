// Text from users (file names, JSON keys and values) made safe to print on a terminal: a
// control character in a message would be interpreted by the terminal (escape sequences
// move the cursor, recolour, retitle or rewrite what is shown), so every one is escaped.
#pragma once

#include <string>
#include <string_view>

namespace gyro::sil {

// `text` with C0 controls and DEL as \n, \t, \r or \xNN, C1 controls (U+0080..U+009F) and the
// bidirectional-text overrides (U+202A..U+202E, U+2066..U+2069) as \u{XXXX}, and every byte
// that is not part of well-formed UTF-8 as \xNN. Printable UTF-8 passes unchanged.
[[nodiscard]] std::string printable(std::string_view text);

}  // namespace gyro::sil
