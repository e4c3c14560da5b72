// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/html_page.hpp"

#include <stdexcept>

#include "animate/script_text.hpp"

namespace kanegen::embedded {
extern const char* const viewer_html_template;
}

namespace kanegen::animate {

std::string viewer_page(const std::string& three_js, const std::string& data_json) {
  if (!script_safe(three_js) || !script_safe(data_json))
    throw std::runtime_error(
        "--format html: three.js's text holds '</script' or '<!--', which would end the page's "
        "<script> early; install the version viewer/package.json pins");
  // The template's first two lines are its SPDX line and what it is, for the repository; the page
  // says its license in an HTML comment.
  std::string page = embedded::viewer_html_template;
  for (int line = 0; line < 2; ++line) page.erase(0, page.find('\n') + 1);
  // One pass over the template's two places, so that nothing put in is read for a place again.
  const std::string places[] = {"/*@THREE_JS@*/", "/*@KANEGEN_DATA@*/"};
  const std::string* texts[] = {&three_js, &data_json};
  std::string out;
  std::size_t from = 0;
  for (int k = 0; k < 2; ++k) {
    const std::size_t at = page.find(places[k], from);
    if (at == std::string::npos) throw std::logic_error("templates/viewer.html.in lacks " + places[k]);
    out.append(page, from, at - from).append(*texts[k]);
    from = at + places[k].size();
  }
  return out.append(page, from, std::string::npos);
}

}  // namespace kanegen::animate
