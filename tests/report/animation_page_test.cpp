#include "eomgen/report/animation_page.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace eomgen {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

const std::string scene = R"({"format": 1, "model": "m", "times": [0, 1], "points": []})";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// the text between the element that starts with `open` and the next `close`
std::string between(const std::string& page, const std::string& open, const std::string& close) {
  const std::size_t start = page.find(open);
  if (start == std::string::npos) return "";
  const std::size_t from = start + open.size();
  return page.substr(from, page.find(close, from) - from);
}

TEST(AnimationPage, IsOneHtmlDocumentWithThreeJsTheViewerAndTheScene) {
  const std::string page = animation_page("double pendulum", scene);
  EXPECT_THAT(page, StartsWith("<!doctype html>\n"));
  EXPECT_THAT(page, HasSubstr("<title>double pendulum</title>"));
  EXPECT_EQ(between(page, "<script type=\"application/json\" id=\"scene\">", "</script>"), scene);
  EXPECT_THAT(page, HasSubstr("REVISION=\"111\""));          // three.min.js
  EXPECT_THAT(page, HasSubstr("OrbitControls"));             // its orbit camera
  EXPECT_THAT(page, HasSubstr("draws it with three.js"));    // viewer.js
  EXPECT_EQ(count(page, "@@"), 0u) << "a placeholder of page.html left unfilled";
  // five script elements (error capture, scene, three.js, controls, viewer), each closed once
  EXPECT_EQ(count(page, "<script"), 5u);
  EXPECT_EQ(count(page, "</script>"), 5u);
}

TEST(AnimationPage, CarriesThreeJsLicenceVerbatim) {
  const std::string page = animation_page("m", scene);
  std::ifstream in(EOMGEN_THREE_JS_COPYRIGHT);  // the file the build embedded
  ASSERT_TRUE(in) << EOMGEN_THREE_JS_COPYRIGHT;
  std::stringstream copyright;
  copyright << in.rdbuf();
  // the licence is shown as text: escaped as HTML, otherwise the file as it is
  std::string escaped = std::regex_replace(copyright.str(), std::regex("&"), "&amp;");
  escaped = std::regex_replace(escaped, std::regex("<"), "&lt;");
  escaped = std::regex_replace(escaped, std::regex(">"), "&gt;");
  escaped = std::regex_replace(escaped, std::regex("\""), "&quot;");
  escaped = std::regex_replace(escaped, std::regex("'"), "&#39;");
  EXPECT_EQ(between(page, "<pre id=\"three-licence\">", "</pre>"), escaped);
  EXPECT_EQ(embedded_three_js_revision(), "r111");
  EXPECT_THAT(page, HasSubstr("three.js r111"));
}

TEST(AnimationPage, NamesFromModelFilesCannotEndAScriptOrOpenAComment) {
  const std::string name = "</script><script>alert(1)</script><!-- <b>";
  const std::string hostile = R"({"format": 1, "model": ")" + std::string("</script><!--") + R"(", "times": []})";
  const std::string page = animation_page(name, hostile);
  EXPECT_THAT(page, HasSubstr("<title>&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;&lt;!-- &lt;b&gt;</title>"));
  EXPECT_EQ(between(page, "<script type=\"application/json\" id=\"scene\">", "</script>"),
            R"({"format": 1, "model": "\u003c/script>\u003c!--", "times": []})");
  EXPECT_EQ(count(page, "</script>"), 5u);
}

TEST(AnimationPage, SameInputSameBytes) {
  EXPECT_EQ(animation_page("m", scene), animation_page("m", scene));
}

TEST(AnimationPage, RequestsNothing) {
  std::string page = animation_page("m", scene);
  // three.js's own code and comments, and its licence, name web addresses; nothing else may
  const std::size_t licence = page.find("<pre id=\"three-licence\">");
  page.erase(licence, page.find("</pre>", licence) - licence);
  // drop each script element that is not the viewer's (three.min.js, OrbitControls.js)
  std::string outside;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("<script>\n", at);
    if (open == std::string::npos) break;
    const std::size_t close = page.find("</script>", open);
    outside += page.substr(at, open - at);
    const std::string body = page.substr(open, close - open);
    if (body.find("REVISION=\"111\"") == std::string::npos &&
        body.find("Generated from 'examples/jsm/controls/OrbitControls.js'") == std::string::npos)
      outside += body;
    at = close;
  }
  outside += page.substr(at);
  EXPECT_THAT(outside, Not(HasSubstr("http:"))) << "a web address outside three.js and its licence";
  EXPECT_THAT(outside, Not(HasSubstr("https:")));
  EXPECT_THAT(outside, Not(HasSubstr("src=")));
  EXPECT_THAT(outside, Not(HasSubstr("href=")));
  EXPECT_THAT(outside, Not(HasSubstr("@import")));
  EXPECT_THAT(outside, Not(HasSubstr("url(")));
  EXPECT_THAT(outside, HasSubstr("new THREE.OrbitControls"));  // the viewer was kept
  EXPECT_THAT(outside, HasSubstr("Content-Security-Policy\" content=\"default-src 'none'"));
}

}  // namespace
}  // namespace eomgen
