// SPDX-License-Identifier: GPL-2.0-or-later
// Text from a model (names of parameters, coordinates, outputs; the model's name) in modelDescription.xml.
// Model files and URDFs are untrusted (docs/errors.md#security): every such text reaches the XML only
// through xml_attribute, which either escapes it so that an XML parser reads back exactly these bytes, or
// refuses it.
#pragma once

#include <stdexcept>
#include <string>

namespace kanegen::fmu {

/// A text that cannot be written into XML 1.0 (a control character other than tab, newline and carriage
/// return, or bytes that are not UTF-8): the message names the text's place and the offending byte.
struct XmlTextError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// `text` as the value of a double-quoted XML attribute: & < > " ' escaped as entities; tab, newline and
/// carriage return as character references (&#9; &#10; &#13;), so that attribute-value normalization does
/// not turn them into spaces; valid UTF-8 kept as it is. Throws XmlTextError, naming `what` (e.g.
/// "the output name \"a.b\""), for other control characters (XML 1.0 has no way to write them) and for
/// bytes that are not UTF-8.
std::string xml_attribute(const std::string& text, const std::string& what);

}  // namespace kanegen::fmu
