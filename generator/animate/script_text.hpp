// SPDX-License-Identifier: GPL-2.0-or-later
// Text that goes into an HTML page's <script> elements (the viewer of
// `kanegen animate --format html`). Model and column names are untrusted
// (docs/errors.md#security): each reaches the page only as a JSON string
// made here, which no name can end early, and the page shows it with
// textContent, never as markup.
#pragma once

#include <string>
#include <string_view>

namespace kanegen::animate {

/// `text` as a JSON string literal, quotes included, that is also safe in
/// the body of an HTML <script> element and as JavaScript: besides JSON's
/// own escapes (" \ and control characters), < > & ' and U+2028, U+2029 are
/// written as \uXXXX, so the result never holds "</script", "<!--" or a line
/// terminator. Bytes that are not UTF-8 (overlong, surrogates, past
/// U+10FFFF, cut short) become U+FFFD; other characters are kept as they are.
std::string script_json_string(std::string_view text);

/// Whether `code` may stand between <script> and </script> as it is: it
/// holds no "</script" and no "<!--" (in any case), which would end the
/// element early or change how the browser reads it.
bool script_safe(std::string_view code);

}  // namespace kanegen::animate
