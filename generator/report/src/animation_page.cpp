#include "eomgen/report/animation_page.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "animation_assets.hpp"
#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

// text for HTML content and attribute values
std::string html_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// JSON for the inside of a <script> element: a '<' can only stand in a JSON string, where
// \u003c means the same character, so no "</script" or "<!--" can end or confuse the element
std::string script_safe_json(const std::string& json) {
  std::string out;
  out.reserve(json.size() + json.size() / 16);
  for (const char c : json) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

// a script the page carries verbatim must not end its element early (or open an HTML comment
// there, which changes how the parser looks for the end); the embedded files are checked here
// rather than escaped, since escaping is only sound inside JavaScript strings
std::string inline_script(const std::string& script, const char* what) {
  std::string lower(script.size(), ' ');
  std::transform(script.begin(), script.end(), lower.begin(),
                 [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  EOMGEN_DEMAND(lower.find("</script") == std::string::npos && lower.find("<!--") == std::string::npos,
                std::string("animation page: the embedded ") + what + " contains </script or <!--");
  return script;
}

// the template with each @@NAME@@ replaced by its text, in one pass (a replacement is never
// searched again, so data cannot inject a placeholder)
std::string filled(const std::string& page, const std::string& title, const std::string& scene_json) {
  std::string out;
  out.reserve(page.size() + scene_json.size() + 1200000);
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("@@", at);
    if (open == std::string::npos) break;
    const std::size_t close = page.find("@@", open + 2);
    EOMGEN_DEMAND(close != std::string::npos, "animation page: an unclosed @@ in page.html");
    out.append(page, at, open - at);
    const std::string name = page.substr(open + 2, close - open - 2);
    if (name == "TITLE") {
      out += html_escaped(title);
    } else if (name == "STYLE") {
      out += animation_assets::viewer_css();
    } else if (name == "THREE_LICENCE") {
      out += html_escaped(animation_assets::three_js_copyright());
    } else if (name == "THREE_REVISION") {
      out += embedded_three_js_revision();
    } else if (name == "THREE") {
      out += inline_script(animation_assets::three_js(), "three.min.js");
    } else if (name == "ORBIT_CONTROLS") {
      out += inline_script(animation_assets::orbit_controls_js(), "OrbitControls.js");
    } else if (name == "VIEWER") {
      out += inline_script(animation_assets::viewer_js(), "viewer.js");
    } else if (name == "SCENE") {
      out += script_safe_json(scene_json);
    } else {
      EOMGEN_UNREACHABLE("animation page: unknown placeholder @@" + name + "@@ in page.html");
    }
    at = close + 2;
  }
  out.append(page, at, std::string::npos);
  return out;
}

}  // namespace

std::string animation_page(const std::string& title, const std::string& scene_json) {
  return filled(animation_assets::page_html(), title, scene_json);
}

std::string embedded_three_js_revision() {
  // three.js states it once: REVISION="111"
  const std::string three = animation_assets::three_js();
  const std::string key = "REVISION=\"";
  const std::size_t at = three.find(key);
  EOMGEN_DEMAND(at != std::string::npos, "animation page: no REVISION in the embedded three.min.js");
  const std::size_t end = three.find('"', at + key.size());
  EOMGEN_DEMAND(end != std::string::npos, "animation page: an unterminated REVISION in three.min.js");
  return "r" + three.substr(at + key.size(), end - at - key.size());
}

}  // namespace eomgen
